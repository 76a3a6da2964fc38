//! Kind `rod_discrete_reference`: the solver's three schemes against a second implementation of
//! the same fully discrete equations ([`crate::rod::reference`]), at round-off.
//!
//! A convergence rate cannot see a scheme that is consistent but not the one documented — data
//! taken at t_{n−1} instead of t_n, the elastic term at the wrong θ, the oil pressure at the wrong
//! time — because such a scheme converges at the same order. Comparing every nodal value of every
//! step with an independent implementation does: the two agree to round-off or the solver does
//! not compute the scheme it claims.
//!
//! The tolerance is a bound from the theory of round-off, not a pin: each step solves a system of
//! condition κ(S) ≤ κ(K) ≈ 4M²/π² + 1 and the errors of N steps add at most linearly, so
//! max_n ‖u_n − u_n^ref‖_∞ ≤ C ε κ N max_n ‖u_n‖_∞ with ε the machine epsilon and C = 16 (a few
//! operations per entry of a tridiagonal solve).

use serde::Deserialize;

use std::sync::Arc;

use contactlab::contact::normal_law::FoundationLaw;
use contactlab::field::{Dependence, Field};
use contactlab::mesh::interval::IntervalMesh;
use contactlab::model::quasistatic::rod::RodProblem;
use contactlab::model::quasistatic::rod_solver::{RodParams, RodSolver, RodStep};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::time::grid::TimeGrid;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::{invalid, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::rod::reference::{max_difference, reference_run, round_off_bound, RodData};

/// The case body of `rod_discrete_reference`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscreteReferenceCase {
    pub data_set: Vec<DataSetSpec>,
}

/// `[[data_set]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DataSetSpec {
    /// A data set of `verification/src/rod/reference.rs` (`switching_oil_pressure`,
    /// `paper_p0_6`, `paper_p0_2`).
    pub data: String,
    /// (M, N) of each run.
    pub runs: Vec<[usize; 2]>,
    pub schemes: Vec<TimeScheme>,
    /// Require every run to exercise both branches of r_+ (the damper acts in some steps and
    /// rests in others).
    #[serde(default)]
    pub both_branches: bool,
}

impl DiscreteReferenceCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: Self = case.body()?;
        let p = &case.path;
        if c.data_set.is_empty() {
            return Err(invalid(p, "data_set", "[]", "at least one [[data_set]]"));
        }
        for (j, s) in c.data_set.iter().enumerate() {
            Self::check_set(p, j, s)?;
        }
        Ok(c)
    }

    fn check_set(p: &std::path::Path, j: usize, s: &DataSetSpec) -> Result<(), CaseError> {
        let field = |k: &str| format!("data_set[{j}].{k}");
        match RodData::named(&s.data) {
            None => {
                return Err(invalid(
                    p,
                    &field("data"),
                    &s.data,
                    &format!("one of {}", RodData::names().join(", ")),
                ))
            }
            Some(d) if !d.check_affine() => {
                return Err(invalid(
                    p,
                    &field("data"),
                    &s.data,
                    "a load affine in x (integrated exactly by both implementations)",
                ))
            }
            Some(_) => {}
        }
        if s.runs.is_empty() {
            return Err(invalid(p, &field("runs"), "[]", "at least one [M, N]"));
        }
        for (i, [m, n]) in s.runs.iter().enumerate() {
            if !(1..=2000).contains(m) || !(1..=20000).contains(n) {
                return Err(invalid(
                    p,
                    &field(&format!("runs[{i}]")),
                    format!("[{m}, {n}]"),
                    "1 ≤ M ≤ 2000 and 1 ≤ N ≤ 20000 (dense reference)",
                ));
            }
        }
        if s.schemes.is_empty() {
            return Err(invalid(p, &field("schemes"), "[]", "at least one scheme"));
        }
        Ok(())
    }
}

/// The solver's problem for the data set (the same functions, as fields).
pub fn problem(d: &RodData) -> RodProblem {
    let (load, oil, init) = (d.load.clone(), d.oil_pressure.clone(), d.initial.clone());
    let dep = |x, t| Dependence { x, y: false, t };
    RodProblem {
        length: d.length,
        final_time: d.final_time,
        viscosity: d.viscosity,
        elasticity: d.elasticity,
        load: Field::function(dep(true, true), move |x, _, t| load(x, t)),
        initial_displacement: Field::function(dep(true, false), move |x, _, _| init(x)),
        foundation: Arc::new(FoundationLaw::Lubricated {
            beta: d.beta,
            p0: Field::function(dep(false, true), move |_, _, t| oil(t)),
        }),
    }
}

/// The solver's u_n at the nodes, n = 0..N.
pub fn solver_run(
    d: &RodData,
    m: usize,
    n: usize,
    scheme: TimeScheme,
) -> Result<Vec<Vec<f64>>, String> {
    let solver = RodSolver::new(
        &problem(d),
        IntervalMesh::uniform(d.length, m).map_err(|e| e.to_string())?,
        TimeGrid::uniform(d.final_time, n).map_err(|e| e.to_string())?,
        scheme,
        RodParams::default(),
    )
    .map_err(|e| e.to_string())?;
    let mut u = Vec::with_capacity(n + 1);
    solver
        .run(&mut |s: &RodStep<'_>| u.push(s.u.to_vec()))
        .map_err(|e| e.to_string())?;
    Ok(u)
}

/// Runs the case.
pub fn run(case: &Case, _ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = DiscreteReferenceCase::parse(case).map_err(|e| e.to_string())?;
    for s in &c.data_set {
        run_set(s, report)?;
    }
    Ok(())
}

fn run_set(s: &DataSetSpec, report: &mut CaseReport) -> Result<(), String> {
    let d = RodData::named(&s.data).ok_or("unknown data set")?;
    let mut rows = Vec::new();
    for &scheme in &s.schemes {
        let mut checks = Vec::new();
        for &[m, n] in &s.runs {
            let ours = solver_run(&d, m, n, scheme)?;
            let reference = reference_run(&d, m, n, scheme);
            let (diff, scale) = max_difference(&ours, &reference.u).ok_or_else(|| {
                format!("{scheme} M = {m}, N = {n}: the solver and the reference differ in shape")
            })?;
            let bound = round_off_bound(m, n, scale);
            let pressing = reference.end_velocity.iter().filter(|w| **w > 0.0).count();
            rows.push(vec![
                scheme.to_string(),
                m.to_string(),
                n.to_string(),
                pressing.to_string(),
                format!("{diff:.3e}"),
                format!("{bound:.3e}"),
            ]);
            checks.push(Check::at_most(
                &format!(
                    "M = {m}, N = {n}: max_n ‖u_n − u_n^ref‖_∞ ({pressing} of {n} steps with the damper acting)"
                ),
                diff,
                bound,
            ));
            if s.both_branches {
                checks.push(Check::holds(
                    &format!("M = {m}, N = {n}: the damper both acts and rests"),
                    pressing > 0 && pressing < n,
                    "the run exercises both branches of r_+",
                ));
            }
        }
        report.gates.push(GateVerdict::from_checks(
            format!(
                "{} / {scheme}: the solver computes the documented scheme",
                d.name
            ),
            "reference",
            checks,
            "bound C ε κ(K) N max‖u‖ (C = 16, κ(K) ≈ 4M²/π² + 1): round-off of N solves",
        ));
    }
    report.tables.push(Table {
        title: format!("the solver against the second implementation ({})", d.name),
        header: [
            "scheme",
            "M",
            "N",
            "steps with the damper acting",
            "max |u − u_ref|",
            "round-off bound",
        ]
        .iter()
        .map(|h| h.to_string())
        .collect(),
        rows,
    });
    Ok(())
}

#[cfg(test)]
mod tests {
    //! The format: an unknown data set and an empty run list are typed errors naming the field;
    //! a small run of each scheme agrees with the reference to round-off.
    use super::*;
    use std::path::Path;

    const CASE: &str = r#"
id = "t"
title = "t"
kind = "rod_discrete_reference"
explanation = "e"
[[data_set]]
data = "switching_oil_pressure"
runs = [[6, 12]]
schemes = ["explicit", "implicit", "midpoint"]
both_branches = true
"#;

    fn parse(text: &str) -> Result<DiscreteReferenceCase, CaseError> {
        DiscreteReferenceCase::parse(&Case::from_text(Path::new("t.toml"), text)?)
    }

    #[test]
    fn bad_data_and_empty_runs_are_typed_errors() {
        assert!(parse(CASE).is_ok());
        let e = parse(&CASE.replace("switching_oil_pressure", "nope")).unwrap_err();
        assert!(e.to_string().contains("data_set[0].data"), "{e}");
        let e = parse(&CASE.replace("[[6, 12]]", "[]")).unwrap_err();
        assert!(e.to_string().contains("data_set[0].runs"), "{e}");
    }

    #[test]
    fn the_solver_agrees_with_the_second_implementation() {
        let d = RodData::switching_oil_pressure();
        for scheme in TimeScheme::ALL {
            let ours = solver_run(&d, 6, 12, scheme).unwrap();
            let r = reference_run(&d, 6, 12, scheme);
            for (a, b) in ours.iter().zip(&r.u) {
                for (x, y) in a.iter().zip(b) {
                    assert!((x - y).abs() < 1e-13, "{scheme}: {x} vs {y}");
                }
            }
        }
    }
}
