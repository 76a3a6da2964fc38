//! The bounds of the moving cases' non-rate checks, stated once: round-off in units of ε (times
//! a stated scale) and error-model ceilings with a factor of at most
//! [`MAX_CEILING_FACTOR`](crate::core::gate::MAX_CEILING_FACTOR).

use std::path::Path;

use nalgebra::{Complex, DMatrix};

use crate::core::format::{invalid, CaseError};
use crate::core::gate::MAX_CEILING_FACTOR;

/// Checks an error-model ceiling factor: 1 < `v` ≤ [`MAX_CEILING_FACTOR`].
pub fn ceiling_factor(path: &Path, field: &str, v: f64) -> Result<(), CaseError> {
    if v > 1.0 && v <= MAX_CEILING_FACTOR {
        Ok(())
    } else {
        Err(invalid(
            path,
            field,
            v,
            &format!("in (1, {MAX_CEILING_FACTOR}]"),
        ))
    }
}

/// The error model E(N) = C N^{−rate} fitted at `coarse` predicts E at `fine`:
/// E(coarse) · (coarse/fine)^rate.
pub fn predicted_error(coarse_error: f64, coarse: f64, fine: f64, rate: f64) -> f64 {
    coarse_error * (coarse / fine).powf(rate)
}

/// The condition number κ(λ) = ‖x‖‖y‖/|yᴴx| of the eigenvalue λ of `a`, with x and y from one
/// step of inverse iteration with A − λI and its adjoint (λ is accurate to round-off, so the
/// solve amplifies the eigenvector's component by 1/|round-off|).
pub fn condition(a: &DMatrix<f64>, lambda: Complex<f64>) -> f64 {
    let n = a.nrows();
    // shifted off λ by 1e-12 |λ| (an exactly singular pivot would stop the solve; the shift
    // changes the iteration's contraction, not its limit)
    let mu = lambda + Complex::new(1.0, 1.0) * (1e-12 * lambda.norm().max(1.0));
    let shifted = DMatrix::from_fn(n, n, |i, j| {
        Complex::new(a[(i, j)], 0.0) - if i == j { mu } else { Complex::new(0.0, 0.0) }
    });
    // a fixed, generic right-hand side (no accidental orthogonality to an eigenvector)
    let rhs = nalgebra::DVector::from_fn(n, |i, _| {
        Complex::new(1.0 + 0.37 * i as f64, 0.11 * i as f64 - 0.5)
    });
    let solve = |m: DMatrix<Complex<f64>>| -> Option<nalgebra::DVector<Complex<f64>>> {
        let lu = m.lu();
        let x = lu.solve(&rhs)?;
        let x = x.unscale(x.norm());
        let x = lu.solve(&x)?;
        Some(x.unscale(x.norm()))
    };
    let (Some(x), Some(y)) = (solve(shifted.clone()), solve(shifted.adjoint())) else {
        // no condition number: the gate that divides by it fails (NaN)
        return f64::NAN;
    };
    1.0 / y.dotc(&x).norm()
}

/// How two eigensolvers' spectra of the same first-order matrix agree.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Agreement {
    /// max over the reference's eigenvalues λ of |Δλ| / (κ(λ) (n ε ‖A‖_F + `perturbation`)),
    /// Δλ the distance to the nearest eigenvalue of the other spectrum: at most about 1 when the
    /// difference is the backward error of a backward-stable solver (first-order perturbation
    /// theory), plus a known matrix perturbation of Frobenius norm `perturbation`.
    pub ratio: f64,
    /// max |Δλ| / max |λ|.
    pub relative: f64,
    /// The largest κ(λ).
    pub max_condition: f64,
}

/// Compares the eigenvalues `other` with `reference`, the eigenvalues of the first-order matrix
/// `a` (see [`Agreement`]); an error when the counts differ.
pub fn agreement(
    a: &DMatrix<f64>,
    reference: &[Complex<f64>],
    other: &[Complex<f64>],
    perturbation: f64,
) -> Result<Agreement, String> {
    if reference.len() != other.len() {
        return Err(format!(
            "{} eigenvalues against {} of the reference",
            other.len(),
            reference.len()
        ));
    }
    let unit = a.nrows() as f64 * f64::EPSILON * a.norm() + perturbation;
    let rho = reference.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let (mut ratio, mut relative, mut max_condition) = (0.0f64, 0.0f64, 0.0f64);
    for &l in reference {
        let nearest = other
            .iter()
            .map(|m| (m - l).norm())
            .fold(f64::INFINITY, f64::min);
        let kappa = condition(a, l);
        max_condition = max_condition.max(kappa);
        ratio = ratio.max(nearest / (unit * kappa));
        relative = relative.max(nearest / rho);
    }
    Ok(Agreement {
        ratio,
        relative,
        max_condition,
    })
}
