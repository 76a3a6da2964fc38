//! `verify scene FILE.toml --out DIR`: runs a user's scene and writes its solution (and, where the
//! scene names an exact solution in an `[exact]` table, its errors) as JSON, with two plots.

use std::path::Path;

use serde::Serialize;

use contactlab::model::quasistatic::rod_output::RodRecorder;
use contactlab::model::quasistatic::rod_solver::{RodObserver, RodStep};
use contactlab::scene::rod::{RodScene, RodSceneFile};

use crate::case::{DiscretizationSpec, ExactSpec};
use crate::plot::{write_svg, Figure, Series};
use crate::rod_errors::RodErrorObserver;
use crate::rod_study::RodStudy;

/// What `verify scene` writes to `errors.json`.
#[derive(Debug, Serialize)]
pub struct SceneErrors {
    pub exact_solution: String,
    pub source: String,
    pub errors: std::collections::BTreeMap<String, f64>,
}

/// Runs the scene at `file`, writing `solution.json` (and `errors.json`) and plots into `out`.
/// Returns a one-paragraph summary.
pub fn run_scene(file: &Path, out: &Path) -> Result<String, String> {
    let text = std::fs::read_to_string(file).map_err(|e| format!("{}: {e}", file.display()))?;
    let source = file.display().to_string();
    let model = contactlab::scene::model_of(&text, &source).map_err(|e| e.to_string())?;
    if contactlab::scene::moving::MovingScene::handles(&model) {
        return crate::moving::scene::run_moving_scene(&text, &source, out);
    }
    if model == "plane" {
        return crate::scene_plane::run_plane_scene(&text, &source, out);
    }
    if model == "dynamic" {
        return crate::scene_dynamic::run_dynamic_scene(&text, &source, out);
    }
    if model != "rod" {
        return Err(format!(
            "{source}: invalid model = \"{model}\": expected \"rod\", \"plane\", \"dynamic\", \"moving_string\" or \"disc_particle\""
        ));
    }
    let mut table: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| format!("{source}: {e}"))?;
    let exact: Option<ExactSpec> = match table.remove("exact") {
        Some(v) => Some(
            v.try_into()
                .map_err(|e: toml::de::Error| format!("{source}: [exact]: {e}"))?,
        ),
        None => None,
    };
    let file_spec: RodSceneFile = table
        .clone()
        .try_into()
        .map_err(|e: toml::de::Error| format!("{source}: {e}"))?;
    let scene = RodScene::from_file(&file_spec).map_err(|e| format!("{source}: {e}"))?;
    let solver = scene.solver().map_err(|e| format!("{source}: {e}"))?;
    let study = match &exact {
        Some(spec) => Some(
            RodStudy::new(Some(&table), Some(spec), &DiscretizationSpec::default())
                .map_err(|e| format!("{source}: {e}"))?,
        ),
        None => None,
    };
    let exact_solution = study.as_ref().and_then(|s| s.exact.as_deref());
    if let (Some(study), Some(_)) = (&study, exact_solution) {
        // A manufactured solution brings its own data; the scene must then describe the same rod.
        if (study.problem.length - scene.problem.length).abs() > 1e-12
            || (study.problem.final_time - scene.problem.final_time).abs() > 1e-12
        {
            return Err(format!(
                "{source}: the exact solution's rod (L = {}, T = {}) differs from the scene's (L = {}, T = {})",
                study.problem.length, study.problem.final_time, scene.problem.length, scene.problem.final_time
            ));
        }
    }
    let mut recorder =
        RodRecorder::new(&solver, &scene.output).map_err(|e| format!("{source}: {e}"))?;
    let mut errors = exact_solution.map(|ex| {
        RodErrorObserver::new(
            ex,
            scene.problem.viscosity,
            scene.problem.elasticity,
            scene.grid.steps(),
        )
    });
    let stats = solver
        .run(&mut |s: &RodStep<'_>| {
            recorder.observe(s);
            if let Some(e) = errors.as_mut() {
                e.observe(s);
            }
        })
        .map_err(|e| format!("{source}: {e}"))?;
    let solution = recorder.finish(stats);
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let write = |name: &str, json: String| {
        std::fs::write(out.join(name), json)
            .map_err(|e| format!("{}: {e}", out.join(name).display()))
    };
    write(
        "solution.json",
        serde_json::to_string_pretty(&solution).map_err(|e| e.to_string())?,
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
            errors: obs.errors(),
        };
        summary.push_str(&format!(
            "; paper E = {:.6e} against {}",
            errs.errors.get("paper_E").copied().unwrap_or(f64::NAN),
            errs.exact_solution
        ));
        write(
            "errors.json",
            serde_json::to_string_pretty(&errs).map_err(|e| e.to_string())?,
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
    for s in &solution.snapshots {
        snaps = snaps.series(Series::line(
            format!("t = {}", s.t),
            solution.nodes.iter().copied().zip(s.u.iter().copied()),
        ));
    }
    write_svg(&snaps, &out.join("snapshots.svg")).map_err(|e| e.to_string())?;
    Ok(summary)
}
