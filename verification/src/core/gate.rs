//! Gates: the verdicts that make `verify` fail.
//!
//! A rate gate is three numbers and a consistency check (scikit-fem's convention): the fitted rate
//! is within `tolerance` of the expected rate, the 95% confidence interval is narrower than
//! `ci_width`, the error on the finest level is below `ceiling`, and the pairwise rates of the finest
//! levels agree with the fit (the levels are in the asymptotic range). [`RateCriteria`] holds
//! those numbers once for every family; a family's `[[gate]]` adds only the keys that select its
//! data ([`RateGate`]). A model gate ([`ModelCriteria`]) fits E(h, k) ≈ C_h h^p ⊕ C_k k^q.

use serde::Serialize;

use std::path::Path;

use serde::de::{DeserializeOwned, Deserializer};
use serde::Deserialize;

use crate::core::format::{invalid, positive, CaseError};
use crate::stats::error_model::{fit_error_model_with, Combination, ErrorModelFit};
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

/// The numbers of a rate gate, the same in every family's `[[gate]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RateCriteria {
    pub expected_rate: f64,
    /// |fitted − expected| ≤ tolerance.
    pub tolerance: f64,
    /// The least-squares fit uses this many of the finest levels (≥ 2).
    pub finest_levels: usize,
    /// The 95% confidence interval must be narrower.
    pub ci_width: f64,
    /// The error on the finest level must be below.
    pub ceiling: f64,
    /// Pairwise rates of the finest pairs must lie within this of the fit (default: `tolerance`).
    pub asymptotic_tolerance: Option<f64>,
    /// For rates with an explained scatter: instead of |fit − expected| ≤ tolerance, require the
    /// expected rate to lie inside the 95% confidence interval (the data do not reject it), with
    /// the interval no wider than `ci_width`.
    #[serde(default)]
    pub expected_in_ci: bool,
    /// Why the gate expects what it expects.
    #[serde(default)]
    pub note: String,
}

/// The keys of [`RateCriteria`] in a gate table.
const CRITERIA_KEYS: [&str; 8] = [
    "expected_rate",
    "tolerance",
    "finest_levels",
    "ci_width",
    "ceiling",
    "asymptotic_tolerance",
    "expected_in_ci",
    "note",
];

impl RateCriteria {
    /// Checks the numbers; `field` names the gate in errors (`gate[2]`).
    pub fn check(&self, path: &Path, field: &str) -> Result<(), CaseError> {
        if self.finest_levels < 2 {
            return Err(invalid(
                path,
                &format!("{field}.finest_levels"),
                self.finest_levels,
                ">= 2",
            ));
        }
        for (name, v) in [
            ("tolerance", self.tolerance),
            ("ci_width", self.ci_width),
            ("ceiling", self.ceiling),
        ] {
            positive(path, &format!("{field}.{name}"), v)?;
        }
        Ok(())
    }

    /// Evaluates the gate on the (parameter, error) pairs of one series.
    pub fn evaluate(&self, name: String, param: &[f64], error: &[f64]) -> GateVerdict {
        let fit = match fit_rate(param, error, self.finest_levels, CONFIDENCE) {
            Ok(fit) => fit,
            Err(e) => {
                return GateVerdict::from_checks(
                    name,
                    "rate",
                    vec![Check::holds(
                        &format!("rate fit ({e})"),
                        false,
                        "a valid fit",
                    )],
                    &self.note,
                )
            }
        };
        let rate_check = if self.expected_in_ci {
            Check {
                name: format!(
                    "expected rate {} inside the 95% CI of the fitted rate",
                    self.expected_rate
                ),
                observed: fit.rate,
                limit: format!(
                    "CI [{:.4}, {:.4}] contains {}",
                    fit.ci_low, fit.ci_high, self.expected_rate
                ),
                passed: fit.ci_low <= self.expected_rate && self.expected_rate <= fit.ci_high,
            }
        } else {
            Check::within("fitted rate", fit.rate, self.expected_rate, self.tolerance)
        };
        let mut checks = vec![
            rate_check,
            Check::at_most("95% CI width", fit.ci_high - fit.ci_low, self.ci_width),
        ];
        let finest = param
            .iter()
            .zip(error)
            .min_by(|a, b| a.0.total_cmp(b.0))
            .map(|(_, e)| *e)
            .unwrap_or(f64::NAN);
        checks.push(Check::at_most("finest-level error", finest, self.ceiling));
        // Asymptotic range: the pairwise rates among the fitted (finest) levels, the last two pairs.
        let asym_tol = self.asymptotic_tolerance.unwrap_or(self.tolerance);
        let fitted_pairs = self.finest_levels.saturating_sub(1).min(fit.pairwise.len());
        let pairs = &fit.pairwise[fit.pairwise.len() - fitted_pairs..];
        for p in pairs.iter().rev().take(2) {
            checks.push(Check::within(
                &format!("pairwise rate {:.3e} -> {:.3e}", p.from, p.to),
                p.rate,
                fit.rate,
                asym_tol,
            ));
        }
        let mut v = GateVerdict::from_checks(name, "rate", checks, &self.note);
        v.rate_fit = Some(fit);
        v
    }
}

/// A family's `[[gate]]`: the keys that select the data (`S`, e.g. sweep, scheme, error, against
/// for a convergence case, or a named series) and the [`RateCriteria`]. Both parts deny unknown
/// keys: the criteria keys are taken out of the table first, the rest must be `S`'s.
#[derive(Debug, Clone)]
pub struct RateGate<S> {
    pub select: S,
    pub criteria: RateCriteria,
}

impl<'de, S: DeserializeOwned> Deserialize<'de> for RateGate<S> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let mut rest = toml::Table::deserialize(deserializer)?;
        let mut criteria = toml::Table::new();
        for key in CRITERIA_KEYS {
            if let Some(v) = rest.remove(key) {
                criteria.insert(key.to_string(), v);
            }
        }
        let criteria: RateCriteria = criteria.try_into().map_err(serde::de::Error::custom)?;
        let select: S = rest.try_into().map_err(serde::de::Error::custom)?;
        Ok(Self { select, criteria })
    }
}

/// The numbers of a model gate: E(h, k) ≈ C_h h^p + C_k k^q (or in quadrature) fitted over several
/// sweeps, p and q within `tolerance` of the expected orders, both intervals narrower than
/// `ci_width`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelCriteria {
    pub expected_p: f64,
    pub expected_q: f64,
    pub tolerance: f64,
    pub ci_width: f64,
    /// `sum` (E = C_h h^p + C_k k^q) or `quadrature` (E² = (C_h h^p)² + (C_k k^q)², for errors
    /// whose spatial and temporal parts are orthogonal).
    #[serde(default)]
    pub combination: Combination,
    #[serde(default)]
    pub note: String,
}

impl ModelCriteria {
    /// Evaluates the model gate on (h, k, error) triples.
    pub fn evaluate(&self, name: String, h: &[f64], k: &[f64], error: &[f64]) -> GateVerdict {
        match fit_error_model_with(h, k, error, CONFIDENCE, self.combination) {
            Ok(fit) => {
                let checks = vec![
                    Check::within("fitted p (space)", fit.p, self.expected_p, self.tolerance),
                    Check::within("fitted q (time)", fit.q, self.expected_q, self.tolerance),
                    Check::at_most("95% CI width of p", fit.p_ci.1 - fit.p_ci.0, self.ci_width),
                    Check::at_most("95% CI width of q", fit.q_ci.1 - fit.q_ci.0, self.ci_width),
                ];
                let mut v = GateVerdict::from_checks(name, "model", checks, &self.note);
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
                &self.note,
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    //! Gate logic on synthetic data with a known rate: the right expectation passes, a deliberately
    //! wrong expected rate fails, a ceiling below the finest error fails, and a pre-asymptotic
    //! sweep fails the pairwise check.
    use super::*;

    fn spec(expected: f64) -> RateCriteria {
        RateCriteria {
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
        let v = spec(1.0).evaluate("g".into(), &h, &e);
        assert!(v.passed, "{v:?}");
    }

    #[test]
    fn deliberately_wrong_expected_rate_fails() {
        let (h, e) = data();
        let v = spec(2.0).evaluate("g".into(), &h, &e);
        assert!(!v.passed);
        assert!(!v.checks[0].passed);
    }

    #[test]
    fn ceiling_below_finest_error_fails() {
        let (h, e) = data();
        let mut s = spec(1.0);
        s.ceiling = 1e-4;
        let v = s.evaluate("g".into(), &h, &e);
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
        assert!(s.evaluate("g".into(), &h, &e).passed);
        s.expected_rate = 1.0;
        assert!(!s.evaluate("g".into(), &h, &e).passed);
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
        let v = s.evaluate("g".into(), &h, &e);
        assert!(!v.passed, "{v:?}");
    }

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Select {
        series: String,
    }

    #[test]
    fn a_gate_table_splits_into_selection_and_criteria_and_denies_unknown_keys() {
        let text = "series = \"sine\"\nexpected_rate = 2.0\ntolerance = 0.1\nfinest_levels = 3\n\
                    ci_width = 0.2\nceiling = 1e-3\n";
        let g: RateGate<Select> = toml::from_str(text).expect("parses");
        assert_eq!(g.select.series, "sine");
        assert_eq!(g.criteria.finest_levels, 3);
        assert!(!g.criteria.expected_in_ci);
        let e = toml::from_str::<RateGate<Select>>(&format!("{text}stray = 1\n"))
            .expect_err("unknown key");
        assert!(e.to_string().contains("stray"), "{e}");
        let e = toml::from_str::<RateGate<Select>>("series = \"s\"\nexpected_rate = 2.0\n")
            .expect_err("missing criteria");
        assert!(e.to_string().contains("tolerance"), "{e}");
    }
}
