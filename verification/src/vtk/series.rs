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

#[cfg(test)]
mod tests {
    //! A series whose last frame holds a NaN is refused before the first file is written: no
    //! partial series is left for ParaView to open.
    use super::*;
    use crate::vtk::frame::{Array, Cells};

    fn frame(t: f64, value: f64) -> Frame {
        Frame {
            time: t,
            points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
            cells: Cells::Lines(vec![[0, 1]]),
            point_data: vec![Array::plane_vectors(
                "displacement",
                [[0.0, 0.0], [value, 0.0]],
            )],
            cell_data: vec![],
        }
    }

    #[test]
    fn a_non_finite_frame_leaves_no_file() {
        let dir =
            std::env::temp_dir().join(format!("contactlab-vtk-series-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let e = write_series(&dir, "s", "t", &[frame(0.0, 1.0), frame(1.0, f64::NAN)]).unwrap_err();
        assert!(e.contains("displacement") && e.contains("t = 1"), "{e}");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        let written = write_series(&dir, "s", "t", &[frame(0.0, 1.0), frame(1.0, 2.0)]).unwrap();
        assert_eq!(written.len(), 3);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
