//! Dynamic contact (Barboteu–Danan–Sofonea, "BDS"; Hauret–Le Tallec, "HLT"): the space
//! discretization's forces against their energies, the schemes' discrete energy identities, the
//! two solver paths, the contact treatments' defining properties, and typed errors.

use std::sync::Arc;

use contactlab::contact::friction::FrictionCoefficient;
use contactlab::error::{Error, SolveError};
use contactlab::field::Field;
use contactlab::material::hyperelastic::{
    Hyperelastic2d, LinearElastic, LinearElastic1d, NeoHooke, StVenantKirchhoff1d,
};
use contactlab::mesh::generators::{annulus, disk};
use contactlab::mesh::interval::IntervalMesh;
use contactlab::model::dynamic::bar::{BarBody, BarData, BarSupports, MassMatrix};
use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::dynamic::contact_model::{BarEnd, ContactModel, NormalTreatment};
use contactlab::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::{
    DynamicParams, DynamicPath, DynamicProblem, DynamicSolution, DynamicSolver,
};
use contactlab::model::quasistatic::plane::BoundarySelector;

fn ring(law: Arc<dyn Hyperelastic2d>) -> Arc<PlaneBody> {
    Arc::new(
        PlaneBody::new(PlaneBodyData {
            mesh: annulus([0.0, 0.502], 0.3, 0.5, 2, 24).expect("mesh"),
            density: 1000.0,
            law,
            dirichlet: vec![],
            traction: vec![],
            body_force: [Field::Constant(0.0), Field::Constant(0.0)],
            mass: MassMatrix::Consistent,
            regions: Vec::new(),
        })
        .expect("body"),
    )
}

fn ball() -> Arc<PlaneBody> {
    Arc::new(
        PlaneBody::new(PlaneBodyData {
            mesh: disk([0.0, 0.501], 0.5, 5).expect("mesh"),
            density: 1000.0,
            law: Arc::new(LinearElastic::from_young_poisson(1e7, 0.3).expect("law")),
            dirichlet: vec![],
            traction: vec![],
            body_force: [Field::Constant(0.0), Field::Constant(0.0)],
            mass: MassMatrix::Consistent,
            regions: Vec::new(),
        })
        .expect("body"),
    )
}

fn uniform_velocity(body: &PlaneBody, v: [f64; 2]) -> Vec<f64> {
    let nodal: Vec<f64> = (0..body.data().mesh.nodes().len())
        .flat_map(|_| v)
        .collect();
    body.from_nodal(&nodal)
}

fn lower_half(level: f64) -> BoundarySelector {
    BoundarySelector::Predicate(Arc::new(move |x: [f64; 2]| x[1] < level))
}

fn impact(
    body: Arc<PlaneBody>,
    treatment: NormalTreatment,
    friction: Option<FrictionCoefficient>,
    scheme: DynamicScheme,
    v: [f64; 2],
    final_time: f64,
    steps: usize,
) -> DynamicProblem {
    let contact = ContactModel::plane_half_space(&body, &lower_half(0.5), 0.0, treatment, friction)
        .expect("contact");
    let n = body.dofs();
    DynamicProblem {
        initial_velocity: uniform_velocity(&body, v),
        body,
        contact: Some(contact),
        scheme,
        final_time,
        steps,
        initial_displacement: vec![0.0; n],
    }
}

fn run(problem: DynamicProblem) -> DynamicSolution {
    DynamicSolver::new(problem, DynamicParams::default())
        .expect("valid problem")
        .solve()
        .expect("run")
}

fn pseudo_random(n: usize, amplitude: f64, seed: u64) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            amplitude * (((s >> 11) as f64 / (1u64 << 53) as f64) - 0.5)
        })
        .collect()
}

#[test]
fn plane_tangent_matches_central_differences_of_internal_forces() {
    let body = ring(Arc::new(
        NeoHooke::from_young_poisson(1e6, 0.3).expect("law"),
    ));
    let n = body.dofs();
    let u = pseudo_random(n, 0.02, 7);
    let dir = pseudo_random(n, 1.0, 11);
    let mut k = vec![0.0; body.pattern().nnz()];
    body.add_tangent(&u, 1.0, &mut k);
    let mut kd = vec![0.0; n];
    body.pattern().symmetric_mul(&k, &dir, &mut kd);
    let h = 1e-6;
    let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
    let up: Vec<f64> = u.iter().zip(&dir).map(|(a, b)| a + h * b).collect();
    let um: Vec<f64> = u.iter().zip(&dir).map(|(a, b)| a - h * b).collect();
    assert!(body.internal_force(&up, &mut fp) && body.internal_force(&um, &mut fm));
    let scale = kd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for i in 0..n {
        let fd = (fp[i] - fm[i]) / (2.0 * h);
        assert!(
            (fd - kd[i]).abs() <= 1e-6 * scale,
            "dof {i}: {fd} vs {}",
            kd[i]
        );
    }
}

#[test]
fn discrete_gradient_symmetric_plus_skew_tangent_is_the_exact_derivative() {
    // J = sym + skew of ∂F^algo/∂u1 against central differences of F^algo(u0, ·): J d and Jᵀ d
    // (the symmetric part alone matches neither once the skew part is not negligible; a sign
    // error in the skew assembly swaps the two products)
    let body = ring(Arc::new(
        NeoHooke::from_young_poisson(1e6, 0.3).expect("law"),
    ));
    let n = body.dofs();
    let u0 = pseudo_random(n, 0.03, 19);
    let u1: Vec<f64> = u0
        .iter()
        .zip(pseudo_random(n, 0.05, 23))
        .map(|(a, b)| a + b)
        .collect();
    let dir = pseudo_random(n, 1.0, 29);
    let pattern = body.pattern();
    let mut sym = vec![0.0; pattern.nnz()];
    let mut skew = vec![0.0; pattern.nnz()];
    body.add_discrete_gradient_tangent(&u0, &u1, 1.0, &mut sym);
    body.add_discrete_gradient_skew(&u0, &u1, 1.0, &mut skew);
    // J d with J_ij = S_ij + W_ij (i < j), J_ji = S_ij − W_ij, from the upper triangles
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let (mut jd, mut sd) = (vec![0.0; n], vec![0.0; n]);
    for j in 0..n {
        for s in cp[j]..cp[j + 1] {
            let i = ri[s];
            jd[i] += (sym[s] + skew[s]) * dir[j];
            sd[i] += sym[s] * dir[j];
            if i != j {
                jd[j] += (sym[s] - skew[s]) * dir[i];
                sd[j] += sym[s] * dir[i];
            }
        }
    }
    let h = 1e-6;
    let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
    let up: Vec<f64> = u1.iter().zip(&dir).map(|(a, b)| a + h * b).collect();
    let um: Vec<f64> = u1.iter().zip(&dir).map(|(a, b)| a - h * b).collect();
    assert!(body.discrete_gradient_force(&u0, &up, &mut fp));
    assert!(body.discrete_gradient_force(&u0, &um, &mut fm));
    let fd: Vec<f64> = (0..n).map(|i| (fp[i] - fm[i]) / (2.0 * h)).collect();
    let scale = fd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = |a: &[f64]| {
        a.iter()
            .zip(&fd)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
            / scale
    };
    assert!(
        err(&jd) <= 1e-6,
        "exact tangent vs differences: {}",
        err(&jd)
    );
    // the skew part is not negligible at this state: the symmetric part alone misses by far more
    assert!(
        err(&sd) > 100.0 * err(&jd).max(1e-8),
        "symmetric part: {}",
        err(&sd)
    );
}

#[test]
fn internal_forces_are_the_gradient_of_the_stored_energy() {
    let body = ring(Arc::new(
        NeoHooke::from_young_poisson(1e6, 0.3).expect("law"),
    ));
    let n = body.dofs();
    let u = pseudo_random(n, 0.02, 3);
    let dir = pseudo_random(n, 1.0, 5);
    let mut f = vec![0.0; n];
    assert!(body.internal_force(&u, &mut f));
    let h = 1e-6;
    let up: Vec<f64> = u.iter().zip(&dir).map(|(a, b)| a + h * b).collect();
    let um: Vec<f64> = u.iter().zip(&dir).map(|(a, b)| a - h * b).collect();
    let fd = (body.stored_energy(&up) - body.stored_energy(&um)) / (2.0 * h);
    let exact: f64 = f.iter().zip(&dir).map(|(a, b)| a * b).sum();
    assert!(
        (fd - exact).abs() <= 1e-6 * exact.abs().max(1.0),
        "{fd} vs {exact}"
    );
}

#[test]
fn discrete_gradient_force_has_exact_discrete_work_bds_1_43() {
    let body = ring(Arc::new(
        NeoHooke::from_young_poisson(1e6, 0.3).expect("law"),
    ));
    let n = body.dofs();
    let u0 = pseudo_random(n, 0.03, 13);
    let u1: Vec<f64> = u0
        .iter()
        .zip(pseudo_random(n, 0.01, 17))
        .map(|(a, b)| a + b)
        .collect();
    let mut f = vec![0.0; n];
    assert!(body.discrete_gradient_force(&u0, &u1, &mut f));
    let work: f64 = f
        .iter()
        .zip(u1.iter().zip(&u0))
        .map(|(g, (a, b))| g * (a - b))
        .sum();
    let dw = body.stored_energy(&u1) - body.stored_energy(&u0);
    assert!(
        (work - dw).abs() <= 1e-12 * body.stored_energy(&u1),
        "{work} vs {dw}"
    );

    let bar = BarBody::new(BarData {
        mesh: IntervalMesh::uniform(1.0, 16).expect("mesh"),
        density: 1.0,
        area: 1.0,
        law: Arc::new(StVenantKirchhoff1d { young: 3.0 }),
        supports: BarSupports {
            left: true,
            right: false,
        },
        mass: MassMatrix::Consistent,
        body_force: Field::Constant(0.0),
    })
    .expect("bar");
    let m = bar.dofs();
    let (a, b) = (pseudo_random(m, 0.1, 1), pseudo_random(m, 0.1, 2));
    let mut g = vec![0.0; m];
    assert!(bar.discrete_gradient_force(&a, &b, &mut g));
    let work: f64 = g
        .iter()
        .zip(b.iter().zip(&a))
        .map(|(g, (x, y))| g * (x - y))
        .sum();
    let dw = bar.stored_energy(&b) - bar.stored_energy(&a);
    assert!((work - dw).abs() <= 1e-13 * bar.stored_energy(&b).max(1e-3));
}

#[test]
fn gonzalez_conserves_the_energy_of_a_free_neo_hookean_ring_to_round_off() {
    let body = ring(Arc::new(
        NeoHooke::from_young_poisson(1e6, 0.3).expect("law"),
    ));
    let n = body.dofs();
    // a spinning, expanding ring without contact: large rotations and strains
    let nodes = body.data().mesh.nodes().to_vec();
    let v: Vec<f64> = nodes
        .iter()
        .flat_map(|p| {
            let (x, y) = (p[0], p[1] - 0.502);
            [-30.0 * y + 10.0 * x, 30.0 * x + 10.0 * y]
        })
        .collect();
    let problem = DynamicProblem {
        body: body.clone(),
        contact: None,
        scheme: DynamicScheme::Gonzalez,
        final_time: 0.05,
        steps: 50,
        initial_displacement: vec![0.0; n],
        initial_velocity: body.from_nodal(&v),
    };
    let sol = run(problem.clone());
    let s = sol.audit.summary();
    let (e0, e1) = (
        sol.audit.records[0].energy(),
        sol.audit.records.last().expect("records").energy(),
    );
    assert!(s.max_residual_1_48 < 1e-12, "{s:?}");
    assert!((e1 - e0).abs() < 1e-11 * e0, "{e0} → {e1}");
    // the midpoint rule's energy is not conserved on the same run
    let mid = run(DynamicProblem {
        scheme: DynamicScheme::Midpoint,
        ..problem
    });
    assert!(mid.audit.summary().max_residual_1_48 > 1e-9);
}

#[test]
fn midpoint_and_gonzalez_coincide_for_a_linear_body() {
    let a = run(impact(
        ball(),
        NormalTreatment::EnergyConsistent { stiffness: 1e9 },
        None,
        DynamicScheme::Midpoint,
        [0.0, -10.0],
        0.004,
        40,
    ));
    let b = run(impact(
        ball(),
        NormalTreatment::EnergyConsistent { stiffness: 1e9 },
        None,
        DynamicScheme::Gonzalez,
        [0.0, -10.0],
        0.004,
        40,
    ));
    assert_eq!(a.final_displacement, b.final_displacement);
}

#[test]
fn condensed_and_full_paths_give_the_same_impact() {
    let problem = impact(
        ball(),
        NormalTreatment::LimitedPenetration {
            stiffness: 1e9,
            depth: 2e-4,
        },
        Some(FrictionCoefficient::Growing {
            mu0: 0.3,
            depth: 2e-4,
        }),
        DynamicScheme::Midpoint,
        [3.0, -10.0],
        0.004,
        40,
    );
    let condensed = DynamicSolver::new(problem.clone(), DynamicParams::default()).expect("ok");
    assert_eq!(condensed.path(), DynamicPath::Condensed);
    let a = condensed.solve().expect("condensed run");
    let full = DynamicSolver::new(
        problem,
        DynamicParams {
            force_full_path: true,
            ..Default::default()
        },
    )
    .expect("ok");
    assert_eq!(full.path(), DynamicPath::Full);
    let b = full.solve().expect("full run");
    let scale = a
        .final_displacement
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    for (x, y) in a.final_displacement.iter().zip(&b.final_displacement) {
        assert!((x - y).abs() <= 1e-9 * scale, "{x} vs {y}");
    }
    assert!(a.audit.records.iter().any(|r| r.stage_b), "stage (b) ran");
}

#[test]
fn energy_consistent_impact_satisfies_bds_propositions_1_1_and_1_3() {
    let sol = run(impact(
        ball(),
        NormalTreatment::EnergyConsistent { stiffness: 1e9 },
        None,
        DynamicScheme::Midpoint,
        [0.0, -10.0],
        0.01,
        100,
    ));
    let s = sol.audit.summary();
    assert!(
        s.max_residual_1_48 < 1e-12 && s.max_residual_1_49 < 1e-12,
        "{s:?}"
    );
    assert!(s.max_residual_3_7 < 1e-12, "{s:?}");
    assert!(sol.audit.records.iter().any(|r| r.contact_force > 0.0));
    // the plain penalty at t_n does not satisfy (1.49)
    let pen = run(impact(
        ball(),
        NormalTreatment::Penalty { stiffness: 1e9 },
        None,
        DynamicScheme::Midpoint,
        [0.0, -10.0],
        0.01,
        100,
    ));
    assert!(pen.audit.summary().max_residual_1_49 > 1e-8);
}

#[test]
fn limited_penetration_holds_the_depth_and_stage_b_only_dissipates() {
    let g = 2e-4;
    let sol = run(impact(
        ring(Arc::new(
            NeoHooke::from_young_poisson(1e6, 0.3).expect("law"),
        )),
        NormalTreatment::LimitedPenetration {
            stiffness: 1e9,
            depth: g,
        },
        Some(FrictionCoefficient::Decreasing { mu0: 0.3, depth: g }),
        DynamicScheme::Gonzalez,
        [4.0, -10.0],
        0.02,
        80,
    ));
    let s = sol.audit.summary();
    let max_pen = sol
        .audit
        .records
        .iter()
        .fold(f64::NEG_INFINITY, |m, r| m.max(r.max_penetration));
    assert!(max_pen <= g * (1.0 + 1e-12), "{max_pen}");
    assert!(sol.stats.stage_b_steps > 0);
    let tol = 1e-12 * s.energy_scale;
    assert!(s.max_step_constraint_work <= tol, "{s:?}");
    assert!(s.max_step_friction_work <= tol, "{s:?}");
    assert!(s.max_residual_1_49 < 1e-12, "{s:?}");
    let last = sol.audit.records.last().expect("records");
    assert!(last.friction_work < 0.0 && last.constraint_work < 0.0);
}

#[test]
fn signorini_bar_never_penetrates() {
    let bar = Arc::new(
        BarBody::new(BarData {
            mesh: IntervalMesh::uniform(1.0, 40).expect("mesh"),
            density: 1.0,
            area: 1.0,
            law: Arc::new(LinearElastic1d { young: 1.0 }),
            supports: BarSupports {
                left: false,
                right: true,
            },
            mass: MassMatrix::Consistent,
            body_force: Field::Constant(0.0),
        })
        .expect("bar"),
    );
    let contact =
        ContactModel::bar_wall(&bar, BarEnd::Left, 0.0, NormalTreatment::Signorini).expect("ok");
    let x: Vec<f64> = bar.data().mesh.nodes().to_vec();
    let u0 = bar.from_nodal(&x.iter().map(|x| 0.5 * (1.0 - x)).collect::<Vec<_>>());
    let n = bar.dofs();
    for scheme in [DynamicScheme::Midpoint, DynamicScheme::Newmark] {
        let problem = DynamicProblem {
            body: bar.clone(),
            contact: Some(contact.clone()),
            scheme,
            final_time: 3.0,
            steps: 120,
            initial_displacement: u0.clone(),
            initial_velocity: vec![0.0; n],
        };
        let mut worst = f64::NEG_INFINITY;
        let sol = DynamicSolver::new(problem, DynamicParams::default())
            .expect("ok")
            .solve_with(&mut |v| worst = worst.max(v.forces[0].p))
            .expect("run");
        assert!(worst <= 1e-14, "{scheme:?}: penetration {worst}");
        let s = sol.audit.summary();
        assert!(s.max_residual_1_48 < 1e-12, "{scheme:?}: {s:?}");
        if scheme == DynamicScheme::Midpoint {
            // the constraint at t_n only dissipates (BDS §1.6.3, stage (b))
            assert!(
                s.max_step_constraint_work <= 1e-12 * s.energy_scale,
                "{s:?}"
            );
        } else {
            // Newmark's trapezoidal contact impulse ½(ξ_{n−1} + ξ_n) still pushes the end in the
            // step it leaves the obstacle: positive work, the energy gain Newmark is known for
            assert!(s.max_step_constraint_work > 0.0, "{s:?}");
        }
    }
}

#[test]
fn newmark_with_an_energy_consistent_force_is_rejected_with_the_field_named() {
    let problem = impact(
        ball(),
        NormalTreatment::EnergyConsistent { stiffness: 1e9 },
        None,
        DynamicScheme::Newmark,
        [0.0, -10.0],
        0.01,
        10,
    );
    match DynamicSolver::new(problem, DynamicParams::default()) {
        Err(Error::Input(e)) => assert_eq!(e.field, "scheme"),
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn initial_state_of_the_wrong_length_is_named() {
    let mut problem = impact(
        ball(),
        NormalTreatment::Penalty { stiffness: 1e9 },
        None,
        DynamicScheme::Newmark,
        [0.0, -10.0],
        0.01,
        10,
    );
    problem.initial_velocity.pop();
    match DynamicSolver::new(problem, DynamicParams::default()) {
        Err(Error::Input(e)) => assert_eq!(e.field, "initial.velocity"),
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn newton_failure_is_a_typed_error_with_step_time_and_residual() {
    let problem = impact(
        ring(Arc::new(
            NeoHooke::from_young_poisson(1e6, 0.3).expect("law"),
        )),
        NormalTreatment::EnergyConsistent { stiffness: 1e9 },
        None,
        DynamicScheme::Gonzalez,
        [0.0, -10.0],
        0.01,
        40,
    );
    let mut params = DynamicParams::default();
    params.newton.max_iterations = 1;
    let err = DynamicSolver::new(problem, params)
        .expect("ok")
        .solve()
        .expect_err("one iteration cannot converge");
    match err {
        Error::Solve(SolveError::DynamicNewtonNotConverged {
            step,
            time,
            iterations,
            residual,
            floor,
            ..
        }) => {
            assert!(step >= 1 && time > 0.0 && iterations == 1 && residual > 1e-12);
            assert!(residual > floor);
        }
        other => panic!("expected DynamicNewtonNotConverged, got {other:?}"),
    }
}

#[test]
fn runs_are_bitwise_deterministic() {
    let make = || {
        impact(
            ring(Arc::new(
                NeoHooke::from_young_poisson(1e6, 0.3).expect("law"),
            )),
            NormalTreatment::LimitedPenetration {
                stiffness: 1e9,
                depth: 2e-4,
            },
            Some(FrictionCoefficient::Growing {
                mu0: 0.3,
                depth: 2e-4,
            }),
            DynamicScheme::Gonzalez,
            [4.0, -10.0],
            0.01,
            30,
        )
    };
    let (a, b) = (run(make()), run(make()));
    assert_eq!(a.final_displacement, b.final_displacement);
    assert_eq!(a.final_velocity, b.final_velocity);
}

#[test]
fn newmark_conserves_the_energy_of_a_free_linear_body() {
    let body = ball();
    let n = body.dofs();
    let v = pseudo_random(n, 1.0, 23);
    let sol = run(DynamicProblem {
        body,
        contact: None,
        scheme: DynamicScheme::Newmark,
        final_time: 0.01,
        steps: 40,
        initial_displacement: vec![0.0; n],
        initial_velocity: v,
    });
    assert!(sol.audit.summary().max_residual_1_48 < 1e-12);
}
