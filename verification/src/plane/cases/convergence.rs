//! Kind `plane_convergence`: sweeps in h and k against a manufactured solution of the plane body
//! (data by automatic differentiation of formulas in `manufactured/plane.rs`), with the core's
//! rate gates, error-model gates and references.

use serde::Deserialize;

use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::convergence::{self, ConvergenceSpec, ModelGate, ReferenceSpec, SweepSelect};
use crate::core::format::{invalid, CaseError};
use crate::core::gate::RateGate;
use crate::core::report::case_report::CaseReport;
use crate::core::sweep::SweepSpec;
use crate::plane::errors::PLANE_ERRORS;
use crate::plane::study::{Discretization, ExactSpec, PlaneStudy};

/// The case body of `plane_convergence`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConvergenceCase {
    pub exact: ExactSpec,
    #[serde(default)]
    pub discretization: Discretization,
    #[serde(default)]
    pub sweep: Vec<SweepSpec<TimeScheme>>,
    #[serde(default)]
    pub gate: Vec<RateGate<SweepSelect<TimeScheme>>>,
    #[serde(default)]
    pub model_gate: Vec<ModelGate<TimeScheme>>,
    #[serde(default)]
    pub reference: Vec<ReferenceSpec<TimeScheme>>,
}

impl ConvergenceCase {
    /// The generic part.
    fn spec(&self) -> ConvergenceSpec<TimeScheme> {
        ConvergenceSpec {
            sweeps: self.sweep.clone(),
            gates: self.gate.clone(),
            model_gates: self.model_gate.clone(),
            references: self.reference.clone(),
        }
    }

    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: Self = case.body()?;
        c.spec().check(case.path(), &PLANE_ERRORS)?;
        c.exact
            .manufactured()
            .map_err(|e| invalid(case.path(), "exact.solution", &c.exact.solution, &e))?;
        Ok(c)
    }
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = ConvergenceCase::parse(case).map_err(|e| e.to_string())?;
    let study = PlaneStudy::from_case(&c.exact, &c.discretization)?;
    convergence::run(&c.spec(), &study, ctx, report)
}
