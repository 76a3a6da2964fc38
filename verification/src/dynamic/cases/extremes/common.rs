//! What the studies of `dynamic_extremes` share: one recorded run of a scene ([`Run`]) and what
//! is measured on it (outcome, Newton iterations and backtracks, largest penetration and contact
//! force, contact interval and impulse, the largest relative drift of the balance (1.49) (BDS)),
//! the gate every run meets (no panic, a finite audit, a failure only as a typed error naming
//! its step; the identities (1.48)/(1.49)/HLT 3.7 where the combination conserves), and small
//! helpers for the scene tables, the report tables and the plots.

use contactlab::model::dynamic::solver::StepView;
use contactlab::scene::dynamic::DynamicScene;

use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, ExtremeReport};
use crate::dynamic::study::audit_checks;
use crate::plot::Series;
use contactlab::model::dynamic::record::{conserving, run_recorded_with, RecordedRun};

use crate::dynamic::scene::scene_from_table;

/// observed ≥ limit.
pub(crate) fn at_least(name: &str, observed: f64, limit: f64) -> Check {
    Check {
        name: name.to_string(),
        observed,
        limit: format!(">= {limit:.3e}"),
        passed: observed >= limit,
    }
}

pub(crate) fn set1(key: &str, value: impl Into<toml::Value>) -> toml::Table {
    let mut t = toml::Table::new();
    t.insert(key.to_string(), value.into());
    t
}

/// One run of a study: the scene, its recorded run (or why it could not run), a label.
pub(crate) struct Run {
    pub(crate) label: String,
    pub(crate) scene: DynamicScene,
    pub(crate) run: Result<RecordedRun, String>,
}

impl Run {
    pub(crate) fn k(&self) -> f64 {
        self.scene.problem.final_time / self.scene.problem.steps as f64
    }

    /// `solution` or the error message.
    pub(crate) fn outcome(&self) -> String {
        match &self.run {
            Ok(r) => match &r.result {
                Ok(_) => "solution".into(),
                Err(e) => format!(
                    "typed error after {} steps: {e}",
                    r.audit.records.len().saturating_sub(1)
                ),
            },
            Err(e) => format!("no run: {e}"),
        }
    }

    pub(crate) fn completed(&self) -> bool {
        matches!(&self.run, Ok(r) if r.result.is_ok())
    }

    /// The checks every run meets whatever it is: no panic, the recorded audit finite, and a
    /// failure (if any) a typed error naming its step.
    pub(crate) fn sanity_checks(&self) -> Vec<Check> {
        let mut checks = Vec::new();
        match &self.run {
            Err(e) => checks.push(Check::holds(
                &format!("runs without a panic ({e})"),
                false,
                "a solution or a typed error",
            )),
            Ok(r) => {
                checks.push(Check::holds(
                    "no NaN or ∞ in any recorded audit value",
                    r.audit.is_finite()
                        && r.displacement
                            .iter()
                            .chain(&r.velocity)
                            .all(|v| v.is_finite()),
                    "all finite",
                ));
                if let Err(e) = &r.result {
                    let msg = e.to_string();
                    checks.push(Check::holds(
                        &format!("the failure is a typed error naming its step or operator: {msg}"),
                        msg.contains("step"),
                        "a typed error with its data",
                    ));
                }
            }
        }
        checks
    }

    /// The audit checks of a completed run (identities at round-off where the combination
    /// conserves, dissipative signs always).
    pub(crate) fn audit_checks(&self) -> Vec<Check> {
        match &self.run {
            Ok(r) => audit_checks(&self.label, &r.summary(), conserving(&self.scene.problem)),
            Err(_) => Vec::new(),
        }
    }

    pub(crate) fn records(&self) -> &[contactlab::model::dynamic::audit::AuditRecord] {
        match &self.run {
            Ok(r) => &r.audit.records,
            Err(_) => &[],
        }
    }

    /// max_n |drift_n| / (E + Φ)_0 of the balance (1.49).
    pub(crate) fn max_relative_drift(&self) -> f64 {
        let Ok(r) = &self.run else {
            return f64::NAN;
        };
        let e0 = r
            .audit
            .records
            .first()
            .map_or(f64::NAN, |f| f.energy() + f.penalty);
        r.audit
            .balance_drift()
            .iter()
            .map(|(_, d)| d.abs())
            .fold(0.0, f64::max)
            / e0
    }

    pub(crate) fn newton(&self) -> (usize, usize) {
        let recs = self.records();
        (
            recs.iter().map(|r| r.newton_iterations).sum(),
            recs.iter().map(|r| r.newton_iterations).max().unwrap_or(0),
        )
    }

    pub(crate) fn max_penetration(&self) -> f64 {
        self.records()
            .iter()
            .map(|r| r.max_penetration)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    pub(crate) fn max_contact_force(&self) -> f64 {
        self.records()
            .iter()
            .map(|r| r.contact_force)
            .fold(0.0, f64::max)
    }

    /// (t_first, t_last, duration = t_last − t_first + k) of the steps with a contact force.
    pub(crate) fn contact_interval(&self) -> Option<(f64, f64, f64)> {
        let recs = self.records();
        let first = recs.iter().find(|r| r.contact_force > 0.0)?;
        let last = recs.iter().rev().find(|r| r.contact_force > 0.0)?;
        Some((first.time, last.time, last.time - first.time + self.k()))
    }

    /// Σ_n k F_n: the normal impulse of the foundation.
    pub(crate) fn impulse(&self) -> f64 {
        self.records()
            .iter()
            .skip(1)
            .map(|r| r.contact_force * self.k())
            .sum()
    }

    pub(crate) fn backtracks(&self) -> usize {
        match &self.run {
            Ok(r) => r.stats().backtracks,
            Err(_) => 0,
        }
    }

    /// Factorizations of an indefinite step Jacobian (the LBLᵀ or exact-tangent LU fallback).
    pub(crate) fn indefinite_factorizations(&self) -> usize {
        match &self.run {
            Ok(r) => r.stats().indefinite_factorizations,
            Err(_) => 0,
        }
    }

    pub(crate) fn summary_value(
        &self,
        f: impl Fn(&contactlab::model::dynamic::audit::AuditSummary) -> f64,
    ) -> f64 {
        match &self.run {
            Ok(r) => f(&r.summary()),
            Err(_) => f64::NAN,
        }
    }
}

/// Builds the scene with `set` and runs it with `extra` observing every step.
pub(crate) fn run_one(
    label: &str,
    table: &toml::Table,
    set: &toml::Table,
    extra: &mut dyn FnMut(&StepView<'_>),
) -> Result<Run, String> {
    let scene = scene_from_table(table, set, label)?;
    let run = match scene.solver() {
        Err(e) => Err(format!("{label}: {e}")),
        Ok(solver) => std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            run_recorded_with(&solver, &[], extra)
        }))
        .map_err(|_| format!("{label}: the solver panicked")),
    };
    Ok(Run {
        label: label.to_string(),
        scene,
        run,
    })
}

pub(crate) fn slug(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect::<String>()
        .split('_')
        .filter(|p| !p.is_empty())
        .collect::<Vec<_>>()
        .join("_")
}

pub(crate) fn push_run_gate(
    report: &mut CaseReport,
    study: &str,
    run: &Run,
    mut checks: Vec<Check>,
    expect: &str,
    note: &str,
) {
    let mut all = run.sanity_checks();
    all.append(&mut checks);
    report.gates.push(GateVerdict::from_checks(
        format!("{study}: {}", run.label),
        "extreme",
        all.clone(),
        note,
    ));
    report.extremes.push(ExtremeReport {
        name: format!("{study}: {}", run.label),
        expect: expect.to_string(),
        outcome: run.outcome(),
        checks: all,
        note: note.to_string(),
    });
}

pub(crate) fn header(cols: &[&str]) -> Vec<String> {
    cols.iter().map(|s| s.to_string()).collect()
}

/// A dashed power law y = y0 (x/x0)^slope from x0 to x1.
pub(crate) fn slope_line(name: &str, (x0, y0): (f64, f64), x1: f64, slope: f64) -> Series {
    Series::line(
        name.to_string(),
        [(x0, y0), (x1, y0 * (x1 / x0).powf(slope))],
    )
    .color(7)
    .dashed()
}
