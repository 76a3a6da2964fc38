//! The per-case report, serialized as `reports/<case id>.json`.

use std::path::Path;

use serde::Serialize;

use crate::core::case::{CaseHeader, Tier};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::metadata::Metadata;
use crate::core::report::split::split;
use crate::core::sweep::SweepReport;

/// A plot written for a case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlotRef {
    pub title: String,
    /// Path relative to the reports directory.
    pub file: String,
}

/// One run of an extremes case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExtremeReport {
    pub name: String,
    pub expect: String,
    /// What happened: `solution` or the error message.
    pub outcome: String,
    pub checks: Vec<Check>,
    pub note: String,
}

/// One point of a work–precision study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorkPoint {
    pub scheme: String,
    pub elements: usize,
    pub steps: usize,
    pub error: f64,
    /// Minimum over the repeats of the solver's wall time, without error evaluation (s).
    pub cpu_seconds: f64,
    /// M·N: the deterministic measure of work.
    pub dof_steps: f64,
}

/// The work–precision data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorkPrecisionReport {
    pub error: String,
    pub points: Vec<WorkPoint>,
}

/// One timed size of a performance case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PerformancePoint {
    pub elements: usize,
    pub steps: usize,
    pub dof_steps: f64,
    /// Minimum over the repeats of the whole time loop (s).
    pub seconds: f64,
    /// seconds / dof_steps (ns).
    pub ns_per_dof_step: f64,
}

/// The performance data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PerformanceReport {
    pub points: Vec<PerformancePoint>,
}

/// A table of a case (rendered in the report; its rows are also in the JSON).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Table {
    pub title: String,
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

/// Everything a case produced.
#[derive(Debug, Clone, Serialize)]
pub struct CaseReport {
    pub id: String,
    pub title: String,
    pub kind: String,
    pub tier: Tier,
    pub explanation: String,
    /// True when every gate passed and nothing failed to run.
    pub passed: bool,
    /// A failure to set up or run the case (then `passed` is false).
    pub failure: Option<String>,
    pub gates: Vec<GateVerdict>,
    pub sweeps: Vec<SweepReport>,
    /// A family's stability study (the rod: the explicit bound, its runs), as JSON.
    pub stability: Option<serde_json::Value>,
    pub extremes: Vec<ExtremeReport>,
    pub work_precision: Option<WorkPrecisionReport>,
    pub performance: Option<PerformanceReport>,
    pub plots: Vec<PlotRef>,
    /// Further tables (model-specific results).
    pub tables: Vec<Table>,
    /// Wall time of the whole case (s).
    pub wall_seconds: f64,
    pub metadata: Metadata,
    /// Markdown sections a family renders from its own typed data (e.g. the rod's stability
    /// runs); shown in `report.md` after the sweeps. Not in the JSON: the data are.
    #[serde(skip)]
    pub sections: Vec<Section>,
}

/// A Markdown section of a case's report, rendered by its family.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    pub title: String,
    /// Markdown text under the title (paragraphs, tables).
    pub body: String,
}

impl CaseReport {
    /// An empty report for a case, to be filled by its runner.
    pub fn new(case: &CaseHeader, metadata: Metadata) -> Self {
        Self {
            id: case.id.clone(),
            title: case.title.clone(),
            kind: case.kind.clone(),
            tier: case.tier,
            explanation: case.explanation.trim().to_string(),
            passed: false,
            failure: None,
            gates: Vec::new(),
            sweeps: Vec::new(),
            stability: None,
            extremes: Vec::new(),
            work_precision: None,
            performance: None,
            plots: Vec::new(),
            tables: Vec::new(),
            wall_seconds: 0.0,
            metadata,
            sections: Vec::new(),
        }
    }

    /// Writes `<out>/<id>.json` (the deterministic numbers) and `<out>/<id>.timings.json`
    /// (timings, timing gates and the run's metadata), split by [`split`].
    pub fn write(&self, out: &Path) -> Result<(), String> {
        let value = serde_json::to_value(self).map_err(|e| format!("{}: {e}", self.id))?;
        let parts = split(&value);
        for (name, v) in [
            (format!("{}.json", self.id), &parts.deterministic),
            (format!("{}.timings.json", self.id), &parts.varying),
        ] {
            let path = out.join(name);
            let text = serde_json::to_string_pretty(v).map_err(|e| format!("{}: {e}", self.id))?;
            std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        }
        Ok(())
    }

    /// Sets `passed` from the gates and the failure.
    pub fn conclude(&mut self) {
        self.passed =
            self.failure.is_none() && !self.gates.is_empty() && self.gates.iter().all(|g| g.passed);
    }
}
