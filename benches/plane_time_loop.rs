//! The 2D time loop of the paper's Test 2D (Fernández & Sofonea 2004 §4.2): clamped sides,
//! β = 1000, k = 0.01, T = 1 (100 steps). The figure: 96 × 96 squares in at most 0.28 s on a
//! 2-core machine (scikit-fem with factorization reuse: 8.56 s; NGSolve: 18.7 s). The factorization
//! happens in the warm-up run; the measured loop reuses it.
//!
//! `cargo bench --bench plane_time_loop`

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};

use contactlab::model::quasistatic::plane::PlaneProblem;
use contactlab::model::quasistatic::plane::Test2dParams;
use contactlab::model::quasistatic::plane_solver::{PlaneParams, PlaneSolver, PlaneStep};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::time::grid::TimeGrid;

fn test_2d(n: usize) -> PlaneProblem {
    PlaneProblem::fernandez_sofonea_test_2d(Test2dParams {
        divisions: n,
        ..Default::default()
    })
    .expect("valid problem")
}

fn time_loop(c: &mut Criterion) {
    let mut g = c.benchmark_group("plane_time_loop");
    g.sample_size(10);
    for n in [48usize, 96] {
        let p = test_2d(n);
        let mut solver = PlaneSolver::new(
            &p,
            TimeGrid::uniform(1.0, 100).expect("grid"),
            TimeScheme::Explicit,
            PlaneParams::default(),
        )
        .expect("valid problem");
        solver
            .run(&mut |_: &PlaneStep<'_>| {})
            .expect("warm-up run");
        g.bench_with_input(
            BenchmarkId::new("test_2d_clamped_beta_1000", format!("{n}x{n}")),
            &n,
            |b, _| {
                b.iter(|| {
                    let mut sink = 0.0;
                    solver
                        .run(&mut |st: &PlaneStep<'_>| sink += st.u[1])
                        .expect("run");
                    black_box(sink)
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, time_loop);
criterion_main!(benches);
