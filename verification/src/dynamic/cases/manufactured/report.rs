//! What `dynamic_manufactured` reports: the rate gates on the series, the persistence of the
//! contact, the audit gates, and the plots and tables of the two studies.

use serde::Serialize;

use contactlab::model::dynamic::audit::AuditSummary;
use contactlab::model::dynamic::solver::DynamicStats;

use crate::core::sweep::Against;

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::dynamic::audit_state::{state_audit_checks, state_audit_gate};
use crate::dynamic::cases::manufactured::format::{
    Combination, ErrorName, ManufacturedCase, ManufacturedGate, SpaceStudy, Study, TimeStudy,
};
use crate::dynamic::cases::manufactured::runs::RunResult;
use crate::dynamic::study::{audit_checks, audit_gate, plot_audits, AuditRun};
use crate::manufactured::dynamic_plane::{DynamicManufactured, MIN_EXACT_PENETRATION};
use crate::plot::{Figure, Series};

/// A series of (parameter, error) points.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct RateSeries {
    pub(crate) label: String,
    pub(crate) param: Vec<f64>,
    pub(crate) error: Vec<f64>,
}

/// The worst audit summary over runs (largest residuals, drifts and step works).
pub(crate) fn worst(summaries: impl Iterator<Item = AuditSummary>) -> AuditSummary {
    summaries.reduce(|a, s| a.worst(&s)).unwrap_or_default()
}

/// Per-step cost and Newton statistics of a run.
pub(crate) fn cost_cells(s: &DynamicStats) -> [String; 3] {
    let steps = s.steps.max(1) as f64;
    [
        format!("{:.2}", s.newton_iterations as f64 / steps),
        format!("{}", s.max_newton_iterations),
        format!("{:.3e}", s.loop_seconds / steps),
    ]
}

/// The rate gate `g` on its series.
pub(crate) fn rate_gate(
    i: usize,
    gate: &ManufacturedGate,
    series: &[(Study, Option<Combination>, ErrorName, RateSeries)],
) -> Result<GateVerdict, String> {
    let g = &gate.select;
    let wanted = match (g.scheme, g.treatment) {
        (Some(scheme), Some(treatment)) => Some(Combination {
            scheme,
            treatment,
            full_path: g.full_path,
        }),
        _ => None,
    };
    let (_, _, _, s) = series
        .iter()
        .find(|(st, c, e, _)| *st == g.study && *c == wanted && *e == g.error)
        .ok_or_else(|| format!("gate[{i}]: no series for it"))?;
    let against = match g.study {
        Study::Time => Against::K,
        Study::Space => Against::H,
    };
    Ok(gate.criteria.evaluate(
        format!("{}: {:?} error vs {}", s.label, g.error, against.label()),
        &s.param,
        &s.error,
    ))
}

/// min p > 0 over every run and step: the contact stayed persistent, as the exact solution's.
pub(crate) fn persistence_gate(runs: &[RunResult]) -> GateVerdict {
    let min_p = runs
        .iter()
        .map(|r| r.min_penetration)
        .fold(f64::INFINITY, f64::min);
    GateVerdict::from_checks(
        "persistent contact: every Γ3 node penetrated at every step of every run".into(),
        "model",
        vec![
            Check {
                name: "exact min_{x,t} p(x, t) = min a(x, t)".into(),
                observed: MIN_EXACT_PENETRATION,
                limit: "> 0".into(),
                passed: MIN_EXACT_PENETRATION > 0.0,
            },
            Check {
                name: "computed min over runs, steps and Γ3 nodes of p_i".into(),
                observed: min_p,
                limit: "> 0".into(),
                passed: min_p > 0.0,
            },
        ],
        "with p > 0 throughout, the energy-consistent force is r (p_n + p_{n−1})/2 and no contact \
         switch limits the rates",
    )
}

/// One audit gate per combination: its worst summary over every level it ran.
pub(crate) fn audit_gates(report: &mut CaseReport, c: &ManufacturedCase, runs: &[RunResult]) {
    let mut combos: Vec<Combination> = Vec::new();
    for r in runs {
        if !combos.contains(&r.combination) {
            combos.push(r.combination);
        }
    }
    for combo in combos {
        let of_combo: Vec<&RunResult> = runs.iter().filter(|r| r.combination == combo).collect();
        let summary = worst(of_combo.iter().map(|r| r.audit.summary()));
        let conserving = combo.conserving(c.law);
        let label = combo.label();
        let note = if conserving.balance {
            "conserving scheme: the body force and the tractions do work; the audit's external \
             work dᵀ f(t_{n−1/2}) is the work of the load the scheme applies, so the identities \
             still hold to round-off"
        } else {
            "not a conserving combination: only the dissipation signs are gated; its residuals \
             are plotted"
        };
        // a combination that claims no identity and has no step work with a sign (Newmark
        // with a penalty: no friction, no Signorini stage) has nothing for this gate; its
        // state audit still compares its records
        let checks = audit_checks(&label, &summary, conserving);
        if !checks.is_empty() {
            report.gates.push(audit_gate(
                &format!(
                    "energy audit, {label} ({} runs, worst over levels)",
                    of_combo.len()
                ),
                checks,
                note,
            ));
        }
    }
    let mut state = Vec::new();
    for r in runs {
        let label = format!(
            "{} on {n}×{n}, N = {}",
            r.combination.label(),
            r.steps,
            n = r.divisions
        );
        match &r.state {
            Ok(a) => state.extend(state_audit_checks(&label, a, r.claims)),
            Err(e) => state.push(Check::holds(
                &format!("{label}: {e}"),
                false,
                "the state audit runs",
            )),
        }
    }
    report
        .gates
        .push(state_audit_gate("audit recomputed from the state", state));
}

/// Time-study series, plots and table: ‖u_N − u(T)‖_{L²} on the affine field, the time error
/// alone.
pub(crate) fn time_outputs(
    ctx: &RunContext,
    report: &mut CaseReport,
    m: &DynamicManufactured,
    t: &TimeStudy,
    omega: f64,
    runs: &[RunResult],
    series: &mut Vec<(Study, Option<Combination>, ErrorName, RateSeries)>,
) -> Result<(), String> {
    let mut fig = Figure::new(format!(
        "time error ‖u_N − u(T)‖_L² on {0}×{0}, affine field (no space error)",
        t.divisions,
    ))
    .x_label("k")
    .y_label("‖u_N − u(T)‖_L²")
    .log_log()
    .reference_slope(1.0, "slope 1")
    .reference_slope(2.0, "slope 2");
    let mut rows = Vec::new();
    for (i, combo) in t.runs.iter().enumerate() {
        let of: Vec<&RunResult> = runs.iter().filter(|r| r.combination == *combo).collect();
        let k: Vec<f64> = of.iter().map(|r| m.final_time / r.steps as f64).collect();
        let e: Vec<f64> = of.iter().map(|r| r.errors.l2).collect();
        for (j, r) in of.iter().enumerate() {
            let rate = if j > 0 {
                format!("{:.3}", (e[j - 1] / e[j]).ln() / (k[j - 1] / k[j]).ln())
            } else {
                "—".into()
            };
            let [mean_it, max_it, per_step] = cost_cells(&r.stats);
            rows.push(vec![
                combo.label(),
                r.steps.to_string(),
                format!("{:.4e}", k[j]),
                format!("{:.3}", k[j] * omega),
                format!("{:.4e}", e[j]),
                rate,
                format!("{:.4e}", r.errors.energy),
                mean_it,
                max_it,
                per_step,
            ]);
        }
        fig = fig.series(
            Series::line_markers(combo.label(), k.iter().copied().zip(e.iter().copied())).color(i),
        );
        series.push((
            Study::Time,
            Some(*combo),
            ErrorName::L2,
            RateSeries {
                label: format!("time, {}", combo.label()),
                param: k,
                error: e,
            },
        ));
    }
    ctx.plot(report, "time_rates", &fig)?;
    report.tables.push(Table {
        title: format!(
            "time study on {0}×{0} (ω_max = {1:.1}), affine field: the error against u(T) is the \
             time error alone; Newton iterations and cost per step",
            t.divisions, omega
        ),
        header: [
            "run",
            "N",
            "k",
            "k ω_max",
            "‖u_N − u(T)‖_L²",
            "pairwise rate",
            "‖ε(u_N − u(T))‖_L²",
            "Newton its/step",
            "max its",
            "s/step",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
    let finest = t.steps.iter().copied().max().unwrap_or(0);
    let audited: Vec<AuditRun<'_>> = runs
        .iter()
        .filter(|r| r.steps == finest)
        .map(|r| AuditRun {
            label: format!("{} (N = {})", r.combination.label(), r.steps),
            audit: &r.audit,
        })
        .collect();
    plot_audits(
        ctx,
        report,
        "time_audit",
        &format!("{0}×{0}, N = {finest}", t.divisions),
        &audited,
        None,
    )
}

/// Space-study series, plot and table.
pub(crate) fn space_outputs(
    ctx: &RunContext,
    report: &mut CaseReport,
    s: &SpaceStudy,
    runs: &[RunResult],
    series: &mut Vec<(Study, Option<Combination>, ErrorName, RateSeries)>,
) -> Result<(), String> {
    let label = Combination {
        scheme: s.scheme,
        treatment: s.treatment,
        full_path: false,
    }
    .label();
    let h: Vec<f64> = runs.iter().map(|r| 1.0 / r.divisions as f64).collect();
    let energy: Vec<f64> = runs.iter().map(|r| r.errors.energy).collect();
    let l2: Vec<f64> = runs.iter().map(|r| r.errors.l2).collect();
    let fig = Figure::new(format!(
        "errors at T against u(T), {label}, N = {} n (k ∝ h)",
        s.steps_per_division
    ))
    .x_label("h = 1/n")
    .y_label("error")
    .log_log()
    .series(
        Series::line_markers(
            "‖ε(u_N − u(T))‖",
            h.iter().copied().zip(energy.iter().copied()),
        )
        .color(0),
    )
    .series(
        Series::line_markers("‖u_N − u(T)‖_L²", h.iter().copied().zip(l2.iter().copied())).color(1),
    )
    .reference_slope(1.0, "slope 1")
    .reference_slope(2.0, "slope 2");
    ctx.plot(report, "space_rates", &fig)?;
    let pair = |v: &[f64], j: usize| {
        if j == 0 {
            "—".to_string()
        } else {
            format!("{:.3}", (v[j - 1] / v[j]).ln() / (h[j - 1] / h[j]).ln())
        }
    };
    report.tables.push(Table {
        title: format!("space study, {label}: errors at T, pairwise rates, Newton iterations and cost per step"),
        header: [
            "n × n",
            "N",
            "‖ε(u_N − u(T))‖",
            "rate",
            "‖u_N − u(T)‖_L²",
            "rate",
            "Newton its/step",
            "max its",
            "s/step",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows: runs
            .iter()
            .enumerate()
            .map(|(j, r)| {
                let [mean_it, max_it, per_step] = cost_cells(&r.stats);
                vec![
                    format!("{0}×{0}", r.divisions),
                    r.steps.to_string(),
                    format!("{:.4e}", energy[j]),
                    pair(&energy, j),
                    format!("{:.4e}", l2[j]),
                    pair(&l2, j),
                    mean_it,
                    max_it,
                    per_step,
                ]
            })
            .collect(),
    });
    series.push((
        Study::Space,
        None,
        ErrorName::Energy,
        RateSeries {
            label: format!("space, {label}, energy norm"),
            param: h.clone(),
            error: energy,
        },
    ));
    series.push((
        Study::Space,
        None,
        ErrorName::L2,
        RateSeries {
            label: format!("space, {label}, L²"),
            param: h,
            error: l2,
        },
    ));
    Ok(())
}
