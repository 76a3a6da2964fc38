//! Kind `plane_paths`: the two solver paths on a linear problem: the condensed path (factor A + θkB once, condense the
//! contact onto Γ3) and the full semismooth Newton path must give the same solution; their cost
//! differs — work–precision (error against CPU time) for both.

use std::time::Instant;

use contactlab::model::quasistatic::plane_solver::{PlaneStep, SolverPath};

use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::{at_least, positive, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use contactlab::fem::norms::l2_difference;

use crate::plane::errors::PlaneErrorObserver;
use crate::plane::study::{plane_solver, Discretization, ExactSpec};
use crate::plot::{Figure, Series};

/// The case body of `plane_paths`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PathsCase {
    pub exact: ExactSpec,
    #[serde(default)]
    pub discretization: Discretization,
    pub plane_paths: PlanePathsSpec,
}

/// `[plane_paths]`: the condensed and Newton paths on a linear problem, error against cost.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanePathsSpec {
    pub elements: Vec<usize>,
    pub steps: Vec<usize>,
    pub error: String,
    pub repeats: usize,
    /// The two paths' u_N may differ by round-off only: ‖Δu_N‖/‖u_N‖ at most this multiple of
    /// ε √(n N), n the solved dofs and N the steps (independent round-off of n unknowns over N
    /// steps).
    pub round_off_factor: f64,
}

impl PathsCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: Self = case.body()?;
        c.exact.check(case.path())?;
        let p = &c.plane_paths;
        at_least(case.path(), "plane_paths.elements", &p.elements, 1)?;
        at_least(case.path(), "plane_paths.steps", &p.steps, 1)?;
        positive(
            case.path(),
            "plane_paths.round_off_factor",
            p.round_off_factor,
        )?;
        Ok(c)
    }
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = PathsCase::parse(case).map_err(|e| e.to_string())?;
    let spec = &c.plane_paths;
    let exact = c.exact.manufactured()?;
    let scheme = c.discretization.scheme.unwrap_or_default();
    let integration = c.discretization.contact_integration.unwrap_or_default();
    let levels = spec.elements.len().max(spec.steps.len());
    let mut rows = Vec::new();
    let mut points: Vec<(SolverPath, f64, f64)> = Vec::new();
    let mut agreement = Vec::new();
    for i in 0..levels {
        let n = *spec.elements.get(i).unwrap_or(&spec.elements[0]);
        let steps = *spec.steps.get(i).unwrap_or(&spec.steps[0]);
        let problem = exact.problem(n, integration)?;
        let mut finals = Vec::new();
        let mut errors = Vec::new();
        let mut dofs = 0;
        for path in [SolverPath::Condensed, SolverPath::Newton] {
            let mut solver = plane_solver(&problem, steps, scheme, path)?;
            let mut obs = PlaneErrorObserver::new(
                &exact,
                problem.mesh.nodes(),
                problem.mesh.triangles(),
                steps,
            );
            let stats = solver.run(&mut obs).map_err(|e| e.to_string())?;
            dofs = stats.dofs;
            let error = obs
                .errors()
                .get(&spec.error)
                .copied()
                .ok_or("unknown error name")?;
            // timing without error evaluation (fresh solver: includes its factorizations)
            let mut best = f64::INFINITY;
            for _ in 0..spec.repeats.max(1) {
                let start = Instant::now();
                let mut s = plane_solver(&problem, steps, scheme, path)?;
                s.run(&mut |_: &PlaneStep<'_>| {})
                    .map_err(|e| e.to_string())?;
                best = best.min(start.elapsed().as_secs_f64());
            }
            rows.push(vec![
                format!("{path:?}").to_lowercase(),
                format!("{n}×{n}"),
                format!("{steps}"),
                format!("{error:.6e}"),
                format!("{best:.4}"),
                format!("{}", stats.factorizations),
                format!("{}", stats.newton_iterations),
            ]);
            points.push((path, best, error));
            finals.push(obs.final_u.clone());
            errors.push(error);
        }
        let diff = l2_difference(
            problem.mesh.nodes(),
            problem.mesh.triangles(),
            &finals[0],
            &finals[1],
        );
        let scale = l2_difference(
            problem.mesh.nodes(),
            problem.mesh.triangles(),
            &finals[0],
            &vec![0.0; finals[0].len()],
        );
        let limit = spec.round_off_factor * f64::EPSILON * ((dofs * steps) as f64).sqrt();
        agreement.push(Check::at_most(
            &format!(
                "{n}×{n} ({dofs} dofs), N = {steps}: ‖u_N(condensed) − u_N(Newton)‖ / ‖u_N‖ \
                 ({} ε √(n N); the errors {} differ by {:.1e} relative)",
                spec.round_off_factor,
                spec.error,
                ((errors[0] - errors[1]) / errors[0]).abs()
            ),
            diff / scale,
            limit,
        ));
    }
    report.gates.push(GateVerdict::from_checks(
        "condensed and Newton paths give the same answer on a linear problem".into(),
        "plane_paths",
        agreement,
        "both solve the same discrete equations; with a piecewise-linear law the semismooth Newton \
         iterate is exact once its active set is right, so they differ by round-off only",
    ));
    report.tables.push(Table {
        title: "the two paths: error, time (best of repeats, fresh solver including its factorizations), work".into(),
        header: ["path", "mesh", "N", &spec.error, "seconds", "sparse factorizations", "Newton iterations"].iter().map(|s| s.to_string()).collect(),
        rows,
    });
    let mut fig = Figure::new(format!(
        "{}: {} against CPU time, both paths",
        case.header.id, spec.error
    ))
    .x_label("seconds (solver, fresh)")
    .y_label(spec.error.clone())
    .log_log();
    for (i, path) in [SolverPath::Condensed, SolverPath::Newton]
        .iter()
        .enumerate()
    {
        let pts: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.0 == *path)
            .map(|p| (p.1, p.2))
            .collect();
        fig = fig.series(Series::line_markers(format!("{path:?}").to_lowercase(), pts).color(i));
    }
    ctx.plot(report, "work_precision_paths", &fig)?;
    Ok(())
}
