//! The planner's models of one scheme, fitted on its pilot runs: the error of the functional as a
//! function of (h, k) and the cost as a function of (M, N) (docs/planner.md §2).
//!
//! The error model is the joint quadrature form E² = (C_h h^p)² + (C_k k^q)²
//! (`stats::error_model`). Where one term is negligible over every pilot (the fit is then rank
//! deficient: e.g. a functional exact at the nodes in space), the one-term power law in the other
//! parameter, E = C k^q or E = C h^p, fitted by least squares in log space over all pilots.

use serde::Serialize;

use crate::stats::cost_model::{fit_cost_model, CostModelFit};
use crate::stats::error_model::{fit_error_model_with, Combination, ErrorModelFit};
use crate::stats::extrapolation::Extrapolation;
use crate::stats::FitError;

/// Confidence level of the fits' intervals.
pub const CONFIDENCE: f64 = 0.95;

/// The error model of a scheme.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "form", rename_all = "snake_case")]
pub enum ErrorModel {
    /// E² = (C_h h^p)² + (C_k k^q)².
    Joint(ErrorModelFit),
    /// E = C k^q (the spatial term negligible over the pilots).
    TimeOnly { c: f64, q: f64, residual_std: f64 },
    /// E = C h^p (the temporal term negligible over the pilots).
    SpaceOnly { c: f64, p: f64, residual_std: f64 },
    /// Self-convergence (no exact solution): F ≈ F* + a h^p + b k^q fitted to the pilots'
    /// values; E = |a| h^p + |b| k^q (`stats::extrapolation`).
    Extrapolated(Extrapolation),
}

impl ErrorModel {
    /// The predicted error at (h, k).
    pub fn predict(&self, h: f64, k: f64) -> f64 {
        match self {
            ErrorModel::Joint(f) => f.predict(h, k),
            ErrorModel::TimeOnly { c, q, .. } => c * k.powf(*q),
            ErrorModel::SpaceOnly { c, p, .. } => c * h.powf(*p),
            ErrorModel::Extrapolated(x) => x.error_bound(h, k),
        }
    }

    /// The observed orders (p, q); None for a term the model does not have.
    pub fn orders(&self) -> (Option<f64>, Option<f64>) {
        match self {
            ErrorModel::Joint(f) => (Some(f.p), Some(f.q)),
            ErrorModel::TimeOnly { q, .. } => (None, Some(*q)),
            ErrorModel::SpaceOnly { p, .. } => (Some(*p), None),
            ErrorModel::Extrapolated(x) => (x.p, x.q),
        }
    }

    /// The residual standard deviation of the fit in log space (≈ the model's relative error
    /// over the pilots).
    pub fn residual_std(&self) -> f64 {
        match self {
            ErrorModel::Joint(f) => f.residual_std,
            ErrorModel::TimeOnly { residual_std, .. }
            | ErrorModel::SpaceOnly { residual_std, .. } => *residual_std,
            ErrorModel::Extrapolated(x) => x.relative_residual,
        }
    }

    /// A one-line description.
    pub fn describe(&self) -> String {
        match self {
            ErrorModel::Joint(f) => format!(
                "E² = ({:.3e} h^{:.3})² + ({:.3e} k^{:.3})² (p ∈ [{:.3}, {:.3}], q ∈ [{:.3}, {:.3}], log residual {:.3})",
                f.c_h, f.p, f.c_k, f.q, f.p_ci.0, f.p_ci.1, f.q_ci.0, f.q_ci.1, f.residual_std
            ),
            ErrorModel::TimeOnly { c, q, residual_std } => format!(
                "E = {c:.3e} k^{q:.3} (the spatial term negligible; log residual {residual_std:.3})"
            ),
            ErrorModel::SpaceOnly { c, p, residual_std } => format!(
                "E = {c:.3e} h^{p:.3} (the temporal term negligible; log residual {residual_std:.3})"
            ),
            ErrorModel::Extrapolated(x) => {
                let part = |c: f64, o: Option<f64>, v: &str| {
                    o.map_or(String::new(), |o| format!(" {:+.3e} {v}^{o:.3}", c))
                };
                format!(
                    "F = {:.6e}{}{} (self-convergence; relative residual {:.3})",
                    x.value,
                    part(x.a, x.p, "h"),
                    part(x.b, x.q, "k"),
                    x.relative_residual
                )
            }
        }
    }
}

/// ln E = ln C + r ln x by least squares over all points: (C, r, residual std).
fn one_term(x: &[f64], e: &[f64]) -> Option<(f64, f64, f64)> {
    let n = x.len() as f64;
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = e.iter().map(|v| v.ln()).collect();
    let mx = lx.iter().sum::<f64>() / n;
    let my = ly.iter().sum::<f64>() / n;
    let sxx: f64 = lx.iter().map(|v| (v - mx) * (v - mx)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let r = sxy / sxx;
    let c = my - r * mx;
    let ss: f64 = lx
        .iter()
        .zip(&ly)
        .map(|(a, b)| (b - c - r * a).powi(2))
        .sum();
    let dof = (x.len() as f64 - 2.0).max(1.0);
    Some((c.exp(), r, (ss / dof).sqrt()))
}

/// Fits the error model of one scheme's pilots (h_i, k_i, E_i) (module docs).
///
/// # Errors
/// The joint fit's errors other than a rank deficiency (too few pilots, a non-positive error,
/// all pilots at one h or one k, no convergence).
pub fn fit_error(h: &[f64], k: &[f64], error: &[f64]) -> Result<ErrorModel, FitError> {
    match fit_error_model_with(h, k, error, CONFIDENCE, Combination::Quadrature) {
        Ok(f) => Ok(ErrorModel::Joint(f)),
        Err(FitError::RankDeficient { ratio }) => {
            let time = one_term(k, error);
            let space = one_term(h, error);
            match (time, space) {
                (Some((c, q, st)), Some((_, _, ss))) if st <= ss => Ok(ErrorModel::TimeOnly {
                    c,
                    q,
                    residual_std: st,
                }),
                (_, Some((c, p, ss))) => Ok(ErrorModel::SpaceOnly {
                    c,
                    p,
                    residual_std: ss,
                }),
                _ => Err(FitError::RankDeficient { ratio }),
            }
        }
        Err(e) => Err(e),
    }
}

/// Fits the cost model t ≈ c M^a N^b of one scheme's pilots.
pub fn fit_cost(size: &[f64], steps: &[f64], seconds: &[f64]) -> Result<CostModelFit, FitError> {
    fit_cost_model(size, steps, seconds, CONFIDENCE)
}

/// A timed cost model whose exponents fall short of the family's work by more than the
/// planner's order tolerance ([`super::ORDER_TOLERANCE`], 30 %), beyond their confidence
/// intervals, is overhead-dominated: the pilots are too short for their time to
/// follow their work (per-run setup, allocation and cache effects of microsecond runs), and the
/// power law would extrapolate that overhead to runs thousands of times larger (the rod's pilots
/// measured t ∝ M^0.15 where its work is M·N; a seconds-mode plan then chose 1.9 × the oracle's
/// time). Such a model is replaced by the work's own exponents (a_w, b_w) = ∂ ln W/∂ ln (M, N) at
/// the finest pilot, its constant calibrated so that it passes through that pilot's time (the
/// scheme's seconds per unit of work, where the overhead weighs least); the reason is returned.
/// A model that grows as fast as the work or faster (e.g. a sparse factorization's fill) stands.
pub fn calibrated_to_work(
    fit: CostModelFit,
    finest: (f64, f64, f64),
    work: impl Fn(f64, f64) -> f64,
) -> (CostModelFit, Option<String>) {
    let (m, n, t) = finest;
    let slope = |w2: f64| (w2 / work(m, n)).ln() / 2f64.ln();
    let (a_w, b_w) = (slope(work(2.0 * m, n)), slope(work(m, 2.0 * n)));
    // short of the work by more than the planner's order tolerance, beyond the interval
    let below = |ci: (f64, f64), w: f64| ci.1 < (1.0 - super::ORDER_TOLERANCE) * w;
    if !(below(fit.a_ci, a_w) || below(fit.b_ci, b_w)) || !(a_w.is_finite() && b_w.is_finite()) {
        return (fit, None);
    }
    let why = format!(
        "overhead-dominated pilot timings: t ∝ M^{:.2} N^{:.2} (a ∈ [{:.2}, {:.2}], b ∈ [{:.2}, {:.2}]) grows slower than the work ∝ M^{a_w:.2} N^{b_w:.2}; the work's exponents used, calibrated at the finest pilot ({m}, {n}): {t:.3e} s",
        fit.a, fit.b, fit.a_ci.0, fit.a_ci.1, fit.b_ci.0, fit.b_ci.1
    );
    let calibrated = CostModelFit {
        log_constant: t.ln() - a_w * m.ln() - b_w * n.ln(),
        a: a_w,
        a_ci: (a_w, a_w),
        b: b_w,
        b_ci: (b_w, b_w),
        ..fit
    };
    (calibrated, Some(why))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(f: impl Fn(f64, f64) -> f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let (mut h, mut k, mut e) = (Vec::new(), Vec::new(), Vec::new());
        for &hi in &[0.1, 0.05, 0.025] {
            for &ki in &[0.04, 0.02, 0.01] {
                h.push(hi);
                k.push(ki);
                e.push(f(hi, ki));
            }
        }
        (h, k, e)
    }

    #[test]
    fn a_quadrature_model_is_recovered_and_predicts_beyond_the_pilots() {
        let truth = |h: f64, k: f64| ((2.0 * h * h).powi(2) + (0.5 * k).powi(2)).sqrt();
        let (h, k, e) = grid(truth);
        let m = fit_error(&h, &k, &e).unwrap();
        assert!(matches!(m, ErrorModel::Joint(_)), "{m:?}");
        let (p, q) = m.orders();
        assert!((p.unwrap() - 2.0).abs() < 1e-6 && (q.unwrap() - 1.0).abs() < 1e-6);
        assert!((m.predict(0.01, 0.003) / truth(0.01, 0.003) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_negligible_spatial_term_falls_back_to_the_time_only_law() {
        // exact in space at the nodes: the error depends on k alone
        let (h, k, e) = grid(|_, k| 3.0 * k * k);
        let m = fit_error(&h, &k, &e).unwrap();
        match m {
            ErrorModel::TimeOnly { c, q, residual_std } => {
                assert!((q - 2.0).abs() < 1e-9 && (c - 3.0).abs() < 1e-9 && residual_std < 1e-9)
            }
            other => panic!("{other:?}"),
        }
    }

    /// The pilot grid (M₀/4 … M₀) × (N₀/4 … N₀) at (40, 20) with times `t(M, N)`.
    fn timed(t: impl Fn(f64, f64) -> f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let (mut m, mut n, mut s) = (Vec::new(), Vec::new(), Vec::new());
        for &mi in &[10.0, 20.0, 40.0] {
            for &ni in &[5.0, 10.0, 20.0] {
                m.push(mi);
                n.push(ni);
                s.push(t(mi, ni));
            }
        }
        (m, n, s)
    }

    #[test]
    fn overhead_dominated_timings_take_the_works_exponents_through_the_finest_pilot() {
        // 2 µs of per-run overhead beside 1 ns per unit of work M·N: the fit's exponents fall
        // far below 1; the calibrated model passes through the finest pilot with a = b = 1
        let truth = |m: f64, n: f64| 2e-6 + 1e-9 * m * n * (1.0 + 0.01 * (m + n).sin());
        let (m, n, t) = timed(truth);
        let fit = fit_cost(&m, &n, &t).unwrap();
        assert!(fit.a_ci.1 < 1.0, "{fit:?}");
        let (c, why) = calibrated_to_work(fit, (40.0, 20.0, truth(40.0, 20.0)), |m, n| m * n);
        assert!(why.is_some_and(|w| w.contains("overhead-dominated")));
        assert_eq!((c.a, c.b), (1.0, 1.0));
        assert!((c.predict(40.0, 20.0) / truth(40.0, 20.0) - 1.0).abs() < 1e-12);
        // 100 times the work: above the truth by at most the finest pilot's time over its work
        // part (the overhead counted as work), 2.8 µs / 0.8 µs
        let ratio = c.predict(400.0, 200.0) / truth(400.0, 200.0);
        let bound = truth(40.0, 20.0) / (1e-9 * 800.0);
        assert!((1.0..=bound).contains(&ratio), "{ratio} ∉ [1, {bound}]");
    }

    #[test]
    fn timings_that_grow_as_fast_as_the_work_or_faster_keep_their_fit() {
        for a in [1.0, 1.4] {
            let (m, n, t) = timed(|m, n| 1e-9 * m.powf(a) * n * (1.0 + 0.01 * (m * n).cos()));
            let fit = fit_cost(&m, &n, &t).unwrap();
            let (kept, why) = calibrated_to_work(fit.clone(), (40.0, 20.0, t[8]), |m, n| m * n);
            assert!(why.is_none(), "a = {a}: {why:?}");
            assert_eq!(kept, fit);
        }
    }
}
