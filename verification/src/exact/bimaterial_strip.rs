//! The two-material strip: a closed form of the quasistatic Kelvin–Voigt plane problem
//! (Fernández & Sofonea 2004, (2.1)–(2.6), without contact) on a body of two materials in series,
//! and of its implicit time steps (docs/quasistatic.md, §The two-material strip).
//!
//! **Setting.** The strip (0, 2L) × (0, H), material 1 on x < L and material 2 on x > L. Each law
//! is the isotropic plane form (Fernández & Sofonea 2004, §4.2)
//!
//!   B_i ε = a1_i (ε11 + ε22) I + a2_i ε,   A_i = τ B_i (the same relaxation time τ in both),
//!
//! with u_x = 0 on x = 0, u_y = 0 on y = 0, the traction (t0, 0) on x = 2L from t > 0 on, the top
//! free, u(0) = 0.
//!
//! **Static solution.** Uniaxial stress σ = t0 e_x ⊗ e_x in both materials satisfies equilibrium,
//! the free top and the loaded end; its strain solves (a1 + a2) ε11 + a1 ε22 = t0,
//! a1 ε11 + (a1 + a2) ε22 = 0 and ε12 = 0:
//!
//!   ε11_i = (a1_i + a2_i) t0 / (a2_i (2 a1_i + a2_i)),   ε22_i = −a1_i t0 / (a2_i (2 a1_i + a2_i)).
//!
//! The displacement u_s = (ε11_1 x, ε22 y) on x ≤ L and (ε11_1 L + ε11_2 (x − L), ε22 y) on
//! x ≥ L is continuous across the interface exactly when ε22_1 = ε22_2 (the *compatibility*
//! [`BimaterialStrip::new`] requires); then it satisfies both supports and is the solution
//! (unique: the supports remove the rigid motions). It is piecewise affine with its kink on
//! x = L: on a mesh with x = L a mesh line, it lies in the P1 space.
//!
//! **Implicit steps.** The implicit scheme A ε((u_n − u_{n−1})/k) + B ε(u_n) = load, with A = τ B,
//! reads B ε(τ (u_n − u_{n−1})/k + u_n) = load; the static problem's uniqueness gives
//! τ (u_n − u_{n−1})/k + u_n = u_s, i.e. u_n − u_s = r (u_{n−1} − u_s) with r = τ/(τ + k), so
//!
//!   u_n = (1 − r^n) u_s.
//!
//! Both the space and the time discretization are exact: the discrete solution on such a mesh
//! equals this to round-off, whatever the triangles, if and only if every triangle carries the
//! law of its side of the interface.

use serde::Serialize;

/// The constants (a1, a2) of an isotropic plane law B ε = a1 tr ε I + a2 ε.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct IsotropicConstants {
    pub a1: f64,
    pub a2: f64,
}

impl IsotropicConstants {
    /// (ε11, ε22) of the uniaxial stress t0 e_x ⊗ e_x (module docs).
    pub fn uniaxial_strain(&self, t0: f64) -> [f64; 2] {
        let d = self.a2 * (2.0 * self.a1 + self.a2);
        [(self.a1 + self.a2) * t0 / d, -self.a1 * t0 / d]
    }
}

/// The two-material strip (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BimaterialStrip {
    /// The interface x = L (the strip is (0, 2L) × (0, H); H does not enter).
    pub interface: f64,
    /// Material on x < L.
    pub first: IsotropicConstants,
    /// Material on x > L.
    pub second: IsotropicConstants,
    /// The end traction t0 (along x).
    pub traction: f64,
    /// τ: A = τ B in both materials.
    pub relaxation_time: f64,
}

impl BimaterialStrip {
    /// The strip, if the two materials are compatible: the same lateral strain ε22 under the
    /// uniaxial stress (to 10⁻¹² relative), the only case in which the uniaxial stress is the
    /// solution.
    pub fn new(
        interface: f64,
        first: IsotropicConstants,
        second: IsotropicConstants,
        traction: f64,
        relaxation_time: f64,
    ) -> Result<Self, String> {
        let (e1, e2) = (
            first.uniaxial_strain(1.0)[1],
            second.uniaxial_strain(1.0)[1],
        );
        if (e1 - e2).abs() > 1e-12 * e1.abs().max(e2.abs()) {
            return Err(format!(
                "incompatible materials: lateral strains {e1} and {e2} per unit traction differ \
                 (a1/(a2 (2 a1 + a2)) must be equal); the uniaxial stress is then not the solution"
            ));
        }
        Ok(Self {
            interface,
            first,
            second,
            traction,
            relaxation_time,
        })
    }

    /// The static solution u_s at (x, y).
    pub fn static_displacement(&self, x: f64, y: f64) -> [f64; 2] {
        let [e1, lateral] = self.first.uniaxial_strain(self.traction);
        let [e2, _] = self.second.uniaxial_strain(self.traction);
        let ux = if x <= self.interface {
            e1 * x
        } else {
            e1 * self.interface + e2 * (x - self.interface)
        };
        [ux, lateral * y]
    }

    /// r = τ/(τ + k) of the implicit scheme with step k.
    pub fn ratio(&self, step: f64) -> f64 {
        self.relaxation_time / (self.relaxation_time + step)
    }

    /// u_n = (1 − r^n) u_s at (x, y), after n implicit steps of length `step`.
    pub fn implicit_step(&self, n: usize, step: f64, x: f64, y: f64) -> [f64; 2] {
        let factor = 1.0 - self.ratio(step).powi(n as i32);
        self.static_displacement(x, y).map(|u| factor * u)
    }
}

#[cfg(test)]
mod tests {
    //! The strip's closed form: the static strain satisfies both constitutive equations of the
    //! uniaxial stress in each material; the displacement is continuous across the interface; the
    //! steps satisfy the implicit recursion τ (u_n − u_{n−1})/k + u_n = u_s; incompatible
    //! materials are refused.
    use super::*;

    fn strip() -> BimaterialStrip {
        let soft = IsotropicConstants { a1: 1.0, a2: 2.0 };
        let stiff = IsotropicConstants { a1: 4.5, a2: 3.0 };
        BimaterialStrip::new(1.0, soft, stiff, 0.6, 0.5).expect("compatible")
    }

    #[test]
    fn the_strain_carries_the_uniaxial_stress_in_each_material() {
        let s = strip();
        for m in [s.first, s.second] {
            let [e11, e22] = m.uniaxial_strain(s.traction);
            let tr = e11 + e22;
            assert!((m.a1 * tr + m.a2 * e11 - s.traction).abs() < 1e-15);
            assert!((m.a1 * tr + m.a2 * e22).abs() < 1e-15);
        }
    }

    #[test]
    fn the_displacement_is_continuous_and_the_steps_follow_the_recursion() {
        let s = strip();
        let (a, b) = (
            s.static_displacement(1.0 - 1e-15, 0.7),
            s.static_displacement(1.0 + 1e-15, 0.7),
        );
        assert!((a[0] - b[0]).abs() < 1e-14 && (a[1] - b[1]).abs() < 1e-15);
        let k = 0.1;
        for n in 1..5 {
            let (un, um) = (
                s.implicit_step(n, k, 1.5, 0.3),
                s.implicit_step(n - 1, k, 1.5, 0.3),
            );
            let us = s.static_displacement(1.5, 0.3);
            for c in 0..2 {
                let lhs = s.relaxation_time * (un[c] - um[c]) / k + un[c];
                assert!((lhs - us[c]).abs() < 1e-14, "{lhs} vs {}", us[c]);
            }
        }
    }

    #[test]
    fn incompatible_materials_are_refused() {
        let soft = IsotropicConstants { a1: 1.0, a2: 2.0 };
        let other = IsotropicConstants { a1: 1.0, a2: 3.0 };
        assert!(BimaterialStrip::new(1.0, soft, other, 0.6, 0.5).is_err());
    }
}
