//! How the two 1D dynamic-contact case kinds (`dynamic_signorini_bar`, `dynamic_bar_wall`) run
//! and report, beyond the formats and measures of [`crate::dynamic::bar_common`]: one run's
//! outcome and its solver time, the contact impulse, the parallel run of a case's jobs, the gates
//! and tables of every case of the two kinds, and the plots they share (the audits of the shown
//! runs, histories against the exact ones, convergence).

use std::sync::Arc;
use std::time::Instant;

use rayon::prelude::*;

use contactlab::model::dynamic::audit::EnergyAudit;
use contactlab::model::dynamic::bar::BarBody;
use contactlab::model::dynamic::contact_model::{BarEnd, ContactModel};
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::{
    DynamicParams, DynamicProblem, DynamicSolution, DynamicSolver, StepView,
};

use crate::core::context::RunContext;
use crate::core::report::case_report::CaseReport;
use crate::dynamic::cases::bars::family::{BarSetup, FamilySpec};
use crate::dynamic::cases::bars::gates::{
    ceiling_gates, rate_gates, worst_summary, CeilingGate, RateGate,
};
use crate::dynamic::cases::bars::report::{
    convergence_figures, cost_and_audit_table, errors_table,
};
use crate::dynamic::cases::bars::sweep::{
    group_outcomes, Job, LevelOutcome, SweepOutcome, SweepSpec,
};
use crate::dynamic::study::{audit_gate, plot_audits, AuditRun};
use crate::plot::{Figure, Series};

/// One run's outcome (histories and audit only when recorded).
pub struct RunOutput<H> {
    pub level: LevelOutcome,
    pub history: Option<H>,
    pub audit: Option<EnergyAudit>,
}

impl<H> RunOutput<H> {
    /// The outcome of a run on (M, N) with mesh size h and step k: its measured errors, the audit
    /// summary and statistics of its solution, the solver's time without the observer's (s); the
    /// histories, and the audit when `record`.
    pub fn new(
        (elements, steps, h, k): (usize, usize, f64, f64),
        errors: &[(&str, f64)],
        solution: DynamicSolution,
        solver_seconds: f64,
        history: Option<H>,
        record: bool,
    ) -> Self {
        Self {
            level: LevelOutcome {
                elements,
                steps,
                h,
                k,
                errors: errors.iter().map(|(n, v)| (n.to_string(), *v)).collect(),
                summary: solution.audit.summary(),
                solver_seconds,
                stats: solution.stats.clone(),
            },
            history,
            audit: record.then_some(solution.audit),
        }
    }
}

/// One family's run of a bar whose left end meets a rigid wall: the body, the solver, and what
/// the observer of the run needs.
pub struct WallRun {
    /// The body (shared with the solver's problem).
    pub body: Arc<BarBody>,
    pub solver: DynamicSolver,
    /// The sign s of the contact node: the applied normal force is −s · (the generalized force on
    /// the normal dof) (`NodeForces::normal` is not it for the tilted HLT force: it holds
    /// λ_{n+1/2} without the correction).
    pub sign: f64,
    /// The element size h.
    pub h: f64,
    /// The time step k.
    pub k: f64,
    /// Whether the scheme is of midpoint type (see [`step_impulse`]).
    pub midpoint: bool,
}

impl WallRun {
    /// `family` on the bar `setup` with M equal elements and N steps up to T, `(M, N, T)` =
    /// `level`, the left end against a wall at x = `wall` (the family's treatment for the
    /// element size h = L/M), from the initial displacement and velocity (free dofs) that
    /// `initial` gives for the body.
    pub fn new(
        setup: &BarSetup,
        family: &FamilySpec,
        (elements, steps, final_time): (usize, usize, f64),
        wall: f64,
        initial: impl FnOnce(&BarBody) -> (Vec<f64>, Vec<f64>),
    ) -> Result<Self, String> {
        let body = setup.body(elements, family.mass, family.law)?;
        let h = setup.length / elements as f64;
        let k = final_time / steps as f64;
        let treatment = family.normal_treatment(h, setup.young);
        let contact = ContactModel::bar_wall(&body, BarEnd::Left, wall, treatment)
            .map_err(|e| e.to_string())?;
        let sign = contact.nodes[0].sign;
        let (initial_displacement, initial_velocity) = initial(&body);
        let body = Arc::new(body);
        let problem = DynamicProblem {
            body: body.clone(),
            contact: Some(contact),
            scheme: family.scheme,
            final_time,
            steps,
            initial_displacement,
            initial_velocity,
        };
        let params = DynamicParams {
            force_full_path: family.full_path,
            ..DynamicParams::default()
        };
        let solver = DynamicSolver::new(problem, params).map_err(|e| e.to_string())?;
        Ok(Self {
            body,
            solver,
            sign,
            h,
            k,
            midpoint: family.scheme.is_midpoint_type(),
        })
    }
}

/// Solves, calling `observe` at every step (and once at t = 0), and measures the time loop
/// without the observer's time: the solution and the solver's seconds. `label` names the run in
/// errors.
pub fn solve_timed(
    solver: &DynamicSolver,
    label: &str,
    mut observe: impl FnMut(&StepView<'_>),
) -> Result<(DynamicSolution, f64), String> {
    let mut observer_seconds = 0.0;
    let mut observer = |view: &StepView<'_>| {
        let start = Instant::now();
        observe(view);
        if view.step > 0 {
            // the initial call falls in the solver's setup, not in its loop
            observer_seconds += start.elapsed().as_secs_f64();
        }
    };
    let solution = solver
        .solve_with(&mut observer)
        .map_err(|e| format!("{label}: {e}"))?;
    let solver_seconds = (solution.stats.loop_seconds - observer_seconds).max(0.0);
    Ok((solution, solver_seconds))
}

/// The impulse of the contact force N_n over step n ≥ 1: k N_n for a midpoint-type scheme (the
/// force at t_n acts over the step), the trapezoidal k (N_{n−1} + N_n)/2 for Newmark.
pub fn step_impulse(midpoint: bool, k: f64, force: f64, previous_force: f64) -> f64 {
    if midpoint {
        k * force
    } else {
        0.5 * k * (force + previous_force)
    }
}

/// A shown run: its family, level, histories and audit.
pub struct ShownRun<H> {
    pub family: usize,
    pub level: LevelOutcome,
    pub history: H,
    pub audit: EnergyAudit,
}

/// Runs the jobs of a case in parallel (a progress bar labelled `id`) and collects them in job
/// order: the sweep runs grouped by (sweep, family) and the shown runs. The first failed run (in
/// job order) is the error.
pub fn run_jobs<H: Send>(
    ctx: &RunContext,
    id: &str,
    jobs: &[Job],
    sweeps: &[SweepSpec],
    families: &[FamilySpec],
    run: impl Fn(&Job) -> Result<RunOutput<H>, String> + Send + Sync,
) -> Result<(Vec<SweepOutcome>, Vec<ShownRun<H>>), String> {
    let bar = ctx.progress_bar(jobs.len() as u64, id);
    let results: Vec<Result<RunOutput<H>, String>> = jobs
        .par_iter()
        .map(|j| {
            let r = run(j);
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    let mut levels = Vec::with_capacity(results.len());
    let mut shown = Vec::new();
    for (job, result) in jobs.iter().zip(results) {
        let out = result?;
        if let (None, Some(history), Some(audit)) = (job.sweep, out.history, out.audit) {
            shown.push(ShownRun {
                family: job.family,
                level: out.level.clone(),
                history,
                audit,
            });
        }
        levels.push(out.level);
    }
    Ok((group_outcomes(jobs, levels, sweeps, families), shown))
}

/// The gates of a case — its rate gates and ceilings, and the audit gate of each family over
/// every run of every sweep — and the tables of every run's measured `errors` (titled `title`)
/// and of each family's cost and worst audit.
pub fn report_runs(
    report: &mut CaseReport,
    title: &str,
    errors: &[&str],
    families: &[FamilySpec],
    gates: &[RateGate],
    ceilings: &[CeilingGate],
    outcomes: &[SweepOutcome],
) {
    let mut verdicts = rate_gates(gates, outcomes);
    verdicts.extend(ceiling_gates(ceilings, outcomes));
    for f in families {
        if let Some(w) = worst_summary(outcomes, &f.name) {
            // a family with nothing to claim of its record audit has no gate (module docs of
            // `crate::dynamic::study`)
            let checks = f.audit_checks(&w);
            if !checks.is_empty() {
                verdicts.push(audit_gate(
                    &format!("energy audit: {}", f.name),
                    checks,
                    &f.audit_note(),
                ));
            }
        }
    }
    report.gates = verdicts;
    report.tables.push(errors_table(title, errors, outcomes));
    report.tables.push(cost_and_audit_table(families, outcomes));
}

/// The audits of the shown runs, midpoint-type and Newmark runs apart (Newmark's energy leaves
/// the scale), against the exact energy; `level` describes the shown level in the titles.
pub fn plot_shown_audits<H>(
    ctx: &RunContext,
    report: &mut CaseReport,
    id: &str,
    level: &str,
    families: &[FamilySpec],
    shown: &[ShownRun<H>],
    energy: f64,
) -> Result<(), String> {
    for (group, newmark) in [("midpoint", false), ("newmark", true)] {
        let runs: Vec<AuditRun<'_>> = shown
            .iter()
            .filter(|o| (families[o.family].scheme == DynamicScheme::Newmark) == newmark)
            .map(|o| AuditRun {
                label: families[o.family].name.clone(),
                audit: &o.audit,
            })
            .collect();
        if !runs.is_empty() {
            plot_audits(
                ctx,
                report,
                &format!("audit_{group}"),
                &format!("{id} ({level}), {group} runs"),
                &runs,
                Some(energy),
            )?;
        }
    }
    Ok(())
}

/// One panel of a shown run: its history against t, with the exact one (dashed).
pub fn history_panel(name: &str, y: &str, time: &[f64], values: &[f64], exact: Series) -> Figure {
    Figure::new(name)
        .x_label("t")
        .y_label(y)
        .series(Series::from_xy("computed", time, values).color(1))
        .series(exact)
}

/// An exact history t ↦ f(t) on `samples` equal steps of [0, T], for [`history_panel`].
pub fn exact_history(
    name: &str,
    final_time: f64,
    samples: usize,
    f: &dyn Fn(f64) -> f64,
) -> Series {
    let fine = (0..=samples).map(|i| final_time * i as f64 / samples as f64);
    Series::line(name, fine.map(|t| (t, f(t))))
        .color(0)
        .dashed()
}

/// The convergence figures of the sweeps ([`convergence_figures`]).
pub fn plot_convergence(
    ctx: &RunContext,
    report: &mut CaseReport,
    id: &str,
    sweeps: &[SweepSpec],
    gates: &[RateGate],
    outcomes: &[SweepOutcome],
) -> Result<(), String> {
    for (name, fig) in convergence_figures(id, sweeps, gates, outcomes) {
        ctx.plot(report, &name, &fig)?;
    }
    Ok(())
}
