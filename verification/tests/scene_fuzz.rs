//! Property-based fuzzing of `verify scene` (proptest): any scene mutated from a shrunk example —
//! whichever seed, base and mutation — ends in a solution with finite outputs, a typed error or a
//! stop at its time limit; never a panic, a hang or a non-finite number written. The bases and
//! their shrink values are those of the campaign `verification/cases/robustness_fuzz_quick.toml`
//! (the long campaign, ≥ 10⁴ scenes per model, is the full-tier case `robustness_fuzz`).

use std::path::PathBuf;
use std::time::Duration;

use contactlab_verify::registry::run_scene;
use contactlab_verify::robustness::{classify, scene_text, shrunk, FuzzCase};
use proptest::prelude::*;

fn campaign() -> (PathBuf, FuzzCase) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases/robustness_fuzz_quick.toml");
    let case = contactlab_verify::core::case::Case::read(&path).expect("the case file");
    let fuzz: FuzzCase = case.body().expect("its format");
    (path, fuzz)
}

proptest! {
    // a fixed seed: the test is the same in every run (the campaign case varies the scenes)
    #![proptest_config(ProptestConfig {
        cases: 96,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x5CE7E),
        ..ProptestConfig::default()
    })]

    #[test]
    fn a_mutated_scene_never_panics_hangs_or_writes_non_finite_numbers(
        seed in any::<u64>(),
        base in 0usize..64,
        index in 0usize..1_000_000,
    ) {
        let (path, c) = campaign();
        let b = base % c.base.len();
        let table = shrunk(path.parent().expect("a directory"), &c.base[b]).expect("the base");
        let scene = scene_text(&table, seed, b, index);
        let mutations = scene.what.clone();
        let dir = std::env::temp_dir().join(format!("contactlab-scene-fuzz-{}", std::process::id()));
        let (outcome, message) = classify(
            run_scene,
            &dir,
            &scene,
            Duration::from_secs(5),
            Duration::from_secs(60),
        );
        prop_assert!(
            !outcome.is_defect(),
            "{outcome:?} for seed/base/index {seed}/{b}/{index} ({mutations}): {message}"
        );
    }
}
