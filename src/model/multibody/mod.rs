//! Bodies against bodies: node-to-segment contact of plane-strain bodies with Lagrange
//! multipliers (or penalty), Coulomb friction, and energy–momentum time integration (the
//! energy–momentum paper, "EM"; docs/multibody.md).
//!
//!   M φ̈ + ∇V(φ) − Σ_s (λ_N,s ∇g_s + λ_T,s ∇τ_s) = f,  g_s ≥ 0, λ_N,s ≥ 0, λ_N,s g_s = 0,
//!   |λ_T,s| ≤ μ λ_N,s with stick (τ̇_s = 0) or slip against the motion   (EM (39)–(57)),
//!
//! with any number of bodies ([`bodies`], each a P1 plane-strain body of its own law), slave nodes
//! paired with master segments by a broad-phase R*-tree and a closest-point narrow phase
//! ([`search`], [`surface`]), the gap and the tangential coordinate written in invariants of the
//! local coordinates ([`invariants`]), each pair's complementarity rows ([`constraint`]) and one
//! sparse Newton matrix per step ([`system`], [`step`]). The schemes ([`scheme`]): Newmark, the
//! midpoint rule (EM (58)–(60)) and the energy–momentum scheme (EM (61)–(67)), which conserves
//! linear and angular momentum to round-off and energy to round-off in every step in which no
//! constraint becomes active. Every run is audited ([`audit`]); [`solver`] holds the time loop and
//! the static equilibrium (the contact patch test).

pub mod audit;
pub mod bodies;
pub mod constraint;
pub mod history;
pub mod invariants;
pub mod scheme;
pub mod search;
pub mod solver;
pub mod step;
pub mod surface;
pub mod system;
