//! What one run measures against the exact impact ([`TwoBarImpact`]), as relative errors:
//!
//! | error | definition |
//! |---|---|
//! | `duration_error` | \|T_c − (t_end − t_start)\| / (t_end − t_start), T_c = k × (the steps from the first with an active constraint to the last with N > 5 % of the exact force, inclusive) |
//! | `plateau_stress_error` | \|⟨N⟩/(A σ_c) − 1\|, ⟨N⟩ the mean of N = Σ λ_N over the steps in the middle half of the exact contact interval (an even number of them: the midpoint rule's force alternates from step to step) |
//! | `final_velocity_error` | max_b \|v_b(T) − v̂_b(T)\| / v, v_b = P_b/m_b the centre-of-mass velocity (x), v the impact speed |
//! | `centre_velocity_max` | max_n max_b \|v_b(t_n) − v̂_b(t_n)\| / v |
//! | `energy_error` | \|E(T) − E_0\| / E_0 |
//! | `activation_work` | \|Σ_n W_act,n\| / E_0: the work −λ g₀ of the constraints that close a gap within a step (the energy–momentum scheme's only loss) |
//! | `onset_work` | \|W_act\| / E_0 of the first contact step alone |
//! | `partition_error` | max_b \|E_b(T) − Ê_b(T)\| / E_0, E_b = ½ v_bᵀ M_b v_b + 𝒲_b(u_b) each bar's energy |
//! | `transverse_max` | max_n max_b \|v_b,y(t_n)\| / v: how far the discrete motion leaves the 1D one |
//!
//! The contact end of the force: the exact force drops from A σ_c to 0 at t_end; the discrete one
//! is smeared by the dispersion of P1 elements with a midpoint-type rule (module docs of
//! [`super`]) and rings about zero after the release; the last step with N above 5 % of A σ_c is
//! the release (the faces of the striker case touch without force after it: an active set that
//! does not end).

use serde::Serialize;

use contactlab::model::multibody::solver::MultibodySolver;

use crate::exact::bar_impact::TwoBarImpact;
use crate::multibody::study::{run_recorded, MaterialSpec, RecordedRun};

/// The measured errors (module docs), in report order.
pub const ERRORS: [&str; 9] = [
    "duration_error",
    "plateau_stress_error",
    "final_velocity_error",
    "centre_velocity_max",
    "energy_error",
    "activation_work",
    "onset_work",
    "partition_error",
    "transverse_max",
];

/// The fraction of the exact force above which a step counts as carrying the contact force.
pub const FORCE_THRESHOLD: f64 = 0.05;

/// The measurements of one run.
#[derive(Debug, Clone, Serialize)]
pub struct Measured {
    /// The errors, in the order of [`ERRORS`].
    pub errors: Vec<f64>,
    /// The measured contact interval (start of the first step with force, end of the last).
    pub start: f64,
    pub end: f64,
    /// The final centre velocities and per-bar energies.
    pub final_velocities: [f64; 2],
    pub final_energies: [f64; 2],
}

impl Measured {
    /// The error named `name`.
    pub fn error(&self, name: &str) -> Option<f64> {
        ERRORS
            .iter()
            .position(|e| *e == name)
            .map(|i| self.errors[i])
    }
}

/// Runs `solver` and measures it against `exact` (impact speed `speed`: the relative speed of
/// the left bar towards the right one in the striker case, each bar's in the head-on case).
pub fn measure(
    solver: &MultibodySolver,
    exact: &dyn TwoBarImpact,
    speed: f64,
    material: &MaterialSpec,
) -> Result<(RecordedRun, Measured), String> {
    let run = run_recorded(solver, &vec![*material; solver.problem().bodies.len()])?;
    let k = solver.problem().final_time / solver.problem().steps as f64;
    let records = &run.solution.records;
    let e0 = records.first().map(|r| r.energy).unwrap_or(0.0);
    if e0 <= 0.0 {
        return Err("the initial energy is not positive".into());
    }
    let force = exact.area() * exact.contact_stress();
    let (t0, t1) = (exact.contact_start(), exact.contact_end());
    let first = run.history.iter().position(|h| h.active > 0);
    let last = run
        .history
        .iter()
        .rposition(|h| h.normal_force > FORCE_THRESHOLD * force);
    let (Some(first), Some(last)) = (first, last) else {
        return Err("the bars never carried a contact force".into());
    };
    if last + 1 == run.history.len() {
        return Err(format!(
            "the contact force is still above {FORCE_THRESHOLD} × the exact one at T"
        ));
    }
    // history[i] is the state at t_i = i k: the step ending there carried the force
    let (start, end) = (run.history[first].time - k, run.history[last].time);
    let (mut plateau, mut count, mut odd) = (0.0, 0usize, 0.0);
    let (mut centre, mut transverse) = (0.0f64, 0.0f64);
    for h in &run.history {
        let mid = h.time - 0.5 * k;
        if (t0 + 0.25 * (t1 - t0)..=t0 + 0.75 * (t1 - t0)).contains(&mid) {
            plateau += h.normal_force;
            count += 1;
            odd = h.normal_force;
        }
        let exact_v = exact.centre_velocities(h.time);
        for b in 0..2 {
            centre = centre.max((h.velocities[b][0] - exact_v[b]).abs() / speed);
            transverse = transverse.max(h.velocities[b][1].abs() / speed);
        }
    }
    if count % 2 == 1 {
        plateau -= odd;
        count -= 1;
    }
    let last_h = run.history.last().ok_or("no steps")?;
    let t_end = last_h.time;
    let exact_v = exact.centre_velocities(t_end);
    let final_velocities = [last_h.velocities[0][0], last_h.velocities[1][0]];
    let final_error = (0..2)
        .map(|b| (final_velocities[b] - exact_v[b]).abs() / speed)
        .fold(0.0, f64::max);
    let bodies = &solver.problem().bodies;
    let (u, v) = (
        &run.solution.final_displacement,
        &run.solution.final_velocity,
    );
    let mut scratch = vec![0.0; v.len()];
    let kinetic = bodies.kinetic_energies(v, &mut scratch);
    let stored = bodies.stored_energies(u);
    let final_energies = [kinetic[0] + stored[0], kinetic[1] + stored[1]];
    let exact_e = exact.energies(t_end);
    let partition = (0..2)
        .map(|b| (final_energies[b] - exact_e[b]).abs() / e0)
        .fold(0.0, f64::max);
    let e_end = records.last().map_or(e0, |r| r.energy);
    let onset = records
        .iter()
        .find(|r| r.activated > 0)
        .map_or(0.0, |r| r.activation_work);
    let duration = end - start;
    let errors = vec![
        (duration - (t1 - t0)).abs() / (t1 - t0),
        (plateau / count.max(1) as f64 / force - 1.0).abs(),
        final_error,
        centre,
        (e_end - e0).abs() / e0,
        run.summary.activation_work.abs() / e0,
        onset.abs() / e0,
        partition,
        transverse,
    ];
    let measured = Measured {
        errors,
        start,
        end,
        final_velocities,
        final_energies,
    };
    Ok((run, measured))
}
