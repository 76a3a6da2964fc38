//! The in-plane stress of the spinning annular disc (plane stress, clamped at r = a: u_r(a) = 0;
//! free at r = b: N_r(b) = 0), whose geometric stiffness stiffens the transverse vibration
//! (centrifugal stiffening; off in the paper's example, an option here).
//!
//! Equilibrium d(r N_r)/dr − N_θ + ρh Ω² r² = 0 with the plane-stress law gives (Timoshenko &
//! Goodier, the rotating disc)
//!
//! ```text
//!   N_r = ρhΩ² [c1 + c2/r² − (3 + ν) r²/8],   N_θ = ρhΩ² [c1 − c2/r² − (1 + 3ν) r²/8],
//! ```
//!
//! with u_r ∝ N_θ − ν N_r = 0 at r = a and N_r(b) = 0:
//! (1 − ν) c1 − (1 + ν) c2/a² = (1 − ν²) a²/8 and c1 + c2/b² = (3 + ν) b²/8
//! (for a = 0: c2 = 0, c1 = (3 + ν) b²/8, the solid disc). The energy
//! ½ ∫∫ [N_r w_r² + N_θ (w_φ/r)²] r dr dφ adds Ω² K_σ to the stiffness.

/// The stress resultants per unit ρhΩ²: r ↦ (N_r, N_θ) / (ρhΩ²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinningDiscStress {
    c1: f64,
    c2: f64,
    poisson: f64,
}

impl SpinningDiscStress {
    /// The stress of the annulus a ≤ r ≤ b (a ≥ 0) with Poisson's ratio ν.
    pub fn new(a: f64, b: f64, poisson: f64) -> Self {
        let nu = poisson;
        if a == 0.0 {
            return Self {
                c1: (3.0 + nu) * b * b / 8.0,
                c2: 0.0,
                poisson,
            };
        }
        // [(1 − ν), −(1 + ν)/a²; 1, 1/b²] (c1, c2) = ((1 − ν²) a²/8, (3 + ν) b²/8)
        let (m11, m12, m21, m22) = (1.0 - nu, -(1.0 + nu) / (a * a), 1.0, 1.0 / (b * b));
        let (r1, r2) = ((1.0 - nu * nu) * a * a / 8.0, (3.0 + nu) * b * b / 8.0);
        let det = m11 * m22 - m12 * m21;
        Self {
            c1: (r1 * m22 - m12 * r2) / det,
            c2: (m11 * r2 - m21 * r1) / det,
            poisson,
        }
    }

    /// N_r / (ρhΩ²) at r.
    pub fn radial(&self, r: f64) -> f64 {
        self.c1 + self.c2 / (r * r) - (3.0 + self.poisson) * r * r / 8.0
    }

    /// N_θ / (ρhΩ²) at r.
    pub fn hoop(&self, r: f64) -> f64 {
        self.c1 - self.c2 / (r * r) - (1.0 + 3.0 * self.poisson) * r * r / 8.0
    }
}

#[cfg(test)]
mod tests {
    //! Setting: the annulus a = 0.3, b = 1.2, ν = 0.3, and the solid disc. Goal: the closed form
    //! satisfies equilibrium (by central differences), u_r(a) = 0 and N_r(b) = 0; the solid
    //! disc's centre stress is (3 + ν) b²/8 in both directions.
    use super::*;

    #[test]
    fn closed_form_satisfies_equilibrium_and_edge_conditions() {
        let (a, b, nu) = (0.3, 1.2, 0.3);
        let s = SpinningDiscStress::new(a, b, nu);
        let h = 1e-5;
        for &r in &[0.35, 0.6, 1.0, 1.15] {
            let d = ((r + h) * s.radial(r + h) - (r - h) * s.radial(r - h)) / (2.0 * h);
            assert!((d - s.hoop(r) + r * r).abs() < 1e-8, "r = {r}");
        }
        assert!((s.hoop(a) - nu * s.radial(a)).abs() < 1e-14);
        assert!(s.radial(b).abs() < 1e-14);
        let solid = SpinningDiscStress::new(0.0, b, nu);
        assert_eq!(solid.radial(1e-100), solid.hoop(1e-100));
        assert!((solid.radial(1e-100) - (3.0 + nu) * b * b / 8.0).abs() < 1e-15);
        assert!(solid.radial(b).abs() < 1e-15);
    }
}
