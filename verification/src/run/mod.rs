//! Runners: one per case kind. Each fills a [`CaseReport`]; a failure to set up or run becomes the
//! report's `failure` (and fails the case), never a panic.

pub mod convergence;
pub mod extremes;
pub mod paper_figures;
pub mod paper_test_2d;
pub mod performance;
pub mod plane_paths;
pub mod plane_performance;
pub mod plane_scene;
pub mod plane_stability;
pub mod stability;
pub mod work_precision;

use std::path::{Path, PathBuf};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};

use crate::case::{Case, CaseError, CaseFile, CaseKind};
use crate::report::case_report::{CaseReport, PlotRef};
use crate::report::metadata::Metadata;

/// Where and how cases run.
#[derive(Debug, Clone)]
pub struct RunContext {
    /// The reports directory (plots go to `<out>/<case id>/`).
    pub out_dir: PathBuf,
    pub metadata: Metadata,
    /// Show progress bars (on a terminal).
    pub progress: bool,
}

impl RunContext {
    /// The directory of a case's plots, created on demand.
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
        bar
    }

    /// Writes `figure` as `<case dir>/<name>.svg` and records it in the report.
    pub fn plot(
        &self,
        report: &mut CaseReport,
        name: &str,
        figure: &crate::plot::Figure,
    ) -> Result<(), String> {
        let dir = self.case_dir(&report.id)?;
        let path = dir.join(format!("{name}.svg"));
        crate::plot::write_svg(figure, &path).map_err(|e| e.to_string())?;
        report.plots.push(PlotRef {
            title: figure.title.clone(),
            file: relative(&self.out_dir, &path),
        });
        Ok(())
    }

    /// Writes several figures side by side as one SVG and records it.
    pub fn panels(
        &self,
        report: &mut CaseReport,
        name: &str,
        title: &str,
        figures: &[crate::plot::Figure],
        columns: usize,
    ) -> Result<(), String> {
        let dir = self.case_dir(&report.id)?;
        let path = dir.join(format!("{name}.svg"));
        crate::plot::write_panels_svg(figures, columns, &path).map_err(|e| e.to_string())?;
        report.plots.push(PlotRef {
            title: title.to_string(),
            file: relative(&self.out_dir, &path),
        });
        Ok(())
    }
}

fn relative(base: &Path, path: &Path) -> String {
    path.strip_prefix(base)
        .unwrap_or(path)
        .to_string_lossy()
        .replace('\\', "/")
}

/// The minimum over `repeats` runs of a solver's whole time loop (s), with an observer that only
/// reads the contact velocity (so the loop cannot be optimized away).
pub fn time_loop_seconds(
    solver: &contactlab::model::quasistatic::rod_solver::RodSolver,
    repeats: usize,
) -> Result<f64, String> {
    let mut best = f64::INFINITY;
    for _ in 0..repeats.max(1) {
        let mut sink = 0.0;
        let start = Instant::now();
        solver
            .run(
                &mut |s: &contactlab::model::quasistatic::rod_solver::RodStep<'_>| {
                    sink += s.contact_velocity
                },
            )
            .map_err(|e| e.to_string())?;
        best = best.min(start.elapsed().as_secs_f64());
        std::hint::black_box(sink);
    }
    Ok(best)
}

/// The kinds of the quasistatic case format ([`CaseFile`]).
const QUASISTATIC_KINDS: [&str; 9] = [
    "convergence",
    "stability",
    "extremes",
    "work_precision",
    "performance",
    "paper_test2d",
    "plane_stability",
    "plane_paths",
    "plane_performance",
];

/// Checks a case with its kind's format (called when a case is loaded).
pub fn check_case(case: &Case) -> Result<(), CaseError> {
    let kind = case.header.kind.as_str();
    if kind.starts_with("moving_") {
        return crate::moving::check_case(case);
    }
    if crate::dynamic::KINDS.contains(&kind) {
        return crate::dynamic::check_case(case);
    }
    if QUASISTATIC_KINDS.contains(&kind) {
        CaseFile::from_case(case).map(|_| ())
    } else {
        Err(CaseError::Invalid {
            path: case.path.display().to_string(),
            field: "kind".into(),
            value: kind.into(),
            expected: format!(
                "one of {}, {}",
                QUASISTATIC_KINDS.join(", "),
                crate::dynamic::KINDS.join(", ")
            ),
        })
    }
}

/// Runs one case and returns its report.
pub fn run_case(case: &Case, ctx: &RunContext) -> CaseReport {
    let start = Instant::now();
    let mut report = CaseReport::new(&case.header, ctx.metadata.clone());
    let outcome = if crate::dynamic::KINDS.contains(&case.header.kind.as_str()) {
        crate::dynamic::run_case(case, ctx, &mut report)
    } else if case.header.kind.starts_with("moving_") {
        crate::moving::run_case(case, ctx, &mut report)
    } else {
        run_quasistatic(case, ctx, &mut report)
    };
    if let Err(message) = outcome {
        report.failure = Some(message);
    }
    report.wall_seconds = start.elapsed().as_secs_f64();
    report.conclude();
    report
}

/// Runs a case of the quasistatic format ([`CaseFile`]).
fn run_quasistatic(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    match CaseFile::from_case(case) {
        Err(e) => Err(e.to_string()),
        Ok(file) => match file.kind {
            CaseKind::Convergence => convergence::run(&file, ctx, report),
            CaseKind::Stability => stability::run(&file, ctx, report),
            CaseKind::Extremes => extremes::run(&file, ctx, report),
            CaseKind::WorkPrecision => work_precision::run(&file, ctx, report),
            CaseKind::Performance => performance::run(&file, ctx, report),
            CaseKind::PaperTest2d => paper_test_2d::run(&file, ctx, report),
            CaseKind::PlaneStability => plane_stability::run(&file, ctx, report),
            CaseKind::PlanePaths => plane_paths::run(&file, ctx, report),
            CaseKind::PlanePerformance => plane_performance::run(&file, ctx, report),
        },
    }
}
