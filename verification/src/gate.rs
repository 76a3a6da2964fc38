//! Gates: the verdicts that make `verify` fail.
//!
//! A rate gate is three numbers and a consistency check (scikit-fem's convention): the fitted rate
//! is within `tolerance` of the expected rate, the 95% confidence interval is narrower than
//! `ci_width`, the error on the finest level is below `ceiling`, and the pairwise rates of the finest
//! levels agree with the fit (the levels are in the asymptotic range).

use serde::Serialize;

use crate::case::{ModelGateSpec, RateGateSpec};
use crate::stats::error_model::{fit_error_model_with, ErrorModelFit};
use crate::stats::rate_fit::{fit_rate, RateFit};

/// The confidence level of every interval in the reports.
pub const CONFIDENCE: f64 = 0.95;

/// One checked condition.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// What is checked.
    pub name: String,
    /// The observed value.
    pub observed: f64,
    /// The condition it must meet, as text (`<= 1e-2`, `in [0.9, 1.1]`).
    pub limit: String,
    pub passed: bool,
}

impl Check {
    /// observed ≤ limit.
    pub fn at_most(name: &str, observed: f64, limit: f64) -> Self {
        Self {
            name: name.to_string(),
            observed,
            limit: format!("<= {limit:.3e}"),
            passed: observed <= limit,
        }
    }

    /// |observed − target| ≤ tol.
    pub fn within(name: &str, observed: f64, target: f64, tol: f64) -> Self {
        Self {
            name: name.to_string(),
            observed,
            limit: format!("in [{:.4}, {:.4}]", target - tol, target + tol),
            passed: (observed - target).abs() <= tol,
        }
    }

    /// A boolean condition.
    pub fn holds(name: &str, passed: bool, limit: &str) -> Self {
        Self {
            name: name.to_string(),
            observed: if passed { 1.0 } else { 0.0 },
            limit: limit.to_string(),
            passed,
        }
    }
}

/// The verdict of one gate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GateVerdict {
    /// A readable name (`diagonal/explicit: paper_E vs h`).
    pub name: String,
    /// `rate`, `model`, `reference`, `stability`, `extreme`, `work_precision`, `performance`.
    pub kind: String,
    pub passed: bool,
    pub checks: Vec<Check>,
    /// Why the gate expects what it expects.
    pub note: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rate_fit: Option<RateFit>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_fit: Option<ErrorModelFit>,
}

impl GateVerdict {
    /// A verdict that passes when every check passes (and there is at least one).
    pub fn from_checks(name: String, kind: &str, checks: Vec<Check>, note: &str) -> Self {
        Self {
            passed: !checks.is_empty() && checks.iter().all(|c| c.passed),
            name,
            kind: kind.to_string(),
            checks,
            note: note.to_string(),
            rate_fit: None,
            model_fit: None,
        }
    }
}

/// Evaluates a rate gate on the (parameter, error) pairs of one sweep and scheme.
pub fn evaluate_rate_gate(
    name: String,
    spec: &RateGateSpec,
    param: &[f64],
    error: &[f64],
) -> GateVerdict {
    let fit = match fit_rate(param, error, spec.finest_levels, CONFIDENCE) {
        Ok(fit) => fit,
        Err(e) => {
            let mut v = GateVerdict::from_checks(
                name,
                "rate",
                vec![Check::holds(
                    &format!("rate fit ({e})"),
                    false,
                    "a valid fit",
                )],
                &spec.note,
            );
            v.passed = false;
            return v;
        }
    };
    let rate_check = if spec.expected_in_ci {
        Check {
            name: format!(
                "expected rate {} inside the 95% CI of the fitted rate",
                spec.expected_rate
            ),
            observed: fit.rate,
            limit: format!(
                "CI [{:.4}, {:.4}] contains {}",
                fit.ci_low, fit.ci_high, spec.expected_rate
            ),
            passed: fit.ci_low <= spec.expected_rate && spec.expected_rate <= fit.ci_high,
        }
    } else {
        Check::within("fitted rate", fit.rate, spec.expected_rate, spec.tolerance)
    };
    let mut checks = vec![
        rate_check,
        Check::at_most("95% CI width", fit.ci_high - fit.ci_low, spec.ci_width),
    ];
    let finest = param
        .iter()
        .zip(error)
        .min_by(|a, b| a.0.total_cmp(b.0))
        .map(|(_, e)| *e)
        .unwrap_or(f64::NAN);
    checks.push(Check::at_most("finest-level error", finest, spec.ceiling));
    // Asymptotic range: the pairwise rates among the fitted (finest) levels, the last two pairs.
    let asym_tol = spec.asymptotic_tolerance.unwrap_or(spec.tolerance);
    let fitted_pairs = spec.finest_levels.saturating_sub(1).min(fit.pairwise.len());
    let pairs = &fit.pairwise[fit.pairwise.len() - fitted_pairs..];
    for p in pairs.iter().rev().take(2) {
        checks.push(Check::within(
            &format!("pairwise rate {:.3e} -> {:.3e}", p.from, p.to),
            p.rate,
            fit.rate,
            asym_tol,
        ));
    }
    let mut v = GateVerdict::from_checks(name, "rate", checks, &spec.note);
    v.rate_fit = Some(fit);
    v
}

/// Evaluates a model gate on (h, k, error) triples.
pub fn evaluate_model_gate(
    name: String,
    spec: &ModelGateSpec,
    h: &[f64],
    k: &[f64],
    error: &[f64],
) -> GateVerdict {
    match fit_error_model_with(h, k, error, CONFIDENCE, spec.combination) {
        Ok(fit) => {
            let checks = vec![
                Check::within("fitted p (space)", fit.p, spec.expected_p, spec.tolerance),
                Check::within("fitted q (time)", fit.q, spec.expected_q, spec.tolerance),
                Check::at_most("95% CI width of p", fit.p_ci.1 - fit.p_ci.0, spec.ci_width),
                Check::at_most("95% CI width of q", fit.q_ci.1 - fit.q_ci.0, spec.ci_width),
            ];
            let mut v = GateVerdict::from_checks(name, "model", checks, &spec.note);
            v.model_fit = Some(fit);
            v
        }
        Err(e) => GateVerdict::from_checks(
            name,
            "model",
            vec![Check::holds(
                &format!("error-model fit ({e})"),
                false,
                "a valid fit",
            )],
            &spec.note,
        ),
    }
}

#[cfg(test)]
mod tests {
    //! Gate logic on synthetic data with a known rate: the right expectation passes, a deliberately
    //! wrong expected rate fails, a ceiling below the finest error fails, and a pre-asymptotic
    //! sweep fails the pairwise check.
    use super::*;
    use crate::case::Against;

    fn spec(expected: f64) -> RateGateSpec {
        RateGateSpec {
            sweep: "s".into(),
            scheme: None,
            error: "paper_E".into(),
            against: Against::H,
            expected_rate: expected,
            tolerance: 0.1,
            finest_levels: 4,
            ci_width: 0.1,
            ceiling: 1e-2,
            asymptotic_tolerance: None,
            expected_in_ci: false,
            note: String::new(),
        }
    }

    fn data() -> (Vec<f64>, Vec<f64>) {
        let h: Vec<f64> = (0..5).map(|i| 0.1 / 2f64.powi(i)).collect();
        let e = h.iter().map(|h| 0.5 * h).collect();
        (h, e)
    }

    #[test]
    fn correct_expected_rate_passes() {
        let (h, e) = data();
        let v = evaluate_rate_gate("g".into(), &spec(1.0), &h, &e);
        assert!(v.passed, "{v:?}");
    }

    #[test]
    fn deliberately_wrong_expected_rate_fails() {
        let (h, e) = data();
        let v = evaluate_rate_gate("g".into(), &spec(2.0), &h, &e);
        assert!(!v.passed);
        assert!(!v.checks[0].passed);
    }

    #[test]
    fn ceiling_below_finest_error_fails() {
        let (h, e) = data();
        let mut s = spec(1.0);
        s.ceiling = 1e-4;
        let v = evaluate_rate_gate("g".into(), &s, &h, &e);
        assert!(!v.passed);
    }

    #[test]
    fn ci_containment_mode_accepts_scatter_around_the_expected_rate_and_rejects_a_wrong_one() {
        // E = h² with ±10% deterministic scatter
        let h: Vec<f64> = (0..6).map(|i| 0.1 / 2f64.powi(i)).collect();
        let wiggle = [1.0, 1.1, 0.9, 1.08, 0.93, 1.02];
        let e: Vec<f64> = h.iter().zip(wiggle).map(|(h, w)| h * h * w).collect();
        let mut s = spec(2.0);
        s.expected_in_ci = true;
        s.finest_levels = 6;
        s.ci_width = 0.5;
        s.ceiling = 1.0;
        s.asymptotic_tolerance = Some(0.5);
        assert!(evaluate_rate_gate("g".into(), &s, &h, &e).passed);
        s.expected_rate = 1.0;
        assert!(!evaluate_rate_gate("g".into(), &s, &h, &e).passed);
    }

    #[test]
    fn pre_asymptotic_finest_pair_fails_the_pairwise_check() {
        let (h, mut e) = data();
        // The finest level suddenly converges faster: the pairwise rate there is ~2, not 1.
        e[4] = e[3] / 4.0;
        let mut s = spec(1.0);
        s.tolerance = 0.5;
        s.ci_width = 10.0;
        s.asymptotic_tolerance = Some(0.2);
        let v = evaluate_rate_gate("g".into(), &s, &h, &e);
        assert!(!v.passed, "{v:?}");
    }
}
