//! Stability maps of the thick string with friction (Hetzler 2009 §4.2.2, ideal contact, N = 20
//! sine functions, 21 coordinates, companion order 42). The figure: a 200 × 200 map in
//! under 5 s on a 2-core machine, parallel over points and deterministic.
//!
//! - `point/*`: one point's eigenvalues — faer's dense eigensolver (the reference), the
//!   eigenvalue-only kernel, and one point of a rank-one line (one Hessenberg reduction per line);
//! - `map/200x200`: the whole map as `string_stability_map` runs it (all cores).
//!
//! `cargo bench --bench moving_stability_map`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};

use contactlab::model::moving::stability_map::{
    string_stability_map, GridAxis, StabilityMapParams,
};
use contactlab::model::moving::string_data::{
    ContactModel, MovingStringData, OscillatorData, StringParameter,
};
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};
use contactlab::solve::quadratic_eigen::{EigenKernel, QuadraticEigenParams, QuadraticEigenSolver};
use contactlab::solve::small_eigenvalues::RankOneLine;

fn data(speed: f64, control: f64) -> MovingStringData {
    MovingStringData {
        speed,
        damping: 0.05,
        oscillator: Some(OscillatorData {
            stiffness: 2.0,
            mass: 0.5,
            position: 0.3,
            contact: ContactModel::Ideal,
            friction: control / 2.0,
            patch_width: 0.0,
        }),
    }
}

fn model() -> MovingStringModel {
    MovingStringModel::new(StringDiscretization::Sine { modes: 20 }, Default::default())
        .expect("valid discretization")
}

fn point(c: &mut Criterion) {
    let m = model();
    let s = m.system(&data(0.5, 0.05)).expect("valid data");
    let (cm, km) = (s.velocity_matrix(), s.stiffness_matrix());
    let mut g = c.benchmark_group("moving_stability_map/point");
    for (name, kernel) in [
        ("faer", EigenKernel::Faer),
        ("small_dense", EigenKernel::SmallDense),
    ] {
        let mut solver = QuadraticEigenSolver::new(
            s.mass.as_ref(),
            QuadraticEigenParams {
                kernel,
                ..Default::default()
            },
        )
        .expect("positive definite mass");
        let mut out = Vec::new();
        g.bench_function(name, |b| {
            b.iter(|| {
                solver
                    .eigenvalues_into(cm.as_ref(), km.as_ref(), &mut out)
                    .expect("converges");
                black_box(out[0])
            })
        });
    }
    // One point of a rank-one line: the Hessenberg matrix is reduced once per line.
    let s0 = m.system(&data(0.5, 0.0)).expect("valid data");
    let mut solver = QuadraticEigenSolver::new(s0.mass.as_ref(), QuadraticEigenParams::default())
        .expect("positive definite mass");
    let (a0, gamma) = solver
        .scaled_companion(
            s0.velocity_matrix().as_ref(),
            s0.stiffness_matrix().as_ref(),
        )
        .expect("valid matrices");
    let (mut r, sv, coef) = m
        .friction_rank_one(&data(0.5, 0.0), StringParameter::ControlParameter)
        .expect("rank one");
    solver.solve_mass(&mut r);
    let n = r.len();
    let mut bv = vec![0.0; 2 * n];
    let mut cv = vec![0.0; 2 * n];
    for i in 0..n {
        bv[n + i] = -coef / (gamma * gamma) * r[i];
        cv[i] = sv[i];
    }
    let mut line = RankOneLine::new(&a0, &bv, &cv);
    let (mut re, mut im) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
    g.bench_function("rank_one_line", |b| {
        b.iter(|| {
            line.eigenvalues_at(black_box(0.05), &mut re, &mut im)
                .expect("converges");
            black_box(re[0])
        })
    });
    g.finish();
}

fn map(c: &mut Criterion) {
    let m = model();
    let base = data(0.0, 0.0);
    let x = GridAxis::linspace(StringParameter::Speed, 0.0, 0.99, 200).expect("valid axis");
    let y =
        GridAxis::linspace(StringParameter::ControlParameter, 0.0, 0.25, 200).expect("valid axis");
    let mut g = c.benchmark_group("moving_stability_map/map");
    g.sample_size(10);
    g.warm_up_time(Duration::from_secs(1));
    g.measurement_time(Duration::from_secs(40));
    g.throughput(Throughput::Elements(40_000));
    g.bench_function("200x200", |b| {
        b.iter(|| {
            let map = string_stability_map(&m, &base, &x, &y, &StabilityMapParams::default())
                .expect("valid map");
            black_box(map.points.len())
        })
    });
    g.finish();
}

criterion_group!(benches, point, map);
criterion_main!(benches);
