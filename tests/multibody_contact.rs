//! Two-body node-to-segment contact: the setting is two plane-strain bodies that meet; the goal is
//! to pin the energy–momentum scheme's conservation, the bars' exact impact and the patch test.

use std::sync::Arc;

use contactlab::field::Field;
use contactlab::material::hyperelastic::{Hyperelastic2d, LinearElastic, NeoHooke};
use contactlab::mesh::triangle::{Diagonal, RectangleSide, TriangleMesh};
use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};
use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::constraint::{Enforcement, PairLaw};
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{
    ContactPair, MultibodyParams, MultibodyProblem, MultibodySolver, PairMaster,
};
use contactlab::model::multibody::surface::ContactSurface;
use contactlab::model::quasistatic::plane::BoundarySelector;

fn body(mesh: TriangleMesh, law: Arc<dyn Hyperelastic2d>, density: f64) -> Arc<PlaneBody> {
    Arc::new(
        PlaneBody::new(PlaneBodyData {
            mesh,
            density,
            law,
            dirichlet: vec![],
            traction: vec![],
            body_force: [Field::Constant(0.0), Field::Constant(0.0)],
            mass: MassMatrix::Consistent,
            regions: vec![],
        })
        .unwrap(),
    )
}

fn bars(
    scheme: MultibodyScheme,
    m: usize,
    steps: usize,
    law: Arc<dyn Hyperelastic2d>,
) -> MultibodySolver {
    let (l, hgt, v0) = (1.0, 0.1, 0.1);
    let left = body(
        TriangleMesh::rectangle([-l - 0.01, 0.0], [l, hgt], [m, 1], Diagonal::Up).unwrap(),
        law.clone(),
        1.0,
    );
    let right = body(
        TriangleMesh::rectangle([0.01, 0.0], [l, hgt], [m, 1], Diagonal::Up).unwrap(),
        law,
        1.0,
    );
    let bodies = BodySet::new(vec![left, right]).unwrap();
    let slave = ContactSurface::new(
        0,
        bodies.body(0),
        &BoundarySelector::side(RectangleSide::Right),
        "slave",
    )
    .unwrap();
    let master = ContactSurface::new(
        1,
        bodies.body(1),
        &BoundarySelector::side(RectangleSide::Left),
        "master",
    )
    .unwrap();
    let mut v = vec![0.0; bodies.dofs()];
    bodies.rigid_velocity(0, [v0, 0.0], 0.0, [0.0, 0.0], &mut v);
    bodies.rigid_velocity(1, [-v0, 0.0], 0.0, [0.0, 0.0], &mut v);
    let n = bodies.dofs();
    MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs: vec![ContactPair {
                slave,
                master: PairMaster::Surface(master),
                law: PairLaw {
                    enforcement: Enforcement::Lagrange,
                    friction: 0.0,
                },
            }],
            scheme,
            final_time: 2.6,
            steps,
            initial_displacement: vec![0.0; n],
            initial_velocity: v,
        },
        MultibodyParams::default(),
    )
    .unwrap()
}

#[test]
fn bars_head_on_energy_momentum() {
    let law: Arc<dyn Hyperelastic2d> =
        Arc::new(LinearElastic::from_young_poisson(1.0, 0.0).unwrap());
    for scheme in MultibodyScheme::ALL {
        let s = bars(scheme, 40, 260, law.clone());
        let sol = s.solve().unwrap();
        let sum = sol.summary();
        let last = sol.records.last().unwrap();
        println!(
            "{scheme:?}: {sum:?}\n stats {:?}\n last E {} P {:?} J {}",
            sol.stats, last.energy, last.momentum, last.angular_momentum
        );
    }
    let nh: Arc<dyn Hyperelastic2d> = Arc::new(NeoHooke::from_young_poisson(1.0, 0.3).unwrap());
    for scheme in MultibodyScheme::ALL {
        let s = bars(scheme, 40, 260, nh.clone());
        match s.solve() {
            Ok(sol) => println!("NH {scheme:?}: {:?}\n stats {:?}", sol.summary(), sol.stats),
            Err(e) => println!("NH {scheme:?}: {e}"),
        }
    }
}

use contactlab::model::quasistatic::plane::{DirichletPart, Support, TractionPart};

fn block(
    origin: [f64; 2],
    size: [f64; 2],
    div: [usize; 2],
    law: Arc<dyn Hyperelastic2d>,
    dirichlet: Vec<DirichletPart>,
    traction: Vec<TractionPart>,
    gravity: f64,
) -> Arc<PlaneBody> {
    Arc::new(
        PlaneBody::new(PlaneBodyData {
            mesh: TriangleMesh::rectangle(origin, size, div, Diagonal::Up).unwrap(),
            density: 1.0,
            law,
            dirichlet,
            traction,
            body_force: [Field::Constant(0.0), Field::Constant(-gravity)],
            mass: MassMatrix::Consistent,
            regions: vec![],
        })
        .unwrap(),
    )
}

#[test]
fn patch_test_explore() {
    let p = 0.01;
    let lower_law: Arc<dyn Hyperelastic2d> =
        Arc::new(LinearElastic::from_young_poisson(1.0, 0.3).unwrap());
    let upper_law: Arc<dyn Hyperelastic2d> =
        Arc::new(LinearElastic::from_young_poisson(1.0, 0.3).unwrap());
    for two_pass in [false, true] {
        let lower = block(
            [0.0, 0.0],
            [2.0, 1.0],
            [4, 2],
            lower_law.clone(),
            vec![
                DirichletPart {
                    boundary: BoundarySelector::side(RectangleSide::Bottom),
                    support: Support::FixY,
                },
                DirichletPart {
                    boundary: BoundarySelector::side(RectangleSide::Left),
                    support: Support::FixX,
                },
            ],
            vec![],
            0.0,
        );
        let upper = block(
            [0.0, 1.0],
            [2.0, 1.0],
            [5, 3],
            upper_law.clone(),
            vec![DirichletPart {
                boundary: BoundarySelector::side(RectangleSide::Left),
                support: Support::FixX,
            }],
            vec![TractionPart {
                boundary: BoundarySelector::side(RectangleSide::Top),
                traction: [Field::Constant(0.0), Field::Constant(-p)],
            }],
            0.0,
        );
        let bodies = BodySet::new(vec![lower, upper]).unwrap();
        let s_up = ContactSurface::new(
            1,
            bodies.body(1),
            &BoundarySelector::side(RectangleSide::Bottom),
            "s",
        )
        .unwrap();
        let s_lo = ContactSurface::new(
            0,
            bodies.body(0),
            &BoundarySelector::side(RectangleSide::Top),
            "m",
        )
        .unwrap();
        let law = PairLaw {
            enforcement: Enforcement::Lagrange,
            friction: 0.0,
        };
        let mut pairs = vec![ContactPair {
            slave: s_up.clone(),
            master: PairMaster::Surface(s_lo.clone()),
            law,
        }];
        if two_pass {
            pairs.push(ContactPair {
                slave: s_lo,
                master: PairMaster::Surface(s_up),
                law,
            });
        }
        let n = bodies.dofs();
        let solver = MultibodySolver::new(
            MultibodyProblem {
                bodies,
                pairs,
                scheme: MultibodyScheme::EnergyMomentum,
                final_time: 1.0,
                steps: 1,
                initial_displacement: vec![0.0; n],
                initial_velocity: vec![0.0; n],
            },
            MultibodyParams::default(),
        )
        .unwrap();
        let sol = solver.solve_static(1.0).unwrap();
        // stress in every element
        let pb = solver.problem();
        let mut worst: f64 = 0.0;
        for b in 0..2 {
            let body = pb.bodies.body(b);
            let u = &sol.displacement[pb.bodies.range(b)];
            for e in 0..body.elements().len() {
                let f = body.deformation_gradient(u, e);
                let s = body.law_of(e).piola(&f);
                worst = worst
                    .max((s[(1, 1)] + p).abs())
                    .max(s[(0, 0)].abs())
                    .max(s[(0, 1)].abs());
                if b == 1 && e < 10 {
                    println!(
                        "   body {b} el {e}: σ {:.6e} {:.6e} {:.6e}",
                        s[(0, 0)],
                        s[(1, 1)],
                        s[(0, 1)]
                    );
                }
            }
        }
        println!(
            "two_pass {two_pass}: iterations {}, worst stress error {worst:e} (p = {p})",
            sol.iterations
        );
        for c in &sol.contacts {
            println!(
                "   pair {} slave {} λ {:.6e} λ/w {:.6e} gap {:e} active {}",
                c.pair,
                c.slave,
                c.lambda_n,
                c.lambda_n / c.weight,
                c.gap,
                c.active
            );
        }
    }
}

#[test]
fn sliding_explore() {
    use contactlab::model::multibody::surface::Foundation;
    let g = 1.0;
    let law: Arc<dyn Hyperelastic2d> =
        Arc::new(LinearElastic::from_young_poisson(1000.0, 0.0).unwrap());
    let lower = block(
        [0.0, 0.0],
        [4.0, 0.5],
        [16, 2],
        law.clone(),
        vec![],
        vec![],
        g,
    );
    let upper = block(
        [0.5, 0.5],
        [1.0, 0.5],
        [5, 3],
        law.clone(),
        vec![],
        vec![],
        g,
    );
    let bodies = BodySet::new(vec![lower, upper]).unwrap();
    let s_up = ContactSurface::new(
        1,
        bodies.body(1),
        &BoundarySelector::side(RectangleSide::Bottom),
        "s",
    )
    .unwrap();
    let s_lo = ContactSurface::new(
        0,
        bodies.body(0),
        &BoundarySelector::side(RectangleSide::Top),
        "m",
    )
    .unwrap();
    let s_base = ContactSurface::new(
        0,
        bodies.body(0),
        &BoundarySelector::side(RectangleSide::Bottom),
        "b",
    )
    .unwrap();
    let mu = 0.3;
    let pairs = vec![
        ContactPair {
            slave: s_up,
            master: PairMaster::Surface(s_lo),
            law: PairLaw {
                enforcement: Enforcement::Lagrange,
                friction: mu,
            },
        },
        ContactPair {
            slave: s_base,
            master: PairMaster::Foundation(Foundation::horizontal(0.0)),
            law: PairLaw {
                enforcement: Enforcement::Lagrange,
                friction: 0.0,
            },
        },
    ];
    let n = bodies.dofs();
    let mut v = vec![0.0; n];
    bodies.rigid_velocity(1, [1.0, 0.0], 0.0, [0.0, 0.0], &mut v);
    let (m1, m2) = (bodies.mass_of(1), bodies.mass_of(0));
    for scheme in [MultibodyScheme::EnergyMomentum, MultibodyScheme::Midpoint] {
        let solver = MultibodySolver::new(
            MultibodyProblem {
                bodies: bodies.clone(),
                pairs: pairs.clone(),
                scheme,
                final_time: 0.6,
                steps: 300,
                initial_displacement: vec![0.0; n],
                initial_velocity: v.clone(),
            },
            MultibodyParams::default(),
        )
        .unwrap();
        let mut rel = Vec::new();
        let sol = solver.solve_with(&mut |view| {
            let vel = view.velocity;
            let r0 = solver.problem().bodies.range(0);
            let r1 = solver.problem().bodies.range(1);
            let mut mv = vec![0.0; vel.len()];
            solver.problem().bodies.mass_mul(vel, &mut mv);
            let p0: f64 = mv[r0].iter().step_by(2).sum();
            let p1: f64 = mv[r1].iter().step_by(2).sum();
            rel.push((
                view.time,
                p1 / m1 - p0 / m2,
                view.record.slipping,
                view.record.sticking,
            ));
        });
        match sol {
            Ok(sol) => {
                let s = sol.summary();
                println!("{scheme:?}: {s:?}\n{:?}", sol.stats);
                let pred = 1.0 / (mu * g * (1.0 + m1 / m2));
                println!("predicted stop {pred}");
                for r in rel.iter().step_by(30) {
                    println!("  {:?}", r);
                }
                let px: Vec<f64> = sol.records.iter().map(|r| r.momentum[0]).collect();
                println!(
                    "  px drift {:e}",
                    px.iter().map(|p| (p - px[0]).abs()).fold(0.0, f64::max)
                );
            }
            Err(e) => println!("{scheme:?}: {e}"),
        }
    }
}

fn ring(
    center: [f64; 2],
    law: Arc<dyn Hyperelastic2d>,
    radial: usize,
    around: usize,
) -> Arc<PlaneBody> {
    Arc::new(
        PlaneBody::new(PlaneBodyData {
            mesh: contactlab::mesh::generators::annulus(center, 0.6, 1.0, radial, around).unwrap(),
            density: 1.0,
            law,
            dirichlet: vec![],
            traction: vec![],
            body_force: [Field::Constant(0.0), Field::Constant(0.0)],
            mass: MassMatrix::Consistent,
            regions: vec![],
        })
        .unwrap(),
    )
}

#[test]
fn rings_explore() {
    let law: Arc<dyn Hyperelastic2d> = Arc::new(NeoHooke::from_young_poisson(20.0, 0.3).unwrap());
    let a = ring([-1.1, 0.0], law.clone(), 4, 48);
    let b = ring([1.1, 0.5], law.clone(), 4, 48);
    let bodies = BodySet::new(vec![a, b]).unwrap();
    let outer = |i: usize| {
        let c = if i == 0 { [-1.1, 0.0] } else { [1.1, 0.5] };
        BoundarySelector::Predicate(Arc::new(move |x: [f64; 2]| {
            ((x[0] - c[0]).powi(2) + (x[1] - c[1]).powi(2)).sqrt() > 0.8
        }))
    };
    let sa = ContactSurface::new(0, bodies.body(0), &outer(0), "a").unwrap();
    let sb = ContactSurface::new(1, bodies.body(1), &outer(1), "b").unwrap();
    for mu in [0.0, 0.3] {
        let law = PairLaw {
            enforcement: Enforcement::Lagrange,
            friction: mu,
        };
        let mut pairs = vec![
            ContactPair {
                slave: sa.clone(),
                master: PairMaster::Surface(sb.clone()),
                law,
            },
            ContactPair {
                slave: sb.clone(),
                master: PairMaster::Surface(sa.clone()),
                law,
            },
        ];
        if std::env::var("ONE_PASS").is_ok() {
            pairs.pop();
        }
        let n = bodies.dofs();
        let mut v = vec![0.0; n];
        bodies.rigid_velocity(0, [1.0, 0.0], 0.0, [-1.1, 0.0], &mut v);
        bodies.rigid_velocity(1, [-1.0, 0.0], 0.0, [1.1, 0.5], &mut v);
        for scheme in MultibodyScheme::ALL {
            let solver = MultibodySolver::new(
                MultibodyProblem {
                    bodies: bodies.clone(),
                    pairs: pairs.clone(),
                    scheme,
                    final_time: 1.0,
                    steps: 200,
                    initial_displacement: vec![0.0; n],
                    initial_velocity: v.clone(),
                },
                MultibodyParams::default(),
            )
            .unwrap();
            match solver.solve() {
                Ok(sol) => {
                    let s = sol.summary();
                    let (t0, t1) = sol
                        .records
                        .iter()
                        .filter(|r| r.active > 0)
                        .fold((f64::INFINITY, 0.0f64), |(a, b), r| {
                            (a.min(r.time), b.max(r.time))
                        });
                    println!("mu {mu} {scheme:?}: drift {:.3e} activation {:.3e} unchanged_rel {:.3e} P {:.2e} J {:.2e} contact [{t0:.4}, {t1:.4}] its {} E_end {:.6}", s.energy_drift, s.activation_relative, s.unchanged_relative, s.momentum_ratio, s.angular_ratio, sol.stats.newton_iterations, sol.records.last().unwrap().energy);
                }
                Err(e) => println!("mu {mu} {scheme:?}: {e}"),
            }
        }
    }
}
