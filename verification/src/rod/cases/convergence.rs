//! Kind `rod_convergence`: sweeps in h and k against an exact solution of the rod (the paper's,
//! the constant-data family, or a manufactured one), rate gates with confidence intervals, joint
//! error-model gates, pinned reference values, and the paper's solution figures.
//!
//! The sweeps, gates and references are the core's ([`crate::core::convergence`]); this file adds
//! the rod's study and the paper's figures.

use serde::Deserialize;

use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::convergence::{self, ConvergenceSpec, ModelGate, ReferenceSpec, SweepSelect};
use crate::core::format::{invalid, CaseError};
use crate::core::gate::RateGate;
use crate::core::report::case_report::CaseReport;
use crate::core::sweep::SweepSpec;
use crate::rod::cases::paper_figures::{self, FiguresSpec};
use crate::rod::errors::ROD_ERRORS;
use crate::rod::study::{Discretization, ExactSpec, RodStudy};

/// The case body of `rod_convergence`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConvergenceCase {
    /// An inline rod scene; mesh and time are set per run.
    pub scene: Option<toml::Table>,
    pub exact: Option<ExactSpec>,
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
    pub figures: Option<FiguresSpec>,
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
        c.spec().check(case.path(), &ROD_ERRORS)?;
        if c.scene.is_none() && c.exact.is_none() {
            return Err(invalid(
                case.path(),
                "scene",
                "(missing)",
                "a [scene] or an [exact] manufactured solution",
            ));
        }
        Ok(c)
    }
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = ConvergenceCase::parse(case).map_err(|e| e.to_string())?;
    let study = RodStudy::new(c.scene.as_ref(), c.exact.as_ref(), &c.discretization)
        .map_err(|e| e.to_string())?;
    convergence::run(&c.spec(), &study, ctx, report)?;
    if let Some(fig) = &c.figures {
        paper_figures::draw(fig, &study, ctx, report)?;
    }
    Ok(())
}
