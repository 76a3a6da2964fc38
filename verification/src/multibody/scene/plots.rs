//! The plots of a multibody scene: the audit (`audit.svg`: the total energy, the drift of the
//! energy identity, the momentum drifts — [`crate::multibody::study::audit_figures`]), the contact
//! forces and the bodies' centre-of-mass velocities against t (`contact.svg`), and the deformed
//! bodies at the output times coloured by the strain-energy density W(F) (`snapshots.svg`).

use std::path::Path;

use contactlab::model::multibody::solver::{MultibodySnapshot, PairMaster};
use contactlab::scene::multibody::MultibodyScene;

use crate::multibody::scene::run::SceneRun;
use crate::multibody::study::{audit_figures, AuditRun};
use crate::plot::{
    write_panels_svg, write_triangle_panels_svg, Figure, Outline, Series, TriangleField,
    TriangleMeshPlot,
};

/// Writes the three plots into `out`.
pub fn write(
    scene: &MultibodyScene,
    title: &str,
    run: &SceneRun,
    out: &Path,
) -> Result<(), String> {
    let e = |e: crate::plot::PlotError| e.to_string();
    let audit = audit_figures(
        title,
        &[AuditRun {
            label: scene.problem.scheme.name().to_string(),
            records: &run.records,
        }],
    );
    write_panels_svg(&audit, 3, &out.join("audit.svg")).map_err(e)?;
    write_panels_svg(
        &contact_figures(scene, title, run),
        3,
        &out.join("contact.svg"),
    )
    .map_err(e)?;
    let mut states: Vec<&MultibodySnapshot> = crate::plot::plotted_snapshots(run.snapshots.len())
        .into_iter()
        .map(|i| &run.snapshots[i])
        .collect();
    if let Some(last) = &run.last {
        if states.last().is_none_or(|s| s.step != last.step) {
            states.push(last);
        }
    }
    let plots: Vec<TriangleMeshPlot> = states.iter().map(|s| deformed(scene, s)).collect();
    write_triangle_panels_svg(&plots, plots.len().min(3), &out.join("snapshots.svg")).map_err(e)
}

/// The contact forces per `[[contact_pair]]` section (the two-step mean of Σ λ_N solid, the raw
/// Σ λ_N as markers — it alternates from step to step at a persistent contact, docs/multibody.md
/// — and Σ λ_T dashed) and each body's centre-of-mass velocity (v_x solid, v_y dashed) against t.
fn contact_figures(scene: &MultibodyScene, title: &str, run: &SceneRun) -> Vec<Figure> {
    let mut forces = Figure::new(format!("{title}: contact forces"))
        .x_label("t")
        .y_label("two-step mean Σ λ_N (solid), raw Σ λ_N (markers), Σ λ_T (dashed)");
    for (p, c) in scene.file.contact_pair.iter().enumerate() {
        let master = c
            .master
            .as_ref()
            .map_or("foundation".to_string(), |m| m.body.clone());
        let label = format!("pair {p}: {} on {master}", c.slave.body);
        forces = forces
            .series(
                Series::line(
                    format!("{label}: two-step mean λ_N"),
                    run.history.iter().map(|h| (h.time, h.normal_force_mean[p])),
                )
                .color(p),
            )
            .series(
                Series::markers(
                    format!("{label}: raw λ_N"),
                    run.history.iter().map(|h| (h.time, h.normal_force[p])),
                )
                .color(p),
            );
        if c.friction > 0.0 {
            forces = forces.series(
                Series::line(
                    format!("{label}: λ_T"),
                    run.history.iter().map(|h| (h.time, h.friction_force[p])),
                )
                .color(p)
                .dashed(),
            );
        }
    }
    let mut velocities = Figure::new("centre-of-mass velocities")
        .x_label("t")
        .y_label("v_x (solid), v_y (dashed)");
    for (b, name) in scene.names.iter().enumerate() {
        for (c, axis) in ["x", "y"].iter().enumerate() {
            let s = Series::line(
                format!("{name}: v_{axis}"),
                run.history.iter().map(|h| (h.time, h.velocities[b][c])),
            )
            .color(b);
            velocities = velocities.series(if c == 1 { s.dashed() } else { s });
        }
    }
    let counts = Figure::new("active constraints and Newton iterations")
        .x_label("t")
        .y_label("count")
        .series(Series::line(
            "active",
            run.records.iter().map(|r| (r.time, r.active as f64)),
        ))
        .series(Series::markers(
            "Newton iterations",
            run.records
                .iter()
                .skip(1)
                .map(|r| (r.time, r.newton_iterations as f64)),
        ));
    vec![forces, velocities, counts]
}

/// The deformed bodies of a state as one mesh, coloured by W(F), with the foundations drawn.
fn deformed(scene: &MultibodyScene, s: &MultibodySnapshot) -> TriangleMeshPlot {
    let set = &scene.problem.bodies;
    let mut nodes = Vec::new();
    let mut triangles = Vec::new();
    let mut density = Vec::new();
    let mut outline = Vec::new();
    for b in 0..set.len() {
        let body = set.body(b);
        let mesh = &body.data().mesh;
        let u = &s.displacement[set.range(b)];
        let un = body.nodal(u);
        let base = nodes.len();
        nodes.extend(
            mesh.nodes()
                .iter()
                .enumerate()
                .map(|(i, x)| [x[0] + un[2 * i], x[1] + un[2 * i + 1]]),
        );
        triangles.extend(
            mesh.triangles()
                .iter()
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
        density.extend(
            (0..mesh.triangles().len())
                .map(|e| body.law_of(e).energy(&body.deformation_gradient(u, e))),
        );
        // the initial boundary: every edge a segment (a non-finite point breaks the line)
        outline.extend(mesh.boundary().iter().flat_map(|edge| {
            [
                mesh.nodes()[edge.nodes[0]],
                mesh.nodes()[edge.nodes[1]],
                [f64::NAN, f64::NAN],
            ]
        }));
    }
    let (xmin, xmax) = nodes
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x[0]), b.max(x[0]))
        });
    let mut plot = TriangleMeshPlot::new(format!("t = {:.4e}: W(F)", s.time), nodes, triangles)
        .field(TriangleField::per_triangle("W(F)", density))
        .outline(Outline::new("initial boundaries", outline).dashed());
    let mut levels: Vec<f64> = Vec::new();
    for p in &scene.problem.pairs {
        if let PairMaster::Foundation(f) = &p.master {
            if !levels.contains(&f.level) {
                levels.push(f.level);
            }
        }
    }
    for level in levels {
        let w = (xmax - xmin).max(f64::MIN_POSITIVE);
        plot = plot.outline(
            Outline::new(
                "foundation",
                [[xmin - 0.25 * w, level], [xmax + 0.25 * w, level]],
            )
            .color(5),
        );
    }
    plot
}
