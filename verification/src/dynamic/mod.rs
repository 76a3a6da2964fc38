//! Dynamic contact with energy-consistent time integration (Barboteu–Danan–Sofonea 2015,
//! "BDS"; Hauret–Le Tallec 2006, "HLT"; docs/dynamic.md): bars and plane-strain bodies against a
//! rigid foundation, Newmark, the midpoint rule and Gonzalez's scheme, every run audited for the
//! discrete energy identities.
//!
//! | kind | file | what it establishes |
//! |---|---|---|
//! | `dynamic_signorini_bar` | [`cases::signorini_bar`] | the periodic Signorini bar against its exact solution: rates by treatment and scheme, energy conservation |
//! | `dynamic_bar_wall` | [`cases::bar_wall`] | a free bar hitting a rigid wall: contact time, plateau stress, rebound, energy returned |
//! | `dynamic_manufactured` | [`cases::manufactured`] | 2D elastodynamics with persistent compliance contact: orders in k and h, identities at round-off |
//! | `dynamic_impact` | [`cases::impact`] | BDS §1.7.1–1.7.2 impacts: identities per step, friction and stage-(b) work, grid convergence |
//! | `dynamic_extremes` | [`cases::extremes`] | blow-up of the midpoint rule, penalty 1 … 1e14, impact speeds, large steps |
//! | `dynamic_performance` | [`cases::performance`] | cost per step against dofs on both solver paths, the ring impact's time |
//! | `dynamic_friction` | [`cases::friction`] | Coulomb friction in size: a sliding block against its closed form (rates in k, the stop), a loaded block's step equations and momentum invariant |
//! | `dynamic_plan` | [`cases::plan`] | the planner on the manufactured problem: achieved against target, cost against a grid search |
//! | `dynamic_plan_self` | [`cases::plan_self`] | the planner by self-convergence on a scene (the ring impact): achieved against a run two levels finer |
//!
//! [`study`] holds what every kind shares: the audited run, its plots and gates.

pub mod audit_state;
pub mod cases;
pub mod errors;
pub mod plan;
pub mod scene;
pub mod scene_plan;
pub mod study;
pub mod vtk;

use std::path::Path;

use contactlab::scene::Scene;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;
use crate::family::Family;

/// The dynamic-contact family.
pub struct Dynamic;

impl Family for Dynamic {
    fn name(&self) -> &'static str {
        "dynamic"
    }

    fn kinds(&self) -> &'static [&'static str] {
        &[
            "dynamic_signorini_bar",
            "dynamic_bar_wall",
            "dynamic_manufactured",
            "dynamic_impact",
            "dynamic_extremes",
            "dynamic_performance",
            "dynamic_friction",
            "dynamic_plan",
            "dynamic_plan_self",
            "dynamic_envelope",
        ]
    }

    fn check(&self, case: &Case) -> Result<(), CaseError> {
        match case.header.kind.as_str() {
            "dynamic_signorini_bar" => cases::signorini_bar::check(case),
            "dynamic_bar_wall" => cases::bar_wall::check(case),
            "dynamic_manufactured" => cases::manufactured::check(case),
            "dynamic_impact" => cases::impact::check(case),
            "dynamic_extremes" => cases::extremes::check(case),
            "dynamic_performance" => cases::performance::check(case),
            "dynamic_friction" => cases::friction::check(case),
            "dynamic_plan" => cases::plan::PlanCase::parse(case).map(|_| ()),
            "dynamic_plan_self" => cases::plan_self::PlanSelfCase::parse(case).map(|_| ()),
            "dynamic_envelope" => cases::envelope::check(case),
            _ => Err(case.unknown_kind(self.kinds())),
        }
    }

    fn run(&self, case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
        match case.header.kind.as_str() {
            "dynamic_signorini_bar" => cases::signorini_bar::run(case, ctx, report),
            "dynamic_bar_wall" => cases::bar_wall::run(case, ctx, report),
            "dynamic_manufactured" => cases::manufactured::run(case, ctx, report),
            "dynamic_impact" => cases::impact::run(case, ctx, report),
            "dynamic_extremes" => cases::extremes::run(case, ctx, report),
            "dynamic_performance" => cases::performance::run(case, ctx, report),
            "dynamic_friction" => cases::friction::run(case, ctx, report),
            "dynamic_plan" => cases::plan::run(case, ctx, report),
            "dynamic_plan_self" => cases::plan_self::run(case, ctx, report),
            "dynamic_envelope" => cases::envelope::run(case, ctx, report),
            _ => Err(case.unknown_kind(self.kinds()).to_string()),
        }
    }

    fn models(&self) -> &'static [&'static str] {
        &["dynamic"]
    }

    fn write_scene(&self, scene: &Scene, source: &str, out: &Path) -> Result<String, String> {
        match scene {
            Scene::Dynamic(s) => scene::write_scene(s, source, out),
            _ => Err(format!("{source}: not a dynamic scene")),
        }
    }
}
