//! `rod_plan_self`: the planner by self-convergence on a rod scene without an `[exact]` table
//! (`core::plan::case::run_targets_self`; docs/planner.md §4): each choice is checked against a
//! run two levels finer, within the GCI band of that reference.

use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::plan::case::{run_targets_self, PlanSpec};
use crate::core::report::case_report::CaseReport;
use crate::rod::plan::RodPlan;
use crate::rod::study::{Discretization, RodStudy};

/// The values a rod plan by self-convergence may name.
pub const ROD_SELF_FUNCTIONALS: [&str; 2] = ["end_displacement", "contact_stress"];

/// The case body of `rod_plan_self`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSelfCase {
    pub scene: toml::Table,
    pub plan: PlanSpec,
}

impl PlanSelfCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: PlanSelfCase = case.body()?;
        c.plan.check_self(case.path(), &ROD_SELF_FUNCTIONALS)?;
        Ok(c)
    }
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = PlanSelfCase::parse(case).map_err(|e| e.to_string())?;
    let study = RodStudy::new(Some(&c.scene), None, &Discretization::default())
        .map_err(|e| e.to_string())?;
    let p = RodPlan {
        study,
        base: (c.plan.base[0], c.plan.base[1]),
    };
    run_targets_self(&p, &c.plan, ctx, report)
}
