//! Kind `rod_convergence`: sweeps in h and k against an exact solution of the rod (the paper's,
//! the constant-data family, or a manufactured one), rate gates with confidence intervals, joint
//! error-model gates, pinned reference values, and the paper's solution figures.
//!
//! The sweeps and gates are the core's ([`crate::core::convergence`]); this file adds
//! the rod's study and the paper's figures.

use serde::Deserialize;

use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::convergence;
use crate::core::format::{invalid, CaseError};
use crate::core::report::case_report::CaseReport;
use crate::rod::cases::paper_figures::{self, FiguresSpec};
use crate::rod::errors::ROD_ERRORS;
use crate::rod::study::{Discretization, ExactSpec, RodStudy};

/// The rod's keys of a `rod_convergence` body (the sweeps and gates are the core's).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RodKeys {
    /// An inline rod scene; mesh and time are set per run.
    pub scene: Option<toml::Table>,
    pub exact: Option<ExactSpec>,
    #[serde(default)]
    pub discretization: Discretization,
    pub figures: Option<FiguresSpec>,
}

/// The case body of `rod_convergence`.
pub type ConvergenceCase = convergence::ConvergenceCase<RodKeys, TimeScheme>;

/// Parses and checks the case body (it needs a scene or an exact solution).
pub fn parse(case: &Case) -> Result<ConvergenceCase, CaseError> {
    let c = ConvergenceCase::parse(case, &ROD_ERRORS)?;
    if c.family.scene.is_none() && c.family.exact.is_none() {
        return Err(invalid(
            case.path(),
            "scene",
            "(missing)",
            "a [scene] or an [exact] manufactured solution",
        ));
    }
    Ok(c)
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = parse(case).map_err(|e| e.to_string())?;
    let k = &c.family;
    let study = RodStudy::new(k.scene.as_ref(), k.exact.as_ref(), &k.discretization)
        .map_err(|e| e.to_string())?;
    convergence::run(&c.spec, &study, ctx, report)?;
    if let Some(fig) = &k.figures {
        paper_figures::draw(fig, &study, ctx, report)?;
    }
    Ok(())
}
