//! PLACEHOLDER: case kind `multibody_extremes` (being written).

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;

/// Checks a case of this kind.
pub fn check(_case: &Case) -> Result<(), CaseError> {
    Ok(())
}

/// Runs a case of this kind.
pub fn run(_case: &Case, _ctx: &RunContext, _report: &mut CaseReport) -> Result<(), String> {
    Err("multibody_extremes: not written yet".into())
}
