//! The gates of the 1D kinds: the names a rate or ceiling gate refers to, the checks of a case's
//! families, sweeps and gates, and the rate, ceiling and audit verdicts on the outcomes.

use serde::{Deserialize, Serialize};

use contactlab::model::dynamic::audit::AuditSummary;

use std::path::Path;

use crate::core::case::Case;
use crate::core::format::{invalid, CaseError};
use crate::core::gate::{Check, GateVerdict, RateGate as CoreRateGate};
use crate::core::sweep::Against;

use crate::dynamic::cases::bars::family::FamilySpec;
use crate::dynamic::cases::bars::sweep::{SweepOutcome, SweepSpec};

/// Checks the names a rate or ceiling gate refers to: a `[[sweep]]`, a `[[family]]` the sweep
/// runs and a measured error; `field` names the gate in errors. The sweep on success.
pub(crate) fn check_gate_names<'a>(
    field: &str,
    (sweep, family, error): (&str, &str, &str),
    sweeps: &'a [SweepSpec],
    families: &[FamilySpec],
    errors: &[&str],
) -> Result<&'a SweepSpec, (String, String, String)> {
    let bad = |f: &str, v: String, e: String| Err((format!("{field}.{f}"), v, e));
    let Some(found) = sweeps.iter().find(|s| s.name == sweep) else {
        return bad("sweep", sweep.into(), "the name of a [[sweep]]".into());
    };
    if !families.iter().any(|f| f.name == family) || !found.runs(family) {
        return bad(
            "family",
            family.into(),
            format!("a [[family]] run by sweep `{}`", found.name),
        );
    }
    if !errors.contains(&error) {
        return bad(
            "error",
            error.into(),
            format!("one of {}", errors.join(", ")),
        );
    }
    Ok(found)
}

/// What a bar `[[gate]]` measures: one error of one family along one sweep, against h or k.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarSelect {
    pub sweep: String,
    pub family: String,
    pub error: String,
    pub against: Against,
}

/// `[[gate]]`: a rate gate of a bar case.
pub type RateGate = CoreRateGate<BarSelect>;

/// Checks a bar rate gate: the names it refers to, its parameter, then the core's criteria.
pub(crate) fn check_rate_gate(
    path: &Path,
    field: &str,
    g: &RateGate,
    sweeps: &[SweepSpec],
    families: &[FamilySpec],
    errors: &[&str],
) -> Result<(), CaseError> {
    let sel = &g.select;
    let names = check_gate_names(
        field,
        (&sel.sweep, &sel.family, &sel.error),
        sweeps,
        families,
        errors,
    );
    if let Err((f, v, e)) = names {
        return Err(invalid(path, &f, v, &e));
    }
    if sel.against == Against::HPlusK {
        return Err(invalid(
            path,
            &format!("{field}.against"),
            "h_plus_k",
            "h or k",
        ));
    }
    g.criteria.check(path, field)
}

/// `[[ceiling]]`: an error of one family on one level (M, N) of a sweep must stay below a value
/// (for quantities that converge without a clean rate, or must vanish to round-off).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CeilingGate {
    pub sweep: String,
    pub family: String,
    pub error: String,
    /// M of the level (default: the finest level of the sweep).
    pub elements: Option<usize>,
    pub ceiling: f64,
    #[serde(default)]
    pub note: String,
}

impl CeilingGate {
    /// Checks the names and the number.
    pub fn check(
        &self,
        field: &str,
        sweeps: &[SweepSpec],
        families: &[FamilySpec],
        errors: &[&str],
    ) -> Result<(), (String, String, String)> {
        let bad = |f: &str, v: String, e: String| Err((format!("{field}.{f}"), v, e));
        let sweep = check_gate_names(
            field,
            (&self.sweep, &self.family, &self.error),
            sweeps,
            families,
            errors,
        )?;
        if let Some(m) = self.elements {
            if !sweep.elements.contains(&m) {
                return bad(
                    "elements",
                    m.to_string(),
                    "the M of a level of the sweep".into(),
                );
            }
        }
        if !(self.ceiling.is_finite() && self.ceiling > 0.0) {
            return bad(
                "ceiling",
                self.ceiling.to_string(),
                "a finite number > 0".into(),
            );
        }
        Ok(())
    }
}

/// The checks common to the case formats: unique family and sweep names, each family, sweep and
/// gate valid.
pub fn check_common(
    case: &Case,
    families: &[FamilySpec],
    sweeps: &[SweepSpec],
    gates: &[RateGate],
    ceilings: &[CeilingGate],
    errors: &[&str],
) -> Result<(), CaseError> {
    let path = case.path.display().to_string();
    let invalid = |(field, value, expected): (String, String, String)| CaseError::Invalid {
        path: path.clone(),
        field,
        value,
        expected,
    };
    if families.is_empty() {
        return Err(invalid((
            "family".into(),
            "(none)".into(),
            "at least one [[family]]".into(),
        )));
    }
    for (i, f) in families.iter().enumerate() {
        f.check(&format!("family[{i}]")).map_err(invalid)?;
        if families[..i].iter().any(|g| g.name == f.name) {
            return Err(invalid((
                format!("family[{i}].name"),
                f.name.clone(),
                "a unique name".into(),
            )));
        }
    }
    for (i, s) in sweeps.iter().enumerate() {
        s.check(&format!("sweep[{i}]")).map_err(invalid)?;
        if let Some(e) = s.plot.iter().find(|e| !errors.contains(&e.as_str())) {
            return Err(invalid((
                format!("sweep[{i}].plot"),
                e.clone(),
                format!("names among {}", errors.join(", ")),
            )));
        }
        if sweeps[..i].iter().any(|g| g.name == s.name) {
            return Err(invalid((
                format!("sweep[{i}].name"),
                s.name.clone(),
                "a unique name".into(),
            )));
        }
        for f in &s.families {
            if !families.iter().any(|g| &g.name == f) {
                return Err(invalid((
                    format!("sweep[{i}].families"),
                    f.clone(),
                    "names of [[family]]s".into(),
                )));
            }
        }
    }
    for (i, g) in gates.iter().enumerate() {
        check_rate_gate(
            case.path(),
            &format!("gate[{i}]"),
            g,
            sweeps,
            families,
            errors,
        )?;
    }
    for (i, g) in ceilings.iter().enumerate() {
        g.check(&format!("ceiling[{i}]"), sweeps, families, errors)
            .map_err(invalid)?;
    }
    Ok(())
}

/// The gate name of a rate gate.
pub(crate) fn gate_name(g: &RateGate) -> String {
    let s = &g.select;
    format!(
        "{}/{}: {} vs {}",
        s.sweep,
        s.family,
        s.error,
        s.against.label()
    )
}

/// Evaluates the rate gates on the outcomes.
pub fn rate_gates(gates: &[RateGate], outcomes: &[SweepOutcome]) -> Vec<GateVerdict> {
    gates
        .iter()
        .map(|g| {
            let Some(o) = outcomes
                .iter()
                .find(|o| o.sweep == g.select.sweep && o.family == g.select.family)
            else {
                return GateVerdict::from_checks(
                    gate_name(g),
                    "rate",
                    vec![Check::holds(
                        "runs of the sweep and family",
                        false,
                        "present",
                    )],
                    &g.criteria.note,
                );
            };
            let param: Vec<f64> = o
                .levels
                .iter()
                .map(|l| {
                    if g.select.against == Against::K {
                        l.k
                    } else {
                        l.h
                    }
                })
                .collect();
            let error: Vec<f64> = o
                .levels
                .iter()
                .map(|l| l.errors.get(&g.select.error).copied().unwrap_or(f64::NAN))
                .collect();
            g.criteria.evaluate(gate_name(g), &param, &error)
        })
        .collect()
}

/// Evaluates the ceiling gates on the outcomes.
pub fn ceiling_gates(ceilings: &[CeilingGate], outcomes: &[SweepOutcome]) -> Vec<GateVerdict> {
    ceilings
        .iter()
        .map(|c| {
            let level = outcomes
                .iter()
                .find(|o| o.sweep == c.sweep && o.family == c.family)
                .and_then(|o| match c.elements {
                    Some(m) => o.levels.iter().find(|l| l.elements == m),
                    None => o.levels.iter().min_by(|a, b| a.h.total_cmp(&b.h)),
                });
            let (name, observed) = match level {
                Some(l) => (
                    format!("{} at M = {}, N = {}", c.error, l.elements, l.steps),
                    l.errors.get(&c.error).copied().unwrap_or(f64::NAN),
                ),
                None => (format!("{} (no such run)", c.error), f64::NAN),
            };
            let mut check = Check::at_most(&name, observed, c.ceiling);
            check.passed &= observed.is_finite();
            GateVerdict::from_checks(
                format!("{}/{}: {} ceiling", c.sweep, c.family, c.error),
                "ceiling",
                vec![check],
                &c.note,
            )
        })
        .collect()
}

/// The audit gate of each family over every run of every sweep: the worst residuals and step
/// works of its runs (each relative to its own run's energy scale).
pub fn worst_summary(outcomes: &[SweepOutcome], family: &str) -> Option<AuditSummary> {
    outcomes
        .iter()
        .filter(|o| o.family == family)
        .flat_map(|o| &o.levels)
        .map(|l| l.summary)
        .reduce(|a, s| a.worst(&s))
}
