//! The oscillator in the bushing (Hetzler 2009 §4.2.1–4.2.2): ideal contact, the penalty bushing
//! with its massless coordinate, and the thick string's friction. The penalty bushing condensed
//! as springs in series equals the DAE's finite eigenvalues (QZ) and the generic Schur
//! complement; its eigenvalues approach ideal contact like 1/k̄_p.

use contactlab::model::moving::c64;
use contactlab::model::moving::properties::{skew_defect, symmetry_defect};
use contactlab::model::moving::string_data::{
    ContactModel, MovingStringData, OscillatorData, StringParameter,
};
use contactlab::model::moving::string_model::{
    MovingStringModel, MovingStringParams, PenaltyCondensation, StringDiscretization,
};
use contactlab::solve::quadratic_eigen::{solve_generalized_quadratic_eigen, QuadraticEigenParams};

fn data(contact: ContactModel, friction: f64) -> MovingStringData {
    MovingStringData {
        speed: 0.4,
        damping: 0.0,
        oscillator: Some(OscillatorData {
            stiffness: 2.0,
            mass: 0.5,
            position: 0.3,
            contact,
            friction,
            patch_width: 0.0,
        }),
    }
}

fn upper(ev: &[c64]) -> Vec<c64> {
    let mut v: Vec<c64> = ev.iter().copied().filter(|l| l.im > 0.0).collect();
    v.sort_by(|a, b| a.im.total_cmp(&b.im));
    v
}

fn model(c: PenaltyCondensation) -> MovingStringModel {
    MovingStringModel::new(
        StringDiscretization::Sine { modes: 12 },
        MovingStringParams { condensation: c },
    )
    .unwrap()
}

fn eig(m: &MovingStringModel, d: &MovingStringData) -> Vec<c64> {
    upper(
        &m.system(d)
            .unwrap()
            .eigen(QuadraticEigenParams::default())
            .unwrap()
            .eigenvalues,
    )
}

#[test]
fn penalty_eigenvalues_approach_ideal_contact_like_one_over_kp() {
    let m = model(PenaltyCondensation::SeriesSprings);
    let ideal = eig(&m, &data(ContactModel::Ideal, 0.0));
    let err = |kp: f64| {
        let p = eig(&m, &data(ContactModel::Penalty { stiffness: kp }, 0.0));
        (0..4)
            .map(|k| (p[k] - ideal[k]).norm() / ideal[k].norm())
            .fold(0.0, f64::max)
    };
    let ratio = err(1e3) / err(1e4);
    assert!((ratio - 10.0).abs() < 0.1, "{ratio}");
}

#[test]
fn dae_qz_schur_and_series_springs_agree() {
    for friction in [0.0, 0.1] {
        let d = data(ContactModel::Penalty { stiffness: 30.0 }, friction);
        let series = eig(&model(PenaltyCondensation::SeriesSprings), &d);
        let schur = eig(&model(PenaltyCondensation::Schur), &d);
        let full = model(PenaltyCondensation::SeriesSprings)
            .system_with_bushing(&d)
            .unwrap();
        assert!(full.mass[(13, 13)] == 0.0 && full.coordinates[13] == "y_c");
        let qz = solve_generalized_quadratic_eigen(
            full.mass.as_ref(),
            full.velocity_matrix().as_ref(),
            full.stiffness_matrix().as_ref(),
            1e-10,
        )
        .unwrap();
        assert_eq!(qz.stats.infinite_eigenvalues, 2);
        let qz = upper(&qz.eigenvalues);
        for k in 0..6 {
            assert!((series[k] - schur[k]).norm() < 1e-11 * series[k].norm());
            assert!((series[k] - qz[k]).norm() < 1e-10 * series[k].norm());
        }
    }
}

#[test]
fn thick_string_friction_splits_into_symmetric_and_circulatory_parts() {
    let m = model(PenaltyCondensation::SeriesSprings);
    let s = m.system(&data(ContactModel::Ideal, 0.2)).unwrap();
    assert!(symmetry_defect(s.stiffness.as_ref()) < 1e-15);
    assert!((skew_defect(s.circulatory.as_ref())) < 1e-15);
    assert!(s.circulatory.norm_max() > 0.0);
    // p = μ c̄ h̄ multiplies N: ‖N‖ is linear in the friction product.
    let s2 = m.system(&data(ContactModel::Ideal, 0.4)).unwrap();
    assert!((s2.circulatory.norm_l2() / s.circulatory.norm_l2() - 2.0).abs() < 1e-13);
}

#[test]
fn nominal_penalty_parameter_grows_with_kp_but_the_condensed_one_does_not() {
    let m = model(PenaltyCondensation::SeriesSprings);
    let full = |kp: f64| {
        m.system_with_bushing(&data(ContactModel::Penalty { stiffness: kp }, 0.1))
            .unwrap()
            .circulatory
            .norm_l2()
    };
    assert!((full(1e4) / full(1e2) - 100.0).abs() < 1e-9);
    let cond = |kp: f64| {
        m.system(&data(ContactModel::Penalty { stiffness: kp }, 0.1))
            .unwrap()
            .circulatory
            .norm_l2()
    };
    let ideal = m
        .system(&data(ContactModel::Ideal, 0.1))
        .unwrap()
        .circulatory
        .norm_l2();
    assert!((cond(1e6) - ideal).abs() < 1e-5 * ideal);
}

#[test]
fn control_parameter_sets_the_friction_product_per_contact() {
    let mut d = data(ContactModel::Penalty { stiffness: 40.0 }, 0.0);
    StringParameter::ControlParameter.set(&mut d, 2.0).unwrap();
    assert!((d.oscillator.unwrap().friction - 0.05).abs() < 1e-15);
    assert!((d.control_parameter() - 2.0).abs() < 1e-15);
}

#[test]
fn bad_oscillator_values_name_their_fields() {
    let m = model(PenaltyCondensation::SeriesSprings);
    let mut d = data(ContactModel::Ideal, 0.0);
    d.oscillator.as_mut().unwrap().mass = 0.0;
    assert_eq!(m.system(&d).unwrap_err().field, "oscillator.mass");
    let d = data(ContactModel::Ideal, -0.1);
    assert_eq!(m.system(&d).unwrap_err().field, "oscillator.friction");
    let e = m
        .system_with_bushing(&MovingStringData::string(0.1, 0.0))
        .unwrap_err();
    assert_eq!(e.field, "oscillator");
}
