//! Meshes. `interval`: 1D meshes of (0, L), uniform or graded.

pub mod interval;
