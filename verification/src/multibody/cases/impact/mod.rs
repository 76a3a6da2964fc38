//! `multibody_impact`: two neo-Hookean rings in oblique impact (docs/multibody.md §3–§4): the
//! energy–momentum scheme's conservation laws, the midpoint rule's energy error and its failure at
//! large steps, the grid convergence of what an experiment reports, and the work–precision of the
//! three schemes.
//!
//! Gates:
//! - per run, the audit (`crate::multibody::study::audit_checks`): the energy identity and the
//!   conservation of energy between changes of the active set for the energy–momentum scheme;
//!   P and J for every midpoint-type run (free rings, objective law), friction's sign always;
//! - the midpoint rule's energy error in steps without a change of the active set at least
//!   `min_energy_error` E_0 (it does not conserve, and this is seen);
//! - a run with the conserving penalty P = (ε/2)(g₋)²: max_n |E_n − E_0 − Σ switch work| / E_0
//!   at most `max_other_energy_change` (the secant force conserves E = K + U + P in every step
//!   but where a penetrated node's master segment changes; the rings'
//!   segments stretch while penetrated, so the discrete gradient of the gap in the invariants is
//!   exercised where the midpoint gradient would differ);
//! - every run separates before T (rebound velocities and contact duration are defined);
//! - at a large step: the energy–momentum run completes and its energy changes only by the
//!   activation and switch work (plus `max_other_energy_change` E_0); the midpoint run stops with a
//!   typed error or ends with an energy error of at least `min_midpoint_energy_error`;
//! - self-convergence: the GCI of each ring's rebound velocity and of the contact duration;
//! - work–precision: one scheme reaches another's finest error with at most a fraction of its work.

pub mod format;
pub mod plots;
pub mod runs;

use rayon::prelude::*;

use contactlab::model::multibody::audit::summarize;
use contactlab::model::multibody::scheme::MultibodyScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table, WorkPoint, WorkPrecisionReport};
use crate::multibody::audit_reference::audit_controls;
use crate::multibody::audit_state::{state_audit_checks, state_audit_gate};
use crate::multibody::study::{audit_checks, audit_gate, plot_audits, AuditRun, Claims};
use crate::stats::gci::{analyse, GciResult};
use format::ImpactCase;
use runs::{run_job, Job, Outcome};

/// Checks the case's format.
pub fn check(case: &Case) -> Result<(), CaseError> {
    case.body::<ImpactCase>()?.check(case.path())
}

/// The jobs of the case, without repeats: the runs, the large-step runs, the GCI levels, the
/// work–precision levels.
fn jobs(c: &ImpactCase) -> Vec<Job> {
    let mut jobs: Vec<Job> = Vec::new();
    let mut push = |j: Job| {
        if !jobs.contains(&j) {
            jobs.push(j);
        }
    };
    for r in &c.runs {
        push(Job::of(r));
    }
    if let Some(l) = &c.large_step {
        for scheme in [MultibodyScheme::EnergyMomentum, MultibodyScheme::Midpoint] {
            push(Job {
                scheme,
                friction: 0.0,
                factor: 1.0,
                steps: Some(l.steps),
                penalty: None,
                size: 1.0,
            });
        }
    }
    if let Some(g) = &c.gci {
        for &f in &g.factors {
            push(Job {
                scheme: MultibodyScheme::EnergyMomentum,
                friction: 0.0,
                factor: f,
                steps: None,
                penalty: None,
                size: 1.0,
            });
        }
    }
    if let Some(w) = &c.work_precision {
        for &scheme in &w.schemes {
            for &f in &w.factors {
                push(Job {
                    scheme,
                    friction: 0.0,
                    factor: f,
                    steps: None,
                    penalty: None,
                    size: 1.0,
                });
            }
        }
    }
    jobs
}

fn label(job: &Job) -> String {
    let mut s = format!("{} μ = {}", job.scheme.name(), job.friction);
    if let Some(e) = job.penalty {
        s.push_str(&format!(" penalty ε = {e:e}"));
    }
    if job.size != 1.0 {
        s.push_str(&format!(" size {}", job.size));
    }
    if job.factor != 1.0 {
        s.push_str(&format!(" ×{}", job.factor));
    }
    if let Some(n) = job.steps {
        s.push_str(&format!(" N = {n}"));
    }
    s
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c: ImpactCase = case.body().map_err(|e| e.to_string())?;
    c.check(case.path()).map_err(|e| e.to_string())?;
    let jobs = jobs(&c);
    let bar = ctx.progress_bar(jobs.len() as u64, &case.header.id);
    let outcomes: Vec<Result<Outcome, String>> = jobs
        .par_iter()
        .map(|j| {
            let o = run_job(&c, j);
            bar.inc(1);
            o
        })
        .collect();
    bar.finish_and_clear();
    let find = |j: &Job| -> &Result<Outcome, String> {
        let i = jobs.iter().position(|x| x == j).unwrap_or(0);
        &outcomes[i]
    };
    let objective = c.material.is_objective();
    // the runs
    let mut rows = Vec::new();
    let mut shown: Vec<(String, &Outcome)> = Vec::new();
    for r in &c.runs {
        let job = Job::of(r);
        let name = format!("{} ({})", r.name, label(&job));
        match find(&job) {
            Err(e) => report.gates.push(GateVerdict::from_checks(
                format!("run {}", r.name),
                "energy audit",
                vec![Check::holds(
                    &format!("{name}: {e}"),
                    false,
                    "the run completes",
                )],
                "",
            )),
            Ok(o) => {
                let s = &o.run.summary;
                let mut checks =
                    audit_checks(&r.name, s, Claims::of(r.scheme, [true, true], objective));
                checks.push(Check::holds(
                    &format!("{}: the rings separate before T (no contact in the last 10 % of the steps)", r.name),
                    o.quantities.separated,
                    "separated",
                ));
                if let Some(max) = r.max_other_energy_change {
                    let records = &o.run.solution.records;
                    let e0 = records.first().map_or(f64::NAN, |x| x.energy);
                    let mut switched = 0.0;
                    let mut other: f64 = 0.0;
                    for x in records {
                        switched += x.switch_work;
                        other = other.max((x.energy - e0 - switched).abs() / e0);
                    }
                    checks.push(Check::at_most(
                        &format!(
                            "{}: max_n |E_n − E_0 − Σ switch work| / E_0 (E = K + U + P: no activation loss; Σ switch work = {:.3e} E_0)",
                            r.name,
                            switched / e0
                        ),
                        other,
                        max,
                    ));
                }
                if let (Some(size), Some(reference), Some(tol)) =
                    (r.size, &r.similar_to, r.similarity_tolerance)
                {
                    checks.extend(similarity(&c, &r.name, size, reference, tol, o, &find));
                }
                if let Some(min) = r.min_energy_error {
                    checks.push(Check::at_least(
                        &format!(
                            "{}: max energy error in a step without a set change / E_0",
                            r.name
                        ),
                        s.unchanged_relative,
                        min,
                    ));
                    // the negative control of the audit: its own unchanged-set check must flag
                    // the scheme that does not conserve (a ratio above 1), or its tolerance is
                    // blind (e.g. not the round-off it claims)
                    checks.push(Check::at_least(
                        &format!(
                            "{}: the audit flags it (unchanged-set ratio > 1: drift over round-off)",
                            r.name
                        ),
                        s.unchanged_ratio,
                        1.0,
                    ));
                    checks.push(Check::at_least(
                        &format!(
                            "{}: the audit flags it (energy identity ratio > 1: the midpoint's internal force is not a discrete gradient)",
                            r.name
                        ),
                        s.identity_ratio,
                        1.0,
                    ));
                }
                report.gates.push(audit_gate(
                    &format!("run {}", r.name),
                    checks,
                    "ratios are drifts over their round-off + Newton tolerances (docs/multibody.md §8)",
                ));
                report.gates.push(state_audit_gate(
                    &format!("run {}: state-recomputed audit", r.name),
                    state_audit_checks(
                        &r.name,
                        &o.run.state,
                        Claims::of(r.scheme, [true, true], objective),
                    ),
                ));
                rows.push(run_row(&r.name, o));
                // the similar problem's curves are its size-1 run's, scaled (the gate says so)
                if r.size.is_none_or(|s| s == 1.0) {
                    shown.push((r.name.clone(), o));
                }
            }
        }
    }
    report.tables.push(Table {
        title: "Runs at resolution 1: conservation (ratios ≤ 1: round-off) and what an experiment reports".into(),
        header: [
            "run", "scheme", "μ", "dofs", "steps", "energy change / E_0", "activation work / E_0",
            "switch work / E_0", "identity ratio", "unchanged ratio", "P ratio", "J ratio", "friction work / E_0",
            "rebound ring 0", "rebound ring 1", "contact duration", "Newton its/step (max)", "CPU (s)",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
    if let Some(a) = &c.audit_control {
        audit_control(a, &c, &find, report);
    }
    let audit_runs: Vec<AuditRun<'_>> = shown
        .iter()
        .map(|(n, o)| AuditRun {
            label: n.clone(),
            records: &o.run.solution.records,
        })
        .collect();
    plot_audits(ctx, report, "runs", "two rings", &audit_runs)?;
    let labelled: Vec<(&str, &Outcome)> = shown.iter().map(|(n, o)| (n.as_str(), *o)).collect();
    ctx.plot(
        report,
        "contact_force",
        &plots::contact_force_figure("two rings", &labelled),
    )?;
    ctx.panels(
        report,
        "velocities",
        "two rings: centre-of-mass velocities (ring 1 dashed)",
        &plots::velocity_figures("two rings", &labelled),
        2,
    )?;
    if let (true, Some((_, first))) = (c.snapshots, shown.first()) {
        let times: Vec<f64> = (0..=5).map(|i| c.final_time * i as f64 / 5.0).collect();
        let mut job = first.job;
        job.steps = Some(first.steps);
        let s = runs::solver(&c, &job)?;
        let params = contactlab::model::multibody::solver::MultibodyParams {
            snapshot_times: times,
            ..Default::default()
        };
        let s =
            contactlab::model::multibody::solver::MultibodySolver::new(s.problem().clone(), params)
                .map_err(|e| e.to_string())?;
        let sol = s.solve().map_err(|e| e.to_string())?;
        ctx.triangle_panels(
            report,
            "snapshots",
            &format!("{}: the rings at six times, coloured by |E|", shown[0].0),
            &plots::snapshot_plots(&s.problem().bodies, &sol.snapshots),
            3,
        )?;
    }
    if let Some(l) = &c.large_step {
        large_step(&c, l, &find, report);
    }
    let extrapolated = match &c.gci {
        Some(g) => gci(g, &find, report, ctx)?,
        None => None,
    };
    if let (Some(w), Some(reference)) = (&c.work_precision, extrapolated) {
        work_precision(&c, w, reference, &find, report, ctx)?;
    }
    Ok(())
}

/// The similarity gate: the run at size s against the run `reference` at size 1 — each ring's
/// rebound velocity / s, the contact duration and (E_N − E_0)/E_0, relative differences at most
/// `tol` (every equation of the problem is invariant under x → s x, v → s v, E → s² E,
/// ε → s² ε at fixed ρ and t; what differs is the rounding, and any tolerance or guard of the
/// solver with a length scale of its own).
fn similarity<'a>(
    c: &ImpactCase,
    name: &str,
    size: f64,
    reference: &str,
    tol: f64,
    o: &Outcome,
    find: &dyn Fn(&Job) -> &'a Result<Outcome, String>,
) -> Vec<Check> {
    let Some(spec) = c.runs.iter().find(|x| x.name == reference) else {
        return Vec::new();
    };
    let base = match find(&Job::of(spec)) {
        Ok(b) => b,
        Err(e) => {
            return vec![Check::holds(
                &format!("{name}: its size-1 run {reference} failed ({e})"),
                false,
                "completes",
            )]
        }
    };
    let (q, q1) = (&o.quantities, &base.quantities);
    let speed = q1
        .rebound
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let velocity = (0..2)
        .flat_map(|b| (0..2).map(move |i| (b, i)))
        .map(|(b, i)| (q.rebound[b][i] / size - q1.rebound[b][i]).abs() / speed)
        .fold(0.0f64, f64::max);
    let change = |r: &[contactlab::model::multibody::audit::MultibodyRecord]| {
        let e0 = r.first().map_or(f64::NAN, |x| x.energy);
        r.last().map_or(f64::NAN, |x| (x.energy - e0) / e0)
    };
    let energy = (change(&o.run.solution.records) - change(&base.run.solution.records)).abs();
    let duration = match (q.contact_duration, q1.contact_duration) {
        (Some(a), Some(b)) => (a - b).abs() / b,
        _ => f64::INFINITY,
    };
    vec![
        Check::at_most(
            &format!("{name} (size {size}) against {reference}: max |v_s/s − v_1| / max |v_1| (rebound velocities)"),
            velocity,
            tol,
        ),
        Check::at_most(
            &format!("{name} (size {size}) against {reference}: |ΔE/E_0 (size s) − ΔE/E_0 (size 1)|"),
            energy,
            tol,
        ),
        Check::at_most(
            &format!("{name} (size {size}) against {reference}: relative difference of the contact durations"),
            duration,
            tol,
        ),
    ]
}

fn fmt_v(v: [f64; 2]) -> String {
    format!("({:.5}, {:.5})", v[0], v[1])
}

fn run_row(name: &str, o: &Outcome) -> Vec<String> {
    let s = &o.run.summary;
    let r = &o.run.solution.records;
    let e0 = r.first().map_or(1.0, |x| x.energy);
    let e1 = r.last().map_or(e0, |x| x.energy);
    vec![
        name.to_string(),
        o.job.scheme.name().to_string(),
        format!("{}", o.job.friction),
        o.dofs.to_string(),
        o.steps.to_string(),
        format!("{:.3e}", (e1 - e0) / e0),
        format!("{:.3e}", s.activation_work / e0),
        format!("{:.3e}", r.iter().map(|x| x.switch_work).sum::<f64>() / e0),
        format!("{:.3}", s.identity_ratio),
        format!("{:.3}", s.unchanged_ratio),
        format!("{:.3}", s.momentum_ratio),
        format!("{:.3}", s.angular_ratio),
        format!("{:.3e}", s.friction_work / e0),
        fmt_v(o.quantities.rebound[0]),
        fmt_v(o.quantities.rebound[1]),
        o.quantities
            .contact_duration
            .map_or("—".into(), |d| format!("{d:.5}")),
        format!(
            "{:.2} ({})",
            o.run.solution.stats.newton_iterations as f64 / o.steps.max(1) as f64,
            o.run.solution.stats.max_newton_iterations
        ),
        format!("{:.2}", o.cpu_seconds),
    ]
}

/// The audit's injected-defect controls (`crate::multibody::audit_reference`) on one run.
fn audit_control<'a>(
    a: &format::AuditControlSpec,
    c: &ImpactCase,
    find: &dyn Fn(&Job) -> &'a Result<Outcome, String>,
    report: &mut CaseReport,
) {
    let Some(r) = c.runs.iter().find(|r| r.name == a.run) else {
        return;
    };
    let job = Job::of(r);
    let (checks, table) = match find(&job) {
        Err(e) => (
            vec![Check::holds(
                &format!("{}: {e}", r.name),
                false,
                "the run completes",
            )],
            None,
        ),
        Ok(o) => audit_controls(&r.name, &o.run.solution.records, summarize, a.defect),
    };
    report.gates.push(GateVerdict::from_checks(
        format!("the audit's controls on run {}", r.name),
        "negative control",
        checks,
        "the summary equals its definition written in the verification crate, and a defect of the given size in any audited quantity is flagged at that size (docs/multibody.md §8)",
    ));
    report.tables.extend(table);
}

fn large_step<'a>(
    c: &ImpactCase,
    l: &format::LargeStepSpec,
    find: &dyn Fn(&Job) -> &'a Result<Outcome, String>,
    report: &mut CaseReport,
) {
    let em = find(&Job {
        scheme: MultibodyScheme::EnergyMomentum,
        friction: 0.0,
        factor: 1.0,
        steps: Some(l.steps),
        penalty: None,
        size: 1.0,
    });
    let mp = find(&Job {
        scheme: MultibodyScheme::Midpoint,
        friction: 0.0,
        factor: 1.0,
        steps: Some(l.steps),
        penalty: None,
        size: 1.0,
    });
    let k = c.final_time / l.steps as f64;
    let mut checks = Vec::new();
    let mut rows = Vec::new();
    match em {
        Err(e) => checks.push(Check::holds(
            &format!("energy_momentum at N = {}: {e}", l.steps),
            false,
            "completes",
        )),
        Ok(o) => {
            let r = &o.run.solution.records;
            let e0 = r[0].energy;
            let closing: f64 = r.iter().map(|x| x.activation_work + x.switch_work).sum();
            let other = (r[r.len() - 1].energy - e0 - closing).abs() / e0;
            checks.push(Check::at_most(
                &format!(
                    "energy_momentum at k = {k}: |E_N − E_0 − Σ (activation + switch work)| / E_0"
                ),
                other,
                l.max_other_energy_change,
            ));
            rows.push(vec![
                "energy_momentum".into(),
                "completed".into(),
                format!("{:.3e}", (r[r.len() - 1].energy - e0) / e0),
                format!("{:.3e}", closing / e0),
                format!("{:.3e}", other),
            ]);
        }
    }
    match mp {
        Err(e) => {
            let typed = !e.contains("NaN") && !e.is_empty();
            checks.push(Check::holds(
                &format!("midpoint at k = {k} stops with a typed error: {e}"),
                typed,
                "a typed error (never NaN)",
            ));
            rows.push(vec![
                "midpoint".into(),
                e.clone(),
                "—".into(),
                "—".into(),
                "—".into(),
            ]);
        }
        Ok(o) => {
            let r = &o.run.solution.records;
            let e0 = r[0].energy;
            let err = (r[r.len() - 1].energy - e0).abs() / e0;
            checks.push(Check::at_least(
                &format!("midpoint at k = {k}: |E_N − E_0| / E_0"),
                err,
                l.min_midpoint_energy_error,
            ));
            rows.push(vec![
                "midpoint".into(),
                "completed".into(),
                format!("{:.3e}", err),
                "—".into(),
                "—".into(),
            ]);
        }
    }
    report.gates.push(GateVerdict::from_checks(
        format!("large step: N = {} over T (k = {k})", l.steps),
        "extreme",
        checks,
        "the energy–momentum scheme's energy changes only where constraints close; the midpoint rule's does not stay bounded",
    ));
    report.tables.push(Table {
        title: format!("Large step N = {} (k = {k})", l.steps),
        header: [
            "scheme",
            "outcome",
            "(E_N − E_0)/E_0",
            "activation + switch work / E_0",
            "other change / E_0",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
}

/// The reported quantities of the GCI study: each ring's rebound components and the contact
/// duration.
const QUANTITIES: [&str; 5] = [
    "ring 0 v_x",
    "ring 0 v_y",
    "ring 1 v_x",
    "ring 1 v_y",
    "contact duration",
];

fn quantity(o: &Outcome, q: usize) -> f64 {
    match q {
        0..=3 => o.quantities.rebound[q / 2][q % 2],
        _ => o.quantities.contact_duration.unwrap_or(f64::NAN),
    }
}

/// The GCI study; returns the extrapolated rebound of ring 0 (the work–precision reference).
fn gci<'a>(
    g: &format::GciSpec,
    find: &dyn Fn(&Job) -> &'a Result<Outcome, String>,
    report: &mut CaseReport,
    ctx: &RunContext,
) -> Result<Option<[f64; 2]>, String> {
    let outs: Vec<&Outcome> = g
        .factors
        .iter()
        .map(|&f| {
            find(&Job {
                scheme: MultibodyScheme::EnergyMomentum,
                friction: 0.0,
                factor: f,
                steps: None,
                penalty: None,
                size: 1.0,
            })
            .as_ref()
            .map_err(|e| format!("GCI level ×{f}: {e}"))
        })
        .collect::<Result<_, _>>()?;
    let ratio = g.factors[1] / g.factors[0];
    let mut results: Vec<(String, Option<GciResult>, Vec<f64>)> = Vec::new();
    let mut rows = Vec::new();
    for (q, name) in QUANTITIES.iter().enumerate() {
        let values: Vec<f64> = outs.iter().map(|o| quantity(o, q)).collect();
        let res = analyse(&values, ratio, g.formal_order).map_err(|e| e.to_string());
        let mut checks = Vec::new();
        match &res {
            Err(e) => checks.push(Check::holds(
                &format!("{name}: {e}"),
                false,
                "an analysable sequence",
            )),
            Ok(r) => {
                checks.push(Check::at_most(
                    &format!(
                        "{name}: GCI_fine (%), p = {}",
                        r.order.map_or("—".into(), |p| format!("{p:.3}"))
                    ),
                    r.gci_fine_percent.unwrap_or(f64::INFINITY),
                    g.max_percent,
                ));
                if let Some(tol) = g.asymptotic_tolerance {
                    checks.push(Check::within(
                        &format!("{name}: asymptotic ratio A"),
                        r.asymptotic_ratio.unwrap_or(f64::INFINITY),
                        1.0,
                        tol,
                    ));
                }
                rows.push(vec![
                    name.to_string(),
                    values
                        .iter()
                        .map(|v| format!("{v:.6}"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    format!("{:?}", r.convergence),
                    r.order.map_or("—".into(), |p| format!("{p:.3}")),
                    r.extrapolated.map_or("—".into(), |v| format!("{v:.6}")),
                    r.gci_fine_percent.map_or("—".into(), |v| format!("{v:.3}")),
                    r.asymptotic_ratio.map_or("—".into(), |v| format!("{v:.3}")),
                ]);
            }
        }
        report.gates.push(GateVerdict::from_checks(
            format!("GCI: {name}"),
            "gci",
            checks,
            &g.note,
        ));
        results.push((name.to_string(), res.ok(), values));
    }
    report.tables.push(Table {
        title: format!(
            "Self-convergence (energy–momentum, frictionless): mesh and step refined together by {ratio}, levels ×{:?}",
            g.factors
        ),
        header: ["quantity", "values (coarse → fine)", "convergence", "observed p", "extrapolated", "GCI_fine (%)", "A"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
        rows,
    });
    let figures: Vec<crate::plot::Figure> = results
        .iter()
        .map(|(name, r, values)| {
            let finest = g.factors[g.factors.len() - 1];
            let mut fig = crate::plot::Figure::new(format!("GCI: {name}"))
                .x_label("h / h_finest")
                .y_label(name.clone())
                .semilog_x()
                .series(crate::plot::Series::line_markers(
                    "levels",
                    g.factors.iter().zip(values).map(|(f, v)| (finest / f, *v)),
                ));
            if let Some(e) = r.as_ref().and_then(|r| r.extrapolated) {
                fig = fig.horizontal_line(e, "Richardson extrapolation");
            }
            fig
        })
        .collect();
    ctx.panels(
        report,
        "gci",
        "self-convergence of the reported quantities",
        &figures,
        3,
    )?;
    let ext = |i: usize| results[i].1.as_ref().and_then(|r| r.extrapolated);
    Ok(match (ext(0), ext(1)) {
        (Some(a), Some(b)) => Some([a, b]),
        _ => None,
    })
}

fn work_precision<'a>(
    c: &ImpactCase,
    w: &format::WorkPrecisionSpec,
    reference: [f64; 2],
    find: &dyn Fn(&Job) -> &'a Result<Outcome, String>,
    report: &mut CaseReport,
    ctx: &RunContext,
) -> Result<(), String> {
    let v0 = c.rings[0].velocity;
    let scale = (v0[0] * v0[0] + v0[1] * v0[1])
        .sqrt()
        .max(f64::MIN_POSITIVE);
    let mut points = Vec::new();
    let mut work_points = Vec::new();
    let mut rows = Vec::new();
    for &scheme in &w.schemes {
        for &f in &w.factors {
            let job = Job {
                scheme,
                friction: 0.0,
                factor: f,
                steps: None,
                penalty: None,
                size: 1.0,
            };
            match find(&job) {
                Ok(o) => {
                    let v = o.quantities.rebound[0];
                    let err = ((v[0] - reference[0]).powi(2) + (v[1] - reference[1]).powi(2))
                        .sqrt()
                        / scale;
                    points.push((scheme.name().to_string(), o.dof_steps(), o.cpu_seconds, err));
                    work_points.push(WorkPoint {
                        scheme: scheme.name().to_string(),
                        elements: o.dofs,
                        steps: o.steps,
                        error: err,
                        cpu_seconds: o.cpu_seconds,
                        dof_steps: o.dof_steps(),
                    });
                    rows.push(vec![
                        scheme.name().into(),
                        format!("{f}"),
                        o.dofs.to_string(),
                        o.steps.to_string(),
                        format!("{err:.3e}"),
                        format!("{:.3}", o.cpu_seconds),
                    ]);
                }
                Err(e) => rows.push(vec![
                    scheme.name().into(),
                    format!("{f}"),
                    "—".into(),
                    "—".into(),
                    e.clone(),
                    "—".into(),
                ]),
            }
        }
    }
    report.tables.push(Table {
        title: "Work–precision: ring 0's rebound error against the Richardson extrapolation of the GCI study".into(),
        header: ["scheme", "resolution", "dofs", "steps", "error / |v_0|", "CPU (s)"].iter().map(|s| s.to_string()).collect(),
        rows,
    });
    report.work_precision = Some(WorkPrecisionReport {
        error: "rebound velocity of ring 0 / |v_0|".into(),
        points: work_points,
    });
    ctx.panels(
        report,
        "work_precision",
        "work–precision of the three schemes",
        &plots::work_precision_figures(&points),
        2,
    )?;
    if let (Some(base), Some(cheap), Some(max)) = (w.baseline, w.cheaper, w.max_work_ratio) {
        let of = |s: MultibodyScheme| {
            points
                .iter()
                .filter(|p| p.0 == s.name())
                .collect::<Vec<_>>()
        };
        let (b, ch) = (of(base), of(cheap));
        let mut checks = Vec::new();
        match b.iter().min_by(|x, y| x.3.total_cmp(&y.3)) {
            None => checks.push(Check::holds(
                &format!("{} has no completed level", base.name()),
                false,
                "levels",
            )),
            Some(finest) => {
                let work = ch
                    .iter()
                    .filter(|p| p.3 <= finest.3)
                    .map(|p| p.1)
                    .fold(f64::INFINITY, f64::min);
                checks.push(Check::at_most(
                    &format!(
                        "dof-steps for {} to reach {}'s finest error {:.3e}, over {}'s",
                        cheap.name(),
                        base.name(),
                        finest.3,
                        base.name()
                    ),
                    work / finest.1,
                    max,
                ));
            }
        }
        report.gates.push(GateVerdict::from_checks(
            "work–precision".into(),
            "work_precision",
            checks,
            &w.note,
        ));
    }
    Ok(())
}
