//! # contactlab-verify — the evidence
//!
//! Exact and manufactured solutions, sweeps in h and k, rate fits with confidence intervals, gates,
//! plots and reports. The solver crate never knows it is being verified: this crate sees solutions,
//! energies and statistics through public types only.

// Numerical kernels index several arrays in lockstep (u_i, w_i, g_i, z_i; rows and columns):
// index loops read as the formulas they implement.
#![allow(clippy::needless_range_loop)]

pub mod case;
pub mod dynamic;
pub mod exact;
pub mod gate;
pub mod manufactured;
pub mod moving;
pub mod plane_errors;
pub mod plane_study;
pub mod plot;
pub mod report;
pub mod rod_errors;
pub mod rod_study;
pub mod run;
pub mod scene_dynamic;
pub mod scene_plane;
pub mod scene_run;
pub mod stats;
pub mod study;
