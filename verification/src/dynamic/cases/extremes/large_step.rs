//! `[[large_step]]` of `dynamic_extremes`: time steps from resolved to far above the
//! wave-crossing time h_min/c and the contact duration. The conserving combinations must stay
//! bounded with the identities (1.48)/(1.49)/HLT 3.7 at round-off (BDS; HLT); the others
//! (Newmark, the midpoint rule on a hyperelastic body, the plain penalty force) are reported.
//! A study-level gate checks that the largest step reaches the extremes claimed.

use std::fmt::Write as _;

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::dynamic::study::{plot_audits, AuditRun};
use crate::plot::{Figure, Series};
use contactlab::model::dynamic::record::conserving;

use super::common::{at_least, header, push_run_gate, run_one, slug, Run};
use super::LargeStepSpec;

pub(super) fn run_large_step(
    index: usize,
    spec: &LargeStepSpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let study = format!("large step: {}", spec.name);
    let mut grid: Vec<Vec<Run>> = Vec::new();
    for variant in &spec.variant {
        let mut row = Vec::new();
        for &n in &spec.steps {
            let mut set = variant.set.clone();
            set.insert("time.steps".into(), toml::Value::Integer(n as i64));
            let mut run = run_one(
                &format!("{}, N = {n}", variant.label),
                &spec.scene,
                &set,
                &mut |_| {},
            )?;
            run.label = format!("{}, k = {:.2e}", variant.label, run.k());
            row.push(run);
        }
        grid.push(row);
    }
    // the contact duration: the finest run of the first conserving variant
    let reference = grid
        .iter()
        .find(|row| {
            let c = conserving(&row[0].scene.problem);
            c.balance && c.contact
        })
        .unwrap_or(&grid[0]);
    let t_contact = reference[0].contact_interval().map_or(f64::NAN, |c| c.2);
    let wave = {
        let b = &reference[0].scene.problem.body;
        b.h_min() / b.wave_speed()
    };
    let mut rows = Vec::new();
    for row in &grid {
        for run in row {
            let cons = conserving(&run.scene.problem);
            let drift = run.max_relative_drift();
            let mut checks = Vec::new();
            let expect = if cons.balance && cons.contact {
                checks.push(Check::holds(
                    &format!("{}: the run completes", run.label),
                    run.completed(),
                    "a solution",
                ));
                checks.extend(run.audit_checks());
                checks.push(Check::at_most(
                    &format!(
                        "{}: bounded energy: max |drift| / (E + Φ)_0 (limit C ε √N S / E_ref)",
                        run.label
                    ),
                    drift,
                    run.summary_value(|s| s.tolerance()),
                ));
                "conserving: a solution, bounded energy, identities at round-off"
            } else {
                "not conserving: reported (a solution or a typed error, nothing non-finite)"
            };
            push_run_gate(report, &study, run, checks, expect, &spec.note);
            let (its, max_it) = run.newton();
            rows.push(vec![
                run.label.clone(),
                if cons.balance && cons.contact {
                    "yes"
                } else {
                    "no"
                }
                .into(),
                run.outcome(),
                format!("{:.2}", run.k() / wave),
                format!("{:.3}", run.k() / t_contact),
                format!("{drift:.3e}"),
                format!("{:.2e}", run.summary_value(|s| s.max_drift_1_48)),
                format!("{:.2e}", run.summary_value(|s| s.max_drift_1_49)),
                format!("{:.2e}", run.summary_value(|s| s.max_drift_3_7)),
                format!("{:.4e}", run.max_penetration()),
                format!("{its} / {max_it}"),
                format!("{}", run.backtracks()),
                format!("{}", run.indefinite_factorizations()),
            ]);
        }
    }
    let k_max = grid[0].iter().map(|r| r.k()).fold(0.0, f64::max);
    report.gates.push(GateVerdict::from_checks(
        format!("{study}: the steps reach the extremes claimed"),
        "extreme",
        vec![
            at_least(
                "largest k / (h_min / c)",
                k_max / wave,
                spec.min_wave_crossings,
            ),
            at_least(
                "largest k / contact duration (finest conserving run)",
                k_max / t_contact,
                spec.min_contact_fraction,
            ),
        ],
        &spec.note,
    ));
    report.tables.push(Table {
        title: format!(
            "{study} ({}; h_min/c = {wave:.3e}, contact duration {t_contact:.3e})",
            grid[0][0].scene.problem.body.describe()
        ),
        header: header(&[
            "run",
            "conserving",
            "outcome",
            "k c / h_min",
            "k / contact time",
            "max |drift| / E_0",
            "max |R(1.48)|/E_ref",
            "max |R(1.49)|/E_ref",
            "max |R(3.7)|/E_ref",
            "max penetration",
            "Newton its (total / max)",
            "backtracks",
            "indefinite factorizations",
        ]),
        rows,
    });
    let mut drift_fig = Figure::new(format!("{}: energy error against the step", spec.name))
        .x_label("k / (h_min / c)")
        .y_label("max_n |drift_n| / (E + Φ)_0 (floored at 1e-17)")
        .log_log()
        .horizontal_line(
            grid[0]
                .iter()
                .map(|r| r.summary_value(|s| s.tolerance()))
                .filter(|t| t.is_finite())
                .fold(0.0, f64::max),
            "gate C ε √N S / E_ref (largest of the runs)",
        );
    for (c, (row, variant)) in grid.iter().zip(&spec.variant).enumerate() {
        drift_fig = drift_fig.series(
            Series::line_markers(
                variant.label.clone(),
                row.iter()
                    .filter(|r| r.run.is_ok())
                    .map(|r| (r.k() / wave, r.max_relative_drift().max(1e-17))),
            )
            .color(c),
        );
    }
    ctx.plot(
        report,
        &format!("large_step_{index}_{}_drift", slug(&spec.name)),
        &drift_fig,
    )?;
    // the energy histories at the largest step that still has a history (≥ 8 steps)
    let shown = spec
        .steps
        .iter()
        .rposition(|&n| n >= 8)
        .unwrap_or(spec.steps.len() - 1);
    let last: Vec<AuditRun<'_>> = grid
        .iter()
        .zip(&spec.variant)
        .filter_map(|(row, v)| {
            let run = row.get(shown)?;
            run.run.as_ref().ok().map(|r| AuditRun {
                label: format!("{} (k = {:.2e})", v.label, run.k()),
                audit: &r.audit,
            })
        })
        .collect();
    let mut title = String::new();
    let _ = write!(title, "{} at N = {} steps", spec.name, spec.steps[shown]);
    plot_audits(
        ctx,
        report,
        &format!("large_step_{index}_{}", slug(&spec.name)),
        &title,
        &last,
        None,
    )
}
