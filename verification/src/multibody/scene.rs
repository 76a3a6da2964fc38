//! `verify scene` for multibody scenes (a dynamic scene with `[[body]]` sections, the format of
//! [`contactlab::scene::multibody`]): runs the scene and writes into `--out`
//!
//! - `solution.json` — the bodies (name, description with the law's λ and μ, nodes, triangles),
//!   the solver pairs (their `[[contact_pair]]` section, slave and master, enforcement, friction,
//!   slave nodes and tributary lengths), every step's audit record (energies, momenta, the works
//!   W_N, W_T, W_ext, the activation work, the identity residual with its tolerances, the contact
//!   counts and forces), the [`MultibodySummary`] (drifts over their tolerances: ≤ 1 is
//!   round-off), the solver statistics, the history (each body's centre-of-mass velocity, each
//!   section's Σ λ_N — raw, its two-step mean (the accurate force: the raw one alternates from
//!   step to step at a persistent contact) and the step's impulse — and Σ λ_T per step) and the snapshots at `[output] times` (each body's nodal
//!   displacement and velocity, the contact states: λ_N, λ_T, λ_N / w, gap, slip, active, stick);
//! - `history.csv` — the history as a table (step, t, per section the raw and two-step mean
//!   Σ λ_N, the step impulse and Σ λ_T, per body v_x and v_y);
//! - a run that stops partway writes `partial_solution.json` instead — the same, as far as the
//!   run got, with the last state reached, the status `failed` and the typed error with its data
//!   (step, time, …) — and the error is reported;
//! - plots ([`scene::plots`](plots)): `audit.svg` (total energy, energy-identity drift, momentum
//!   drifts), `contact.svg` (contact forces per section and centre-of-mass velocities against t,
//!   active constraints and Newton iterations), `snapshots.svg` (the deformed bodies coloured by
//!   W(F));
//! - with `[output] vtk = true` (or `--vtk`): `solution.pvd` and one `solution_<i>.vtu` per
//!   snapshot with all bodies ([`scene::vtk`](vtk)).
//!
//! The summary paragraph gives the energy drift, the activation and friction work, the identity
//! and momentum ratios, the contact counts, the Newton counts and the time.

mod claims;
mod json;
mod plots;
mod run;
mod vtk;

pub(crate) use json::normal_force;

use std::path::Path;

use serde::Serialize;
use serde_json::Value;

use contactlab::model::multibody::audit::{summarize, MultibodySummary};
use contactlab::model::multibody::solver::MultibodyStats;
use contactlab::scene::multibody::MultibodyScene;
use contactlab::scene::Scene;

use crate::multibody::scene::json::{BodyOut, PairOut, SnapshotOut};
use crate::multibody::scene::run::{Ending, HistoryRow, SceneRun};

/// `solution.json` (or `partial_solution.json`).
#[derive(Debug, Serialize)]
struct SolutionFile<'a> {
    source: &'a str,
    title: &'a str,
    /// `completed` or `failed`.
    status: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<Value>,
    scheme: &'a str,
    /// The time of the last completed step, the steps completed and asked for.
    final_time: f64,
    steps_completed: usize,
    steps_requested: usize,
    bodies: Vec<BodyOut>,
    pairs: Vec<PairOut>,
    /// Which of the summary's ratios the setting lets the scheme conserve.
    claims: claims::SceneClaims,
    summary: Value,
    /// The solver statistics (a completed run).
    #[serde(skip_serializing_if = "Option::is_none")]
    stats: Option<&'a MultibodyStats>,
    records: &'a [contactlab::model::multibody::audit::MultibodyRecord],
    history: &'a [HistoryRow],
    snapshots: Vec<SnapshotOut>,
    /// The last state reached.
    #[serde(skip_serializing_if = "Option::is_none")]
    last: Option<SnapshotOut>,
}

/// Runs a multibody scene and writes its outputs into `out`; returns a summary, or an error
/// (after writing what was computed) when the run failed.
pub fn write_scene(scene: &Scene, source: &str, out: &Path) -> Result<String, String> {
    let Scene::Multibody(scene) = scene else {
        return Err(format!("{source}: not a multibody scene"));
    };
    // every check of the solver, before the run
    scene.solver().map_err(|e| format!("{source}: {e}"))?;
    let run = run::run(scene);
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let title = if scene.title.is_empty() {
        source.to_string()
    } else {
        scene.title.clone()
    };
    let summary = summarize(&run.records);
    let e0 = run.records.first().map_or(0.0, |r| r.energy);
    let (status, error, stats) = match &run.ending {
        Ending::Completed(stats) => ("completed", None, Some(stats.as_ref())),
        Ending::Failed(e) => ("failed", Some(json::error(e)), None),
        Ending::Panicked(p) => (
            "failed",
            Some(serde_json::json!({
                "message": format!("the solver panicked: {p}"), "kind": "panic"
            })),
            None,
        ),
    };
    let file = SolutionFile {
        source,
        title: &title,
        status,
        error,
        scheme: scene.problem.scheme.name(),
        final_time: run.records.last().map_or(0.0, |r| r.time),
        steps_completed: run.steps_completed(),
        steps_requested: scene.problem.steps,
        bodies: json::bodies(scene),
        pairs: json::pairs(scene),
        claims: claims::of(scene),
        summary: json::summary(&summary, e0),
        stats,
        records: &run.records,
        history: &run.history,
        snapshots: run
            .snapshots
            .iter()
            .map(|s| json::snapshot(scene, s))
            .collect(),
        last: run.last.as_ref().map(|s| json::snapshot(scene, s)),
    };
    let name = if status == "completed" {
        "solution.json"
    } else {
        "partial_solution.json"
    };
    let text = crate::core::json_out::finite_json(&file, true)
        .map_err(|e| format!("{source}: {name}: {e}"))?;
    std::fs::write(out.join(name), text)
        .map_err(|e| format!("{}: {e}", out.join(name).display()))?;
    std::fs::write(out.join("history.csv"), history_csv(scene, &run.history))
        .map_err(|e| format!("{}: {e}", out.join("history.csv").display()))?;
    plots::write(scene, &title, &run, out).map_err(|e| format!("{source}: {e}"))?;
    let mut text = summary_text(scene, source, &run, &summary);
    let multipliers = scene
        .problem
        .pairs
        .iter()
        .any(|p| p.law.has_normal_multiplier());
    if let Some(w) = contactlab::model::multibody::audit::scheme_energy_warning(
        scene.problem.scheme,
        multipliers,
        &summary,
    ) {
        text.push_str(&format!("\n{source}: warning: {w}"));
    }
    if scene.file.output.vtk {
        let frames = vtk::frames(scene, &run.snapshots);
        crate::vtk::write_series(out, "solution", &title, &frames)
            .map_err(|e| format!("{source}: {e}"))?;
        text.push_str(&format!(
            "; ParaView: {} ({} .vtu)",
            out.join("solution.pvd").display(),
            frames.len()
        ));
    }
    match &run.ending {
        Ending::Completed(_) => Ok(text),
        Ending::Failed(e) => Err(format!(
            "{text}\n{source}: the run stopped: {e}{}; what the {} completed steps computed is \
             in {}",
            likely_inputs(scene, e),
            run.steps_completed(),
            out.join(name).display()
        )),
        Ending::Panicked(p) => Err(format!(
            "{text}\n{source}: the solver panicked: {p}; what the {} completed steps computed is \
             in {}",
            run.steps_completed(),
            out.join(name).display()
        )),
    }
}

/// `history.csv`: per step t_n and, per `[[contact_pair]]` section, the raw Σ λ_N (it alternates
/// from step to step at a persistent contact), its two-step mean (the accurate force), the step's
/// contact impulse and Σ λ_T; then each body's centre-of-mass velocity.
fn history_csv(scene: &MultibodyScene, history: &[HistoryRow]) -> String {
    let mut text = String::from("step,time");
    for p in 0..scene.file.contact_pair.len() {
        text.push_str(&format!(
            ",pair{p}_normal_force_raw,pair{p}_normal_force_mean,pair{p}_normal_impulse,\
             pair{p}_friction_force"
        ));
    }
    for name in &scene.names {
        let name = name.replace([',', '"'], "_");
        text.push_str(&format!(",{name}_vx,{name}_vy"));
    }
    text.push('\n');
    for h in history {
        text.push_str(&format!("{},{:e}", h.step, h.time));
        for p in 0..h.normal_force.len() {
            let at = |v: &[f64]| v.get(p).copied().unwrap_or(f64::NAN);
            text.push_str(&format!(
                ",{:e},{:e},{:e},{:e}",
                h.normal_force[p],
                at(&h.normal_force_mean),
                at(&h.normal_impulse),
                at(&h.friction_force)
            ));
        }
        for v in &h.velocities {
            text.push_str(&format!(",{:e},{:e}", v[0], v[1]));
        }
        text.push('\n');
    }
    text
}

/// The summary paragraph.
fn summary_text(
    scene: &MultibodyScene,
    source: &str,
    run: &SceneRun,
    s: &MultibodySummary,
) -> String {
    let recs = &run.records;
    let (e0, en) = (
        recs.first().map_or(0.0, |r| r.energy),
        recs.last().map_or(0.0, |r| r.energy),
    );
    let drift = if e0 == 0.0 {
        "E_0 = 0: no relative drift".to_string()
    } else {
        format!("max_n |E_n − E_0|/E_0 = {:.3e}", s.energy_drift)
    };
    let max_active = recs.iter().map(|r| r.active).max().unwrap_or(0);
    let max_stick = recs.iter().map(|r| r.sticking).max().unwrap_or(0);
    let max_slip = recs.iter().map(|r| r.slipping).max().unwrap_or(0);
    let (activated, released, switches) = recs.iter().fold((0, 0, 0), |(a, b, c), r| {
        (a + r.activated, b + r.released, c + r.switches)
    });
    let newton: usize = recs.iter().map(|r| r.newton_iterations).sum();
    let time = match &run.ending {
        Ending::Completed(st) => format!(
            "; {} symbolic analyses, {} search retries; setup {:.3} s, loop {:.3} s (search \
             {:.3} s)",
            st.analyses, st.search_retries, st.setup_seconds, st.loop_seconds, st.search_seconds
        ),
        _ => String::new(),
    };
    let c = claims::of(scene);
    let claimed = |value: f64, yes: bool, why: &str| {
        if yes {
            format!("{value:.3e}")
        } else {
            format!("{value:.3e} (not conserved here: {why})")
        }
    };
    let scheme = scene.problem.scheme.name();
    let activation = if e0 == 0.0 {
        String::new()
    } else {
        format!(" ({:.2e} of E_0)", s.activation_relative)
    };
    format!(
        "{source}: {} bodies ({}), {} contact pair section(s) ({} solver pairs); {scheme} scheme, \
         {} of {} steps (k = {:.4e}): E_0 = {:.6e}, E_N = {:.6e}, {drift}; activation work \
         {:.4e}{activation}, friction work {:.4e}; ratios to the round-off tolerance (≤ 1: \
         conserved to round-off): energy identity {}, energy between active-set changes {}, \
         P_x {}, P_y {}, J {}, friction's sign {:.3e}; contact in {} steps, at most \
         {max_active} active constraints ({max_stick} sticking, {max_slip} slipping), \
         {activated} activations, {released} releases, {switches} segment switches, {} steps \
         with an active-set change; {newton} Newton iterations (max {} per step){time}",
        scene.names.len(),
        scene.names.join(", "),
        scene.file.contact_pair.len(),
        scene.problem.pairs.len(),
        run.steps_completed(),
        scene.problem.steps,
        scene.problem.final_time / scene.problem.steps as f64,
        e0,
        en,
        s.activation_work,
        s.friction_work,
        claimed(
            s.identity_ratio,
            c.identity,
            &format!("the {scheme} scheme")
        ),
        claimed(
            s.unchanged_ratio,
            c.identity,
            &format!("the {scheme} scheme")
        ),
        claimed(s.momentum_ratio_x, c.momentum[0], &c.reasons[0]),
        claimed(s.momentum_ratio_y, c.momentum[1], &c.reasons[1]),
        claimed(s.angular_ratio, c.angular, &c.angular_reason(scene)),
        s.friction_ratio,
        s.steps_with_contact,
        s.steps_with_set_change,
        s.max_newton_iterations,
    )
}

/// For a solver failure (not a stop), the keys that set the step's scales with their values
/// ([`crate::core::likely_inputs`]): the time grid, each body's stiffness, density and velocity,
/// each pair's penalty stiffness and friction.
fn likely_inputs(scene: &MultibodyScene, e: &contactlab::error::Error) -> String {
    use crate::core::likely_inputs::{clause, optional, time_grid};
    use contactlab::error::{Error, SolveError};
    if !matches!(e, Error::Solve(s) if !matches!(s, SolveError::Stopped { .. })) {
        return String::new();
    }
    let f = &scene.file;
    let mut inputs = time_grid(f.time.final_time, Some(f.time.steps));
    for (i, b) in f.body.iter().enumerate() {
        inputs.extend(optional(
            &format!("body[{i}].material.young"),
            Some(b.material.young),
        ));
        inputs.extend(optional(&format!("body[{i}].density"), Some(b.density)));
        inputs.push((
            format!("body[{i}].velocity"),
            format!("[{}, {}]", b.velocity[0], b.velocity[1]),
        ));
    }
    for (j, p) in f.contact_pair.iter().enumerate() {
        inputs.extend(optional(
            &format!("contact_pair[{j}].stiffness"),
            p.stiffness,
        ));
        if p.friction != 0.0 {
            inputs.extend(optional(
                &format!("contact_pair[{j}].friction"),
                Some(p.friction),
            ));
        }
    }
    clause(&inputs)
}
