//! The dynamic-contact case family (issue: dynamic contact with energy-consistent time
//! integration). Each kind has its own file with its TOML format (`check`) and runner (`run`);
//! [`audit`] holds what every dynamic case shares: the energy-audit plots and gates.

pub mod audit;
pub mod bar_common;
pub mod bar_runs;
pub mod bar_wall;
pub mod extremes;
pub mod impact;
pub mod impact_gci;
pub mod impact_plots;
pub mod impact_runs;
pub mod manufactured;
pub mod manufactured_errors;
pub mod performance;
pub mod signorini_bar;

use crate::case::{Case, CaseError};
use crate::report::case_report::CaseReport;
use crate::run::RunContext;

/// The case kinds of the family.
pub const KINDS: [&str; 6] = [
    "dynamic_signorini_bar",
    "dynamic_bar_wall",
    "dynamic_manufactured",
    "dynamic_impact",
    "dynamic_extremes",
    "dynamic_performance",
];

/// Checks a case of the family with its kind's format.
pub fn check_case(case: &Case) -> Result<(), CaseError> {
    match case.header.kind.as_str() {
        "dynamic_signorini_bar" => signorini_bar::check(case),
        "dynamic_bar_wall" => bar_wall::check(case),
        "dynamic_manufactured" => manufactured::check(case),
        "dynamic_impact" => impact::check(case),
        "dynamic_extremes" => extremes::check(case),
        "dynamic_performance" => performance::check(case),
        other => Err(CaseError::Invalid {
            path: case.path.display().to_string(),
            field: "kind".into(),
            value: other.into(),
            expected: format!("one of {}", KINDS.join(", ")),
        }),
    }
}

/// Runs a case of the family.
pub fn run_case(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    match case.header.kind.as_str() {
        "dynamic_signorini_bar" => signorini_bar::run(case, ctx, report),
        "dynamic_bar_wall" => bar_wall::run(case, ctx, report),
        "dynamic_manufactured" => manufactured::run(case, ctx, report),
        "dynamic_impact" => impact::run(case, ctx, report),
        "dynamic_extremes" => extremes::run(case, ctx, report),
        "dynamic_performance" => performance::run(case, ctx, report),
        other => Err(format!("unknown dynamic case kind {other}")),
    }
}
