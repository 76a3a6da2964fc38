//! The recorded solution of a plane run: snapshots (u, w, the stress and its plane-stress von
//! Mises norm per triangle) at requested times, and contact histories (total normal force,
//! active points, the deformed contact line).

use serde::Serialize;

use crate::error::InputError;
use crate::fem::triangle_p1::Sym2;
use crate::material::plane_law::von_mises_plane_stress;
use crate::model::quasistatic::plane::{EdgeRole, PlaneProblem};
use crate::model::quasistatic::plane_dofs::PlaneDofs;
use crate::model::quasistatic::plane_step::{PlaneObserver, PlaneStats, PlaneStep};
use crate::time::grid::TimeGrid;

/// What to record.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PlaneOutputRequest {
    /// Grid times at which to store snapshots.
    pub snapshot_times: Vec<f64>,
}

/// Fields at one time.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlaneSnapshot {
    pub n: usize,
    pub t: f64,
    /// u at the nodes, interleaved (u_x, u_y).
    pub u: Vec<f64>,
    /// w at the nodes (absent at n = 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub w: Option<Vec<f64>>,
    /// σ = A ε(w) + B ε(u) per triangle (σ11, σ22, σ12) (B ε(u) alone at n = 0).
    pub stress: Vec<[f64; 3]>,
    /// The plane-stress von Mises norm of σ per triangle.
    pub von_mises: Vec<f64>,
    /// The normal velocity w_ν = (C w)_g at the contact points (in the order of
    /// `PlaneDofs::contact_points`: two Gauss points per Γ3 edge, or the Γ3 nodes).
    pub contact_velocity: Vec<f64>,
    /// The pressure p_ν(w_ν) at the contact points.
    pub contact_pressure: Vec<f64>,
}

/// The recorded solution.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlaneSolution {
    pub nodes: Vec<[f64; 2]>,
    pub triangles: Vec<[usize; 3]>,
    pub times: Vec<f64>,
    /// Σ_g W_g p_ν at each time (the resultant normal contact force).
    pub contact_force: Vec<f64>,
    /// Contact points with p_ν′ > 0 at each time.
    pub active_points: Vec<usize>,
    /// The Γ3 nodes in boundary order (for contact lines).
    pub contact_nodes: Vec<usize>,
    pub snapshots: Vec<PlaneSnapshot>,
    pub stats: PlaneStats,
}

impl PlaneSolution {
    /// The node positions displaced by the snapshot's u.
    pub fn deformed(&self, snapshot: &PlaneSnapshot) -> Vec<[f64; 2]> {
        self.nodes
            .iter()
            .enumerate()
            .map(|(i, p)| [p[0] + snapshot.u[2 * i], p[1] + snapshot.u[2 * i + 1]])
            .collect()
    }
}

/// Stress σ = A ε(w) + B ε(u) on every triangle.
pub fn element_stresses(
    problem: &PlaneProblem,
    dofs: &PlaneDofs,
    u: &[f64],
    w: Option<&[f64]>,
) -> Vec<Sym2> {
    problem
        .mesh
        .triangles()
        .iter()
        .zip(&dofs.elements)
        .enumerate()
        .map(|(e, (t, el))| {
            let ul: [f64; 6] = std::array::from_fn(|p| u[2 * t[p / 2] + p % 2]);
            let sb = problem.elasticity_of(e).stress(&el.strain(&ul));
            match w {
                Some(w) => {
                    let wl: [f64; 6] = std::array::from_fn(|p| w[2 * t[p / 2] + p % 2]);
                    let sa = problem.viscosity_of(e).stress(&el.strain(&wl));
                    [sa[0] + sb[0], sa[1] + sb[1], sa[2] + sb[2]]
                }
                None => sb,
            }
        })
        .collect()
}

/// The Γ3 nodes in boundary order.
pub fn contact_nodes(problem: &PlaneProblem, dofs: &PlaneDofs) -> Vec<usize> {
    let mut nodes = Vec::new();
    for (e, role) in dofs.edge_roles.iter().enumerate() {
        if *role == EdgeRole::Contact {
            for &n in &problem.mesh.boundary()[e].nodes {
                if !nodes.contains(&n) {
                    nodes.push(n);
                }
            }
        }
    }
    nodes
}

/// An observer that records a [`PlaneSolution`] (it keeps its own copy of the problem and the
/// discrete structure, so the solver stays free to run).
#[derive(Debug)]
pub struct PlaneRecorder {
    problem: PlaneProblem,
    dofs: PlaneDofs,
    steps: Vec<usize>,
    weights: Vec<f64>,
    snapshots: Vec<Option<PlaneSnapshot>>,
    solution: PlaneSolution,
}

impl PlaneRecorder {
    /// Checks the request against a run's grid (the problem and its dofs as the solver set them
    /// up).
    pub fn new(
        problem: &PlaneProblem,
        dofs: &PlaneDofs,
        grid: &TimeGrid,
        request: &PlaneOutputRequest,
    ) -> Result<Self, InputError> {
        let mut steps = Vec::new();
        let mut seen = std::collections::BTreeSet::new();
        for (i, &t) in request.snapshot_times.iter().enumerate() {
            let n = grid.index_of(t).ok_or_else(|| {
                InputError::new(
                    format!("output.times[{i}]"),
                    t,
                    format!(
                        "a time of the grid: t_n = n k, n = 0 … {} (time.steps), up to \
                         time.final_time = {}",
                        grid.steps(),
                        grid.final_time()
                    ),
                )
            })?;
            // a time written twice (or two times of one step) is recorded once
            if seen.insert(n) {
                steps.push(n);
            }
        }
        let problem = problem.clone();
        let dofs = dofs.clone();
        let solution = PlaneSolution {
            nodes: problem.mesh.nodes().to_vec(),
            triangles: problem.mesh.triangles().to_vec(),
            times: Vec::new(),
            contact_force: Vec::new(),
            active_points: Vec::new(),
            contact_nodes: contact_nodes(&problem, &dofs),
            snapshots: Vec::new(),
            stats: PlaneStats::default(),
        };
        Ok(Self {
            weights: dofs.contact_points.iter().map(|p| p.weight).collect(),
            snapshots: vec![None; steps.len()],
            steps,
            problem,
            dofs,
            solution,
        })
    }

    /// The solution with the run's statistics.
    pub fn finish(mut self, stats: PlaneStats) -> PlaneSolution {
        self.solution.snapshots = self.snapshots.into_iter().flatten().collect();
        self.solution.stats = stats;
        self.solution
    }
}

impl PlaneObserver for PlaneRecorder {
    fn observe(&mut self, step: &PlaneStep<'_>) {
        let s = &mut self.solution;
        s.times.push(step.t);
        s.contact_force.push(
            self.weights
                .iter()
                .zip(step.contact_pressure)
                .map(|(w, p)| w * p)
                .sum(),
        );
        let active = match &self.problem.contact {
            Some(c) => self
                .dofs
                .contact_points
                .iter()
                .zip(step.contact_velocity)
                .filter(|(pt, r)| {
                    c.law.derivative(
                        **r,
                        crate::contact::normal_law::SpaceTime {
                            x: pt.position[0],
                            y: pt.position[1],
                            t: step.data_time,
                        },
                    ) > 0.0
                })
                .count(),
            None => 0,
        };
        s.active_points.push(active);
        for (slot, &n) in self.snapshots.iter_mut().zip(&self.steps) {
            if n == step.n {
                let stress = element_stresses(&self.problem, &self.dofs, step.u, step.w);
                *slot = Some(PlaneSnapshot {
                    n,
                    t: step.t,
                    u: step.u.to_vec(),
                    w: step.w.map(|w| w.to_vec()),
                    von_mises: stress.iter().map(von_mises_plane_stress).collect(),
                    stress,
                    contact_velocity: step.contact_velocity.to_vec(),
                    contact_pressure: step.contact_pressure.to_vec(),
                });
            }
        }
    }
}
