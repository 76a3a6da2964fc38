//! PLACEHOLDER: `verify scene` for multibody scenes (being written).

use std::path::Path;

use contactlab::scene::Scene;

/// Runs a multibody scene and writes its results.
pub fn write_scene(_scene: &Scene, source: &str, _out: &Path) -> Result<String, String> {
    Err(format!("{source}: multibody scenes are not written yet"))
}
