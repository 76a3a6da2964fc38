//! Work–precision: error against cost for every scheme — where users see the trade of speed for
//! accuracy. CPU seconds are measured (minimum over repeats, solver only); the gate uses dof-steps
//! M·N, which are deterministic.

use serde::Deserialize;

use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, WorkPoint, WorkPrecisionReport};
use crate::plot::{Figure, Series};
use crate::rod::study::{time_loop_seconds, Discretization, ExactSpec, RodStudy};

/// The case body of `rod_work_precision`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkPrecisionCase {
    pub scene: toml::Table,
    pub exact: ExactSpec,
    pub work_precision: WorkPrecisionSpec,
}

/// `[work_precision]`: error against cost for every scheme.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkPrecisionSpec {
    pub error: String,
    /// Levels (M, N) along which every scheme is run.
    pub elements: Vec<usize>,
    pub steps: Vec<usize>,
    pub schemes: Vec<TimeScheme>,
    /// Timing repeats per run (the minimum is reported).
    pub repeats: usize,
    /// Gate: the `cheaper` scheme reaches the finest error of `baseline` with at most this
    /// fraction of its work (counted in dof-steps, which is deterministic).
    pub baseline: TimeScheme,
    pub cheaper: TimeScheme,
    pub max_work_ratio: f64,
}

impl WorkPrecisionCase {
    /// Parses the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        case.body()
    }
}

/// Runs the work–precision study.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = WorkPrecisionCase::parse(case).map_err(|e| e.to_string())?;
    let spec = &c.work_precision;
    let study = RodStudy::new(Some(&c.scene), Some(&c.exact), &Discretization::default())
        .map_err(|e| e.to_string())?;
    let id = &case.header.id;
    let n_levels = spec.elements.len().max(spec.steps.len());
    let level = |i: usize| {
        (
            *spec.elements.get(i).unwrap_or(&spec.elements[0]),
            *spec.steps.get(i).unwrap_or(&spec.steps[0]),
        )
    };
    let bar = ctx.progress_bar((n_levels * spec.schemes.len()) as u64, id);
    let mut points = Vec::new();
    // Sequential on purpose: timings of concurrent runs would measure contention.
    for &scheme in &spec.schemes {
        for i in 0..n_levels {
            let (m, n) = level(i);
            let errors = study
                .run_at(m, n, scheme)
                .map_err(|e| format!("work–precision ({scheme}, M = {m}, N = {n}): {e}"))?;
            let error =
                errors.errors.get(&spec.error).copied().ok_or_else(|| {
                    format!("work–precision: error `{}` is not measured", spec.error)
                })?;
            let solver = study.solver(m, n, scheme).map_err(|e| e.to_string())?;
            let best = time_loop_seconds(&solver, spec.repeats)?;
            points.push(WorkPoint {
                scheme: scheme.to_string(),
                elements: m,
                steps: n,
                error,
                cpu_seconds: best,
                dof_steps: (m * n) as f64,
            });
            bar.inc(1);
        }
    }
    bar.finish_and_clear();

    // Gate: the cheaper scheme reaches the baseline's finest error with ≤ max_work_ratio of its work.
    let finest_base = points
        .iter()
        .filter(|p| p.scheme == spec.baseline.name())
        .min_by(|a, b| a.error.total_cmp(&b.error))
        .ok_or("work–precision: no baseline runs")?
        .clone();
    let cheapest = points
        .iter()
        .filter(|p| p.scheme == spec.cheaper.name() && p.error <= finest_base.error)
        .min_by(|a, b| a.dof_steps.total_cmp(&b.dof_steps));
    let checks = match cheapest {
        Some(c) => vec![Check::at_most(
            &format!(
                "{} work (M·N) to reach the finest {} error {:.3e}, as a fraction of {}'s",
                spec.cheaper, spec.baseline, finest_base.error, spec.baseline
            ),
            c.dof_steps / finest_base.dof_steps,
            spec.max_work_ratio,
        )],
        None => vec![Check::holds(
            &format!(
                "{} reaches the finest {} error",
                spec.cheaper, spec.baseline
            ),
            false,
            "some level at or below it",
        )],
    };
    report.gates.push(GateVerdict::from_checks(
        format!("work–precision: {} against {}", spec.cheaper, spec.baseline),
        "work_precision",
        checks,
        "work counted in dof-steps (deterministic); CPU seconds are reported",
    ));

    let mut fig = Figure::new(format!("{id}: {} against CPU time", spec.error))
        .x_label("CPU seconds (solver time loop)")
        .y_label(spec.error.clone())
        .log_log();
    let mut fig_work = Figure::new(format!("{id}: {} against work M·N", spec.error))
        .x_label("dof-steps M·N")
        .y_label(spec.error.clone())
        .log_log();
    for (i, &scheme) in spec.schemes.iter().enumerate() {
        let pts: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.scheme == scheme.name())
            .map(|p| (p.cpu_seconds, p.error))
            .collect();
        let work: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.scheme == scheme.name())
            .map(|p| (p.dof_steps, p.error))
            .collect();
        fig = fig.series(Series::line_markers(scheme.name(), pts).color(i));
        fig_work = fig_work.series(Series::line_markers(scheme.name(), work).color(i));
    }
    ctx.plot(report, "work_precision_cpu", &fig)?;
    ctx.plot(report, "work_precision_dof_steps", &fig_work)?;
    report.work_precision = Some(WorkPrecisionReport {
        error: spec.error.clone(),
        points,
    });
    Ok(())
}
