//! A time series: `<stem>_<i>.vtu` for each frame and `<stem>.pvd` listing them, all in one
//! directory (the `verify scene --out` directory, whose marker file makes the next run replace
//! them). Every frame is checked before the first file is written, so a non-finite value leaves
//! no partial series behind.

use std::path::{Path, PathBuf};

use crate::vtk::frame::Frame;

/// Writes the series; returns the files written (the `.pvd` last).
pub fn write_series(
    dir: &Path,
    stem: &str,
    title: &str,
    frames: &[Frame],
) -> Result<Vec<PathBuf>, String> {
    if frames.is_empty() {
        return Err(
            "VTK output: no output time (list the times to write in [output] times)".into(),
        );
    }
    for f in frames {
        f.check()?;
    }
    let mut written = Vec::with_capacity(frames.len() + 1);
    let mut entries = Vec::with_capacity(frames.len());
    for (i, f) in frames.iter().enumerate() {
        let name = format!("{stem}_{i:04}.vtu");
        let path = dir.join(&name);
        crate::vtk::vtu::write(f, &format!("{title}, t = {}", f.time), &path)?;
        written.push(path);
        entries.push((f.time, name));
    }
    let pvd = dir.join(format!("{stem}.pvd"));
    std::fs::write(&pvd, crate::vtk::pvd::collection(&entries)?)
        .map_err(|e| format!("{}: {e}", pvd.display()))?;
    written.push(pvd);
    Ok(written)
}
