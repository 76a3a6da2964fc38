//! The time treatment of the elastic term of the step equation.
//!
//! With the velocity w_n and u_n = u_{n−1} + k_n w_n, each scheme evaluates the elastic term at
//! u_{n−1} + θ k_n w_n and the data at τ_n:
//!
//! | scheme     | θ   | τ_n        | order in k | note                                                     |
//! |------------|-----|------------|------------|----------------------------------------------------------|
//! | `explicit` | 0   | t_n        | 1          | the paper's scheme (Fernández & Sofonea 2004, (3.3)); stable for k < 2 / λ_max(A⁻¹B) |
//! | `implicit` | 1   | t_n        | 1          | backward Euler; unconditionally stable                   |
//! | `midpoint` | 1/2 | t_{n−1/2}  | 2          | w_n approximates u̇(t_{n−1/2}) to O(k²)                 |

use serde::{Deserialize, Serialize};

/// The time treatment of the elastic term B ε(u).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TimeScheme {
    /// B ε(u_{n−1}): the paper's scheme.
    #[default]
    Explicit,
    /// B ε(u_n): backward Euler.
    Implicit,
    /// B ε((u_n + u_{n−1})/2), data at t_{n−1/2}.
    Midpoint,
}

impl TimeScheme {
    /// All schemes, in report order.
    pub const ALL: [TimeScheme; 3] = [
        TimeScheme::Explicit,
        TimeScheme::Implicit,
        TimeScheme::Midpoint,
    ];

    /// θ in B ε(u_{n−1} + θ k_n w_n).
    pub fn theta(self) -> f64 {
        match self {
            TimeScheme::Explicit => 0.0,
            TimeScheme::Implicit => 1.0,
            TimeScheme::Midpoint => 0.5,
        }
    }

    /// The time τ_n at which the data (f0, f2, p_ν) are evaluated in step n.
    pub fn data_time(self, t_prev: f64, t: f64) -> f64 {
        match self {
            TimeScheme::Explicit | TimeScheme::Implicit => t,
            TimeScheme::Midpoint => 0.5 * (t_prev + t),
        }
    }

    /// The scheme's name as written in scenes.
    pub fn name(self) -> &'static str {
        match self {
            TimeScheme::Explicit => "explicit",
            TimeScheme::Implicit => "implicit",
            TimeScheme::Midpoint => "midpoint",
        }
    }

    /// The formal order of w_n (and u_n) in k for smooth solutions.
    pub fn order(self) -> u32 {
        match self {
            TimeScheme::Explicit | TimeScheme::Implicit => 1,
            TimeScheme::Midpoint => 2,
        }
    }
}

impl std::fmt::Display for TimeScheme {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
