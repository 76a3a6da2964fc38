//! `rod_plan`: the planner itself under test on a rod scene with an exact solution
//! (`core::plan::case`; docs/planner.md §4). The cost is the deterministic work M·N.

use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::plan::case::{run_targets, PlanSpec};
use crate::core::report::case_report::CaseReport;
use crate::rod::plan::RodPlan;
use crate::rod::study::{Discretization, ExactSpec, RodStudy};

/// The case body of `rod_plan`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanCase {
    pub scene: toml::Table,
    pub exact: ExactSpec,
    pub plan: PlanSpec,
}

impl PlanCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: PlanCase = case.body()?;
        c.plan.check(case.path())?;
        Ok(c)
    }
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = PlanCase::parse(case).map_err(|e| e.to_string())?;
    let study = RodStudy::new(Some(&c.scene), Some(&c.exact), &Discretization::default())
        .map_err(|e| e.to_string())?;
    let p = RodPlan {
        study,
        base: (c.plan.base[0], c.plan.base[1]),
    };
    run_targets(&p, &c.plan, ctx, report)
}
