//! `verify scene` for plane scenes (`model = "plane"`): runs the scene and writes `solution.json`
//! (nodes, triangles, snapshots with u, w, stress and von Mises per triangle, the contact force
//! history, solver statistics), a deformed-mesh plot with the von Mises field at the last snapshot,
//! and the contact force history.

use std::path::Path;

use contactlab::scene::plane::PlaneScene;

use crate::plot::{
    write_svg, write_triangle_svg, Figure, Outline, Series, TriangleField, TriangleMeshPlot,
};

/// Runs a plane scene from its text; returns a summary.
pub fn run_plane_scene(text: &str, source: &str, out: &Path) -> Result<String, String> {
    let scene = PlaneScene::from_toml_str(text, source).map_err(|e| format!("{source}: {e}"))?;
    let mut solver = scene.solver().map_err(|e| format!("{source}: {e}"))?;
    // The explicit step bound of a linear scene (dense eigenproblem; small and medium meshes).
    let bound = if scene.scheme == contactlab::model::quasistatic::scheme::TimeScheme::Explicit
        && scene.problem.is_linear()
    {
        contactlab::model::quasistatic::plane_stability::explicit_stability_eigenvalue(&solver)
            .ok()
            .map(|l| 2.0 / l)
    } else {
        None
    };
    let sol = solver.solve(&scene.output).map_err(|e| match bound {
        Some(kmax) if scene.grid.k_max() >= kmax => format!(
            "{source}: {e} (the explicit step bound 2/λ_max(A⁻¹B) of this scene is {kmax:.6}, k = {})",
            scene.grid.k_max()
        ),
        _ => format!("{source}: {e}"),
    })?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let path = out.join("solution.json");
    std::fs::write(
        &path,
        serde_json::to_string_pretty(&sol).map_err(|e| e.to_string())?,
    )
    .map_err(|e| format!("{}: {e}", path.display()))?;
    let title = if scene.title.is_empty() {
        source.to_string()
    } else {
        scene.title.clone()
    };
    if let Some(snap) = sol.snapshots.last() {
        let deformed = sol.deformed(snap);
        let boundary: Vec<[f64; 2]> = scene
            .problem
            .mesh
            .boundary()
            .iter()
            .map(|e| sol.nodes[e.nodes[0]])
            .collect();
        let plot = TriangleMeshPlot::new(
            format!("{title}: von Mises at t = {}", snap.t),
            deformed,
            sol.triangles.clone(),
        )
        .field(TriangleField::per_triangle(
            "|σ|",
            snap.von_mises.iter().copied(),
        ))
        .outline(Outline::new("initial boundary", boundary).closed().dashed());
        write_triangle_svg(&plot, &out.join("von_mises.svg")).map_err(|e| e.to_string())?;
    }
    let fig = Figure::new(format!("{title}: contact force"))
        .x_label("t")
        .y_label("Σ W p_ν")
        .series(Series::line(
            "resultant normal contact force",
            sol.times
                .iter()
                .copied()
                .zip(sol.contact_force.iter().copied()),
        ));
    write_svg(&fig, &out.join("contact_force.svg")).map_err(|e| e.to_string())?;
    let vm_max = sol
        .snapshots
        .last()
        .map(|s| {
            s.von_mises
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .unwrap_or(f64::NAN);
    let bound_text = match bound {
        Some(kmax) => format!(
            "; explicit step bound 2/λ_max(A⁻¹B) = {kmax:.6} (k = {})",
            scene.grid.k_max()
        ),
        None => String::new(),
    };
    Ok(format!(
        "{source}: {} path, {} dofs, {} steps ({} skipped for lack of equilibrium), {} sparse factorizations, {} Newton iterations; von Mises max at the last snapshot {vm_max:.4}{bound_text}",
        sol.stats.path,
        sol.stats.dofs,
        sol.stats.steps,
        sol.stats.skipped_steps.len(),
        sol.stats.factorizations,
        sol.stats.newton_iterations
    ))
}
