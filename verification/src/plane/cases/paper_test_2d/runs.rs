//! The runs of Test 2D (one per reading, mesh and β) and what each contributes: the von Mises
//! range and the contact line at T, and for the rollers reading the mean sinking of Γ3 with its
//! closed form.
//!
//! The closed form. With rollers the vertical translation v = (0, 1) lies in V^h; in the scheme's
//! equation tested with it the viscous and elastic terms vanish (ε(v) = 0), so in every step the
//! contact pressures carry the whole vertical load: Σ_g W_g p_ν(r_g) = R(τ_n), with r_g = w_ν(x_g)
//! at the 2-point Gauss points x_g of the Γ3 edges (weights W_g = half the edge), R(t) the
//! resultant −∫_Γ2 f2_y of the top load (180 t N in Test 2D; f0 = 0). With (2.8),
//! β r_+ = β r + β r_−, r_− = max(−r, 0), so Σ_g W_g r_g = (R(τ_n) − p0 L)/β − S_n,
//! S_n = Σ_g W_g (r_g)_−, L = |Γ3|; the Gauss rule integrates the P1 velocity exactly, and summing
//! u_n = u_{n−1} + k w_n over the steps run (the skipped ones leave u = 0):
//!
//!   mean of u_y over Γ3 at T = −(1/L) Σ_n k [(R(τ_n) − p0 L)/β − S_n].
//!
//! S_n (the receding part, zero while every point presses into the foundation) is computed here
//! from the nodal w_n at our own Gauss points, and the mean of u_y from the nodal u_N — not from
//! the solver's contact points, weights or pressures. A wrong β, p0, weight, data time or
//! contact-point position changes the balance.

use contactlab::contact::normal_law::FoundationLaw;
use contactlab::model::quasistatic::plane::{PlaneProblem, Support};
use contactlab::model::quasistatic::plane_output::{
    PlaneOutputRequest, PlaneRecorder, PlaneSolution,
};
use contactlab::model::quasistatic::plane_step::{PlaneObserver, PlaneStep};
use contactlab::scene::plane::PlaneScene;

use super::format::Reading;
use crate::plane::scene::{variant, Variant};

/// The quantities of one run at T.
#[derive(Debug, Clone, serde::Serialize)]
pub struct PaperTestRun {
    pub reading: Reading,
    pub divisions: usize,
    pub beta: f64,
    /// Steps skipped for lack of equilibrium.
    pub skipped_steps: Vec<usize>,
    pub von_mises_min: f64,
    pub von_mises_max: f64,
    /// min and max of u_y over the Γ3 nodes at T.
    pub contact_line_min: f64,
    pub contact_line_max: f64,
    /// (1/L) ∫_Γ3 u_y at T (exact for P1: the trapezoidal rule on the Γ3 nodes).
    pub contact_line_mean: f64,
    /// k Σ_n S_n / (Σ_n k (R(τ_n) − p0 L)/β): the share of the receding part (0 when every point
    /// presses into the foundation in every step).
    pub receding_share: f64,
    /// The closed form of the mean sinking (rollers; see the module documentation).
    pub sinking_closed_form: Option<f64>,
}

impl PaperTestRun {
    /// A quantity by name.
    pub fn value(&self, q: super::format::Quantity) -> f64 {
        use super::format::Quantity::*;
        match q {
            VonMisesMin => self.von_mises_min,
            VonMisesMax => self.von_mises_max,
            ContactLineMin => self.contact_line_min,
            ContactLineMax => self.contact_line_max,
        }
    }
}

/// min and max of a slice.
fn range(v: &[f64]) -> (f64, f64) {
    (
        v.iter().copied().fold(f64::INFINITY, f64::min),
        v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    )
}

/// The 3-point Gauss rule on [0, 1].
const GAUSS3: [(f64, f64); 3] = [
    (0.5 - 0.387_298_334_620_741_7, 5.0 / 18.0),
    (0.5, 8.0 / 18.0),
    (0.5 + 0.387_298_334_620_741_7, 5.0 / 18.0),
];

/// R(t) = −∫_Γ2 f2_y (exact for data of degree ≤ 5 along each edge).
pub(super) fn load_resultant(problem: &PlaneProblem, t: f64) -> f64 {
    let mesh = &problem.mesh;
    let mut r = 0.0;
    for part in &problem.traction {
        for (e, edge) in mesh.boundary().iter().enumerate() {
            if !part.boundary.contains(mesh, e) {
                continue;
            }
            let (a, b) = (mesh.nodes()[edge.nodes[0]], mesh.nodes()[edge.nodes[1]]);
            let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            for (s, w) in GAUSS3 {
                let x = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
                r -= w * len * part.traction[1].eval(x[0], x[1], t);
            }
        }
    }
    r
}

/// The closed form of the mean sinking of Γ3 at T for a rollers run with the lubricated law
/// (constant p0) or the linear law (p0 = 0, S_n = 0: Σ_g W_g β r_g = R(τ_n)), and no body force
/// (None otherwise).
fn sinking_closed_form(
    scene: &PlaneScene,
    beta: f64,
    skipped: &[usize],
    receding: f64,
) -> Option<(f64, f64)> {
    let problem = &scene.problem;
    let contact = problem.contact.as_ref()?;
    // The linear law p = β r has no positive part: (2.8) with p0 = 0 and no receding term.
    let (p0, receding) = match contact.law.as_foundation_law()? {
        FoundationLaw::Lubricated { p0, .. } => (p0.as_constant()?, receding),
        FoundationLaw::Linear { .. } => (0.0, 0.0),
        _ => return None,
    };
    if problem
        .body_force
        .iter()
        .any(|f| f.as_constant() != Some(0.0))
        || contact.source.is_some()
    {
        return None;
    }
    let length = contact_length(problem);
    let times = scene.grid.times();
    let last_skipped = skipped.iter().copied().max().unwrap_or(0);
    let sum: f64 = (last_skipped + 1..times.len())
        .map(|n| {
            let tau = scene.scheme.data_time(times[n - 1], times[n]);
            (times[n] - times[n - 1]) * (load_resultant(problem, tau) - p0 * length)
        })
        .sum();
    Some((-(sum / beta - receding) / length, receding * beta / sum))
}

/// L = |Γ3|, the sum of the contact edges' lengths (0 without contact).
pub(super) fn contact_length(problem: &PlaneProblem) -> f64 {
    contact_edges(problem).iter().map(|e| e.2).sum()
}

/// The Γ3 edges (node a, node b, length) of a problem.
fn contact_edges(problem: &PlaneProblem) -> Vec<(usize, usize, f64)> {
    let mesh = &problem.mesh;
    let Some(contact) = problem.contact.as_ref() else {
        return Vec::new();
    };
    mesh.boundary()
        .iter()
        .enumerate()
        .filter(|&(e, _)| contact.boundary.contains(mesh, e))
        .map(|(_, edge)| (edge.nodes[0], edge.nodes[1], mesh.edge_normal(edge).1))
        .collect()
}

/// k Σ_n S_n over the steps run: S_n = Σ_g W_g max(−r_g, 0), r_g = −w_y at the 2-point Gauss
/// points of the Γ3 edges (ν = (0, −1)), W_g = half the edge.
struct Receding {
    edges: Vec<(usize, usize, f64)>,
    sum: f64,
}

impl Receding {
    fn observe(&mut self, step: &PlaneStep<'_>) {
        let (Some(w), false) = (step.w, step.skipped) else {
            return;
        };
        let g = 0.5 / 3f64.sqrt();
        for &(a, b, len) in &self.edges {
            for s in [0.5 - g, 0.5 + g] {
                let r = -((1.0 - s) * w[2 * a + 1] + s * w[2 * b + 1]);
                self.sum += step.k * 0.5 * len * (-r).max(0.0);
            }
        }
    }
}

/// One run of Test 2D at T and its summary (and the solution, for the pictures).
pub fn run_one(
    scene_table: &toml::Table,
    reading: Reading,
    divisions: usize,
    beta: f64,
) -> Result<(PaperTestRun, PlaneSolution), String> {
    let support = match reading {
        Reading::Clamped => Support::Clamped,
        Reading::Rollers => Support::FixX,
    };
    let scene = variant(
        scene_table,
        Variant {
            divisions: Some(divisions),
            beta: Some(beta),
            support: Some(support),
            start_at_first_equilibrium: Some(true),
            ..Default::default()
        },
    )?;
    let label = format!("{}, {divisions}×{divisions}, β = {beta}", reading.name());
    let mut solver = scene.solver().map_err(|e| format!("{label}: {e}"))?;
    let request = PlaneOutputRequest {
        snapshot_times: vec![scene.grid.final_time()],
    };
    let mut recorder = PlaneRecorder::new(solver.problem(), solver.dofs(), solver.grid(), &request)
        .map_err(|e| format!("{label}: {e}"))?;
    let mut receding = Receding {
        edges: contact_edges(&scene.problem),
        sum: 0.0,
    };
    let stats = solver
        .run(&mut |st: &PlaneStep<'_>| {
            recorder.observe(st);
            receding.observe(st);
        })
        .map_err(|e| format!("{label}: {e}"))?;
    let sol = recorder.finish(stats);
    let snap = sol
        .snapshots
        .first()
        .ok_or_else(|| format!("{label}: no snapshot at T"))?;
    // the Γ3 nodes in boundary order, sorted by x for the line
    let mut line: Vec<(f64, f64)> = sol
        .contact_nodes
        .iter()
        .map(|&i| (sol.nodes[i][0], snap.u[2 * i + 1]))
        .collect();
    line.sort_by(|a, b| a.0.total_cmp(&b.0));
    let length = line.last().map_or(0.0, |l| l.0) - line.first().map_or(0.0, |l| l.0);
    let integral: f64 = line
        .windows(2)
        .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1 + w[1].1))
        .sum();
    let (vm_lo, vm_hi) = range(&snap.von_mises);
    let ys: Vec<f64> = line.iter().map(|p| p.1).collect();
    let (c_lo, c_hi) = range(&ys);
    let skipped = sol.stats.skipped_steps.clone();
    let sinking = match reading {
        Reading::Rollers => sinking_closed_form(&scene, beta, &skipped, receding.sum),
        Reading::Clamped => None,
    };
    Ok((
        PaperTestRun {
            reading,
            divisions,
            beta,
            skipped_steps: skipped,
            von_mises_min: vm_lo,
            von_mises_max: vm_hi,
            contact_line_min: c_lo,
            contact_line_max: c_hi,
            contact_line_mean: integral / length,
            receding_share: sinking.map_or(f64::NAN, |s| s.1),
            sinking_closed_form: sinking.map(|s| s.0),
        },
        sol,
    ))
}
