//! Kind `rod_performance`: the whole time loop of the paper's rod at growing sizes and the cost per
//! dof-step across sizes (linear growth in M·N: a ratio of times, machine-independent). The
//! absolute budget lives in the criterion benchmark `benches/rod_time_loop.rs` (`verify benches`).

use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, PerformancePoint, PerformanceReport};
use crate::plot::{Figure, Series};
use crate::rod::study::{time_loop_seconds, Discretization, RodStudy};

/// The case body of `rod_performance`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerformanceCase {
    pub scene: toml::Table,
    pub performance: PerformanceSpec,
}

/// `[performance]`: the time loop at several sizes.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerformanceSpec {
    /// Sizes (M, N) timed.
    pub elements: Vec<usize>,
    pub steps: Vec<usize>,
    pub repeats: usize,
    /// Largest allowed spread of the per-dof-step cost across sizes (max/min): linear growth.
    pub max_cost_spread: f64,
}

impl PerformanceCase {
    /// Parses the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        case.body()
    }
}

/// Runs the performance case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = PerformanceCase::parse(case).map_err(|e| e.to_string())?;
    let spec = &c.performance;
    let study = RodStudy::new(Some(&c.scene), None, &Discretization::default())
        .map_err(|e| e.to_string())?;
    let mut points = Vec::new();
    for (i, &m) in spec.elements.iter().enumerate() {
        let n = *spec.steps.get(i).unwrap_or(&spec.steps[0]);
        let solver = study
            .solver(m, n, study.scheme)
            .map_err(|e| e.to_string())?;
        let best = time_loop_seconds(&solver, spec.repeats)?;
        let dof_steps = (m * n) as f64;
        points.push(PerformancePoint {
            elements: m,
            steps: n,
            dof_steps,
            seconds: best,
            ns_per_dof_step: best / dof_steps * 1e9,
        });
    }
    let costs: Vec<f64> = points.iter().map(|p| p.ns_per_dof_step).collect();
    let spread = costs.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        / costs.iter().cloned().fold(f64::INFINITY, f64::min);
    report.gates.push(GateVerdict::from_timing_checks(
        "performance: linear growth in M·N".into(),
        vec![Check::at_most(
            "spread of ns per dof-step across sizes (max/min)",
            spread,
            spec.max_cost_spread,
        )],
        "minimum over repeats; the absolute time is the criterion benchmark's (verify benches)",
    ));
    let fig = Figure::new(format!("{}: time loop against M·N", case.header.id))
        .x_label("dof-steps M·N")
        .y_label("seconds")
        .log_log()
        .series(Series::line_markers(
            "time loop",
            points.iter().map(|p| (p.dof_steps, p.seconds)),
        ))
        .reference_slope(1.0, "slope 1 (linear)");
    ctx.plot(report, "time_loop", &fig)?;
    report.performance = Some(PerformanceReport { points });
    Ok(())
}
