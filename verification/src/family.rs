//! A model family of the verification suite: the case kinds it owns, and the `verify scene`
//! writer of its scene models.
//!
//! Every family folder has the same shape — `mod.rs` (this trait), `study.rs` (one run of the
//! model at a discretization level), `errors.rs` (its error functionals against exact or
//! manufactured solutions), `scene.rs` (case scenes and the `verify scene` writer) and `cases/`
//! (one file per case kind: its format and runner). A family imports the core and the shared
//! modules (`stats`, `plot`, `exact`, `manufactured`), never another family.

use std::path::Path;

use contactlab::scene::Scene;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;

/// A model family.
pub trait Family: Sync {
    /// The family's name, as its case kinds start (`rod`, `plane`, `dynamic`, `moving`).
    fn name(&self) -> &'static str;

    /// The case kinds the family owns.
    fn kinds(&self) -> &'static [&'static str];

    /// Checks a case of one of its kinds with the kind's format.
    fn check(&self, case: &Case) -> Result<(), CaseError>;

    /// Runs a case of one of its kinds, filling its report; a failure to set up or run is the
    /// error (the report then records it and fails the case).
    fn run(&self, case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String>;

    /// The scene models (`model = "…"`) whose results the family writes.
    fn models(&self) -> &'static [&'static str];

    /// Runs a user's scene (`source` names its file) and writes its results into `out`; returns
    /// a summary.
    fn write_scene(&self, scene: &Scene, source: &str, out: &Path) -> Result<String, String>;
}
