//! The dynamic audit recomputed from the state (docs/dynamic.md, "The audit recomputed from the
//! state"). The solver's audit (`contactlab::model::dynamic::audit`) books E_n, Φ_n and the works
//! from its own numbers; this one reads only what a run's observer sees after every step — u_n,
//! the scheme's velocity v_n (δu_n or Newmark's v_n) and, per contact node, its normal force N,
//! friction force T and multiplier λ (per weight) — and the case's scene (density, mass kind,
//! law and constants, the foundation's level, Γ3, the stiffness r), and recomputes:
//!
//! - K = ½ vᵀ M v with the P1 mass assembled here, consistent or lumped ([`sums`]), and the stored
//!   energy 𝒲 = Σ_T A W(∇u) by the laws written in `crate::manufactured::strain_energy`;
//! - Φ_n = Σ_i w_i (r/2) (p_i)_+² with w_i = Σ ½ |e| over the Γ3 edges at node i and
//!   p_i = level − (y_i + u_{y,i}) from the foundation {y ≤ level} ([`geometry`]);
//! - the step works from the forces applied over the step (those of t_n for the midpoint-type
//!   schemes, the mean of t_{n−1} and t_n for Newmark) and the increments d = u_n − u_{n−1}:
//!   W_ext = f̄·d (f̄ the body's load vector — the scene's body force and tractions — at t_{n−½}, or
//!   the mean of both ends for Newmark), W_c = Σ w N̄ d_y (for the tilted force (3.69), whose tilt
//!   is no per-weight normal force, its generalized forces on u_y and u_x), W_τ = Σ w T̄ d_x,
//!   D_b = −Σ w λ̄ (p_n − p_{n−1});
//!
//! and then (module [`run`]):
//!
//! 1. compares the solver's records — K, 𝒲, Φ at every step, the cumulative W_ext, W_c, W_τ, D_b
//!    and the step's W_τ, D_b — with these, each difference over the round-off floor
//!    C ε (N + 30) S, S the sum of the magnitudes of the N recomputed terms (with the rounding of
//!    H = ∇u, F = I + H, p and d from u), C = 2. Derivation: a sum of N terms computed in any order
//!    is in error by at most (N − 1) ε/2 Σ|terms| (Higham's γ_{N−1}, to first order); each term is
//!    itself a product of a few rounded factors (the solver's and this one: two computations of
//!    the same quantity, so twice), and 30 covers the few further operations per term (the
//!    element's area, the gradients, the law's own arithmetic) that do not grow with N;
//! 2. gates the sign laws on the RECOMPUTED works: D_b ≤ its floor and W_τ ≤ its floor
//!    (midpoint-type schemes; Newmark's trapezoidal mean of the t_{n−1} and t_n friction forces
//!    times the slip has no sign), each floor its own C ε Σ|terms| plus the step's Newton part
//!    ν_n + C ε s_n (the solver's reported bound of the work of the residual it stopped at, and
//!    the magnitude of the terms of the step equation — slack, never a booked energy);
//! 3. where the scheme claims them (`model/dynamic/record.rs::conserving`: (1.48) for Gonzalez and
//!    for the midpoint rule on a linear body, (1.49) when the contact force is energy-consistent
//!    or exact too), gates the recomputed (1.48) and (1.49) drifts, and the rise
//!    (E + Φ)_n − (E + Φ)_0 − Σ W_ext (which must stay ≤ 0: W_τ, D_b ≤ 0), over the tolerance of
//!    the recomputed identity: the floors of E + Φ at t_0 and t_n plus, per step, the works'
//!    floors and the Newton part.
//!
//! **Not audited here: the 1D bar** (`dynamic_bar_wall`, `dynamic_signorini_bar`, the envelope's
//! bars). Its body is a `BarBody` (interval mesh, cross-section A, one contact end of weight A),
//! not a plane body; those cases compare the state with exact solutions and the envelope
//! recomputes the bar's final energy from its state, but an auditor of the bar's records (the same
//! three checks with the 1D mass and Hooke energy) is not written yet. Nor are Γ3 selected by a
//! Gmsh group or bodies with material regions: the auditor refuses them with a named reason (a
//! failed check), it does not guess.

pub mod geometry;
pub mod run;
pub mod sums;

pub use run::{state_audit_checks, state_audit_gate, AuditSpec, StateAudit, StateAuditor};
