//! The cost of a multibody step (issue: "a step of two neo-Hookean rings with 10⁴ dofs and 10³
//! slave nodes: contact search ≤ 10 % of the step; the step cost within 1.5× of a one-body step of
//! the same size").
//!
//! - `multibody/two_rings_step`: two thin neo-Hookean rings (6000 + 4000 dofs), the slave surface the
//!   outer boundary of the first (1000 nodes), already pressed together at t = 0 and approaching,
//!   one energy–momentum step with Lagrange multipliers (the time loop of one step, setup
//!   excluded);
//! - `multibody/two_rings_search`: the contact search of that step alone (the broad-phase tree and
//!   the narrow phase for every slave node);
//! - `multibody/one_ring_step`: one neo-Hookean ring of the same size (10 000 dofs) pressed on the
//!   rigid foundation, one Gonzalez step of the one-body dynamic solver (its full Newton path);
//! - `multibody/one_ring_step_multibody`: the same ring and foundation through the multibody solver.
//!
//! `verify benches` reads these means into reports/benchmarks.md; the ratios the issue asks for are
//! computed there from the means.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};

use contactlab::model::multibody::solver::MultibodySolver;
use contactlab::scene::dynamic::DynamicScene;

#[path = "common/multibody_scenes.rs"]
mod multibody_scenes;

fn one_ring_dynamic() -> DynamicScene {
    let text = r#"
model = "dynamic"
[body]
shape = "annulus"
center = [0.0, 1.0]
inner = 0.95
outer = 1.0
radial = 4
around = 1000
density = 1.0
[material]
law = "neo_hooke"
young = 100.0
poisson = 0.3
[time]
final_time = 1e-3
steps = 1
scheme = "gonzalez"
[initial]
velocity = [0.0, -1.0]
[contact]
level = 0.0
where = "(x^2 + (y - 1)^2)^0.5 - 0.975"
treatment = "signorini"
"#;
    DynamicScene::from_toml_str(text, "bench one ring").expect("valid scene")
}

fn step(c: &mut Criterion) {
    let mut g = c.benchmark_group("multibody");
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(6));
    g.warm_up_time(Duration::from_secs(1));
    let two: MultibodySolver = multibody_scenes::two_rings(1).expect("valid problem");
    let sol = two.solve().expect("runs");
    assert!(sol.records[1].active > 0, "the rings are not in contact");
    g.bench_function("two_rings_step", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                let sol = two.solve().expect("runs");
                total += Duration::from_secs_f64(sol.stats.loop_seconds);
                black_box(sol.final_displacement[0]);
            }
            total
        })
    });
    g.bench_function("two_rings_search", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                let sol = two.solve().expect("runs");
                total += Duration::from_secs_f64(sol.stats.search_seconds);
            }
            total
        })
    });
    let one = multibody_scenes::one_ring_on_foundation(1).expect("valid problem");
    let sol = one.solve().expect("runs");
    assert!(
        sol.records[1].active > 0,
        "the ring is not on the foundation"
    );
    g.bench_function("one_ring_step_multibody", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                let sol = one.solve().expect("runs");
                total += Duration::from_secs_f64(sol.stats.loop_seconds);
            }
            total
        })
    });
    let scene = one_ring_dynamic();
    let solver = scene.solver().expect("valid problem");
    let sol = solver.solve().expect("runs");
    assert!(sol.audit.records[1].contact_force > 0.0, "no contact");
    g.bench_function("one_ring_step", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                let sol = solver.solve().expect("runs");
                total += Duration::from_secs_f64(sol.stats.loop_seconds);
                black_box(sol.final_displacement[0]);
            }
            total
        })
    });
    g.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
