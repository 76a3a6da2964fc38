//! `verify scene` for rod scenes: runs the scene and writes its solution (and, where the scene
//! names an exact solution in an `[exact]` table, its errors) as JSON, with two plots.

use std::path::Path;

use serde::Serialize;

use contactlab::model::quasistatic::rod_output::RodRecorder;
use contactlab::model::quasistatic::rod_solver::{RodObserver, RodStep};
use contactlab::scene::rod::RodScene;

use crate::plot::{write_svg, Figure, Series};
use crate::rod::errors::RodErrorObserver;
use crate::rod::study::{exact_solution, ExactSpec};

/// What `verify scene` writes to `errors.json`.
#[derive(Debug, Serialize)]
pub struct SceneErrors {
    pub exact_solution: String,
    pub source: String,
    pub errors: std::collections::BTreeMap<String, f64>,
}

/// Runs a rod scene and writes `solution.json` (and, with an `[exact]` table, `errors.json`) and
/// two plots into `out` (with `[output] vtk = true` also the ParaView line series
/// `solution.pvd`, [`crate::rod::vtk`]). Returns a one-paragraph summary.
pub fn write_scene(scene: &RodScene, source: &str, out: &Path) -> Result<String, String> {
    let source = source.to_string();
    let exact: Option<ExactSpec> = match &scene.exact {
        Some(t) => Some(
            t.clone()
                .try_into()
                .map_err(|e: toml::de::Error| format!("{source}: [exact]: {e}"))?,
        ),
        None => None,
    };
    let solver = scene.solver().map_err(|e| format!("{source}: {e}"))?;
    let exact = match &exact {
        Some(spec) => {
            Some(exact_solution(spec, Some(&scene.problem)).map_err(|e| format!("{source}: {e}"))?)
        }
        None => None,
    };
    if let Some((_, Some(own))) = &exact {
        // A manufactured solution brings its own data; the scene must then describe the same rod.
        if (own.length - scene.problem.length).abs() > 1e-12
            || (own.final_time - scene.problem.final_time).abs() > 1e-12
        {
            return Err(format!(
                "{source}: the exact solution's rod (L = {}, T = {}) differs from the scene's (L = {}, T = {})",
                own.length, own.final_time, scene.problem.length, scene.problem.final_time
            ));
        }
    }
    let exact_solution = exact.as_ref().map(|(e, _)| e.as_ref());
    let mut recorder =
        RodRecorder::new(solver.mesh(), solver.grid(), solver.scheme(), &scene.output)
            .map_err(|e| format!("{source}: {e}"))?;
    let mut errors = exact_solution.map(|ex| {
        RodErrorObserver::new(
            ex,
            scene.problem.viscosity,
            scene.problem.elasticity,
            scene.grid.steps(),
        )
    });
    let outcome = solver.run(&mut |s: &RodStep<'_>| {
        recorder.observe(s);
        if let Some(e) = errors.as_mut() {
            e.observe(s);
        }
    });
    let stats = match outcome {
        Ok(stats) => stats,
        Err(e) => {
            // what was computed up to the failure is written (the steps observed, every number
            // finite), and the error says where
            let partial = recorder.finish(Default::default());
            let written = std::fs::create_dir_all(out)
                .map_err(|e| e.to_string())
                .and_then(|()| crate::core::json_out::finite_json(&partial, true))
                .and_then(|json| {
                    std::fs::write(out.join("partial_solution.json"), json)
                        .map_err(|e| e.to_string())
                });
            return Err(match written {
                Ok(()) => format!(
                    "{source}: {e}; the results of steps 0 to {} are in {}",
                    partial.times.len().saturating_sub(1),
                    out.join("partial_solution.json").display()
                ),
                Err(w) => format!("{source}: {e} (nothing written: {w})"),
            });
        }
    };
    let solution = recorder.finish(stats);
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let write = |name: &str, json: String| {
        std::fs::write(out.join(name), json)
            .map_err(|e| format!("{}: {e}", out.join(name).display()))
    };
    write(
        "solution.json",
        crate::core::json_out::finite_json(&solution, true)
            .map_err(|e| format!("{source}: solution.json: {e}"))?,
    )?;
    let mut summary = format!(
        "{source}: {} scheme, M = {}, N = {}: u_h(L, T) = {:.12e}, {} Newton iterations (max {} per step), {} steps with the damper active",
        solution.scheme,
        solution.nodes.len() - 1,
        solution.times.len() - 1,
        solution.end_displacement.last().copied().unwrap_or(f64::NAN),
        solution.stats.newton_iterations,
        solution.stats.max_newton_iterations,
        solution.stats.active_contact_steps
    );
    if let (Some(obs), Some(ex)) = (&errors, exact_solution) {
        let errs = SceneErrors {
            exact_solution: ex.name().to_string(),
            source: ex.source().to_string(),
            errors: obs.checked_errors().map_err(|e| {
                // the closed form was evaluated with the scene's data: name them as written
                let p = &scene.problem;
                format!(
                    "{source}: {e} (evaluated with rod.length = {}, rod.final_time = {}, rod.viscosity = {}, rod.elasticity = {} and the [foundation]: the closed form's exponentials in t·elasticity/viscosity leave the range of doubles when that product is large)",
                    p.length, p.final_time, p.viscosity, p.elasticity
                )
            })?,
        };
        summary.push_str(&format!(
            "; paper E = {:.6e} against {}",
            errs.errors.get("paper_E").copied().unwrap_or(f64::NAN),
            errs.exact_solution
        ));
        write(
            "errors.json",
            crate::core::json_out::finite_json(&errs, true)
                .map_err(|e| format!("{source}: errors.json: {e}"))?,
        )?;
    }
    let title = if scene.title.is_empty() {
        source.clone()
    } else {
        scene.title.clone()
    };
    let end = Figure::new(format!("{title}: end displacement and velocity"))
        .x_label("t (s)")
        .y_label("value")
        .series(Series::line(
            "u_h(L, t)",
            solution
                .times
                .iter()
                .copied()
                .zip(solution.end_displacement.iter().copied()),
        ))
        .series(Series::line(
            "w_n(L)",
            solution
                .times
                .iter()
                .copied()
                .zip(solution.end_velocity.iter().copied()),
        ))
        .series(Series::line(
            "σ_h(L, t)",
            solution
                .times
                .iter()
                .copied()
                .zip(solution.contact_stress.iter().copied()),
        ));
    write_svg(&end, &out.join("histories.svg")).map_err(|e| e.to_string())?;
    let mut snaps = Figure::new(format!("{title}: displacement snapshots"))
        .x_label("x")
        .y_label("u_h");
    for i in crate::plot::plotted_snapshots(solution.snapshots.len()) {
        let s = &solution.snapshots[i];
        snaps = snaps.series(Series::line(
            format!("t = {}", s.t),
            solution.nodes.iter().copied().zip(s.u.iter().copied()),
        ));
    }
    write_svg(&snaps, &out.join("snapshots.svg")).map_err(|e| e.to_string())?;
    if scene.vtk {
        let frames =
            crate::rod::vtk::frames(scene, &solution).map_err(|e| format!("{source}: {e}"))?;
        crate::vtk::write_series(out, "solution", &title, &frames)
            .map_err(|e| format!("{source}: {e}"))?;
        summary.push_str(&format!(
            "; ParaView: {} ({} .vtu)",
            out.join("solution.pvd").display(),
            frames.len()
        ));
    }
    Ok(summary)
}
