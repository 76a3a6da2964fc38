//! Time integrators of M ü + F_int(u) = f + ξ, with uniform step k (Barboteu–Danan–Sofonea,
//! "BDS", §1.6). All three are written as one equation for the increment d = u_n − u_{n−1}:
//!
//! | scheme     | step equation R(d) = 0                                                  | velocity update                          |
//! |------------|-------------------------------------------------------------------------|------------------------------------------|
//! | `newmark`  | (4/k²) M (d − k v_{n−1}) − M a_{n−1} + F_int(u_n) = f(t_n) + ξ_n          | a_n = (4/k²)(d − k v_{n−1}) − a_{n−1}, v_n = v_{n−1} + (k/2)(a_{n−1} + a_n) |
//! | `midpoint` | (2/k²) M (d − k δu_{n−1}) + F_int(u_{n−1/2}) = f(t_{n−1/2}) + ξ_n         | δu_n = (2/k) d − δu_{n−1}  (BDS (1.31)/(1.40)) |
//! | `gonzalez` | (2/k²) M (d − k δu_{n−1}) + F^algo(u_{n−1}, u_n) = f(t_{n−1/2}) + ξ_n     | as the midpoint rule (BDS (1.41)–(1.43)) |
//!
//! Newmark is the trapezoidal rule (γ = 1/2, β = 1/4). The contact forces ξ_n are those of the
//! contact treatment, imposed at t_n (BDS §1.5: at t_{n−1/2} they would not control the
//! penetration). For a small-strain (linear) law the midpoint rule and Gonzalez's scheme coincide
//! and conserve energy exactly; for a hyperelastic law only Gonzalez's does (BDS (1.43)).

use serde::{Deserialize, Serialize};

/// The time integrator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DynamicScheme {
    /// Newmark trapezoidal rule, γ = 1/2, β = 1/4.
    Newmark,
    /// The midpoint rule (BDS (1.31)/(1.40)): internal force at u_{n−1/2}.
    Midpoint,
    /// The Gonzalez energy-conserving scheme (BDS (1.41)–(1.43)).
    Gonzalez,
}

impl DynamicScheme {
    /// All schemes, in report order.
    pub const ALL: [DynamicScheme; 3] = [Self::Newmark, Self::Midpoint, Self::Gonzalez];

    /// The scheme's name as written in scenes.
    pub fn name(self) -> &'static str {
        match self {
            Self::Newmark => "newmark",
            Self::Midpoint => "midpoint",
            Self::Gonzalez => "gonzalez",
        }
    }

    /// α of the step equation (the mass factor).
    pub fn alpha(self, k: f64) -> f64 {
        match self {
            Self::Newmark => 4.0 / (k * k),
            Self::Midpoint | Self::Gonzalez => 2.0 / (k * k),
        }
    }

    /// Whether the scheme is of midpoint type (velocity δu, data at t_{n−1/2}).
    pub fn is_midpoint_type(self) -> bool {
        !matches!(self, Self::Newmark)
    }
}
