//! Bodies against bodies: node-to-segment contact of plane-strain bodies with Lagrange
//! multipliers, friction and the energy–momentum scheme (the energy–momentum paper, "EM";
//! docs/multibody.md), against exact wave solutions, the contact patch test, a closed-form slide
//! and the conservation laws.
//!
//! | kind | file | what it establishes |
//! |---|---|---|
//! | `multibody_bars` | [`cases::bars`] | two bars meeting head-on and a short bar striking a long one, against their exact wave solutions: contact duration, stress, rebound, rates in h and k |
//! | `multibody_patch` | [`cases::patch`] | the contact patch test (Taylor & Papadopoulos): two-pass passes to round-off, single-pass's failure measured |
//! | `multibody_friction` | [`cases::friction`] | a block sliding on a larger block: deceleration set by μ and the load, momentum exact, dissipation = μ N × slip, the stick time's rate in k |
//! | `multibody_impact` | [`cases::impact`] | two rings in oblique impact: EM's momenta and energy at round-off, the midpoint rule's energy error and blow-up, GCI of rebound and duration, work–precision |
//! | `multibody_extremes` | [`cases::extremes`] | steps of several contact durations, speeds over three decades, penalty → ∞ against the multipliers (compliant and conserving penalties) |
//! | `multibody_sliding` | [`cases::sliding`] | grazing impact on the foundation over decades of v_n/v_t, and a block sliding off the master's free end (the release, loaded and unloaded) |
//! | `multibody_envelope` | [`cases::envelope`] | the range's edges on the head-on bars: speeds, meshes, cells, passes, Newmark, an overlapping start; every point past the range a typed error or a stated warning |
//!
//! [`study`] holds what every kind shares: building bodies from a case's numbers, running a
//! problem with its step records, the audit's gates and plots; [`errors`] the measured
//! functionals (centre-of-mass velocities, contact intervals); [`audit_reference`] the audit's
//! own evidence (its summary from the definition, injected defects it must flag).

pub mod audit_reference;
pub mod audit_state;
pub mod cases;
pub mod errors;
pub mod scene;
pub mod scene_plan;
pub mod spec;
pub mod study;

use std::path::Path;

use contactlab::scene::Scene;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;
use crate::family::Family;

/// The multibody family.
pub struct Multibody;

impl Family for Multibody {
    fn name(&self) -> &'static str {
        "multibody"
    }

    fn kinds(&self) -> &'static [&'static str] {
        &[
            "multibody_bars",
            "multibody_patch",
            "multibody_friction",
            "multibody_impact",
            "multibody_extremes",
            "multibody_sliding",
            "multibody_envelope",
        ]
    }

    fn check(&self, case: &Case) -> Result<(), CaseError> {
        match case.header.kind.as_str() {
            "multibody_bars" => cases::bars::check(case),
            "multibody_patch" => cases::patch::check(case),
            "multibody_friction" => cases::friction::check(case),
            "multibody_impact" => cases::impact::check(case),
            "multibody_extremes" => cases::extremes::check(case),
            "multibody_sliding" => cases::sliding::check(case),
            "multibody_envelope" => cases::envelope::check(case),
            _ => Err(case.unknown_kind(self.kinds())),
        }
    }

    fn run(&self, case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
        match case.header.kind.as_str() {
            "multibody_bars" => cases::bars::run(case, ctx, report),
            "multibody_patch" => cases::patch::run(case, ctx, report),
            "multibody_friction" => cases::friction::run(case, ctx, report),
            "multibody_impact" => cases::impact::run(case, ctx, report),
            "multibody_extremes" => cases::extremes::run(case, ctx, report),
            "multibody_sliding" => cases::sliding::run(case, ctx, report),
            "multibody_envelope" => cases::envelope::run(case, ctx, report),
            _ => Err(case.unknown_kind(self.kinds()).to_string()),
        }
    }

    fn models(&self) -> &'static [&'static str] {
        &["multibody"]
    }

    fn write_scene(&self, scene: &Scene, source: &str, out: &Path) -> Result<String, String> {
        scene::write_scene(scene, source, out)
    }
}
