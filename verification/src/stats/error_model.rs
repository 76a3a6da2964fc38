//! Joint space–time error model `E(h, k) ≈ C_h h^p + C_k k^q`, fitted over all runs of a study,
//! or its quadrature form `E(h, k)² ≈ (C_h h^p)² + (C_k k^q)²` (see [`Combination`]).
//!
//! Used when a `k`-sweep at fixed `h` bends towards the spatial error floor (or an `h`-sweep
//! towards the temporal one), so that a one-parameter power law no longer describes the data.
//!
//! With `θ = (a, p, c, q)`, `C_h = e^a`, `C_k = e^c`, the fit minimises the log residuals
//!
//! ```text
//! S(θ) = Σ_i r_i²,   r_i = ln E_i − L_i(θ),   L_i(θ) = ln(e^{a + p ln h_i} + e^{c + q ln k_i})
//! ```
//!
//! by Levenberg–Marquardt: with `J_ij = ∂L_i/∂θ_j`,
//! `w_i = e^{a + p ln h_i − L_i}` (share of the spatial term),
//! `J_i = (w_i, w_i ln h_i, 1 − w_i, (1 − w_i) ln k_i)`, the step solves
//! `(JᵀJ + λ diag(JᵀJ)) δ = Jᵀ r`; it is accepted if it lowers `S` (then `λ ← λ/10`), else
//! `λ ← 10 λ`. Starts: the grid `(p₀, q₀) ∈ {0.5, 1, 2, 3}²` with `(C_h, C_k)` from a linear
//! relative least-squares fit at fixed exponents; the converged fit with the smallest `S` wins.
//!
//! Confidence intervals (`γ = confidence`, `n` runs, `n ≥ 5`):
//!
//! ```text
//! s² = S(θ*) / (n − 4),   θ*_j ± t_{(1+γ)/2, n−4} · sqrt(s² [(JᵀJ)⁻¹]_jj)   for j = p, q
//! ```
//!
//! With `n = 4` the intervals are `(−∞, +∞)`.
//!
//! The quadrature form (`s = 2` below) is the right model when the spatial and temporal errors are
//! orthogonal in the error norm — e.g. for P1 in 1D, where Galerkin orthogonality makes the
//! spatial error (u − R_h u)_x orthogonal to every discrete function, in particular to the gradient
//! of the time error, so |e|²_V = |e_h|²_V + |e_k|²_V. In general, with `s ∈ {1, 2}`,
//! `L_i(θ) = (1/s) ln(e^{s u_i} + e^{s v_i})`, `u_i = a + p ln h_i`, `v_i = c + q ln k_i`, and the
//! Jacobian keeps the form above with `w_i = e^{s (u_i − L_i)}`.

use nalgebra::{DMatrix, Matrix4, Vector4};
use serde::Serialize;

use super::{check_confidence, check_positive, t_quantile, FitError};

/// How the spatial and temporal terms combine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Combination {
    /// `E = C_h h^p + C_k k^q`.
    #[default]
    Sum,
    /// `E² = (C_h h^p)² + (C_k k^q)²`: orthogonal spatial and temporal errors.
    Quadrature,
}

impl Combination {
    /// The exponent `s` of `E^s = (C_h h^p)^s + (C_k k^q)^s`.
    pub fn exponent(self) -> f64 {
        match self {
            Combination::Sum => 1.0,
            Combination::Quadrature => 2.0,
        }
    }
}

/// Result of [`fit_error_model`]: `E(h, k)^s ≈ (c_h h^p)^s + (c_k k^q)^s`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorModelFit {
    /// How the two terms combine.
    pub combination: Combination,
    /// Spatial exponent `p`.
    pub p: f64,
    /// Confidence interval `p ± t_{(1+γ)/2, n−4} · sqrt(s² [(JᵀJ)⁻¹]_pp)` (infinite when `n = 4`).
    pub p_ci: (f64, f64),
    /// Temporal exponent `q`.
    pub q: f64,
    /// Confidence interval `q ± t_{(1+γ)/2, n−4} · sqrt(s² [(JᵀJ)⁻¹]_qq)` (infinite when `n = 4`).
    pub q_ci: (f64, f64),
    /// Spatial constant `C_h = e^a`.
    pub c_h: f64,
    /// Temporal constant `C_k = e^c`.
    pub c_k: f64,
    /// Confidence level `γ` of the intervals, in (0, 1).
    pub confidence: f64,
    /// Number `n` of runs used.
    pub points_used: usize,
    /// Residual standard deviation in log space, `s = sqrt(S(θ*) / (n − 4))` (0 when `n = 4`).
    pub residual_std: f64,
    /// Levenberg–Marquardt iterations (trial steps) spent by the winning start.
    pub iterations: usize,
}

impl ErrorModelFit {
    /// The model's error at (h, k): `((C_h h^p)^s + (C_k k^q)^s)^{1/s}`.
    pub fn predict(&self, h: f64, k: f64) -> f64 {
        let s = self.combination.exponent();
        ((self.c_h * h.powf(self.p)).powf(s) + (self.c_k * k.powf(self.q)).powf(s)).powf(1.0 / s)
    }
}

/// Initial exponents tried, on both axes.
const START_EXPONENTS: [f64; 4] = [0.5, 1.0, 2.0, 3.0];
/// Iteration cap per start.
const MAX_ITERATIONS: usize = 500;
/// Relative change of the objective below which an accepted step counts as converged.
const F_TOL: f64 = 1e-12;
/// Relative change of θ below which a step counts as converged.
const X_TOL: f64 = 1e-10;
/// Objective per point below which the residuals are at round-off level: converged.
const S_FLOOR_PER_POINT: f64 = 1e-26;
/// Smallest admissible `σ_min / σ_max` of the Jacobian at the fit.
const RANK_TOL: f64 = 1e-8;
const LAMBDA_INIT: f64 = 1e-3;
const LAMBDA_MIN: f64 = 1e-15;
const LAMBDA_MAX: f64 = 1e20;

/// Fits `E(h, k) ≈ C_h h^p + C_k k^q` to all runs `(h_i, k_i, E_i)` of a study.
///
/// Minimises `S(θ) = Σ_i (ln E_i − ln(e^a h_i^p + e^c k_i^q))²` over `θ = (a, p, c, q)` by
/// Levenberg–Marquardt from a grid of starts `(p₀, q₀) ∈ {0.5, 1, 2, 3}²` and keeps the converged
/// fit with the smallest `S`. Converged when an accepted step changes `S` by at most
/// `1e-12 · S` and `θ` by at most `1e-10 · (‖θ‖ + 1e-10)`, when no step of that size lowers `S`,
/// or when `S ≤ 1e-26 · n`. Intervals:
/// `p ± t_{(1+γ)/2, n−4} · sqrt(s² [(JᵀJ)⁻¹]_pp)`, likewise for `q`, `s² = S/(n−4)`;
/// `(−∞, +∞)` when `n = 4`. Deterministic.
///
/// # Errors
/// [`FitError::InvalidConfidence`], [`FitError::LengthMismatch`],
/// [`FitError::TooFewPoints`] (`n < 4`), [`FitError::InvalidValue`] (non-finite or non-positive
/// `h`, `k` or `E`), [`FitError::Unidentifiable`] (all runs share the same `h`, or the same `k`),
/// [`FitError::NotConverged`] (no start converged within the iteration cap),
/// [`FitError::RankDeficient`] (`σ_min/σ_max(J) < 1e-8` at the fit, e.g. one term negligible in
/// every run).
pub fn fit_error_model(
    h: &[f64],
    k: &[f64],
    error: &[f64],
    confidence: f64,
) -> Result<ErrorModelFit, FitError> {
    fit_error_model_with(h, k, error, confidence, Combination::Sum)
}

/// [`fit_error_model`] with the terms combined as `combination` says (`Sum`: s = 1,
/// `Quadrature`: s = 2); same algorithm, intervals and errors.
pub fn fit_error_model_with(
    h: &[f64],
    k: &[f64],
    error: &[f64],
    confidence: f64,
    combination: Combination,
) -> Result<ErrorModelFit, FitError> {
    check_confidence(confidence)?;
    let n = h.len();
    for (name, len) in [("k", k.len()), ("error", error.len())] {
        if len != n {
            return Err(FitError::LengthMismatch {
                name,
                found: len,
                expected: n,
            });
        }
    }
    if n < 4 {
        return Err(FitError::TooFewPoints {
            needed: 4,
            found: n,
        });
    }
    check_positive("h", h)?;
    check_positive("k", k)?;
    check_positive("error", error)?;

    let data = Data {
        s: combination.exponent(),
        lh: h.iter().map(|v| v.ln()).collect(),
        lk: k.iter().map(|v| v.ln()).collect(),
        y: error.iter().map(|v| v.ln()).collect(),
    };
    if data.lh.iter().all(|&v| v == data.lh[0]) {
        return Err(FitError::Unidentifiable {
            parameter: "p",
            reason: format!("all {n} runs share the same mesh size h = {}", h[0]),
        });
    }
    if data.lk.iter().all(|&v| v == data.lk[0]) {
        return Err(FitError::Unidentifiable {
            parameter: "q",
            reason: format!("all {n} runs share the same time step k = {}", k[0]),
        });
    }

    let mut best: Option<Outcome> = None;
    let mut best_failed: Option<Outcome> = None;
    for &p0 in &START_EXPONENTS {
        for &q0 in &START_EXPONENTS {
            let outcome = levenberg_marquardt(&data, data.initial_guess(p0, q0));
            let slot = if outcome.converged {
                &mut best
            } else {
                &mut best_failed
            };
            if slot
                .as_ref()
                .is_none_or(|b| outcome.objective < b.objective)
            {
                *slot = Some(outcome);
            }
        }
    }
    let Some(best) = best else {
        let (iterations, objective) = best_failed
            .map(|o| (o.iterations, o.objective))
            .unwrap_or((0, f64::INFINITY));
        return Err(FitError::NotConverged {
            iterations,
            objective,
        });
    };

    // Identifiability at the fit: singular values of J.
    let theta = best.theta;
    let mut jac = DMatrix::<f64>::zeros(n, 4);
    for i in 0..n {
        let (_, row) = data.log_model(&theta, i);
        for j in 0..4 {
            jac[(i, j)] = row[j];
        }
    }
    let sv = jac.singular_values();
    let (s_min, s_max) = (sv.min(), sv.max());
    let ratio = if s_max > 0.0 { s_min / s_max } else { 0.0 };
    if ratio.is_nan() || ratio < RANK_TOL {
        return Err(FitError::RankDeficient { ratio });
    }
    let jtj: Matrix4<f64> = jac.tr_mul(&jac).fixed_view::<4, 4>(0, 0).into_owned();
    let Some(cov) = jtj.try_inverse() else {
        return Err(FitError::RankDeficient { ratio });
    };

    let (p, q) = (theta[1], theta[3]);
    let (p_ci, q_ci, residual_std) = if n > 4 {
        let dof = n - 4;
        let s2 = best.objective / dof as f64;
        let t = t_quantile(confidence, dof)?;
        let half_p = t * (s2 * cov[(1, 1)].max(0.0)).sqrt();
        let half_q = t * (s2 * cov[(3, 3)].max(0.0)).sqrt();
        (
            (p - half_p, p + half_p),
            (q - half_q, q + half_q),
            s2.sqrt(),
        )
    } else {
        let inf = (f64::NEG_INFINITY, f64::INFINITY);
        (inf, inf, 0.0)
    };

    Ok(ErrorModelFit {
        combination,
        p,
        p_ci,
        q,
        q_ci,
        c_h: theta[0].exp(),
        c_k: theta[2].exp(),
        confidence,
        points_used: n,
        residual_std,
        iterations: best.iterations,
    })
}

/// Log data of a study: `ln h_i`, `ln k_i`, `ln E_i`.
struct Data {
    /// The combination exponent s.
    s: f64,
    lh: Vec<f64>,
    lk: Vec<f64>,
    y: Vec<f64>,
}

/// Result of one Levenberg–Marquardt run.
struct Outcome {
    theta: Vector4<f64>,
    objective: f64,
    iterations: usize,
    converged: bool,
}

impl Data {
    /// `L_i(θ) = (1/s) ln(e^{s u} + e^{s v})`, `u = a + p ln h_i`, `v = c + q ln k_i`, and its
    /// gradient `(w, w ln h_i, 1 − w, (1 − w) ln k_i)` with `w = e^{s (u − L_i)}`, computed as a
    /// log-sum-exp.
    fn log_model(&self, theta: &Vector4<f64>, i: usize) -> (f64, Vector4<f64>) {
        let s = self.s;
        let u = theta[0] + theta[1] * self.lh[i];
        let v = theta[2] + theta[3] * self.lk[i];
        let m = u.max(v);
        let log_model = m + ((s * (u - m)).exp() + (s * (v - m)).exp()).ln() / s;
        let w = (s * (u - log_model)).exp();
        let w_k = (s * (v - log_model)).exp();
        (
            log_model,
            Vector4::new(w, w * self.lh[i], w_k, w_k * self.lk[i]),
        )
    }

    /// `S(θ) = Σ (ln E_i − L_i(θ))²` (non-finite if θ is).
    fn objective(&self, theta: &Vector4<f64>) -> f64 {
        (0..self.y.len())
            .map(|i| (self.y[i] - self.log_model(theta, i).0).powi(2))
            .sum()
    }

    /// `JᵀJ` and `Jᵀr` at θ.
    fn normal_equations(&self, theta: &Vector4<f64>) -> (Matrix4<f64>, Vector4<f64>) {
        let mut jtj = Matrix4::zeros();
        let mut jtr = Vector4::zeros();
        for i in 0..self.y.len() {
            let (log_model, row) = self.log_model(theta, i);
            jtj += row * row.transpose();
            jtr += row * (self.y[i] - log_model);
        }
        (jtj, jtr)
    }

    /// Start at exponents `(p₀, q₀)`: `(C_h, C_k)` from the linear least-squares fit of the
    /// relative misfit `Σ (1 − (C_h h_i^{p₀} + C_k k_i^{q₀}) / E_i)²`; if that gives a
    /// non-positive or non-finite constant, each term is set to half of its one-term log fit,
    /// `ln C = mean(ln E − p₀ ln h) − ln 2`.
    fn initial_guess(&self, p0: f64, q0: f64) -> Vector4<f64> {
        let n = self.y.len() as f64;
        let (mut suu, mut suv, mut svv, mut su, mut sv) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for i in 0..self.y.len() {
            let u = (p0 * self.lh[i] - self.y[i]).exp();
            let v = (q0 * self.lk[i] - self.y[i]).exp();
            suu += u * u;
            suv += u * v;
            svv += v * v;
            su += u;
            sv += v;
        }
        let det = suu * svv - suv * suv;
        let c_h = (svv * su - suv * sv) / det;
        let c_k = (suu * sv - suv * su) / det;
        let fallback_a = self
            .y
            .iter()
            .zip(&self.lh)
            .map(|(y, lh)| y - p0 * lh)
            .sum::<f64>()
            / n
            - std::f64::consts::LN_2;
        let fallback_c = self
            .y
            .iter()
            .zip(&self.lk)
            .map(|(y, lk)| y - q0 * lk)
            .sum::<f64>()
            / n
            - std::f64::consts::LN_2;
        let usable = |c: f64| c.is_finite() && c > 0.0 && c.ln().is_finite();
        let (a, c) = if usable(c_h) && usable(c_k) {
            (c_h.ln(), c_k.ln())
        } else {
            (fallback_a, fallback_c)
        };
        Vector4::new(a, p0, c, q0)
    }
}

/// Damped Gauss–Newton (Levenberg–Marquardt with Marquardt's diagonal scaling) from `theta`.
fn levenberg_marquardt(data: &Data, mut theta: Vector4<f64>) -> Outcome {
    let n = data.y.len() as f64;
    let mut objective = data.objective(&theta);
    let mut lambda = LAMBDA_INIT;
    let mut iterations = 0;
    let outcome = |theta, objective, iterations, converged| Outcome {
        theta,
        objective,
        iterations,
        converged,
    };
    if !objective.is_finite() {
        return outcome(theta, f64::INFINITY, 0, false);
    }
    loop {
        if objective <= S_FLOOR_PER_POINT * n {
            return outcome(theta, objective, iterations, true);
        }
        if iterations >= MAX_ITERATIONS || lambda > LAMBDA_MAX {
            return outcome(theta, objective, iterations, false);
        }
        iterations += 1;

        let (jtj, jtr) = data.normal_equations(&theta);
        let diag_floor = 1e-12 * jtj.diagonal().max().max(f64::MIN_POSITIVE);
        let mut damped = jtj;
        for j in 0..4 {
            damped[(j, j)] += lambda * jtj[(j, j)].max(diag_floor);
        }
        let Some(chol) = damped.cholesky() else {
            lambda *= 10.0;
            continue;
        };
        let delta = chol.solve(&jtr);
        let trial = theta + delta;
        let trial_objective = data.objective(&trial);
        let step_small = delta.norm() <= X_TOL * (theta.norm() + X_TOL);

        if trial_objective.is_finite() && trial_objective < objective {
            let decrease = objective - trial_objective;
            let previous = objective;
            theta = trial;
            objective = trial_objective;
            lambda = (lambda / 10.0).max(LAMBDA_MIN);
            if step_small && decrease <= F_TOL * previous {
                return outcome(theta, objective, iterations, true);
            }
        } else {
            // No descent even for a step below the resolution of θ: a minimum to round-off.
            if step_small && delta.iter().all(|d| d.is_finite()) {
                return outcome(theta, objective, iterations, true);
            }
            lambda *= 10.0;
        }
    }
}

#[cfg(test)]
mod tests {
    // Setting: synthetic studies E = 0.7 h + 3 k² on an h-sweep at fine k, a k-sweep at fine h and
    // a diagonal h = k, exact or with fixed ±0.5% perturbations.
    // Goal: recover (p, q, C_h, C_k), intervals that contain the truth, and every typed error.
    use super::*;

    const C_H: f64 = 0.7;
    const C_K: f64 = 3.0;

    fn truth(h: f64, k: f64) -> f64 {
        C_H * h + C_K * k * k
    }

    /// h-sweep at k = 1/1024, k-sweep at h = 1/1024, diagonal h = k; 15 runs.
    fn design() -> (Vec<f64>, Vec<f64>) {
        let sweep: Vec<f64> = (2..7).map(|i| 0.5_f64.powi(i)).collect();
        let fine = 1.0 / 1024.0;
        let mut h = Vec::new();
        let mut k = Vec::new();
        for &s in &sweep {
            h.push(s);
            k.push(fine);
        }
        for &s in &sweep {
            h.push(fine);
            k.push(s);
        }
        for &s in &sweep {
            h.push(s);
            k.push(s);
        }
        (h, k)
    }

    const NOISE: [f64; 15] = [
        0.005, -0.004, 0.002, -0.005, 0.003, -0.003, 0.005, -0.002, 0.004, -0.005, 0.001, -0.004,
        0.005, -0.001, 0.003,
    ];

    #[test]
    fn exact_two_term_model_is_recovered() {
        let (h, k) = design();
        let e: Vec<f64> = h.iter().zip(&k).map(|(&h, &k)| truth(h, k)).collect();
        let fit = fit_error_model(&h, &k, &e, 0.95).unwrap();
        assert!((fit.p - 1.0).abs() <= 1e-8, "{fit:?}");
        assert!((fit.q - 2.0).abs() <= 1e-8, "{fit:?}");
        assert!((fit.c_h - C_H).abs() <= 1e-8 * C_H, "{fit:?}");
        assert!((fit.c_k - C_K).abs() <= 1e-8 * C_K, "{fit:?}");
        assert!(fit.p_ci.1 - fit.p_ci.0 <= 1e-8, "{fit:?}");
        assert!(fit.q_ci.1 - fit.q_ci.0 <= 1e-8, "{fit:?}");
        assert!(fit.residual_std <= 1e-10);
        assert_eq!(fit.points_used, 15);
        assert!(fit.iterations > 0 && fit.iterations <= MAX_ITERATIONS);
    }

    #[test]
    fn exact_quadrature_model_is_recovered_and_the_sum_model_misfits_it() {
        let (h, k) = design();
        let e: Vec<f64> = h
            .iter()
            .zip(&k)
            .map(|(&h, &k)| ((C_H * h).powi(2) + (C_K * k * k).powi(2)).sqrt())
            .collect();
        let fit = fit_error_model_with(&h, &k, &e, 0.95, Combination::Quadrature).unwrap();
        assert_eq!(fit.combination, Combination::Quadrature);
        assert!((fit.p - 1.0).abs() <= 1e-8, "{fit:?}");
        assert!((fit.q - 2.0).abs() <= 1e-8, "{fit:?}");
        assert!((fit.c_h - C_H).abs() <= 1e-8 * C_H, "{fit:?}");
        assert!((fit.c_k - C_K).abs() <= 1e-8 * C_K, "{fit:?}");
        let sum = fit_error_model(&h, &k, &e, 0.95).unwrap();
        assert!(
            sum.residual_std > 1e3 * fit.residual_std.max(1e-12),
            "{sum:?}"
        );
    }

    #[test]
    fn noisy_model_intervals_contain_the_truth() {
        let (h, k) = design();
        let e: Vec<f64> = h
            .iter()
            .zip(&k)
            .zip(NOISE)
            .map(|((&h, &k), d)| truth(h, k) * (1.0 + d))
            .collect();
        let fit = fit_error_model(&h, &k, &e, 0.95).unwrap();
        assert!(fit.p_ci.0 < 1.0 && 1.0 < fit.p_ci.1, "{fit:?}");
        assert!(fit.q_ci.0 < 2.0 && 2.0 < fit.q_ci.1, "{fit:?}");
        assert!(fit.p_ci.0 < fit.p && fit.p < fit.p_ci.1);
        assert!(fit.q_ci.0 < fit.q && fit.q < fit.q_ci.1);
        assert!(fit.p_ci.1 - fit.p_ci.0 < 0.1, "{fit:?}");
        assert!(fit.q_ci.1 - fit.q_ci.0 < 0.1, "{fit:?}");
        assert!(fit.residual_std > 0.0 && fit.residual_std < 0.01, "{fit:?}");
    }

    #[test]
    fn fit_is_deterministic() {
        let (h, k) = design();
        let e: Vec<f64> = h
            .iter()
            .zip(&k)
            .zip(NOISE)
            .map(|((&h, &k), d)| truth(h, k) * (1.0 + d))
            .collect();
        assert_eq!(
            fit_error_model(&h, &k, &e, 0.95),
            fit_error_model(&h, &k, &e, 0.95)
        );
    }

    #[test]
    fn four_runs_give_infinite_intervals() {
        let fine = 1.0 / 1024.0;
        let h = [0.25, 0.0625, fine, fine];
        let k = [fine, fine, 0.25, 0.0625];
        let e: Vec<f64> = h.iter().zip(&k).map(|(&h, &k)| truth(h, k)).collect();
        let fit = fit_error_model(&h, &k, &e, 0.95).unwrap();
        assert!(
            (fit.p - 1.0).abs() <= 1e-8 && (fit.q - 2.0).abs() <= 1e-8,
            "{fit:?}"
        );
        assert_eq!(fit.p_ci, (f64::NEG_INFINITY, f64::INFINITY));
        assert_eq!(fit.q_ci, (f64::NEG_INFINITY, f64::INFINITY));
        assert_eq!(fit.residual_std, 0.0);
    }

    #[test]
    fn all_runs_at_one_time_step_is_unidentifiable() {
        let h = [0.5, 0.25, 0.125, 0.0625, 0.03125];
        let k = [0.01; 5];
        let e: Vec<f64> = h.iter().zip(&k).map(|(&h, &k)| truth(h, k)).collect();
        assert!(matches!(
            fit_error_model(&h, &k, &e, 0.95),
            Err(FitError::Unidentifiable { parameter: "q", .. })
        ));
        assert!(matches!(
            fit_error_model(&k, &h, &e, 0.95),
            Err(FitError::Unidentifiable { parameter: "p", .. })
        ));
    }

    #[test]
    fn data_without_a_temporal_term_is_a_typed_error() {
        // E = 0.7 h exactly although k varies: C_k → 0 is not a finite fit.
        let (h, k) = design();
        let e: Vec<f64> = h.iter().map(|&h| C_H * h).collect();
        match fit_error_model(&h, &k, &e, 0.95) {
            Err(FitError::RankDeficient { .. } | FitError::NotConverged { .. }) => {}
            other => panic!("expected RankDeficient or NotConverged, got {other:?}"),
        }
    }

    #[test]
    fn input_errors_are_typed() {
        let h = [0.5, 0.25, 0.125, 0.0625, 0.03125];
        let k = [0.5, 0.25, 0.125, 0.0625, 0.03125];
        let e = [1.0, 0.5, 0.25, 0.125, 0.0625];
        assert_eq!(
            fit_error_model(&h, &k[..4], &e, 0.95),
            Err(FitError::LengthMismatch {
                name: "k",
                found: 4,
                expected: 5
            })
        );
        assert_eq!(
            fit_error_model(&h, &k, &e[..3], 0.95),
            Err(FitError::LengthMismatch {
                name: "error",
                found: 3,
                expected: 5
            })
        );
        assert_eq!(
            fit_error_model(&h[..3], &k[..3], &e[..3], 0.95),
            Err(FitError::TooFewPoints {
                needed: 4,
                found: 3
            })
        );
        assert_eq!(
            fit_error_model(&h, &[0.5, 0.25, -0.1, 0.0625, 0.03125], &e, 0.95),
            Err(FitError::InvalidValue {
                name: "k",
                index: 2,
                value: -0.1
            })
        );
        assert_eq!(
            fit_error_model(&h, &k, &[1.0, 0.5, 0.25, 0.125, f64::INFINITY], 0.95),
            Err(FitError::InvalidValue {
                name: "error",
                index: 4,
                value: f64::INFINITY
            })
        );
        assert_eq!(
            fit_error_model(&h, &k, &e, 1.0),
            Err(FitError::InvalidConfidence(1.0))
        );
    }
}
