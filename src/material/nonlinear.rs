//! Nonlinear Kelvin–Voigt operators allowed by (2.10)–(2.11) of Fernández & Sofonea (2004): A
//! Lipschitz and strongly monotone, B Lipschitz. Both are gradients of convex/smooth potentials,
//! so their tangents are symmetric.
//!
//! |τ| is the Frobenius norm (τ11² + τ22² + 2 τ12²)^{1/2}.

use serde::{Deserialize, Serialize};

use crate::error::{require_nonnegative, require_positive, InputError};
use crate::fem::triangle_p1::{contract, Sym2};
use crate::material::plane_law::{IsotropicLinear, PlaneLaw};

fn norm(t: &Sym2) -> f64 {
    contract(t, t).sqrt()
}

/// A saturating viscosity: A(τ) = μ tr(τ) I + η τ + γ tanh(|τ|/τ_c) τ/|τ|.
///
/// The last term is a viscous stress that grows linearly (slope γ/τ_c) for slow flow and saturates
/// at magnitude γ for fast flow — a regularized Bingham/friction-type damper. It is the gradient of
/// the convex potential γ τ_c ln cosh(|τ|/τ_c), so A is strongly monotone (constant η, for μ ≥ 0)
/// and Lipschitz (constant ≤ 2|μ| + η + γ/τ_c).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SaturatingViscosity {
    pub mu: f64,
    pub eta: f64,
    pub gamma: f64,
    pub tau_c: f64,
}

/// g(s) = tanh(s)/s and g'(s)/s, with their series at small s.
fn tanh_ratio(s: f64) -> (f64, f64) {
    if s < 1e-4 {
        let s2 = s * s;
        (
            1.0 - s2 / 3.0 + 2.0 * s2 * s2 / 15.0,
            -2.0 / 3.0 + 8.0 * s2 / 15.0,
        )
    } else {
        let th = s.tanh();
        let g = th / s;
        let dg = (1.0 - th * th) / s - th / (s * s);
        (g, dg / s)
    }
}

impl PlaneLaw for SaturatingViscosity {
    fn stress(&self, t: &Sym2) -> Sym2 {
        let lin = IsotropicLinear::viscosity(self.mu, self.eta).apply(t);
        let (g, _) = tanh_ratio(norm(t) / self.tau_c);
        let c = self.gamma / self.tau_c * g;
        [lin[0] + c * t[0], lin[1] + c * t[1], lin[2] + c * t[2]]
    }

    fn tangent_apply(&self, t: &Sym2, d: &Sym2) -> Sym2 {
        let lin = IsotropicLinear::viscosity(self.mu, self.eta).apply(d);
        let s = norm(t) / self.tau_c;
        let (g, dg_over_s) = tanh_ratio(s);
        // d/dτ [γ/τ_c g(|τ|/τ_c) τ] dτ = γ/τ_c [g dτ + g'(s)/s (τ : dτ)/τ_c² τ]
        let k = self.gamma / self.tau_c;
        let proj = dg_over_s * contract(t, d) / (self.tau_c * self.tau_c);
        [
            lin[0] + k * (g * d[0] + proj * t[0]),
            lin[1] + k * (g * d[1] + proj * t[1]),
            lin[2] + k * (g * d[2] + proj * t[2]),
        ]
    }

    fn describe(&self) -> String {
        format!(
            "saturating viscosity (μ = {}, η = {}, γ = {}, τ_c = {})",
            self.mu, self.eta, self.gamma, self.tau_c
        )
    }

    fn validate(&self, field: &str) -> Result<(), InputError> {
        IsotropicLinear::viscosity(self.mu, self.eta).check(field)?;
        require_nonnegative(&format!("{field}.gamma"), self.gamma)?;
        require_positive(&format!("{field}.tau_c"), self.tau_c)?;
        Ok(())
    }
}

/// A softening elasticity: B(ε) = λ tr(ε) I + 2G (1 − δ |ε|²/(|ε|² + ε_c²)) ε.
///
/// The shear stiffness softens from 2G at small strain towards 2G(1 − δ) at strains well above ε_c
/// (a damaged or yielding solid). Lipschitz for 0 ≤ δ < 1; it is the gradient of the potential
/// W(ε) = λ/2 tr(ε)² + G (|ε|² − δ |ε|² + δ ε_c² ln(1 + |ε|²/ε_c²)), so the tangent is symmetric.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SofteningElasticity {
    pub lambda: f64,
    pub shear: f64,
    pub delta: f64,
    pub eps_c: f64,
}

impl SofteningElasticity {
    /// φ(s²) = 2G(1 − δ s²/(s² + c²)) and its derivative with respect to s².
    fn phi(&self, s2: f64) -> (f64, f64) {
        let c2 = self.eps_c * self.eps_c;
        let d = s2 + c2;
        (
            2.0 * self.shear * (1.0 - self.delta * s2 / d),
            -2.0 * self.shear * self.delta * c2 / (d * d),
        )
    }
}

impl PlaneLaw for SofteningElasticity {
    fn stress(&self, e: &Sym2) -> Sym2 {
        let tr = self.lambda * (e[0] + e[1]);
        let (phi, _) = self.phi(contract(e, e));
        [tr + phi * e[0], tr + phi * e[1], phi * e[2]]
    }

    fn tangent_apply(&self, e: &Sym2, d: &Sym2) -> Sym2 {
        let tr = self.lambda * (d[0] + d[1]);
        let (phi, dphi) = self.phi(contract(e, e));
        // d[φ(|ε|²) ε] = φ dε + 2 φ'(|ε|²) (ε : dε) ε
        let k = 2.0 * dphi * contract(e, d);
        [
            tr + phi * d[0] + k * e[0],
            tr + phi * d[1] + k * e[1],
            phi * d[2] + k * e[2],
        ]
    }

    fn describe(&self) -> String {
        format!(
            "softening elasticity (λ = {}, G = {}, δ = {}, ε_c = {})",
            self.lambda, self.shear, self.delta, self.eps_c
        )
    }

    fn validate(&self, field: &str) -> Result<(), InputError> {
        IsotropicLinear {
            a1: self.lambda,
            a2: 2.0 * self.shear,
        }
        .check(field)?;
        if !(self.delta.is_finite() && (0.0..1.0).contains(&self.delta)) {
            return Err(InputError::new(
                format!("{field}.delta"),
                self.delta,
                "a number in [0, 1)",
            ));
        }
        require_positive(&format!("{field}.eps_c"), self.eps_c)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! Nonlinear laws: tangents against central finite differences at several states (including
    //! near zero, where the series branch is used), monotonicity of the saturating viscosity, and
    //! the saturation limit.
    use super::*;

    fn fd_check(law: &dyn PlaneLaw, t: Sym2) {
        let eps = 1e-6;
        for k in 0..3 {
            let mut d = [0.0; 3];
            d[k] = 1.0;
            let mut tp = t;
            let mut tm = t;
            tp[k] += eps;
            tm[k] -= eps;
            let (sp, sm) = (law.stress(&tp), law.stress(&tm));
            let tan = law.tangent_apply(&t, &d);
            for i in 0..3 {
                let fd = (sp[i] - sm[i]) / (2.0 * eps);
                assert!(
                    (fd - tan[i]).abs() < 1e-6 * (1.0 + tan[i].abs()),
                    "{}: at {t:?}, component {i}/{k}: fd {fd} vs {}",
                    law.describe(),
                    tan[i]
                );
            }
        }
    }

    #[test]
    fn tangents_match_finite_differences() {
        let visc = SaturatingViscosity {
            mu: 3.0,
            eta: 2.0,
            gamma: 5.0,
            tau_c: 0.1,
        };
        let soft = SofteningElasticity {
            lambda: 4.0,
            shear: 3.0,
            delta: 0.6,
            eps_c: 0.05,
        };
        for t in [
            [0.3, -0.2, 0.15],
            [1e-7, 2e-7, -1e-7],
            [0.02, 0.01, 0.0],
            [5.0, 1.0, -2.0],
        ] {
            fd_check(&visc, t);
            fd_check(&soft, t);
        }
    }

    #[test]
    fn saturating_viscosity_is_strongly_monotone_with_constant_eta() {
        let a = SaturatingViscosity {
            mu: 1.0,
            eta: 2.0,
            gamma: 10.0,
            tau_c: 0.05,
        };
        let pts = [
            [0.1, -0.3, 0.2],
            [0.0, 0.01, -0.02],
            [2.0, 1.0, 0.5],
            [-1.0, 0.4, 0.0],
        ];
        for x in &pts {
            for y in &pts {
                let (sx, sy) = (a.stress(x), a.stress(y));
                let d = [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
                let ds = [sx[0] - sy[0], sx[1] - sy[1], sx[2] - sy[2]];
                assert!(contract(&ds, &d) >= 2.0 * contract(&d, &d) - 1e-12);
            }
        }
    }

    #[test]
    fn saturated_term_tends_to_gamma() {
        let a = SaturatingViscosity {
            mu: 0.0,
            eta: 1e-9,
            gamma: 7.0,
            tau_c: 1e-3,
        };
        let t = [0.0, 0.0, 1.0 / 2f64.sqrt()]; // |τ| = 1
        let s = a.stress(&t);
        assert!((contract(&s, &s).sqrt() - 7.0).abs() < 1e-6);
    }

    #[test]
    fn invalid_constants_are_named() {
        let e = SofteningElasticity {
            lambda: 1.0,
            shear: 1.0,
            delta: 1.5,
            eps_c: 0.1,
        }
        .validate("elasticity")
        .unwrap_err();
        assert_eq!(e.field, "elasticity.delta");
    }
}
