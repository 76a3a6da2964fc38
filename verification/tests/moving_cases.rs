//! The moving-continuum cases: every `moving_*` file parses with its kind's format, explains
//! its numbers, has the file name of its id; the quick tier holds the cheap ones and the 200 × 200
//! map and the long studies stay in the full tier; a typo is named; the quick cases pass.

use std::path::PathBuf;

use contactlab_verify::core::case::{Case, Tier};
use contactlab_verify::core::context::RunContext;
use contactlab_verify::core::report::metadata::Metadata;
use contactlab_verify::registry;

fn moving_cases() -> Vec<Case> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases");
    contactlab_verify::registry::load_all(&dir)
        .expect("every case file parses")
        .into_iter()
        .filter(|c| c.header.kind.starts_with("moving_"))
        .collect()
}

#[test]
fn every_moving_case_parses_with_an_explanation() {
    let cases = moving_cases();
    assert!(cases.len() >= 8);
    for c in &cases {
        contactlab_verify::registry::check(c).expect("its kind's format");
        assert!(
            c.header.explanation.trim().len() > 200,
            "{}: explain the numbers",
            c.header.id
        );
        assert!(!c.header.explanation.contains("TBD"), "{}", c.header.id);
        assert_eq!(
            c.path.file_stem().and_then(|s| s.to_str()),
            Some(c.header.id.as_str())
        );
    }
}

#[test]
fn the_long_moving_studies_are_full_tier_the_mid_ones_default_and_the_rest_quick() {
    for c in moving_cases() {
        // full: the 200 × 200 map (its timing), the finite-element onsets (14 s of eigenvalue
        // bisections) and the plate pad's long time checks (20 s); default: the 4–8 s studies
        // (the thick string's references, the patch, the CI versions of the map and of the pad)
        let id = c.header.id.as_str();
        let expected = if [
            "moving_map",
            "moving_flutter_elements",
            "moving_plate_pad",
            "moving_envelope_full",
        ]
        .contains(&id)
        {
            Tier::Full
        } else if [
            "moving_flutter",
            "moving_flutter_patch",
            "moving_map_quick",
            "moving_plate_pad_quick",
            "moving_envelope",
        ]
        .contains(&id)
        {
            Tier::Default
        } else {
            Tier::Quick
        };
        assert_eq!(c.header.tier, expected, "{id}");
    }
}

#[test]
fn an_unknown_key_in_a_moving_case_is_named() {
    let dir = std::env::temp_dir().join(format!("contactlab-moving-cases-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases/moving_symmetry.toml");
    let text = std::fs::read_to_string(src)
        .unwrap()
        .replace("round_off = ", "roundoff = ");
    let path = dir.join("moving_symmetry.toml");
    std::fs::write(&path, text).unwrap();
    let err = contactlab_verify::registry::load(&path)
        .unwrap_err()
        .to_string();
    assert!(err.contains("roundoff"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn quick_moving_cases_pass() {
    let out = std::env::temp_dir().join(format!("contactlab-moving-run-{}", std::process::id()));
    let ctx = RunContext {
        out_dir: out.clone(),
        metadata: Metadata::collect("quick"),
        progress: false,
        bars: None,
    };
    for c in moving_cases()
        .iter()
        .filter(|c| c.header.tier == Tier::Quick)
    {
        let r = registry::run(c, &ctx);
        assert!(
            r.passed,
            "{}: {:?} {:?}",
            r.id,
            r.failure,
            r.gates
                .iter()
                .filter(|g| !g.passed)
                .map(|g| &g.name)
                .collect::<Vec<_>>()
        );
        assert!(out.join(&r.id).join("data.json").exists());
    }
    std::fs::remove_dir_all(&out).ok();
}
