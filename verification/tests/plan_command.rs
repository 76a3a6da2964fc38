//! `verify plan` end to end (`registry::plan_scene`): a rod scene planned and run with the
//! deterministic work measure, and the typed refusals of what it cannot plan.

use std::path::{Path, PathBuf};

use contactlab_verify::core::plan::{CostMeasure, PlanRequest};
use contactlab_verify::registry::plan_scene;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn request(target: f64, schemes: Option<Vec<String>>) -> PlanRequest {
    PlanRequest {
        target,
        functional: "paper_E".into(),
        schemes,
        cost: CostMeasure::Work,
        rounds: 1,
    }
}

#[test]
fn a_rod_plan_meets_its_target_and_writes_its_files() {
    let out = std::env::temp_dir().join(format!("plan-command-{}", std::process::id()));
    let md = plan_scene(
        &root().join("examples/scenes/rod_paper_p0_6.toml"),
        &request(2e-2, None),
        &out,
    )
    .unwrap();
    assert!(md.contains("chosen: **"), "{md}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    let ratio = json["executed"]["error_ratio"].as_f64().unwrap();
    assert!((0.5..=1.0).contains(&ratio), "achieved / target = {ratio}");
    assert!(out.join("plan.svg").exists() && out.join("plan.md").exists());
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn an_unknown_scheme_and_an_unplanned_model_are_typed_errors() {
    let out = std::env::temp_dir().join(format!("plan-command-err-{}", std::process::id()));
    let e = plan_scene(
        &root().join("examples/scenes/rod_paper_p0_6.toml"),
        &request(1e-2, Some(vec!["leapfrog".into()])),
        &out,
    )
    .unwrap_err();
    assert!(e.contains("leapfrog") && e.contains("explicit"), "{e}");
    let e = plan_scene(
        &root().join("examples/scenes/plane_paper_test_2d.toml"),
        &request(1e-2, None),
        &out,
    )
    .unwrap_err();
    assert!(e.contains("does not plan model `plane`"), "{e}");
    let e = plan_scene(
        &root().join("examples/scenes/rod_paper_p0_6.toml"),
        &request(-1.0, None),
        &out,
    )
    .unwrap_err();
    assert!(e.contains("--target"), "{e}");
}
