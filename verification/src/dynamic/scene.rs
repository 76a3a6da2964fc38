//! `verify scene` for dynamic scenes (`model = "dynamic"`, the format of
//! [`contactlab::scene::dynamic`]): runs the scene and writes
//!
//! - `energy_audit.json` — **always**, also when the run stops with an error: every step's
//!   [`AuditRecord`] (energies E_n = ½ vᵀMv + 𝒲(u_n), penalty energy Φ_n, cumulative works, the
//!   residuals of BDS Prop. 1.1 (1.48), Prop. 1.3 (1.49) and HLT Prop. 3.7, contact force,
//!   largest penetration, Newton iterations), the [`AuditSummary`] of the steps computed, the
//!   status and, on failure, the typed error with its data (step, time, iterations, residual);
//! - `solution.json` — the mesh (nodes, triangles for a plane body), the final displacement and
//!   velocity (free dofs and nodal values), the snapshots at `[output] times`, and the solver
//!   statistics (path, Newton iterations, factorizations, backtracks, setup and loop time, factor
//!   nonzeros); on failure the last completed state;
//! - plots: `energy.svg` (E_n + Φ_n against t) and `identities.svg` (the three identity residuals
//!   per step, |r_n|/E_ref on a log axis, with the round-off gate of the suite), `contact.svg`
//!   (normal and friction force resultants, largest penetration, Newton iterations per step),
//!   and the snapshots (`snapshots.svg`: the deformed plane body coloured by the strain-energy
//!   density W(F) with the foundation and the initial boundary; u(x) for a bar).
//!
//! - with `[output] vtk = true`: the ParaView series `solution.pvd` and one `solution_<i>.vtu` per
//!   snapshot reached ([`crate::dynamic::vtk`]).
//!
//! The summary paragraph gives the energies, the largest penetration and contact force, the
//! largest identity residuals and the Newton statistics.

use std::path::Path;

use serde::Serialize;
use serde_json::json;

use contactlab::error::{Error as LabError, SolveError};
use contactlab::model::dynamic::audit::{AuditRecord, AuditSummary};
use contactlab::model::dynamic::solver::{DynamicSolver, DynamicStats};
use contactlab::scene::dynamic::{DynamicScene, DynamicSceneFile, SceneBody};

use contactlab::model::dynamic::record::{run_recorded, RecordedRun};

use crate::dynamic::study::{energy_figure, residual_figures, AuditRun};
use crate::plot::{
    write_panels_svg, write_svg, write_triangle_panels_svg, Figure, Outline, Series, TriangleField,
    TriangleMeshPlot,
};

/// A dynamic scene from an inline TOML table (a case's `scene`) with dotted-key overrides
/// (`"time.steps" = 40`); `model = "dynamic"` is implied. Unknown keys are errors (the scene
/// format denies them), named with `source`.
pub fn scene_from_table(
    table: &toml::Table,
    set: &toml::Table,
    source: &str,
) -> Result<DynamicScene, String> {
    let mut t = table.clone();
    t.entry("model".to_string())
        .or_insert_with(|| toml::Value::String("dynamic".into()));
    crate::core::overrides::apply(&mut t, set).map_err(|e| format!("{source}: {e}"))?;
    let file: DynamicSceneFile = t
        .try_into()
        .map_err(|e: toml::de::Error| format!("{source}: {e}"))?;
    DynamicScene::from_file(file).map_err(|e| format!("{source}: {e}"))
}

/// [`run_recorded`] with a panic turned into an error (the suite's promise: a correct run or a
/// typed error, never a panic).
pub fn run_guarded(solver: &DynamicSolver, snapshot_times: &[f64]) -> Result<RecordedRun, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        run_recorded(solver, snapshot_times)
    }))
    .map_err(|p| {
        let what = p
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        format!("the solver panicked: {what}")
    })
}

/// A number as JSON, or its text when it is not finite (JSON has no NaN or ∞; serde would write
/// null, which reads as "absent").
fn finite_or_text(x: f64) -> serde_json::Value {
    if x.is_finite() {
        json!(x)
    } else {
        json!(x.to_string())
    }
}

/// The typed error as JSON: its message and its data.
pub fn error_json(e: &LabError) -> serde_json::Value {
    match e {
        LabError::Solve(SolveError::NewtonNotConverged {
            step,
            time,
            iterations,
            residual,
            tolerance,
        }) => json!({
            "message": e.to_string(), "kind": "newton_not_converged", "step": step, "time": time,
            "iterations": iterations, "residual": finite_or_text(*residual),
            "tolerance": finite_or_text(*tolerance),
        }),
        LabError::Solve(SolveError::DynamicNewtonNotConverged {
            step,
            time,
            iterations,
            residual,
            tolerance,
            floor,
            row,
            excess,
        }) => json!({
            "message": e.to_string(), "kind": "newton_not_converged", "step": step, "time": time,
            "iterations": iterations, "residual": finite_or_text(*residual),
            "tolerance": finite_or_text(*tolerance), "floor": finite_or_text(*floor),
            "row": row, "excess": finite_or_text(*excess),
        }),
        LabError::Solve(SolveError::NonFinite {
            step,
            time,
            quantity,
            value,
            hint,
        }) => json!({
            "message": e.to_string(), "kind": "non_finite", "step": step, "time": time,
            "quantity": quantity, "value": value.to_string(), "hint": hint,
        }),
        LabError::Solve(SolveError::ActiveSetCycle {
            step,
            time,
            iterations,
            residual,
            period,
            constraints,
        }) => json!({
            "message": e.to_string(), "kind": "active_set_cycle", "step": step, "time": time,
            "iterations": iterations, "residual": finite_or_text(*residual), "period": period,
            "constraints": constraints,
        }),
        LabError::Solve(SolveError::NoEquilibrium { step, time, reason }) => json!({
            "message": e.to_string(), "kind": "no_equilibrium", "step": step, "time": time,
            "reason": reason,
        }),
        LabError::Solve(SolveError::Singular {
            operator,
            row,
            pivot,
        }) => json!({
            "message": e.to_string(), "kind": "singular", "operator": operator, "row": row,
            "pivot": pivot.to_string(),
        }),
        LabError::Solve(SolveError::Stopped { at, reason }) => json!({
            "message": e.to_string(), "kind": "stopped", "at": at, "reason": reason,
        }),
        LabError::Solve(SolveError::Eigenproblem { at, .. }) => json!({
            "message": e.to_string(), "kind": "eigenproblem", "at": at,
        }),
        LabError::Solve(SolveError::EnergyGain {
            step,
            time,
            energy,
            initial,
            constraint,
            work,
            ..
        }) => json!({
            "message": e.to_string(), "kind": "energy_gain", "step": step, "time": time,
            "energy": energy, "initial": initial, "constraint": constraint, "work": work,
        }),
        LabError::Input(_) => json!({ "message": e.to_string(), "kind": "input" }),
        LabError::Scene { .. } => json!({ "message": e.to_string(), "kind": "scene" }),
        LabError::Mesh(_) => json!({ "message": e.to_string(), "kind": "mesh" }),
    }
}

/// `energy_audit.json`.
#[derive(Debug, Serialize)]
struct AuditFile<'a> {
    source: &'a str,
    title: &'a str,
    /// `completed` or `failed`.
    status: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<serde_json::Value>,
    /// Steps completed (records − 1) of the steps asked for.
    steps_completed: usize,
    steps_requested: usize,
    summary: AuditSummary,
    records: &'a [AuditRecord],
}

/// One snapshot of `solution.json`.
#[derive(Debug, Serialize)]
struct SnapshotOut {
    time: f64,
    /// Nodal values (interleaved u_x, u_y per node in 2D; one per node for a bar).
    displacement: Vec<f64>,
}

/// `solution.json`.
#[derive(Debug, Serialize)]
struct SolutionFile<'a> {
    source: &'a str,
    title: &'a str,
    status: &'a str,
    body: String,
    scheme: &'a str,
    /// `bar` or `plane`.
    dimension: &'a str,
    /// Node coordinates ([x] for a bar, [x, y] in 2D).
    nodes: Vec<Vec<f64>>,
    /// Triangles (2D).
    triangles: Vec<[usize; 3]>,
    /// Time of the last completed step.
    final_time: f64,
    final_displacement: Vec<f64>,
    final_velocity: Vec<f64>,
    /// The same, as nodal values.
    final_displacement_nodal: Vec<f64>,
    final_velocity_nodal: Vec<f64>,
    snapshots: Vec<SnapshotOut>,
    stats: DynamicStats,
}

/// Runs a dynamic scene and writes its outputs into `out`; returns a summary, or an error (after
/// writing the energy audit of the steps computed) when the run failed.
pub fn write_scene(scene: &DynamicScene, source: &str, out: &Path) -> Result<String, String> {
    let solver = scene.solver().map_err(|e| format!("{source}: {e}"))?;
    let run = run_recorded(&solver, &scene.params.snapshot_times);
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let write = |name: &str, json: String| {
        std::fs::write(out.join(name), json)
            .map_err(|e| format!("{}: {e}", out.join(name).display()))
    };
    let title = if scene.title.is_empty() {
        source.to_string()
    } else {
        scene.title.clone()
    };
    let status = if run.result.is_ok() {
        "completed"
    } else {
        "failed"
    };
    let summary = run.summary();
    let steps_completed = run.audit.records.len().saturating_sub(1);
    let audit_file = AuditFile {
        source,
        title: &title,
        status,
        error: run.result.as_ref().err().map(error_json),
        steps_completed,
        steps_requested: scene.problem.steps,
        summary,
        records: &run.audit.records,
    };
    write(
        "energy_audit.json",
        crate::core::json_out::finite_json(&audit_file, true)
            .map_err(|e| format!("{source}: energy_audit.json: {e}"))?,
    )?;
    let body = &scene.problem.body;
    let nodal = |u: &[f64]| -> Vec<f64> {
        match &scene.body {
            SceneBody::Bar(b) => b.nodal(u),
            SceneBody::Plane(p) => p.nodal(u),
        }
    };
    let (dimension, nodes, triangles): (&str, Vec<Vec<f64>>, Vec<[usize; 3]>) = match &scene.body {
        SceneBody::Bar(b) => (
            "bar",
            b.data().mesh.nodes().iter().map(|&x| vec![x]).collect(),
            Vec::new(),
        ),
        SceneBody::Plane(p) => (
            "plane",
            p.data()
                .mesh
                .nodes()
                .iter()
                .map(|x| vec![x[0], x[1]])
                .collect(),
            p.data().mesh.triangles().to_vec(),
        ),
    };
    let snapshots: &[(f64, Vec<f64>)] = match &run.result {
        Ok(sol) => &sol.snapshots,
        Err(_) => &run.snapshots,
    };
    let final_time = run.audit.records.last().map_or(0.0, |r| r.time);
    let solution = SolutionFile {
        source,
        title: &title,
        status,
        body: body.describe(),
        scheme: scene.problem.scheme.name(),
        dimension,
        nodes,
        triangles,
        final_time,
        final_displacement: run.displacement.clone(),
        final_velocity: run.velocity.clone(),
        final_displacement_nodal: nodal(&run.displacement),
        final_velocity_nodal: nodal(&run.velocity),
        snapshots: snapshots
            .iter()
            .map(|(t, u)| SnapshotOut {
                time: *t,
                displacement: nodal(u),
            })
            .collect(),
        stats: run.stats(),
    };
    write(
        "solution.json",
        crate::core::json_out::finite_json(&solution, true)
            .map_err(|e| format!("{source}: solution.json: {e}"))?,
    )?;
    write_plots(scene, &title, &run, snapshots, out)?;
    let mut text = summary_text(scene, source, &run, &summary);
    if scene.file.output.vtk {
        let frames =
            crate::dynamic::vtk::frames(scene, &run).map_err(|e| format!("{source}: {e}"))?;
        crate::vtk::write_series(out, "solution", &title, &frames)
            .map_err(|e| format!("{source}: {e}"))?;
        text.push_str(&format!(
            "; ParaView: {} ({} .vtu)",
            out.join("solution.pvd").display(),
            frames.len()
        ));
    }
    match &run.result {
        Ok(_) => Ok(text),
        Err(e) => Err(format!(
            "{text}\n{source}: the run stopped: {e}{}; the energy audit of the {steps_completed} \
             completed steps is in {}",
            likely_inputs(scene, e),
            out.join("energy_audit.json").display()
        )),
    }
}

/// For a solver failure (not a stop), the keys that set the step's scales with their values
/// ([`crate::core::likely_inputs`]).
fn likely_inputs(scene: &DynamicScene, e: &contactlab::error::Error) -> String {
    use crate::core::likely_inputs::{clause, optional, time_grid};
    use contactlab::error::{Error, SolveError};
    if !matches!(e, Error::Solve(s) if !matches!(s, SolveError::Stopped { .. })) {
        return String::new();
    }
    let f = &scene.file;
    let mut inputs = time_grid(f.time.final_time, Some(f.time.steps));
    inputs.extend(optional("material.young", Some(f.material.young)));
    inputs.extend(optional("body.density", Some(f.body.density)));
    if let Some(c) = &f.contact {
        inputs.extend(optional("contact.stiffness", c.stiffness));
        inputs.extend(optional("contact.depth", c.depth));
        inputs.extend(optional("contact.level", c.level));
    }
    clause(&inputs)
}

fn summary_text(scene: &DynamicScene, source: &str, run: &RecordedRun, s: &AuditSummary) -> String {
    let recs = &run.audit.records;
    let (first, last) = match (recs.first(), recs.last()) {
        (Some(f), Some(l)) => (*f, *l),
        _ => (AuditRecord::default(), AuditRecord::default()),
    };
    let max_pen = recs
        .iter()
        .map(|r| r.max_penetration)
        .fold(f64::NEG_INFINITY, f64::max);
    let max_force = recs.iter().map(|r| r.contact_force).fold(0.0f64, f64::max);
    let iterations: usize = recs.iter().map(|r| r.newton_iterations).sum();
    let max_it = recs.iter().map(|r| r.newton_iterations).max().unwrap_or(0);
    let stats = run.stats();
    let path = match &run.result {
        Ok(sol) => format!("{:?}", sol.stats.path.unwrap_or(solver_path(scene))).to_lowercase(),
        Err(_) => format!("{:?}", solver_path(scene)).to_lowercase(),
    };
    let contact = if scene.problem.contact.is_some() {
        format!(
            "; largest penetration {max_pen:.4e}, largest normal contact force {max_force:.4e}, \
             friction work {:.4e}, constraint work {:.4e}",
            last.friction_work, last.constraint_work
        )
    } else {
        String::new()
    };
    format!(
        "{source}: {}; {} scheme, {} path, {} of {} steps (k = {:.4e}): E_0 = {:.6e}, E_N = {:.6e}, \
         (E + Φ)_N − (E + Φ)_0 = {:.4e}, external work {:.4e}{contact}; largest identity \
         drifts |R_n|/E_ref: (1.48) {:.2e}, (1.49) {:.2e}, HLT 3.7 {:.2e}; {iterations} Newton \
         iterations (max {max_it} per step, {} stopped at the residual's round-off floor), {} \
         backtracks, {} factorizations ({} of an indefinite Jacobian), loop {:.3} s",
        scene.problem.body.describe(),
        scene.problem.scheme.name(),
        path,
        recs.len().saturating_sub(1),
        scene.problem.steps,
        scene.problem.final_time / scene.problem.steps as f64,
        first.energy(),
        last.energy(),
        (last.energy() + last.penalty) - (first.energy() + first.penalty),
        last.external_work,
        s.max_drift_1_48,
        s.max_drift_1_49,
        s.max_drift_3_7,
        stats.newton_floor_stops,
        stats.backtracks,
        stats.factorizations,
        stats.indefinite_factorizations,
        stats.loop_seconds,
    )
}

fn solver_path(scene: &DynamicScene) -> contactlab::model::dynamic::solver::DynamicPath {
    scene
        .solver()
        .map(|s| s.path())
        .unwrap_or(contactlab::model::dynamic::solver::DynamicPath::Full)
}

fn write_plots(
    scene: &DynamicScene,
    title: &str,
    run: &RecordedRun,
    snapshots: &[(f64, Vec<f64>)],
    out: &Path,
) -> Result<(), String> {
    let e = |e: crate::plot::PlotError| e.to_string();
    let runs = [AuditRun {
        label: scene.problem.scheme.name().to_string(),
        audit: &run.audit,
    }];
    write_svg(
        &energy_figure(&format!("{title}: energy history"), &runs, None),
        &out.join("energy.svg"),
    )
    .map_err(e)?;
    write_panels_svg(&residual_figures(&runs), 3, &out.join("identities.svg")).map_err(e)?;
    let recs = &run.audit.records;
    let series = |name: &str, f: &dyn Fn(&AuditRecord) -> f64| {
        Series::line(name.to_string(), recs.iter().map(|r| (r.time, f(r))))
    };
    let forces = Figure::new(format!("{title}: contact forces"))
        .x_label("t")
        .y_label("force")
        .series(series("Σ w_i N_i (normal)", &|r| r.contact_force))
        .series(series("Σ w_i T_i (friction)", &|r| r.friction_force));
    let pen = Figure::new("largest penetration")
        .x_label("t")
        .y_label("max_i p_i")
        .series(series("max penetration", &|r| r.max_penetration))
        .horizontal_line(0.0, "");
    let its = Figure::new("Newton iterations per step")
        .x_label("t")
        .y_label("iterations")
        .series(Series::markers(
            "iterations",
            recs.iter()
                .skip(1)
                .map(|r| (r.time, r.newton_iterations as f64)),
        ));
    write_panels_svg(&[forces, pen, its], 3, &out.join("contact.svg")).map_err(e)?;
    match &scene.body {
        SceneBody::Bar(b) => {
            let x = b.data().mesh.nodes();
            let mut fig = Figure::new(format!("{title}: displacement snapshots"))
                .x_label("x")
                .y_label("u");
            for i in crate::plot::plotted_snapshots(snapshots.len()) {
                let (t, u) = &snapshots[i];
                fig = fig.series(Series::line(
                    format!("t = {t:.4e}"),
                    x.iter().copied().zip(b.nodal(u)),
                ));
            }
            let t_last = recs.last().map_or(0.0, |r| r.time);
            if snapshots.last().is_none_or(|(t, _)| *t != t_last) {
                fig = fig.series(Series::line(
                    format!("t = {t_last:.4e} (last)"),
                    x.iter().copied().zip(b.nodal(&run.displacement)),
                ));
            }
            write_svg(&fig, &out.join("snapshots.svg")).map_err(e)?;
        }
        SceneBody::Plane(p) => {
            let mesh = &p.data().mesh;
            let mut states: Vec<(f64, &[f64])> = crate::plot::plotted_snapshots(snapshots.len())
                .into_iter()
                .map(|i| (snapshots[i].0, snapshots[i].1.as_slice()))
                .collect();
            let t_last = recs.last().map_or(0.0, |r| r.time);
            if states.last().is_none_or(|(t, _)| *t != t_last) {
                states.push((t_last, &run.displacement));
            }
            // every boundary edge as a segment (a non-finite point breaks the line): the
            // boundary of an annulus has two loops
            let boundary: Vec<[f64; 2]> = mesh
                .boundary()
                .iter()
                .flat_map(|edge| {
                    [
                        mesh.nodes()[edge.nodes[0]],
                        mesh.nodes()[edge.nodes[1]],
                        [f64::NAN, f64::NAN],
                    ]
                })
                .collect();
            let (xmin, xmax) = mesh
                .nodes()
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                    (a.min(x[0]), b.max(x[0]))
                });
            let plots: Vec<TriangleMeshPlot> = states
                .iter()
                .map(|(t, u)| {
                    let deformed = mesh.displaced(&p.nodal(u), 1.0);
                    let density: Vec<f64> = (0..mesh.triangles().len())
                        .map(|el| p.law_of(el).energy(&p.deformation_gradient(u, el)))
                        .collect();
                    let mut plot = TriangleMeshPlot::new(
                        format!("t = {t:.4e}: W(F)"),
                        deformed,
                        mesh.triangles().to_vec(),
                    )
                    .field(TriangleField::per_triangle("W(F)", density))
                    .outline(Outline::new("initial boundary", boundary.clone()).dashed());
                    if let Some(level) = scene.file.contact.as_ref().and_then(|c| c.level) {
                        let w = xmax - xmin;
                        plot = plot.outline(
                            Outline::new(
                                "foundation",
                                [[xmin - 0.25 * w, level], [xmax + 0.25 * w, level]],
                            )
                            .color(5),
                        );
                    }
                    plot
                })
                .collect();
            write_triangle_panels_svg(&plots, plots.len().min(3), &out.join("snapshots.svg"))
                .map_err(e)?;
        }
    }
    Ok(())
}
