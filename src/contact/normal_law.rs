//! Normal damped response: −σ_ν = p_ν(u̇_ν) on Γ3 (Fernández & Sofonea 2004, (2.5)).
//!
//! A law gives the value p_ν(r) and an element of its generalized (Clarke) derivative, which is all
//! a semismooth Newton method needs. The paper's three laws:
//!
//! - (2.7) `Linear`:      p_ν(r) = β r                 (granular or sand foundation)
//! - (2.8) `Lubricated`:  p_ν(r) = β r_+ + p0(t)       (oil layer with pressure p0; damps only
//!   when the surface moves towards the foundation)
//! - (2.9) `Prescribed`:  p_ν(r) = S(t)                (prescribed normal stress)
//!
//! Assumptions (2.13): p_ν Lipschitz and monotone; p0 ≥ 0, β ≥ 0.

use std::fmt;

use crate::error::{require_nonnegative, InputError};
use crate::field::Field;

/// Where and when a law is evaluated (a law may depend on the point of Γ3 and on time).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpaceTime {
    pub x: f64,
    pub y: f64,
    pub t: f64,
}

/// A normal damped response law p_ν(r) on Γ3, r the normal velocity.
pub trait NormalLaw: Send + Sync + fmt::Debug {
    /// p_ν(r) at `at`.
    fn value(&self, r: f64, at: SpaceTime) -> f64;
    /// An element of the generalized derivative ∂p_ν(r) at `at`.
    fn derivative(&self, r: f64, at: SpaceTime) -> f64;
    /// An upper bound of the Lipschitz constant of r ↦ p_ν(r) (the slope bound).
    fn lipschitz_constant(&self) -> f64;
    /// Whether the law depends on time (p0(t), S(t)).
    fn depends_on_time(&self) -> bool;
    /// Whether the law is linear in r (p_ν(r) = β r + s): the condensed equation is solved in one step.
    fn is_affine(&self) -> bool;
    /// Checks the data (β ≥ 0, finite constants).
    fn validate(&self) -> Result<(), InputError>;
    /// A primitive Ψ of the law (Ψ′ = p_ν), if known: then the contact term is the gradient of
    /// Σ W Ψ(r) and a Newton method can globalize on the energy instead of the residual norm.
    fn potential(&self, _r: f64, _at: SpaceTime) -> Option<f64> {
        None
    }
    /// The range (inf, sup) of r ↦ p_ν(r) at `at` (±∞ when unbounded). A body whose only support
    /// in some direction is the contact has an equilibrium only if the load lies in the range of the
    /// contact forces, which this bounds.
    fn range(&self, _at: SpaceTime) -> (f64, f64) {
        (f64::NEG_INFINITY, f64::INFINITY)
    }
    /// The law as one of the paper's laws (2.7)–(2.9), if it is one (lets a caller recognise the
    /// standard laws, e.g. to pick an exact solution).
    fn as_foundation_law(&self) -> Option<&FoundationLaw> {
        None
    }
}

/// The paper's laws (2.7)–(2.9).
#[derive(Debug, Clone)]
pub enum FoundationLaw {
    /// (2.7) p_ν(r) = β r.
    Linear { beta: f64 },
    /// (2.8) p_ν(r) = β r_+ + p0(t).
    Lubricated { beta: f64, p0: Field },
    /// (2.9) p_ν(r) = S(t).
    Prescribed { stress: Field },
}

impl FoundationLaw {
    fn source(&self, at: SpaceTime) -> f64 {
        match self {
            FoundationLaw::Linear { .. } => 0.0,
            FoundationLaw::Lubricated { p0, .. } => p0.eval(at.x, at.y, at.t),
            FoundationLaw::Prescribed { stress } => stress.eval(at.x, at.y, at.t),
        }
    }
}

impl NormalLaw for FoundationLaw {
    #[inline]
    fn value(&self, r: f64, at: SpaceTime) -> f64 {
        match self {
            FoundationLaw::Linear { beta } => beta * r,
            FoundationLaw::Lubricated { beta, .. } => beta * r.max(0.0) + self.source(at),
            FoundationLaw::Prescribed { .. } => self.source(at),
        }
    }

    /// For r ↦ r_+ the generalized derivative at r = 0 is [0, 1]; we take 0 (Heaviside H(r) with
    /// H(0) = 0), which makes the first Newton step from r = 0 exact on the inactive branch.
    #[inline]
    fn derivative(&self, r: f64, _at: SpaceTime) -> f64 {
        match self {
            FoundationLaw::Linear { beta } => *beta,
            FoundationLaw::Lubricated { beta, .. } => {
                if r > 0.0 {
                    *beta
                } else {
                    0.0
                }
            }
            FoundationLaw::Prescribed { .. } => 0.0,
        }
    }

    fn lipschitz_constant(&self) -> f64 {
        match self {
            FoundationLaw::Linear { beta } | FoundationLaw::Lubricated { beta, .. } => *beta,
            FoundationLaw::Prescribed { .. } => 0.0,
        }
    }

    fn depends_on_time(&self) -> bool {
        match self {
            FoundationLaw::Linear { .. } => false,
            FoundationLaw::Lubricated { p0, .. } => p0.dependence().t,
            FoundationLaw::Prescribed { stress } => stress.dependence().t,
        }
    }

    fn is_affine(&self) -> bool {
        match self {
            FoundationLaw::Linear { .. } | FoundationLaw::Prescribed { .. } => true,
            FoundationLaw::Lubricated { beta, .. } => *beta == 0.0,
        }
    }

    fn validate(&self) -> Result<(), InputError> {
        match self {
            FoundationLaw::Linear { beta } => {
                require_nonnegative("foundation.beta", *beta)?;
            }
            FoundationLaw::Lubricated { beta, p0 } => {
                require_nonnegative("foundation.beta", *beta)?;
                p0.validate("foundation.p0")?;
                if let Some(c) = p0.as_constant() {
                    require_nonnegative("foundation.p0", c)?;
                }
            }
            FoundationLaw::Prescribed { stress } => stress.validate("foundation.stress")?,
        }
        Ok(())
    }

    fn as_foundation_law(&self) -> Option<&FoundationLaw> {
        Some(self)
    }

    fn potential(&self, r: f64, at: SpaceTime) -> Option<f64> {
        Some(match self {
            FoundationLaw::Linear { beta } => 0.5 * beta * r * r,
            FoundationLaw::Lubricated { beta, .. } => {
                let rp = r.max(0.0);
                0.5 * beta * rp * rp + self.source(at) * r
            }
            FoundationLaw::Prescribed { .. } => self.source(at) * r,
        })
    }

    fn range(&self, at: SpaceTime) -> (f64, f64) {
        match self {
            FoundationLaw::Linear { beta } if *beta > 0.0 => (f64::NEG_INFINITY, f64::INFINITY),
            FoundationLaw::Linear { .. } => (0.0, 0.0),
            FoundationLaw::Lubricated { beta, .. } => {
                let p0 = self.source(at);
                (p0, if *beta > 0.0 { f64::INFINITY } else { p0 })
            }
            FoundationLaw::Prescribed { .. } => {
                let s = self.source(at);
                (s, s)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    //! Normal laws: values of (2.7)–(2.9), derivative against central finite differences away from
    //! the kink, and data validation.
    use super::*;

    const AT: SpaceTime = SpaceTime {
        x: 1.0,
        y: 0.0,
        t: 0.3,
    };

    fn laws() -> Vec<FoundationLaw> {
        vec![
            FoundationLaw::Linear { beta: 2.5 },
            FoundationLaw::Lubricated {
                beta: 1.5,
                p0: Field::Constant(6.0),
            },
            FoundationLaw::Prescribed {
                stress: Field::function(
                    crate::field::Dependence {
                        t: true,
                        ..Default::default()
                    },
                    |_, _, t| 1.0 + t,
                ),
            },
        ]
    }

    #[test]
    fn derivative_matches_finite_differences_away_from_the_kink() {
        for law in laws() {
            for &r in &[-2.0, -0.3, 0.4, 3.0] {
                let eps = 1e-6;
                let fd = (law.value(r + eps, AT) - law.value(r - eps, AT)) / (2.0 * eps);
                assert!(
                    (fd - law.derivative(r, AT)).abs() < 1e-8,
                    "{law:?} at r = {r}: fd {fd} vs {}",
                    law.derivative(r, AT)
                );
            }
        }
    }

    #[test]
    fn potential_is_a_primitive_of_the_law() {
        for law in laws() {
            for &r in &[-1.5, -0.2, 0.3, 2.0] {
                let eps = 1e-6;
                let fd = (law.potential(r + eps, AT).unwrap()
                    - law.potential(r - eps, AT).unwrap())
                    / (2.0 * eps);
                assert!((fd - law.value(r, AT)).abs() < 1e-7, "{law:?} at {r}");
            }
        }
    }

    #[test]
    fn lubricated_law_is_p0_when_receding_and_damped_when_approaching() {
        let law = FoundationLaw::Lubricated {
            beta: 1.0,
            p0: Field::Constant(2.0),
        };
        assert_eq!(law.value(-3.0, AT), 2.0);
        assert_eq!(law.value(1.5, AT), 3.5);
        assert!(!law.is_affine());
    }

    #[test]
    fn laws_are_monotone() {
        for law in laws() {
            let mut prev = f64::NEG_INFINITY;
            for i in -50..=50 {
                let v = law.value(i as f64 * 0.1, AT);
                assert!(v >= prev);
                prev = v;
            }
        }
    }

    #[test]
    fn negative_beta_and_negative_oil_pressure_are_rejected() {
        let err = FoundationLaw::Linear { beta: -1.0 }.validate().unwrap_err();
        assert_eq!(err.field, "foundation.beta");
        let err = FoundationLaw::Lubricated {
            beta: 1.0,
            p0: Field::Constant(-2.0),
        }
        .validate()
        .unwrap_err();
        assert_eq!(err.field, "foundation.p0");
    }
}
