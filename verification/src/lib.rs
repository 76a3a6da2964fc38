//! # contactlab-verify — the evidence
//!
//! Exact and manufactured solutions, sweeps in h and k, rate fits with confidence intervals, gates,
//! plots and reports. The solver crate never knows it is being verified: this crate sees solutions,
//! energies and statistics through public types only.

pub mod case;
pub mod exact;
pub mod gate;
pub mod manufactured;
pub mod plot;
pub mod report;
pub mod rod_errors;
pub mod rod_study;
pub mod run;
pub mod scene_run;
pub mod stats;
