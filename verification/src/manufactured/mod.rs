//! Manufactured solutions: one closure u(x, t) per solution; the data that make it exact (loads,
//! boundary sources) are derived from it by automatic differentiation (num-dual), so a new
//! manufactured solution is one function, not a page of hand-derived terms.
//!
//! - `rod`: manufactured solutions of the rod problem T1D with time-dependent load and oil pressure.
//! - `plane`, `plane_fields`: the plane body's solutions and their displacement fields;
//!   `plane_laws`, `normal_response`: the constitutive laws and the contact laws (2.7)–(2.9)
//!   written independently of the solver's, from which alone the plane data are built.
//! - `dynamic_plane`: plane-strain elastodynamics with normal compliance.
//! - `strain_energy`: the stored energies of the plane-strain laws, for the audits recomputed from
//!   the state (multibody, dynamic).

pub mod dynamic_plane;
pub mod normal_response;
pub mod plane;
pub mod plane_fields;
pub mod plane_laws;
pub mod rod;
pub mod strain_energy;
