//! Performance: the whole time loop of the paper's rod at growing sizes, against the issue's
//! budget, and the cost per dof-step across sizes (linear growth in M·N).

use crate::case::CaseFile;
use crate::gate::{Check, GateVerdict};
use crate::plot::{Figure, Series};
use crate::report::case_report::{CaseReport, PerformancePoint, PerformanceReport};
use crate::rod_study::RodStudy;
use crate::run::RunContext;

/// Runs the performance case.
pub fn run(case: &CaseFile, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let spec = case.performance.as_ref().ok_or("missing [performance]")?;
    let study = RodStudy::from_case(case).map_err(|e| e.to_string())?;
    let mut points = Vec::new();
    for (i, &m) in spec.elements.iter().enumerate() {
        let n = *spec.steps.get(i).unwrap_or(&spec.steps[0]);
        let solver = study
            .solver(m, n, study.scheme)
            .map_err(|e| e.to_string())?;
        let best = crate::run::time_loop_seconds(&solver, spec.repeats)?;
        let dof_steps = (m * n) as f64;
        points.push(PerformancePoint {
            elements: m,
            steps: n,
            dof_steps,
            seconds: best,
            ns_per_dof_step: best / dof_steps * 1e9,
        });
    }
    let last = points.last().ok_or("no sizes")?;
    let costs: Vec<f64> = points.iter().map(|p| p.ns_per_dof_step).collect();
    let spread = costs.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        / costs.iter().cloned().fold(f64::INFINITY, f64::min);
    report.gates.push(GateVerdict::from_checks(
        "performance: time loop and linear growth".into(),
        "performance",
        vec![
            Check::at_most(
                &format!("time loop at M = {}, N = {} (s)", last.elements, last.steps),
                last.seconds,
                spec.budget_seconds,
            ),
            Check::at_most(
                "spread of ns per dof-step across sizes (max/min)",
                spread,
                spec.max_cost_spread,
            ),
        ],
        "minimum over repeats; the same figure is measured by the criterion benchmark",
    ));
    let fig = Figure::new(format!("{}: time loop against M·N", case.id))
        .x_label("dof-steps M·N")
        .y_label("seconds")
        .log_log()
        .series(Series::line_markers(
            "time loop",
            points.iter().map(|p| (p.dof_steps, p.seconds)),
        ))
        .reference_slope(1.0, "slope 1 (linear)");
    ctx.plot(report, "time_loop", &fig)?;
    report.performance = Some(PerformanceReport {
        points,
        budget_seconds: spec.budget_seconds,
    });
    Ok(())
}
