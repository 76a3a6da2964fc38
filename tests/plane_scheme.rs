//! The plane Kelvin–Voigt scheme (Fernández & Sofonea 2004, problem P in 2D): every step solves its
//! discrete equations to round-off on both solver paths, the two paths agree, the paper's Test 2D
//! behaves as each reading of Γ1 demands, and failures are typed errors with their data.

use std::sync::Arc;

use contactlab::contact::normal_law::{FoundationLaw, SpaceTime};
use contactlab::error::{Error, SolveError};
use contactlab::field::Field;
use contactlab::material::nonlinear::{SaturatingViscosity, SofteningElasticity};
use contactlab::mesh::triangle::RectangleSide;
use contactlab::model::quasistatic::plane::Test2dParams;
use contactlab::model::quasistatic::plane::{
    BoundarySelector, ContactIntegration, ContactPart, PlaneProblem, Support,
};
use contactlab::model::quasistatic::plane_dofs::PlaneDofs;
use contactlab::model::quasistatic::plane_solver::{
    PlaneParams, PlaneSolver, PlaneStep, SolverPath,
};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::time::grid::TimeGrid;

fn test_2d(n: usize, beta: f64, support: Support, integration: ContactIntegration) -> PlaneProblem {
    PlaneProblem::fernandez_sofonea_test_2d(Test2dParams {
        divisions: n,
        beta,
        support,
        integration,
    })
    .unwrap()
}

fn final_u(
    p: &PlaneProblem,
    steps: usize,
    scheme: TimeScheme,
    params: PlaneParams,
) -> Result<Vec<f64>, Error> {
    let mut s = PlaneSolver::new(p, TimeGrid::uniform(p.final_time, steps)?, scheme, params)?;
    let mut u = Vec::new();
    s.run(&mut |st: &PlaneStep<'_>| u = st.u.to_vec())?;
    Ok(u)
}

/// ‖R‖∞ / scale of the step equation
/// Σ_e [A ε(w) + B ε(u_prev + θ k w)] : ε(φ) + Σ_g W_g p_ν((Cw)_g) C_g − F(τ) on the solved dofs.
fn step_residual(
    p: &PlaneProblem,
    dofs: &PlaneDofs,
    u_prev: &[f64],
    w: &[f64],
    theta_k: f64,
    tau: f64,
) -> f64 {
    let mut r = vec![0.0; w.len()];
    let mut scale = vec![0.0f64; w.len()];
    for (t, el) in p.mesh.triangles().iter().zip(&dofs.elements) {
        let wl: [f64; 6] = std::array::from_fn(|q| w[2 * t[q / 2] + q % 2]);
        let ul: [f64; 6] = std::array::from_fn(|q| u_prev[2 * t[q / 2] + q % 2] + theta_k * wl[q]);
        let sa = p.viscosity.stress(&el.strain(&wl));
        let sb = p.elasticity.stress(&el.strain(&ul));
        let fa = el.internal_forces(&sa);
        let fb = el.internal_forces(&sb);
        for q in 0..6 {
            let d = 2 * t[q / 2] + q % 2;
            r[d] += fa[q] + fb[q];
            scale[d] = scale[d].max(fa[q].abs()).max(fb[q].abs());
        }
    }
    let law = p.contact.as_ref().unwrap().law.clone();
    for pt in &dofs.contact_points {
        let rn: f64 = pt.entries.iter().map(|&(d, c)| c * w[d]).sum();
        let pn = law.value(
            rn,
            SpaceTime {
                x: pt.position[0],
                y: pt.position[1],
                t: tau,
            },
        );
        for &(d, c) in &pt.entries {
            r[d] += pt.weight * pn * c;
            scale[d] = scale[d].max((pt.weight * pn * c).abs());
        }
    }
    let mut load = vec![0.0; w.len()];
    dofs.load_into(p, tau, &|_| true, &mut load);
    let mut worst = 0.0f64;
    let mut big = 0.0f64;
    for d in 0..w.len() {
        if dofs.solved[d].is_none() {
            continue;
        }
        worst = worst.max((r[d] - load[d]).abs());
        big = big.max(scale[d]).max(load[d].abs());
    }
    worst / big
}

#[test]
fn every_step_solves_its_discrete_equations_to_round_off_on_both_paths() {
    for (path, integration) in [
        (SolverPath::Condensed, ContactIntegration::Gauss2),
        (SolverPath::Newton, ContactIntegration::Gauss2),
        (SolverPath::Condensed, ContactIntegration::Nodal),
    ] {
        for scheme in TimeScheme::ALL {
            let p = test_2d(6, 100.0, Support::Clamped, integration);
            let mut s = PlaneSolver::new(
                &p,
                TimeGrid::uniform(1.0, 12).unwrap(),
                scheme,
                PlaneParams {
                    path,
                    ..Default::default()
                },
            )
            .unwrap();
            let dofs = s.dofs().clone();
            let mut prev = vec![0.0; 2 * dofs.n_nodes];
            let mut worst = 0.0f64;
            let pc = p.clone();
            s.run(&mut |st: &PlaneStep<'_>| {
                if let Some(w) = st.w {
                    worst = worst.max(step_residual(
                        &pc,
                        &dofs,
                        &prev,
                        w,
                        scheme.theta() * st.k,
                        st.data_time,
                    ));
                }
                prev.copy_from_slice(st.u);
            })
            .unwrap();
            let tol = if path == SolverPath::Newton {
                1e-10
            } else {
                1e-12
            };
            assert!(
                worst < tol,
                "{path:?} {scheme} {integration:?}: relative residual {worst:e}"
            );
        }
    }
}

#[test]
fn condensed_and_newton_paths_agree_on_a_linear_problem() {
    let p = test_2d(8, 1000.0, Support::Clamped, ContactIntegration::Gauss2);
    for scheme in TimeScheme::ALL {
        let a = final_u(
            &p,
            20,
            scheme,
            PlaneParams {
                path: SolverPath::Condensed,
                ..Default::default()
            },
        )
        .unwrap();
        let b = final_u(
            &p,
            20,
            scheme,
            PlaneParams {
                path: SolverPath::Newton,
                ..Default::default()
            },
        )
        .unwrap();
        let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(diff < 1e-9 * scale, "{scheme}: {diff:e} vs {scale}");
    }
}

#[test]
fn model_picks_the_condensed_path_for_linear_and_newton_for_nonlinear_laws() {
    let p = test_2d(4, 100.0, Support::Clamped, ContactIntegration::Gauss2);
    let s = PlaneSolver::new(
        &p,
        TimeGrid::uniform(1.0, 4).unwrap(),
        TimeScheme::Explicit,
        PlaneParams::default(),
    )
    .unwrap();
    assert_eq!(s.path(), SolverPath::Condensed);
    let mut q = p.clone();
    q.viscosity = Arc::new(SaturatingViscosity {
        mu: 30.0,
        eta: 20.0,
        gamma: 5.0,
        tau_c: 0.1,
    });
    q.elasticity = Arc::new(SofteningElasticity {
        lambda: 30.0,
        shear: 38.0,
        delta: 0.3,
        eps_c: 0.05,
    });
    let s = PlaneSolver::new(
        &q,
        TimeGrid::uniform(1.0, 4).unwrap(),
        TimeScheme::Explicit,
        PlaneParams::default(),
    )
    .unwrap();
    assert_eq!(s.path(), SolverPath::Newton);
    let e = PlaneSolver::new(
        &q,
        TimeGrid::uniform(1.0, 4).unwrap(),
        TimeScheme::Explicit,
        PlaneParams {
            path: SolverPath::Condensed,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("solver.path"), "{e}");
}

#[test]
fn rollers_stop_at_step_one_with_the_missing_equilibrium_named() {
    let p = test_2d(6, 1000.0, Support::FixX, ContactIntegration::Gauss2);
    match final_u(&p, 100, TimeScheme::Explicit, PlaneParams::default()).unwrap_err() {
        Error::Solve(SolveError::NoEquilibrium { step, time, reason }) => {
            assert_eq!(step, 1);
            assert!((time - 0.01).abs() < 1e-12);
            assert!(
                reason.contains("-1.8") && reason.contains("12.0"),
                "{reason}"
            );
        }
        other => panic!("{other}"),
    }
}

#[test]
fn rollers_variant_skips_exactly_the_steps_below_twelve_newtons_and_never_prints_nan() {
    let p = test_2d(6, 1000.0, Support::FixX, ContactIntegration::Gauss2);
    let mut s = PlaneSolver::new(
        &p,
        TimeGrid::uniform(1.0, 100).unwrap(),
        TimeScheme::Explicit,
        PlaneParams {
            start_at_first_equilibrium: true,
            ..Default::default()
        },
    )
    .unwrap();
    let mut all_finite = true;
    let stats = s
        .run(&mut |st: &PlaneStep<'_>| {
            all_finite &= st.u.iter().all(|v| v.is_finite());
        })
        .unwrap();
    assert_eq!(stats.skipped_steps, vec![1, 2, 3, 4, 5, 6]);
    assert_eq!(stats.free_rigid_motions, 1);
    assert!(all_finite);
}

#[test]
fn explicit_step_above_the_bound_overflows_into_a_clear_error() {
    let p = test_2d(4, 1000.0, Support::Clamped, ContactIntegration::Gauss2);
    let mut q = p.clone();
    q.final_time = 2000.0 * 1.5 * 0.52;
    q.contact = Some(ContactPart {
        boundary: BoundarySelector::side(RectangleSide::Bottom),
        law: Arc::new(FoundationLaw::Prescribed {
            stress: Field::Constant(2.0),
        }),
        integration: ContactIntegration::Gauss2,
        source: None,
    });
    match final_u(&q, 2000, TimeScheme::Explicit, PlaneParams::default()).unwrap_err() {
        Error::Solve(SolveError::NonFinite { hint, step, .. }) => {
            assert!(step > 100);
            assert!(hint.contains("λ_max"), "{hint}");
        }
        other => panic!("{other}"),
    }
}

#[test]
fn a_newton_iteration_cap_is_a_typed_error_with_step_time_and_residual() {
    let mut p = test_2d(4, 100.0, Support::Clamped, ContactIntegration::Gauss2);
    p.viscosity = Arc::new(SaturatingViscosity {
        mu: 30.0,
        eta: 20.0,
        gamma: 50.0,
        tau_c: 0.01,
    });
    let mut params = PlaneParams::default();
    params.newton.max_iterations = 1;
    match final_u(&p, 10, TimeScheme::Implicit, params).unwrap_err() {
        Error::Solve(SolveError::NewtonNotConverged {
            step,
            time,
            iterations,
            residual,
            ..
        }) => {
            assert_eq!(step, 1);
            assert!((time - 0.1).abs() < 1e-12);
            assert_eq!(iterations, 1);
            assert!(residual.is_finite() && residual > 0.0);
        }
        other => panic!("{other}"),
    }
}

#[test]
fn overlapping_boundary_parts_and_an_unsupported_body_are_input_errors() {
    let mut p = test_2d(4, 100.0, Support::Clamped, ContactIntegration::Gauss2);
    p.dirichlet[0].boundary =
        BoundarySelector::Sides(vec![RectangleSide::Left, RectangleSide::Bottom]);
    let e = PlaneSolver::new(
        &p,
        TimeGrid::uniform(1.0, 4).unwrap(),
        TimeScheme::Explicit,
        PlaneParams::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("contact"), "{e}");
    let mut q = test_2d(4, 100.0, Support::Clamped, ContactIntegration::Gauss2);
    q.dirichlet.clear();
    q.contact = None;
    let e = PlaneSolver::new(
        &q,
        TimeGrid::uniform(1.0, 4).unwrap(),
        TimeScheme::Explicit,
        PlaneParams::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("dirichlet"), "{e}");
}

#[test]
fn runs_are_bit_for_bit_deterministic() {
    let p = test_2d(8, 1000.0, Support::FixX, ContactIntegration::Gauss2);
    let params = PlaneParams {
        start_at_first_equilibrium: true,
        ..Default::default()
    };
    let a = final_u(&p, 50, TimeScheme::Midpoint, params).unwrap();
    let b = final_u(&p, 50, TimeScheme::Midpoint, params).unwrap();
    assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
}
