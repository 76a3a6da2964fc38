//! Kind `plane_convergence`: sweeps in h and k against a manufactured solution of the plane body
//! (data by automatic differentiation of formulas in `manufactured/plane.rs`), with the core's
//! rate gates, error-model gates and references.

use serde::Deserialize;

use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::convergence;
use crate::core::format::{invalid, CaseError};
use crate::core::report::case_report::CaseReport;
use crate::plane::errors::PLANE_ERRORS;
use crate::plane::study::{Discretization, ExactSpec, PlaneStudy};

/// The plane's keys of a `plane_convergence` body (the sweeps, gates and references are the
/// core's).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneKeys {
    pub exact: ExactSpec,
    #[serde(default)]
    pub discretization: Discretization,
}

/// The case body of `plane_convergence`.
pub type ConvergenceCase = convergence::ConvergenceCase<PlaneKeys, TimeScheme>;

/// Parses and checks the case body (the manufactured solution must be one of
/// `manufactured/plane.rs`).
pub fn parse(case: &Case) -> Result<ConvergenceCase, CaseError> {
    let c = ConvergenceCase::parse(case, &PLANE_ERRORS)?;
    let exact = &c.family.exact;
    exact
        .manufactured()
        .map_err(|e| invalid(case.path(), "exact.solution", &exact.solution, &e))?;
    Ok(c)
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = parse(case).map_err(|e| e.to_string())?;
    let study = PlaneStudy::from_case(&c.family.exact, &c.family.discretization)?;
    convergence::run(&c.spec, &study, ctx, report)
}
