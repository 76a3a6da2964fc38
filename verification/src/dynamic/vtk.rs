//! The ParaView series of a dynamic scene (`[output] vtk = true`): one frame per snapshot of
//! `[output] times` (the step nearest each time).
//!
//! Point data: `displacement` (x, y, 0) and `velocity` — the scheme's velocity at t_n (v_n, or
//! δu_n for the schemes that carry it); on the contact nodes (zero elsewhere): `contact_pressure`
//! N_i (normal force per unit length of the step ending at t_n, compliance plus multiplier),
//! `contact_gap` −p_i = −(o_i + s_i u_ν,i) (the distance to the foundation; negative where the
//! node penetrates), `contact_active` (1 where N_i > 0), `contact_node` (1); with friction also
//! `friction_traction` T_i and `slip_velocity` (the tangential velocity of the node: the
//! foundation is at rest).
//!
//! Cell data: `body_id` (0), `region` (the index of the element's `[[region]]` + 1, 0 where the
//! body's own material applies; 0 on a bar), `strain`, `stress` (full 3 × 3 tensors) and
//! `von_mises` from [`contactlab::material::stress_state`] with each element's law: the
//! small-strain law's ε and σ, the finite-strain laws' Green–Lagrange E and Cauchy
//! σ = J⁻¹ P Fᵀ, with σ_33 of plane strain, and
//! σ_vM = (½[(σ11 − σ22)² + (σ22 − σ33)² + (σ33 − σ11)²] + 3 σ12²)^{1/2}. A bar is a line
//! series: points (x, 0, 0), one line cell per element, strain F − 1 and stress P(F) as the 11
//! entry of the tensors (a uniaxial state, σ_vM = |P|).

use contactlab::material::stress_state::hyperelastic_state;
use contactlab::model::dynamic::record::RecordedRun;
use contactlab::scene::dynamic::{DynamicScene, SceneBody};

use crate::vtk::{Array, Cells, Frame};

/// The contact arrays of one snapshot (point data over `n` nodes).
fn contact_arrays(
    scene: &DynamicScene,
    u: &[f64],
    v: &[f64],
    run_state: &[contactlab::model::dynamic::newton::NodeForces],
    n: usize,
) -> Vec<Array> {
    let Some(c) = &scene.problem.contact else {
        return Vec::new();
    };
    let mut pressure = vec![0.0; n];
    let mut gap = vec![0.0; n];
    let mut active = vec![0.0; n];
    let mut node = vec![0.0; n];
    let mut traction = vec![0.0; n];
    let mut slip = vec![0.0; n];
    for (i, cn) in c.nodes.iter().enumerate() {
        let f = run_state.get(i).copied().unwrap_or_default();
        pressure[cn.node] = f.normal;
        gap[cn.node] = -(cn.offset + cn.sign * u[cn.normal_dof]);
        active[cn.node] = f64::from(u8::from(f.normal > 0.0));
        node[cn.node] = 1.0;
        traction[cn.node] = f.tangential;
        slip[cn.node] = cn.tangent_dof.map_or(0.0, |d| v[d]);
    }
    let mut arrays = vec![
        Array::scalars("contact_pressure", pressure),
        Array::scalars("contact_gap", gap),
        Array::scalars("contact_active", active),
        Array::scalars("contact_node", node),
    ];
    if c.friction.is_some() {
        arrays.push(Array::scalars("friction_traction", traction));
        arrays.push(Array::scalars("slip_velocity", slip));
    }
    arrays
}

/// The frames of a recorded run (its snapshots, as far as the run got).
pub fn frames(scene: &DynamicScene, run: &RecordedRun) -> Result<Vec<Frame>, String> {
    if run.snapshot_states.len() != run.snapshots.len() {
        return Err(format!(
            "VTK output: {} snapshots but {} recorded states",
            run.snapshots.len(),
            run.snapshot_states.len()
        ));
    }
    let mut frames = Vec::with_capacity(run.snapshots.len());
    for ((t, u), state) in run.snapshots.iter().zip(&run.snapshot_states) {
        let v = &state.velocity;
        let frame = match &scene.body {
            SceneBody::Plane(p) => {
                let mesh = &p.data().mesh;
                let n = mesh.nodes().len();
                let (un, vn) = (p.nodal(u), p.nodal(v));
                let states: Vec<_> = (0..mesh.triangles().len())
                    .map(|e| hyperelastic_state(p.law_of(e), &p.deformation_gradient(u, e)))
                    .collect();
                let mut point_data = vec![
                    Array::plane_vectors(
                        "displacement",
                        (0..n).map(|i| [un[2 * i], un[2 * i + 1]]),
                    ),
                    Array::plane_vectors("velocity", (0..n).map(|i| [vn[2 * i], vn[2 * i + 1]])),
                ];
                point_data.extend(contact_arrays(scene, u, v, &state.forces, n));
                Frame {
                    time: *t,
                    points: mesh.nodes().iter().map(|x| [x[0], x[1], 0.0]).collect(),
                    cells: Cells::Triangles(mesh.triangles().to_vec()),
                    point_data,
                    cell_data: vec![
                        Array::plane_tensors("strain", states.iter().map(|s| (s.strain, 0.0))),
                        Array::plane_tensors(
                            "stress",
                            states.iter().map(|s| (s.stress, s.stress_33)),
                        ),
                        Array::scalars("von_mises", states.iter().map(|s| s.von_mises()).collect()),
                        Array::labels("body_id", vec![0; states.len()]),
                        Array::labels(
                            "region",
                            (0..states.len())
                                .map(|e| p.region_of(e).map_or(0, |r| r as i32 + 1))
                                .collect(),
                        ),
                    ],
                }
            }
            SceneBody::Bar(b) => {
                let x = b.data().mesh.nodes();
                let n = x.len();
                let (un, vn) = (b.nodal(u), b.nodal(v));
                let strain: Vec<f64> = (0..n - 1)
                    .map(|e| (un[e + 1] - un[e]) / (x[e + 1] - x[e]))
                    .collect();
                let stress: Vec<f64> = strain.iter().map(|s| b.data().law.piola(1.0 + s)).collect();
                let mut point_data = vec![
                    Array::plane_vectors("displacement", un.iter().map(|&a| [a, 0.0])),
                    Array::plane_vectors("velocity", vn.iter().map(|&a| [a, 0.0])),
                ];
                point_data.extend(contact_arrays(scene, u, v, &state.forces, n));
                Frame {
                    time: *t,
                    points: x.iter().map(|&xi| [xi, 0.0, 0.0]).collect(),
                    cells: Cells::Lines((0..n - 1).map(|e| [e, e + 1]).collect()),
                    point_data,
                    cell_data: vec![
                        Array::plane_tensors(
                            "strain",
                            strain.iter().map(|&s| ([s, 0.0, 0.0], 0.0)),
                        ),
                        Array::plane_tensors(
                            "stress",
                            stress.iter().map(|&s| ([s, 0.0, 0.0], 0.0)),
                        ),
                        Array::scalars("von_mises", stress.iter().map(|s| s.abs()).collect()),
                        Array::labels("body_id", vec![0; n - 1]),
                        Array::labels("region", vec![0; n - 1]),
                    ],
                }
            }
        };
        frames.push(frame);
    }
    Ok(frames)
}
