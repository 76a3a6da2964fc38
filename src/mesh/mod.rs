//! Meshes. `interval`: 1D meshes of (0, L), uniform or graded. `triangle`: triangle meshes of
//! plane bodies with tagged boundaries.

pub mod interval;
pub mod triangle;
