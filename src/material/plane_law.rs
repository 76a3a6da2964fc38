//! Plane constitutive laws: τ ↦ σ on 2D symmetric tensors (τ11, τ22, τ12), with their tangents.

use std::fmt::Debug;

use serde::{Deserialize, Serialize};

use crate::error::{require_finite, InputError};
use crate::fem::triangle_p1::Sym2;

/// A constitutive law σ = L(τ) on plane symmetric tensors.
pub trait PlaneLaw: Send + Sync + Debug {
    /// σ = L(τ).
    fn stress(&self, tau: &Sym2) -> Sym2;
    /// dσ = T(τ) dτ: the tangent applied to dτ.
    fn tangent_apply(&self, tau: &Sym2, dtau: &Sym2) -> Sym2;
    /// The linear form, if the law is linear (lets a model factor once).
    fn as_linear(&self) -> Option<&IsotropicLinear> {
        None
    }
    /// A short description for reports.
    fn describe(&self) -> String;
    /// Checks the constants.
    fn validate(&self, field: &str) -> Result<(), InputError>;
}

/// (L τ)_{αβ} = a1 (τ11 + τ22) δ_{αβ} + a2 τ_{αβ}: the isotropic form of the paper's Test 2D
/// (Fernández & Sofonea 2004, §4.2), for A (a1 = μ, a2 = η) and B.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct IsotropicLinear {
    pub a1: f64,
    pub a2: f64,
}

impl IsotropicLinear {
    /// Plane stress elasticity: a1 = E κ/(1 − κ²), a2 = E/(1 + κ) (the paper's B).
    pub fn plane_stress(young: f64, poisson: f64) -> Self {
        Self {
            a1: young * poisson / (1.0 - poisson * poisson),
            a2: young / (1.0 + poisson),
        }
    }

    /// Plane strain elasticity: a1 = E κ/((1 + κ)(1 − 2κ)) (Lamé's λ), a2 = E/(1 + κ) (2G).
    pub fn plane_strain(young: f64, poisson: f64) -> Self {
        Self {
            a1: young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)),
            a2: young / (1.0 + poisson),
        }
    }

    /// The paper's viscosity form (A τ) = μ (τ11 + τ22) δ + η τ.
    pub fn viscosity(mu: f64, eta: f64) -> Self {
        Self { a1: mu, a2: eta }
    }

    /// σ = L τ.
    #[inline]
    pub fn apply(&self, t: &Sym2) -> Sym2 {
        let tr = self.a1 * (t[0] + t[1]);
        [tr + self.a2 * t[0], tr + self.a2 * t[1], self.a2 * t[2]]
    }

    /// The strong-monotonicity constant min over unit τ of τ : L τ (= a2 when a1 ≥ 0,
    /// a2 + 2 a1 when −a2/2 < a1 < 0).
    pub fn coercivity(&self) -> f64 {
        if self.a1 >= 0.0 {
            self.a2
        } else {
            self.a2 + 2.0 * self.a1
        }
    }

    /// Checks that the form is finite and positive definite (a2 > 0, a2 + 2 a1 > 0).
    pub fn check(&self, field: &str) -> Result<(), InputError> {
        require_finite(&format!("{field}.a1"), self.a1)?;
        require_finite(&format!("{field}.a2"), self.a2)?;
        if !(self.a2 > 0.0 && self.a2 + 2.0 * self.a1 > 0.0) {
            return Err(InputError::new(
                field,
                format!("a1 = {}, a2 = {}", self.a1, self.a2),
                "a positive definite form: a2 > 0 and a2 + 2 a1 > 0 (for E, κ: E > 0, −1 < κ < 1/2)",
            ));
        }
        Ok(())
    }
}

impl PlaneLaw for IsotropicLinear {
    fn stress(&self, tau: &Sym2) -> Sym2 {
        self.apply(tau)
    }
    fn tangent_apply(&self, _tau: &Sym2, dtau: &Sym2) -> Sym2 {
        self.apply(dtau)
    }
    fn as_linear(&self) -> Option<&IsotropicLinear> {
        Some(self)
    }
    fn describe(&self) -> String {
        format!("isotropic linear (a1 = {}, a2 = {})", self.a1, self.a2)
    }
    fn validate(&self, field: &str) -> Result<(), InputError> {
        self.check(field)
    }
}

/// The plane-stress von Mises norm |σ| = (σ11² + σ22² − σ11 σ22 + 3 σ12²)^{1/2}
/// (Fernández & Sofonea 2004, §4.2).
pub fn von_mises_plane_stress(s: &Sym2) -> f64 {
    (s[0] * s[0] + s[1] * s[1] - s[0] * s[1] + 3.0 * s[2] * s[2]).sqrt()
}

#[cfg(test)]
mod tests {
    //! Linear isotropic laws: the paper's plane-stress form, plane strain, validation, von Mises.
    use super::*;

    #[test]
    fn paper_plane_stress_constants() {
        let b = IsotropicLinear::plane_stress(100.0, 0.3);
        assert!((b.a1 - 100.0 * 0.3 / 0.91).abs() < 1e-12);
        assert!((b.a2 - 100.0 / 1.3).abs() < 1e-12);
        // uniaxial stress σ11 = E ε11 when ε22 = −κ ε11
        let s = b.apply(&[1.0, -0.3, 0.0]);
        assert!((s[0] - 100.0).abs() < 1e-12 && s[1].abs() < 1e-12);
    }

    #[test]
    fn plane_strain_uses_lame_constants() {
        let b = IsotropicLinear::plane_strain(210.0, 0.25);
        assert!((b.a1 - 84.0).abs() < 1e-12);
        assert!((b.a2 - 168.0).abs() < 1e-12);
    }

    #[test]
    fn indefinite_forms_are_rejected() {
        assert!(IsotropicLinear { a1: 1.0, a2: -1.0 }
            .check("viscosity")
            .is_err());
        assert!(IsotropicLinear { a1: -1.0, a2: 1.5 }
            .check("viscosity")
            .is_err());
        assert!(IsotropicLinear::viscosity(30.0, 20.0)
            .check("viscosity")
            .is_ok());
    }

    #[test]
    fn von_mises_of_pure_shear_and_uniaxial() {
        assert!((von_mises_plane_stress(&[2.0, 0.0, 0.0]) - 2.0).abs() < 1e-15);
        assert!((von_mises_plane_stress(&[0.0, 0.0, 1.0]) - 3f64.sqrt()).abs() < 1e-15);
    }
}
