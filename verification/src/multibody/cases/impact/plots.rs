//! The figures of the two-ring impact: deformed snapshots of both rings coloured by the strain,
//! the contact force and the rings' centre velocities against time, and the work–precision
//! diagram.

use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::solver::MultibodySnapshot;

use crate::multibody::cases::impact::runs::Outcome;
use crate::plot::{Figure, Series, TriangleField, TriangleMeshPlot};

/// The Green–Lagrange strain norm |E| = |½ (FᵀF − I)| of every triangle of body `b`.
fn green_strains(bodies: &BodySet, b: usize, u: &[f64]) -> Vec<f64> {
    let body = bodies.body(b);
    let ub = &u[bodies.range(b)];
    (0..body.elements().len())
        .map(|e| {
            let f = body.deformation_gradient(ub, e);
            let g = 0.5 * (f.transpose() * f - nalgebra::Matrix2::identity());
            g.norm()
        })
        .collect()
}

/// Both rings at each snapshot on one colour scale.
pub fn snapshot_plots(bodies: &BodySet, snapshots: &[MultibodySnapshot]) -> Vec<TriangleMeshPlot> {
    let strains: Vec<Vec<f64>> = snapshots
        .iter()
        .map(|s| {
            (0..bodies.len())
                .flat_map(|b| green_strains(bodies, b, &s.displacement))
                .collect()
        })
        .collect();
    let top = strains
        .iter()
        .flatten()
        .copied()
        .fold(0.0f64, f64::max)
        .max(1e-12);
    snapshots
        .iter()
        .zip(strains)
        .map(|(s, e)| {
            let mut nodes = Vec::new();
            let mut triangles = Vec::new();
            for b in 0..bodies.len() {
                let body = bodies.body(b);
                let mesh = &body.data().mesh;
                let offset = nodes.len();
                let u = body.nodal(&s.displacement[bodies.range(b)]);
                nodes.extend(mesh.displaced(&u, 1.0));
                triangles.extend(
                    mesh.triangles()
                        .iter()
                        .map(|t| [t[0] + offset, t[1] + offset, t[2] + offset]),
                );
            }
            TriangleMeshPlot::new(format!("t = {:.3}", s.time), nodes, triangles)
                .field(TriangleField::per_triangle("|E| (Green–Lagrange)", e).range(0.0, top))
        })
        .collect()
}

/// Σ λ_N against time for each labelled run.
pub fn contact_force_figure(title: &str, runs: &[(&str, &Outcome)]) -> Figure {
    let mut fig = Figure::new(format!(
        "{title}: total normal contact force Σ λ_N (two-step mean)"
    ))
    .x_label("t")
    .y_label("Σ λ_N, two-step mean");
    for (i, (label, o)) in runs.iter().enumerate() {
        fig = fig.series(
            Series::line(
                *label,
                o.run.history.iter().map(|h| (h.time, h.normal_force_mean)),
            )
            .color(i),
        );
    }
    fig
}

/// Each ring's centre-of-mass velocity (x and y panels).
pub fn velocity_figures(title: &str, runs: &[(&str, &Outcome)]) -> Vec<Figure> {
    ["x", "y"]
        .iter()
        .enumerate()
        .map(|(c, name)| {
            let mut fig = Figure::new(format!("{title}: centre-of-mass velocity v_{name}"))
                .x_label("t")
                .y_label(format!("v_{name}"));
            for (i, (label, o)) in runs.iter().enumerate() {
                for ring in 0..2 {
                    let series = Series::line(
                        format!("{label}: ring {ring}"),
                        o.run
                            .history
                            .iter()
                            .map(|h| (h.time, h.velocities[ring][c])),
                    )
                    .color(i);
                    fig = fig.series(if ring == 1 { series.dashed() } else { series });
                }
            }
            fig
        })
        .collect()
}

/// Error of ring 0's rebound against work (dof-steps and CPU seconds), per scheme.
pub fn work_precision_figures(points: &[(String, f64, f64, f64)]) -> Vec<Figure> {
    let mut schemes: Vec<&str> = points.iter().map(|p| p.0.as_str()).collect();
    schemes.dedup();
    let make = |x_label: &str, pick: fn(&(String, f64, f64, f64)) -> f64| {
        let mut fig = Figure::new(format!("work–precision: rebound error against {x_label}"))
            .x_label(x_label)
            .y_label("|v_rebound − v_ref| / |v_0|")
            .log_log();
        for (i, s) in schemes.iter().enumerate() {
            fig = fig.series(
                Series::line_markers(
                    *s,
                    points
                        .iter()
                        .filter(|p| p.0 == *s)
                        .map(|p| (pick(p), p.3.max(1e-16))),
                )
                .color(i),
            );
        }
        fig
    };
    vec![make("dofs × steps", |p| p.1), make("CPU seconds", |p| p.2)]
}
