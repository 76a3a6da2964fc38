//! Symmetric sparse matrices assembled from element matrices: the upper triangle in compressed
//! sparse column form (what faer's Cholesky reads), with precomputed scatter slots so that each
//! reassembly is a pass over the element matrices without searching, and a symmetric
//! matrix–vector product.

/// The sparsity pattern of a symmetric matrix (upper triangle, CSC) and, for each element, the
/// slot of every local entry (p, q) with global g_p ≤ g_q (`u32::MAX` where the entry is dropped:
/// a fixed dof, or the lower triangle).
#[derive(Debug, Clone)]
pub struct SymmetricPattern {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// slots[e * k * k + p * k + q] for elements with k local dofs.
    slots: Vec<u32>,
    local: usize,
}

impl SymmetricPattern {
    /// The pattern of n × n matrices assembled from elements whose local dof `p` maps to the
    /// global dof `dofs[e][p]` (`None` for fixed dofs).
    pub fn new<const K: usize>(n: usize, dofs: &[[Option<usize>; K]]) -> Self {
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n];
        for d in dofs {
            for p in d.iter().flatten() {
                for q in d.iter().flatten() {
                    if p <= q {
                        cols[*q].push(*p);
                    }
                }
            }
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for c in cols.iter_mut() {
            c.sort_unstable();
            c.dedup();
            row_idx.extend_from_slice(c);
            col_ptr.push(row_idx.len());
        }
        let mut slots = vec![u32::MAX; dofs.len() * K * K];
        for (e, d) in dofs.iter().enumerate() {
            for p in 0..K {
                for q in 0..K {
                    if let (Some(gp), Some(gq)) = (d[p], d[q]) {
                        if gp <= gq {
                            let col = &row_idx[col_ptr[gq]..col_ptr[gq + 1]];
                            let pos = col.binary_search(&gp).map(|i| col_ptr[gq] + i);
                            if let Ok(pos) = pos {
                                slots[e * K * K + p * K + q] = pos as u32;
                            }
                        }
                    }
                }
            }
        }
        Self {
            n,
            col_ptr,
            row_idx,
            slots,
            local: K,
        }
    }

    /// The pattern of the upper-triangle entries (i, j), i ≤ j, listed by column: `cols[j]` holds
    /// the rows i ≤ j of column j (in any order, repeats allowed). Such a pattern has no element
    /// slots: fill it through [`Self::slot`].
    pub fn from_columns(mut cols: Vec<Vec<usize>>) -> Self {
        let n = cols.len();
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for (j, c) in cols.iter_mut().enumerate() {
            c.sort_unstable();
            c.dedup();
            debug_assert!(c.last().is_none_or(|&i| i <= j));
            row_idx.extend_from_slice(c);
            col_ptr.push(row_idx.len());
        }
        Self {
            n,
            col_ptr,
            row_idx,
            slots: Vec::new(),
            local: 0,
        }
    }

    /// The order n.
    pub fn order(&self) -> usize {
        self.n
    }

    /// Stored entries (upper triangle).
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Column pointers.
    pub fn col_ptr(&self) -> &[usize] {
        &self.col_ptr
    }

    /// Row indices.
    pub fn row_idx(&self) -> &[usize] {
        &self.row_idx
    }

    /// Adds the element matrix `k` (row-major K × K) of element `e` into `values`.
    #[inline]
    pub fn add_element(&self, values: &mut [f64], e: usize, k: &[f64]) {
        let kk = self.local * self.local;
        for (slot, v) in self.slots[e * kk..(e + 1) * kk].iter().zip(k) {
            if *slot != u32::MAX {
                values[*slot as usize] += v;
            }
        }
    }

    /// The position of the diagonal entry of dof `i`.
    pub fn diagonal_slot(&self, i: usize) -> Option<usize> {
        let col = &self.row_idx[self.col_ptr[i]..self.col_ptr[i + 1]];
        col.binary_search(&i).ok().map(|k| self.col_ptr[i] + k)
    }

    /// The position of entry (i, j), i ≤ j.
    pub fn slot(&self, i: usize, j: usize) -> Option<usize> {
        let (i, j) = (i.min(j), i.max(j));
        let col = &self.row_idx[self.col_ptr[j]..self.col_ptr[j + 1]];
        col.binary_search(&i).ok().map(|k| self.col_ptr[j] + k)
    }

    /// y = A x for the symmetric matrix with upper-triangle `values`.
    pub fn symmetric_mul(&self, values: &[f64], x: &[f64], y: &mut [f64]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        for j in 0..self.n {
            let xj = x[j];
            let mut acc = 0.0;
            for k in self.col_ptr[j]..self.col_ptr[j + 1] {
                let i = self.row_idx[k];
                let a = values[k];
                if i == j {
                    acc += a * xj;
                } else {
                    acc += a * x[i];
                    y[i] += a * xj;
                }
            }
            y[j] += acc;
        }
    }
}

#[cfg(test)]
mod tests {
    //! Symmetric patterns: two overlapping 2-dof elements assemble the expected matrix, fixed dofs
    //! are dropped, and the symmetric product matches a dense one.
    use super::*;

    #[test]
    fn assembly_and_product_match_dense() {
        // dofs: element 0 → (0, 1), element 1 → (1, 2), element 2 → (2, fixed)
        let dofs = vec![[Some(0), Some(1)], [Some(1), Some(2)], [Some(2), None]];
        let pat = SymmetricPattern::new(3, &dofs);
        let mut values = vec![0.0; pat.nnz()];
        let k = [2.0, -1.0, -1.0, 2.0];
        for e in 0..3 {
            pat.add_element(&mut values, e, &k);
        }
        let dense = [[2.0, -1.0, 0.0], [-1.0, 4.0, -1.0], [0.0, -1.0, 4.0]];
        let x = [1.0, -2.0, 0.5];
        let mut y = [0.0; 3];
        pat.symmetric_mul(&values, &x, &mut y);
        for i in 0..3 {
            let expected: f64 = (0..3).map(|j| dense[i][j] * x[j]).sum();
            assert!((y[i] - expected).abs() < 1e-14);
        }
        assert_eq!(pat.nnz(), 5);
        assert!(pat.slot(0, 2).is_none());
        assert!(pat.diagonal_slot(2).is_some());
    }
}
