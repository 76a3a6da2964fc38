//! The ParaView line series of a rod scene (`[output] vtk = true`): one frame per snapshot, the
//! interval mesh as points (x, 0, 0) with one line cell per element.
//!
//! Point data: `displacement` (u, 0, 0); `velocity` (w, 0, 0), the scheme's u̇ (absent at t_0,
//! where the quasistatic problem defines none); at the contact end x = L (zero elsewhere):
//! `contact_pressure` p_ν(w(L)) = −σ(L), `contact_normal_velocity` w(L), `contact_active` (1 where
//! p_ν′(w(L)) > 0: the damper acts), `contact_node` (1). No gap (the damped-response law acts on
//! the velocity of an end that stays on its foundation, Fernández & Sofonea 2004, (4.4)) and no
//! slip (1D).
//!
//! Cell data: `strain` u_x and `stress` σ = a w_x + b u_x ((4.1); b u_x alone at t_0) as the 11
//! entry of the tensors, `von_mises` |σ| (uniaxial), `body_id` (0), `region` (0: one material,
//! as on a dynamic bar).

use contactlab::contact::normal_law::SpaceTime;
use contactlab::model::quasistatic::rod_output::RodSolution;
use contactlab::scene::rod::RodScene;

use crate::vtk::{Array, Cells, Frame};

/// The frames of a rod solution.
pub fn frames(scene: &RodScene, sol: &RodSolution) -> Result<Vec<Frame>, String> {
    let x = &sol.nodes;
    let n = x.len();
    let (a, b) = (scene.problem.viscosity, scene.problem.elasticity);
    let gradient = |v: &[f64]| -> Vec<f64> {
        (0..n - 1)
            .map(|e| (v[e + 1] - v[e]) / (x[e + 1] - x[e]))
            .collect()
    };
    let mut frames = Vec::with_capacity(sol.snapshots.len());
    for s in &sol.snapshots {
        let (Some(&sigma_l), Some(&w_l)) = (sol.contact_stress.get(s.n), sol.end_velocity.get(s.n))
        else {
            return Err(format!(
                "VTK output at t = {}: no contact history at step {}",
                s.t, s.n
            ));
        };
        let strain = gradient(&s.u);
        let stress: Vec<f64> = match &s.w {
            Some(w) => strain
                .iter()
                .zip(gradient(w))
                .map(|(ux, wx)| a * wx + b * ux)
                .collect(),
            None => strain.iter().map(|ux| b * ux).collect(),
        };
        let at = SpaceTime {
            x: scene.problem.length,
            y: 0.0,
            t: s.t,
        };
        let end = |value: f64| -> Vec<f64> {
            let mut v = vec![0.0; n];
            v[n - 1] = value;
            v
        };
        let mut point_data = vec![Array::plane_vectors(
            "displacement",
            s.u.iter().map(|&u| [u, 0.0]),
        )];
        if let Some(w) = &s.w {
            point_data.push(Array::plane_vectors(
                "velocity",
                w.iter().map(|&v| [v, 0.0]),
            ));
        }
        let active = scene.problem.foundation.derivative(w_l, at) > 0.0;
        point_data.extend([
            Array::scalars("contact_pressure", end(-sigma_l)),
            Array::scalars("contact_normal_velocity", end(w_l)),
            Array::scalars("contact_active", end(f64::from(u8::from(active)))),
            Array::scalars("contact_node", end(1.0)),
        ]);
        frames.push(Frame {
            time: s.t,
            points: x.iter().map(|&xi| [xi, 0.0, 0.0]).collect(),
            cells: Cells::Lines((0..n - 1).map(|e| [e, e + 1]).collect()),
            point_data,
            cell_data: vec![
                Array::plane_tensors("strain", strain.iter().map(|&e| ([e, 0.0, 0.0], 0.0))),
                Array::plane_tensors("stress", stress.iter().map(|&e| ([e, 0.0, 0.0], 0.0))),
                Array::scalars("von_mises", stress.iter().map(|s| s.abs()).collect()),
                Array::labels("body_id", vec![0; n - 1]),
                Array::labels("region", vec![0; n - 1]),
            ],
        });
    }
    Ok(frames)
}
