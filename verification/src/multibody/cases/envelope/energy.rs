//! The energy and the momentum of a multibody state, assembled HERE from the meshes, the densities
//! and the small-strain linear law (not from the solver's records or its mass and stiffness
//! operators). Per P1 triangle T of area A, nodes i = 0, 1, 2 with velocities v_i and displacements
//! u_i (the held components read as 0):
//!
//! - kinetic: the consistent mass M_ij = ρ A/12 (1 + δ_ij) per component gives
//!   ½ vᵀ M_T v = ρ A/24 (Σ_i |v_i|² + |Σ_i v_i|²);
//! - stored: ∇u = Σ_i u_i ⊗ ∇N_i (∇N_i constant on T, from the reference coordinates),
//!   ε = sym ∇u, W = A [μ ε : ε + λ/2 (tr ε)²] with λ = E ν/((1 + ν)(1 − 2ν)),
//!   μ = E/(2(1 + ν)) (plane strain);
//! - momentum: the rows of M_T sum to ρ A/3, so P = Σ_T ρ A/3 Σ_i v_i, and each body's mass is
//!   Σ_T ρ A.
//!
//! **Round-off floors.** E is a sum of n non-negative terms, each a few dozen operations: its
//! round-off is at most ≈ (n + 30) ε E. The strains are differences of displacements that carry
//! the bars' rigid translation (|u| ≈ v T ≫ h |ε|): each entry of ∇u rounds by ≈ ε Σ_i |u_i||∇N_i|
//! =: δ_T, and W_T by A |σ|_T δ_T with |σ| ≤ (2μ + 2|λ|) max|ε|. The floor of E_T − E_0 is
//! C ε [(n + 30)(E_0 + E_T) + Σ_T A |σ|_T δ_T] (both states), C = `energy_round_off`. The momentum
//! is a sum of n signed terms of total size S_P = Σ_T ρ A/3 Σ_i |v_i|; the steps' updates
//! M (v_{n+1} − v_n) = k F add the round-off of F's assembly, whose x-sum is zero exactly (equal
//! and opposite contact forces, internal forces of a free body), once per step: the floor of
//! |P_T − P_0| is C ε (n + N) max(S_P(0), S_P(T)), N the steps, C = `momentum_round_off`.

use contactlab::model::multibody::bodies::BodySet;

/// The sums of one state.
#[derive(Debug, Clone, Default)]
pub struct StateSums {
    /// ½ vᵀ M v + W(u).
    pub energy: f64,
    pub kinetic: f64,
    pub stored: f64,
    /// P over every body, and per body.
    pub momentum: [f64; 2],
    pub body_momentum: Vec<[f64; 2]>,
    /// Σ_T ρ A per body.
    pub body_mass: Vec<f64>,
    /// n: the triangles summed.
    pub terms: usize,
    /// Σ_T A |σ|_T δ_T (module docs).
    pub strain_rounding: f64,
    /// S_P = Σ_T ρ A/3 Σ_i |v_i| (the larger component).
    pub momentum_size: f64,
}

/// λ and μ of plane strain.
fn lame(young: f64, poisson: f64) -> (f64, f64) {
    let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    (lambda, 0.5 * young / (1.0 + poisson))
}

/// The sums of the state (u, v) of `bodies`, each body of the linear law (E, ν).
pub fn state_sums(bodies: &BodySet, young: f64, poisson: f64, u: &[f64], v: &[f64]) -> StateSums {
    let (lambda, mu) = lame(young, poisson);
    let mut s = StateSums::default();
    let mut size = [0.0f64; 2];
    for b in 0..bodies.len() {
        let body = bodies.body(b);
        let mesh = &body.data().mesh;
        let read =
            |x: &[f64], node: usize| [0, 1].map(|c| bodies.dof(b, node, c).map_or(0.0, |d| x[d]));
        let (mut pb, mut mb) = ([0.0; 2], 0.0);
        for (e, tri) in mesh.triangles().iter().enumerate() {
            let x = tri.map(|n| mesh.nodes()[n]);
            let two_a = (x[1][0] - x[0][0]) * (x[2][1] - x[0][1])
                - (x[2][0] - x[0][0]) * (x[1][1] - x[0][1]);
            let area = 0.5 * two_a.abs();
            let rho = body.density_of(e);
            // ∇N_i = (y_j − y_k, x_k − x_j)/(2A), (i, j, k) cyclic
            let grad: [[f64; 2]; 3] = [0, 1, 2].map(|i| {
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                [(x[j][1] - x[k][1]) / two_a, (x[k][0] - x[j][0]) / two_a]
            });
            let (vs, us) = (tri.map(|n| read(v, n)), tri.map(|n| read(u, n)));
            let mut du = [[0.0; 2]; 2];
            let mut delta = 0.0;
            for i in 0..3 {
                for r in 0..2 {
                    for c in 0..2 {
                        du[r][c] += us[i][r] * grad[i][c];
                    }
                }
                delta += f64::EPSILON
                    * (us[i][0].abs() + us[i][1].abs())
                    * (grad[i][0].abs() + grad[i][1].abs());
            }
            let shear = 0.5 * (du[0][1] + du[1][0]);
            let trace = du[0][0] + du[1][1];
            let eps2 = du[0][0] * du[0][0] + du[1][1] * du[1][1] + 2.0 * shear * shear;
            s.stored += area * (mu * eps2 + 0.5 * lambda * trace * trace);
            let strain_max = du[0][0].abs().max(du[1][1].abs()).max(shear.abs());
            s.strain_rounding += area * (2.0 * mu + 2.0 * lambda.abs()) * strain_max * delta;
            let sum = [0, 1].map(|c| vs.iter().map(|w| w[c]).sum::<f64>());
            let squares: f64 = vs.iter().map(|w| w[0] * w[0] + w[1] * w[1]).sum();
            s.kinetic += rho * area / 24.0 * (squares + sum[0] * sum[0] + sum[1] * sum[1]);
            for c in 0..2 {
                pb[c] += rho * area / 3.0 * sum[c];
                size[c] += rho * area / 3.0 * vs.iter().map(|w| w[c].abs()).sum::<f64>();
            }
            mb += rho * area;
            s.terms += 1;
        }
        s.momentum[0] += pb[0];
        s.momentum[1] += pb[1];
        s.body_momentum.push(pb);
        s.body_mass.push(mb);
    }
    s.energy = s.kinetic + s.stored;
    s.momentum_size = size[0].max(size[1]);
    s
}

/// The round-off floor of E_T − E_0 over `steps` steps (module docs), C = `c`.
pub fn energy_floor(c: f64, start: &StateSums, end: &StateSums, steps: usize) -> f64 {
    let n = (start.terms + 30 + steps) as f64;
    c * f64::EPSILON * (n * (start.energy + end.energy))
        + c * (start.strain_rounding + end.strain_rounding)
}

/// The round-off floor of |P_T − P_0| over `steps` steps (module docs), C = `c`.
pub fn momentum_floor(c: f64, start: &StateSums, end: &StateSums, steps: usize) -> f64 {
    let n = (start.terms + steps) as f64;
    c * f64::EPSILON * n * start.momentum_size.max(end.momentum_size)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multibody::study::{rectangle_body, LawName, MaterialSpec};

    fn two_bars() -> BodySet {
        let m = MaterialSpec {
            law: LawName::Linear,
            young: 2.0,
            poisson: 0.3,
        };
        let body = |x: f64| {
            rectangle_body(
                [x, 0.0],
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
        BodySet::new(vec![body(-1.0), body(0.1)]).unwrap()
    }

    /// The recomputed sums agree with the solver's operators (½ vᵀ M v with its mass matrix, its
    /// stored energy, Σ M v) on a state with every component nonzero — two independent
    /// assemblies of the same quantities.
    #[test]
    fn recomputed_energy_and_momentum_match_the_solvers_operators() {
        let set = two_bars();
        let n = set.dofs();
        let u: Vec<f64> = (0..n).map(|i| 1e-3 * ((i * 7 % 11) as f64 - 5.0)).collect();
        let v: Vec<f64> = (0..n).map(|i| 0.1 * ((i * 3 % 5) as f64 - 2.0)).collect();
        let s = state_sums(&set, 2.0, 0.3, &u, &v);
        let mut scratch = vec![0.0; n];
        let kinetic: f64 = set.kinetic_energies(&v, &mut scratch).iter().sum();
        let stored: f64 = set.stored_energies(&u).iter().sum();
        assert!(
            (s.kinetic - kinetic).abs() <= 1e-13 * kinetic,
            "{s:?} {kinetic}"
        );
        assert!(
            (s.stored - stored).abs() <= 1e-13 * stored,
            "{s:?} {stored}"
        );
        set.mass_mul(&v, &mut scratch);
        let px: f64 = scratch.iter().step_by(2).sum();
        assert!(
            (s.momentum[0] - px).abs() <= 1e-14 * s.momentum_size,
            "{s:?} {px}"
        );
        assert!((s.body_mass[0] - 0.3).abs() < 1e-15, "{s:?}");
    }
}
