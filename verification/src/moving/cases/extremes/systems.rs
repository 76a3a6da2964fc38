//! The systems the extreme studies analyse: the string with the standard oscillator, the 2-dof
//! circulatory (Ziegler-type) system with its exact growth rate, and the eigenvalues with the
//! companion's norm.

use nalgebra::Complex;

use contactlab::model::moving::c64;
use contactlab::model::moving::string_data::{ContactModel, MovingStringData};
use contactlab::model::moving::system::MovingSystem;
use contactlab::model::moving::Mat;
use contactlab::solve::quadratic_eigen::QuadraticEigenParams;

use crate::moving::study::Bushing;

/// The eigenvalues of `s` (default eigensolver parameters) and the norm of its companion form.
pub(super) fn eigen(s: &MovingSystem) -> Result<(Vec<c64>, f64), String> {
    let r = s
        .eigen(QuadraticEigenParams::default())
        .map_err(|e| e.to_string())?;
    Ok((r.eigenvalues, r.stats.companion_norm))
}

/// The standard oscillator of the extreme studies: c̄ = 2, m̄ = 1/2 at ā = 0.3.
const STANDARD: Bushing = Bushing {
    stiffness: 2.0,
    mass: 0.5,
    position: 0.3,
};

/// The string at speed v̄ = `speed` with damping ᾱ = `damping` and the standard oscillator, held
/// by `contact` with the friction product μh̄ = `friction`.
pub(super) fn osc(
    speed: f64,
    damping: f64,
    contact: ContactModel,
    friction: f64,
) -> MovingStringData {
    STANDARD.data(speed, damping, contact, friction)
}

/// The 2-dof circulatory system q̈ + (K + pN) q = 0, K = diag(1, 4), N = [0 1; −1 0]:
/// λ² = −(2.5 ± sqrt(2.25 − p²)), a Jordan block at p* = 3/2.
pub(super) fn ziegler(p: f64) -> MovingSystem {
    let mut s = MovingSystem::zeros(vec!["q1".into(), "q2".into()]);
    s.mass = Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { 0.0 });
    s.stiffness = Mat::from_fn(2, 2, |i, j| if i == j { [1.0, 4.0][i] } else { 0.0 });
    s.circulatory = Mat::from_fn(2, 2, |i, j| match (i, j) {
        (0, 1) => p,
        (1, 0) => -p,
        _ => 0.0,
    });
    s
}

/// The exact max Re λ of [`ziegler`].
pub(super) fn ziegler_exact(p: f64) -> f64 {
    let disc = Complex::new(2.25 - p * p, 0.0).sqrt();
    [Complex::new(2.5, 0.0) + disc, Complex::new(2.5, 0.0) - disc]
        .iter()
        .map(|mu| (-mu).sqrt().re.abs())
        .fold(0.0, f64::max)
}
