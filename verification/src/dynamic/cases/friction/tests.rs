//! The case format (unknown keys, a missing depth for μ1, a gate on an unknown error, a loaded
//! family with the limited penetration are typed errors naming the field), and small runs: the
//! sliding block stops at the predicted step with the predicted errors, the loaded block passes
//! its step check, and a friction law other than the solver's fails that check.
use std::path::Path;

use super::*;
use crate::dynamic::cases::friction::format::FamilySpec;
use crate::exact::coulomb_friction::FrictionLaw;

const MINIMAL: &str = r#"
id = "t"
title = "t"
kind = "dynamic_friction"
explanation = "e"

[[family]]
name = "mu1"
law = "growing"
mu0 = 0.4
depth = 0.013333333333333334
treatment = "energy_consistent"

[slide]
length = 1.0
height = 0.25
divisions = [2, 1]
density = 1.0
young = 2e7
poisson = 0.0
stiffness = 50.0
penetration = 0.01
speed = 1.0
duration = 1.5
steps = [32, 64, 128]
tolerance = 1e-10

[loaded]
length = 1.0
height = 0.25
divisions = [8, 2]
density = 1.0
young = 1e4
poisson = 0.3
stiffness = 50.0
pressure = 0.5
speed = 1.0
duration = 0.6
steps = [40]

[[gate]]
family = "mu1"
error = "stop_distance_error"
expected_rate = 2.0
tolerance = 0.05
ci_width = 0.05
"#;

fn load(text: &str) -> Result<FrictionCase, CaseError> {
    let case = Case::from_text(Path::new("t.toml"), text)?;
    FrictionCase::from_case(&case)
}

#[test]
fn minimal_case_parses_and_bad_input_is_a_typed_error() {
    assert!(load(MINIMAL).is_ok());
    let e = load(&MINIMAL.replace(
        "speed = 1.0\nduration = 1.5",
        "speed = 1.0\ncolour = 1\nduration = 1.5",
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("colour"), "{e}");
    let e = load(&MINIMAL.replace("depth = 0.013333333333333334\n", ""))
        .unwrap_err()
        .to_string();
    assert!(e.contains("family[0].depth"), "{e}");
    let e = load(&MINIMAL.replace("error = \"stop_distance_error\"", "error = \"nope\""))
        .unwrap_err()
        .to_string();
    assert!(e.contains("gate[0].error"), "{e}");
    let e = load(&MINIMAL.replace(
        "treatment = \"energy_consistent\"",
        "treatment = \"limited_penetration\"\nbase = 0.05",
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("loaded.families"), "{e}");
    let e = load(&MINIMAL.replace("duration = 1.5", "duration = 0.9"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("slide.duration"), "{e}");
}

#[test]
fn sliding_block_stops_at_the_predicted_step_with_the_predicted_errors() {
    // with T = 1.5 t* and N = 32, 64 the phase of t*/k is 1/3 or 2/3: errors k/3 and a k²/18
    let file = load(MINIMAL).unwrap();
    let spec = file.slide.as_ref().unwrap();
    let f = &file.families[0];
    let b = spec.block(f);
    for n in [32, 64] {
        let r = slide::run(spec, f, n).unwrap();
        assert_eq!(r.errors["stop_step_offset"], 0.0, "N = {n}");
        let k = r.k;
        let t_err = r.errors["stop_time_error"] * b.stop_time();
        assert!(
            (t_err - k / 3.0).abs() < 1e-9 * k,
            "N = {n}: {t_err} vs {}",
            k / 3.0
        );
        let s_err = r.errors["stop_distance_error"] * b.stop_distance();
        let predicted = b.deceleration() * k * k / 18.0;
        assert!(
            (s_err - predicted).abs() < 0.01 * predicted,
            "N = {n}: {s_err} vs {predicted}"
        );
        assert!(r.errors["slip_after_stop"] <= 2.0 * b.shear_lag());
    }
}

#[test]
fn loaded_block_satisfies_its_step_equations_and_a_wrong_law_does_not() {
    let file = load(MINIMAL).unwrap();
    let spec = file.loaded.as_ref().unwrap();
    let f = &file.families[0];
    let r = loaded::run(spec, f, 40).unwrap();
    assert!(r.max_residual <= 1.0, "{r:?}");
    assert!(r.all_slide_until >= 0.5 * r.rigid_stop_time, "{r:?}");
    // the penetration crosses the layer depth g: both branches of μ1 are exercised
    let g = f.depth.unwrap();
    assert!(
        r.penetration_range[0] < g && r.penetration_range[1] > 0.5 * g,
        "{r:?}"
    );
    // the same run checked against μ = μ0 (the solver keeps μ1): the residual is the friction's
    // size, far above the tolerance
    let wrong = FamilySpec {
        law: FrictionLaw::Constant,
        depth: None,
        ..f.clone()
    };
    let mut spec_wrong = spec.clone();
    spec_wrong.families = None;
    let r_wrong = loaded::run_with_reference(&spec_wrong, f, &wrong, 40).unwrap();
    assert!(r_wrong.max_residual > 1e3, "{r_wrong:?}");
}
