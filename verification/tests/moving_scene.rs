//! `verify scene` with moving-continuum scenes: the example scenes run and write eigenvalues,
//! sweeps and maps as JSON; a scene with a typo fails naming the key.

use std::path::PathBuf;

use contactlab_verify::registry::run_scene;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

#[test]
fn thick_string_scene_writes_eigenvalues_sweeps_and_map() {
    let out = std::env::temp_dir().join(format!("contactlab-moving-scene-{}", std::process::id()));
    let summary = run_scene(
        &root().join("examples/scenes/moving_thick_string.toml"),
        &out,
    )
    .unwrap();
    assert!(summary.contains("stable at the scene's point"), "{summary}");
    let point: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("eigenvalues.json")).unwrap())
            .unwrap();
    assert_eq!(point["eigenvalues"].as_array().unwrap().len(), 42);
    assert_eq!(point["assessment"]["verdict"], "stable");
    let sweep: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("sweep_0.json")).unwrap()).unwrap();
    assert_eq!(sweep["values"].as_array().unwrap().len(), 100);
    assert_eq!(sweep["branches"].as_array().unwrap().len(), 42);
    let map: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("map.json")).unwrap()).unwrap();
    assert_eq!(map["verdict"].as_array().unwrap().len(), 3600);
    for f in ["spectrum.svg", "sweep_0.svg", "map.svg"] {
        assert!(out.join(f).exists(), "{f}");
    }
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn every_moving_example_scene_runs() {
    for name in [
        "moving_thick_string",
        "moving_penalty_bushing",
        "moving_disc_particle",
    ] {
        let out = std::env::temp_dir().join(format!(
            "contactlab-moving-example-{name}-{}",
            std::process::id()
        ));
        run_scene(&root().join(format!("examples/scenes/{name}.toml")), &out)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(out.join("eigenvalues.json").exists());
        std::fs::remove_dir_all(&out).ok();
    }
}

#[test]
fn misspelt_key_in_a_moving_scene_is_named() {
    let dir = std::env::temp_dir().join(format!("contactlab-moving-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(root().join("examples/scenes/moving_disc_particle.toml"))
        .unwrap()
        .replace("normal_force", "normal_forse");
    let path = dir.join("bad.toml");
    std::fs::write(&path, text).unwrap();
    let err = run_scene(&path, &dir.join("out")).unwrap_err();
    assert!(err.contains("normal_forse"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
