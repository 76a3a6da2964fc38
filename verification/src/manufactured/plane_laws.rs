//! The constitutive laws of the plane manufactured solutions, written a second time, from the
//! formulas, independently of the solver's law objects (`contactlab::material`), and generic over
//! dual numbers so that Div σ is the automatic derivative of σ(x, y, t) itself.
//!
//! Tensors are plane symmetric tensors stored as (τ11, τ22, τ12); |τ| = (τ11² + τ22² + 2 τ12²)^½
//! is the Frobenius norm. The laws (docs/quasistatic.md):
//!
//! - plane stress Hooke (Fernández & Sofonea 2004, §4.2, the B of Test 2D), written in the
//!   engineering form σ11 = E/(1 − κ²) (τ11 + κ τ22), σ22 = E/(1 − κ²) (κ τ11 + τ22),
//!   σ12 = E/(1 + κ) τ12;
//! - plane strain Hooke, σ11 = E/((1 + κ)(1 − 2κ)) ((1 − κ) τ11 + κ τ22), σ22 likewise,
//!   σ12 = E/(1 + κ) τ12;
//! - the paper's viscosity form (§4.2), (A τ)_{αβ} = μ (τ11 + τ22) δ_{αβ} + η τ_{αβ};
//! - a saturating viscosity allowed by (2.10): A(τ) = μ tr τ I + η τ + γ tanh(|τ|/τ_c) τ/|τ|,
//!   the gradient of Φ(τ) = μ/2 (tr τ)² + η/2 |τ|² + γ τ_c ln cosh(|τ|/τ_c);
//! - a softening elasticity allowed by (2.11): B(ε) = λ tr ε I + 2G (1 − δ |ε|²/(|ε|² + ε_c²)) ε,
//!   the gradient of W(ε) = λ/2 (tr ε)² + G ((1 − δ)|ε|² + δ ε_c² ln(1 + |ε|²/ε_c²)).
//!
//! The tests compare every law with the solver's at pseudo-random points — values, and the
//! automatic tangent against the solver's `tangent_apply` — and the two nonlinear laws with the
//! gradients of their potentials. That comparison is the cross-check; the verification data use
//! only the laws of this file.

use std::sync::Arc;

use num_dual::DualNum;

use contactlab::material::nonlinear::{SaturatingViscosity, SofteningElasticity};
use contactlab::material::plane_law::{IsotropicLinear, PlaneLaw};

/// A plane symmetric tensor (τ11, τ22, τ12) on any (dual) number type.
pub type Sym<D> = [D; 3];

/// A constitutive law of the manufactured solutions, by its constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MaterialLaw {
    /// Plane stress Hooke law with Young's modulus E and Poisson's ratio κ.
    PlaneStress { young: f64, poisson: f64 },
    /// Plane strain Hooke law with E and κ.
    PlaneStrain { young: f64, poisson: f64 },
    /// The paper's viscosity form μ tr τ I + η τ.
    Viscosity { mu: f64, eta: f64 },
    /// μ tr τ I + η τ + γ tanh(|τ|/τ_c) τ/|τ|.
    Saturating {
        mu: f64,
        eta: f64,
        gamma: f64,
        tau_c: f64,
    },
    /// λ tr ε I + 2G (1 − δ |ε|²/(|ε|² + ε_c²)) ε.
    Softening {
        lambda: f64,
        shear: f64,
        delta: f64,
        eps_c: f64,
    },
}

/// |τ|² = τ11² + τ22² + 2 τ12².
pub fn norm2<D: DualNum<Primitive = f64> + Copy>(t: &Sym<D>) -> D {
    t[0] * t[0] + t[1] * t[1] + t[2] * t[2] * 2.0
}

/// tanh(s)/s as a function of s² (its Taylor series 1 − s²/3 + 2s⁴/15 − 17s⁶/315 below
/// s² = 1e-6, where tanh(s)/s loses digits and its derivative at s = 0 is 0/0).
fn tanh_over<D: DualNum<Primitive = f64> + Copy>(s2: D) -> D {
    if s2.re() < 1e-6 {
        D::one() - s2 / 3.0 + s2 * s2 * (2.0 / 15.0) - s2 * s2 * s2 * (17.0 / 315.0)
    } else {
        let s = s2.sqrt();
        s.tanh() / s
    }
}

impl MaterialLaw {
    /// σ = L(τ) on any (dual) number type, from the formulas of the module documentation.
    pub fn stress<D: DualNum<Primitive = f64> + Copy>(&self, t: &Sym<D>) -> Sym<D> {
        match *self {
            MaterialLaw::PlaneStress { young, poisson } => {
                let c = young / (1.0 - poisson * poisson);
                [
                    (t[0] + t[1] * poisson) * c,
                    (t[0] * poisson + t[1]) * c,
                    t[2] * (young / (1.0 + poisson)),
                ]
            }
            MaterialLaw::PlaneStrain { young, poisson } => {
                let c = young / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
                [
                    (t[0] * (1.0 - poisson) + t[1] * poisson) * c,
                    (t[0] * poisson + t[1] * (1.0 - poisson)) * c,
                    t[2] * (young / (1.0 + poisson)),
                ]
            }
            MaterialLaw::Viscosity { mu, eta } => {
                let tr = (t[0] + t[1]) * mu;
                [tr + t[0] * eta, tr + t[1] * eta, t[2] * eta]
            }
            MaterialLaw::Saturating {
                mu,
                eta,
                gamma,
                tau_c,
            } => {
                // γ tanh(|τ|/τ_c) τ/|τ| = (γ/τ_c) [tanh(s)/s] τ with s = |τ|/τ_c
                let c = tanh_over(norm2(t) / (tau_c * tau_c)) * (gamma / tau_c);
                let tr = (t[0] + t[1]) * mu;
                [
                    tr + t[0] * eta + t[0] * c,
                    tr + t[1] * eta + t[1] * c,
                    t[2] * eta + t[2] * c,
                ]
            }
            MaterialLaw::Softening {
                lambda,
                shear,
                delta,
                eps_c,
            } => {
                let n2 = norm2(t);
                let phi = (D::one() - n2 * delta / (n2 + eps_c * eps_c)) * (2.0 * shear);
                let tr = (t[0] + t[1]) * lambda;
                [tr + t[0] * phi, tr + t[1] * phi, t[2] * phi]
            }
        }
    }

    /// The potential whose gradient the law is (Φ of the module documentation; for the linear
    /// laws ½ τ : L τ), used by the tests to check the stress formulas a second way.
    pub fn potential<D: DualNum<Primitive = f64> + Copy>(&self, t: &Sym<D>) -> D {
        match *self {
            MaterialLaw::Saturating {
                mu,
                eta,
                gamma,
                tau_c,
            } => {
                let tr = t[0] + t[1];
                let s = norm2(t).sqrt() / tau_c;
                tr * tr * (mu / 2.0) + norm2(t) * (eta / 2.0) + s.cosh().ln() * (gamma * tau_c)
            }
            MaterialLaw::Softening {
                lambda,
                shear,
                delta,
                eps_c,
            } => {
                let tr = t[0] + t[1];
                let n2 = norm2(t);
                let c2 = eps_c * eps_c;
                tr * tr * (lambda / 2.0)
                    + (n2 * (1.0 - delta) + (n2 / c2).ln_1p() * (delta * c2)) * shear
            }
            _ => {
                let s = self.stress(t);
                (s[0] * t[0] + s[1] * t[1] + s[2] * t[2] * 2.0) * 0.5
            }
        }
    }

    /// The solver's law object with the same constants (the problem handed to the solver is
    /// built with it; the verification data never call it).
    pub fn solver_law(&self) -> Arc<dyn PlaneLaw> {
        match *self {
            MaterialLaw::PlaneStress { young, poisson } => {
                Arc::new(IsotropicLinear::plane_stress(young, poisson))
            }
            MaterialLaw::PlaneStrain { young, poisson } => {
                Arc::new(IsotropicLinear::plane_strain(young, poisson))
            }
            MaterialLaw::Viscosity { mu, eta } => Arc::new(IsotropicLinear::viscosity(mu, eta)),
            MaterialLaw::Saturating {
                mu,
                eta,
                gamma,
                tau_c,
            } => Arc::new(SaturatingViscosity {
                mu,
                eta,
                gamma,
                tau_c,
            }),
            MaterialLaw::Softening {
                lambda,
                shear,
                delta,
                eps_c,
            } => Arc::new(SofteningElasticity {
                lambda,
                shear,
                delta,
                eps_c,
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    //! The cross-check: the laws written here against the solver's law objects at pseudo-random
    //! tensors (values, and the automatic tangent in a random direction against the solver's
    //! `tangent_apply`), and the nonlinear laws against the gradients of their potentials. A wrong
    //! constant or term on either side fails here; the manufactured data use only this file's laws.
    use super::*;
    use num_dual::Dual64;

    /// Deterministic points in [−1, 1) (the MMIX linear congruential generator).
    struct Points(u64);
    impl Points {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            2.0 * ((self.0 >> 11) as f64 / (1u64 << 53) as f64) - 1.0
        }
        /// A tensor of magnitude about `scale`.
        fn tensor(&mut self, scale: f64) -> [f64; 3] {
            [
                scale * self.next(),
                scale * self.next(),
                scale * self.next(),
            ]
        }
    }

    /// The laws of the manufactured solutions (and the paper's Test 2D constants).
    pub(crate) fn laws() -> Vec<MaterialLaw> {
        vec![
            MaterialLaw::PlaneStress {
                young: 10.0,
                poisson: 0.3,
            },
            MaterialLaw::PlaneStress {
                young: 100.0,
                poisson: 0.3,
            },
            MaterialLaw::PlaneStrain {
                young: 10.0,
                poisson: 0.3,
            },
            MaterialLaw::PlaneStrain {
                young: 210.0,
                poisson: 0.25,
            },
            MaterialLaw::Viscosity { mu: 3.0, eta: 2.0 },
            MaterialLaw::Saturating {
                mu: 3.0,
                eta: 2.0,
                gamma: 1.0,
                tau_c: 0.1,
            },
            MaterialLaw::Softening {
                lambda: 5.0,
                shear: 4.0,
                delta: 0.5,
                eps_c: 0.05,
            },
        ]
    }

    /// max_i |a_i − b_i| / (1 + max |b|).
    fn rel(a: &[f64; 3], b: &[f64; 3]) -> f64 {
        let scale = 1.0 + b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        (0..3).fold(0.0f64, |m, i| m.max((a[i] - b[i]).abs())) / scale
    }

    #[test]
    fn independent_laws_agree_with_the_solver_values_and_tangents_at_random_points() {
        let mut pts = Points(2024);
        let mut worst_value = 0.0f64;
        let mut worst_tangent = 0.0f64;
        for law in laws() {
            let solver = law.solver_law();
            // magnitudes across the linear, transition and saturated/softened ranges
            for scale in [1e-7, 1e-3, 0.05, 0.3, 2.0] {
                for _ in 0..40 {
                    let t = pts.tensor(scale);
                    let d = pts.tensor(1.0);
                    let ours = law.stress(&t);
                    worst_value = worst_value.max(rel(&ours, &solver.stress(&t)));
                    // the tangent in direction d: σ(τ + ε d) on dual numbers
                    let td: Sym<Dual64> = std::array::from_fn(|i| Dual64::new(t[i], d[i]));
                    let s = law.stress(&td);
                    let ad = [s[0].eps, s[1].eps, s[2].eps];
                    worst_tangent = worst_tangent.max(rel(&ad, &solver.tangent_apply(&t, &d)));
                }
            }
        }
        // both sides evaluate a handful of operations on numbers of size ≤ ~300: round-off
        assert!(worst_value < 1e-13, "values differ by {worst_value:e}");
        assert!(
            worst_tangent < 1e-11,
            "tangents differ by {worst_tangent:e}"
        );
    }

    #[test]
    fn every_stress_is_the_gradient_of_its_potential() {
        // σ11 = ∂Φ/∂τ11, σ22 = ∂Φ/∂τ22, σ12 = ½ ∂Φ/∂τ12 (τ12 counts twice in τ : τ)
        let mut pts = Points(7);
        for law in laws() {
            for scale in [1e-3, 0.05, 0.3, 2.0] {
                for _ in 0..20 {
                    let t = pts.tensor(scale);
                    let s = law.stress(&t);
                    for (i, factor) in [(0, 1.0), (1, 1.0), (2, 0.5)] {
                        let td: Sym<Dual64> = std::array::from_fn(|j| {
                            Dual64::new(t[j], if i == j { 1.0 } else { 0.0 })
                        });
                        let g = law.potential(&td).eps * factor;
                        assert!(
                            (g - s[i]).abs() < 1e-12 * (1.0 + s[i].abs()),
                            "{law:?} at {t:?}, component {i}: ∇Φ {g} vs σ {}",
                            s[i]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn plane_stress_is_uniaxial_and_plane_strain_has_lame_constants() {
        // uniaxial stress: ε22 = −κ ε11 gives σ22 = 0 and σ11 = E ε11
        let s = MaterialLaw::PlaneStress {
            young: 100.0,
            poisson: 0.3,
        }
        .stress(&[1.0f64, -0.3, 0.0]);
        assert!((s[0] - 100.0).abs() < 1e-12 && s[1].abs() < 1e-12);
        // E = 210, κ = 0.25: λ = 84, 2G = 168
        let s = MaterialLaw::PlaneStrain {
            young: 210.0,
            poisson: 0.25,
        }
        .stress(&[1.0f64, 0.0, 1.0]);
        assert!((s[0] - (84.0 + 168.0)).abs() < 1e-12);
        assert!((s[1] - 84.0).abs() < 1e-12 && (s[2] - 168.0).abs() < 1e-12);
    }
}
