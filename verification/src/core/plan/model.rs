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
}
