//! Time integration of M q̈ + C q̇ + K q = 0 by the classical fourth-order Runge–Kutta method,
//! the independent check of eigenvalue-based stability verdicts: the observed growth rate of
//! ln ‖(q, q̇)‖ must approach max Re λ.
//!
//! With A = M⁻¹C and B = M⁻¹K (one Cholesky factorization of M, `Par::Seq`), the state
//! y = (q, v) obeys y' = F y, F = [0 I; −B −A], and a step is
//! y_{n+1} = y_n + k (k1 + 2k2 + 2k3 + k4)/6 (Hairer, Nørsett & Wanner 1993, II.1). For a mode
//! e^{λt} the step multiplies by R(kλ) = 1 + kλ + (kλ)²/2 + (kλ)³/6 + (kλ)⁴/24, so the observed
//! rate is ln|R(kλ)|/k = Re λ + O(k⁴|λ|⁵); steps must satisfy |kλ| < 2.7 for every λ.
//! The state is renormalized whenever its norm exceeds 1e100 (the scale is kept in the log), so
//! long runs of unstable systems never overflow.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::{Conj, Mat, MatRef, Par};

use crate::error::{Error, InputError, SolveError};
use crate::solve::dense_cholesky::cholesky_factor;

/// Options of the integration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearOdeParams {
    /// The time step k > 0.
    pub step: f64,
    /// The number of steps.
    pub steps: usize,
    /// Record ln ‖y‖ every this many steps (and at the end).
    pub record_every: usize,
}

impl Default for LinearOdeParams {
    fn default() -> Self {
        Self {
            step: 1e-2,
            steps: 10_000,
            record_every: 10,
        }
    }
}

impl LinearOdeParams {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), InputError> {
        crate::error::require_positive("integration.step", self.step)?;
        if self.steps == 0 {
            return Err(InputError::new("integration.steps", 0, "at least 1 step"));
        }
        if self.record_every == 0 {
            return Err(InputError::new("integration.record_every", 0, "at least 1"));
        }
        Ok(())
    }
}

/// What the integration did.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct LinearOdeStats {
    pub steps: usize,
    /// Renormalizations of the state (each adds its scale to the log).
    pub rescalings: usize,
}

/// The recorded history.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearTrajectory {
    pub times: Vec<f64>,
    /// ln ‖(q, q̇)‖₂ at `times` (including the renormalizations).
    pub log_norms: Vec<f64>,
    /// q at the end, scaled by e^{−(accumulated log scale)}.
    pub final_q: Vec<f64>,
    pub stats: LinearOdeStats,
}

/// Integrates M q̈ + C q̇ + K q = 0 from (q0, v0) (see the module docs). M must be symmetric
/// positive definite.
pub fn integrate_second_order(
    mass: MatRef<'_, f64>,
    damping: MatRef<'_, f64>,
    stiffness: MatRef<'_, f64>,
    q0: &[f64],
    v0: &[f64],
    params: &LinearOdeParams,
) -> Result<LinearTrajectory, Error> {
    params.validate()?;
    let n = mass.nrows();
    for (name, a) in [
        ("mass", mass),
        ("damping", damping),
        ("stiffness", stiffness),
    ] {
        if a.nrows() != n || a.ncols() != n {
            return Err(InputError::new(
                format!("integration.{name}"),
                format!("{}×{}", a.nrows(), a.ncols()),
                format!("{n}×{n}"),
            )
            .into());
        }
    }
    if q0.len() != n || v0.len() != n {
        return Err(InputError::new(
            "integration.initial_state",
            format!("{} + {} values", q0.len(), v0.len()),
            format!("{n} + {n} values"),
        )
        .into());
    }
    // [B, A] = M⁻¹ [K, C].
    let factor = cholesky_factor(mass).map_err(|index| SolveError::Singular {
        operator: "mass matrix (integration)".into(),
        row: index,
        pivot: f64::NAN,
    })?;
    let mut buf = MemBuffer::new(llt::solve::solve_in_place_scratch::<f64>(
        n,
        2 * n,
        Par::Seq,
    ));
    let mut ba = Mat::<f64>::from_fn(n, 2 * n, |i, j| {
        if j < n {
            stiffness[(i, j)]
        } else {
            damping[(i, j - n)]
        }
    });
    llt::solve::solve_in_place_with_conj(
        factor.as_ref(),
        Conj::No,
        ba.as_mut(),
        Par::Seq,
        MemStack::new(&mut buf),
    );
    let rhs = |q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]| {
        dq.copy_from_slice(v);
        for (i, d) in dv.iter_mut().enumerate() {
            let mut s = 0.0;
            for j in 0..n {
                s -= ba[(i, j)] * q[j] + ba[(i, n + j)] * v[j];
            }
            *d = s;
        }
    };
    let k = params.step;
    let (mut q, mut v) = (q0.to_vec(), v0.to_vec());
    let mut k1 = (vec![0.0; n], vec![0.0; n]);
    let mut k2 = k1.clone();
    let mut k3 = k1.clone();
    let mut k4 = k1.clone();
    let mut tmp = k1.clone();
    let mut log_scale = 0.0;
    let mut stats = LinearOdeStats::default();
    let norm = |q: &[f64], v: &[f64]| {
        (q.iter().map(|x| x * x).sum::<f64>() + v.iter().map(|x| x * x).sum::<f64>()).sqrt()
    };
    let mut times = vec![0.0];
    let mut log_norms = vec![norm(&q, &v).ln()];
    for step in 1..=params.steps {
        if step % 1024 == 0 {
            crate::run_control::check(|| {
                format!("step {step} of {} of the time integration", params.steps)
            })?;
        }
        rhs(&q, &v, &mut k1.0, &mut k1.1);
        for i in 0..n {
            tmp.0[i] = q[i] + 0.5 * k * k1.0[i];
            tmp.1[i] = v[i] + 0.5 * k * k1.1[i];
        }
        rhs(&tmp.0, &tmp.1, &mut k2.0, &mut k2.1);
        for i in 0..n {
            tmp.0[i] = q[i] + 0.5 * k * k2.0[i];
            tmp.1[i] = v[i] + 0.5 * k * k2.1[i];
        }
        rhs(&tmp.0, &tmp.1, &mut k3.0, &mut k3.1);
        for i in 0..n {
            tmp.0[i] = q[i] + k * k3.0[i];
            tmp.1[i] = v[i] + k * k3.1[i];
        }
        rhs(&tmp.0, &tmp.1, &mut k4.0, &mut k4.1);
        for i in 0..n {
            q[i] += k / 6.0 * (k1.0[i] + 2.0 * k2.0[i] + 2.0 * k3.0[i] + k4.0[i]);
            v[i] += k / 6.0 * (k1.1[i] + 2.0 * k2.1[i] + 2.0 * k3.1[i] + k4.1[i]);
        }
        let nrm = norm(&q, &v);
        if !nrm.is_finite() {
            return Err(SolveError::NonFinite {
                step,
                time: step as f64 * k,
                quantity: "state norm".into(),
                value: nrm,
                hint: " (is the step above the RK4 bound 2.7/max|λ|?)".into(),
            }
            .into());
        }
        if nrm > 1e100 || (nrm < 1e-100 && nrm > 0.0) {
            q.iter_mut().chain(v.iter_mut()).for_each(|x| *x /= nrm);
            log_scale += nrm.ln();
            stats.rescalings += 1;
        }
        stats.steps = step;
        if step % params.record_every == 0 || step == params.steps {
            times.push(step as f64 * k);
            log_norms.push(norm(&q, &v).ln() + log_scale);
        }
    }
    Ok(LinearTrajectory {
        times,
        log_norms,
        final_q: q,
        stats,
    })
}

#[cfg(test)]
mod tests {
    //! Setting: a damped scalar oscillator, q̈ + 0.2 q̇ + q = 0, and an unstable one. Goal: the
    //! log-norm decays at Re λ = −0.1 and grows at the unstable rate.
    use super::*;

    fn one(x: f64) -> Mat<f64> {
        Mat::from_fn(1, 1, |_, _| x)
    }

    #[test]
    fn damped_oscillator_decays_at_re_lambda() {
        let p = LinearOdeParams {
            step: 0.01,
            steps: 20_000,
            record_every: 100,
        };
        let t = integrate_second_order(
            one(1.0).as_ref(),
            one(0.2).as_ref(),
            one(1.0).as_ref(),
            &[1.0],
            &[0.0],
            &p,
        )
        .unwrap();
        // exact q = e^{−0.1t}(cos ωt + 0.1/ω sin ωt): the envelope of ‖y‖ decays at −0.1.
        let n = t.times.len();
        let rate = (t.log_norms[n - 1] - t.log_norms[n / 2]) / (t.times[n - 1] - t.times[n / 2]);
        assert!((rate + 0.1).abs() < 2e-3, "{rate}");
    }

    #[test]
    fn negative_stiffness_grows_without_overflow() {
        // q̈ − q = 0: λ = ±1; over t = 1000 the norm grows by e^1000 (renormalized).
        let p = LinearOdeParams {
            step: 0.01,
            steps: 100_000,
            record_every: 1000,
        };
        let t = integrate_second_order(
            one(1.0).as_ref(),
            one(0.0).as_ref(),
            one(-1.0).as_ref(),
            &[1.0],
            &[0.0],
            &p,
        )
        .unwrap();
        let n = t.times.len();
        let rate = (t.log_norms[n - 1] - t.log_norms[n / 2]) / (t.times[n - 1] - t.times[n / 2]);
        assert!((rate - 1.0).abs() < 1e-9, "{rate}");
        assert!(t.stats.rescalings > 0);
    }

    #[test]
    fn bad_step_and_singular_mass_are_typed_errors() {
        let p = LinearOdeParams {
            step: -1.0,
            ..Default::default()
        };
        let e = integrate_second_order(
            one(1.0).as_ref(),
            one(0.0).as_ref(),
            one(1.0).as_ref(),
            &[1.0],
            &[0.0],
            &p,
        )
        .unwrap_err();
        assert!(matches!(e, Error::Input(ref i) if i.field == "integration.step"));
        let e = integrate_second_order(
            one(0.0).as_ref(),
            one(0.0).as_ref(),
            one(1.0).as_ref(),
            &[1.0],
            &[0.0],
            &LinearOdeParams::default(),
        )
        .unwrap_err();
        assert!(matches!(e, Error::Solve(SolveError::Singular { .. })));
    }
}
