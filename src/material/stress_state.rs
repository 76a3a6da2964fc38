//! The strain and stress a result file reports per element, in one place for every plane model:
//! the in-plane tensors and the out-of-plane stress σ_33, and the von Mises equivalent stress
//!
//!   σ_vM = ( ½ [(σ_11 − σ_22)² + (σ_22 − σ_33)² + (σ_33 − σ_11)²] + 3 σ_12² )^{1/2}
//!
//! of the 3D tensor with σ_13 = σ_23 = 0 (plane stress: σ_33 = 0, where it reduces to the paper's
//! (σ11² + σ22² − σ11 σ22 + 3 σ12²)^{1/2}, Fernández & Sofonea 2004, §4.2; plane strain: σ_33 as
//! the law gives it).
//!
//! Measures of a hyperelastic plane-strain body (F = I + ∇u constant on a P1 triangle, F_33 = 1):
//! - the small-strain law: ε = sym(F − I) and σ = P (the linear theory's stress), σ_33 = λ tr ε;
//! - the finite-strain laws: the Green–Lagrange strain E = ½ (FᵀF − I) and the Cauchy stress
//!   σ = J⁻¹ P Fᵀ, J = det F, σ_33 = J⁻¹ S_33 ([`Hyperelastic2d::out_of_plane_stress`]).

use nalgebra::Matrix2;

use crate::material::hyperelastic::Hyperelastic2d;
use crate::material::plane_law::IsotropicLinear;

/// The reported state of one element: strain and stress as (11, 22, 12) plus σ_33.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StressState {
    /// The in-plane strain (ε or E) as (11, 22, 12); the out-of-plane strain is 0 in plane strain.
    pub strain: [f64; 3],
    /// The in-plane stress as (11, 22, 12).
    pub stress: [f64; 3],
    /// The out-of-plane stress σ_33.
    pub stress_33: f64,
}

impl StressState {
    /// The von Mises equivalent stress of (σ_11, σ_22, σ_33, σ_12) (module docs).
    pub fn von_mises(&self) -> f64 {
        von_mises(&self.stress, self.stress_33)
    }
}

/// σ_vM of the 3D tensor (σ_11, σ_22, σ_33, σ_12) with σ_13 = σ_23 = 0 (module docs).
pub fn von_mises(s: &[f64; 3], s33: f64) -> f64 {
    let (a, b, c) = (s[0] - s[1], s[1] - s33, s33 - s[0]);
    (0.5 * (a * a + b * b + c * c) + 3.0 * s[2] * s[2]).sqrt()
}

/// The state of an element of a hyperelastic plane-strain body with deformation gradient `f`
/// (the measures of the module docs).
pub fn hyperelastic_state(law: &dyn Hyperelastic2d, f: &Matrix2<f64>) -> StressState {
    let p = law.piola(f);
    let s33 = law.out_of_plane_stress(f);
    let (strain, sigma) = if law.is_small_strain() {
        let h = f - Matrix2::identity();
        (0.5 * (h + h.transpose()), p)
    } else {
        let e = 0.5 * (f.transpose() * f - Matrix2::identity());
        (e, p * f.transpose() / f.determinant())
    };
    StressState {
        strain: [strain[(0, 0)], strain[(1, 1)], strain[(0, 1)]],
        // the Cauchy stress is symmetric; its two off-diagonal entries are averaged against
        // round-off
        stress: [
            sigma[(0, 0)],
            sigma[(1, 1)],
            0.5 * (sigma[(0, 1)] + sigma[(1, 0)]),
        ],
        stress_33: s33,
    }
}

/// σ_33 of a linear isotropic law L τ = a1 tr τ I + a2 τ read as a 3D isotropic law in plane
/// strain (τ_33 = 0): σ_33 = a1 tr τ (= κ (σ_11 + σ_22) for the plane-strain constants
/// a1 = λ, a2 = 2G).
pub fn plane_strain_out_of_plane(law: &IsotropicLinear, tau: &[f64; 3]) -> f64 {
    law.a1 * (tau[0] + tau[1])
}

#[cfg(test)]
mod tests {
    //! The reported stress of each hyperelastic law against its definition: σ_33 = κ (σ11 + σ22)
    //! for the linear law, the Cauchy stress J⁻¹PFᵀ symmetric and equal to the linear one at small
    //! strain, and von Mises against its plane-stress reduction and a uniaxial stress.
    use super::*;
    use crate::material::hyperelastic::{LinearElastic, NeoHooke, StVenantKirchhoff};

    fn f(eps: f64) -> Matrix2<f64> {
        Matrix2::new(1.0 + 0.3 * eps, 0.2 * eps, -0.1 * eps, 1.0 - 0.4 * eps)
    }

    #[test]
    fn linear_out_of_plane_stress_is_poisson_times_in_plane_trace() {
        let (young, nu) = (210.0, 0.3);
        let law = LinearElastic::from_young_poisson(young, nu).unwrap();
        let s = hyperelastic_state(&law, &f(1e-2));
        assert!((s.stress_33 - nu * (s.stress[0] + s.stress[1])).abs() < 1e-12);
        let b = IsotropicLinear::plane_strain(young, nu);
        let sb = b.apply(&s.strain);
        assert!((plane_strain_out_of_plane(&b, &s.strain) - nu * (sb[0] + sb[1])).abs() < 1e-12);
    }

    #[test]
    fn finite_strain_laws_agree_with_the_linear_law_at_small_strain() {
        let lin = LinearElastic::from_lame(2.0, 1.5).unwrap();
        let svk = StVenantKirchhoff::from_lame(2.0, 1.5).unwrap();
        let nh = NeoHooke::from_lame(2.0, 1.5).unwrap();
        let eps = 1e-6;
        let l = hyperelastic_state(&lin, &f(eps));
        for s in [
            hyperelastic_state(&svk, &f(eps)),
            hyperelastic_state(&nh, &f(eps)),
        ] {
            for i in 0..3 {
                assert!((s.stress[i] - l.stress[i]).abs() < 1e-10, "{s:?} {l:?}");
                assert!((s.strain[i] - l.strain[i]).abs() < 1e-11);
            }
            assert!((s.stress_33 - l.stress_33).abs() < 1e-10);
        }
    }

    #[test]
    fn von_mises_reduces_to_the_plane_stress_norm_and_to_a_uniaxial_stress() {
        let s = [3.0, -1.0, 0.5];
        let plane = crate::material::plane_law::von_mises_plane_stress(&s);
        assert!((von_mises(&s, 0.0) - plane).abs() < 1e-14);
        // uniaxial σ_33 = 2: σ_vM = 2
        assert!((von_mises(&[0.0, 0.0, 0.0], 2.0) - 2.0).abs() < 1e-14);
        // a hydrostatic state has none
        assert!(von_mises(&[1.5, 1.5, 0.0], 1.5).abs() < 1e-14);
    }
}
