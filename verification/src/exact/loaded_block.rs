//! The loaded block: the two-dimensional friction benchmark (`docs/dynamic.md` §6).
//!
//! **Setting.** A free plane-strain rectangle (0, L) × (0, H) (no support), pressed into the
//! compliant foundation {y ≤ 0} by a uniform pressure p on its top — a known load — and launched
//! along x with the velocity v0 everywhere. Its bottom is the contact boundary Γ3.
//!
//! **Initial state.** The static state of the compliance contact (BDS (1.8)): uniaxial
//! compression σ_yy = −p, σ_xx = 0 (free sides), so in plane strain ε_yy = −p/E′
//! (E′ = E/(1 − ν²)), ε_xx = ν/(1 − ν) · p/E′, and the bottom penetrates by η = p/r:
//!
//!   u = (ε_xx (x − L/2), −η − (p/E′) y).
//!
//! It is affine (P1 elements represent it exactly, and the nodal loads of the uniform pressures
//! balance it node by node) and it is the equilibrium of the linear law; a hyperelastic law
//! differs from it by O(strain²), which starts a small vertical oscillation.
//!
//! **What is exact.** Once launched the block is a genuinely two-dimensional body: the friction
//! on the bottom and the inertia in the volume form a couple that rocks it on the compliant
//! foundation, the penetration varies along the bottom and in time, and shear waves cross it.
//! No closed form gives its motion. The momentum balance does give one invariant: while every
//! contact point slides in +x, with a constant coefficient μ the friction traction is −μ times
//! the normal traction point by point (BDS (1.12)), so with P_x, P_y the momentum,
//!
//!   dP_x/dt = −μ ∫_Γ3 N,   dP_y/dt = ∫_Γ3 N − p L   ⇒   J = P_x + μ P_y = J(0) − μ p L t,
//!
//! whatever the deformation, the rocking or the distribution of N. The discrete problem keeps it
//! step by step: the sum of the x rows (and of the y rows) of BDS (1.36) cancels the internal
//! forces and leaves (P_n − P_{n−1})/k = the load and contact forces of step n, with the
//! friction of each sliding node −μ times its normal force. For μ1 and μ2 the friction is not
//! proportional to N and no such invariant exists; the cases then check each step's equations
//! with the laws of [`crate::exact::coulomb_friction`] (see the case kind).
//!
//! The rigid-limit deceleration μ(η) p/(ρ H) and stop time t* = ρ H v0/(μ(η) p) set the time
//! scale of the runs (the rocking moves the stop, so they are not gated).

use serde::Serialize;

/// The loaded block (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LoadedBlock {
    pub length: f64,
    pub height: f64,
    pub density: f64,
    pub young: f64,
    pub poisson: f64,
    /// r of the compliance.
    pub stiffness: f64,
    /// p.
    pub pressure: f64,
    pub speed: f64,
}

impl LoadedBlock {
    /// E′ = E/(1 − ν²).
    pub fn plane_strain_modulus(&self) -> f64 {
        self.young / (1.0 - self.poisson * self.poisson)
    }

    /// η = p/r.
    pub fn penetration(&self) -> f64 {
        self.pressure / self.stiffness
    }

    /// m = ρ L H.
    pub fn mass(&self) -> f64 {
        self.density * self.length * self.height
    }

    /// The static displacement at (x, y) (module docs).
    pub fn static_displacement(&self, x: f64, y: f64) -> [f64; 2] {
        let eyy = -self.pressure / self.plane_strain_modulus();
        let nu = self.poisson;
        [
            -nu / (1.0 - nu) * eyy * (x - 0.5 * self.length),
            -self.penetration() + eyy * y,
        ]
    }

    /// J(t) = P_x(0) − μ p L t (P_y(0) = 0): the invariant of a constant μ while every contact
    /// point slides forward.
    pub fn invariant(&self, mu: f64, t: f64) -> f64 {
        self.mass() * self.speed - mu * self.pressure * self.length * t
    }

    /// The rigid-limit stop time ρ H v0/(μ p) for the coefficient μ (the time scale of a run).
    pub fn rigid_stop_time(&self, mu: f64) -> f64 {
        self.density * self.height * self.speed / (mu * self.pressure)
    }
}

#[cfg(test)]
mod tests {
    //! The static state against the equations it claims to solve (σ_xx = 0, σ_yy = −p, the
    //! compliance r η = p at the bottom), and the invariant against the momentum balance of a
    //! rigid block (where P_y = 0).
    use super::*;

    const BLOCK: LoadedBlock = LoadedBlock {
        length: 1.0,
        height: 0.25,
        density: 1.0,
        young: 1e4,
        poisson: 0.3,
        stiffness: 50.0,
        pressure: 0.5,
        speed: 1.0,
    };

    #[test]
    fn static_state_is_uniaxial_compression_balanced_by_the_compliance() {
        let b = BLOCK;
        let (e, nu) = (b.young, b.poisson);
        let lam = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = 0.5 * e / (1.0 + nu);
        let h = 1e-3;
        let d = |i: usize, dx: f64, dy: f64| {
            let plus = b.static_displacement(0.4 + dx, 0.1 + dy)[i];
            let minus = b.static_displacement(0.4 - dx, 0.1 - dy)[i];
            (plus - minus) / (2.0 * h)
        };
        let (exx, eyy) = (d(0, h, 0.0), d(1, 0.0, h));
        assert!(((lam + 2.0 * mu) * exx + lam * eyy).abs() < 1e-9);
        assert!((lam * exx + (lam + 2.0 * mu) * eyy + b.pressure).abs() < 1e-9);
        assert!((d(0, 0.0, h) + d(1, h, 0.0)).abs() < 1e-12, "no shear");
        let p_bottom = 0.0 - b.static_displacement(0.7, 0.0)[1];
        assert!((b.stiffness * p_bottom - b.pressure).abs() < 1e-14);
    }

    #[test]
    fn invariant_is_the_momentum_of_a_rigid_block_under_constant_friction() {
        let b = BLOCK;
        let mu = 0.3;
        // a rigid block: P_y = 0, dP_x/dt = −μ p L
        let t = 0.7;
        let px = b.mass() * (b.speed - mu * b.pressure * b.length / b.mass() * t);
        assert!((b.invariant(mu, t) - px).abs() < 1e-15);
        let t_star = b.rigid_stop_time(mu);
        assert!(b.invariant(mu, t_star).abs() < 1e-15);
    }
}
