//! `verify --shard I/N` and `verify merge`: the shards of a run, joined, give the unsharded run's
//! deterministic numbers and its report's cases in the same order.
//!
//! Setting: five fast cases of three families run once unsharded and once as shards 1/3 … 3/3 by
//! the `verify` binary; `verify merge` joins the shards. Goal: the merged directory compares equal
//! to the unsharded one (`verify compare`: every number and text but timings), every case lands
//! in exactly one shard, and a merge with a shard missing is refused.

use std::path::{Path, PathBuf};
use std::process::Command;

const CASES: [&str; 5] = [
    "rod_schemes",
    "rod_stability",
    "plane_stability",
    "moving_disc",
    "moving_symmetry",
];

fn verify(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .output()
        .expect("the verify binary runs")
}

fn run(out: &Path, shard: Option<&str>) {
    let mut args: Vec<String> = vec![
        "--no-progress".into(),
        "--out".into(),
        out.display().to_string(),
    ];
    for c in CASES {
        args.push("--case".into());
        args.push(c.into());
    }
    if let Some(s) = shard {
        args.push("--shard".into());
        args.push(s.into());
    }
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = verify(&refs);
    assert!(
        o.status.success(),
        "verify {args:?}: {}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

fn case_ids_in_report(dir: &Path) -> Vec<String> {
    let md = std::fs::read_to_string(dir.join("report.md")).expect("report.md");
    md.lines()
        .filter_map(|l| l.strip_prefix("## "))
        .filter(|t| *t != "Summary")
        .map(String::from)
        .collect()
}

#[test]
fn three_shards_merged_equal_the_unsharded_run() {
    let base: PathBuf =
        std::env::temp_dir().join(format!("contactlab-shards-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&base);
    let whole = base.join("whole");
    run(&whole, None);
    let shards: Vec<PathBuf> = (1..=3).map(|i| base.join(format!("s{i}"))).collect();
    let mut count = 0;
    for (i, dir) in shards.iter().enumerate() {
        run(dir, Some(&format!("{}/3", i + 1)));
        count += CASES
            .iter()
            .filter(|c| dir.join(format!("{c}.json")).is_file())
            .count();
    }
    assert_eq!(count, CASES.len(), "every case in exactly one shard");

    let merged = base.join("merged");
    let mut args = vec!["merge".to_string()];
    args.extend(shards.iter().map(|d| d.display().to_string()));
    args.extend(["--out".into(), merged.display().to_string()]);
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = verify(&refs);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));

    let o = verify(&[
        "compare",
        &whole.display().to_string(),
        &merged.display().to_string(),
    ]);
    assert!(
        o.status.success(),
        "merged ≠ unsharded: {}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert_eq!(case_ids_in_report(&whole), case_ids_in_report(&merged));

    let o = verify(&[
        "merge",
        &shards[0].display().to_string(),
        &shards[2].display().to_string(),
        "--out",
        &base.join("bad").display().to_string(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("missing 2/3"));
    let _ = std::fs::remove_dir_all(&base);
}
