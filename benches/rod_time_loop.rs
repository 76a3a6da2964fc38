//! The rod's time loop (Fernández & Sofonea 2004 §4.1 data, p0 = 2): the physical-limit case of a
//! factor-once, condensed solver. The figure: M = 10⁴, N = 10³ (10⁷ dof-steps) in at most
//! 0.036 s on a 2-core machine; the cost must grow linearly in M·N.
//!
//! `cargo bench --bench rod_time_loop`

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

use contactlab::field::{Dependence, Field};
use contactlab::mesh::interval::IntervalMesh;
use contactlab::model::quasistatic::rod::RodProblem;
use contactlab::model::quasistatic::rod_solver::{RodParams, RodSolver, RodStep};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::time::grid::TimeGrid;

fn solver(problem: &RodProblem, m: usize, n: usize, scheme: TimeScheme) -> RodSolver {
    RodSolver::new(
        problem,
        IntervalMesh::uniform(problem.length, m).expect("valid mesh"),
        TimeGrid::uniform(problem.final_time, n).expect("valid grid"),
        scheme,
        RodParams::default(),
    )
    .expect("valid problem")
}

fn run(s: &RodSolver) -> f64 {
    let mut sink = 0.0;
    s.run(&mut |step: &RodStep<'_>| sink += step.contact_velocity)
        .expect("the paper's data run");
    sink
}

fn time_loop(c: &mut Criterion) {
    let problem = RodProblem::fernandez_sofonea(2.0);
    let mut g = c.benchmark_group("rod_time_loop");
    g.sample_size(20);
    for &(m, n) in &[
        (1_000, 1_000),
        (10_000, 100),
        (10_000, 1_000),
        (100_000, 100),
    ] {
        let s = solver(&problem, m, n, TimeScheme::Explicit);
        g.throughput(Throughput::Elements((m * n) as u64));
        g.bench_with_input(
            BenchmarkId::new("explicit", format!("M{m}_N{n}")),
            &s,
            |b, s| b.iter(|| black_box(run(s))),
        );
    }
    for scheme in [TimeScheme::Implicit, TimeScheme::Midpoint] {
        let s = solver(&problem, 10_000, 1_000, scheme);
        g.throughput(Throughput::Elements(10_000_000));
        g.bench_with_input(
            BenchmarkId::new(scheme.name(), "M10000_N1000"),
            &s,
            |b, s| b.iter(|| black_box(run(s))),
        );
    }
    // A load depending on x and t: assembly and one tridiagonal solve per step.
    let mut space_time = problem.clone();
    space_time.load = Field::function(
        Dependence {
            x: true,
            y: false,
            t: true,
        },
        |x, _, t| 10.0 * (1.0 + x * t),
    );
    let s = solver(&space_time, 10_000, 1_000, TimeScheme::Explicit);
    g.throughput(Throughput::Elements(10_000_000));
    g.bench_with_input(
        BenchmarkId::new("explicit_space_time_load", "M10000_N1000"),
        &s,
        |b, s| b.iter(|| black_box(run(s))),
    );
    g.finish();
}

fn setup(c: &mut Criterion) {
    let problem = RodProblem::fernandez_sofonea(2.0);
    c.bench_function("rod_setup_factor_M10000", |b| {
        b.iter(|| black_box(solver(&problem, 10_000, 1_000, TimeScheme::Explicit)))
    });
}

criterion_group!(benches, time_loop, setup);
criterion_main!(benches);
