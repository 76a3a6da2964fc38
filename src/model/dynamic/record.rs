//! The run recorder: a dynamic run observed step by step, so that a run that stops partway still
//! yields everything it computed — the energy audit of every completed step, the snapshots and the
//! last state — beside the solution or the typed error; and which discrete energy identities a
//! problem satisfies to round-off.

use crate::error::Error;
use crate::model::dynamic::audit::{AuditSummary, EnergyAudit};
use crate::model::dynamic::newton::NodeForces;
use crate::model::dynamic::scheme::DynamicScheme;
use crate::model::dynamic::solver::{
    DynamicProblem, DynamicSolution, DynamicSolver, DynamicStats, StepView,
};

/// What a result file shows beside a snapshot's displacement.
#[derive(Debug, Clone, PartialEq)]
pub struct SnapshotState {
    /// The scheme's velocity at the snapshot's step (free dofs).
    pub velocity: Vec<f64>,
    /// The contact nodes' forces of the step (in the order of the contact model's nodes).
    pub forces: Vec<NodeForces>,
}

/// A run observed step by step: what was computed, whether or not the run completed.
#[derive(Debug)]
pub struct RecordedRun {
    /// The audit of every step completed (record 0 is the initial state).
    pub audit: EnergyAudit,
    /// (t, u) at the requested times (nearest step), as far as the run got.
    pub snapshots: Vec<(f64, Vec<f64>)>,
    /// The state beside each snapshot (same order): the velocity and the contact nodes' forces.
    pub snapshot_states: Vec<SnapshotState>,
    /// The last completed state (free dofs).
    pub displacement: Vec<f64>,
    pub velocity: Vec<f64>,
    /// The solution, or the typed error that stopped the run.
    pub result: Result<DynamicSolution, Error>,
}

impl RecordedRun {
    /// The summary of the audit of the steps computed.
    pub fn summary(&self) -> AuditSummary {
        self.audit.summary()
    }

    /// The solver statistics (of the completed run; default on failure).
    pub fn stats(&self) -> DynamicStats {
        self.result
            .as_ref()
            .map(|s| s.stats.clone())
            .unwrap_or_default()
    }
}

/// Runs `solver`, recording every step's audit record, the snapshots at `snapshot_times` (the
/// solver's rule: the step nearest each time) and the last state, so that a run that fails
/// partway still yields everything it computed.
pub fn run_recorded(solver: &DynamicSolver, snapshot_times: &[f64]) -> RecordedRun {
    run_recorded_with(solver, snapshot_times, &mut |_| {})
}

/// [`run_recorded`] with a further observer `extra` called after each step.
pub fn run_recorded_with(
    solver: &DynamicSolver,
    snapshot_times: &[f64],
    extra: &mut dyn FnMut(&StepView<'_>),
) -> RecordedRun {
    let k = solver.problem().final_time / solver.problem().steps as f64;
    let mut times = snapshot_times.to_vec();
    times.sort_by(f64::total_cmp);
    let mut next = 0;
    let mut audit = EnergyAudit {
        dofs: solver.problem().body.dofs(),
        ..Default::default()
    };
    let mut snapshots: Vec<(f64, Vec<f64>)> = Vec::new();
    let mut snapshot_states = Vec::new();
    let mut displacement = solver.problem().initial_displacement.clone();
    let mut velocity = solver.problem().initial_velocity.clone();
    let result = solver.solve_with(&mut |view: &StepView<'_>| {
        extra(view);
        audit.records.push(*view.record);
        displacement.copy_from_slice(view.displacement);
        velocity.copy_from_slice(view.velocity);
        while next < times.len() && times[next] <= view.time + 0.5 * k {
            // a time written twice (or two times of one step) is recorded once
            let fresh = snapshots.last().is_none_or(|(t, _)| *t != view.time);
            if (times[next] > view.time - 0.5 * k || view.step == 0) && fresh {
                snapshots.push((view.time, view.displacement.to_vec()));
                snapshot_states.push(SnapshotState {
                    velocity: view.velocity.to_vec(),
                    forces: view.forces.to_vec(),
                });
            }
            next += 1;
        }
    });
    RecordedRun {
        audit,
        snapshots,
        snapshot_states,
        displacement,
        velocity,
        result,
    }
}

/// The discrete energy identities a problem satisfies to round-off (BDS (1.48), (1.49) and
/// HLT Prop. 3.7; docs/dynamic.md §2–3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Conserving {
    /// BDS (1.48): conserving internal forces (linear midpoint / Gonzalez).
    pub balance: bool,
    /// The contact work is accounted for exactly: no compliance force, or an energy-consistent
    /// one (then HLT 3.7 holds).
    pub contact: bool,
    /// The problem has a compliance force (penalty, energy-consistent, tilted, IPM).
    pub compliance: bool,
}

impl Conserving {
    /// Whether the drift of the balance (1.49) over the run is round-off: (1.48) holds and the
    /// contact work is exact.
    pub fn total(&self) -> bool {
        self.balance && self.contact
    }

    /// Whether HLT 3.7 is a claim: an energy-consistent compliance force. (Without a compliance
    /// force its residual is identically zero.)
    pub fn claims_3_7(&self) -> bool {
        self.compliance && self.contact
    }

    /// Whether (1.49) is a claim of its own: it holds and differs from (1.48) (without a
    /// compliance force Φ = 0 and the two balances are the same).
    pub fn claims_1_49(&self) -> bool {
        self.total() && self.compliance
    }
}

/// Which energy identities a problem must satisfy to round-off: BDS (1.48) for Gonzalez's
/// scheme, and for the midpoint rule on a linear (small-strain) body; HLT 3.7 when the compliance
/// force is energy-consistent (BDS (1.46) = HLT (3.68), its tilted variant (3.69), the IPM);
/// (1.49) when both hold (or when (1.48) holds and there is no compliance force: Signorini, no
/// contact).
pub fn conserving(problem: &DynamicProblem) -> Conserving {
    let balance = match problem.scheme {
        DynamicScheme::Gonzalez => true,
        DynamicScheme::Midpoint => problem.body.is_linear(),
        DynamicScheme::Newmark => false,
    };
    let treatment = problem.contact.as_ref().map(|c| c.treatment);
    let compliance = treatment.is_some_and(|t| t.stiffness().is_some());
    Conserving {
        balance,
        contact: !compliance || treatment.is_some_and(|t| t.is_energy_consistent()),
        compliance,
    }
}
