//! The case catalogue: every file in verification/cases parses, has a unique id, an explanation and
//! gates of its kind; the quick tier is non-empty.

use std::path::PathBuf;

use contactlab_verify::case::{Case, CaseFile, CaseKind, Tier};

fn cases() -> Vec<Case> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases");
    Case::load_all(&dir).expect("every case file parses")
}

#[test]
fn every_case_parses_with_an_explanation_and_gates() {
    let cases = cases();
    assert!(cases.len() >= 9);
    for c in &cases {
        // every family checks its own format (the dynamic and moving families have their own)
        contactlab_verify::run::check_case(c).expect("the case's format");
        assert!(
            c.header.explanation.trim().len() > 80,
            "{}: explain the expected numbers",
            c.header.id
        );
        assert_eq!(
            c.path.file_stem().and_then(|s| s.to_str()),
            Some(c.header.id.as_str()),
            "file name = id"
        );
        let Ok(f) = CaseFile::from_case(c) else {
            continue;
        };
        let f = &f;
        assert!(
            f.explanation.trim().len() > 80,
            "{}: explain the expected numbers",
            f.id
        );
        let gated = match f.kind {
            CaseKind::Convergence => !f.gate.is_empty() || !f.reference.is_empty(),
            CaseKind::Stability => f.stability.is_some(),
            CaseKind::Extremes => !f.extreme.is_empty(),
            CaseKind::WorkPrecision => f.work_precision.is_some(),
            CaseKind::Performance => f.performance.is_some(),
            CaseKind::PaperTest2d => f.paper_test.is_some(),
            CaseKind::PlaneStability => f.plane_stability.is_some(),
            CaseKind::PlanePaths => f.plane_paths.is_some(),
            CaseKind::PlanePerformance => f.plane_performance.is_some(),
        };
        assert!(gated, "{}: no gates", f.id);
        assert_eq!(
            c.path.file_stem().and_then(|s| s.to_str()),
            Some(f.id.as_str()),
            "file name = id"
        );
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
        "id = \"bad\"\ntitle = \"t\"\nkind = \"convergence\"\nexplanation = \"e\"\ntolerence = 1\n",
    )
    .unwrap();
    let err = Case::load(&path).unwrap_err().to_string();
    assert!(err.contains("tolerence"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
