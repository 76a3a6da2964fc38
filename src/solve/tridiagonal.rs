//! LDLᵀ factorization of a symmetric tridiagonal matrix.
//!
//! The 1D P1 stiffness is tridiagonal; its factorization costs O(M) and a solve is one forward and
//! one backward pass. No general sparse library beats two dependent passes over M numbers, so this
//! kernel is written here rather than taken from faer (which has no banded path).

use crate::error::SolveError;

/// T = L D Lᵀ with L unit lower bidiagonal (multipliers `l`) and D diagonal (pivots `d`).
#[derive(Debug, Clone)]
pub struct SymmetricTridiagonalLdlt {
    inv_d: Vec<f64>,
    l: Vec<f64>,
}

impl SymmetricTridiagonalLdlt {
    /// Factors the matrix with diagonal `diag` (length m) and off-diagonal `off` (length m − 1).
    /// Fails with [`SolveError::Singular`] at the first pivot that is not finite and positive
    /// relative to the row's scale (the matrix must be symmetric positive definite).
    pub fn factor(diag: &[f64], off: &[f64], operator: &str) -> Result<Self, SolveError> {
        let m = diag.len();
        assert_eq!(
            off.len(),
            m.saturating_sub(1),
            "off-diagonal length must be m - 1"
        );
        let mut inv_d = vec![0.0; m];
        let mut l = vec![0.0; m.saturating_sub(1)];
        for i in 0..m {
            let mut d = diag[i];
            if i > 0 {
                d -= l[i - 1] * off[i - 1];
            }
            let scale = diag[i].abs() + if i > 0 { off[i - 1].abs() } else { 0.0 };
            if !(d.is_finite() && d > 1e-14 * scale) {
                return Err(SolveError::Singular {
                    operator: operator.to_string(),
                    row: i,
                    pivot: d,
                });
            }
            inv_d[i] = 1.0 / d;
            if i + 1 < m {
                l[i] = off[i] / d;
            }
        }
        Ok(Self { inv_d, l })
    }

    /// The order m.
    pub fn order(&self) -> usize {
        self.inv_d.len()
    }

    /// Solves T x = b in place (b becomes x).
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let m = self.inv_d.len();
        debug_assert_eq!(b.len(), m);
        for i in 1..m {
            b[i] -= self.l[i - 1] * b[i - 1];
        }
        for (x, inv) in b.iter_mut().zip(&self.inv_d) {
            *x *= inv;
        }
        for i in (0..m.saturating_sub(1)).rev() {
            b[i] -= self.l[i] * b[i + 1];
        }
    }
}

#[cfg(test)]
mod tests {
    //! Tridiagonal LDLᵀ: solves against a dense multiply, and reports indefinite matrices.
    use super::*;

    fn multiply(diag: &[f64], off: &[f64], x: &[f64]) -> Vec<f64> {
        let m = diag.len();
        (0..m)
            .map(|i| {
                let mut s = diag[i] * x[i];
                if i > 0 {
                    s += off[i - 1] * x[i - 1];
                }
                if i + 1 < m {
                    s += off[i] * x[i + 1];
                }
                s
            })
            .collect()
    }

    #[test]
    fn solve_inverts_multiply() {
        let diag = vec![4.0, 5.0, 6.0, 3.0, 2.5];
        let off = vec![-1.0, 2.0, -0.5, 1.0];
        let x: Vec<f64> = vec![1.0, -2.0, 0.5, 3.0, -1.5];
        let mut b = multiply(&diag, &off, &x);
        let f = SymmetricTridiagonalLdlt::factor(&diag, &off, "test").unwrap();
        f.solve_in_place(&mut b);
        for (a, e) in b.iter().zip(&x) {
            assert!((a - e).abs() < 1e-13);
        }
    }

    #[test]
    fn indefinite_matrix_is_reported_with_its_row() {
        let err = SymmetricTridiagonalLdlt::factor(&[1.0, 1.0], &[2.0], "K").unwrap_err();
        match err {
            SolveError::Singular { row, operator, .. } => {
                assert_eq!(row, 1);
                assert_eq!(operator, "K");
            }
            other => panic!("unexpected {other:?}"),
        }
    }

    #[test]
    fn one_by_one_system() {
        let f = SymmetricTridiagonalLdlt::factor(&[2.0], &[], "K").unwrap();
        let mut b = vec![3.0];
        f.solve_in_place(&mut b);
        assert_eq!(b[0], 1.5);
    }
}
