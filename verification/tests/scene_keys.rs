//! The scene-key reference: `docs/scenes.md` is what `verify scene-keys` generates from the
//! solver's scene types, every key of every model has a doc comment on its field, and the walk
//! finds known keys at the paths a user writes (so a broken walk cannot pass with empty tables).

use std::path::PathBuf;

use contactlab_verify::scene_keys::{generate, models, reference, undocumented, ModelKeys};

fn root() -> PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the repository")
        .to_path_buf()
}

fn keys() -> Vec<ModelKeys> {
    generate(&root().join("src")).unwrap_or_else(|e| panic!("the generator fails: {e}"))
}

#[test]
fn docs_scenes_md_equals_the_generators_output() {
    let generated = reference(&root()).expect("the reference renders");
    let committed = std::fs::read_to_string(root().join("docs/scenes.md")).unwrap_or_default();
    assert!(
        generated == committed,
        "docs/scenes.md differs from the scene types: run `cargo run --release --bin verify -- scene-keys`"
    );
}

#[test]
fn every_key_of_every_model_has_a_doc_comment() {
    let missing = undocumented(&keys());
    assert!(
        missing.is_empty(),
        "{} scene keys have no doc comment on their field (say what the key means, its unit or \
         range, its default):\n{}",
        missing.len(),
        missing.join("\n")
    );
}

#[test]
fn the_walk_covers_the_models_of_the_solver_and_finds_known_keys_at_their_paths() {
    let names: Vec<&str> = models::MODELS.iter().map(|m| m.0).collect();
    assert_eq!(names, contactlab::scene::any::MODELS.to_vec());
    let all = keys();
    let find = |model: &str, path: &str| {
        let m = all.iter().find(|m| m.model == model).expect("the model");
        m.rows
            .iter()
            .find(|r| r.path == path)
            .unwrap_or_else(|| panic!("{model}: no key {path}"))
            .clone()
    };
    assert_eq!(find("rod", "rod.length").ty, "number");
    assert_eq!(find("rod", "rod.length").requirement, "required");
    assert_eq!(find("rod", "exact.solution").ty, "string");
    let scheme = find("rod", "time.scheme");
    assert_eq!(scheme.requirement, "default: `\"explicit\"`");
    let values: Vec<&str> = scheme.values.iter().map(|v| v.0.as_str()).collect();
    assert_eq!(values, ["explicit", "implicit", "midpoint"]);
    assert_eq!(find("plane", "[[dirichlet]].where").ty, "string");
    let support: Vec<String> = find("plane", "[[dirichlet]].support")
        .values
        .into_iter()
        .map(|v| v.0)
        .collect();
    assert_eq!(support, ["clamped", "fix_x", "fix_y"]);
    assert_eq!(find("plane", "geometry.size").ty, "array of 2 numbers");
    assert_eq!(find("dynamic", "contact.friction.law").ty, "string");
    assert_eq!(find("dynamic", "contact.friction").requirement, "optional");
    assert_eq!(
        find("moving_string", "[[sweep]].scale").requirement,
        "default: `\"linear\"`"
    );
    assert_eq!(
        find("rotating_plate", "plate.outer_edge").requirement,
        "default: `\"free\"`"
    );
    assert_eq!(find("rotating_plate", "map.y.points").ty, "integer ≥ 0");
    assert_eq!(find("disc_particle", "particle.angular_speed").ty, "number");
    for m in &all {
        assert!(m.rows.len() >= 8, "{}: only {} keys", m.model, m.rows.len());
        assert_eq!(m.rows[0].path, "model", "{}", m.model);
    }
}
