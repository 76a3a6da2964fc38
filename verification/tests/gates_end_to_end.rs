//! Gates end to end: the paper's p0 = 6 rod with its true expected rate passes; the same case with
//! a deliberately wrong expected rate fails — and a failing case makes the report say so; a gate
//! that picks its levels by hand is refused. Sweeps run on 1 and 2 threads give bit-identical
//! errors.

use contactlab_verify::core::case::Case;
use contactlab_verify::core::context::RunContext;
use contactlab_verify::core::report::metadata::Metadata;
use contactlab_verify::registry;

const CASE: &str = r#"
id = "e2e"
title = "end to end"
kind = "rod_convergence"
explanation = "test"
[scene]
model = "rod"
[scene.rod]
length = 1.0
final_time = 0.5
viscosity = 1.0
elasticity = 1.0
load = 10.0
[scene.foundation]
law = "lubricated"
beta = 1.0
p0 = 6.0
[exact]
solution = "rod_constant_data"
[[sweep]]
name = "diagonal"
elements = [20, 40, 80, 160]
steps = [10, 20, 40, 80]
[[gate]]
sweep = "diagonal"
error = "paper_E"
against = "h_plus_k"
expected_rate = EXPECTED
tolerance = 0.05
ci_width = 0.05
"#;

fn case(expected: f64) -> Case {
    let text = CASE.replace("EXPECTED", &expected.to_string());
    Case::from_text(std::path::Path::new("e2e.toml"), &text).unwrap()
}

fn ctx(tag: &str) -> RunContext {
    RunContext {
        out_dir: std::env::temp_dir().join(format!("contactlab-e2e-{tag}-{}", std::process::id())),
        metadata: Metadata::collect("test"),
        progress: false,
        bars: None,
    }
}

#[test]
fn true_expected_rate_passes() {
    let r = registry::run(&case(1.0), &ctx("pass"));
    assert!(r.passed, "{:?}", r.gates);
}

#[test]
fn deliberately_wrong_expected_rate_fails() {
    let r = registry::run(&case(2.0), &ctx("rate"));
    assert!(!r.passed);
    assert!(!r.gates[0].checks[0].passed);
}

#[test]
fn levels_picked_by_hand_are_refused() {
    let text = CASE
        .replace("EXPECTED", "1.0")
        .replace("ci_width = 0.05", "ci_width = 0.05\nfinest_levels = 3");
    let c = Case::from_text(std::path::Path::new("e2e.toml"), &text).unwrap();
    let e = registry::check(&c).unwrap_err().to_string();
    assert!(e.contains("finest_levels"), "{e}");
}

#[test]
fn sweeps_are_bit_identical_on_one_and_two_threads() {
    let c = case(1.0);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let a = one.install(|| registry::run(&c, &ctx("t1")));
    let b = two.install(|| registry::run(&c, &ctx("t2")));
    for (la, lb) in a.sweeps[0].levels.iter().zip(&b.sweeps[0].levels) {
        for (k, v) in &la.errors {
            assert_eq!(v.to_bits(), lb.errors[k].to_bits(), "{k}");
        }
        assert_eq!(la.u_end.to_bits(), lb.u_end.to_bits());
    }
}
