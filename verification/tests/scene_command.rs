//! `verify scene`: a user's rod scene runs and writes its solution and, with an [exact] table, its
//! errors; a scene with a typo fails with a message that names the key.

use std::path::PathBuf;

use contactlab_verify::registry::run_scene;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

#[test]
fn paper_scene_writes_solution_and_errors() {
    let out = std::env::temp_dir().join(format!("contactlab-scene-{}", std::process::id()));
    let summary = run_scene(&root().join("examples/scenes/rod_paper_p0_6.toml"), &out).unwrap();
    assert!(summary.contains("paper E = 4.204803e-2"), "{summary}");
    let solution: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("solution.json")).unwrap()).unwrap();
    let end = solution["end_displacement"].as_array().unwrap();
    assert!((end[50].as_f64().unwrap() + 0.394993932862).abs() < 1e-11);
    let errors: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("errors.json")).unwrap()).unwrap();
    let e = errors["errors"]["paper_E"].as_f64().unwrap();
    assert!(((e - 4.20480289895e-2) / 4.20480289895e-2).abs() < 1e-10);
    assert!(out.join("histories.svg").exists() && out.join("snapshots.svg").exists());
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn every_example_scene_runs() {
    let dir = root().join("examples/scenes");
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let out = std::env::temp_dir().join(format!(
            "contactlab-example-{}-{}",
            path.file_stem().unwrap().to_string_lossy(),
            std::process::id()
        ));
        run_scene(&path, &out).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        std::fs::remove_dir_all(&out).ok();
    }
}

#[test]
fn misspelt_key_is_named_in_the_error() {
    let dir = std::env::temp_dir().join(format!("contactlab-bad-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(root().join("examples/scenes/rod_paper_p0_6.toml"))
        .unwrap()
        .replace("elasticity", "elastisity");
    let path = dir.join("bad.toml");
    std::fs::write(&path, text).unwrap();
    let err = run_scene(&path, &dir.join("out")).unwrap_err();
    assert!(err.contains("elastisity"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn unknown_model_is_rejected() {
    let dir = std::env::temp_dir().join(format!("contactlab-model-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("plate.toml");
    std::fs::write(&path, "model = \"plate\"\n").unwrap();
    let err = run_scene(&path, &dir.join("out")).unwrap_err();
    assert!(err.contains("model"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
