//! What both quadratic eigensolvers share: their parameters, results and errors, and the checks
//! of their input matrices.

use faer::{c64, Mat, MatRef};

/// Which dense eigensolver runs on the companion matrix.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EigenKernel {
    /// faer's dense real eigensolver (Hessenberg reduction and Francis QR, `Par::Seq`): the
    /// reference, and the only kernel that computes eigenvectors.
    #[default]
    Faer,
    /// The eigenvalue-only kernel of `solve::small_eigenvalues` (Householder + Francis QR on an
    /// L1-resident row-major array), ≈ 2× faster for orders ≈ 40: the stability maps' kernel.
    SmallDense,
}

/// Options of the quadratic eigensolver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadraticEigenParams {
    /// Also compute the eigenvectors x (unit 2-norm), and their backward errors.
    pub compute_eigenvectors: bool,
    /// Scale the eigenvalue by γ = sqrt(‖K‖_F/‖M‖_F) (Fan, Lin & Van Dooren 2004). Leave on.
    pub scale: bool,
    /// Balance the companion matrix by a diagonal similarity with powers of 2 (exact in
    /// floating point; Parlett & Reinsch 1969, LAPACK dgebal) before the QR algorithm: rows and
    /// columns of comparable norm reduce the round-off of small eigenvalues and the number of QR
    /// sweeps. Applied to eigenvalue-only solves.
    pub balance: bool,
    /// Largest accepted relative symmetry defect ‖M − Mᵀ‖_F / ‖M‖_F of the mass matrix.
    pub mass_symmetry_tolerance: f64,
    /// The dense eigensolver (eigenvectors always use faer).
    pub kernel: EigenKernel,
}

impl Default for QuadraticEigenParams {
    fn default() -> Self {
        Self {
            compute_eigenvectors: false,
            scale: true,
            balance: true,
            mass_symmetry_tolerance: 1e-12,
            kernel: EigenKernel::Faer,
        }
    }
}

impl QuadraticEigenParams {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), QuadraticEigenError> {
        let t = self.mass_symmetry_tolerance;
        if !(t.is_finite() && (0.0..1.0).contains(&t)) {
            return Err(QuadraticEigenError::InvalidParameter {
                field: "mass_symmetry_tolerance".into(),
                value: t,
                expected: "a finite number in [0, 1)".into(),
            });
        }
        Ok(())
    }
}

/// What the solve did and how well.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct QuadraticEigenStats {
    /// n, the number of coordinates.
    pub dimension: usize,
    /// The eigenvalue scaling γ (1 without scaling).
    pub scaling: f64,
    /// ‖A_γ‖_F of the scaled companion matrix.
    pub companion_norm: f64,
    /// (max/min diagonal of the Cholesky factor of M)²: a lower bound of the condition number of M.
    pub mass_condition_bound: f64,
    /// Largest backward error η(x, λ) = ‖(λ²M + λC + K)x‖ / ((|λ|²‖M‖ + |λ|‖C‖ + ‖K‖)‖x‖) over
    /// the eigenpairs (Tisseur 2000, Thm 1); 0 when the eigenvectors were not computed.
    pub max_backward_error: f64,
    /// Eigenvalues discarded as infinite (generalized solver only).
    pub infinite_eigenvalues: usize,
}

/// The eigenvalues (and eigenvectors) of a quadratic eigenproblem.
#[derive(Debug, Clone)]
pub struct QuadraticEigen {
    /// The 2n eigenvalues (fewer for a singular mass: the finite ones), in the eigensolver's order;
    /// complex ones come in adjacent conjugate pairs.
    pub eigenvalues: Vec<c64>,
    /// The n × (number of eigenvalues) matrix of eigenvectors x (unit 2-norm), column j for
    /// eigenvalue j, when asked for.
    pub eigenvectors: Option<Mat<c64>>,
    pub stats: QuadraticEigenStats,
}

/// Why a quadratic eigenproblem could not be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QuadraticEigenError {
    /// A matrix of the wrong shape.
    #[error("invalid {matrix}: {rows}×{cols}, expected {expected}×{expected}")]
    Shape {
        matrix: &'static str,
        rows: usize,
        cols: usize,
        expected: usize,
    },
    /// A NaN or infinite entry.
    #[error("invalid {matrix}[{row}, {col}] = {value}: expected a finite number")]
    NonFinite {
        matrix: &'static str,
        row: usize,
        col: usize,
        value: f64,
    },
    /// The mass matrix is not symmetric.
    #[error(
        "invalid mass matrix: relative symmetry defect ‖M − Mᵀ‖/‖M‖ = {defect:e}, expected <= {tolerance:e}"
    )]
    MassNotSymmetric { defect: f64, tolerance: f64 },
    /// The mass matrix is singular or indefinite (a massless coordinate: condense it, or use the
    /// generalized solver).
    #[error(
        "singular or indefinite mass matrix: Cholesky pivot {pivot} at row {row}; condense massless \
         coordinates or use the generalized (QZ) solver"
    )]
    MassNotPositiveDefinite { row: usize, pivot: usize },
    /// The dense eigensolver reached its iteration limit.
    #[error("the dense eigensolver did not converge on the {dimension}×{dimension} {what}")]
    NoConvergence {
        dimension: usize,
        what: &'static str,
    },
    /// An invalid parameter of the solver.
    #[error("invalid {field} = {value}: expected {expected}")]
    InvalidParameter {
        field: String,
        value: f64,
        expected: String,
    },
}

/// Checks that `a` (named `matrix` in errors) is n × n with finite entries.
pub(super) fn check_square(
    matrix: &'static str,
    a: MatRef<'_, f64>,
    n: usize,
) -> Result<(), QuadraticEigenError> {
    if a.nrows() != n || a.ncols() != n {
        return Err(QuadraticEigenError::Shape {
            matrix,
            rows: a.nrows(),
            cols: a.ncols(),
            expected: n,
        });
    }
    for j in 0..n {
        for i in 0..n {
            let v = a[(i, j)];
            if !v.is_finite() {
                return Err(QuadraticEigenError::NonFinite {
                    matrix,
                    row: i,
                    col: j,
                    value: v,
                });
            }
        }
    }
    Ok(())
}

/// ‖A‖_F.
pub fn frobenius_norm(a: MatRef<'_, f64>) -> f64 {
    let mut s = 0.0;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            s += a[(i, j)] * a[(i, j)];
        }
    }
    s.sqrt()
}
