//! The axially moving string (Hetzler 2009 §4.2.1) with its exact eigenvalues
//! λ_n = (1 − v̄²)(−ᾱ/2 ± i sqrt(n²π² − ᾱ²/4)): the Ritz models (sine, P1, Hermite) approach
//! them, keep the structure M = Mᵀ, G = −Gᵀ, K = Kᵀ, and put every frequency at zero at v̄ = 1.

use contactlab::model::moving::c64;
use contactlab::model::moving::finite_element_basis::ElementKind;
use contactlab::model::moving::properties::{skew_defect, symmetry_defect};
use contactlab::model::moving::stability::{assess, Verdict, VerdictParams};
use contactlab::model::moving::string_data::MovingStringData;
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};
use contactlab::solve::quadratic_eigen::QuadraticEigenParams;

const PI: f64 = std::f64::consts::PI;

fn eigenvalues(disc: StringDiscretization, speed: f64, damping: f64) -> Vec<c64> {
    let m = MovingStringModel::new(disc, Default::default()).unwrap();
    m.system(&MovingStringData::string(speed, damping))
        .unwrap()
        .eigen(QuadraticEigenParams::default())
        .unwrap()
        .eigenvalues
}

fn frequencies(ev: &[c64]) -> Vec<f64> {
    let mut f: Vec<f64> = ev.iter().filter(|l| l.im > 0.0).map(|l| l.im).collect();
    f.sort_by(f64::total_cmp);
    f
}

#[test]
fn sine_basis_at_rest_is_exact() {
    let f = frequencies(&eigenvalues(
        StringDiscretization::Sine { modes: 12 },
        0.0,
        0.0,
    ));
    for (k, w) in f.iter().enumerate() {
        assert!((w - (k + 1) as f64 * PI).abs() < 1e-13 * w);
    }
}

#[test]
fn sine_n64_first_frequency_at_v_0_6_within_1e_6() {
    // measured 7.31e-7 (rate 3 in 1/N: see the case moving_string_exact)
    let f = frequencies(&eigenvalues(
        StringDiscretization::Sine { modes: 64 },
        0.6,
        0.0,
    ));
    let exact = PI * (1.0 - 0.36);
    assert!((f[0] - exact).abs() / exact < 1e-6);
}

#[test]
fn p1_and_hermite_approach_the_exact_frequency() {
    let exact = PI * (1.0 - 0.09);
    let p1 = frequencies(&eigenvalues(
        StringDiscretization::FiniteElements {
            kind: ElementKind::P1,
            elements: 64,
        },
        0.3,
        0.0,
    ));
    let he = frequencies(&eigenvalues(
        StringDiscretization::FiniteElements {
            kind: ElementKind::Hermite,
            elements: 16,
        },
        0.3,
        0.0,
    ));
    assert!((p1[0] - exact).abs() / exact < 2e-4); // measured 1.55e-4
    assert!((he[0] - exact).abs() / exact < 1e-8); // measured 3.6e-9
}

#[test]
fn damped_string_real_parts_are_minus_alpha_one_minus_v2_over_2() {
    let (v, a) = (0.6, 0.1);
    let ev = eigenvalues(StringDiscretization::Sine { modes: 48 }, v, a);
    let mut low: Vec<c64> = ev.into_iter().filter(|l| l.im > 0.0).collect();
    low.sort_by(|x, y| x.im.total_cmp(&y.im));
    for (k, l) in low.iter().take(3).enumerate() {
        let n = (k + 1) as f64;
        let exact = c64::new(-a / 2.0, (n * n * PI * PI - a * a / 4.0).sqrt()) * (1.0 - v * v);
        assert!((l - exact).norm() / exact.norm() < 1e-4, "{l} vs {exact}");
    }
}

#[test]
fn structure_of_the_matrices_for_every_basis() {
    for disc in [
        StringDiscretization::Sine { modes: 9 },
        StringDiscretization::FiniteElements {
            kind: ElementKind::P1,
            elements: 9,
        },
        StringDiscretization::FiniteElements {
            kind: ElementKind::Hermite,
            elements: 9,
        },
    ] {
        let s = MovingStringModel::new(disc, Default::default())
            .unwrap()
            .system(&MovingStringData::string(0.7, 0.2))
            .unwrap();
        assert!(symmetry_defect(s.mass.as_ref()) < 1e-15);
        assert!(symmetry_defect(s.stiffness.as_ref()) < 1e-15);
        assert!(skew_defect(s.gyroscopic.as_ref()) < 1e-14);
    }
}

#[test]
fn every_mode_reaches_zero_frequency_at_v_1_and_all_are_unstable_beyond() {
    let n = 10;
    let ev = eigenvalues(StringDiscretization::Sine { modes: n }, 1.0, 0.0);
    let rho = ev.iter().map(|l| l.norm()).fold(0.0, f64::max);
    assert!(ev.iter().filter(|l| l.norm() < 1e-12 * rho).count() >= n);
    let a = assess(
        &eigenvalues(StringDiscretization::Sine { modes: n }, 1.1, 0.1),
        &VerdictParams::default(),
    );
    assert_eq!(a.unstable_eigenvalues, n); // Kelvin–Tait–Chetaev
    let one = assess(
        &eigenvalues(StringDiscretization::Sine { modes: 1 }, 1.1, 0.1),
        &VerdictParams::default(),
    );
    assert_eq!(one.verdict, Verdict::Divergence);
}

#[test]
fn undamped_string_is_marginal_and_damped_string_is_stable() {
    let p = VerdictParams::default();
    let d = StringDiscretization::Sine { modes: 16 };
    assert_eq!(
        assess(&eigenvalues(d, 0.5, 0.0), &p).verdict,
        Verdict::Marginal
    );
    assert_eq!(
        assess(&eigenvalues(d, 0.5, 0.05), &p).verdict,
        Verdict::Stable
    );
}

#[test]
fn invalid_discretizations_and_data_are_typed_errors() {
    let e = MovingStringModel::new(StringDiscretization::Sine { modes: 0 }, Default::default())
        .unwrap_err();
    assert_eq!(e.field, "discretization.modes");
    let m = MovingStringModel::new(StringDiscretization::Sine { modes: 3 }, Default::default())
        .unwrap();
    let e = m.system(&MovingStringData::string(0.5, -1.0)).unwrap_err();
    assert_eq!(e.field, "string.damping");
    assert_eq!(e.value, "-1");
}
