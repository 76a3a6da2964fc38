//! A solved patch test against the exact uniform state ([`crate::exact::contact_patch`]): element
//! stresses (Hooke's law written in the verification crate, applied to the solver's displacement
//! gradients), nodal displacements, the multipliers, and the interface nodal forces assembled
//! here from the multipliers by node-to-segment interpolation in the current configuration.
//!
//! The interface forces: a multiplier λ of slave node s on master segment (x₁, x₂) pushes s by
//! λ n and the segment's ends by −λ (1 − ξ) n and −λ ξ n, with n = (a_y, −a_x)/|a|, a = x₂ − x₁,
//! ξ = (x_s − x₁)·a/|a|² (the gradient of the gap g = n·(x_s − x₁), which is exactly this for
//! any g: the derivative of n contributes −ξ n·da at every configuration). Whatever the split of
//! the multipliers between the passes, the sum of these forces on a node is unique (it is the
//! node's internal minus external force); the patch test asks that it be the consistent load
//! p w_i (up on B's nodes, down on A's).

use serde::Serialize;

use crate::exact::contact_patch::{Block, ContactPatch};
use crate::multibody::cases::patch::setup::{Passes, PatchRun};

const BLOCKS: [Block; 2] = [Block::Lower, Block::Upper];

fn index(block: Block) -> usize {
    match block {
        Block::Lower => 0,
        Block::Upper => 1,
    }
}

/// The contact pressure at an interface node: its reference position and λ/w.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct NodalPressure {
    pub pair: usize,
    pub x: f64,
    pub pressure: f64,
}

/// The errors of one run (module docs); relative to p, to the displacement scale or to p L.
#[derive(Debug, Clone, Serialize)]
pub struct PatchErrors {
    /// max over the elements of max(|σ_xx|, |σ_yy + p|, |σ_xy|, |σ_zz + ν p|) / p.
    pub stress_max: f64,
    /// (Σ_e |e| |σ_e − σ|² / |Ω|)^{1/2} / p (the Frobenius norm of the in-plane components).
    pub stress_l2: f64,
    /// max over the nodes of max_c |u_c − u_c^exact| / max |u^exact|.
    pub displacement_max: f64,
    /// |Σ λ − p L| / (p L) over every multiplier of every pass.
    pub total_force: f64,
    /// max over the interface nodes of |f_i − f_i^exact| / (p max w) (both components), f
    /// assembled here from the multipliers (module docs).
    pub interface_force_max: f64,
    /// Single-pass: max over the slave nodes of |λ_i/w_i − p| / p (the multipliers are unique).
    pub pressure_max: Option<f64>,
    /// max |g| over the active candidates / max |u^exact|.
    pub gap_max: f64,
    /// Candidates that are not active.
    pub inactive: usize,
    /// Newton iterations of the static solve.
    pub iterations: usize,
    /// Per block, the per-element stress error max(|σ − σ^exact|) / p.
    #[serde(skip)]
    pub element_errors: [Vec<f64>; 2],
    /// The nodal pressures λ_i/w_i of every pass.
    #[serde(skip)]
    pub pressures: Vec<NodalPressure>,
    /// Per block, (x, f_i/w_i) of its interface nodes: the compressive traction assembled from
    /// the multipliers (module docs).
    #[serde(skip)]
    pub tractions: [Vec<(f64, f64)>; 2],
}

/// Measures `run` against `patch`.
pub fn measure(patch: &ContactPatch, run: &PatchRun) -> PatchErrors {
    let pb = run.solver.problem();
    let bodies = &pb.bodies;
    let u = &run.solution.displacement;
    let p = patch.pressure;
    let materials = [patch.lower, patch.upper];
    let mut stress_max = 0.0f64;
    let mut l2 = 0.0;
    let mut area = 0.0;
    let mut displacement_max = 0.0f64;
    let mut element_errors: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    let scale = patch.displacement_scale();
    for block in BLOCKS {
        let b = index(block);
        let body = bodies.body(b);
        let ub = &u[bodies.range(b)];
        let mesh = &body.data().mesh;
        let exact = patch.stress(block);
        for e in 0..body.elements().len() {
            let f = body.deformation_gradient(ub, e);
            let grad = [[f[(0, 0)] - 1.0, f[(0, 1)]], [f[(1, 0)], f[(1, 1)] - 1.0]];
            let s = materials[b].stress(grad);
            let d: Vec<f64> = s.iter().zip(exact).map(|(a, b)| a - b).collect();
            let worst = d.iter().fold(0.0f64, |m, v| m.max(v.abs())) / p;
            stress_max = stress_max.max(worst);
            element_errors[b].push(worst);
            let a = mesh.area(e);
            l2 += a * (d[0] * d[0] + d[1] * d[1] + 2.0 * d[2] * d[2]);
            area += a;
        }
        let nodal = body.nodal(ub);
        for (i, x) in mesh.nodes().iter().enumerate() {
            let ex = patch.displacement(block, x[0], x[1]);
            for c in 0..2 {
                displacement_max = displacement_max.max((nodal[2 * i + c] - ex[c]).abs() / scale);
            }
        }
    }
    // the interface forces assembled from the multipliers (module docs)
    let mut force: [Vec<[f64; 2]>; 2] = [
        vec![[0.0; 2]; bodies.body(0).data().mesh.nodes().len()],
        vec![[0.0; 2]; bodies.body(1).data().mesh.nodes().len()],
    ];
    let mut total = 0.0;
    let mut gap_max = 0.0f64;
    let mut inactive = 0;
    let mut pressures = Vec::new();
    for c in &run.solution.contacts {
        total += c.lambda_n;
        if !c.active {
            inactive += 1;
            continue;
        }
        gap_max = gap_max.max(c.gap.abs() / scale);
        let pair = &pb.pairs[c.pair];
        let sb = pair.slave.body;
        let mb = 1 - sb;
        let master = if mb == 0 {
            &run.lower_top
        } else {
            &run.upper_bottom
        };
        let Some(seg) = c.segment else { continue };
        let [n1, n2] = master.segments[seg];
        let (x1, x2) = (bodies.position(mb, n1, u), bodies.position(mb, n2, u));
        let xs = bodies.position(sb, c.slave, u);
        let a = [x2[0] - x1[0], x2[1] - x1[1]];
        let len2 = a[0] * a[0] + a[1] * a[1];
        let len = len2.sqrt();
        let xi = ((xs[0] - x1[0]) * a[0] + (xs[1] - x1[1]) * a[1]) / len2;
        let n = [a[1] / len, -a[0] / len];
        for k in 0..2 {
            force[sb][c.slave][k] += c.lambda_n * n[k];
            force[mb][n1][k] -= c.lambda_n * (1.0 - xi) * n[k];
            force[mb][n2][k] -= c.lambda_n * xi * n[k];
        }
        let x = bodies.body(sb).data().mesh.nodes()[c.slave][0];
        pressures.push(NodalPressure {
            pair: c.pair,
            x,
            pressure: c.lambda_n / c.weight,
        });
    }
    let mut interface_force_max = 0.0f64;
    let mut tractions: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
    for block in BLOCKS {
        let b = index(block);
        let surface = run.surface(block);
        let w_max = surface.weights.iter().fold(0.0f64, |m, w| m.max(*w));
        let sign = if b == 0 { -1.0 } else { 1.0 };
        let nodes = bodies.body(b).data().mesh.nodes();
        for (&node, &w) in surface.nodes.iter().zip(&surface.weights) {
            tractions[b].push((nodes[node][0], sign * force[b][node][1] / w));
            let exact = [0.0, sign * patch.nodal_force(w)];
            for k in 0..2 {
                interface_force_max =
                    interface_force_max.max((force[b][node][k] - exact[k]).abs() / (p * w_max));
            }
        }
    }
    let pressure_max = match run.passes {
        Passes::Single { .. } => Some(
            pressures
                .iter()
                .fold(0.0f64, |m, q| m.max((q.pressure - p).abs() / p)),
        ),
        Passes::Two => None,
    };
    PatchErrors {
        stress_max,
        stress_l2: (l2 / area).sqrt() / p,
        displacement_max,
        total_force: (total - patch.total_force()).abs() / patch.total_force(),
        interface_force_max,
        pressure_max,
        gap_max,
        inactive,
        iterations: run.solution.iterations,
        element_errors,
        pressures,
        tractions,
    }
}
