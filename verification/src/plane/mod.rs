//! The quasistatic Kelvin–Voigt plane body (Fernández & Sofonea 2004, §4.2 and beyond;
//! docs/quasistatic.md): P1 triangles, plane stress or strain, linear or nonlinear A and B, a
//! damped foundation on Γ3.
//!
//! | kind | file | what it establishes |
//! |---|---|---|
//! | `plane_convergence` | [`cases::convergence`] | rates in h and k against manufactured solutions whose data come from laws written in this crate (energy O(h), L² O(h²), the paper's E O(h + k); time orders by scheme against a field in V^h, whose error is the time error alone) |
//! | `plane_paper_test_2d` | [`cases::paper_test_2d`] | the paper's Test 2D under both readings of Γ1: mesh-converged quantities with their GCI set beside Figs 11–15, the rollers' rigid sinking against its closed form |
//! | `plane_stability` | [`cases::stability`] | the explicit bound k λ_max(A⁻¹B) < 2 |
//! | `plane_paths` | [`cases::paths`] | the condensed and Newton paths agree; error against cost of both |
//! | `plane_performance` | [`cases::performance`] | the Test 2D time loop and its cost against the sparse solve |
//! | `plane_envelope` | [`cases::envelope`] | the edges of the range: Gmsh blocks with a hole and fine rectangles, many steps, both contact integrations — every point answers on both paths and they agree to round-off; one factorization per uniform grid; typed errors past the range |
//! | `plane_gmsh` | [`cases::gmsh`] | Gmsh meshes: the three formats against our own rectangle, rates on the files' meshes, the two-material strip's closed form, every mesh check on crafted files |

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

/// The plane family.
pub struct Plane;

impl Family for Plane {
    fn name(&self) -> &'static str {
        "plane"
    }

    fn kinds(&self) -> &'static [&'static str] {
        &[
            "plane_convergence",
            "plane_paper_test_2d",
            "plane_stability",
            "plane_paths",
            "plane_performance",
            "plane_gmsh",
            "plane_plan",
            "plane_plan_self",
            "plane_envelope",
        ]
    }

    fn check(&self, case: &Case) -> Result<(), CaseError> {
        match case.header.kind.as_str() {
            "plane_convergence" => cases::convergence::parse(case).map(|_| ()),
            "plane_paper_test_2d" => cases::paper_test_2d::PaperTestCase::parse(case).map(|_| ()),
            "plane_stability" => cases::stability::StabilityCase::parse(case).map(|_| ()),
            "plane_paths" => cases::paths::PathsCase::parse(case).map(|_| ()),
            "plane_performance" => cases::performance::PerformanceCase::parse(case).map(|_| ()),
            "plane_gmsh" => cases::gmsh::parse(case).map(|_| ()),
            "plane_plan" => cases::plan::PlanCase::parse(case).map(|_| ()),
            "plane_plan_self" => cases::plan_self::PlanSelfCase::parse(case).map(|_| ()),
            "plane_envelope" => cases::envelope::EnvelopeCase::parse(case).map(|_| ()),
            _ => Err(case.unknown_kind(self.kinds())),
        }
    }

    fn run(&self, case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
        match case.header.kind.as_str() {
            "plane_convergence" => cases::convergence::run(case, ctx, report),
            "plane_paper_test_2d" => cases::paper_test_2d::run(case, ctx, report),
            "plane_stability" => cases::stability::run(case, ctx, report),
            "plane_paths" => cases::paths::run(case, ctx, report),
            "plane_performance" => cases::performance::run(case, ctx, report),
            "plane_gmsh" => cases::gmsh::run(case, ctx, report),
            "plane_plan" => cases::plan::run(case, ctx, report),
            "plane_plan_self" => cases::plan_self::run(case, ctx, report),
            "plane_envelope" => cases::envelope::run(case, ctx, report),
            _ => Err(case.unknown_kind(self.kinds()).to_string()),
        }
    }

    fn models(&self) -> &'static [&'static str] {
        &["plane"]
    }

    fn write_scene(&self, scene: &Scene, source: &str, out: &Path) -> Result<String, String> {
        match scene {
            Scene::Plane(s) => scene::write_scene(s, source, out),
            _ => Err(format!("{source}: not a plane scene")),
        }
    }
}
