//! The stored energies of the plane-strain laws, written HERE from their formulas (not the
//! solver's law objects), for the audits recomputed from the state of every family with plane
//! bodies (multibody, dynamic). Moved from `multibody::audit_state::sums`.
//!
//! With H = ∇u, F = I + H, λ = E ν/((1 + ν)(1 − 2ν)), μ = E/(2(1 + ν)), per unit reference area:
//!
//! - linear W = λ/2 (tr ε)² + μ ε : ε, ε = sym H;
//! - St Venant–Kirchhoff W = λ/2 (tr E)² + μ E : E, E = sym H + ½ HᵀH;
//! - neo-Hooke W = μ/2 (tr C − 2 − 2 ln J) + λ/2 (ln J)², tr C − 2 = 2 tr H + H : H,
//!   ln J = ln(1 + tr H + det H) (J > 0, else the state is inadmissible).
//!
//! Beside W, [`PlaneLaw::energy`] returns the magnitude of its terms (Σ |terms|) and a bound of
//! the stress (an entry of H or F rounded by δ moves W by at most the stress times δ): the
//! round-off floors of the audits are built from them.

/// Which stored energy.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StrainEnergy {
    Linear,
    StVenantKirchhoff,
    NeoHooke,
}

/// A law with its plane-strain Lamé constants.
#[derive(Debug, Clone, Copy)]
pub struct PlaneLaw {
    pub law: StrainEnergy,
    pub lambda: f64,
    pub mu: f64,
}

impl PlaneLaw {
    /// The law with λ = E ν/((1 + ν)(1 − 2ν)), μ = E/(2(1 + ν)) (plane strain).
    pub fn from_young_poisson(law: StrainEnergy, e: f64, nu: f64) -> Self {
        Self {
            law,
            lambda: e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            mu: 0.5 * e / (1.0 + nu),
        }
    }

    /// W(H) per unit reference area and the magnitude of its terms and of the stress (module
    /// docs); `None` where the state is inadmissible (neo-Hooke with J ≤ 0).
    pub fn energy(&self, h: &[[f64; 2]; 2]) -> Option<(f64, f64, f64)> {
        let (l, m) = (self.lambda, self.mu);
        let hmax = h.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
        let quadratic = |e: [[f64; 2]; 2]| {
            let tr = e[0][0] + e[1][1];
            let ee = e[0][0] * e[0][0] + e[1][1] * e[1][1] + 2.0 * e[0][1] * e[0][1];
            let emax = e.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
            (0.5 * l * tr * tr, m * ee, emax)
        };
        match self.law {
            StrainEnergy::Linear => {
                let s = 0.5 * (h[0][1] + h[1][0]);
                let (a, b, emax) = quadratic([[h[0][0], s], [s, h[1][1]]]);
                Some((a + b, a.abs() + b, (2.0 * m + 2.0 * l.abs()) * emax))
            }
            StrainEnergy::StVenantKirchhoff => {
                // E = sym H + ½ HᵀH
                let mut e = [[0.0; 2]; 2];
                for (r, row) in e.iter_mut().enumerate() {
                    for (c, x) in row.iter_mut().enumerate() {
                        let hth = h[0][r] * h[0][c] + h[1][r] * h[1][c];
                        *x = 0.5 * (h[r][c] + h[c][r]) + 0.5 * hth;
                    }
                }
                let (a, b, emax) = quadratic(e);
                let stress = (2.0 * m + 2.0 * l.abs()) * emax * (1.0 + hmax);
                Some((a + b, a.abs() + b, stress))
            }
            StrainEnergy::NeoHooke => {
                let tr = h[0][0] + h[1][1];
                let det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
                if 1.0 + tr + det <= 0.0 {
                    return None;
                }
                let ln_j = (tr + det).ln_1p();
                let hh: f64 = h.iter().flatten().map(|x| x * x).sum();
                let tr_c = 2.0 * tr + hh;
                let w = 0.5 * m * (tr_c - 2.0 * ln_j) + 0.5 * l * ln_j * ln_j;
                let size = 0.5 * m * (tr_c.abs() + 2.0 * ln_j.abs()) + 0.5 * l.abs() * ln_j * ln_j;
                let j = 1.0 + tr + det;
                let stress = (m + (m + l.abs() * ln_j.abs()) / j) * (1.0 + 2.0 * hmax);
                Some((w, size, stress))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    //! The laws written here against the solver's law objects at a finite strain (two
    //! independent implementations of the same formulas).
    use super::*;
    use contactlab::material::hyperelastic::{
        Hyperelastic2d, LinearElastic, NeoHooke, StVenantKirchhoff,
    };
    use nalgebra::Matrix2;

    #[test]
    fn each_law_written_here_matches_the_solvers_law_at_a_finite_strain() {
        let h = [[0.03, -0.02], [0.05, -0.04]];
        let f = Matrix2::new(1.0 + h[0][0], h[0][1], h[1][0], 1.0 + h[1][1]);
        let (e, nu) = (2.0, 0.3);
        let theirs: [(StrainEnergy, Box<dyn Hyperelastic2d>); 3] = [
            (
                StrainEnergy::Linear,
                Box::new(LinearElastic::from_young_poisson(e, nu).unwrap()),
            ),
            (
                StrainEnergy::StVenantKirchhoff,
                Box::new(StVenantKirchhoff::from_young_poisson(e, nu).unwrap()),
            ),
            (
                StrainEnergy::NeoHooke,
                Box::new(NeoHooke::from_young_poisson(e, nu).unwrap()),
            ),
        ];
        for (law, solver_law) in theirs {
            let (w, size, _) = PlaneLaw::from_young_poisson(law, e, nu).energy(&h).unwrap();
            let theirs = solver_law.energy(&f);
            assert!((w - theirs).abs() <= 1e-14 * size, "{law:?}: {w} {theirs}");
        }
    }
}
