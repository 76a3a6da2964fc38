//! The quasistatic Kelvin–Voigt rod (Fernández & Sofonea 2004, Test T1D; docs/quasistatic.md).
//!
//! | kind | file | what it establishes |
//! |---|---|---|
//! | `rod_envelope` | [`cases::envelope`] | the edges of the range: M to 10⁵, N to 10⁵, graded meshes, soft and stiff foundation, every scheme — the end displacement equals the scheme's scalar recurrence to round-off; typed errors past the range |
//! | `rod_convergence` | [`cases::convergence`] | rates in h, k and h + k against exact and manufactured solutions, the joint error model, the paper's pinned values and figures |
//! | `rod_stability` | [`cases::stability`] | the explicit bound k < 2a/b: predicted against observed amplification |
//! | `rod_extremes` | [`cases::extremes`] | data at the edge of the admissible range: correct numbers or a clear error |
//! | `rod_work_precision` | [`cases::work_precision`] | error against cost for each scheme |
//! | `rod_performance` | [`cases::performance`] | the time loop at several sizes: its growth in M·N |
//! | `rod_discrete_reference` | [`cases::discrete_reference`] | the three schemes against a second implementation ([`reference`]) at round-off |

pub mod cases;
pub mod errors;
pub mod plan;
pub mod reference;
pub mod scene;
pub mod study;
pub mod vtk;

use std::path::Path;

use contactlab::scene::Scene;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;
use crate::family::Family;

/// The rod family.
pub struct Rod;

impl Family for Rod {
    fn name(&self) -> &'static str {
        "rod"
    }

    fn kinds(&self) -> &'static [&'static str] {
        &[
            "rod_convergence",
            "rod_stability",
            "rod_extremes",
            "rod_work_precision",
            "rod_performance",
            "rod_discrete_reference",
            "rod_plan",
            "rod_plan_self",
            "rod_envelope",
        ]
    }

    fn check(&self, case: &Case) -> Result<(), CaseError> {
        match case.header.kind.as_str() {
            "rod_convergence" => cases::convergence::parse(case).map(|_| ()),
            "rod_stability" => cases::stability::StabilityCase::parse(case).map(|_| ()),
            "rod_extremes" => cases::extremes::ExtremesCase::parse(case).map(|_| ()),
            "rod_work_precision" => {
                cases::work_precision::WorkPrecisionCase::parse(case).map(|_| ())
            }
            "rod_performance" => cases::performance::PerformanceCase::parse(case).map(|_| ()),
            "rod_discrete_reference" => {
                cases::discrete_reference::DiscreteReferenceCase::parse(case).map(|_| ())
            }
            "rod_plan" => cases::plan::PlanCase::parse(case).map(|_| ()),
            "rod_plan_self" => cases::plan_self::PlanSelfCase::parse(case).map(|_| ()),
            "rod_envelope" => cases::envelope::EnvelopeCase::parse(case).map(|_| ()),
            _ => Err(case.unknown_kind(self.kinds())),
        }
    }

    fn run(&self, case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
        match case.header.kind.as_str() {
            "rod_convergence" => cases::convergence::run(case, ctx, report),
            "rod_stability" => cases::stability::run(case, ctx, report),
            "rod_extremes" => cases::extremes::run(case, ctx, report),
            "rod_work_precision" => cases::work_precision::run(case, ctx, report),
            "rod_performance" => cases::performance::run(case, ctx, report),
            "rod_discrete_reference" => cases::discrete_reference::run(case, ctx, report),
            "rod_plan" => cases::plan::run(case, ctx, report),
            "rod_plan_self" => cases::plan_self::run(case, ctx, report),
            "rod_envelope" => cases::envelope::run(case, ctx, report),
            _ => Err(case.unknown_kind(self.kinds()).to_string()),
        }
    }

    fn models(&self) -> &'static [&'static str] {
        &["rod"]
    }

    fn write_scene(&self, scene: &Scene, source: &str, out: &Path) -> Result<String, String> {
        match scene {
            Scene::Rod(s) => scene::write_scene(s, source, out),
            _ => Err(format!("{source}: not a rod scene")),
        }
    }
}
