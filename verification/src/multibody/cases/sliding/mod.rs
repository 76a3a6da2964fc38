//! Case kind `multibody_sliding`: the extremes of tangential motion (docs/multibody.md), each
//! gated against a reference the solver does not compute ([`reference`]):
//! - [`grazing`]: a bar striking the rigid foundation at a grazing angle, v_n/v_t over decades:
//!   the tangential velocity is untouched (frictionless flat contact has no x-force), the normal
//!   motion is the bar-on-wall solution, the same relative to v_n at every angle;
//! - [`slide_off`]: a block sliding along a longer one and off its free end: rigid translation
//!   exact without load, each node released in the step the kinematics give, P exact and no
//!   energy gain when the interface is loaded.
//!
//! The format: [`format`]; the bodies and what a run observes: [`setup`].

pub mod format;
pub mod grazing;
pub mod reference;
pub mod setup;
pub mod slide_off;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;

use format::SlidingCase;

/// Checks a case of this kind.
pub fn check(case: &Case) -> Result<(), CaseError> {
    SlidingCase::from_case(case).map(|_| ())
}

/// Runs a case of this kind.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let file = SlidingCase::from_case(case).map_err(|e| e.to_string())?;
    if let Some(spec) = &file.grazing {
        grazing::study(&file, spec, ctx, report)?;
    }
    if let Some(spec) = &file.slide_off {
        slide_off::study(&file, spec, ctx, report)?;
    }
    Ok(())
}
