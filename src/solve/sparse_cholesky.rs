//! Sparse Cholesky LLᵀ (faer, supernodal) of a symmetric positive definite matrix given by its
//! upper triangle, with a fill-reducing order that can keep chosen dofs last.
//!
//! Keeping the contact dofs last makes the trailing block of L the Cholesky factor of the Schur
//! complement on those dofs, so a step that condenses the contact onto them costs one forward and
//! one backward pass (split here) instead of two full solves. The symbolic analysis is done once;
//! numeric refactorizations reuse it (Newton iterations, new step sizes).
//!
//! A matrix that may be indefinite (the tangent of Gonzalez's discrete gradient at large steps)
//! goes through [`SparseCholesky::factor_symmetric`]: LLᵀ first, and when a pivot is not
//! positive, faer's intranode LBLᵀ (Bunch–Kaufman pivoting inside each supernode) on the same
//! symbolic analysis. The fallbacks are counted; solves with such a factor are checked by their
//! residual (pivoting is restricted to a supernode, so a small pivot outside it is not avoided).

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, supernodal::SupernodalLltRef, CholeskySymbolicParams,
    IntranodeLbltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::{amd, SupernodalThreshold};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

use crate::error::SolveError;
use crate::fem::sparse::SymmetricPattern;

/// Scratch memory of the solves (allocated once, reused every step).
pub struct CholeskyWorkspace {
    stack: MemBuffer,
    permuted: Vec<f64>,
}

impl std::fmt::Debug for CholeskyWorkspace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "CholeskyWorkspace({} values)", self.permuted.len())
    }
}

/// Which triangular solve a kernel runs: with L (forward) or with Lᵀ (backward).
#[derive(Debug, Clone, Copy)]
enum Sweep {
    Forward,
    Backward,
}

/// The supernodal structure and values of a factor, as the triangular-solve kernels read them.
struct Supernodes<'a> {
    begin: &'a [usize],
    end: &'a [usize],
    row_ptr: &'a [usize],
    value_ptr: &'a [usize],
    rows: &'a [usize],
    values: &'a [f64],
}

impl<'a> Supernodes<'a> {
    /// The number of supernodes.
    #[inline(always)]
    fn count(&self) -> usize {
        self.begin.len()
    }

    /// Supernode `s`: its first column, its number of columns, the rows of its pattern below the
    /// diagonal block, and its values (column-major, size + pattern rows per column).
    #[inline(always)]
    fn get(&self, s: usize) -> (usize, usize, &'a [usize], &'a [f64]) {
        let start = self.begin[s];
        (
            start,
            self.end[s] - start,
            &self.rows[self.row_ptr[s]..self.row_ptr[s + 1]],
            &self.values[self.value_ptr[s]..self.value_ptr[s + 1]],
        )
    }
}

/// The numeric factorization that holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FactorKind {
    /// A = L Lᵀ (positive definite).
    Llt,
    /// P A Pᵀ = L B Lᵀ with B block diagonal (1 × 1 and 2 × 2 blocks), intranode pivoting.
    Lblt,
}

/// The storage of an intranode LBLᵀ factorization (allocated at the first fallback).
struct Lblt {
    values: Vec<f64>,
    subdiag: Vec<f64>,
    fwd: Vec<usize>,
    inv: Vec<usize>,
    solve: MemBuffer,
}

impl std::fmt::Debug for Lblt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Lblt({} values)", self.values.len())
    }
}

/// A symbolic analysis and (after [`SparseCholesky::factor`]) a numeric factorization.
#[derive(Debug)]
pub struct SparseCholesky {
    n: usize,
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// perm[new] = old, inv[old] = new.
    perm: Vec<usize>,
    inv: Vec<usize>,
    factor_stack: StackReq,
    factored: bool,
    operator: String,
    kind: FactorKind,
    lblt: Option<Box<Lblt>>,
    indefinite_factorizations: usize,
}

impl SparseCholesky {
    /// Analyzes `pattern`: approximate minimum degree order, then the dofs of `last` moved (in the
    /// given order) to the end.
    pub fn analyze(
        pattern: &SymmetricPattern,
        last: &[usize],
        operator: &str,
    ) -> Result<Self, SolveError> {
        let n = pattern.order();
        let singular = |why: &str| SolveError::Singular {
            operator: format!("{operator} ({why})"),
            row: 0,
            pivot: f64::NAN,
        };
        let sym =
            SymbolicSparseColMatRef::new_checked(n, n, pattern.col_ptr(), None, pattern.row_idx());
        let mut fwd = vec![0usize; n];
        let mut inv = vec![0usize; n];
        {
            let mut mem = MemBuffer::new(amd::order_scratch::<usize>(n, pattern.nnz()));
            amd::order(
                &mut fwd,
                &mut inv,
                sym,
                amd::Control::default(),
                MemStack::new(&mut mem),
            )
            .map_err(|_| singular("ordering failed"))?;
        }
        // Stable partition: AMD order without the tail, then the tail.
        let mut is_last = vec![false; n];
        for &d in last {
            is_last[d] = true;
        }
        let mut perm: Vec<usize> = fwd.iter().copied().filter(|&d| !is_last[d]).collect();
        perm.extend_from_slice(last);
        if perm.len() != n {
            return Err(singular("the trailing dofs repeat or are out of range"));
        }
        for (new, &old) in perm.iter().enumerate() {
            inv[old] = new;
        }
        let perm_ref = PermRef::new_checked(&perm, &inv, n);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(
            sym,
            Side::Upper,
            SymmetricOrdering::Custom(perm_ref),
            params,
        )
        .map_err(|_| singular("symbolic analysis failed"))?;
        let factor_stack =
            symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default());
        Ok(Self {
            n,
            values: vec![0.0; symbolic.len_val()],
            symbolic,
            perm,
            inv,
            factor_stack,
            factored: false,
            operator: operator.to_string(),
            kind: FactorKind::Llt,
            lblt: None,
            indefinite_factorizations: 0,
        })
    }

    /// The factorization that holds (after a successful factor).
    pub fn kind(&self) -> FactorKind {
        self.kind
    }

    /// Factorizations that fell back to LBLᵀ so far.
    pub fn indefinite_factorizations(&self) -> usize {
        self.indefinite_factorizations
    }

    /// The order n.
    pub fn order(&self) -> usize {
        self.n
    }

    /// Stored entries of L.
    pub fn factor_nnz(&self) -> usize {
        self.values.len()
    }

    /// The position of original dof `old` in the factor's order.
    #[inline]
    pub fn position(&self, old: usize) -> usize {
        self.inv[old]
    }

    /// Factors the matrix with upper-triangle `values` on the analyzed pattern. A non-positive or
    /// non-finite pivot is a [`SolveError::Singular`] naming the (original) row.
    pub fn factor(&mut self, pattern: &SymmetricPattern, values: &[f64]) -> Result<(), SolveError> {
        if let Some(bad) = values.iter().position(|v| !v.is_finite()) {
            return Err(SolveError::Singular {
                operator: format!("{} (non-finite matrix entry)", self.operator),
                row: pattern.row_idx()[bad],
                pivot: values[bad],
            });
        }
        let a = SparseColMatRef::new(
            SymbolicSparseColMatRef::new_checked(
                self.n,
                self.n,
                pattern.col_ptr(),
                None,
                pattern.row_idx(),
            ),
            values,
        );
        let mut mem = MemBuffer::new(self.factor_stack);
        let result = self.symbolic.factorize_numeric_llt(
            &mut self.values,
            a,
            Side::Upper,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        );
        self.factored = false;
        match result {
            Ok(_) => {
                if self.values.iter().any(|v| !v.is_finite()) {
                    return Err(SolveError::Singular {
                        operator: format!("{} (non-finite factor)", self.operator),
                        row: 0,
                        pivot: f64::NAN,
                    });
                }
                self.factored = true;
                self.kind = FactorKind::Llt;
                Ok(())
            }
            Err(e) => {
                let row = match e {
                    faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                        self.perm.get(index).copied().unwrap_or(index)
                    }
                };
                Err(SolveError::Singular {
                    operator: self.operator.clone(),
                    row,
                    pivot: f64::NAN,
                })
            }
        }
    }

    /// Factors a symmetric matrix that may be indefinite: LLᵀ, and when a pivot is not positive
    /// the intranode LBLᵀ on the same symbolic analysis (counted in
    /// [`Self::indefinite_factorizations`]). A non-finite entry, or a non-finite LBLᵀ factor (an
    /// exactly singular matrix), is a [`SolveError::Singular`].
    pub fn factor_symmetric(
        &mut self,
        pattern: &SymmetricPattern,
        values: &[f64],
    ) -> Result<(), SolveError> {
        match self.factor(pattern, values) {
            Ok(()) => Ok(()),
            Err(SolveError::Singular { pivot, .. })
                if pivot.is_nan() && values.iter().all(|v| v.is_finite()) =>
            {
                self.factor_lblt(pattern, values)
            }
            Err(e) => Err(e),
        }
    }

    fn factor_lblt(
        &mut self,
        pattern: &SymmetricPattern,
        values: &[f64],
    ) -> Result<(), SolveError> {
        let n = self.n;
        if self.lblt.is_none() {
            let solve = self.symbolic.solve_in_place_scratch::<f64>(1, Par::Seq);
            self.lblt = Some(Box::new(Lblt {
                values: vec![0.0; self.symbolic.len_val()],
                subdiag: vec![0.0; n],
                fwd: vec![0; n],
                inv: vec![0; n],
                solve: MemBuffer::new(solve),
            }));
        }
        let Some(lblt) = self.lblt.as_mut() else {
            unreachable!("allocated above")
        };
        let a = SparseColMatRef::new(
            SymbolicSparseColMatRef::new_checked(n, n, pattern.col_ptr(), None, pattern.row_idx()),
            values,
        );
        let scratch = self
            .symbolic
            .factorize_numeric_intranode_lblt_scratch::<f64>(Par::Seq, Default::default());
        let mut mem = MemBuffer::new(scratch);
        self.symbolic.factorize_numeric_intranode_lblt(
            &mut lblt.values,
            &mut lblt.subdiag,
            &mut lblt.fwd,
            &mut lblt.inv,
            a,
            Side::Upper,
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        );
        self.factored = false;
        if lblt
            .values
            .iter()
            .chain(&lblt.subdiag)
            .any(|v| !v.is_finite())
        {
            return Err(SolveError::Singular {
                operator: format!("{} (indefinite, and singular in LBLᵀ)", self.operator),
                row: 0,
                pivot: f64::NAN,
            });
        }
        self.indefinite_factorizations += 1;
        self.kind = FactorKind::Lblt;
        self.factored = true;
        Ok(())
    }

    /// A workspace for up to `columns` right-hand sides.
    pub fn workspace(&self, columns: usize) -> CholeskyWorkspace {
        let req = match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => {
                s.solve_in_place_scratch::<f64>(columns, Par::Seq)
            }
            SymbolicCholeskyRaw::Simplicial(_) => StackReq::empty(),
        };
        CholeskyWorkspace {
            stack: MemBuffer::new(req),
            permuted: vec![0.0; self.n * columns.max(1)],
        }
    }

    fn supernodal(&self) -> SupernodalLltRef<'_, usize, f64> {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => SupernodalLltRef::new(s, &self.values),
            SymbolicCholeskyRaw::Simplicial(_) => {
                unreachable!("supernodal factorization is forced")
            }
        }
    }

    /// Solves A x = b in place (original order).
    pub fn solve_in_place(&mut self, x: &mut [f64], ws: &mut CholeskyWorkspace) {
        debug_assert!(self.factored);
        if self.kind == FactorKind::Lblt {
            if let Some(lblt) = self.lblt.as_mut() {
                let perm = PermRef::new_checked(&lblt.fwd, &lblt.inv, self.n);
                IntranodeLbltRef::new(&self.symbolic, &lblt.values, &lblt.subdiag, perm)
                    .solve_in_place_with_conj(
                        Conj::No,
                        MatMut::from_column_major_slice_mut(x, self.n, 1),
                        Par::Seq,
                        MemStack::new(&mut lblt.solve),
                    );
                return;
            }
        }
        let p = &mut ws.permuted[..self.n];
        for (new, &old) in self.perm.iter().enumerate() {
            p[new] = x[old];
        }
        let l = self.supernodal();
        let stack = MemStack::new(&mut ws.stack);
        l.l_solve_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(p, self.n, 1),
            Par::Seq,
            stack,
        );
        l.l_transpose_solve_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(p, self.n, 1),
            Par::Seq,
            stack,
        );
        for (new, &old) in self.perm.iter().enumerate() {
            x[old] = p[new];
        }
    }

    /// y = L⁻¹ P b in the factor's order (`y` has length n; `b` is in original order).
    ///
    /// A single right-hand side goes through a direct kernel over the supernodes (a dense
    /// triangular solve per diagonal block and one contiguous update per column): for one vector
    /// the generic blocked routines spend most of their time in dispatch on small supernodes.
    pub fn forward(&self, b: &[f64], y: &mut [f64], ws: &mut CholeskyWorkspace) {
        for (new, &old) in self.perm.iter().enumerate() {
            y[new] = b[old];
        }
        self.kernel(Sweep::Forward, y, &mut ws.permuted);
    }

    /// x = Pᵀ L⁻ᵀ y (original order); `y` (factor order) is overwritten.
    pub fn backward(&self, y: &mut [f64], x: &mut [f64], ws: &mut CholeskyWorkspace) {
        self.kernel(Sweep::Backward, y, &mut ws.permuted);
        for (new, &old) in self.perm.iter().enumerate() {
            x[old] = y[new];
        }
    }

    fn symbolic_supernodal(
        &self,
    ) -> &faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky<usize> {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => s,
            SymbolicCholeskyRaw::Simplicial(_) => {
                unreachable!("supernodal factorization is forced")
            }
        }
    }

    /// The supernodes of the factor, for the triangular-solve kernels.
    #[inline(always)]
    fn supernodes(&self) -> Supernodes<'_> {
        let sym = self.symbolic_supernodal();
        Supernodes {
            begin: sym.supernode_begin(),
            end: sym.supernode_end(),
            row_ptr: sym.col_ptr_for_row_idx(),
            value_ptr: sym.col_ptr_for_val(),
            rows: sym.row_idx(),
            values: &self.values,
        }
    }

    /// x ← L⁻¹ x ([`Sweep::Forward`]) or x ← L⁻ᵀ x ([`Sweep::Backward`]) in factor order, with
    /// AVX2/FMA when the processor has them (detected at run time; the same kernel, compiled for
    /// wider vectors).
    fn kernel(&self, sweep: Sweep, x: &mut [f64], tmp: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
        {
            // SAFETY: the features the function is compiled for were detected on this processor.
            unsafe { self.kernel_avx2(sweep, x, tmp) };
            return;
        }
        self.kernel_generic(sweep, x, tmp)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn kernel_avx2(&self, sweep: Sweep, x: &mut [f64], tmp: &mut [f64]) {
        self.kernel_generic(sweep, x, tmp)
    }

    /// The solve of `sweep` without a choice of instructions (inlined where it is called).
    #[inline(always)]
    fn kernel_generic(&self, sweep: Sweep, x: &mut [f64], tmp: &mut [f64]) {
        match sweep {
            Sweep::Forward => self.forward_kernel_generic(x, tmp),
            Sweep::Backward => self.backward_kernel_generic(x, tmp),
        }
    }

    /// x ← L⁻¹ x in factor order; `tmp` has length ≥ the largest supernode pattern.
    #[inline(always)]
    fn forward_kernel_generic(&self, x: &mut [f64], tmp: &mut [f64]) {
        let sn = self.supernodes();
        for s in 0..sn.count() {
            let (start, size, pat, vals) = sn.get(s);
            let nrows = size + pat.len();
            let acc = &mut tmp[..pat.len()];
            acc.iter_mut().for_each(|v| *v = 0.0);
            for j in 0..size {
                let col = &vals[j * nrows..(j + 1) * nrows];
                let xj = x[start + j] / col[j];
                x[start + j] = xj;
                let (diag_block, below) = col.split_at(size);
                for (xi, l) in x[start + j + 1..start + size]
                    .iter_mut()
                    .zip(&diag_block[j + 1..])
                {
                    *xi -= l * xj;
                }
                for (a, l) in acc.iter_mut().zip(below) {
                    *a += l * xj;
                }
            }
            for (&row, a) in pat.iter().zip(acc.iter()) {
                x[row] -= a;
            }
        }
    }

    /// x ← L⁻ᵀ x in factor order.
    #[inline(always)]
    fn backward_kernel_generic(&self, x: &mut [f64], tmp: &mut [f64]) {
        let sn = self.supernodes();
        for s in (0..sn.count()).rev() {
            let (start, size, pat, vals) = sn.get(s);
            let nrows = size + pat.len();
            let gathered = &mut tmp[..pat.len()];
            for (g, &row) in gathered.iter_mut().zip(pat) {
                *g = x[row];
            }
            for j in (0..size).rev() {
                let col = &vals[j * nrows..(j + 1) * nrows];
                let (diag_block, below) = col.split_at(size);
                let acc = x[start + j]
                    - dot(below, gathered)
                    - dot(&diag_block[j + 1..], &x[start + j + 1..start + size]);
                x[start + j] = acc / col[j];
            }
        }
    }

    /// The trailing m × m block of L (rows and columns n − m..n of the factor order), dense and
    /// lower triangular: for a tail of dofs ordered last, the Cholesky factor of their Schur
    /// complement.
    pub fn trailing_block(&self, m: usize) -> faer::Mat<f64> {
        let n = self.n;
        let first = n - m;
        let mut out = faer::Mat::<f64>::zeros(m, m);
        let l = self.supernodal();
        let symbolic = l.symbolic();
        for s in 0..symbolic.n_supernodes() {
            let sn = l.supernode(s);
            let start = sn.start();
            let val = sn.val();
            let size = val.ncols();
            if start + size <= first {
                continue;
            }
            let pattern = sn.pattern();
            for c in start.max(first)..start + size {
                let lc = c - start;
                for i in lc..size {
                    out[(start + i - first, c - first)] = val[(i, lc)];
                }
                for (k, &row) in pattern.iter().enumerate() {
                    out[(row - first, c - first)] = val[(size + k, lc)];
                }
            }
        }
        out
    }

    /// L⁻¹ applied to several right-hand sides in factor order (columns of `b`, column-major).
    pub fn forward_many(&self, b: &mut [f64], columns: usize, ws: &mut CholeskyWorkspace) {
        let stack = MemStack::new(&mut ws.stack);
        self.supernodal().l_solve_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(b, self.n, columns),
            Par::Seq,
            stack,
        );
    }
}

/// Σ a_i b_i with four independent accumulators (a single running sum is bound by the latency of
/// the additions and does not vectorize).
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 4];
    let (ac, bc) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ar, br) = (ac.remainder(), bc.remainder());
    for (x, y) in ac.zip(bc) {
        acc[0] += x[0] * y[0];
        acc[1] += x[1] * y[1];
        acc[2] += x[2] * y[2];
        acc[3] += x[3] * y[3];
    }
    let mut tail = 0.0;
    for (x, y) in ar.iter().zip(br) {
        tail += x * y;
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

#[cfg(test)]
mod tests {
    //! Sparse Cholesky: solves a small SPD system in original order, the split forward/backward
    //! passes compose to the solve, trailing dofs are ordered last, and an indefinite matrix is a
    //! typed error.
    use super::*;

    fn laplacian(n: usize) -> (SymmetricPattern, Vec<f64>) {
        let dofs: Vec<[Option<usize>; 2]> = (0..n - 1).map(|i| [Some(i), Some(i + 1)]).collect();
        let pat = SymmetricPattern::new(n, &dofs);
        let mut v = vec![0.0; pat.nnz()];
        for e in 0..n - 1 {
            pat.add_element(&mut v, e, &[1.0, -1.0, -1.0, 1.0]);
        }
        // ground node 0
        let d = pat.diagonal_slot(0).unwrap();
        v[d] += 1.0;
        (pat, v)
    }

    #[test]
    fn solve_and_split_passes_agree() {
        let n = 40;
        let (pat, v) = laplacian(n);
        let mut c = SparseCholesky::analyze(&pat, &[5, 17, 33], "K").unwrap();
        c.factor(&pat, &v).unwrap();
        assert_eq!(c.position(33), n - 1);
        assert_eq!(c.position(5), n - 3);
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let mut ws = c.workspace(3);
        let mut x = b.clone();
        c.solve_in_place(&mut x, &mut ws);
        let mut ax = vec![0.0; n];
        pat.symmetric_mul(&v, &x, &mut ax);
        for i in 0..n {
            assert!((ax[i] - b[i]).abs() < 1e-10);
        }
        let mut y = vec![0.0; n];
        let mut x2 = vec![0.0; n];
        c.forward(&b, &mut y, &mut ws);
        c.backward(&mut y, &mut x2, &mut ws);
        for i in 0..n {
            assert!((x[i] - x2[i]).abs() < 1e-12);
        }
        // The trailing block is the inverse of L⁻¹ on the tail.
        let m = 3;
        let l_gg = c.trailing_block(m);
        let mut e = vec![0.0; n * m];
        for j in 0..m {
            e[j * n + n - m + j] = 1.0;
        }
        c.forward_many(&mut e, m, &mut ws);
        for i in 0..m {
            for j in 0..m {
                let prod: f64 = (0..m).map(|k| l_gg[(i, k)] * e[j * n + n - m + k]).sum();
                let id = if i == j { 1.0 } else { 0.0 };
                assert!((prod - id).abs() < 1e-12, "({i}, {j}): {prod}");
            }
        }
    }

    #[test]
    fn indefinite_matrix_falls_back_to_lblt_and_solves() {
        let n = 40;
        let (pat, mut v) = laplacian(n);
        // a negative shift makes the matrix indefinite (eigenvalues of the grounded Laplacian lie
        // in (0, 4]) but not singular at this n
        for i in 0..n {
            let d = pat.diagonal_slot(i).unwrap();
            v[d] -= 1.3;
        }
        let mut c = SparseCholesky::analyze(&pat, &[], "K").unwrap();
        assert!(
            c.factor(&pat, &v).is_err(),
            "LLᵀ must refuse an indefinite matrix"
        );
        c.factor_symmetric(&pat, &v).unwrap();
        assert_eq!(c.kind(), FactorKind::Lblt);
        assert_eq!(c.indefinite_factorizations(), 1);
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let mut ws = c.workspace(1);
        let mut x = b.clone();
        c.solve_in_place(&mut x, &mut ws);
        let mut ax = vec![0.0; n];
        pat.symmetric_mul(&v, &x, &mut ax);
        for i in 0..n {
            assert!(
                (ax[i] - b[i]).abs() < 1e-10,
                "row {i}: {} vs {}",
                ax[i],
                b[i]
            );
        }
        // a definite matrix afterwards goes back to LLᵀ
        let (_, spd) = laplacian(n);
        c.factor_symmetric(&pat, &spd).unwrap();
        assert_eq!(c.kind(), FactorKind::Llt);
        assert_eq!(c.indefinite_factorizations(), 1);
    }

    #[test]
    fn singular_matrix_is_a_typed_error() {
        let n = 10;
        let (pat, mut v) = laplacian(n);
        let d = pat.diagonal_slot(0).unwrap();
        v[d] -= 1.0; // pure Neumann: singular
        let mut c = SparseCholesky::analyze(&pat, &[], "K").unwrap();
        assert!(matches!(
            c.factor(&pat, &v),
            Err(SolveError::Singular { .. })
        ));
    }
}
