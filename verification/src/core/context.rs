//! Where and how a case runs: the reports directory, the metadata, progress bars, and the one path
//! by which a case writes a file next to its report (plots, `data.json`) and records it.

use std::path::{Path, PathBuf};

use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use serde::Serialize;

use crate::core::report::case_report::{CaseReport, PlotRef};
use crate::core::report::metadata::Metadata;
use crate::plot::{Figure, PlotError, TriangleMeshPlot};

/// Where and how cases run.
#[derive(Debug, Clone)]
pub struct RunContext {
    /// The reports directory (a case's files go to `<out>/<case id>/`).
    pub out_dir: PathBuf,
    pub metadata: Metadata,
    /// Show progress bars (on a terminal).
    pub progress: bool,
    /// The run's bars, when it draws one for the whole tier: a case's sweep bars join it.
    pub bars: Option<MultiProgress>,
}

impl RunContext {
    /// The directory of a case's files, created on demand.
    pub fn case_dir(&self, id: &str) -> Result<PathBuf, String> {
        let dir = self.out_dir.join(id);
        std::fs::create_dir_all(&dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        Ok(dir)
    }

    /// A progress bar of `total` runs (hidden when not wanted).
    pub fn progress_bar(&self, total: u64, label: &str) -> ProgressBar {
        if !self.progress || total < 4 {
            return ProgressBar::hidden();
        }
        let bar = ProgressBar::new(total);
        if let Ok(style) =
            ProgressStyle::with_template("{prefix:>28} [{bar:30}] {pos}/{len} runs {elapsed}")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_prefix(label.to_string());
        match &self.bars {
            Some(m) => m.add(bar),
            None => bar,
        }
    }

    /// Writes `<case dir>/<name>.svg` with `write` and records it in the report under `title`.
    fn record_svg(
        &self,
        report: &mut CaseReport,
        name: &str,
        title: &str,
        write: impl FnOnce(&Path) -> Result<(), PlotError>,
    ) -> Result<(), String> {
        let dir = self.case_dir(&report.id)?;
        let path = dir.join(format!("{name}.svg"));
        write(&path).map_err(|e| e.to_string())?;
        report.plots.push(PlotRef {
            title: title.to_string(),
            file: relative(&self.out_dir, &path),
        });
        Ok(())
    }

    /// Writes `figure` as `<case dir>/<name>.svg` and records it.
    pub fn plot(&self, report: &mut CaseReport, name: &str, figure: &Figure) -> Result<(), String> {
        self.record_svg(report, name, &figure.title, |p| {
            crate::plot::write_svg(figure, p)
        })
    }

    /// Writes several figures side by side (`columns` per row) as one SVG and records it.
    pub fn panels(
        &self,
        report: &mut CaseReport,
        name: &str,
        title: &str,
        figures: &[Figure],
        columns: usize,
    ) -> Result<(), String> {
        self.record_svg(report, name, title, |p| {
            crate::plot::write_panels_svg(figures, columns, p)
        })
    }

    /// Writes several triangle-mesh plots side by side as one SVG and records it.
    pub fn triangle_panels(
        &self,
        report: &mut CaseReport,
        name: &str,
        title: &str,
        plots: &[TriangleMeshPlot],
        columns: usize,
    ) -> Result<(), String> {
        self.record_svg(report, name, title, |p| {
            crate::plot::write_triangle_panels_svg(plots, columns, p)
        })
    }

    /// Writes a case's detailed numbers as `<case dir>/data.json`.
    pub fn write_data<T: Serialize>(&self, report: &CaseReport, data: &T) -> Result<(), String> {
        let dir = self.case_dir(&report.id)?;
        let path = dir.join("data.json");
        let json = serde_json::to_string_pretty(data).map_err(|e| e.to_string())?;
        std::fs::write(&path, json).map_err(|e| format!("{}: {e}", path.display()))
    }
}

/// `path` relative to `base`, with forward slashes (for links in the report).
fn relative(base: &Path, path: &Path) -> String {
    path.strip_prefix(base)
        .unwrap_or(path)
        .to_string_lossy()
        .replace('\\', "/")
}
