//! What every `multibody_extremes` run records: each bar's centre-of-mass velocity after every
//! step, the sum of the candidates' penetrations Σ_i (−g_i)⁺ (the penalty force is ε times it),
//! the smallest gap, and the audit.

use contactlab::model::multibody::audit::MultibodySummary;
use contactlab::model::multibody::solver::{MultibodySolution, MultibodySolver};

use crate::multibody::audit_state::{StateAudit, StateAuditor};
use crate::multibody::errors::centre_velocity;
use crate::multibody::study::MaterialSpec;

/// One step's observations.
#[derive(Debug, Clone, Copy, Default)]
pub struct Observation {
    pub time: f64,
    /// The bars' centre velocities (x).
    pub velocities: [f64; 2],
    /// Σ_i max(−g_i, 0) over the candidates at t_{n+1}.
    pub penetration: f64,
    /// min_i g_i (∞ without candidates).
    pub min_gap: f64,
    pub active: usize,
}

/// A run with its observations.
pub struct Observed {
    pub solution: MultibodySolution,
    pub summary: MultibodySummary,
    /// The audit recomputed from the state (`crate::multibody::audit_state`).
    pub state: StateAudit,
    pub steps: Vec<Observation>,
}

impl Observed {
    /// The bars' centre velocities at T.
    pub fn final_velocities(&self) -> [f64; 2] {
        self.steps.last().map_or([f64::NAN; 2], |o| o.velocities)
    }

    /// max_n max(−g_min, 0).
    pub fn max_penetration(&self) -> f64 {
        self.steps
            .iter()
            .map(|o| (-o.min_gap).max(0.0))
            .fold(0.0, f64::max)
    }

    /// The mean of Σ (−g)⁺ over the steps whose midpoints lie in [a, b] (an even number of
    /// them: the midpoint-type force alternates from step to step).
    pub fn mean_penetration(&self, k: f64, a: f64, b: f64) -> f64 {
        let inside: Vec<f64> = self
            .steps
            .iter()
            .filter(|o| (a..=b).contains(&(o.time - 0.5 * k)))
            .map(|o| o.penetration)
            .collect();
        let n = inside.len() - inside.len() % 2;
        if n == 0 {
            return f64::NAN;
        }
        inside[..n].iter().sum::<f64>() / n as f64
    }
}

/// Solves `solver`'s problem, observing every step.
pub fn observe(solver: &MultibodySolver, material: &MaterialSpec) -> Result<Observed, String> {
    let bodies = &solver.problem().bodies;
    let materials = vec![*material; bodies.len()];
    let mut auditor = StateAuditor::new(solver.problem(), &materials, &[])?;
    let mut scratch = vec![0.0; bodies.dofs()];
    let mut steps = Vec::new();
    let solution = solver
        .solve_with(&mut |view| {
            auditor.observe(view);
            steps.push(Observation {
                time: view.time,
                velocities: [
                    centre_velocity(bodies, 0, view.velocity, &mut scratch)[0],
                    centre_velocity(bodies, 1, view.velocity, &mut scratch)[0],
                ],
                penetration: view.contacts.iter().map(|c| (-c.gap).max(0.0)).sum(),
                min_gap: view.record.min_gap,
                active: view.record.active,
            });
        })
        .map_err(|e| e.to_string())?;
    let summary = solution.summary();
    Ok(Observed {
        solution,
        summary,
        state: auditor.finish()?,
        steps,
    })
}
