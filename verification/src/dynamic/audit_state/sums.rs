//! The kinetic and stored energies of a plane body's state, written HERE: the P1 consistent (or
//! lumped) mass element by element and the stored energy by the laws of
//! [`crate::manufactured::strain_energy`], from the density, mass kind and material of the case's
//! scene — never the solver's mass operator or its law objects. The mesh (reference coordinates,
//! triangles) and the numbering of the free dofs are the body's (a held component reads 0).
//!
//! Per triangle T of reference area A, nodes i = 0, 1, 2 with displacements u_i and velocities v_i:
//!
//! - consistent mass M_ij = ρ A/12 (1 + δ_ij) per component: ½ vᵀ M_T v = ρ A/24 (Σ|v_i|² + |Σ v_i|²);
//!   lumped (row sums) M_ii = ρ A/3: ½ vᵀ M_T v = ρ A/6 Σ |v_i|²;
//! - H = Σ_i u_i ⊗ ∇N_i, W_T = A W(H).
//!
//! **Magnitudes** (for the round-off floors of `super::run`): the kinetic energy carries
//! ρ A/24 (Σ_i |v_i|² + (Σ_i |v_i|)²) per element (the magnitudes of the terms v_i (M v)_i the
//! solver adds), the stored energy A (Σ |terms of W| + s (1 + |H| + Σ_i |u_i| |∇N_i|)) with s the
//! law's stress bound (an entry of H rounds by ε Σ_i |u_i| |∇N_i|, an entry of F = I + H by
//! ε (1 + |H|), and W moves by the stress times that).

use contactlab::model::dynamic::plane_body::PlaneBody;

use crate::manufactured::strain_energy::PlaneLaw;

/// The recomputed energies of one state, with their magnitudes (module docs).
#[derive(Debug, Clone, Copy, Default)]
pub struct PlaneSums {
    pub kinetic: f64,
    pub stored: f64,
    pub kinetic_size: f64,
    pub stored_size: f64,
    /// The triangles summed.
    pub terms: usize,
}

/// The energies of the state (u, v) (free dofs of `body`) with density ρ, the mass kind and the
/// law given. Errors name the element of an inadmissible state (neo-Hooke with J ≤ 0).
pub fn plane_sums(
    body: &PlaneBody,
    density: f64,
    lumped: bool,
    law: &PlaneLaw,
    u: &[f64],
    v: &[f64],
) -> Result<PlaneSums, String> {
    let mesh = &body.data().mesh;
    let read = |x: &[f64], node: usize| [0, 1].map(|c| body.dof(node, c).map_or(0.0, |d| x[d]));
    let mut s = PlaneSums::default();
    for (e, tri) in mesh.triangles().iter().enumerate() {
        let xr = tri.map(|n| mesh.nodes()[n]);
        let two_a = (xr[1][0] - xr[0][0]) * (xr[2][1] - xr[0][1])
            - (xr[2][0] - xr[0][0]) * (xr[1][1] - xr[0][1]);
        let area = 0.5 * two_a.abs();
        // ∇N_i = (y_j − y_k, x_k − x_j)/(2A), (i, j, k) cyclic
        let grad: [[f64; 2]; 3] = [0, 1, 2].map(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            [(xr[j][1] - xr[k][1]) / two_a, (xr[k][0] - xr[j][0]) / two_a]
        });
        let (vs, us) = (tri.map(|n| read(v, n)), tri.map(|n| read(u, n)));
        let mut h = [[0.0; 2]; 2];
        let mut rounding = 0.0;
        for i in 0..3 {
            for (r, row) in h.iter_mut().enumerate() {
                for (c, x) in row.iter_mut().enumerate() {
                    *x += us[i][r] * grad[i][c];
                }
            }
            rounding += (us[i][0].abs() + us[i][1].abs()) * (grad[i][0].abs() + grad[i][1].abs());
        }
        let (w, w_size, stress) = law
            .energy(&h)
            .ok_or_else(|| format!("element {e}: det F ≤ 0 (inadmissible state)"))?;
        let hmax = h.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
        s.stored += area * w;
        s.stored_size += area * (w_size + stress * (1.0 + hmax + rounding));
        let m = density * area;
        let squares: f64 = vs.iter().map(|w| w[0] * w[0] + w[1] * w[1]).sum();
        if lumped {
            s.kinetic += m / 6.0 * squares;
            s.kinetic_size += m / 6.0 * squares;
        } else {
            let sum = [0, 1].map(|c| vs.iter().map(|w| w[c]).sum::<f64>());
            let abs_sum = [0, 1].map(|c| vs.iter().map(|w| w[c].abs()).sum::<f64>());
            s.kinetic += m / 24.0 * (squares + sum[0] * sum[0] + sum[1] * sum[1]);
            s.kinetic_size +=
                m / 24.0 * (squares + abs_sum[0] * abs_sum[0] + abs_sum[1] * abs_sum[1]);
        }
        s.terms += 1;
    }
    Ok(s)
}
