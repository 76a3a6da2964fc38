//! Case kind `multibody_extremes`: the multibody solver at the edges of its range, each extreme
//! gated against a reference the solver does not compute (docs/multibody.md).
//!
//! The setting is the `head_on` configuration of `multibody_bars`: two plane-strain bars
//! (ν = 0: exactly the 1D bar, c = √(E/ρ)) of length L at ±v meet at t0; the exact solution
//! ([`crate::exact::bar_impact::HeadOnBars`]) is contact for 2L/c under the stress ρ c v and the
//! rebound ∓v. The extremes:
//! - [`penalty`]: P = (ε/2)(g₋)² with ε → ∞ converges to the multipliers' run at O(1/ε), and the
//!   penetration is the exact force over ε;
//! - [`speeds`]: v over decades: the errors relative to v are the same at every speed (the
//!   problem is linear in v);
//! - [`large_steps`]: k of several contact durations: the energy–momentum scheme keeps P, never
//!   gains energy and never penetrates.
//!
//! The format: [`format`]; the bars: [`setup`]; what a run records: [`observe`].

pub mod format;
pub mod large_steps;
pub mod observe;
pub mod penalty;
pub mod setup;
pub mod speeds;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;

use format::ExtremesCase;

/// Checks a case of this kind.
pub fn check(case: &Case) -> Result<(), CaseError> {
    ExtremesCase::from_case(case).map(|_| ())
}

/// Runs a case of this kind.
pub fn run(case: &Case, _ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let file = ExtremesCase::from_case(case).map_err(|e| e.to_string())?;
    if let Some(spec) = &file.penalty {
        let (gates, tables) = penalty::study(&file, spec)?;
        report.gates.extend(gates);
        report.tables.extend(tables);
    }
    if let Some(spec) = &file.speeds {
        let (gates, table) = speeds::study(&file, spec)?;
        report.gates.extend(gates);
        report.tables.push(table);
    }
    if let Some(spec) = &file.large_steps {
        let (gates, table) = large_steps::study(&file, spec)?;
        report.gates.extend(gates);
        report.tables.push(table);
    }
    Ok(())
}
