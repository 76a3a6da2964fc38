//! The cost of one step of the dynamic contact solver at about 10⁴ dofs, with contact active in
//! the step, and of the kernels a step is made of (Barboteu–Danan–Sofonea, "BDS", §1.6).
//!
//! - `step/linear_ball_condensed`: a linear elastic disk (rings = 40, 9 842 dofs) pressed 2 mm
//!   into the foundation and thrown at it at 10 m/s; midpoint rule with the energy-consistent
//!   force (BDS (1.46)), r = 1e9: the condensed path (α M + θ K factored once with the contact
//!   dofs last; one forward and one backward pass per step, the Newton method on the 81 contact
//!   dofs).
//! - `step/neo_hooke_ring_full`: a neo-Hookean annulus (radial = 16, around = 300, 10 200 dofs),
//!   same contact, Gonzalez's scheme (BDS (1.41)–(1.43)): the full path (per Newton iteration the
//!   discrete-gradient force, its tangent, a numeric sparse Cholesky refactorization, a solve).
//!
//! A step is timed by the solver's own clock over the time loop of a one-step run
//! (`DynamicStats::loop_seconds`, setup excluded), through `iter_custom`.
//!
//! Kernels (same ring, same mesh): the Gonzalez force F^algo(u0, u1) (BDS (1.42)), its symmetric
//! tangent, the midpoint tangent K_T(u), the numeric factorization of α M + θ K_T with the
//! analysis reused, one sparse solve, and the condensed path's forward + backward pass on the
//! ball.
//!
//! The whole run `run/ring_impact_mu1_report`: the ring impact of the report
//! (`examples/scenes/dynamic_ring_impact_mu1.toml`: BDS §1.7.2, 1 152 dofs, 700 steps, Gonzalez +
//! IPM + Coulomb μ1), scene to solution; its budget is in `benches/budgets.toml`.
//!
//! `cargo bench --bench dynamic_step`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};

use contactlab::scene::dynamic::DynamicScene;
use contactlab::solve::sparse_cholesky::SparseCholesky;

/// A linear elastic disk pressed 2 mm into the foundation, one step of k = 1e-4.
fn ball(steps: usize) -> DynamicScene {
    let text = format!(
        r#"
model = "dynamic"
[body]
shape = "disk"
center = [0.0, 0.498]
radius = 0.5
rings = 40
density = 1000.0
[material]
law = "linear"
young = 1e7
poisson = 0.3
[time]
final_time = {}
steps = {steps}
scheme = "midpoint"
[initial]
velocity = [0.0, -10.0]
[contact]
level = 0.0
where = "0.5 - y"
treatment = "energy_consistent"
stiffness = 1e9
"#,
        1e-4 * steps as f64
    );
    DynamicScene::from_toml_str(&text, "bench ball").expect("valid scene")
}

/// A neo-Hookean annulus pressed 2 mm into the foundation, one step of k = 1e-4.
fn ring(steps: usize) -> DynamicScene {
    let text = format!(
        r#"
model = "dynamic"
[body]
shape = "annulus"
center = [0.0, 0.498]
inner = 0.3
outer = 0.5
radial = 16
around = 300
density = 1000.0
[material]
law = "neo_hooke"
young = 1e6
poisson = 0.3
[time]
final_time = {}
steps = {steps}
scheme = "gonzalez"
[initial]
velocity = [2.0, -5.0]
[contact]
level = 0.0
where = "0.5 - y"
treatment = "energy_consistent"
stiffness = 1e9
"#,
        1e-4 * steps as f64
    );
    DynamicScene::from_toml_str(&text, "bench ring").expect("valid scene")
}

/// One step, timed by the solver's loop clock (setup excluded).
fn one_step(c: &mut Criterion) {
    let mut g = c.benchmark_group("step");
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(4));
    g.warm_up_time(Duration::from_secs(1));
    for (name, scene) in [
        ("linear_ball_condensed_9842_dofs", ball(1)),
        ("neo_hooke_ring_full_10200_dofs", ring(1)),
    ] {
        let solver = scene.solver().expect("valid problem");
        // contact is active in the step
        let sol = solver.solve().expect("runs");
        assert!(
            sol.audit.records[1].contact_force > 0.0,
            "{name}: no contact"
        );
        g.bench_function(name, |b| {
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
    }
    g.finish();
}

/// The kernels of a step.
fn kernels(c: &mut Criterion) {
    let mut g = c.benchmark_group("kernels");
    g.sample_size(20);
    g.measurement_time(Duration::from_secs(3));
    g.warm_up_time(Duration::from_millis(500));
    let scene = ring(1);
    let body = scene.problem.body.clone();
    let n = body.dofs();
    let pattern = body.pattern().clone();
    // a state after one step (u0) and a trial state u1 = u0 + k v
    let sol = scene.solve().expect("runs");
    let u0 = sol.final_displacement.clone();
    let u1: Vec<f64> = u0
        .iter()
        .zip(&sol.final_velocity)
        .map(|(u, v)| u + 1e-4 * v)
        .collect();
    let mut f = vec![0.0; n];
    g.bench_function("ring_gonzalez_force", |b| {
        b.iter(|| black_box(body.discrete_gradient_force(&u0, &u1, &mut f)))
    });
    g.bench_function("ring_internal_force", |b| {
        b.iter(|| black_box(body.internal_force(&u1, &mut f)))
    });
    let alpha = 2.0 / (1e-4 * 1e-4);
    let base: Vec<f64> = body.mass().iter().map(|m| alpha * m).collect();
    let mut values = base.clone();
    g.bench_function("ring_gonzalez_tangent_assembly", |b| {
        b.iter(|| {
            values.copy_from_slice(&base);
            body.add_discrete_gradient_tangent(&u0, &u1, 1.0, &mut values);
            black_box(values[0])
        })
    });
    g.bench_function("ring_tangent_assembly", |b| {
        b.iter(|| {
            values.copy_from_slice(&base);
            body.add_tangent(&u1, 0.5, &mut values);
            black_box(values[0])
        })
    });
    values.copy_from_slice(&base);
    body.add_discrete_gradient_tangent(&u0, &u1, 1.0, &mut values);
    let mut chol = SparseCholesky::analyze(&pattern, &[], "bench").expect("analysis");
    g.bench_function("ring_numeric_factorization", |b| {
        b.iter(|| chol.factor(&pattern, &values).expect("SPD"))
    });
    let mut ws = chol.workspace(1);
    let mut x = vec![1.0; n];
    g.bench_function("ring_sparse_solve", |b| {
        b.iter(|| {
            chol.solve_in_place(&mut x, &mut ws);
            black_box(x[0])
        })
    });
    // the condensed path's passes on the ball
    let ball = ball(1);
    let bb = ball.problem.body.clone();
    let kv = bb.linear_stiffness().expect("linear");
    let a: Vec<f64> = bb
        .mass()
        .iter()
        .zip(kv)
        .map(|(m, k)| alpha * m + 0.5 * k)
        .collect();
    let bg = ball
        .problem
        .contact
        .as_ref()
        .map(|c| c.dofs())
        .unwrap_or_default();
    let mut bchol = SparseCholesky::analyze(bb.pattern(), &bg, "bench ball").expect("analysis");
    bchol.factor(bb.pattern(), &a).expect("SPD");
    let mut bws = bchol.workspace(1);
    let rhs = vec![1.0; bb.dofs()];
    let mut y = vec![0.0; bb.dofs()];
    let mut out = vec![0.0; bb.dofs()];
    g.bench_function("ball_forward_backward", |b| {
        b.iter(|| {
            bchol.forward(&rhs, &mut y, &mut bws);
            bchol.backward(&mut y, &mut out, &mut bws);
            black_box(out[0])
        })
    });
    g.finish();
}

/// The report's ring impact, scene to solution.
fn whole_run(c: &mut Criterion) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes/dynamic_ring_impact_mu1.toml");
    let scene = contactlab::scene::Scene::load(&path).expect("the example scene loads");
    let mut g = c.benchmark_group("run");
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(60));
    g.warm_up_time(Duration::from_secs(1));
    g.bench_function("ring_impact_mu1_report", |b| {
        b.iter(|| black_box(scene.run().expect("the example runs")))
    });
    g.finish();
}

criterion_group!(benches, one_step, kernels, whole_run);
criterion_main!(benches);
