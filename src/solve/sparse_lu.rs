//! Sparse LU with partial pivoting (faer, supernodal) of an unsymmetric matrix J = S + W whose
//! symmetric part S and skew part W are stored on one symmetric pattern (upper triangles):
//! J_ij = S_ij + W_ij and J_ji = S_ij − W_ij for i < j.
//!
//! The exact Newton tangent of Gonzalez's discrete gradient, ∂F^algo/∂u1, is not symmetric; the
//! step operator factors its symmetric part by Cholesky and keeps that symmetric tangent as long
//! as it is positive definite. When it is not (large steps of a stiff hyperelastic body), the
//! symmetric part alone is no longer a useful Newton matrix — the Newton direction need not
//! reduce ‖R‖ — and the step falls back to this factorization of the exact tangent. The column
//! order (COLAMD) and the supernodal structure are analyzed once; each factorization is numeric
//! only, sequential (the same bits whatever the machine).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuSymbolicParams, NumericLu, SymbolicLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par};

use crate::error::SolveError;
use crate::fem::sparse::SymmetricPattern;

/// The analysis of J's full pattern and the storage of its factors.
pub struct SparseLu {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// For each slot of the symmetric pattern (entry (i, j), i ≤ j): the full pattern's slots
    /// of (i, j) and of (j, i) (equal on the diagonal).
    slots: Vec<(usize, usize)>,
    values: Vec<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    factor_stack: MemBuffer,
    solve_stack: MemBuffer,
    operator: String,
}

impl std::fmt::Debug for SparseLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SparseLu(n = {}, {} entries)", self.n, self.values.len())
    }
}

impl SparseLu {
    /// Analyzes the full pattern of matrices whose symmetric and skew parts live on `pattern`
    /// (faer chooses the simplicial or the supernodal factorization by its flop estimate).
    pub fn analyze(pattern: &SymmetricPattern, operator: &str) -> Result<Self, SolveError> {
        Self::analyze_with(pattern, operator, SupernodalThreshold::AUTO)
    }

    /// [`Self::analyze`] with the supernodal factorization whatever the size: faer's simplicial
    /// LU has no symbolic structure (it redoes the column reaches at every factorization), which
    /// a step matrix refactored at every Newton iteration pays each time (measured on the
    /// two-ring impact, 960 unknowns: 59 % of the run in the simplicial factorization).
    pub fn analyze_supernodal(
        pattern: &SymmetricPattern,
        operator: &str,
    ) -> Result<Self, SolveError> {
        Self::analyze_with(pattern, operator, SupernodalThreshold::FORCE_SUPERNODAL)
    }

    fn analyze_with(
        pattern: &SymmetricPattern,
        operator: &str,
        threshold: SupernodalThreshold,
    ) -> Result<Self, SolveError> {
        let n = pattern.order();
        let failed = |why: &str| SolveError::Singular {
            operator: format!("{operator} ({why})"),
            row: 0,
            pivot: f64::NAN,
        };
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        // column j of the full pattern: the rows i ≤ j of column j (upper part and diagonal),
        // then the rows i > j, i.e. the columns i whose upper part holds row j
        let mut count = vec![0usize; n];
        for j in 0..n {
            for &i in &ri[cp[j]..cp[j + 1]] {
                count[j] += 1;
                if i != j {
                    count[i] += 1;
                }
            }
        }
        let mut col_ptr = vec![0usize; n + 1];
        for j in 0..n {
            col_ptr[j + 1] = col_ptr[j] + count[j];
        }
        let mut next = col_ptr[..n].to_vec();
        let mut row_idx = vec![0usize; col_ptr[n]];
        let mut slots = vec![(0usize, 0usize); ri.len()];
        // rows in increasing order in every column: upper rows i ≤ j come first (columns visited
        // in order j, and within a column in increasing i), the lower rows i > j are appended
        // while visiting the later columns i in increasing order
        for j in 0..n {
            for s in cp[j]..cp[j + 1] {
                let i = ri[s];
                let upper = next[j];
                row_idx[upper] = i;
                next[j] += 1;
                if i == j {
                    slots[s] = (upper, upper);
                }
            }
        }
        for j in 0..n {
            for s in cp[j]..cp[j + 1] {
                let i = ri[s];
                if i != j {
                    // entry (j, i) lies in column i, row j > i
                    let lower = next[i];
                    row_idx[lower] = j;
                    next[i] += 1;
                    let upper = col_ptr[j] + (s - cp[j]);
                    slots[s] = (upper, lower);
                }
            }
        }
        let sym = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
        let params = LuSymbolicParams {
            supernodal_flop_ratio_threshold: threshold,
            ..Default::default()
        };
        let symbolic =
            factorize_symbolic_lu(sym, params).map_err(|_| failed("symbolic analysis"))?;
        let factor_stack = MemBuffer::new(
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
        );
        let solve_stack = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        Ok(Self {
            n,
            values: vec![0.0; row_idx.len()],
            col_ptr,
            row_idx,
            slots,
            symbolic,
            numeric: NumericLu::new(),
            factor_stack,
            solve_stack,
            operator: operator.to_string(),
        })
    }

    /// Factors J = S + W (`sym`, `skew`: upper triangles on the analyzed pattern) and solves
    /// J x = b in place. A non-finite entry, a structurally or numerically singular J or a
    /// non-finite solution is a [`SolveError::Singular`].
    pub fn factor_solve(
        &mut self,
        sym: &[f64],
        skew: &[f64],
        x: &mut [f64],
    ) -> Result<(), SolveError> {
        for (s, &(upper, lower)) in self.slots.iter().enumerate() {
            self.values[upper] = sym[s] + skew[s];
            if lower != upper {
                self.values[lower] = sym[s] - skew[s];
            }
        }
        if let Some(bad) = self.values.iter().position(|v| !v.is_finite()) {
            return Err(SolveError::Singular {
                operator: format!("{} (non-finite matrix entry)", self.operator),
                row: self.row_idx[bad],
                pivot: self.values[bad],
            });
        }
        let a = SparseColMatRef::new(
            SymbolicSparseColMatRef::new_checked(
                self.n,
                self.n,
                &self.col_ptr,
                None,
                &self.row_idx,
            ),
            &self.values,
        );
        let lu = self
            .symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                a,
                Par::Seq,
                MemStack::new(&mut self.factor_stack),
                Default::default(),
            )
            .map_err(|e| SolveError::Singular {
                operator: format!("{} (LU)", self.operator),
                row: match e {
                    faer::sparse::linalg::LuError::SymbolicSingular { index } => index,
                    faer::sparse::linalg::LuError::Generic(_) => 0,
                },
                pivot: 0.0,
            })?;
        lu.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(x, self.n, 1),
            Par::Seq,
            MemStack::new(&mut self.solve_stack),
        );
        if let Some(bad) = x.iter().position(|v| !v.is_finite()) {
            return Err(SolveError::Singular {
                operator: format!("{} (LU: singular, non-finite solution)", self.operator),
                row: bad,
                pivot: f64::NAN,
            });
        }
        Ok(())
    }

    /// y = J x with J = S + W as stored by [`Self::factor_solve`] (its last call).
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        for (j, &xj) in x.iter().enumerate().take(self.n) {
            for s in self.col_ptr[j]..self.col_ptr[j + 1] {
                y[self.row_idx[s]] += self.values[s] * xj;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    //! The LU of S + W: its solve against a dense product, and a singular matrix is a typed
    //! error.
    use super::*;

    fn chain(n: usize) -> SymmetricPattern {
        let dofs: Vec<[Option<usize>; 2]> = (0..n - 1).map(|i| [Some(i), Some(i + 1)]).collect();
        SymmetricPattern::new(n, &dofs)
    }

    #[test]
    fn lu_solves_an_unsymmetric_indefinite_system() {
        let n = 30;
        let pat = chain(n);
        let mut sym = vec![0.0; pat.nnz()];
        let mut skew = vec![0.0; pat.nnz()];
        for e in 0..n - 1 {
            pat.add_element(&mut sym, e, &[0.0, 0.3, 0.3, 0.0]);
            pat.add_element(&mut skew, e, &[0.0, 0.7, -0.7, 0.0]);
        }
        // an indefinite symmetric part (alternating signs on the diagonal), diagonally dominant
        // so that J is well conditioned
        for i in 0..n {
            sym[pat.diagonal_slot(i).unwrap()] = if i % 2 == 0 { 3.0 } else { -3.0 };
        }
        let mut lu = SparseLu::analyze(&pat, "J").unwrap();
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos()).collect();
        let mut x = b.clone();
        lu.factor_solve(&sym, &skew, &mut x).unwrap();
        // J x by the definition J_ij = S_ij + W_ij (i < j), J_ji = S_ij − W_ij, written densely
        let mut dense = vec![0.0; n * n];
        for j in 0..n {
            for s in pat.col_ptr()[j]..pat.col_ptr()[j + 1] {
                let i = pat.row_idx()[s];
                dense[i * n + j] = sym[s] + skew[s];
                if i != j {
                    dense[j * n + i] = sym[s] - skew[s];
                }
            }
        }
        for i in 0..n {
            let ax: f64 = (0..n).map(|j| dense[i * n + j] * x[j]).sum();
            assert!((ax - b[i]).abs() < 1e-12, "row {i}: {ax} vs {}", b[i]);
        }
        let mut y = vec![0.0; n];
        lu.mul(&x, &mut y);
        for i in 0..n {
            assert!((y[i] - b[i]).abs() < 1e-12);
        }
    }

    #[test]
    fn singular_lu_is_a_typed_error() {
        let n = 6;
        let pat = chain(n);
        let mut sym = vec![0.0; pat.nnz()];
        for e in 0..n - 1 {
            pat.add_element(&mut sym, e, &[1.0, -1.0, -1.0, 1.0]); // pure Neumann: singular
        }
        let skew = vec![0.0; pat.nnz()];
        let mut lu = SparseLu::analyze(&pat, "J").unwrap();
        let mut x = vec![1.0; n];
        assert!(matches!(
            lu.factor_solve(&sym, &skew, &mut x),
            Err(SolveError::Singular { .. })
        ));
    }
}
