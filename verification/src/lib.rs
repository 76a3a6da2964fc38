//! # contactlab-verify — the evidence
//!
//! Exact and manufactured solutions, sweeps in h and k, rate fits with confidence intervals, gates,
//! plots and reports. The solver crate never knows it is being verified: this crate sees solutions,
//! energies and statistics through public types only.
//!
//! Imports run one way: `bin → suite → registry → families → core → {stats, plot, vtk, exact,
//! manufactured} → contactlab`. The [`core`] knows no model family; each family ([`rod`], [`plane`], [`dynamic`],
//! [`moving`], [`multibody`]) has the same shape (see [`family`]) and imports no other family.

// Numerical kernels index several arrays in lockstep (u_i, w_i, g_i, z_i; rows and columns):
// index loops read as the formulas they implement.
#![allow(clippy::needless_range_loop)]

pub mod core;
pub mod dynamic;
pub mod exact;
pub mod family;
pub mod manufactured;
pub mod moving;
pub mod multibody;
pub mod plane;
pub mod plot;
pub mod registry;
pub mod robustness;
pub mod rod;
pub mod scene_keys;
pub mod stats;
pub mod suite;
pub mod vtk;

/// The speed–accuracy planner (docs/planner.md): `plan::plan(&study, &request)` for any family's
/// [`plan::Plannable`] — the rod, the plane and dynamic manufactured problems, and rod, plane,
/// dynamic and multibody scenes ([`registry::plan_scene`] reads a scene file).
pub use crate::core::plan;
