//! Quasistatic Kelvin–Voigt contact with normal damped response (Fernández & Sofonea 2004).
//!
//! Problem P: σ = A ε(u̇) + B ε(u), Div σ + f0 = 0, u = 0 on Γ1, σν = f2 on Γ2,
//! −σ_ν = p_ν(u̇_ν) and σ_τ = 0 on Γ3, u(0) = u0 ((2.1)–(2.6)). The fully discrete scheme (§3)
//! solves for the velocity w_n each step and sets u_n = u_{n−1} + k_n w_n.
//!
//! - `scheme`: the time treatment of the elastic term (explicit, implicit, midpoint).
//! - `rod`: the 1D problem T1D (§4.1) with general data.
//! - `rod_solver`: factor once, condense onto the contact node, one scalar equation per step.
//! - `rod_output`: the recorded solution (snapshots, histories, statistics).

pub mod plane;
pub mod plane_condensed;
pub mod plane_contact;
pub mod plane_dofs;
pub mod plane_newton;
pub mod plane_output;
pub mod plane_solver;
pub mod plane_stability;
pub mod plane_step;
pub mod rod;
pub mod rod_output;
pub mod rod_solver;
pub mod rod_step;
pub mod scheme;
