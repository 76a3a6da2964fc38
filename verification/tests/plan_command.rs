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
        None,
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
        None,
        &out,
    )
    .unwrap_err();
    assert!(e.contains("leapfrog") && e.contains("explicit"), "{e}");
    // an eigenvalue problem has no mesh–step trade
    let e = plan_scene(
        &root().join("examples/scenes/moving_thick_string.toml"),
        &request(1e-2, None),
        None,
        &out,
    )
    .unwrap_err();
    assert!(e.contains("does not plan model `moving_string`"), "{e}");
    // a Gmsh mesh is not refinable by the planner
    let e = plan_scene(
        &root().join("examples/scenes/plane_gmsh_notched_block.toml"),
        &PlanRequest {
            functional: String::new(),
            ..request(1e-2, None)
        },
        None,
        &out,
    )
    .unwrap_err();
    assert!(e.contains("gmsh") && e.contains("geometry.shape"), "{e}");
    let e = plan_scene(
        &root().join("examples/scenes/rod_paper_p0_6.toml"),
        &request(-1.0, None),
        None,
        &out,
    )
    .unwrap_err();
    assert!(e.contains("--target"), "{e}");
}

#[test]
fn a_plane_scene_without_an_exact_solution_is_planned_by_self_convergence() {
    // Test 2D from its own resolution (24 × 24, 100 steps): the largest displacement's pilots
    // give p ≈ 1.23 against the expected 2 — refused as pre-asymptotic, nothing run; the contact
    // force at T is fixed by global equilibrium (the load, 180) for the explicit and implicit
    // schemes — their pilots agree to round-off, and a pilot meets any target
    let scene = root().join("examples/scenes/plane_paper_test_2d.toml");
    let out = std::env::temp_dir().join(format!("plan-command-plane-{}", std::process::id()));
    let ask = |functional: &str, target: f64| PlanRequest {
        functional: functional.into(),
        ..request(target, None)
    };
    let md = plan_scene(&scene, &ask("max_displacement", 1e-2), None, &out).unwrap();
    assert!(
        md.contains("pre-asymptotic") && md.contains("expected 2"),
        "{md}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    assert_eq!(json["decision"]["kind"], "pre_asymptotic");
    assert!(json["executed"].is_null());
    let md = plan_scene(&scene, &ask("", 1e-6), None, &out).unwrap();
    assert!(
        md.contains("Plan: contact_force") && md.contains("a pilot already meets"),
        "{md}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    let value = json["executed"]["value"].as_f64().unwrap();
    assert!((value - 180.0).abs() < 1e-9, "contact force {value}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_rod_scene_without_an_exact_table_plans_its_end_displacement() {
    // the p0 = 6 rod without [exact]: u_h(L, T) by self-convergence (the default functional)
    let text = std::fs::read_to_string(root().join("examples/scenes/rod_paper_p0_6.toml")).unwrap();
    let mut table: toml::Table = toml::from_str(&text).unwrap();
    table.remove("exact");
    let dir = std::env::temp_dir().join(format!("plan-command-rod-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("rod.toml");
    std::fs::write(&scene, toml::to_string(&table).unwrap()).unwrap();
    let md = plan_scene(
        &scene,
        &PlanRequest {
            functional: String::new(),
            ..request(1e-4, None)
        },
        None,
        &dir.join("out"),
    )
    .unwrap();
    assert!(
        md.contains("Plan: end_displacement") && md.contains("self-convergence"),
        "{md}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/plan.json")).unwrap()).unwrap();
    let estimated = json["executed"]["achieved_error"].as_f64().unwrap();
    assert!(estimated <= 1e-4, "estimated error {estimated}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_readme_plan_example_is_what_its_command_writes() {
    // README: `verify plan examples/scenes/rod_paper_p0_6.toml --target 1e-2 --cost work
    // --rounds 3 --out reports/plan_example`: with the work measure the plan is deterministic,
    // so the committed plan.md (whose tables the README shows) is what the command writes now
    let out = std::env::temp_dir().join(format!("plan-command-example-{}", std::process::id()));
    let md = plan_scene(
        &root().join("examples/scenes/rod_paper_p0_6.toml"),
        &PlanRequest {
            rounds: 3,
            ..request(1e-2, None)
        },
        None,
        &out,
    )
    .unwrap();
    let committed = std::fs::read_to_string(root().join("reports/plan_example/plan.md")).unwrap();
    assert!(
        md == committed,
        "reports/plan_example/plan.md differs from what the README's command writes now: run it \
         again (and `verify readme`)"
    );
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_dynamic_scene_is_planned_by_self_convergence_and_its_failures_are_reasons() {
    let out = std::env::temp_dir().join(format!("plan-command-dyn-{}", std::process::id()));
    // the Signorini bar (held at one end): the end displacement by default; the contact at x = 0
    // is exact (Signorini), the Newmark rule is allowed with it
    let md = plan_scene(
        &root().join("examples/scenes/dynamic_signorini_bar.toml"),
        &PlanRequest {
            functional: String::new(),
            ..request(1e-2, None)
        },
        None,
        &out,
    )
    .unwrap();
    assert!(
        md.contains("Plan: end_displacement")
            && md.contains("| newmark |")
            && md.contains("| midpoint |"),
        "{md}"
    );
    // a rebound is defined once the body has left: the ball stopped at 5 ms, halfway through
    // its contact, has none, and every scheme's pilots fail with that reason
    let text =
        std::fs::read_to_string(root().join("examples/scenes/dynamic_ball_impact.toml")).unwrap();
    let mut table: toml::Table = toml::from_str(&text).unwrap();
    table["time"]["final_time"] = toml::Value::Float(0.005);
    table["time"]["steps"] = toml::Value::Integer(160);
    table["body"]["rings"] = toml::Value::Integer(8);
    std::fs::create_dir_all(&out).unwrap();
    let scene = out.join("ball_in_contact.toml");
    std::fs::write(&scene, toml::to_string(&table).unwrap()).unwrap();
    let md = plan_scene(
        &scene,
        &PlanRequest {
            functional: String::new(),
            ..request(1e-2, None)
        },
        None,
        &out.join("plan"),
    )
    .unwrap();
    assert!(
        md.contains("every scheme had a pilot that failed") && md.contains("still in contact at T"),
        "{md}"
    );
    // a functional the body does not have is named with the ones it has
    let e = plan_scene(
        &root().join("examples/scenes/dynamic_spinning_ring.toml"),
        &PlanRequest {
            functional: "rebound_velocity_y".into(),
            ..request(1e-2, None)
        },
        None,
        &out,
    )
    .unwrap_err();
    assert!(
        e.contains("max_displacement") && !e.contains("expected one of rebound"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_multibody_scene_refines_every_body_and_plans_its_bodies_velocities() {
    // the two rings from pilots at radial = 1, 2, 4 (around = 18, 36, 72 for both rings):
    // the left ring's rebound velocity by default, every scheme modelled
    let out = std::env::temp_dir().join(format!("plan-command-mb-{}", std::process::id()));
    let md = plan_scene(
        &root().join("examples/scenes/multibody_rings.toml"),
        &PlanRequest {
            functional: String::new(),
            ..request(0.05, None)
        },
        Some((4, 100)),
        &out,
    )
    .unwrap();
    assert!(md.contains("Plan: velocity_x.left"), "{md}");
    for scheme in ["newmark", "midpoint", "energy_momentum"] {
        assert!(md.contains(&format!("| {scheme} | F = ")), "{scheme}: {md}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    let pilots = json["pilots"].as_array().unwrap();
    assert_eq!(pilots.len(), 27);
    // the work counts both rings: 2 × (radial + 1) × around nodes × N at M = 4, N = 100
    let finest = pilots
        .iter()
        .find(|p| p["elements"] == 4 && p["steps"] == 100)
        .unwrap();
    assert_eq!(finest["cost"].as_f64(), Some(2.0 * 5.0 * 72.0 * 100.0));
    let e = plan_scene(
        &root().join("examples/scenes/multibody_rings.toml"),
        &PlanRequest {
            functional: "velocity_x.middle".into(),
            ..request(0.05, None)
        },
        None,
        &out,
    )
    .unwrap_err();
    assert!(
        e.contains("velocity_x.left") && e.contains("velocity_y.right"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&out);
}
