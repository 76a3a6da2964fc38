//! Manufactured solutions: one closure u(x, t) per solution; the data that make it exact (loads,
//! boundary sources) are derived from it by automatic differentiation (num-dual), so a new
//! manufactured solution is one function, not a page of hand-derived terms.
//!
//! - `rod`: manufactured solutions of the rod problem T1D with time-dependent load and oil pressure.

pub mod dynamic_plane;
pub mod plane;
pub mod rod;
