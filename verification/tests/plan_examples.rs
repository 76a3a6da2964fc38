//! `verify plan` on every example scene (docs/planner.md): each scene whose mesh the planner
//! can refine and which has a functional is planned from its own resolution — a decision (a
//! choice run and measured, a pilot that meets the target, or a typed refusal with its reason)
//! written to plan.json, plan.md and plan.svg; the others are refused with an error that says
//! why (a Gmsh mesh, an eigenvalue problem). A new example scene is covered without editing this
//! test.

use std::path::{Path, PathBuf};

use contactlab_verify::plan::{CostMeasure, PlanRequest};
use contactlab_verify::registry::plan_scene;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// What planning `scene` must give.
enum Expect {
    Plan,
    Refused(&'static str),
}

fn expectation(text: &str) -> Expect {
    let table: toml::Table = toml::from_str(text).unwrap();
    let model = table.get("model").and_then(|m| m.as_str()).unwrap_or("");
    if text.contains("shape = \"gmsh\"") {
        Expect::Refused("gmsh")
    } else if !["rod", "plane", "dynamic"].contains(&model) {
        Expect::Refused("eigenvalue problem")
    } else {
        Expect::Plan
    }
}

#[test]
fn every_example_scene_is_planned_or_refused_with_its_reason() {
    let dir = root().join("examples/scenes");
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    scenes.sort();
    let out_root = std::env::temp_dir().join(format!("plan-examples-{}", std::process::id()));
    let mut planned = Vec::new();
    for scene in &scenes {
        let name = scene.file_stem().unwrap().to_string_lossy().to_string();
        let text = std::fs::read_to_string(scene).unwrap();
        // the block comes to rest on the foundation: no rebound; its slide instead
        let functional = match name.as_str() {
            "dynamic_block_drop" => "max_displacement",
            _ => "",
        };
        let request = PlanRequest {
            target: 1e-2,
            functional: functional.into(),
            schemes: None,
            cost: CostMeasure::Work,
            rounds: 1,
        };
        let out = out_root.join(&name);
        let result = plan_scene(scene, &request, None, &out);
        match (expectation(&text), result) {
            (Expect::Plan, Ok(md)) => {
                assert!(md.contains("## Decision"), "{name}: {md}");
                let json: serde_json::Value =
                    serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap())
                        .unwrap();
                let kind = json["decision"]["kind"].as_str().unwrap().to_string();
                // a run that was executed carries its measured error and cost, finite
                if let Some(x) = json["executed"].as_object() {
                    for key in ["achieved_error", "measured_cost"] {
                        assert!(
                            x[key].as_f64().is_some_and(f64::is_finite),
                            "{name}: {key} = {}",
                            x[key]
                        );
                    }
                }
                assert!(out.join("plan.svg").exists(), "{name}");
                planned.push(format!("{name}: {kind}"));
            }
            (Expect::Refused(why), Err(e)) => {
                assert!(
                    e.contains(why),
                    "{name}: expected a refusal naming {why}: {e}"
                )
            }
            (Expect::Plan, Err(e)) => panic!("{name}: the planner failed: {e}"),
            (Expect::Refused(why), Ok(md)) => {
                panic!("{name}: expected a refusal ({why}), got a plan: {md}")
            }
        }
    }
    let _ = std::fs::remove_dir_all(&out_root);
    // every family with generated shapes is among the planned scenes
    for prefix in ["rod_", "plane_", "dynamic_", "multibody_"] {
        assert!(
            planned.iter().any(|p| p.starts_with(prefix)),
            "no {prefix} scene planned: {planned:?}"
        );
    }
}
