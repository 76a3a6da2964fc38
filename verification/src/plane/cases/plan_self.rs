//! `plane_plan_self`: the planner by self-convergence on a plane scene without an exact solution
//! (`core::plan::case::run_targets_self`; docs/planner.md §4): each choice is checked against a
//! run two levels finer, within the GCI band of that reference.

use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::plan::case::{run_targets_self, PlanSpec};
use crate::core::report::case_report::CaseReport;
use crate::plane::scene_plan::{PlaneScenePlan, PLANE_SCENE_FUNCTIONALS};

/// The case body of `plane_plan_self`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSelfCase {
    /// The scene (as in a scene file, `model = "plane"` included).
    pub scene: toml::Table,
    pub plan: PlanSpec,
}

impl PlanSelfCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: PlanSelfCase = case.body()?;
        c.plan.check_self(case.path(), &PLANE_SCENE_FUNCTIONALS)?;
        PlaneScenePlan::from_table(c.scene.clone(), "[scene]").map_err(|e| {
            crate::core::format::invalid(case.path(), "scene", e, "a plane scene on a rectangle")
        })?;
        Ok(c)
    }
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = PlanSelfCase::parse(case).map_err(|e| e.to_string())?;
    let p = PlaneScenePlan::from_table(c.scene.clone(), "[scene]")?
        .with_base((c.plan.base[0], c.plan.base[1]));
    run_targets_self(&p, &c.plan, ctx, report)
}
