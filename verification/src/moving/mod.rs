//! The verification of the moving-continuum models (Hetzler 2009; `shared/spec/moving-continua.md`):
//! case kinds starting with `moving_`, their runners, exact solutions and plots.
//!
//! | kind | runner | what it establishes |
//! |---|---|---|
//! | `moving_string` | [`string_case`] | ω_n = nπ(1 − v̄²) with observed rates in N and h (sine, P1, Hermite), zero real parts, the divergence boundary v̄ = 1, loci and Campbell diagram |
//! | `moving_oscillator` | [`oscillator_case`] | the string with an oscillator against the exact characteristic equation: rates, tracked branches through veering |
//! | `moving_symmetry` | [`symmetry_case`] | G = −Gᵀ and K_T = K_Tᵀ exactly when R_P, R_Q vanish (Figs 10–12), both directions |
//! | `moving_penalty` | [`penalty_case`] | penalty → ideal contact at rate 1 in 1/k̄_p; with friction, the nominal circulatory parameter μ k̄_p h̄ and the flutter boundary |
//! | `moving_disc` | [`disc_case`] | the friction damping μN/(Ω r0) recovered from the eigenvalues across Ω |
//! | `moving_time_check` | [`time_case`] | every kind of verdict confirmed by time integration: observed growth rate = max Re λ |
//! | `moving_extremes` | [`extremes_case`] | v̄ → 1, k̄_p → 10¹⁵, undamped gyroscopic–circulatory systems, near-defective eigenvalues |
//! | `moving_map` | [`map_case`] | the 200 × 200 map under its time budget, deterministic, every point checked against faer, boundaries converged in N |
//!
//! Each runner writes its detailed numbers to `<out>/<case id>/data.json`.

pub mod disc_case;
pub mod exact;
pub mod extremes_case;
pub mod format;
pub mod growth;
pub mod map_case;
pub mod oscillator_case;
pub mod penalty_case;
pub mod plots;
pub mod scene;
pub mod string_case;
pub mod symmetry_case;
pub mod time_case;

use crate::case::{Case, CaseError};
use crate::report::case_report::CaseReport;
use crate::run::RunContext;

/// The case kinds of this module.
pub const KINDS: [&str; 8] = [
    "moving_string",
    "moving_oscillator",
    "moving_symmetry",
    "moving_penalty",
    "moving_disc",
    "moving_time_check",
    "moving_extremes",
    "moving_map",
];

/// Checks a `moving_*` case with its kind's format.
pub fn check_case(case: &Case) -> Result<(), CaseError> {
    let p = case.path.as_path();
    match case.header.kind.as_str() {
        "moving_string" => format::parse::<string_case::StringCase>(case).map(|c| c.check(p))?,
        "moving_oscillator" => {
            format::parse::<oscillator_case::OscillatorCase>(case).map(|c| c.check(p))?
        }
        "moving_symmetry" => {
            format::parse::<symmetry_case::SymmetryCase>(case).map(|c| c.check(p))?
        }
        "moving_penalty" => format::parse::<penalty_case::PenaltyCase>(case).map(|c| c.check(p))?,
        "moving_disc" => format::parse::<disc_case::DiscCase>(case).map(|c| c.check(p))?,
        "moving_time_check" => format::parse::<time_case::TimeCase>(case).map(|c| c.check(p))?,
        "moving_extremes" => {
            format::parse::<extremes_case::ExtremesCase>(case).map(|c| c.check(p))?
        }
        "moving_map" => format::parse::<map_case::MapCase>(case).map(|c| c.check(p))?,
        other => Err(CaseError::Invalid {
            path: p.display().to_string(),
            field: "kind".into(),
            value: other.into(),
            expected: format!("one of {}", KINDS.join(", ")),
        }),
    }
}

/// Runs a `moving_*` case into `report`.
pub fn run_case(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let e = |e: CaseError| e.to_string();
    match case.header.kind.as_str() {
        "moving_string" => string_case::run(&format::parse(case).map_err(e)?, ctx, report),
        "moving_oscillator" => oscillator_case::run(&format::parse(case).map_err(e)?, ctx, report),
        "moving_symmetry" => symmetry_case::run(&format::parse(case).map_err(e)?, ctx, report),
        "moving_penalty" => penalty_case::run(&format::parse(case).map_err(e)?, ctx, report),
        "moving_disc" => disc_case::run(&format::parse(case).map_err(e)?, ctx, report),
        "moving_time_check" => time_case::run(&format::parse(case).map_err(e)?, ctx, report),
        "moving_extremes" => extremes_case::run(&format::parse(case).map_err(e)?, ctx, report),
        "moving_map" => map_case::run(&format::parse(case).map_err(e)?, ctx, report),
        other => Err(format!("unknown moving case kind {other}")),
    }
}
