//! Moving continua with contacts and sliding friction (Hetzler 2009; docs/moving_continua.md):
//! eigenvalue studies of the axially moving string (with an oscillator, ideal or penalty contact,
//! friction) and of a particle on a rotating disc, their stability verdicts and maps.
//!
//! | kind | file | what it establishes |
//! |---|---|---|
//! | `moving_string` | [`cases::string`] | ω_n = nπ(1 − v̄²) with observed rates in N and h (sine, P1, Hermite), zero real parts, the divergence boundary v̄ = 1, loci and Campbell diagram |
//! | `moving_flutter` | [`cases::flutter`] | the thick string with friction against an independent sine-Galerkin model (equal N: matrices, eigenvalues, onsets to round-off) and against the continuum's characteristic function (rates, resolved onsets) |
//! | `moving_oscillator` | [`cases::oscillator`] | the string with an oscillator against the exact characteristic equation: rates, tracked branches through veering |
//! | `moving_symmetry` | [`cases::symmetry`] | G = −Gᵀ and K_T = K_Tᵀ exactly when R_P, R_Q vanish (Figs 10–12), both directions |
//! | `moving_penalty` | [`cases::penalty`] | penalty → ideal contact at rate 1 in 1/k̄_p; with friction, the nominal circulatory parameter μ k̄_p h̄ and the flutter boundary |
//! | `moving_disc` | [`cases::disc`] | the friction damping μN/(Ω r0) recovered from the eigenvalues across Ω |
//! | `moving_time_check` | [`cases::time_check`] | every kind of verdict confirmed by time integration: observed growth rate = max Re λ |
//! | `moving_extremes` | [`cases::extremes`] | v̄ → 1, k̄_p → 10¹⁵, undamped gyroscopic–circulatory systems, near-defective eigenvalues |
//! | `moving_map` | [`cases::map`] | the 200 × 200 map, deterministic, every point checked against faer, boundaries converged in N |
//! | `moving_plate` | [`cases::plate::case`] | the rotating plate: frequencies against the Bessel characteristic equation with rates in h, the spatial-frame spectrum i(±ω − nΩ) to round-off, the Campbell diagram's tracked branches, G skew / K_T symmetric exactly where R_P / R_Q vanish |
//! | `moving_envelope` | [`cases::envelope`] | the family at the edges of its range: the verdict's flutter onset against the continuum's to N = 320 sines and M = 200 elements, the plate's frequencies to M = 512, speeds near 0 and past v̄ = 1, typed errors past the limits |
//! | `moving_plate_pad` | [`cases::plate::pad`] | the rotating plate with a stationary pad: stable below the critical speed (theorem) and destabilized above, friction flutter maps confirmed in time, the onset converged in the basis, k_p → ∞, N = 20 harmonics |

pub mod bounds;
pub mod cases;
pub mod convergence;
pub mod errors;
pub mod plate_scene;
pub mod plots;
pub mod scene;
pub mod scene_json;
pub mod study;

use std::path::Path;

use contactlab::scene::Scene;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;
use crate::family::Family;
use cases::disc::DiscCase;
use cases::envelope::EnvelopeCase;
use cases::extremes::ExtremesCase;
use cases::flutter::FlutterCase;
use cases::map::MapCase;
use cases::oscillator::OscillatorCase;
use cases::penalty::PenaltyCase;
use cases::plate::case::PlateCase;
use cases::plate::pad_format::PadCase;
use cases::string::StringCase;
use cases::symmetry::SymmetryCase;
use cases::time_check::TimeCase;

/// The moving-continuum family.
pub struct Moving;

/// A case body parsed into its kind's format `T` and checked by `check`.
fn checked<T: serde::de::DeserializeOwned>(
    case: &Case,
    check: impl Fn(&T, &std::path::Path) -> Result<(), CaseError>,
) -> Result<T, CaseError> {
    let c: T = case.body()?;
    check(&c, case.path())?;
    Ok(c)
}

impl Family for Moving {
    fn name(&self) -> &'static str {
        "moving"
    }

    fn kinds(&self) -> &'static [&'static str] {
        &[
            "moving_string",
            "moving_oscillator",
            "moving_flutter",
            "moving_symmetry",
            "moving_penalty",
            "moving_disc",
            "moving_time_check",
            "moving_extremes",
            "moving_map",
            "moving_plate",
            "moving_plate_pad",
            "moving_envelope",
        ]
    }

    fn check(&self, case: &Case) -> Result<(), CaseError> {
        match case.header.kind.as_str() {
            "moving_string" => checked(case, StringCase::check).map(|_| ()),
            "moving_oscillator" => checked(case, OscillatorCase::check).map(|_| ()),
            "moving_flutter" => checked(case, FlutterCase::check).map(|_| ()),
            "moving_symmetry" => checked(case, SymmetryCase::check).map(|_| ()),
            "moving_penalty" => checked(case, PenaltyCase::check).map(|_| ()),
            "moving_disc" => checked(case, DiscCase::check).map(|_| ()),
            "moving_time_check" => checked(case, TimeCase::check).map(|_| ()),
            "moving_extremes" => checked(case, ExtremesCase::check).map(|_| ()),
            "moving_map" => checked(case, MapCase::check).map(|_| ()),
            "moving_plate" => checked(case, PlateCase::check).map(|_| ()),
            "moving_plate_pad" => checked(case, PadCase::check).map(|_| ()),
            "moving_envelope" => checked(case, EnvelopeCase::check).map(|_| ()),
            _ => Err(case.unknown_kind(self.kinds())),
        }
    }

    fn run(&self, case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
        let e = |e: CaseError| e.to_string();
        match case.header.kind.as_str() {
            "moving_string" => {
                cases::string::run(&checked(case, StringCase::check).map_err(e)?, ctx, report)
            }
            "moving_oscillator" => cases::oscillator::run(
                &checked(case, OscillatorCase::check).map_err(e)?,
                ctx,
                report,
            ),
            "moving_flutter" => {
                cases::flutter::run(&checked(case, FlutterCase::check).map_err(e)?, ctx, report)
            }
            "moving_symmetry" => {
                cases::symmetry::run(&checked(case, SymmetryCase::check).map_err(e)?, ctx, report)
            }
            "moving_penalty" => {
                cases::penalty::run(&checked(case, PenaltyCase::check).map_err(e)?, ctx, report)
            }
            "moving_disc" => {
                cases::disc::run(&checked(case, DiscCase::check).map_err(e)?, ctx, report)
            }
            "moving_time_check" => {
                cases::time_check::run(&checked(case, TimeCase::check).map_err(e)?, ctx, report)
            }
            "moving_extremes" => {
                cases::extremes::run(&checked(case, ExtremesCase::check).map_err(e)?, ctx, report)
            }
            "moving_map" => {
                cases::map::run(&checked(case, MapCase::check).map_err(e)?, ctx, report)
            }
            "moving_plate" => {
                cases::plate::case::run(&checked(case, PlateCase::check).map_err(e)?, ctx, report)
            }
            "moving_plate_pad" => {
                cases::plate::pad::run(&checked(case, PadCase::check).map_err(e)?, ctx, report)
            }
            "moving_envelope" => {
                cases::envelope::run(&checked(case, EnvelopeCase::check).map_err(e)?, ctx, report)
            }
            _ => Err(case.unknown_kind(self.kinds()).to_string()),
        }
    }

    fn models(&self) -> &'static [&'static str] {
        &["moving_string", "disc_particle", "rotating_plate"]
    }

    fn write_scene(&self, scene: &Scene, source: &str, out: &Path) -> Result<String, String> {
        match scene {
            Scene::Moving(s) => scene::write_scene(s, source, out),
            _ => Err(format!("{source}: not a moving-continuum scene")),
        }
    }
}
