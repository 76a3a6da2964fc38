//! Meshes. `interval`: 1D meshes of (0, L), uniform or graded. `triangle`: triangle meshes of
//! plane bodies with tagged boundaries.
//! `generators`: triangle meshes of a disk and an annulus. `gmsh`: Gmsh `.msh` files in.

pub mod generators;
pub mod gmsh;
pub mod interval;
pub mod triangle;
