//! `dynamic_plan`: the planner itself under test on the dynamic manufactured problem
//! (`core::plan::case`; docs/planner.md §4). The cost is the deterministic work n²·N.

use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::plan::case::{run_targets, PlanSpec};
use crate::core::report::case_report::CaseReport;
use crate::dynamic::plan::DynamicPlan;
use crate::manufactured::dynamic_plane::{DynamicManufactured, ManufacturedLaw};

/// The case body of `dynamic_plan`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanCase {
    /// The material law of the manufactured problem (`linear`, …).
    pub law: ManufacturedLaw,
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
    let p = DynamicPlan {
        exact: DynamicManufactured::standard(c.law),
        base: (c.plan.base[0], c.plan.base[1]),
    };
    run_targets(&p, &c.plan, ctx, report)
}
