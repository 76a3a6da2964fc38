//! The figures of an impact case: contact-force, penetration and centre-of-mass velocity
//! histories per run, deformed snapshots, and the self-convergence of the reported quantities.

use super::runs::RunOutput;
use crate::plot::{Figure, Outline, Series, TriangleField, TriangleMeshPlot};
use crate::stats::gci::GciResult;

/// A labelled run.
pub struct Labelled<'a> {
    pub label: &'a str,
    pub run: &'a RunOutput,
}

/// Total normal force Σ w N against time.
pub fn contact_force_figure(title: &str, runs: &[Labelled<'_>]) -> Figure {
    let mut fig = Figure::new(format!("{title}: total normal contact force Σ w N"))
        .x_label("t (s)")
        .y_label("Σ w N (N/m)");
    for (i, r) in runs.iter().enumerate() {
        fig = fig.series(
            Series::line(
                r.label,
                r.run.history.iter().map(|h| (h.time, h.normal_force)),
            )
            .color(i),
        );
    }
    fig
}

/// Largest penetration against time, with the layer depth g.
pub fn penetration_figure(title: &str, runs: &[Labelled<'_>], depth: Option<f64>) -> Figure {
    let mut fig = Figure::new(format!("{title}: largest penetration max_i p_i"))
        .x_label("t (s)")
        .y_label("max p (m)");
    for (i, r) in runs.iter().enumerate() {
        fig = fig.series(
            Series::line(
                r.label,
                r.run
                    .history
                    .iter()
                    .map(|h| (h.time, h.max_penetration.max(-2.0 * depth.unwrap_or(0.0)))),
            )
            .color(i),
        );
    }
    if let Some(g) = depth {
        fig = fig.horizontal_line(g, "g (layer depth)");
    }
    fig.horizontal_line(0.0, "")
}

/// Centre-of-mass velocity components against time.
pub fn velocity_figures(title: &str, runs: &[Labelled<'_>]) -> Vec<Figure> {
    ["x", "y"]
        .iter()
        .enumerate()
        .map(|(c, name)| {
            let mut fig = Figure::new(format!("{title}: centre-of-mass velocity v_{name}"))
                .x_label("t (s)")
                .y_label(format!("v_{name} (m/s)"));
            for (i, r) in runs.iter().enumerate() {
                fig = fig.series(
                    Series::line(
                        r.label,
                        r.run.history.iter().map(|h| (h.time, h.velocity[c])),
                    )
                    .color(i),
                );
            }
            fig
        })
        .collect()
}

/// Deformed snapshots of a run, coloured by the Green–Lagrange strain norm on one scale, with the
/// foundation line x2 = `level`.
pub fn snapshot_plots(run: &RunOutput, level: f64) -> Vec<TriangleMeshPlot> {
    let mesh = &run.body.data().mesh;
    let strains: Vec<Vec<f64>> = run
        .snapshots
        .iter()
        .map(|(_, u)| run.green_strains(u))
        .collect();
    let top = strains
        .iter()
        .flatten()
        .copied()
        .fold(0.0f64, f64::max)
        .max(1e-12);
    let (xmin, xmax) = mesh
        .nodes()
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p[0]), b.max(p[0]))
        });
    let drift = run
        .snapshots
        .iter()
        .map(|(_, u)| run.body.nodal(u))
        .flat_map(|u| u.chunks(2).map(|c| c[0]).collect::<Vec<_>>())
        .fold((0.0f64, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    let span = [xmin + drift.0 - 0.1, xmax + drift.1 + 0.1];
    run.snapshots
        .iter()
        .zip(strains)
        .map(|((t, u), s)| {
            TriangleMeshPlot::new(
                format!("t = {:.4} s", t),
                mesh.displaced(&run.body.nodal(u), 1.0),
                mesh.triangles().to_vec(),
            )
            .field(TriangleField::per_triangle("|E| (Green–Lagrange)", s).range(0.0, top))
            .outline(Outline::new("foundation", [[span[0], level], [span[1], level]]).dashed())
        })
        .collect()
}

/// One panel per quantity: the values against h/h_finest, with the Richardson extrapolation.
pub fn gci_figures(
    title: &str,
    factors: &[f64],
    results: &[(String, Option<GciResult>, Vec<f64>)],
) -> Vec<Figure> {
    let finest = factors.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    results
        .iter()
        .map(|(name, g, values)| {
            let mut fig = Figure::new(format!("{title}: {name}"))
                .x_label("h / h_finest")
                .y_label(name.clone())
                .semilog_x()
                .series(Series::line_markers(
                    "levels",
                    factors.iter().zip(values).map(|(f, v)| (finest / f, *v)),
                ));
            if let Some(e) = g.as_ref().and_then(|g| g.extrapolated) {
                fig = fig.horizontal_line(e, "Richardson extrapolation");
            }
            fig
        })
        .collect()
}
