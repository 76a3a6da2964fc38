//! Stability analysis of moving continua: the disc particle's friction damping, verdicts, maps
//! that do not depend on the thread count, eigenvectors with small backward errors, time
//! integration against eigenvalues, and the typed errors of scenes.

use contactlab::error::Error;
use contactlab::model::moving::disc::DiscParticle;
use contactlab::model::moving::stability::{assess, Verdict, VerdictParams};
use contactlab::model::moving::stability_map::{
    string_stability_map, GridAxis, StabilityMapParams,
};
use contactlab::model::moving::string_data::{
    ContactModel, MovingStringData, OscillatorData, StringParameter,
};
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};
use contactlab::scene::moving::MovingScene;
use contactlab::solve::linear_ode::{integrate_second_order, LinearOdeParams};
use contactlab::solve::quadratic_eigen::QuadraticEigenParams;

fn thick(speed: f64, control: f64) -> MovingStringData {
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

#[test]
fn disc_damping_is_recovered_from_the_eigenvalues_across_omega() {
    for omega in [0.1, 1.0, 10.0, 1000.0] {
        let p = DiscParticle {
            mass: 1.0,
            stiffness: 100.0,
            normal_force: 10.0,
            friction_coefficient: 0.3,
            radius: 0.2,
            angular_speed: omega,
        };
        let ev = p
            .system()
            .unwrap()
            .eigen(QuadraticEigenParams::default())
            .unwrap()
            .eigenvalues;
        let rec = -p.mass * ev.iter().map(|l| l.re).sum::<f64>();
        assert!(
            (rec - 15.0 / omega).abs() < 1e-12 * (15.0 / omega).max(1.0),
            "Ω = {omega}"
        );
    }
}

#[test]
fn eigenvectors_have_round_off_backward_errors() {
    let m = MovingStringModel::new(StringDiscretization::Sine { modes: 10 }, Default::default())
        .unwrap();
    let r = m
        .system(&thick(0.5, 0.3))
        .unwrap()
        .eigen(QuadraticEigenParams {
            compute_eigenvectors: true,
            ..Default::default()
        })
        .unwrap();
    assert_eq!(r.eigenvectors.as_ref().unwrap().ncols(), 22);
    assert!(
        r.stats.max_backward_error < 1e-13,
        "{}",
        r.stats.max_backward_error
    );
}

#[test]
fn maps_do_not_depend_on_the_thread_count_or_the_kernel_verdicts() {
    let m = MovingStringModel::new(StringDiscretization::Sine { modes: 8 }, Default::default())
        .unwrap();
    let x = GridAxis::linspace(StringParameter::Speed, 0.0, 0.95, 9).unwrap();
    let y = GridAxis::linspace(StringParameter::ControlParameter, 0.0, 0.3, 8).unwrap();
    let run = |threads: usize, faer: bool| {
        let mut p = StabilityMapParams {
            threads,
            ..Default::default()
        };
        if faer {
            p.eigen = QuadraticEigenParams::default();
        }
        string_stability_map(&m, &thick(0.0, 0.0), &x, &y, &p).unwrap()
    };
    let (a, b, f) = (run(1, false), run(2, false), run(2, true));
    assert_eq!(a.points, b.points);
    for (p, q) in a.points.iter().zip(&f.points) {
        assert_eq!(p.verdict, q.verdict);
    }
    assert!(a.count(Verdict::Stable) > 0 && a.count(Verdict::Flutter) > 0);
}

#[test]
fn rk4_growth_matches_max_re_lambda_of_a_fluttering_string() {
    let m = MovingStringModel::new(StringDiscretization::Sine { modes: 6 }, Default::default())
        .unwrap();
    let s = m.system(&thick(0.5, 0.5)).unwrap();
    let ev = s
        .eigen(QuadraticEigenParams::default())
        .unwrap()
        .eigenvalues;
    let a = assess(&ev, &VerdictParams::default());
    assert_eq!(a.verdict, Verdict::Flutter);
    let k = 0.2 / a.spectral_scale;
    let t = integrate_second_order(
        s.mass.as_ref(),
        s.velocity_matrix().as_ref(),
        s.stiffness_matrix().as_ref(),
        &[1.0, 0.5, -0.3, 0.2, 0.1, -0.4, 0.3],
        &[0.0; 7],
        &LinearOdeParams {
            step: k,
            steps: (150.0 / k) as usize,
            record_every: 100,
        },
    )
    .unwrap();
    let n = t.times.len();
    let rate = (t.log_norms[n - 1] - t.log_norms[n / 2]) / (t.times[n - 1] - t.times[n / 2]);
    assert!(
        (rate - a.max_real_part).abs() < 0.05 * a.max_real_part + 2e-3,
        "{rate} vs {}",
        a.max_real_part
    );
}

#[test]
fn scene_errors_name_the_field() {
    let base = r#"
model = "moving_string"
[string]
speed = 0.3
[discretization]
basis = "sine"
modes = 4
"#;
    assert!(matches!(
        MovingScene::from_toml_str(base, "s"),
        Ok(MovingScene::String(_))
    ));
    let bad = base.replace("speed = 0.3", "speed = 0.3\nsped = 1");
    let e = MovingScene::from_toml_str(&bad, "s").unwrap_err();
    assert!(matches!(e, Error::Scene { .. }) && e.to_string().contains("sped"));
    let bad = base.replace("basis = \"sine\"", "basis = \"chebyshev\"");
    let e = MovingScene::from_toml_str(&bad, "s").unwrap_err();
    assert!(matches!(e, Error::Input(ref i) if i.field == "discretization.basis"));
    let bad =
        format!("{base}[[sweep]]\nparameter = \"position\"\nfrom = 0.1\nto = 0.9\npoints = 5\n");
    let e = MovingScene::from_toml_str(&bad, "s").unwrap_err();
    assert!(e.to_string().contains("sweep[0].from/to"), "{e}");
}
