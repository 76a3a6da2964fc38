//! Stability maps of the rotating annular plate with a stationary friction pad (Hetzler 2009
//! §4.1 with the pad of `model::moving::plate`): harmonics n = 0 … 5 (six Fourier modes, 11
//! angular functions) × 20 radial Hermite elements reduced to 2 radial modes per angular function
//! (22 coordinates, companion order 44). The figure: a 200 × 200 map over (Ω, μ) within
//! 10 s on the 2-core machine, bit-identical for any thread count (`moving_plate_pad`, unit tests).
//!
//! - `point/*`: one point's eigenvalues (faer, the reference);
//! - `map/200x200`: the whole (Ω, μ) map as `stability_map` runs it (all cores; rank-one lines
//!   along μ).
//!
//! `cargo bench --bench rotating_plate_map`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};

use contactlab::model::moving::linearized::LinearizedModel;
use contactlab::model::moving::plate::angular::AngularBasis;
use contactlab::model::moving::plate::{
    PadData, PlateData, PlateDiscretization, PlateParameter, PlateProperties, RotatingPlateModel,
};
use contactlab::model::moving::stability_map::{stability_map, GridAxis, StabilityMapParams};
use contactlab::solve::quadratic_eigen::QuadraticEigenParams;

fn model() -> RotatingPlateModel {
    RotatingPlateModel::new(
        PlateProperties {
            thickness: 0.1,
            ..Default::default()
        },
        PlateDiscretization {
            angular: AngularBasis::Periodic { harmonics: 5 },
            elements: 20,
            radial_modes: Some(2),
        },
    )
    .expect("valid plate")
}

fn data(omega: f64, mu: f64) -> PlateData {
    PlateData {
        angular_speed: omega,
        damping: 0.05,
        pad: Some(PadData {
            radius: 0.95,
            angle: 0.0,
            stiffness: 50.0,
            friction: mu,
        }),
    }
}

fn point(c: &mut Criterion) {
    let m = model();
    let s = m.system(&data(1.5, 0.2)).expect("valid data");
    let mut g = c.benchmark_group("rotating_plate_map/point");
    g.bench_function("faer", |b| {
        b.iter(|| {
            let e = s.eigen(QuadraticEigenParams::default()).expect("solves");
            black_box(e.eigenvalues.len())
        })
    });
    g.finish();
}

fn map(c: &mut Criterion) {
    let m = model();
    let base = data(0.0, 0.0);
    let x = GridAxis::linspace(PlateParameter::AngularSpeed, 0.0, 3.0, 200).expect("valid axis");
    let y = GridAxis::linspace(PlateParameter::Friction, 0.0, 0.5, 200).expect("valid axis");
    let mut g = c.benchmark_group("rotating_plate_map/map");
    g.sample_size(10);
    g.warm_up_time(Duration::from_secs(1));
    g.measurement_time(Duration::from_secs(60));
    g.throughput(Throughput::Elements(40_000));
    g.bench_function("200x200", |b| {
        b.iter(|| {
            let map = stability_map(&m, &base, &x, &y, &StabilityMapParams::default())
                .expect("valid map");
            black_box(map.points.len())
        })
    });
    g.finish();
}

criterion_group!(benches, point, map);
criterion_main!(benches);
