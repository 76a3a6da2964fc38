//! The mutation campaign covers the source as it is (issue 10: "a change to those files re-runs
//! the campaign on its diff"). `verification/mutants/campaign.toml` records the FNV-1a 64 hash of
//! every file `.cargo/mutants.toml` mutates, as the last campaign or `in-diff` run saw it
//! (`verification/mutants/stamp`); a mutated file that differs has mutants no run has tested.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the repository")
        .to_path_buf()
}

/// FNV-1a, 64 bits (the same function as verification/mutants/stamp).
fn fnv1a64(data: &[u8]) -> u64 {
    data.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

#[derive(serde::Deserialize)]
struct Config {
    examine_globs: Vec<String>,
}

#[derive(serde::Deserialize)]
struct Stamp {
    commit: String,
    files: BTreeMap<String, String>,
}

#[test]
fn fnv1a64_matches_its_reference_values() {
    // The published test vectors of FNV-1a 64.
    assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
    assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
    assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
}

#[test]
fn every_mutated_file_is_the_one_the_campaign_tested() {
    let root = root();
    let config: Config = toml::from_str(
        &std::fs::read_to_string(root.join(".cargo/mutants.toml")).expect(".cargo/mutants.toml"),
    )
    .expect("the campaign's configuration parses");
    let stamp: Stamp = toml::from_str(
        &std::fs::read_to_string(root.join("verification/mutants/campaign.toml"))
            .expect("verification/mutants/campaign.toml"),
    )
    .expect("the stamp parses");
    // The globs name files (no wildcards in this configuration): each must exist and be stamped.
    let mut stale = Vec::new();
    for file in &config.examine_globs {
        assert!(
            !file.contains('*'),
            "examine_globs entry {file}: name files (the stamp records files, not patterns)"
        );
        let data = std::fs::read(root.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        let now = format!("{:016x}", fnv1a64(&data));
        match stamp.files.get(file) {
            Some(h) if *h == now => {}
            Some(_) => stale.push(format!("{file} (changed since {})", stamp.commit)),
            None => stale.push(format!("{file} (never campaigned)")),
        }
    }
    assert!(
        stale.is_empty(),
        "mutated files the campaign has not seen: {}.\nRun `verification/mutants/in-diff` (the campaign on the change), kill or explain its survivors in reports/mutants.md, then `verification/mutants/stamp`.",
        stale.join(", ")
    );
}
