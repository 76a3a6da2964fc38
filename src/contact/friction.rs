//! Coulomb friction with a penetration-dependent coefficient (Barboteu–Danan–Sofonea, "BDS",
//! (1.13), (1.19)): ‖ξ_τ‖ ≤ μ(u_ν) |ξ_ν|, with ξ_τ = −μ(u_ν)|ξ_ν| u̇_τ/‖u̇_τ‖ when sliding.
//!
//! With μ0 = μ(g) and g the depth of the asperity layer:
//!
//!   μ1(η) = 0 (η ≤ 0),  (η/g) μ0 (0 < η < g),        μ0 (η ≥ g)   (bound grows as asperities flatten)
//!   μ2(η) = 0 (η ≤ 0),  (2 − η/g) μ0 (0 < η < g),    μ0 (η ≥ g)   (bound decreases)

use crate::error::{require_nonnegative, require_positive, InputError};

/// The friction coefficient μ(η) of (1.13), η the penetration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FrictionCoefficient {
    /// μ(η) = μ0 for η > 0 (0 outside contact).
    Constant { mu0: f64 },
    /// μ1 of (1.13).
    Growing { mu0: f64, depth: f64 },
    /// μ2 of (1.13).
    Decreasing { mu0: f64, depth: f64 },
}

impl FrictionCoefficient {
    /// μ(η).
    pub fn value(&self, eta: f64) -> f64 {
        if eta <= 0.0 {
            return 0.0;
        }
        match *self {
            Self::Constant { mu0 } => mu0,
            Self::Growing { mu0, depth } => {
                if eta < depth {
                    eta / depth * mu0
                } else {
                    mu0
                }
            }
            Self::Decreasing { mu0, depth } => {
                if eta < depth {
                    (2.0 - eta / depth) * mu0
                } else {
                    mu0
                }
            }
        }
    }

    /// μ0 = μ(g), the coefficient on the rigid base (stage (b) of the IPM).
    pub fn mu0(&self) -> f64 {
        match *self {
            Self::Constant { mu0 } | Self::Growing { mu0, .. } | Self::Decreasing { mu0, .. } => {
                mu0
            }
        }
    }

    /// Whether friction is absent (μ0 = 0): then no friction code runs.
    pub fn is_zero(&self) -> bool {
        self.mu0() == 0.0
    }

    /// Checks μ0 ≥ 0 and g > 0; errors name `field.mu0` / `field.depth`.
    pub fn validate(&self, field: &str) -> Result<(), InputError> {
        require_nonnegative(&format!("{field}.mu0"), self.mu0())?;
        match *self {
            Self::Constant { .. } => Ok(()),
            Self::Growing { depth, .. } | Self::Decreasing { depth, .. } => {
                require_positive(&format!("{field}.depth"), depth).map(|_| ())
            }
        }
    }

    /// A short description for reports.
    pub fn describe(&self) -> String {
        match *self {
            Self::Constant { mu0 } => format!("constant μ = {mu0}"),
            Self::Growing { mu0, depth } => format!("μ1 (growing), μ0 = {mu0}, g = {depth}"),
            Self::Decreasing { mu0, depth } => format!("μ2 (decreasing), μ0 = {mu0}, g = {depth}"),
        }
    }
}

#[cfg(test)]
mod tests {
    //! The coefficients of (1.13): values at the ends of the layer, continuity at η = g.
    use super::*;

    #[test]
    fn coefficients_follow_bds_1_13() {
        let g = 0.01;
        let m1 = FrictionCoefficient::Growing { mu0: 0.4, depth: g };
        let m2 = FrictionCoefficient::Decreasing { mu0: 0.4, depth: g };
        assert_eq!(m1.value(-1.0), 0.0);
        assert!((m1.value(0.5 * g) - 0.2).abs() < 1e-15);
        assert!((m2.value(0.5 * g) - 0.6).abs() < 1e-15);
        assert!((m1.value(g * (1.0 - 1e-12)) - 0.4).abs() < 1e-10);
        assert!((m2.value(g * (1.0 - 1e-12)) - 0.4).abs() < 1e-10);
        assert_eq!(m2.value(2.0 * g), 0.4);
        assert!(m2.value(1e-9) > 0.79);
        assert!(FrictionCoefficient::Constant { mu0: 0.0 }.is_zero());
        assert!(FrictionCoefficient::Growing {
            mu0: 0.3,
            depth: 0.0
        }
        .validate("friction")
        .is_err());
    }
}
