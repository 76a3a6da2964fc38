//! The contact patch test (Taylor & Papadopoulos 1991): two elastic blocks stacked along a flat
//! interface, pressed together by a uniform pressure (docs/multibody.md, the patch test).
//!
//! **Setting.** The lower block A = (0, L) × (0, H_A) stands on rollers (u_y = 0 on y = 0) with
//! its left side on rollers (u_x = 0 on x = 0); the upper block B = (0, L) × (H_A, H_A + H_B) has
//! its left side on rollers (u_x = 0) and carries the uniform pressure p on its top (the dead
//! traction (0, −p)); nothing else holds B vertically: the contact carries it. Frictionless
//! contact along y = H_A; each block has its own linear (small-strain) plane-strain law (E, ν).
//!
//! **Exact solution.** Uniaxial compression in both blocks,
//!
//!   σ_xx = σ_xy = 0,  σ_yy = −p,  σ_zz = ν (σ_xx + σ_yy) = −ν p   (plane strain),
//!
//! with the strains ε_xx = ν (1 + ν) p / E (the lateral expansion) and ε_yy = −(1 − ν²) p / E,
//! and the affine displacements that meet the supports:
//!
//!   A: u = (ε_xx^A x, ε_yy^A y),   B: u = (ε_xx^B x, ε_yy^A H_A + ε_yy^B (y − H_A)).
//!
//! P1 elements represent both exactly, and the consistent nodal force of the contact pressure on
//! an interface node is p w_i, w_i its tributary length (half its edges). The contact traction
//! is p everywhere: the patch test asks that the discrete contact forces reproduce it.
//!
//! **The interface in the current configuration.** The interface stays flat (at height
//! H_A (1 + ε_yy^A)), but the two traces stretch differently when the lateral strains differ:
//! a point X of A's top moves to X (1 + ε_xx^A), one of B's bottom to X (1 + ε_xx^B). A contact
//! constraint written in the current configuration (the gap of node-to-segment contact) then
//! sees B's load centroid shifted by L (ε_xx^B − ε_xx^A)/2 against A's: the consistent loads of
//! the uniform state have the same resultant p L but moments about x = 0 that differ by
//! [`ContactPatch::moment_mismatch`] = p L²/2 · (ε_xx^B − ε_xx^A), O(p²/E). The uniform state is
//! exact for the small-strain problem, and an exact equilibrium of the current-configuration
//! constraints only when ν_A (1 + ν_A)/E_A = ν_B (1 + ν_B)/E_B.

use serde::Serialize;

/// A plane-strain linear material (E, ν).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Hooke {
    pub young: f64,
    pub poisson: f64,
}

impl Hooke {
    /// The Lamé constants (λ, μ) of plane strain.
    pub fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.young, self.poisson);
        (
            e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            e / (2.0 * (1.0 + nu)),
        )
    }

    /// [σ_xx, σ_yy, σ_xy, σ_zz] of the small strain ε = sym(∇u) (ε_zz = 0):
    /// σ = λ tr ε I + 2 μ ε, σ_zz = λ tr ε. Written here, independent of the solver's law.
    pub fn stress(&self, grad_u: [[f64; 2]; 2]) -> [f64; 4] {
        let (lambda, mu) = self.lame();
        let exx = grad_u[0][0];
        let eyy = grad_u[1][1];
        let exy = 0.5 * (grad_u[0][1] + grad_u[1][0]);
        let tr = exx + eyy;
        [
            lambda * tr + 2.0 * mu * exx,
            lambda * tr + 2.0 * mu * eyy,
            2.0 * mu * exy,
            lambda * tr,
        ]
    }

    /// The strains (ε_xx, ε_yy) of uniaxial compression by p (σ_yy = −p, σ_xx = 0, plane strain).
    pub fn uniaxial_strains(&self, p: f64) -> (f64, f64) {
        let (e, nu) = (self.young, self.poisson);
        (nu * (1.0 + nu) * p / e, -(1.0 - nu * nu) * p / e)
    }
}

/// Which block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Block {
    /// A, below the interface.
    Lower,
    /// B, above it.
    Upper,
}

/// The patch test (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactPatch {
    /// L.
    pub length: f64,
    /// H_A (the interface's height) and H_B.
    pub lower_height: f64,
    pub upper_height: f64,
    /// p.
    pub pressure: f64,
    pub lower: Hooke,
    pub upper: Hooke,
}

impl ContactPatch {
    fn material(&self, block: Block) -> Hooke {
        match block {
            Block::Lower => self.lower,
            Block::Upper => self.upper,
        }
    }

    /// [σ_xx, σ_yy, σ_xy, σ_zz] in `block`: [0, −p, 0, −ν p].
    pub fn stress(&self, block: Block) -> [f64; 4] {
        let p = self.pressure;
        [0.0, -p, 0.0, -self.material(block).poisson * p]
    }

    /// The displacement of the material point (x, y) of `block` (module docs).
    pub fn displacement(&self, block: Block, x: f64, y: f64) -> [f64; 2] {
        let (exx_a, eyy_a) = self.lower.uniaxial_strains(self.pressure);
        match block {
            Block::Lower => [exx_a * x, eyy_a * y],
            Block::Upper => {
                let (exx_b, eyy_b) = self.upper.uniaxial_strains(self.pressure);
                [
                    exx_b * x,
                    eyy_a * self.lower_height + eyy_b * (y - self.lower_height),
                ]
            }
        }
    }

    /// The largest |u| component of the exact field (the displacements' scale).
    pub fn displacement_scale(&self) -> f64 {
        let corners = [
            (Block::Lower, self.length, self.lower_height),
            (
                Block::Upper,
                self.length,
                self.lower_height + self.upper_height,
            ),
        ];
        corners
            .iter()
            .flat_map(|&(b, x, y)| self.displacement(b, x, y))
            .fold(0.0, |m: f64, v| m.max(v.abs()))
    }

    /// The consistent nodal contact force on an interface node of tributary length w: p w.
    pub fn nodal_force(&self, weight: f64) -> f64 {
        self.pressure * weight
    }

    /// The total contact force p L.
    pub fn total_force(&self) -> f64 {
        self.pressure * self.length
    }

    /// ε_xx^B − ε_xx^A: the difference of the traces' stretches (module docs).
    pub fn lateral_strain_mismatch(&self) -> f64 {
        self.upper.uniaxial_strains(self.pressure).0 - self.lower.uniaxial_strains(self.pressure).0
    }

    /// p L²/2 · (ε_xx^B − ε_xx^A): the difference of the moments about x = 0 of the two traces'
    /// consistent loads in the current configuration (module docs).
    pub fn moment_mismatch(&self) -> f64 {
        0.5 * self.pressure * self.length * self.length * self.lateral_strain_mismatch()
    }
}

#[cfg(test)]
mod tests {
    //! The exact field meets the supports and the interface, and Hooke's law gives back the
    //! uniaxial stress from its strains.
    use super::*;

    fn patch(lower: Hooke, upper: Hooke) -> ContactPatch {
        ContactPatch {
            length: 2.0,
            lower_height: 1.0,
            upper_height: 1.5,
            pressure: 0.01,
            lower,
            upper,
        }
    }

    #[test]
    fn uniaxial_strains_give_the_uniaxial_stress_through_hookes_law() {
        let m = Hooke {
            young: 3.0,
            poisson: 0.27,
        };
        let (exx, eyy) = m.uniaxial_strains(0.02);
        let s = m.stress([[exx, 0.0], [0.0, eyy]]);
        assert!(s[0].abs() < 1e-17 && (s[1] + 0.02).abs() < 1e-17);
        assert!((s[3] + 0.27 * 0.02).abs() < 1e-17, "σ_zz = ν (σ_xx + σ_yy)");
    }

    #[test]
    fn exact_field_meets_the_supports_and_the_interface() {
        let pa = patch(
            Hooke {
                young: 1.0,
                poisson: 0.3,
            },
            Hooke {
                young: 2.0,
                poisson: 0.2,
            },
        );
        assert_eq!(pa.displacement(Block::Lower, 0.0, 0.7)[0], 0.0);
        assert_eq!(pa.displacement(Block::Lower, 1.3, 0.0)[1], 0.0);
        assert_eq!(pa.displacement(Block::Upper, 0.0, 1.7)[0], 0.0);
        // the interface: both traces at the same height
        let (a, b) = (
            pa.displacement(Block::Lower, 0.4, 1.0),
            pa.displacement(Block::Upper, 1.1, 1.0),
        );
        assert!((a[1] - b[1]).abs() < 1e-18);
        // the mismatch vanishes for equal lateral strains ν(1 + ν)/E
        let nu_b = 0.5 * (-1.0 + (1.0f64 + 4.0 * 0.5 * 0.39).sqrt());
        let same = patch(
            Hooke {
                young: 1.0,
                poisson: 0.3,
            },
            Hooke {
                young: 0.5,
                poisson: nu_b,
            },
        );
        assert!(same.moment_mismatch().abs() < 1e-18);
        assert!(pa.moment_mismatch() < 0.0);
    }
}
