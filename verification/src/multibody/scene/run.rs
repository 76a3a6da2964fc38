//! A multibody scene's run, recorded step by step so that a run that stops partway still has
//! what it computed: every step's audit record, each body's centre-of-mass velocity and each
//! `[[contact_pair]]` section's contact forces (raw, two-step mean, step impulse), the snapshots at the output times (taken as the
//! solver takes them: the step nearest each time) and the last state reached.

use contactlab::error::Error as LabError;
use contactlab::model::multibody::audit::MultibodyRecord;
use contactlab::model::multibody::history::{step_impulses, two_step_mean};
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{MultibodySnapshot, MultibodyStats, MultibodyStepView};
use contactlab::scene::multibody::MultibodyScene;
use serde::Serialize;

use crate::multibody::errors::centre_velocity;
use crate::multibody::scene::json::normal_force;

/// One step of the history.
#[derive(Debug, Clone, Serialize)]
pub struct HistoryRow {
    pub step: usize,
    pub time: f64,
    /// Each body's centre-of-mass velocity Σ_I (M v)_I / m_b.
    pub velocities: Vec<[f64; 2]>,
    /// Per `[[contact_pair]]` section (both passes of a two-pass one): Σ λ_N (with penalty
    /// enforcement Σ ε g₋) and Σ λ_T over its candidates at t_n.
    pub normal_force: Vec<f64>,
    pub friction_force: Vec<f64>,
    /// Per section: the two-step mean of Σ λ_N, F̄_n = (J_n + J_{n+1})/(2k) — the accurate
    /// contact force (the raw Σ λ_N of the implicit schemes alternates from step to step about
    /// it at a persistent contact; `contactlab::model::multibody::history`).
    pub normal_force_mean: Vec<f64>,
    /// Per section: the contact impulse J_n of the step ending at t_n (k Σ λ_N for the
    /// midpoint types, the trapezoidal rule for Newmark).
    pub normal_impulse: Vec<f64>,
}

/// Fills the history's two-step mean forces and step impulses from its raw forces, section by
/// section (a run that stopped: over the steps it completed).
fn add_means(history: &mut [HistoryRow], scheme: MultibodyScheme, k: f64) {
    let sections = history.first().map_or(0, |h| h.normal_force.len());
    for s in 0..sections {
        let raw: Vec<f64> = history.iter().map(|h| h.normal_force[s]).collect();
        let mean = two_step_mean(&raw, scheme, k);
        let impulse = step_impulses(&raw, scheme, k);
        for (h, (m, j)) in history.iter_mut().zip(mean.into_iter().zip(impulse)) {
            h.normal_force_mean.push(m);
            h.normal_impulse.push(j);
        }
    }
}

/// How a run ended.
#[derive(Debug)]
pub enum Ending {
    Completed(Box<MultibodyStats>),
    /// The typed error of the solver.
    Failed(LabError),
    /// A panic of the solver (a defect: reported, never propagated).
    Panicked(String),
}

/// A recorded run.
#[derive(Debug)]
pub struct SceneRun {
    pub records: Vec<MultibodyRecord>,
    pub history: Vec<HistoryRow>,
    pub snapshots: Vec<MultibodySnapshot>,
    /// The last state reached (the initial state if no step completed).
    pub last: Option<MultibodySnapshot>,
    pub ending: Ending,
}

impl SceneRun {
    /// The steps completed.
    pub fn steps_completed(&self) -> usize {
        self.records.len().saturating_sub(1)
    }
}

/// The snapshots at the requested times, as the solver takes them
/// (`contactlab::model::multibody::solver`): the times sorted, each taken at the first step
/// t_n with time ≤ t_n + k/2, if time > t_n − k/2 or at n = 0.
struct SnapshotTaker {
    times: Vec<f64>,
    next: usize,
    k: f64,
}

impl SnapshotTaker {
    fn take(&mut self, view: &MultibodyStepView<'_>, out: &mut Vec<MultibodySnapshot>) {
        let t = view.time;
        while self.next < self.times.len() && self.times[self.next] <= t + 0.5 * self.k {
            if self.times[self.next] > t - 0.5 * self.k || view.step == 0 {
                out.push(snapshot(view));
            }
            self.next += 1;
        }
    }
}

fn snapshot(view: &MultibodyStepView<'_>) -> MultibodySnapshot {
    MultibodySnapshot {
        step: view.step,
        time: view.time,
        displacement: view.displacement.to_vec(),
        velocity: view.velocity.to_vec(),
        contacts: view.contacts.to_vec(),
    }
}

/// Runs the scene, recording it; a panic of the solver is caught and reported.
pub fn run(scene: &MultibodyScene) -> SceneRun {
    let bodies = &scene.problem.bodies;
    let sections = scene.file.contact_pair.len();
    let mut scratch = vec![0.0; bodies.dofs()];
    let mut times = scene.params.snapshot_times.clone();
    times.sort_by(f64::total_cmp);
    let mut taker = SnapshotTaker {
        times,
        next: 0,
        k: scene.problem.final_time / scene.problem.steps as f64,
    };
    let mut records = Vec::new();
    let mut history = Vec::new();
    let mut snapshots = Vec::new();
    let mut last = None;
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let solver = scene.solver()?;
        solver.solve_with(&mut |view| {
            records.push(*view.record);
            let mut normal = vec![0.0; sections];
            let mut friction = vec![0.0; sections];
            for c in view.contacts {
                if let Some(o) = scene.origins.get(c.pair) {
                    normal[o.section] += normal_force(scene, c);
                    friction[o.section] += c.lambda_t;
                }
            }
            history.push(HistoryRow {
                step: view.step,
                time: view.time,
                velocities: (0..bodies.len())
                    .map(|b| centre_velocity(bodies, b, view.velocity, &mut scratch))
                    .collect(),
                normal_force: normal,
                friction_force: friction,
                normal_force_mean: Vec::new(),
                normal_impulse: Vec::new(),
            });
            taker.take(view, &mut snapshots);
            last = Some(snapshot(view));
        })
    }));
    let ending = match outcome {
        Ok(Ok(solution)) => {
            // the solver's own snapshots (the same steps as the observer's)
            snapshots = solution.snapshots;
            Ending::Completed(Box::new(solution.stats))
        }
        Ok(Err(e)) => Ending::Failed(e),
        Err(p) => Ending::Panicked(
            p.downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default(),
        ),
    };
    add_means(
        &mut history,
        scene.problem.scheme,
        scene.problem.final_time / scene.problem.steps as f64,
    );
    SceneRun {
        records,
        history,
        snapshots,
        last,
        ending,
    }
}
