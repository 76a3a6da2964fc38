//! The case catalogue: every file in verification/cases parses with its kind's format, has a
//! unique id equal to its file name, an explanation, and a kind owned by one family (whose name it
//! starts with); the quick tier holds the rod's paper cases.

use std::path::PathBuf;

use contactlab_verify::core::case::{Case, Tier};
use contactlab_verify::registry;

fn cases() -> Vec<Case> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases");
    registry::load_all(&dir).expect("every case file parses with its kind's format")
}

#[test]
fn every_case_parses_with_an_explanation_and_a_family() {
    let cases = cases();
    assert!(cases.len() >= 9);
    for c in &cases {
        registry::check(c).expect("the case's format");
        assert!(
            c.header.explanation.trim().len() > 80,
            "{}: explain the expected numbers",
            c.header.id
        );
        if contactlab_verify::robustness::KINDS.contains(&c.header.kind.as_str()) {
            continue; // the fuzz campaign runs every family's scenes: no family owns it
        }
        let family = registry::family_of(&c.header.kind).expect("a family owns the kind");
        assert!(
            c.header.kind.starts_with(family.name()),
            "{}: the kind names its family",
            c.header.id
        );
    }
}

#[test]
fn every_kind_belongs_to_exactly_one_family() {
    let kinds = registry::kinds();
    for (i, k) in kinds.iter().enumerate() {
        assert!(!kinds[..i].contains(k), "{k} is claimed twice");
    }
}

#[test]
fn quick_tier_holds_the_rod_convergence_cases() {
    let cases = cases();
    let quick: Vec<&str> = cases
        .iter()
        .filter(|c| c.header.tier == Tier::Quick)
        .map(|c| c.header.id.as_str())
        .collect();
    for id in [
        "rod_p0_6_explicit",
        "rod_p0_2_explicit",
        "rod_schemes",
        "rod_stability",
        "rod_extremes",
    ] {
        assert!(quick.contains(&id), "{id} must run in CI");
    }
}

#[test]
fn a_case_with_an_unknown_key_is_rejected() {
    let dir = std::env::temp_dir().join(format!("contactlab-cases-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.toml");
    std::fs::write(
        &path,
        "id = \"bad\"\ntitle = \"t\"\nkind = \"rod_convergence\"\nexplanation = \"e\"\ntolerence = 1\n",
    )
    .unwrap();
    let err = registry::load(&path).unwrap_err().to_string();
    assert!(err.contains("tolerence"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
