//! The ParaView series of a multibody scene (`[output] vtk = true` or `--vtk`): one frame per
//! snapshot, all bodies in one unstructured grid (each body's nodes after the previous bodies').
//!
//! Point data: `displacement` and `velocity` (x, y, 0); on the contact boundary — the slave
//! nodes of every pair, zero elsewhere: `contact_node` (1), `contact_pressure` Σ λ_N / w (the
//! normal multiplier — with penalty enforcement ε g₋ — over the node's tributary length w,
//! summed over the pairs the node is a slave of), `contact_gap` (for a node that is a candidate of the step the solver's gap g at
//! t_n, the smallest over its pairs; for the others, beyond the search margin, the distance to
//! the master: y − level for the foundation, the distance to the nearest master segment at t_n
//! otherwise), `contact_slip` (τ₁ − τ₀ of the step, of the pair with the smallest gap),
//! `contact_active` (1 where a constraint is active); with friction also `friction_traction`
//! Σ λ_T / w.
//!
//! Cell data: `body_id` (the body's index in the scene), `strain`, `stress` (full 3 × 3 tensors)
//! and `von_mises` from [`contactlab::material::stress_state`] with the body's law (Green–Lagrange
//! E and Cauchy σ = J⁻¹ P Fᵀ for the finite-strain laws, ε and σ for the small-strain law, with
//! σ_33 of plane strain), as for a dynamic body (`dynamic/vtk.rs`).

use contactlab::material::stress_state::hyperelastic_state;
use contactlab::model::multibody::solver::{MultibodySnapshot, PairMaster};
use contactlab::scene::multibody::MultibodyScene;

use crate::multibody::scene::json::normal_force;
use crate::vtk::{Array, Cells, Frame};

/// The distance from p to the segment [a, b].
fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let ap = [p[0] - a[0], p[1] - a[1]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1];
    let s = if len2 > 0.0 {
        ((ap[0] * ab[0] + ap[1] * ab[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d = [ap[0] - s * ab[0], ap[1] - s * ab[1]];
    (d[0] * d[0] + d[1] * d[1]).sqrt()
}

/// The contact arrays of a snapshot over the `n` points (`offsets[b]`: body b's first point).
fn contact_arrays(
    scene: &MultibodyScene,
    s: &MultibodySnapshot,
    offsets: &[usize],
    n: usize,
) -> Vec<Array> {
    let set = &scene.problem.bodies;
    let pairs = &scene.problem.pairs;
    if pairs.is_empty() {
        return Vec::new();
    }
    let u = &s.displacement;
    let mut node = vec![0.0; n];
    let mut pressure = vec![0.0; n];
    let mut traction = vec![0.0; n];
    let mut gap = vec![f64::INFINITY; n];
    let mut slip = vec![0.0; n];
    let mut active = vec![0.0; n];
    let mut candidate = vec![false; n];
    for c in &s.contacts {
        let Some(pair) = pairs.get(c.pair) else {
            continue;
        };
        let i = offsets[pair.slave.body] + c.slave;
        pressure[i] += normal_force(scene, c) / c.weight;
        traction[i] += c.lambda_t / c.weight;
        if !candidate[i] || c.gap < gap[i] {
            gap[i] = c.gap;
            slip[i] = c.slip;
        }
        candidate[i] = true;
        if c.active {
            active[i] = 1.0;
        }
    }
    for pair in pairs {
        let sb = pair.slave.body;
        for &sn in &pair.slave.nodes {
            let i = offsets[sb] + sn;
            node[i] = 1.0;
            if candidate[i] {
                continue;
            }
            let x = set.position(sb, sn, u);
            let d = match &pair.master {
                PairMaster::Foundation(f) => f.normal[0] * x[0] + f.normal[1] * x[1] - f.level,
                PairMaster::Surface(m) => m
                    .segments
                    .iter()
                    .map(|seg| {
                        segment_distance(
                            x,
                            set.position(m.body, seg[0], u),
                            set.position(m.body, seg[1], u),
                        )
                    })
                    .fold(f64::INFINITY, f64::min),
            };
            gap[i] = gap[i].min(d);
        }
    }
    for g in gap.iter_mut() {
        if !g.is_finite() {
            *g = 0.0;
        }
    }
    let mut arrays = vec![
        Array::scalars("contact_node", node),
        Array::scalars("contact_pressure", pressure),
        Array::scalars("contact_gap", gap),
        Array::scalars("contact_slip", slip),
        Array::scalars("contact_active", active),
    ];
    if pairs.iter().any(|p| p.law.friction > 0.0) {
        arrays.push(Array::scalars("friction_traction", traction));
    }
    arrays
}

/// The frames of the snapshots.
pub fn frames(scene: &MultibodyScene, snapshots: &[MultibodySnapshot]) -> Vec<Frame> {
    let set = &scene.problem.bodies;
    let mut offsets = Vec::with_capacity(set.len());
    let mut points = Vec::new();
    let mut triangles = Vec::new();
    for b in 0..set.len() {
        let mesh = &set.body(b).data().mesh;
        offsets.push(points.len());
        let base = points.len();
        points.extend(mesh.nodes().iter().map(|x| [x[0], x[1], 0.0]));
        triangles.extend(
            mesh.triangles()
                .iter()
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
    }
    let n = points.len();
    snapshots
        .iter()
        .map(|s| {
            let (mut un, mut vn) = (Vec::with_capacity(2 * n), Vec::with_capacity(2 * n));
            let mut states = Vec::with_capacity(triangles.len());
            let mut body_id = Vec::with_capacity(triangles.len());
            for b in 0..set.len() {
                let body = set.body(b);
                let r = set.range(b);
                let u = &s.displacement[r.clone()];
                un.extend(body.nodal(u));
                vn.extend(body.nodal(&s.velocity[r]));
                for e in 0..body.data().mesh.triangles().len() {
                    states.push(hyperelastic_state(
                        body.law_of(e),
                        &body.deformation_gradient(u, e),
                    ));
                    body_id.push(b as i32);
                }
            }
            let mut point_data = vec![
                Array::plane_vectors("displacement", (0..n).map(|i| [un[2 * i], un[2 * i + 1]])),
                Array::plane_vectors("velocity", (0..n).map(|i| [vn[2 * i], vn[2 * i + 1]])),
            ];
            point_data.extend(contact_arrays(scene, s, &offsets, n));
            Frame {
                time: s.time,
                points: points.clone(),
                cells: Cells::Triangles(triangles.clone()),
                point_data,
                cell_data: vec![
                    Array::plane_tensors("strain", states.iter().map(|s| (s.strain, 0.0))),
                    Array::plane_tensors("stress", states.iter().map(|s| (s.stress, s.stress_33))),
                    Array::scalars("von_mises", states.iter().map(|s| s.von_mises()).collect()),
                    Array::labels("body_id", body_id),
                ],
            }
        })
        .collect()
}
