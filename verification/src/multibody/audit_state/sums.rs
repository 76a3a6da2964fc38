//! The mass and the stored energy of a multibody state, written HERE: the P1 consistent (or
//! lumped) mass element by element and the three plane-strain laws the multibody model supports
//! (linear, St Venant–Kirchhoff, neo-Hooke), from a case's material constants — never the
//! solver's mass operator or its law objects.
//!
//! Per triangle T of reference area A, nodes i = 0, 1, 2 with positions x_i = X_i + u_i and
//! velocities v_i (a held component reads 0), ∇N_i constant on T from the reference coordinates:
//!
//! - consistent mass M_ij = ρ A/12 (1 + δ_ij) per component: ½ vᵀ M_T v = ρ A/24 (Σ|v_i|² + |Σ v_i|²),
//!   (M v)_i = ρ A/12 (v_i + Σ_j v_j); lumped M_ii = ρ A/3: ½ vᵀ M_T v = ρ A/6 Σ |v_i|²;
//! - P = Σ_T Σ_i (M v)_i (both masses: ρ A/3 Σ_i v_i), J = Σ_T Σ_i x_i × (M v)_i;
//! - H = ∇u = Σ_i u_i ⊗ ∇N_i, F = I + H, and W_T = A W(H) with, in plane strain
//!   (λ = E ν/((1 + ν)(1 − 2ν)), μ = E/(2(1 + ν))):
//!   linear W = λ/2 (tr ε)² + μ ε : ε, ε = sym H;
//!   St Venant–Kirchhoff W = λ/2 (tr E)² + μ E : E, E = sym H + ½ HᵀH;
//!   neo-Hooke W = μ/2 (tr C − 2 − 2 ln J) + λ/2 (ln J)², tr C − 2 = 2 tr H + H : H,
//!   ln J = ln(1 + tr H + det H) (J > 0, else the state is inadmissible).
//!
//! **Magnitudes** (for the round-off floors of `super`): each sum carries Σ |terms| — for the
//! kinetic energy ρ A/24 (Σ_i |v_i|² + (Σ_i |v_i|)²) per element (bounding the magnitudes of the
//! terms v_i (M v)_i the solver adds), for P and J the sums of |(M v)_i| and |x_i| |(M v)_i|, for
//! the stored energy A (Σ |terms of W| + s (1 + |H| + Σ_i |u_i| |∇N_i|)) with s a bound of the
//! stress: an entry of H computed from displacements of size |u| rounds by ε Σ_i |u_i| |∇N_i| (a
//! rigid translation cancels in it), an entry of F = I + H (the solver's argument of W) by
//! ε (1 + |H|), and W moves by the stress times that.

use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::multibody::bodies::BodySet;

use crate::manufactured::strain_energy::{PlaneLaw, StrainEnergy};
use crate::multibody::spec::{LawName, MaterialSpec};

/// The law of a case's material, with its plane-strain Lamé constants (λ = E ν/((1 + ν)(1 − 2ν)),
/// μ = E/(2(1 + ν))).
pub fn plane_law(m: &MaterialSpec) -> PlaneLaw {
    let law = match m.law {
        LawName::Linear => StrainEnergy::Linear,
        LawName::StVenantKirchhoff => StrainEnergy::StVenantKirchhoff,
        LawName::NeoHooke => StrainEnergy::NeoHooke,
    };
    PlaneLaw::from_young_poisson(law, m.young, m.poisson)
}

/// The recomputed sums of one state, with their magnitudes (module docs).
#[derive(Debug, Clone, Copy, Default)]
pub struct StateSums {
    pub kinetic: f64,
    pub stored: f64,
    pub momentum: [f64; 2],
    pub angular: f64,
    pub kinetic_size: f64,
    pub stored_size: f64,
    pub momentum_size: [f64; 2],
    pub angular_size: f64,
    /// The triangles summed.
    pub terms: usize,
}

/// The sums of the state (u, v) of `bodies`, body b of law `laws[b]`. Errors name the body and
/// the element of an inadmissible state.
pub fn state_sums(
    bodies: &BodySet,
    laws: &[PlaneLaw],
    u: &[f64],
    v: &[f64],
) -> Result<StateSums, String> {
    let mut s = StateSums::default();
    for b in 0..bodies.len() {
        let body = bodies.body(b);
        let data = body.data();
        let mesh = &data.mesh;
        let lumped = data.mass == MassMatrix::Lumped;
        let law = laws[b];
        let read =
            |x: &[f64], node: usize| [0, 1].map(|c| bodies.dof(b, node, c).map_or(0.0, |d| x[d]));
        for (e, tri) in mesh.triangles().iter().enumerate() {
            let xr = tri.map(|n| mesh.nodes()[n]);
            let two_a = (xr[1][0] - xr[0][0]) * (xr[2][1] - xr[0][1])
                - (xr[2][0] - xr[0][0]) * (xr[1][1] - xr[0][1]);
            let area = 0.5 * two_a.abs();
            let rho = body.density_of(e);
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
                rounding +=
                    (us[i][0].abs() + us[i][1].abs()) * (grad[i][0].abs() + grad[i][1].abs());
            }
            let (w, w_size, stress) = law
                .energy(&h)
                .ok_or_else(|| format!("body {b} element {e}: det F ≤ 0 (inadmissible state)"))?;
            let hmax = h.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
            s.stored += area * w;
            // F = I + H as the solver forms it carries ε (1 + |H|) in each entry
            s.stored_size += area * (w_size + stress * (1.0 + hmax + rounding));
            element_motion(&mut s, rho * area, lumped, &xr, &us, &vs);
            s.terms += 1;
        }
    }
    Ok(s)
}

/// The kinetic energy, P and J of one element of mass m = ρ A (module docs).
fn element_motion(
    s: &mut StateSums,
    m: f64,
    lumped: bool,
    xr: &[[f64; 2]; 3],
    us: &[[f64; 2]; 3],
    vs: &[[f64; 2]; 3],
) {
    let sum = [0, 1].map(|c| vs.iter().map(|w| w[c]).sum::<f64>());
    let abs_sum = [0, 1].map(|c| vs.iter().map(|w| w[c].abs()).sum::<f64>());
    let squares: f64 = vs.iter().map(|w| w[0] * w[0] + w[1] * w[1]).sum();
    if lumped {
        s.kinetic += m / 6.0 * squares;
        s.kinetic_size += m / 6.0 * squares;
    } else {
        s.kinetic += m / 24.0 * (squares + sum[0] * sum[0] + sum[1] * sum[1]);
        s.kinetic_size += m / 24.0 * (squares + abs_sum[0] * abs_sum[0] + abs_sum[1] * abs_sum[1]);
    }
    for c in 0..2 {
        s.momentum[c] += m / 3.0 * sum[c];
        s.momentum_size[c] += m / 3.0 * abs_sum[c];
    }
    for i in 0..3 {
        let x = [xr[i][0] + us[i][0], xr[i][1] + us[i][1]];
        // (M v)_i and the magnitude of its terms
        let (mv, mv_size) = if lumped {
            (
                [0, 1].map(|c| m / 3.0 * vs[i][c]),
                [0, 1].map(|c| m / 3.0 * vs[i][c].abs()),
            )
        } else {
            (
                [0, 1].map(|c| m / 12.0 * (vs[i][c] + sum[c])),
                [0, 1].map(|c| m / 12.0 * (vs[i][c].abs() + abs_sum[c])),
            )
        };
        s.angular += x[0] * mv[1] - x[1] * mv[0];
        s.angular_size += x[0].abs() * mv_size[1] + x[1].abs() * mv_size[0];
    }
}

#[cfg(test)]
mod tests {
    //! The sums against the solver's operators on a state with every component nonzero (the laws
    //! themselves are checked against the solver's in `crate::manufactured::strain_energy`).
    use super::*;
    use crate::multibody::study::rectangle_body;

    fn spec(law: LawName) -> MaterialSpec {
        MaterialSpec {
            law,
            young: 2.0,
            poisson: 0.3,
        }
    }

    #[test]
    fn recomputed_kinetic_stored_momentum_and_angular_momentum_match_the_solvers_operators() {
        let m = spec(LawName::NeoHooke);
        let body = |x: f64| {
            rectangle_body(
                [x, 0.2],
                [1.0, 0.1],
                [4, 2],
                3.0,
                &m,
                vec![],
                vec![],
                [0.0; 2],
            )
            .unwrap()
        };
        let set = BodySet::new(vec![body(-1.0), body(0.1)]).unwrap();
        let n = set.dofs();
        let u: Vec<f64> = (0..n).map(|i| 1e-3 * ((i * 7 % 11) as f64 - 5.0)).collect();
        let v: Vec<f64> = (0..n).map(|i| 0.1 * ((i * 3 % 5) as f64 - 2.0)).collect();
        let laws = [plane_law(&m); 2];
        let s = state_sums(&set, &laws, &u, &v).unwrap();
        let mut scratch = vec![0.0; n];
        let kinetic: f64 = set.kinetic_energies(&v, &mut scratch).iter().sum();
        let stored: f64 = set.stored_energies(&u).iter().sum();
        assert!(
            (s.kinetic - kinetic).abs() <= 1e-13 * s.kinetic_size,
            "{s:?}"
        );
        assert!((s.stored - stored).abs() <= 1e-13 * s.stored_size, "{s:?}");
        let (mut p, mut j) = ([0.0; 2], 0.0);
        for (x, q) in set.nodal_momenta(&u, &v, &mut scratch) {
            p[0] += q[0];
            p[1] += q[1];
            j += x[0] * q[1] - x[1] * q[0];
        }
        for c in 0..2 {
            assert!(
                (s.momentum[c] - p[c]).abs() <= 1e-14 * s.momentum_size[c],
                "{s:?}"
            );
        }
        assert!((s.angular - j).abs() <= 1e-14 * s.angular_size, "{s:?} {j}");
    }
}
