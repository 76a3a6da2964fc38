//! Gates: the verdicts that make `verify` fail.
//!
//! A rate gate (scikit-fem's convention, made strict): on the levels chosen by the level rule
//! ([`crate::stats::levels`]: pre-asymptotic levels and floors left out automatically, the same
//! way everywhere),
//!
//! 1. the fitted rate is within `tolerance` of the expected rate;
//! 2. its 95% confidence interval is narrower than `ci_width`;
//! 3. the two finest pairwise rates are each within `tolerance` of the *expected* rate (the levels
//!    are in the asymptotic range of the expected behaviour, not merely self-consistent);
//! 4. the error on the finest level is at most `ceiling_factor` (≤ [`MAX_CEILING_FACTOR`]) times
//!    the error model's prediction there: E ≈ C p^expected with C fitted on the other levels used
//!    (a finest level that leaves the model — a floor reached unnoticed, a loss of convergence —
//!    fails, whatever its rate).
//!
//! [`RateCriteria`] holds those numbers once for every family; a family's `[[gate]]` adds only
//! the keys that select its data ([`RateGate`]). A model gate ([`ModelCriteria`]) fits
//! E(h, k) ≈ C_h h^p ⊕ C_k k^q. Every printed limit is the exact number compared.

use serde::Serialize;

use std::path::Path;

use serde::de::{DeserializeOwned, Deserializer};
use serde::Deserialize;

use crate::core::format::{invalid, positive, CaseError};
use crate::stats::error_model::{fit_error_model_with, Combination, ErrorModelFit};
use crate::stats::levels::{asymptotic_window, LevelWindow, MIN_LEVELS};
use crate::stats::rate_fit::{fit_rate, pairwise_rates, RateFit};

/// The confidence level of every interval in the reports.
pub const CONFIDENCE: f64 = 0.95;

/// The largest factor a ceiling may put above the error model's prediction.
pub const MAX_CEILING_FACTOR: f64 = 3.0;

/// The ceiling factor of a rate gate that does not state one.
pub const DEFAULT_CEILING_FACTOR: f64 = 2.0;

/// One checked condition.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// What is checked.
    pub name: String,
    /// The observed value.
    pub observed: f64,
    /// The condition it must meet, as text, with the exact numbers compared (`<= 0.01`,
    /// `in [0.95, 1.05]`).
    pub limit: String,
    pub passed: bool,
}

impl Check {
    /// observed ≤ limit.
    pub fn at_most(name: &str, observed: f64, limit: f64) -> Self {
        Self {
            name: name.to_string(),
            observed,
            limit: format!("<= {limit:e}"),
            passed: observed <= limit,
        }
    }

    /// observed ≥ limit.
    pub fn at_least(name: &str, observed: f64, limit: f64) -> Self {
        Self {
            name: name.to_string(),
            observed,
            limit: format!(">= {limit:e}"),
            passed: observed >= limit,
        }
    }

    /// target − tol ≤ observed ≤ target + tol (the bounds as computed, printed exactly).
    pub fn within(name: &str, observed: f64, target: f64, tol: f64) -> Self {
        let (low, high) = (target - tol, target + tol);
        Self {
            name: name.to_string(),
            observed,
            limit: format!("in [{low}, {high}]"),
            passed: low <= observed && observed <= high,
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
    /// The levels of a rate gate and which of them the level rule used.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub levels: Option<LevelWindow>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_fit: Option<ErrorModelFit>,
    /// The checks compare measured times or ratios of them: the verdict can differ from run to
    /// run, so the gate is kept apart from the deterministic report (`core::report::split`).
    /// Only machine-independent figures may be gated so (ratios, slopes), never absolute times.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub timing: bool,
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
            levels: None,
            model_fit: None,
            timing: false,
        }
    }

    /// A verdict on measured times (ratios or slopes of them, never absolute times): see
    /// [`GateVerdict::timing`].
    pub fn from_timing_checks(name: String, checks: Vec<Check>, note: &str) -> Self {
        let mut v = Self::from_checks(name, "performance", checks, note);
        v.timing = true;
        v
    }
}

/// The numbers of a rate gate, the same in every family's `[[gate]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RateCriteria {
    pub expected_rate: f64,
    /// |fitted − expected| ≤ tolerance, and the same for the two finest pairwise rates; also the
    /// drift threshold of the level rule.
    pub tolerance: f64,
    /// The 95% confidence interval must be narrower.
    pub ci_width: f64,
    /// The finest error must be at most this times the error model's prediction
    /// (1 < factor ≤ [`MAX_CEILING_FACTOR`]; default [`DEFAULT_CEILING_FACTOR`]).
    pub ceiling_factor: Option<f64>,
    /// Why the gate expects what it expects.
    #[serde(default)]
    pub note: String,
}

/// The keys of [`RateCriteria`] in a gate table.
const CRITERIA_KEYS: [&str; 5] = [
    "expected_rate",
    "tolerance",
    "ci_width",
    "ceiling_factor",
    "note",
];

impl RateCriteria {
    /// Checks the numbers; `field` names the gate in errors (`gate[2]`).
    pub fn check(&self, path: &Path, field: &str) -> Result<(), CaseError> {
        for (name, v) in [("tolerance", self.tolerance), ("ci_width", self.ci_width)] {
            positive(path, &format!("{field}.{name}"), v)?;
        }
        if let Some(f) = self.ceiling_factor {
            if !(f > 1.0 && f <= MAX_CEILING_FACTOR) {
                return Err(invalid(
                    path,
                    &format!("{field}.ceiling_factor"),
                    f,
                    &format!("in (1, {MAX_CEILING_FACTOR}]"),
                ));
            }
        }
        Ok(())
    }

    /// The ceiling factor in force.
    pub fn ceiling_factor(&self) -> f64 {
        self.ceiling_factor.unwrap_or(DEFAULT_CEILING_FACTOR)
    }

    /// Evaluates the gate on the (parameter, error) pairs of one series, with no known floor.
    pub fn evaluate(&self, name: String, param: &[f64], error: &[f64]) -> GateVerdict {
        self.evaluate_with_floor(name, param, error, 0.0)
    }

    /// Evaluates the gate on one series whose errors cannot fall below `floor` (round-off, the
    /// solver's tolerance, or the other variable's error; 0 when none is known): the level rule
    /// leaves out the levels at the floor and the pre-asymptotic ones.
    pub fn evaluate_with_floor(
        &self,
        name: String,
        param: &[f64],
        error: &[f64],
        floor: f64,
    ) -> GateVerdict {
        let fail = |what: String| {
            GateVerdict::from_checks(
                name.clone(),
                "rate",
                vec![Check::holds(&what, false, "a valid fit")],
                &self.note,
            )
        };
        if param.len() != error.len() {
            return fail(format!(
                "{} parameters for {} errors",
                param.len(),
                error.len()
            ));
        }
        if let Some(i) = (0..param.len()).find(|&i| {
            !(param[i].is_finite() && param[i] > 0.0 && error[i].is_finite() && error[i] > 0.0)
        }) {
            return fail(format!(
                "level {i}: parameter {} and error {} must be finite and positive",
                param[i], error[i]
            ));
        }
        let window = asymptotic_window(param, error, self.tolerance, floor);
        let (p, e) = window.used();
        if p.len() < MIN_LEVELS {
            let mut v = fail(format!(
                "at least {MIN_LEVELS} levels outside the floor ({})",
                window.describe()
            ));
            v.levels = Some(window);
            return v;
        }
        let mut fit = match fit_rate(&p, &e, p.len(), CONFIDENCE) {
            Ok(fit) => fit,
            Err(err) => return fail(format!("rate fit ({err})")),
        };
        fit.pairwise = pairwise_rates(param, error);
        let expected = self.expected_rate;
        let mut checks = vec![
            Check::within(
                &format!("fitted rate ({})", window.describe()),
                fit.rate,
                expected,
                self.tolerance,
            ),
            Check::at_most("95% CI width", fit.ci_high - fit.ci_low, self.ci_width),
        ];
        // the finest two pairwise rates of the used levels, against the expected rate
        let n = p.len();
        for i in (n - 2..n).rev() {
            let j = i - 1;
            let rate = (e[j].ln() - e[i].ln()) / (p[j].ln() - p[i].ln());
            checks.push(Check::within(
                &format!(
                    "pairwise rate {:e} -> {:e} vs the expected rate",
                    p[j], p[i]
                ),
                rate,
                expected,
                self.tolerance,
            ));
        }
        // ceiling: the error model E = C p^expected on the other used levels predicts the finest
        let log_c = (0..n - 1)
            .map(|i| e[i].ln() - expected * p[i].ln())
            .sum::<f64>()
            / (n - 1) as f64;
        let predicted = (log_c + expected * p[n - 1].ln()).exp();
        let factor = self.ceiling_factor();
        checks.push(Check::at_most(
            &format!(
                "finest-level error vs {factor} × the prediction {predicted:e} of E = C·p^{expected} \
                 from the coarser levels"
            ),
            e[n - 1],
            factor * predicted,
        ));
        let mut v = GateVerdict::from_checks(name, "rate", checks, &self.note);
        v.rate_fit = Some(fit);
        v.levels = Some(window);
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
    //! Gate logic on synthetic data with a known rate: the right expectation passes; a wrong
    //! expected rate fails; a finest level above the model's prediction fails; a scatter that the
    //! old "expected inside the CI" mode let through fails; pairwise rates are held to the
    //! expected rate, not to the fit; printed limits are the compared numbers.
    use super::*;

    fn spec(expected: f64) -> RateCriteria {
        RateCriteria {
            expected_rate: expected,
            tolerance: 0.1,
            ci_width: 0.1,
            ceiling_factor: None,
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
        assert_eq!(v.levels.as_ref().map(|w| w.count()), Some(5));
    }

    #[test]
    fn deliberately_wrong_expected_rate_fails() {
        let (h, e) = data();
        let v = spec(2.0).evaluate("g".into(), &h, &e);
        assert!(!v.passed);
        assert!(!v.checks[0].passed);
    }

    #[test]
    fn a_finest_level_above_the_model_prediction_fails_the_ceiling() {
        // rate 1 on the coarse levels, then the finest level stalls at 2.5× the prediction
        let (h, mut e) = data();
        e[4] *= 2.5;
        let mut s = spec(1.0);
        s.tolerance = 2.0;
        s.ci_width = 10.0;
        let v = s.evaluate("g".into(), &h, &e);
        let ceiling = v.checks.last().unwrap();
        assert!(ceiling.name.contains("prediction"), "{v:?}");
        assert!(!ceiling.passed, "{v:?}");
        s.ceiling_factor = Some(3.0);
        assert!(s.evaluate("g".into(), &h, &e).checks.last().unwrap().passed);
    }

    #[test]
    fn scattered_pairwise_rates_fail_even_when_the_fit_is_right() {
        // E = h² with ±10% deterministic scatter: the old CI-containment mode passed this
        let h: Vec<f64> = (0..6).map(|i| 0.1 / 2f64.powi(i)).collect();
        let wiggle = [1.0, 1.1, 0.9, 1.08, 0.93, 1.02];
        let e: Vec<f64> = h.iter().zip(wiggle).map(|(h, w)| h * h * w).collect();
        let mut s = spec(2.0);
        s.ci_width = 0.5;
        let v = s.evaluate("g".into(), &h, &e);
        assert!(!v.passed, "{v:?}");
        assert!(v
            .checks
            .iter()
            .any(|c| c.name.contains("pairwise") && !c.passed));
    }

    #[test]
    fn pairwise_rates_are_compared_with_the_expected_rate_not_the_fit() {
        // a clean rate 1.5 sweep: self-consistent (pairwise = fit), but not the expected 2
        let h: Vec<f64> = (0..6).map(|i| 0.1 / 2f64.powi(i)).collect();
        let e: Vec<f64> = h.iter().map(|h| h.powf(1.5)).collect();
        let mut s = spec(2.0);
        s.tolerance = 0.6; // the fit alone would pass
        let v = s.evaluate("g".into(), &h, &e);
        assert!(v.checks[0].passed);
        s.tolerance = 0.4;
        let v = s.evaluate("g".into(), &h, &e);
        assert!(v
            .checks
            .iter()
            .filter(|c| c.name.contains("pairwise"))
            .all(|c| !c.passed));
    }

    #[test]
    fn pre_asymptotic_coarse_levels_are_left_out_automatically() {
        let h: Vec<f64> = (0..7).map(|i| 0.5 / 2f64.powi(i)).collect();
        let e: Vec<f64> = h.iter().map(|h| h * h + 3.0 * h.powi(4)).collect();
        let mut s = spec(2.0);
        s.tolerance = 0.05;
        let v = s.evaluate("g".into(), &h, &e);
        assert!(v.passed, "{v:?}");
        assert!(v.levels.unwrap().describe().contains("pre-asymptotic"));
    }

    #[test]
    fn a_floor_leaves_the_fine_levels_out_and_too_few_levels_fail() {
        let h: Vec<f64> = (0..6).map(|i| 0.1 / 2f64.powi(i)).collect();
        let floor = 1e-4;
        let e: Vec<f64> = h.iter().map(|h| h * h + floor).collect();
        let v = spec(2.0).evaluate_with_floor("g".into(), &h, &e, floor);
        assert!(!v.passed, "only the first levels are above 10 F: {v:?}");
        assert!(v.checks[0].name.contains("at least 3 levels"), "{v:?}");
    }

    #[test]
    fn printed_limits_are_the_numbers_compared() {
        let c = Check::at_most("x", 5.000000000000001e-4, 5e-4);
        assert!(!c.passed);
        assert_eq!(c.limit, "<= 5e-4");
        let c = Check::within("x", 1.0, 2.0, 0.1);
        assert_eq!(c.limit, "in [1.9, 2.1]");
    }

    #[test]
    fn a_ceiling_factor_above_three_is_a_typed_error() {
        let mut s = spec(1.0);
        s.ceiling_factor = Some(4.0);
        let e = s
            .check(Path::new("c.toml"), "gate[0]")
            .unwrap_err()
            .to_string();
        assert!(e.contains("gate[0].ceiling_factor"), "{e}");
    }

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Select {
        series: String,
    }

    #[test]
    fn a_gate_table_splits_into_selection_and_criteria_and_denies_unknown_keys() {
        let text = "series = \"sine\"\nexpected_rate = 2.0\ntolerance = 0.1\n\
                    ci_width = 0.2\n";
        let g: RateGate<Select> = toml::from_str(text).expect("parses");
        assert_eq!(g.select.series, "sine");
        assert_eq!(g.criteria.ceiling_factor(), DEFAULT_CEILING_FACTOR);
        let e = toml::from_str::<RateGate<Select>>(&format!("{text}stray = 1\n"))
            .expect_err("unknown key");
        assert!(e.to_string().contains("stray"), "{e}");
        let e = toml::from_str::<RateGate<Select>>(&format!("{text}finest_levels = 3\n"))
            .expect_err("levels are chosen by the rule, not by hand");
        assert!(e.to_string().contains("finest_levels"), "{e}");
        let e = toml::from_str::<RateGate<Select>>("series = \"s\"\nexpected_rate = 2.0\n")
            .expect_err("missing criteria");
        assert!(e.to_string().contains("tolerance"), "{e}");
    }
}
