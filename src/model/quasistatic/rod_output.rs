//! The recorded solution of a rod run: snapshots at requested times, histories of the contact end
//! and of probe points, and the solver statistics.

use serde::Serialize;

use crate::error::InputError;
use crate::fem::p1_interval::evaluate;
use crate::mesh::interval::IntervalMesh;
use crate::model::quasistatic::rod_step::{RodObserver, RodStats, RodStep};
use crate::model::quasistatic::scheme::TimeScheme;
use crate::time::grid::TimeGrid;

/// What to record besides the contact-end histories.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RodOutputRequest {
    /// Times t_n at which to store u_n, w_n (and v_n); each must be a time of the grid.
    pub snapshot_times: Vec<f64>,
    /// Points x ∈ [0, L] whose displacement history u_h(x, t_n) is recorded.
    pub probes: Vec<f64>,
}

/// Nodal fields at one time.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RodSnapshot {
    /// Step index n.
    pub n: usize,
    /// t_n.
    pub t: f64,
    /// u_n at the nodes.
    pub u: Vec<f64>,
    /// w_n at the nodes (absent at n = 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub w: Option<Vec<f64>>,
    /// The post-processed velocity v_n at the nodes, where computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub v: Option<Vec<f64>>,
}

/// The displacement history of one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProbeHistory {
    /// The point x.
    pub x: f64,
    /// u_h(x, t_n), n = 0..N.
    pub displacement: Vec<f64>,
}

/// The recorded solution.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RodSolution {
    /// The scheme that produced it.
    pub scheme: String,
    /// Mesh nodes x_0..x_M.
    pub nodes: Vec<f64>,
    /// t_0..t_N.
    pub times: Vec<f64>,
    /// u_n(L).
    pub end_displacement: Vec<f64>,
    /// w_n(L) (v_0(L) at n = 0).
    pub end_velocity: Vec<f64>,
    /// σ(L, t_n) = −p_ν(w_n(L)).
    pub contact_stress: Vec<f64>,
    /// Probe histories.
    pub probes: Vec<ProbeHistory>,
    /// Snapshots, in the order requested.
    pub snapshots: Vec<RodSnapshot>,
    /// Solver statistics.
    pub stats: RodStats,
}

/// An observer that records a [`RodSolution`].
#[derive(Debug)]
pub struct RodRecorder {
    mesh: IntervalMesh,
    snapshot_steps: Vec<usize>,
    snapshots: Vec<Option<RodSnapshot>>,
    solution: RodSolution,
}

impl RodRecorder {
    /// Checks the request against a run's mesh and grid.
    pub fn new(
        mesh: &IntervalMesh,
        grid: &TimeGrid,
        scheme: TimeScheme,
        request: &RodOutputRequest,
    ) -> Result<Self, InputError> {
        let mut snapshot_steps = Vec::with_capacity(request.snapshot_times.len());
        let mut seen = std::collections::BTreeSet::new();
        for (i, &t) in request.snapshot_times.iter().enumerate() {
            let n = grid.index_of(t).ok_or_else(|| {
                InputError::new(
                    format!("output.times[{i}]"),
                    t,
                    format!(
                        "a time of the grid: t_n = n k, n = 0 … {} (time.steps), up to \
                         rod.final_time = {} (k = final_time/steps for uniform steps)",
                        grid.steps(),
                        grid.final_time()
                    ),
                )
            })?;
            // a time written twice (or two times of one step) is recorded once
            if seen.insert(n) {
                snapshot_steps.push(n);
            }
        }
        let length = mesh.length();
        for (i, &x) in request.probes.iter().enumerate() {
            if !(x.is_finite() && (0.0..=length).contains(&x)) {
                return Err(InputError::new(
                    format!("output.probes[{i}]"),
                    x,
                    format!("a point of [0, {length}]"),
                ));
            }
        }
        let steps = grid.steps() + 1;
        Ok(Self {
            mesh: mesh.clone(),
            snapshots: vec![None; snapshot_steps.len()],
            snapshot_steps,
            solution: RodSolution {
                scheme: scheme.name().to_string(),
                nodes: mesh.nodes().to_vec(),
                times: Vec::with_capacity(steps),
                end_displacement: Vec::with_capacity(steps),
                end_velocity: Vec::with_capacity(steps),
                contact_stress: Vec::with_capacity(steps),
                probes: request
                    .probes
                    .iter()
                    .map(|&x| ProbeHistory {
                        x,
                        displacement: Vec::with_capacity(steps),
                    })
                    .collect(),
                snapshots: Vec::new(),
                stats: RodStats::default(),
            },
        })
    }

    /// The recorded solution with the run's statistics.
    pub fn finish(mut self, stats: RodStats) -> RodSolution {
        self.solution.snapshots = self.snapshots.into_iter().flatten().collect();
        self.solution.stats = stats;
        self.solution
    }
}

impl RodObserver for RodRecorder {
    fn observe(&mut self, step: &RodStep<'_>) {
        let s = &mut self.solution;
        let m = step.u.len() - 1;
        s.times.push(step.t);
        s.end_displacement.push(step.u[m]);
        s.end_velocity.push(step.contact_velocity);
        s.contact_stress.push(step.contact_stress);
        for probe in &mut s.probes {
            let value = evaluate(&self.mesh, step.u, probe.x).unwrap_or(f64::NAN);
            probe.displacement.push(value);
        }
        for (slot, &n) in self.snapshots.iter_mut().zip(&self.snapshot_steps) {
            if n == step.n {
                *slot = Some(RodSnapshot {
                    n: step.n,
                    t: step.t,
                    u: step.u.to_vec(),
                    w: step.w.map(|w| w.to_vec()),
                    v: step.v.map(|v| v.to_vec()),
                });
            }
        }
    }
}
