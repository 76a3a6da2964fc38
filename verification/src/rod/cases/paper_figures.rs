//! The paper's solution figures for one run (Fernández & Sofonea 2004, Figs 2–4 for p0 = 6 and
//! Figs 6–8 for p0 = 2): displacement snapshots and their errors, node histories and their errors,
//! the contact stress at x = L and its error.

use serde::Deserialize;

use contactlab::model::quasistatic::rod_output::RodOutputRequest;
use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::context::RunContext;
use crate::core::report::case_report::CaseReport;
use crate::plot::{Figure, Series};
use crate::rod::study::RodStudy;

/// `[figures]`: the paper's figures (snapshots, node histories, contact stress) for one run.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FiguresSpec {
    pub elements: usize,
    pub steps: usize,
    #[serde(default)]
    pub scheme: TimeScheme,
    pub snapshot_times: Vec<f64>,
    pub probes: Vec<f64>,
    /// Label of the paper figures reproduced, e.g. "Figs 2–4".
    #[serde(default)]
    pub paper_figures: String,
}

/// Runs the figure's discretization and draws the three two-panel figures.
pub fn draw(
    spec: &FiguresSpec,
    study: &RodStudy,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let solver = study
        .solver(spec.elements, spec.steps, spec.scheme)
        .map_err(|e| format!("figures: {e}"))?;
    let request = RodOutputRequest {
        snapshot_times: spec.snapshot_times.clone(),
        probes: spec.probes.clone(),
    };
    let sol = solver
        .solve(&request)
        .map_err(|e| format!("figures: {e}"))?;
    let exact = study.exact.as_deref();
    let (a, b) = (study.problem.viscosity, study.problem.elasticity);
    let label = |what: &str| {
        format!(
            "{what} (M = {}, N = {}, {}){}",
            spec.elements,
            spec.steps,
            spec.scheme,
            if spec.paper_figures.is_empty() {
                String::new()
            } else {
                format!(" — cf. {}", spec.paper_figures)
            }
        )
    };

    // Snapshots u_h(x, t) and u_h − u.
    let mut field = Figure::new(label("displacement u_h(x, t)"))
        .x_label("x (m)")
        .y_label("u (m)");
    let mut error = Figure::new("error u_h − u at the same times")
        .x_label("x (m)")
        .y_label("u_h − u (m)");
    for (i, s) in sol.snapshots.iter().enumerate() {
        let pts: Vec<(f64, f64)> = sol.nodes.iter().copied().zip(s.u.iter().copied()).collect();
        field = field.series(Series::line(format!("t = {}", s.t), pts).color(i));
        if let Some(ex) = exact {
            let errs: Vec<(f64, f64)> = sol
                .nodes
                .iter()
                .zip(&s.u)
                .map(|(&x, &u)| (x, u - ex.jet(x, s.t).u))
                .collect();
            error = error.series(Series::line(format!("t = {}", s.t), errs).color(i));
        }
    }
    let mut panels = vec![field];
    if exact.is_some() {
        panels.push(error);
    }
    ctx.panels(
        report,
        "snapshots",
        &label("displacement snapshots and errors"),
        &panels,
        2,
    )?;

    // Node histories.
    let mut hist = Figure::new(label("node histories u_h(x, t)"))
        .x_label("t (s)")
        .y_label("u (m)");
    let mut herr = Figure::new("error of the node histories")
        .x_label("t (s)")
        .y_label("u_h − u (m)");
    for (i, p) in sol.probes.iter().enumerate() {
        let pts: Vec<(f64, f64)> = sol
            .times
            .iter()
            .copied()
            .zip(p.displacement.iter().copied())
            .collect();
        hist = hist.series(Series::line(format!("x = {}", p.x), pts).color(i));
        if let Some(ex) = exact {
            let exact_pts: Vec<(f64, f64)> =
                sol.times.iter().map(|&t| (t, ex.jet(p.x, t).u)).collect();
            hist = hist.series(
                Series::line(format!("exact x = {}", p.x), exact_pts)
                    .dashed()
                    .color(i),
            );
            let errs: Vec<(f64, f64)> = sol
                .times
                .iter()
                .zip(&p.displacement)
                .map(|(&t, &u)| (t, u - ex.jet(p.x, t).u))
                .collect();
            herr = herr.series(Series::line(format!("x = {}", p.x), errs).color(i));
        }
    }
    let mut panels = vec![hist];
    if exact.is_some() {
        panels.push(herr);
    }
    ctx.panels(
        report,
        "node_histories",
        &label("node histories and errors"),
        &panels,
        2,
    )?;

    // Contact stress σ(L, t).
    let l = study.problem.length;
    let pts: Vec<(f64, f64)> = sol
        .times
        .iter()
        .copied()
        .zip(sol.contact_stress.iter().copied())
        .collect();
    let mut stress = Figure::new(label("contact stress σ_h(L, t) = −p_ν(w_n(L))"))
        .x_label("t (s)")
        .y_label("σ (N)")
        .series(Series::line_markers("discrete", pts));
    let mut serr = Figure::new("error of the contact stress")
        .x_label("t (s)")
        .y_label("σ_h − σ (N)");
    if let Some(ex) = exact {
        let exact_pts: Vec<(f64, f64)> = sol
            .times
            .iter()
            .map(|&t| {
                let j = ex.jet(l, t);
                (t, a * j.u_xt + b * j.u_x)
            })
            .collect();
        stress = stress.series(Series::line("exact", exact_pts).dashed());
        let errs: Vec<(f64, f64)> = sol
            .times
            .iter()
            .zip(&sol.contact_stress)
            .map(|(&t, &s)| {
                let j = ex.jet(l, t);
                (t, s - (a * j.u_xt + b * j.u_x))
            })
            .collect();
        serr = serr.series(Series::line_markers("σ_h − σ", errs));
    }
    let mut panels = vec![stress];
    if exact.is_some() {
        panels.push(serr);
    }
    ctx.panels(
        report,
        "contact_stress",
        &label("contact stress at x = L and its error"),
        &panels,
        2,
    )?;
    Ok(())
}
