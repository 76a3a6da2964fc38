//! `dynamic_plan_self`: the planner by self-convergence on a dynamic scene without an exact
//! solution (`core::plan::case::run_targets_self`; docs/planner.md §4): each choice is checked
//! against a run two levels finer, within the GCI band of that reference.

use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::{invalid, CaseError};
use crate::core::plan::case::{run_targets_self, PlanSpec};
use crate::core::report::case_report::CaseReport;
use crate::dynamic::cases::impact::format::scene_file;
use crate::dynamic::scene_plan::{DynamicScenePlan, BAR_FUNCTIONALS, PLANE_FUNCTIONALS};

/// The case body of `dynamic_plan_self`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSelfCase {
    /// The scene file (`model = "dynamic"`), relative to the case file.
    pub scene: String,
    pub plan: PlanSpec,
}

impl PlanSelfCase {
    /// Parses and checks the case body: the plan, the scene and its functional.
    pub fn parse(case: &Case) -> Result<(Self, DynamicScenePlan), CaseError> {
        let c: PlanSelfCase = case.body()?;
        let known: Vec<&str> = PLANE_FUNCTIONALS
            .iter()
            .chain(BAR_FUNCTIONALS.iter())
            .copied()
            .collect();
        c.plan.check_self(case.path(), &known)?;
        let (path, source) = scene_file(case.path(), &c.scene)
            .map_err(|e| invalid(case.path(), "scene", &c.scene, &e))?;
        let p = DynamicScenePlan::from_table(
            source.table,
            &path.display().to_string(),
            &c.plan.functional,
        )
        .map_err(|e| invalid(case.path(), "scene", &c.scene, &e))?
        .with_base((c.plan.base[0], c.plan.base[1]));
        Ok((c, p))
    }
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let (c, p) = PlanSelfCase::parse(case).map_err(|e| e.to_string())?;
    run_targets_self(&p, &c.plan, ctx, report)
}
