//! The case format of `dynamic_performance` and its checks: the series of growing meshes and
//! the timed whole runs, every level's scene validated.

use serde::{Deserialize, Serialize};

use contactlab::scene::dynamic::DynamicScene;

use crate::core::case::Case;
use crate::core::format::{invalid, CaseError};
use crate::dynamic::scene::scene_from_table;

/// The case format of `dynamic_performance` (unknown keys are errors).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PerformanceCase {
    #[serde(default)]
    pub series: Vec<SeriesSpec>,
    #[serde(default)]
    pub timed: Vec<TimedSpec>,
}

/// `[[series]]`: one scene on meshes of growing size.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SeriesSpec {
    pub name: String,
    pub scene: toml::Table,
    /// Dotted scene keys per level (`{ "body.rings" = 12 }`), smallest first.
    pub levels: Vec<toml::Table>,
    /// Timed runs per level (the best is kept; a first run warms the caches).
    pub repeats: usize,
    /// The cost ratio (step / forward–backward pass, or Newton iteration / factorization + solve)
    /// at any level may be at most this multiple of its value at the first level.
    pub max_ratio_growth: f64,
    #[serde(default)]
    pub note: String,
}

/// `[[timed]]`: one whole run, timed and reported (its wall-clock budget lives with the criterion
/// benchmarks, `benches/budgets.toml`: an absolute time on an unknown machine is no verdict).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TimedSpec {
    pub name: String,
    /// The scene inline (`[timed.scene]`) ...
    #[serde(default)]
    pub scene: Option<toml::Table>,
    /// ... or a scene file relative to the case file (exactly one of the two).
    #[serde(default)]
    pub scene_file: Option<String>,
    /// Dotted scene keys overriding the scene's (`{ "body.radial" = 16 }`).
    #[serde(default)]
    pub set: toml::Table,
    #[serde(default = "one")]
    pub repeats: usize,
    #[serde(default)]
    pub note: String,
}

impl TimedSpec {
    /// The timed run's scene: read (from its file) and built with its overrides.
    pub(super) fn load(
        &self,
        case_path: &std::path::Path,
        index: usize,
    ) -> Result<DynamicScene, String> {
        let source = format!("timed[{index}]");
        match (&self.scene, &self.scene_file) {
            (Some(table), None) => scene_from_table(table, &self.set, &source),
            (None, Some(file)) => {
                let path = case_path
                    .parent()
                    .unwrap_or(std::path::Path::new("."))
                    .join(file);
                let text = std::fs::read_to_string(&path)
                    .map_err(|e| format!("{source}: scene_file {}: {e}", path.display()))?;
                let table: toml::Table = text
                    .parse()
                    .map_err(|e: toml::de::Error| format!("{}: {e}", path.display()))?;
                scene_from_table(&table, &self.set, &path.display().to_string())
            }
            _ => Err(format!(
                "{source}: give exactly one of scene = {{ ... }} and scene_file = \"...\""
            )),
        }
    }
}

pub(super) fn one() -> usize {
    1
}

/// Checks the case's format: known keys only, valid scenes at every level, positive growth factors.
pub fn check(case: &Case) -> Result<(), CaseError> {
    let c: PerformanceCase = case.body()?;
    if c.series.is_empty() && c.timed.is_empty() {
        return Err(invalid(
            case.path(),
            "series / timed",
            "(none)",
            "at least one [[series]] or [[timed]]",
        ));
    }
    let read = |e: String| CaseError::Read {
        path: case.path().display().to_string(),
        message: e,
    };
    for (i, s) in c.series.iter().enumerate() {
        if s.levels.len() < 2 {
            return Err(invalid(
                case.path(),
                &format!("series[{i}].levels"),
                format!("{} levels", s.levels.len()),
                "at least 2 levels",
            ));
        }
        // the smallest level only: the largest may be expensive to assemble at load time
        scene_from_table(&s.scene, &s.levels[0], &format!("series[{i}].levels[0]"))
            .map_err(read)?;
        if s.repeats == 0 {
            return Err(invalid(
                case.path(),
                &format!("series[{i}].repeats"),
                0,
                "at least 1",
            ));
        }
        for (f, v) in [("max_ratio_growth", s.max_ratio_growth)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(
                    case.path(),
                    &format!("series[{i}].{f}"),
                    v,
                    "a finite number > 0",
                ));
            }
        }
    }
    for (i, b) in c.timed.iter().enumerate() {
        b.load(case.path(), i).map_err(read)?;
    }
    Ok(())
}
