//! The files of `plane_gmsh`: mesh paths in a case file are relative to the repository root.

use std::path::{Path, PathBuf};

use contactlab::mesh::gmsh::{GmshMesh, Placement};

/// The repository root, which the case's mesh paths are relative to.
pub fn repository_root() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().unwrap_or(manifest).to_path_buf()
}

/// Reads the mesh at `file` (relative to the repository root).
pub fn read_mesh(file: &str) -> Result<GmshMesh, String> {
    GmshMesh::read(&repository_root().join(file), Placement::default()).map_err(|e| e.to_string())
}
