//! The levels of a sweep: what a case asks for (`[[sweep]]`: M elements and N steps per level, the
//! schemes) and what one run at a level measured ([`Level`]), with the parameter a rate is
//! measured against.

use std::collections::BTreeMap;
use std::fmt::Display;
use std::path::Path;
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::core::format::{invalid, CaseError};

/// The parameter a rate is measured against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Against {
    H,
    K,
    HPlusK,
}

impl Against {
    /// The label used in reports.
    pub fn label(self) -> &'static str {
        match self {
            Against::H => "h",
            Against::K => "k",
            Against::HPlusK => "h + k",
        }
    }

    /// The label used in file names.
    pub fn file_label(self) -> &'static str {
        match self {
            Against::H => "h",
            Against::K => "k",
            Against::HPlusK => "h_plus_k",
        }
    }

    /// The parameter value of a level.
    pub fn of(self, level: &Level) -> f64 {
        match self {
            Against::H => level.h,
            Against::K => level.k,
            Against::HPlusK => level.h + level.k,
        }
    }
}

/// One run of a study at (M, N, scheme).
#[derive(Debug, Clone, Serialize)]
pub struct Level {
    pub elements: usize,
    pub steps: usize,
    /// Largest element size.
    pub h: f64,
    /// Largest time step.
    pub k: f64,
    pub scheme: String,
    /// Error functionals by name (empty without an exact solution).
    pub errors: BTreeMap<String, f64>,
    /// Values of output functionals by name (the planner's self-convergence: a contact force at
    /// T, a rebound velocity; empty where a study measures errors only).
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub values: BTreeMap<String, f64>,
    /// The study's end value (the rod: u_h(L, T); a plane body: max |u_N|).
    pub u_end: f64,
    /// Wall time of the solver run including the error evaluation (s).
    pub cpu_seconds: f64,
    /// The CPU time of the same on its thread (s; not in the reports: a timing the planner's
    /// cost model may be fitted on, `Plannable::run_seconds`).
    #[serde(skip)]
    pub thread_seconds: f64,
    /// The solver's statistics (the model's own statistics type, as JSON).
    pub stats: serde_json::Value,
}

/// What one run of a study measured, before it is filed as a [`Level`].
#[derive(Debug, Clone)]
pub struct Measured<St> {
    /// Largest element size.
    pub h: f64,
    /// Largest time step.
    pub k: f64,
    /// Error functionals by name.
    pub errors: BTreeMap<String, f64>,
    /// The study's end value.
    pub u_end: f64,
    /// The solver's statistics.
    pub stats: St,
}

impl Level {
    /// Times `run` (a solver run with its error evaluation at M = `elements`, N = `steps` with
    /// `scheme`) and files what it measured as the level: its wall time as `cpu_seconds`, its
    /// statistics as JSON (null when they do not serialize).
    pub fn timed<St: Serialize, E>(
        elements: usize,
        steps: usize,
        scheme: impl Display,
        run: impl FnOnce() -> Result<Measured<St>, E>,
    ) -> Result<Self, E> {
        let start = Instant::now();
        let thread_start = crate::core::cpu_clock::thread_cpu_seconds();
        let m = run()?;
        let thread_seconds = crate::core::cpu_clock::thread_cpu_seconds() - thread_start;
        let cpu_seconds = start.elapsed().as_secs_f64();
        Ok(Self {
            elements,
            steps,
            h: m.h,
            k: m.k,
            scheme: scheme.to_string(),
            errors: m.errors,
            values: BTreeMap::new(),
            u_end: m.u_end,
            cpu_seconds,
            thread_seconds,
            stats: serde_json::to_value(&m.stats).unwrap_or(serde_json::Value::Null),
        })
    }
}

/// `[[sweep]]`: a list of levels (M elements, N steps), each run with each scheme.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec<S> {
    pub name: String,
    pub elements: Vec<usize>,
    /// One entry per level, or a single entry used for every level.
    pub steps: Vec<usize>,
    #[serde(default = "Vec::new")]
    pub schemes: Vec<S>,
    /// Also measure the time error against the study's same-mesh reference run.
    #[serde(default)]
    pub time_error: bool,
}

impl<S: Copy> SweepSpec<S> {
    /// The (M, N) levels.
    pub fn levels(&self) -> Vec<(usize, usize)> {
        let n = self.elements.len().max(self.steps.len());
        (0..n)
            .map(|i| {
                let m = *self.elements.get(i).unwrap_or(&self.elements[0]);
                let s = *self.steps.get(i).unwrap_or(&self.steps[0]);
                (m, s)
            })
            .collect()
    }

    /// The schemes the sweep runs (`default` when it names none).
    pub fn schemes_or(&self, default: S) -> Vec<S> {
        if self.schemes.is_empty() {
            vec![default]
        } else {
            self.schemes.clone()
        }
    }

    /// Checks the level lists; `field` names the sweep in errors (`sweep[0]`).
    pub fn check(&self, path: &Path, field: &str) -> Result<(), CaseError> {
        if self.elements.is_empty() || self.steps.is_empty() {
            return Err(invalid(
                path,
                field,
                "(empty)",
                "non-empty elements and steps",
            ));
        }
        if self.elements.len() != self.steps.len()
            && self.elements.len() != 1
            && self.steps.len() != 1
        {
            return Err(invalid(
                path,
                &format!("{field}.steps"),
                format!("{} entries", self.steps.len()),
                "one entry per level, or a single entry",
            ));
        }
        Ok(())
    }
}

/// The runs of one sweep with one scheme.
#[derive(Debug, Clone, Serialize)]
pub struct SweepReport {
    pub name: String,
    pub scheme: String,
    /// Levels in the order of the case file.
    pub levels: Vec<Level>,
}
