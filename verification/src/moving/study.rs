//! The moving family's study: the eigenvalues of a discretized moving continuum (the string alone
//! or with an oscillator in the bushing), sweeps of the tracked branches over the speed, the
//! flutter onset by bisection, and the independent check of a stability verdict.
//!
//! The check integrates M q̈ + C q̇ + K q = 0 in time from a pseudo-random state (`contactlab::solve::linear_ode`, classical RK4) and compare the observed
//! growth rate of ln ‖(q, q̇)‖ with max Re λ.
//!
//! Observed rate: the least-squares slope through the peaks of ln ‖y(t)‖ in ten windows over the
//! last half of the run ([`envelope_slope`]). For y(t) = Σ c_j x_j e^{λ_j t},
//! ln ‖y‖ = σ t + O(1) with σ = max Re λ once the leading modes dominate (t ≫ 1/(σ − σ₂)); the
//! bounded O(1) part — the beating of a complex pair's real and imaginary parts, and of modes with
//! equal real parts — is largely removed by taking peaks, and what remains contributes
//! (its spread)/(half the run) to the slope, which the tolerance allows for. RK4 damps a mode
//! λ = σ + iω numerically: |R(ikω)|² = 1 − (kω)⁶/72 + O((kω)⁸), a growth-rate error of
//! −k⁵ω⁶/144 per unit time; with k = 0.2/max|λ| it is below 2.3e-6 max|λ| (at k = 0.5/max|λ| it
//! would already bias a mode at ω = 50 by −0.01).

use serde::{Deserialize, Serialize};

use contactlab::model::moving::c64;
use contactlab::model::moving::stability::VerdictParams;
use contactlab::model::moving::stability_map::GridAxis;
use contactlab::model::moving::string_data::{
    ContactModel, MovingStringData, OscillatorData, StringParameter,
};
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};
use contactlab::model::moving::sweep::{string_sweep, Sweep};
use contactlab::model::moving::system::MovingSystem;
use contactlab::solve::linear_ode::{integrate_second_order, LinearOdeParams, LinearTrajectory};
use contactlab::solve::quadratic_eigen::{
    solve_generalized_quadratic_eigen, QuadraticEigen, QuadraticEigenError, QuadraticEigenParams,
};

use crate::stats::lcg::Lcg;

/// What a moving case's `[[gate]]` measures: a named series of (parameter, error) points, e.g.
/// `sine/0.6` (basis/speed).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeriesSelect {
    pub series: String,
}

/// The eigenvalues of a system (default eigensolver parameters).
pub fn eigenvalues(s: &MovingSystem) -> Result<Vec<c64>, String> {
    Ok(s.eigen(QuadraticEigenParams::default())
        .map_err(|e| e.to_string())?
        .eigenvalues)
}

/// The eigenvalues of the string model `model` with data `d`.
pub fn model_eigenvalues(
    model: &MovingStringModel,
    d: &MovingStringData,
) -> Result<Vec<c64>, String> {
    eigenvalues(&model.system(d).map_err(|e| e.to_string())?)
}

/// The eigenvalues of the string discretized by `disc` with data `d`.
pub fn string_eigenvalues(
    disc: StringDiscretization,
    d: &MovingStringData,
) -> Result<Vec<c64>, String> {
    let model = MovingStringModel::new(disc, Default::default()).map_err(|e| e.to_string())?;
    model_eigenvalues(&model, d)
}

/// The oscillator in the bushing: spring c̄, mass m̄, at ā on the string.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bushing {
    pub stiffness: f64,
    pub mass: f64,
    pub position: f64,
}

impl Bushing {
    /// The string at speed v̄ = `speed` with damping ᾱ = `damping` and this oscillator, held by
    /// `contact` with the friction product μh̄ = `friction`.
    pub fn data(
        &self,
        speed: f64,
        damping: f64,
        contact: ContactModel,
        friction: f64,
    ) -> MovingStringData {
        MovingStringData {
            speed,
            damping,
            oscillator: Some(OscillatorData {
                stiffness: self.stiffness,
                mass: self.mass,
                position: self.position,
                contact,
                friction,
                patch_width: 0.0,
            }),
        }
    }
}

/// The eigenvalues of the singular-mass pencil of `full` (a system that keeps the massless
/// bushing coordinate) by QZ on its companion form, eigenvalues beyond 1e-10 of the scale
/// counted infinite.
pub fn pencil_eigen(full: &MovingSystem) -> Result<QuadraticEigen, QuadraticEigenError> {
    solve_generalized_quadratic_eigen(
        full.mass.as_ref(),
        full.velocity_matrix().as_ref(),
        full.stiffness_matrix().as_ref(),
        1e-10,
    )
}

/// `points` speeds v̄ equally spaced from `from` to `to`.
pub fn speed_axis(from: f64, to: f64, points: usize) -> Result<GridAxis, String> {
    GridAxis::linspace(StringParameter::Speed, from, to, points).map_err(|e| e.to_string())
}

/// The spectra and tracked eigenvalue branches of `model` along `axis`, starting from the data
/// `base` (default eigensolver and verdict parameters, every thread).
pub fn speed_sweep(
    model: &MovingStringModel,
    base: &MovingStringData,
    axis: &GridAxis,
) -> Result<Sweep, String> {
    string_sweep(
        model,
        base,
        axis,
        QuadraticEigenParams::default(),
        &VerdictParams::default(),
        0,
    )
    .map_err(|e| e.to_string())
}

/// The flutter onset: the smallest value of the parameter `name` in (0, `hi`] at which the
/// growth rate `growth` (max Re λ) is positive, by bisection. `hi` is doubled until the system
/// is unstable there (an error beyond `limit`), then the bracket is halved until its width is at
/// most `rel_tol` times its upper end; the midpoint of the last bracket. The system must be
/// stable at 0.
pub fn flutter_onset(
    growth: impl Fn(f64) -> Result<f64, String>,
    name: &str,
    hi: f64,
    rel_tol: f64,
    limit: f64,
) -> Result<f64, String> {
    if growth(0.0)? >= 0.0 {
        return Err(format!("not stable at {name} = 0"));
    }
    let (mut lo, mut hi) = (0.0, hi);
    while growth(hi)? <= 0.0 {
        lo = hi;
        hi *= 2.0;
        if hi > limit {
            return Err(format!("no flutter onset below {name} = {limit:e}"));
        }
    }
    while hi - lo > rel_tol * hi {
        let mid = 0.5 * (lo + hi);
        if growth(mid)? > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// One time-integration check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GrowthCheck {
    /// max Re λ from the eigenvalues.
    pub predicted: f64,
    /// The fitted slope of ln ‖y‖ over the last half.
    pub observed: f64,
    pub step: f64,
    pub duration: f64,
    pub steps: usize,
}

/// The growth rate of an oscillating log-norm: the least-squares slope through the maxima of
/// `y` in `windows` equal windows over t ≥ `from` (each maximum at its own time). The peaks of
/// ln ‖y‖ carry the same bounded factor of the mode's geometry, so their slope is σ without the
/// beating that biases a fit through every point.
pub fn envelope_slope(t: &[f64], y: &[f64], from: f64, windows: usize) -> f64 {
    let end = t.last().copied().unwrap_or(0.0);
    let w = (end - from) / windows.max(1) as f64;
    let mut peaks: Vec<(f64, f64)> = Vec::new();
    for k in 0..windows.max(1) {
        let (a, b) = (from + k as f64 * w, from + (k + 1) as f64 * w);
        let best = t
            .iter()
            .zip(y)
            .filter(|(t, y)| **t >= a && **t <= b && y.is_finite())
            .max_by(|p, q| p.1.total_cmp(q.1));
        if let Some((tt, yy)) = best {
            peaks.push((*tt, *yy));
        }
    }
    let (ts, ys): (Vec<f64>, Vec<f64>) = peaks.into_iter().unzip();
    slope_from(&ts, &ys, f64::NEG_INFINITY)
}

/// The least-squares slope of `y` against `t` over t ≥ `from`.
pub fn slope_from(t: &[f64], y: &[f64], from: f64) -> f64 {
    let pts: Vec<(f64, f64)> = t
        .iter()
        .zip(y)
        .filter(|(t, y)| **t >= from && y.is_finite())
        .map(|(t, y)| (*t, *y))
        .collect();
    let n = pts.len() as f64;
    if n < 2.0 {
        return f64::NAN;
    }
    let mt = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mt).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mt) * (p.1 - my)).sum();
    sxy / sxx
}

/// The most RK4 steps a time check may take (the suite's checks take at most about 2·10⁵).
pub const MAX_TIME_CHECK_STEPS: usize = 5_000_000;

/// Integrates `system` over `duration` from a pseudo-random state (seed `seed`) with the step
/// 0.2/ρ (ρ = max |λ|, capped to duration/200) and compares the growth rate with `predicted`;
/// refuses (an error) when that needs more than [`MAX_TIME_CHECK_STEPS`] steps.
pub fn check_growth(
    system: &MovingSystem,
    predicted: f64,
    spectral_scale: f64,
    duration: f64,
    seed: u64,
) -> Result<(GrowthCheck, LinearTrajectory), String> {
    let n = system.dimension();
    let mut rng = Lcg(seed);
    let q0: Vec<f64> = (0..n).map(|_| rng.next_signed()).collect();
    let v0: Vec<f64> = (0..n).map(|_| rng.next_signed()).collect();
    let step = (0.2 / spectral_scale.max(1e-300)).min(duration / 200.0);
    let steps = (duration / step).ceil();
    // A stiff system (ρ huge: a spring of 10³² from a lost basis value, say) would need ~10¹⁹
    // RK4 steps: refuse with the reason instead of running for ever.
    if steps.is_nan() || steps > MAX_TIME_CHECK_STEPS as f64 {
        return Err(format!(
            "the time check would need {steps:.3e} RK4 steps (spectral scale ρ = {spectral_scale:.3e}, \
             step 0.2/ρ over {duration}), more than {MAX_TIME_CHECK_STEPS}: the system is too stiff \
             for an explicit check"
        ));
    }
    let steps = steps as usize;
    let record_every = (steps / 2000).max(1);
    let params = LinearOdeParams {
        step,
        steps,
        record_every,
    };
    let traj = integrate_second_order(
        system.mass.as_ref(),
        system.velocity_matrix().as_ref(),
        system.stiffness_matrix().as_ref(),
        &q0,
        &v0,
        &params,
    )
    .map_err(|e| e.to_string())?;
    let observed = envelope_slope(&traj.times, &traj.log_norms, 0.5 * duration, 10);
    Ok((
        GrowthCheck {
            predicted,
            observed,
            step,
            duration: steps as f64 * step,
            steps,
        },
        traj,
    ))
}
