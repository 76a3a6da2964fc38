//! Kind `plane_convergence`: sweeps in h and k against a manufactured solution of the plane body
//! (data by automatic differentiation of formulas in `manufactured/plane.rs`), with the core's
//! rate gates and error-model gates.

use serde::Deserialize;

use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::convergence;
use crate::core::format::{invalid, CaseError};
use crate::core::report::case_report::CaseReport;
use crate::plane::errors::PLANE_ERRORS;
use crate::plane::study::{Discretization, ExactSpec, PlaneStudy};

/// The plane's keys of a `plane_convergence` body (the sweeps and gates are the
/// core's).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneKeys {
    pub exact: ExactSpec,
    #[serde(default)]
    pub discretization: Discretization,
}

/// The case body of `plane_convergence`.
pub type ConvergenceCase = convergence::ConvergenceCase<PlaneKeys, TimeScheme>;

/// The error measured against a run of the same code (a diagnostic, never a gate).
pub const SAME_CODE_ERROR: &str = "time_l2_final";

/// Parses and checks the case body: the manufactured solution must be one of
/// `manufactured/plane.rs`, and no gate may compare with a run of the same code
/// (`time_l2_final` is a diagnostic column of the sweep tables only).
pub fn parse(case: &Case) -> Result<ConvergenceCase, CaseError> {
    let c = ConvergenceCase::parse(case, &PLANE_ERRORS)?;
    c.family.exact.check(case.path())?;
    let expected = "an error against the exact solution (time_l2_final compares with a run of the \
                    same code: a diagnostic, not a gate)";
    for (i, g) in c.spec.gates.iter().enumerate() {
        if g.select.error == SAME_CODE_ERROR {
            return Err(invalid(
                case.path(),
                &format!("gate[{i}].error"),
                SAME_CODE_ERROR,
                expected,
            ));
        }
    }
    for (i, g) in c.spec.model_gates.iter().enumerate() {
        if g.error == SAME_CODE_ERROR {
            return Err(invalid(
                case.path(),
                &format!("model_gate[{i}].error"),
                SAME_CODE_ERROR,
                expected,
            ));
        }
    }
    Ok(c)
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = parse(case).map_err(|e| e.to_string())?;
    let study = PlaneStudy::from_case(&c.family.exact, &c.family.discretization)?;
    convergence::run(&c.spec, &study, ctx, report)
}

#[cfg(test)]
mod tests {
    //! The plane convergence format: a gate against a run of the same code is a typed error naming
    //! the gate; an affine field without its switching time, or with one outside (0, T), names
    //! `exact.switch_time`; a gate against the exact solution parses.
    use super::*;
    use std::path::Path;

    fn case(exact: &str, gate_error: &str) -> Result<ConvergenceCase, CaseError> {
        let text = format!(
            "id = \"t\"\ntitle = \"t\"\nkind = \"plane_convergence\"\ntier = \"quick\"\n\
             explanation = \"t\"\n[exact]\n{exact}\n[discretization]\ntime_reference_steps = 64\n\
             [[sweep]]\nname = \"k\"\ntime_error = true\nelements = [4]\nsteps = [4, 8, 16]\n\
             [[gate]]\nsweep = \"k\"\nerror = \"{gate_error}\"\nagainst = \"k\"\n\
             expected_rate = 2.0\ntolerance = 0.1\nci_width = 0.1\n"
        );
        parse(&Case::from_text(Path::new("t.toml"), &text)?)
    }

    #[test]
    fn a_gate_on_the_same_code_reference_is_a_typed_error() {
        let e = case("solution = \"plane_manufactured_linear\"", "time_l2_final")
            .map(|_| ())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("gate[0].error") && e.contains("same code"),
            "{e}"
        );
        assert!(case("solution = \"plane_manufactured_linear\"", "l2_final").is_ok());
    }

    #[test]
    fn the_affine_field_needs_a_switching_time_inside_the_run() {
        for bad in ["", "switch_time = 0.0", "switch_time = 1.5"] {
            let exact =
                format!("solution = \"plane_manufactured_linear\"\nfield = \"affine\"\n{bad}");
            let e = case(&exact, "l2_final")
                .map(|_| ())
                .unwrap_err()
                .to_string();
            assert!(e.contains("exact.switch_time"), "{e}");
        }
        let e = case(
            "solution = \"plane_manufactured_linear\"\nswitch_time = 0.5",
            "l2_final",
        )
        .map(|_| ())
        .unwrap_err()
        .to_string();
        assert!(e.contains("exact.switch_time"), "{e}");
        let e = case(
            "solution = \"plane_manufactured_linear\"\nbeta = -1.0",
            "l2_final",
        )
        .map(|_| ())
        .unwrap_err()
        .to_string();
        assert!(e.contains("exact.beta"), "{e}");
    }
}
