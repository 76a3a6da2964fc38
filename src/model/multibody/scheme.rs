//! The time integrators of the multibody system M φ̈ + ∇V(φ) − Σ λ_s ∇g_s = f, g_s ≥ 0 (the
//! energy–momentum paper, "EM", (39)–(42)), each written as one equation for the step increment
//! d = u_{n+1} − u_n, with the contact constraints at t_{n+1}:
//!
//! | scheme            | step equation                                                               | forces                          |
//! |-------------------|-----------------------------------------------------------------------------|---------------------------------|
//! | `newmark`         | (4/k²) M (d − k v_n) − M a_n + ∇V(u_{n+1}) − Σ λ ∇g(x_{n+1}) = f(t_{n+1})      | at t_{n+1}                      |
//! | `midpoint`        | (2/k²) M (d − k v_n) + ∇V(u_{n+1/2}) − Σ λ ∇g(x_{n+1/2}) = f(t_{n+1/2})        | at the midpoint, EM (58)–(60)   |
//! | `energy_momentum` | (2/k²) M (d − k v_n) + ∇̄V(u_n, u_{n+1}) − Σ λ ∇̄g = f(t_{n+1/2})              | discrete gradients, EM (61)–(67)|
//!
//! with g(x_{n+1}) = 0 on the active set in every scheme, v_{n+1} = 2d/k − v_n for the midpoint
//! types (EM (58): v_{n+1/2} = d/k) and the trapezoidal velocity update for Newmark (γ = 1/2,
//! β = 1/4). ∇̄V is Gonzalez's discrete gradient of the stored energy (BDS (1.41)–(1.43)), ∇̄g the
//! discrete gradient of the gap in the invariants ([`super::invariants`]).

use serde::{Deserialize, Serialize};

use crate::model::multibody::invariants::Evaluation;

/// The time integrator of a multibody run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MultibodyScheme {
    /// Newmark's trapezoidal rule (γ = 1/2, β = 1/4), forces at t_{n+1}.
    Newmark,
    /// The implicit midpoint rule, EM (58)–(60).
    Midpoint,
    /// The energy–momentum scheme, EM (61)–(67).
    EnergyMomentum,
}

impl MultibodyScheme {
    /// Every scheme, in report order.
    pub const ALL: [Self; 3] = [Self::Newmark, Self::Midpoint, Self::EnergyMomentum];

    /// The name written in scenes.
    pub fn name(self) -> &'static str {
        match self {
            Self::Newmark => "newmark",
            Self::Midpoint => "midpoint",
            Self::EnergyMomentum => "energy_momentum",
        }
    }

    /// α of the inertia term α M (d − k v_n).
    pub fn alpha(self, k: f64) -> f64 {
        match self {
            Self::Newmark => 4.0 / (k * k),
            Self::Midpoint | Self::EnergyMomentum => 2.0 / (k * k),
        }
    }

    /// Where the contact forces' directions are evaluated.
    pub fn evaluation(self) -> Evaluation {
        match self {
            Self::Newmark => Evaluation::End,
            Self::Midpoint => Evaluation::Midpoint,
            Self::EnergyMomentum => Evaluation::DiscreteGradient,
        }
    }

    /// Whether loads are taken at t_{n+1/2} and v_{n+1} = 2d/k − v_n.
    pub fn is_midpoint_type(self) -> bool {
        !matches!(self, Self::Newmark)
    }
}
