//! The multibody audit recomputed from the state (docs/multibody.md, "The audit recomputed from
//! the state"). The solver's audit (`contactlab::model::multibody::audit`) books energies,
//! momenta and works from its own step records; this one reads only what a run's observer sees
//! after every step — the displacements u_n, the velocities v_n, and per candidate its pair,
//! slave node, master segment, λ_N, λ_T and whether it is active — and recomputes:
//!
//! - K = ½ vᵀ M v, P = Σ (M v)_I, J = Σ x_I × (M v)_I from a mass assembled here, and the stored
//!   energy V by the laws written here ([`sums`]); with the penalty, Σ (ε/2) (g₋)² by the gap
//!   written here ([`geometry`]); E = K + V (+ penalty);
//! - the contact works of step n from λ at t_n and the gaps of the step's pairing at both ends:
//!   W_N = Σ λ_N (g₁ − g₀), split into entries (constraints active at t_n that were not active at
//!   t_{n−1}: the activation work −λ g₀ ≤ 0 of EM §6.2), re-pairings from outside (an entry on
//!   another segment than the node's candidate at t_{n−1}, whose gap there was ≥ 0: its g₀
//!   against the new line is the master vertex's non-smoothness), switches of held nodes (active
//!   at both ends on different segments), holding constraints (same segment) and releases (active at
//!   t_{n−1}, not at t_n: λ = 0, no work); W_T = Σ λ_T ℓ₀ (ξ₁ − ξ₀), ℓ₀ the segment's length at
//!   t_{n−1} (1 for the foundation); W_ext = f·d with f at t_{n−½} (midpoint types) or the mean
//!   of f at both ends (Newmark) — f the bodies' load vectors, the scene's data;
//! - with the penalty, the redefinition jump Σ_{C_n} P(x_{n−1}) − Σ_{C_{n−1}} P(x_{n−1}) (the
//!   candidates of steps n and n−1 at the same positions), booked where a penetrated node's
//!   segment changed (§3.1).
//!
//! The solver's records are compared with these values — each difference over its round-off
//! floor C ε (N + 30) S, S the sum of the magnitudes of the terms, N the terms summed (the
//! worst-case bound of a sum in any order), C = 2 — and the sign laws are checked on the
//! recomputed works: an entry's work ≤ its floor, friction's ≤ its floor, releases' |W| ≤ its
//! floor, and the energy never above E₀ + Σ W_ext + the booked, allowed gains (held nodes'
//! switches and re-pairings from outside at a master's kinks, the penalty's jumps, pairs that allow a gain) beyond the
//! tolerance of the recomputed identity (module [`run`]).

pub mod geometry;
pub mod run;
pub mod sums;

pub use run::{state_audit_checks, state_audit_gate, StateAudit, StateAuditor};
