//! Kind `rod_extremes`: data at the edges. Each run gives correct numbers (checked against the
//! constant-data exact solution, a one-step closed form, Newton iteration counts) or stops with a
//! clear error.

use serde::Deserialize;

use contactlab::error::Error as LabError;
use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::{at_least, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::overrides;
use crate::core::report::case_report::{CaseReport, ExtremeReport};
use crate::exact::rod_constant_data::{ConstantLaw, RodConstantData};
use crate::exact::RodExactSolution;
use crate::rod::errors::RodErrorObserver;
use crate::rod::reference::{max_difference, reference_run, round_off_bound, RodData};
use crate::rod::study::{Discretization, RodStudy};

use super::extreme_checks::{
    error_checks, overflow_checks, ErrorExpectation, FastPath, FiniteWatch,
};

/// The case body of `rod_extremes`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtremesCase {
    /// The rod every run starts from.
    pub scene: toml::Table,
    pub extreme: Vec<ExtremeSpec>,
    /// The work every completed run must report (the fast path the scene's data allow).
    pub fast_path: Option<FastPath>,
}

impl ExtremesCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: Self = case.body()?;
        at_least(case.path(), "extreme", &c.extreme, 1)?;
        Ok(c)
    }
}

/// `[[extreme]]`: one run at the edge of the admissible data.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtremeSpec {
    pub name: String,
    /// Dotted scene keys and values overriding the case's scene (`"foundation.p0" = 5.000000001`).
    #[serde(default)]
    pub set: toml::Table,
    pub elements: usize,
    pub steps: usize,
    #[serde(default)]
    pub scheme: TimeScheme,
    /// `solution` (must run and meet the checks below), `non_finite_error` (must stop with
    /// `SolveError::NonFinite`) or `not_converged` (must stop with
    /// `SolveError::NewtonNotConverged`), naming the step, time and what failed.
    pub expect: String,
    /// Compare every nodal value of every step with the second implementation of the scheme
    /// ([`crate::rod::reference`]) within its round-off bound: the numbers at the extreme are the
    /// scheme's, not an overflow or a lost branch.
    #[serde(default)]
    pub discrete_reference: bool,
    /// Largest Newton iteration count allowed in one step.
    pub max_newton_iterations: Option<usize>,
    /// Compare a single step with its independent closed form, within the round-off bound of one
    /// solve ([`crate::rod::reference::round_off_bound`] with N = 1).
    #[serde(default)]
    pub one_step: bool,
    /// Also run (2M, 2N) and (4M, 4N): the pairwise rates of the paper error E must lie within
    /// `refinement_tolerance` of this rate (the data still converge at the theory's order).
    pub refinement_rate: Option<f64>,
    pub refinement_tolerance: Option<f64>,
    /// For an error: the step it must name (any step > 0 when absent).
    pub error_step: Option<usize>,
    /// For an error: the quantity it must name (`SolveError::NonFinite`'s `quantity`).
    pub error_quantity: Option<String>,
    /// For an error: texts its message must contain (a hint, a bound).
    #[serde(default)]
    pub message_contains: Vec<String>,
    /// For an explicit step above its bound: the run must stop at the first step whose velocity
    /// overflows (see [`super::extreme_checks::overflow_checks`]).
    #[serde(default)]
    pub first_overflow: bool,
    #[serde(default)]
    pub note: String,
}

/// The first step from u0 = 0 in closed form. With α = a + θ b k the step solves
/// α (−w'') = f0, w(0) = 0, α w'(L) = −p_ν(w(L)), whose solution
/// w(x) = (f0 (L x − x²/2) − p x)/α is reproduced exactly at the nodes by P1 (1D nodal
/// exactness), with w(L) = c/(α + L β_act), c = f0 L²/2 − L p0, β_act = β if c > 0 (law (2.8)).
pub fn one_step_displacement(
    exact: &RodConstantData,
    alpha: f64,
    beta: f64,
    p0: f64,
    k: f64,
    x: f64,
) -> f64 {
    let (l, f0) = (exact.length, exact.load);
    let c = f0 * l * l / 2.0 - l * p0;
    let w_l = if c > 0.0 {
        c / (alpha + l * beta)
    } else {
        c / alpha
    };
    let p = beta * w_l.max(0.0) + p0;
    k * (f0 * (l * x - 0.5 * x * x) - p * x) / alpha
}

/// The run's nodal states against the second implementation of the scheme, for constant data
/// (laws (2.7) and (2.8)), within the round-off bound of N solves.
fn discrete_reference_check(
    study: &RodStudy,
    family: Option<&RodConstantData>,
    spec: &ExtremeSpec,
    states: &[Vec<f64>],
) -> Result<Check, String> {
    let fam = family.ok_or("discrete_reference needs constant data")?;
    let (beta, p0) = match fam.law {
        ConstantLaw::Lubricated { beta, p0 } => (beta, p0),
        ConstantLaw::Linear { beta } => (beta, 0.0),
        ConstantLaw::Prescribed { .. } => {
            return Err("discrete_reference needs the law (2.7) or (2.8)".into())
        }
    };
    if matches!(fam.law, ConstantLaw::Linear { .. }) {
        // (2.7) is β r without the positive part: not the reference's (2.8)
        return Err("discrete_reference covers the law (2.8) (β r_+ + p0)".into());
    }
    let p = &study.problem;
    let data = RodData::constant(
        &spec.name,
        (p.length, p.final_time),
        (p.viscosity, p.elasticity, beta),
        fam.load,
        p0,
    );
    let reference = reference_run(&data, spec.elements, spec.steps, spec.scheme);
    let (diff, scale) = max_difference(states, &reference.u)
        .ok_or("the solver and the reference differ in shape")?;
    Ok(Check::at_most(
        "max_n ‖u_n − u_n^ref‖_∞ against the second implementation (bound: round-off of N solves)",
        diff,
        round_off_bound(spec.elements, spec.steps, scale),
    ))
}

fn run_one(case: &ExtremesCase, spec: &ExtremeSpec) -> ExtremeReport {
    let mut checks = Vec::new();
    let outcome = (|| -> Result<String, String> {
        let scene = overrides::applied(&case.scene, &spec.set).map_err(|e| e.to_string())?;
        let study = RodStudy::new(Some(&scene), None, &Discretization::default())
            .map_err(|e| e.to_string())?;
        let solver = study
            .solver(spec.elements, spec.steps, spec.scheme)
            .map_err(|e| e.to_string())?;
        let family = RodConstantData::for_problem(&study.problem).ok();
        let exact: Option<&dyn RodExactSolution> =
            family.as_ref().map(|f| f as &dyn RodExactSolution);
        let (a, b) = (study.problem.viscosity, study.problem.elasticity);
        let mut u_final = Vec::new();
        let mut states: Vec<Vec<f64>> = Vec::new();
        let mut errors = None;
        let mut watch = FiniteWatch::default();
        let result = match exact {
            Some(ex) => {
                let mut obs = RodErrorObserver::new(ex, a, b, spec.steps);
                let steps = spec.steps;
                let r = solver.run(
                    &mut |s: &contactlab::model::quasistatic::rod_solver::RodStep<'_>| {
                        contactlab::model::quasistatic::rod_solver::RodObserver::observe(
                            &mut obs, s,
                        );
                        watch.observe(s);
                        if s.n == steps {
                            u_final = s.u.to_vec();
                        }
                        states.push(s.u.to_vec());
                    },
                );
                errors = Some(obs.errors());
                r
            }
            None => solver.run(
                &mut |s: &contactlab::model::quasistatic::rod_solver::RodStep<'_>| watch.observe(s),
            ),
        };
        match (spec.expect.as_str(), result) {
            ("solution", Ok(stats)) => {
                checks.push(Check::holds("run completes", true, "a solution"));
                if let Some(fp) = &case.fast_path {
                    checks.extend(fp.checks(&stats, spec.scheme, a, b));
                }
                if spec.discrete_reference {
                    checks.push(discrete_reference_check(
                        &study,
                        family.as_ref(),
                        spec,
                        &states,
                    )?);
                }
                if let (Some(rate), Some(ex)) = (spec.refinement_rate, exact) {
                    let tol = spec.refinement_tolerance.unwrap_or(0.1);
                    let mut e = vec![errors
                        .as_ref()
                        .and_then(|m| m.get("paper_E").copied())
                        .unwrap_or(f64::NAN)];
                    for factor in [2, 4] {
                        let (m, n) = (spec.elements * factor, spec.steps * factor);
                        let solver = study.solver(m, n, spec.scheme).map_err(|e| e.to_string())?;
                        let mut obs = RodErrorObserver::new(ex, a, b, n);
                        solver.run(&mut obs).map_err(|e| e.to_string())?;
                        e.push(obs.errors().get("paper_E").copied().unwrap_or(f64::NAN));
                    }
                    for i in 0..2 {
                        let observed = (e[i] / e[i + 1]).log2();
                        let mut c = Check::within(
                            &format!("pairwise rate of E, (M, N) × {} → × {}", 1 << i, 2 << i),
                            observed,
                            rate,
                            tol,
                        );
                        c.passed &= observed.is_finite();
                        checks.push(c);
                    }
                }
                if let Some(max_it) = spec.max_newton_iterations {
                    checks.push(Check::at_most(
                        "most Newton iterations in one step",
                        stats.max_newton_iterations as f64,
                        max_it as f64,
                    ));
                }
                if let (true, Some(fam)) = (spec.one_step, &family) {
                    let k = study.problem.final_time / spec.steps as f64;
                    let alpha = a + spec.scheme.theta() * b * k;
                    let (beta, p0) = match fam.law {
                        ConstantLaw::Lubricated { beta, p0 } => (beta, p0),
                        ConstantLaw::Linear { beta } => (beta, 0.0),
                        ConstantLaw::Prescribed { stress } => (0.0, stress),
                    };
                    let mesh = study.mesh(spec.elements).map_err(|e| e.to_string())?;
                    let scale = u_final
                        .iter()
                        .fold(0.0f64, |m, v| m.max(v.abs()))
                        .max(1e-300);
                    let dev = mesh
                        .nodes()
                        .iter()
                        .zip(&u_final)
                        .map(|(&x, &u)| {
                            (u - one_step_displacement(fam, alpha, beta, p0, k, x)).abs()
                        })
                        .fold(0.0f64, f64::max)
                        / scale;
                    checks.push(Check::at_most(
                        "single step against its closed form (max nodal relative deviation; \
                         bound: the round-off of one solve)",
                        dev,
                        round_off_bound(spec.elements, 1, 1.0),
                    ));
                }
                Ok("solution".into())
            }
            ("solution", Err(e)) => {
                checks.push(Check::holds(
                    &format!("run completes ({e})"),
                    false,
                    "a solution",
                ));
                Ok(format!("error: {e}"))
            }
            ("non_finite_error" | "not_converged", Ok(_)) => {
                checks.push(Check::holds(
                    &format!("stops with an error ({})", spec.expect),
                    false,
                    "an error",
                ));
                Ok("solution (unexpected)".into())
            }
            ("non_finite_error" | "not_converged", Err(e)) => {
                let message = LabError::from(e.clone()).to_string();
                let expectation = ErrorExpectation {
                    expect: &spec.expect,
                    error_step: spec.error_step,
                    error_quantity: spec.error_quantity.as_deref(),
                    message_contains: &spec.message_contains,
                };
                checks.extend(error_checks(&expectation, &e, &message));
                if spec.first_overflow {
                    let k = study.problem.final_time / spec.steps as f64;
                    // u_n = (1 − kb/(a + θkb)) u_{n−1} + (terms bounded by the data)
                    let amplification = (1.0 - k * b / (a + spec.scheme.theta() * k * b)).abs();
                    checks.extend(overflow_checks(&watch, &e, amplification));
                }
                Ok(format!("error: {message}"))
            }
            (other, _) => Err(format!("unknown expect = \"{other}\"")),
        }
    })();
    let outcome = match outcome {
        Ok(o) => o,
        Err(e) => {
            checks.push(Check::holds(&format!("setup ({e})"), false, "a valid run"));
            format!("setup error: {e}")
        }
    };
    ExtremeReport {
        name: spec.name.clone(),
        expect: spec.expect.clone(),
        outcome,
        checks,
        note: spec.note.clone(),
    }
}

/// Runs every `[[extreme]]` of the case.
pub fn run(case: &Case, _ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = ExtremesCase::parse(case).map_err(|e| e.to_string())?;
    for spec in &c.extreme {
        let r = run_one(&c, spec);
        report.gates.push(GateVerdict::from_checks(
            format!("extreme: {}", r.name),
            "extreme",
            r.checks.clone(),
            &r.note,
        ));
        report.extremes.push(r);
    }
    Ok(())
}
