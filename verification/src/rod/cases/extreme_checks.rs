//! The checks of an extreme run beyond its numbers. A run that must stop: which typed error, at
//! which step, naming what; for an explicit step above its bound, that it stops at the first
//! overflow — no non-finite value reaches an observer, and the run does not stop early. A run that
//! completes: the work it reports is the fast path its data allow (one factorization, the load's
//! path, the stiffness solves) and the explicit bound it enforces is 2a/b of the data.

use serde::Deserialize;

use contactlab::error::SolveError;
use contactlab::model::quasistatic::rod_solver::RodStep;
use contactlab::model::quasistatic::rod_step::RodStats;
use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::gate::Check;

/// What the observer saw of a run: the last step observed, its largest |u_i|, and whether every
/// observed u and w was finite.
#[derive(Debug, Clone, Copy)]
pub struct FiniteWatch {
    pub last_step: Option<usize>,
    pub last_displacement: f64,
    pub all_finite: bool,
}

impl Default for FiniteWatch {
    fn default() -> Self {
        Self {
            last_step: None,
            last_displacement: 0.0,
            all_finite: true,
        }
    }
}

impl FiniteWatch {
    /// Records one observed step.
    pub fn observe(&mut self, s: &RodStep<'_>) {
        let w = s.w.unwrap_or(&[]);
        self.all_finite &= s.u.iter().chain(w).all(|v| v.is_finite());
        self.last_step = Some(s.n);
        self.last_displacement = s.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    }
}

/// What an extreme run that must stop is expected to report (an `[[extreme]]` entry's keys).
#[derive(Debug, Clone, Copy)]
pub struct ErrorExpectation<'a> {
    /// `non_finite_error` or `not_converged`.
    pub expect: &'a str,
    /// The step the error must name (any step > 0 when absent).
    pub error_step: Option<usize>,
    /// The quantity a `NonFinite` error must name.
    pub error_quantity: Option<&'a str>,
    /// Texts the message must contain.
    pub message_contains: &'a [String],
}

/// The step, time and kind of `e` against the expectation.
pub fn error_checks(spec: &ErrorExpectation<'_>, e: &SolveError, message: &str) -> Vec<Check> {
    let (kind, step, quantity) = match e {
        SolveError::NonFinite { step, quantity, .. } => {
            ("non_finite_error", Some(*step), Some(quantity.as_str()))
        }
        SolveError::NewtonNotConverged { step, .. } => ("not_converged", Some(*step), None),
        _ => ("another error", None, None),
    };
    let mut checks = vec![Check::holds(
        &format!("stops with the typed error {} ({kind})", spec.expect),
        kind == spec.expect,
        match spec.expect {
            "not_converged" => "SolveError::NewtonNotConverged",
            _ => "SolveError::NonFinite",
        },
    )];
    let step_ok = match (spec.error_step, step) {
        (Some(want), Some(got)) => want == got,
        (None, Some(got)) => got > 0,
        (_, None) => false,
    };
    checks.push(Check::holds(
        &format!("names the step ({step:?})"),
        step_ok,
        &spec
            .error_step
            .map_or("a step > 0".into(), |s| format!("step {s}")),
    ));
    if let Some(want) = spec.error_quantity {
        checks.push(Check::holds(
            &format!("names the quantity ({})", quantity.unwrap_or("none")),
            quantity == Some(want),
            want,
        ));
    }
    for text in spec.message_contains {
        checks.push(Check::holds(
            &format!("the message names \"{text}\""),
            message.contains(text.as_str()),
            "contained",
        ));
    }
    checks
}

/// The run stopped at the first overflow: every observed state finite, the error at the step
/// after the last observed one, with an infinite (not NaN) value, and the last observed max |u_i|
/// so large that one more amplification `amplification` = |1 − kb/(a + θkb)| (u_n = (1 − kb/(a +
/// θkb)) u_{n−1} + the data's part, negligible there) exceeds the largest double, to 10⁻⁶: the
/// run did not stop early.
pub fn overflow_checks(watch: &FiniteWatch, e: &SolveError, amplification: f64) -> Vec<Check> {
    let (step, value) = match e {
        SolveError::NonFinite { step, value, .. } => (Some(*step), *value),
        _ => (None, f64::NAN),
    };
    // written so that it cannot overflow itself
    let reach = watch.last_displacement / (f64::MAX / amplification);
    vec![
        Check::holds(
            "no non-finite u or w reached the observer",
            watch.all_finite,
            "all finite",
        ),
        Check::holds(
            &format!(
                "the error's step {step:?} follows the last observed step {:?}, with an overflow ({value})",
                watch.last_step
            ),
            step.is_some()
                && step == watch.last_step.map(|n| n + 1)
                && value.is_infinite(),
            "last observed + 1, ±inf",
        ),
        Check::at_least(
            "last observed max |u_i| · |1 − kb/a| / the largest double",
            reach,
            1.0 - 1e-6,
        ),
    ]
}

/// `[fast_path]`: what every completed run of the case must report.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FastPath {
    /// `static` (f0 of x only), `time_scaled` (f0 = s(t) f(x)) or `space_time`.
    pub load_path: String,
    /// Triangular solve pairs with the stiffness factor over the whole run.
    pub stiffness_solves: usize,
}

impl FastPath {
    /// The run's statistics against the fast path, and the explicit scheme's bound against 2a/b
    /// computed here from the data (`None` for the implicit and midpoint schemes).
    pub fn checks(&self, stats: &RodStats, scheme: TimeScheme, a: f64, b: f64) -> Vec<Check> {
        let bound = (scheme == TimeScheme::Explicit).then_some(2.0 * a / b);
        vec![
            Check::holds(
                &format!("factorizations of K: {}", stats.factorizations),
                stats.factorizations == 1,
                "1 (the operator does not change)",
            ),
            Check::holds(
                &format!("load path: {}", stats.load_path),
                stats.load_path == self.load_path,
                &self.load_path,
            ),
            Check::holds(
                &format!("stiffness solves: {}", stats.stiffness_solves),
                stats.stiffness_solves == self.stiffness_solves,
                &self.stiffness_solves.to_string(),
            ),
            Check::holds(
                &format!(
                    "the explicit bound the run reports: {:?}",
                    stats.explicit_stability_bound
                ),
                stats.explicit_stability_bound == bound,
                &format!("{bound:?} (2a/b of the data, explicit scheme only)"),
            ),
        ]
    }
}
