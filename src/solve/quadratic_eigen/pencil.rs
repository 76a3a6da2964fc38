//! The QZ path for a singular mass matrix: the generalized companion pencil, its infinite
//! eigenvalues dropped.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::ComputeEigenvectors;
use faer::linalg::gevd;
use faer::{c64, Mat, MatRef, Par};

use crate::solve::quadratic_eigen::types::{
    check_square, frobenius_norm, QuadraticEigen, QuadraticEigenError, QuadraticEigenStats,
};

/// Solves (λ² M + λ C + K) x = 0 for a symmetric positive *semi*-definite M (massless
/// coordinates) through the generalized companion pencil
/// `[0 I; −K −C] y = λ [I 0; 0 M] y`, by faer's QZ algorithm (`Par::Seq`). Eigenvalues with
/// |β| ≤ `infinite_tolerance`·|α| (α/β = λ) are infinite — one per massless coordinate for the
/// DAEs of this crate — and are dropped; the finite ones are returned. No scaling is applied.
pub fn solve_generalized_quadratic_eigen(
    mass: MatRef<'_, f64>,
    damping: MatRef<'_, f64>,
    stiffness: MatRef<'_, f64>,
    infinite_tolerance: f64,
) -> Result<QuadraticEigen, QuadraticEigenError> {
    let n = mass.nrows();
    check_square("mass matrix", mass, n)?;
    check_square("damping matrix", damping, n)?;
    check_square("stiffness matrix", stiffness, n)?;
    if !(infinite_tolerance.is_finite() && infinite_tolerance > 0.0) {
        return Err(QuadraticEigenError::InvalidParameter {
            field: "infinite_tolerance".into(),
            value: infinite_tolerance,
            expected: "a finite number > 0".into(),
        });
    }
    let mut a = Mat::<f64>::zeros(2 * n, 2 * n);
    let mut b = Mat::<f64>::zeros(2 * n, 2 * n);
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        b[(i, i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = -stiffness[(i, j)];
            a[(n + i, n + j)] = -damping[(i, j)];
            b[(n + i, n + j)] = mass[(i, j)];
        }
    }
    let companion_norm = frobenius_norm(a.as_ref());
    let mut s_re = faer::diag::Diag::<f64>::zeros(2 * n);
    let mut s_im = faer::diag::Diag::<f64>::zeros(2 * n);
    let mut beta = faer::diag::Diag::<f64>::zeros(2 * n);
    // faer 0.24.4's gevd_real returns zero α and β for most eigenvalues of pencils of order
    // ≳ 40 when no eigenvectors are requested (reproduced at order 44 with B = I); with the right
    // eigenvectors requested it is correct. Request them.
    let mut vectors = Mat::<f64>::zeros(2 * n, 2 * n);
    let mut buf = MemBuffer::new(gevd::gevd_scratch::<f64>(
        2 * n,
        ComputeEigenvectors::No,
        ComputeEigenvectors::Yes,
        Par::Seq,
        Default::default(),
    ));
    gevd::gevd_real(
        a.as_mut(),
        b.as_mut(),
        s_re.as_mut(),
        s_im.as_mut(),
        beta.as_mut(),
        None,
        Some(vectors.as_mut()),
        Par::Seq,
        MemStack::new(&mut buf),
        Default::default(),
    )
    .map_err(|_| QuadraticEigenError::NoConvergence {
        dimension: 2 * n,
        what: "generalized companion pencil",
    })?;
    let mut eigenvalues = Vec::with_capacity(2 * n);
    let mut infinite = 0;
    // A complex pair occupies i, i+1 with α = re ± i·im and the common β = beta[i].
    let mut i = 0;
    while i < 2 * n {
        let pair = s_im[i] != 0.0 && i + 1 < 2 * n;
        let alpha = c64::new(s_re[i], s_im[i]);
        let b = beta[i];
        let count = if pair { 2 } else { 1 };
        if b.abs() <= infinite_tolerance * alpha.norm() {
            infinite += count;
        } else {
            eigenvalues.push(alpha / b);
            if pair {
                eigenvalues.push(alpha.conj() / b);
            }
        }
        i += count;
    }
    Ok(QuadraticEigen {
        eigenvalues,
        eigenvectors: None,
        stats: QuadraticEigenStats {
            dimension: n,
            scaling: 1.0,
            companion_norm,
            mass_condition_bound: f64::INFINITY,
            max_backward_error: 0.0,
            infinite_eigenvalues: infinite,
        },
    })
}
