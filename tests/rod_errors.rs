//! Error paths of the rod solver: bad data give typed input errors naming the field and the value;
//! failures during a run give solve errors carrying the step, the time and, for Newton, the
//! iteration count and the residual. Never a panic, never a NaN result.

use std::sync::Arc;

use contactlab::contact::normal_law::{NormalLaw, SpaceTime};
use contactlab::error::{Error, InputError, SolveError};
use contactlab::field::{Expression, Field};
use contactlab::mesh::interval::IntervalMesh;
use contactlab::model::quasistatic::rod::RodProblem;
use contactlab::model::quasistatic::rod_output::RodOutputRequest;
use contactlab::model::quasistatic::rod_solver::{RodParams, RodSolver};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::time::grid::TimeGrid;

fn build(problem: &RodProblem, m: usize, n: usize, scheme: TimeScheme) -> Result<RodSolver, Error> {
    RodSolver::new(
        problem,
        IntervalMesh::uniform(problem.length, m)?,
        TimeGrid::uniform(problem.final_time, n)?,
        scheme,
        RodParams::default(),
    )
}

fn input_field(e: Error) -> InputError {
    match e {
        Error::Input(i) => i,
        other => panic!("expected an input error, got {other}"),
    }
}

#[test]
fn negative_viscosity_names_field_and_value() {
    let mut p = RodProblem::fernandez_sofonea(6.0);
    p.viscosity = -1.0;
    let e = input_field(build(&p, 10, 10, TimeScheme::Explicit).unwrap_err());
    assert_eq!(e.field, "rod.viscosity");
    assert_eq!(e.value, "-1");
    assert!(e.to_string().contains("expected"));
}

#[test]
fn zero_elements_and_zero_steps_are_input_errors() {
    let p = RodProblem::fernandez_sofonea(6.0);
    assert_eq!(
        input_field(build(&p, 0, 10, TimeScheme::Explicit).unwrap_err()).field,
        "mesh.elements"
    );
    assert_eq!(
        input_field(build(&p, 10, 0, TimeScheme::Explicit).unwrap_err()).field,
        "time.steps"
    );
}

#[test]
fn non_positive_final_time_is_an_input_error() {
    let mut p = RodProblem::fernandez_sofonea(6.0);
    p.final_time = 0.0;
    assert_eq!(p.validate().unwrap_err().field, "rod.final_time");
    assert_eq!(
        input_field(build(&p, 10, 10, TimeScheme::Explicit).unwrap_err()).field,
        "time.final_time"
    );
}

#[test]
fn mesh_of_another_length_is_rejected() {
    let p = RodProblem::fernandez_sofonea(6.0);
    let e = RodSolver::new(
        &p,
        IntervalMesh::uniform(2.0, 10).unwrap(),
        TimeGrid::uniform(0.5, 10).unwrap(),
        TimeScheme::Explicit,
        RodParams::default(),
    )
    .unwrap_err();
    assert_eq!(input_field(e).field, "mesh.length");
}

#[test]
fn load_that_is_nan_on_the_rod_is_an_input_error() {
    let mut p = RodProblem::fernandez_sofonea(6.0);
    p.load = Field::Expression(Expression::parse("rod.load", "sqrt(x - 2)").unwrap());
    assert_eq!(
        input_field(build(&p, 10, 10, TimeScheme::Explicit).unwrap_err()).field,
        "rod.load"
    );
}

#[test]
fn space_time_load_that_turns_nan_is_a_solve_error_with_step_and_time() {
    let mut p = RodProblem::fernandez_sofonea(6.0);
    p.load = Field::Expression(Expression::parse("rod.load", "x*sqrt(0.25 - t)").unwrap());
    let s = build(&p, 10, 10, TimeScheme::Explicit).unwrap();
    match s.solve(&RodOutputRequest::default()).unwrap_err() {
        Error::Solve(SolveError::NonFinite {
            step,
            time,
            quantity,
            ..
        }) => {
            assert_eq!(step, 6);
            assert!((time - 0.3).abs() < 1e-12);
            assert!(quantity.contains("load"));
        }
        other => panic!("{other}"),
    }
}

#[test]
fn explicit_step_above_the_bound_overflows_into_a_clear_error() {
    let mut p = RodProblem::fernandez_sofonea(6.0);
    p.final_time = 3.0 * 2000.0;
    let s = build(&p, 10, 2000, TimeScheme::Explicit).unwrap();
    match s.solve(&RodOutputRequest::default()).unwrap_err() {
        Error::Solve(SolveError::NonFinite { step, hint, .. }) => {
            assert!(step > 1000 && step < 1100, "step {step}");
            assert!(hint.contains("stability bound 2a/b = 2"), "{hint}");
        }
        other => panic!("{other}"),
    }
    // The implicit and midpoint variants run the same data to the end.
    for scheme in [TimeScheme::Implicit, TimeScheme::Midpoint] {
        let sol = build(&p, 10, 2000, scheme)
            .unwrap()
            .solve(&RodOutputRequest::default())
            .unwrap();
        assert!(sol.end_displacement.iter().all(|v| v.is_finite()));
    }
}

/// A monotone, Lipschitz but nonlinear law: p(r) = r + 10 tanh(5 r).
#[derive(Debug)]
struct Tanh;

impl NormalLaw for Tanh {
    fn value(&self, r: f64, _: SpaceTime) -> f64 {
        r + 10.0 * (5.0 * r).tanh()
    }
    fn derivative(&self, r: f64, _: SpaceTime) -> f64 {
        1.0 + 50.0 / (5.0 * r).cosh().powi(2)
    }
    fn lipschitz_constant(&self) -> f64 {
        51.0
    }
    fn depends_on_time(&self) -> bool {
        false
    }
    fn is_affine(&self) -> bool {
        false
    }
    fn validate(&self) -> Result<(), InputError> {
        Ok(())
    }
}

#[test]
fn user_law_converges_and_an_iteration_cap_is_reported_with_step_time_and_residual() {
    let mut p = RodProblem::fernandez_sofonea(6.0);
    p.foundation = Arc::new(Tanh);
    let sol = build(&p, 20, 10, TimeScheme::Implicit)
        .unwrap()
        .solve(&RodOutputRequest::default())
        .unwrap();
    assert!(sol.stats.max_newton_iterations >= 2);
    let mut params = RodParams::default();
    params.newton.max_iterations = 1;
    let s = RodSolver::new(
        &p,
        IntervalMesh::uniform(1.0, 20).unwrap(),
        TimeGrid::uniform(0.5, 10).unwrap(),
        TimeScheme::Implicit,
        params,
    )
    .unwrap();
    match s.solve(&RodOutputRequest::default()).unwrap_err() {
        Error::Solve(SolveError::NewtonNotConverged {
            step,
            iterations,
            residual,
            ..
        }) => {
            assert_eq!(step, 0);
            assert_eq!(iterations, 1);
            assert!(residual > 0.0 && residual.is_finite());
        }
        other => panic!("{other}"),
    }
}

#[test]
fn probe_outside_the_rod_is_an_input_error() {
    let p = RodProblem::fernandez_sofonea(6.0);
    let s = build(&p, 10, 10, TimeScheme::Explicit).unwrap();
    let e = s
        .solve(&RodOutputRequest {
            snapshot_times: vec![],
            probes: vec![1.5],
        })
        .unwrap_err();
    assert_eq!(input_field(e).field, "output.probes[0]");
}
