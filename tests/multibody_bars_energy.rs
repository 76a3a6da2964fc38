//! Two identical linear bars (ν = 0, height 0.1, L = 1, c = 1) head-on at v/c = 0.1, single pass,
//! with Lagrange multipliers (issue 31, item 5): probes and regression tests.

use std::sync::Arc;

use contactlab::error::{Error, SolveError};
use contactlab::field::Field;
use contactlab::material::hyperelastic::{Hyperelastic2d, LinearElastic};
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

fn body(mesh: TriangleMesh) -> Arc<PlaneBody> {
    let mass = if std::env::var("LUMPED").is_ok() {
        MassMatrix::Lumped
    } else {
        MassMatrix::Consistent
    };
    let law: Arc<dyn Hyperelastic2d> =
        Arc::new(LinearElastic::from_young_poisson(1.0, 0.0).unwrap());
    Arc::new(
        PlaneBody::new(PlaneBodyData {
            mesh,
            density: 1.0,
            law,
            dirichlet: vec![],
            traction: vec![],
            body_force: [Field::Constant(0.0), Field::Constant(0.0)],
            mass,
            regions: vec![],
        })
        .unwrap(),
    )
}

/// Two bars [−1 − g/2, −g/2] and [g/2, 1 + g/2] × [0, 0.1] (M elements along, one row), at ±v,
/// k = h/c (Courant 1), T = 2.6 (contact over [g/(2v), g/(2v) + 2]).
fn bars(scheme: MultibodyScheme, m: usize, v0: f64, two_pass: bool) -> MultibodySolver {
    let rows: usize = if std::env::var("SQUARE").is_ok() {
        m / 10
    } else {
        std::env::var("ROWS")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(1)
    };
    bars_with(scheme, m, rows, v0, two_pass)
}

/// The bars with `rows` elements across, single pass.
fn bars_rows(scheme: MultibodyScheme, m: usize, rows: usize, v0: f64) -> MultibodySolver {
    bars_with(scheme, m, rows, v0, false)
}

fn bars_with(
    scheme: MultibodyScheme,
    m: usize,
    rows: usize,
    v0: f64,
    two_pass: bool,
) -> MultibodySolver {
    let (l, hgt, gap) = (1.0, 0.1, 0.02);
    let dl = if std::env::var("DL").is_ok() {
        Diagonal::Down
    } else {
        Diagonal::Up
    };
    let dr = if std::env::var("DR").is_ok() {
        Diagonal::Down
    } else {
        Diagonal::Up
    };
    let left =
        body(TriangleMesh::rectangle([-l - 0.5 * gap, 0.0], [l, hgt], [m, rows], dl).unwrap());
    let right = body(TriangleMesh::rectangle([0.5 * gap, 0.0], [l, hgt], [m, rows], dr).unwrap());
    let bodies = BodySet::new(vec![left, right]).unwrap();
    let side = |b: usize, s: RectangleSide| {
        ContactSurface::new(b, bodies.body(b), &BoundarySelector::side(s), "side").unwrap()
    };
    let (slave, master) = (side(0, RectangleSide::Right), side(1, RectangleSide::Left));
    let law = PairLaw {
        enforcement: Enforcement::Lagrange,
        friction: 0.0,
    };
    let mut pairs = vec![ContactPair {
        slave: slave.clone(),
        master: PairMaster::Surface(master.clone()),
        law,
    }];
    if two_pass {
        pairs.push(ContactPair {
            slave: master,
            master: PairMaster::Surface(slave),
            law,
        });
    }
    let mut v = vec![0.0; bodies.dofs()];
    bodies.rigid_velocity(0, [v0, 0.0], 0.0, [0.0, 0.0], &mut v);
    bodies.rigid_velocity(1, [-v0, 0.0], 0.0, [0.0, 0.0], &mut v);
    let n = bodies.dofs();
    let steps = 26 * m / 10;
    MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs,
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

fn centre_velocity(solver: &MultibodySolver, velocity: &[f64], b: usize) -> f64 {
    let bodies = &solver.problem().bodies;
    let mut mv = vec![0.0; velocity.len()];
    bodies.mass_mul(velocity, &mut mv);
    mv[bodies.range(b)].iter().step_by(2).sum::<f64>() / bodies.mass_of(b)
}

/// A diagnostic, not a check: the head-on bars with the scheme, speed, levels, rows, diagonals and
/// mass chosen by environment variables (SCHEME, V, MS, ROWS or SQUARE, DL/DR = `Diagonal::Down`,
/// LUMPED, TWO = two passes, VERB = per-step lines), printing E_end/E_0, the rebound, the corners'
/// transverse velocity and slide. `cargo test --release --test multibody_bars_energy -- --ignored
/// --nocapture`.
#[test]
#[ignore]
fn probe() {
    let scheme = match std::env::var("SCHEME").as_deref() {
        Ok("newmark") => MultibodyScheme::Newmark,
        Ok("midpoint") => MultibodyScheme::Midpoint,
        _ => MultibodyScheme::EnergyMomentum,
    };
    let two = std::env::var("TWO").is_ok();
    let v0: f64 = std::env::var("V")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.1);
    let ms: Vec<usize> = std::env::var("MS")
        .unwrap_or("10,20,40,80".into())
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    let verbose = std::env::var("VERB").is_ok();
    for m in ms {
        let solver = bars(scheme, m, v0, two);
        let mut lines = Vec::new();
        let mut vy_max = 0.0f64;
        let mut rel_max = 0.0f64;
        let rows: usize = if std::env::var("SQUARE").is_ok() {
            m / 10
        } else {
            std::env::var("ROWS")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(1)
        };
        let res = solver.solve_with(&mut |view| {
            {
                let b = &solver.problem().bodies;
                let top = rows * (m + 1);
                let y = |bb: usize, node: usize| b.dof(bb, node, 1).map_or(0.0, |d| view.displacement[d]);
                let vy = |bb: usize, node: usize| b.dof(bb, node, 1).map_or(0.0, |d| view.velocity[d]);
                for (s, mm) in [(m, 0), (top + m, top)] {
                    vy_max = vy_max.max(vy(0, s).abs()).max(vy(1, mm).abs());
                    rel_max = rel_max.max((y(0, s) - y(1, mm)).abs());
                }
            }
            if verbose {
                // the slave corners' velocities (left bar's right end: nodes m and 2m+1)
                let b = &solver.problem().bodies;
                let corner = |node: usize, c: usize| b.dof(0, node, c).map(|d| view.velocity[d]);
                let mcorner = |node: usize, c: usize| b.dof(1, node, c).map(|d| view.velocity[d]);
                lines.push(format!(
                    "step {} E {:.6e} act {} rel {} W_act {:.3e} W_sw {:.3e} slave vy {:?} {:?} master vy {:?} {:?}",
                    view.step,
                    view.record.energy,
                    view.record.active,
                    view.record.released,
                    view.record.activation_work,
                    view.record.switch_work,
                    corner(m, 1),
                    corner(2 * m + 1, 1),
                    mcorner(0, 1),
                    mcorner(m + 1, 1),
                ));
            }
        });
        for l in &lines {
            println!("{l}");
        }
        match res {
            Ok(sol) => {
                let s = sol.summary();
                let e0 = sol.records[0].energy;
                let e1 = sol.records.last().unwrap().energy;
                let vb = centre_velocity(&solver, &sol.final_velocity, 0);
                println!(
                    "  max corner |vy|/v {:.3} max |y_s - y_m| / (H/rows) {:.4}",
                    vy_max / v0,
                    rel_max / (0.1 / rows as f64)
                );
                println!(
                    "M {m}: E_end/E0 {:.6} rebound/v {:.6} act {:.3e} releases {} switches {} id {:.2e}",
                    e1 / e0,
                    vb / v0,
                    s.activation_work / e0,
                    sol.stats.releases,
                    sol.stats.switches,
                    s.identity_ratio
                );
            }
            Err(e) => println!(
                "M {m}: error {e}\n  max corner |vy|/v {:.3} max |y_s - y_m| / (H/rows) {:.4}",
                vy_max / v0,
                rel_max / (0.1 / rows as f64)
            ),
        }
    }
}

/// The head-on run's outcome: max_n (E_n − E_0)/E_0, the left bar's rebound over v, and the
/// positive set-change work the audit flagged, over E_0.
fn head_on(m: usize, rows: usize, scheme: MultibodyScheme) -> (f64, f64, f64) {
    let solver = bars_rows(scheme, m, rows, 0.1);
    let sol = solver
        .solve()
        .unwrap_or_else(|e| panic!("{m} elements, {rows} rows: {e}"));
    let e0 = sol.records[0].energy;
    let rise = sol
        .records
        .iter()
        .map(|r| (r.energy - e0) / e0)
        .fold(f64::NEG_INFINITY, f64::max);
    let rebound = centre_velocity(&solver, &sol.final_velocity, 0) / 0.1;
    let flagged = sol.records.iter().map(|r| r.positive_set_work).sum::<f64>() / e0;
    (rise, rebound, flagged)
}

/// Issue 31, item 5: the head-on bars at v/c = 0.1 with 10, 20, 40 and 80 elements along (one row,
/// and square cells) run to the end and rebound at −v within the discretization error: the
/// error falls at every refinement, at the fitted rate ≥ 0.5 (`multibody_bars` measures the
/// velocities after the release at rate ≈ 2/3; measured 0.57 and 0.63 here), from ≤ 5 % on 10
/// elements (measured 4.7 %). With one row E ≤ E₀ at every step (1e-12 relative); with square
/// cells E exceeds E₀ only by the positive work of held nodes switching segment at a concave kink
/// of the deformed master face, which the audit flags (measured ≤ 1.2e-6 E₀). Before the fix the
/// corner nodes were released 2 % past the master's free end under load and re-activated from
/// inside: E rose by 11 % (20 elements, one row) or the step stopped with `no_equilibrium` (10
/// elements; 10 … 80 with square cells).
#[test]
fn head_on_bars_at_a_tenth_of_c_never_gain_energy_and_rebound_at_minus_v() {
    for square in [false, true] {
        let mut errors = Vec::new();
        for m in [10, 20, 40, 80] {
            let rows = if square { m / 10 } else { 1 };
            let (rise, rebound, flagged) = head_on(m, rows, MultibodyScheme::EnergyMomentum);
            let allowed = if square { flagged } else { 0.0 };
            assert!(
                rise <= allowed + 1e-12,
                "{m} × {rows}: E rose by {rise:e} E_0 (flagged switch work {flagged:e} E_0)"
            );
            errors.push((rebound + 1.0).abs());
        }
        assert!(errors[0] < 0.05, "square {square}: {errors:?}");
        assert!(
            errors.windows(2).all(|w| w[1] < w[0]),
            "square {square}: {errors:?}"
        );
        // least-squares slope of log error against log h over the four levels
        let xs: Vec<f64> = (0..4).map(|i| -(i as f64) * 2f64.ln()).collect();
        let ys: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
        let (mx, my) = (xs.iter().sum::<f64>() / 4.0, ys.iter().sum::<f64>() / 4.0);
        let rate = xs
            .iter()
            .zip(&ys)
            .map(|(x, y)| (x - mx) * (y - my))
            .sum::<f64>()
            / xs.iter().map(|x| (x - mx) * (x - mx)).sum::<f64>();
        assert!(rate >= 0.5, "square {square}: rate {rate} ({errors:?})");
    }
}

/// A block moving sideways at (1, 0) below the top line of a master block it approaches from
/// beside the master's free end (only the master's top is a master surface): its top corner
/// enters the band past the free end where it is held on the end segment's line extended, from
/// 0.05 below it — a node re-activated from inside. `allow`: the pair accepts the energy gain.
fn side_entry(allow: bool) -> MultibodySolver {
    let law: Arc<dyn Hyperelastic2d> =
        Arc::new(LinearElastic::from_young_poisson(100.0, 0.0).unwrap());
    let block = |origin: [f64; 2], size: [f64; 2], div: [usize; 2]| {
        Arc::new(
            PlaneBody::new(PlaneBodyData {
                mesh: TriangleMesh::rectangle(origin, size, div, Diagonal::Up).unwrap(),
                density: 1.0,
                law: law.clone(),
                dirichlet: vec![],
                traction: vec![],
                body_force: [Field::Constant(0.0), Field::Constant(0.0)],
                mass: MassMatrix::Consistent,
                regions: vec![],
            })
            .unwrap(),
        )
    };
    let master = block([0.0, -0.5], [1.0, 0.5], [4, 2]);
    let slave = block([-0.45, -0.25], [0.2, 0.2], [1, 1]);
    let bodies = BodySet::new(vec![slave, master]).unwrap();
    let top = |b: usize| {
        ContactSurface::new(
            b,
            bodies.body(b),
            &BoundarySelector::side(RectangleSide::Top),
            "top",
        )
        .unwrap()
    };
    let pairs = vec![ContactPair {
        slave: top(0),
        master: PairMaster::Surface(top(1)),
        law: PairLaw {
            enforcement: Enforcement::Lagrange,
            friction: 0.0,
        },
    }];
    let mut v = vec![0.0; bodies.dofs()];
    bodies.rigid_velocity(0, [1.0, 0.0], 0.0, [0.0, 0.0], &mut v);
    let n = bodies.dofs();
    MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs,
            scheme: MultibodyScheme::EnergyMomentum,
            final_time: 0.3,
            steps: 30,
            initial_displacement: vec![0.0; n],
            initial_velocity: v,
        },
        MultibodyParams {
            allow_energy_gain: vec![allow],
            ..MultibodyParams::default()
        },
    )
    .unwrap()
}

/// Issue 31: an energy–momentum run whose energy rose through a constraint's positive work (a node
/// re-activated from inside the master) is a typed `EnergyGain` error naming the step, the
/// constraint and its work, E and E/E_0 — and the same run completes when the pair allows it,
/// with E above E_0 and the positive work flagged by the audit.
#[test]
fn energy_gain_through_a_node_entering_from_inside_is_refused_unless_the_pair_allows_it() {
    let err = side_entry(false).solve().expect_err("an energy gain");
    let Error::Solve(SolveError::EnergyGain {
        energy,
        initial,
        ratio,
        rise,
        tolerance,
        constraint,
        kind,
        work,
        ..
    }) = &err
    else {
        panic!("expected EnergyGain, got {err}");
    };
    assert!(*rise > *tolerance && *work > 0.0, "{err}");
    assert!(
        *energy > *initial && (ratio - energy / initial).abs() < 1e-15,
        "{err}"
    );
    assert!(constraint.starts_with("pair 0 slave node"), "{constraint}");
    assert_eq!(kind, "activation");
    let message = err.to_string();
    assert!(message.contains("allow_energy_gain"), "{message}");
    let sol = side_entry(true).solve().expect("allowed");
    let s = sol.summary();
    assert!(
        s.energy_rise_ratio > 1.0 && s.final_energy_ratio > 1.0,
        "{s:?}"
    );
    assert!(
        s.positive_set_work_steps >= 1 && s.positive_set_work_relative > 0.0,
        "{s:?}"
    );
}
