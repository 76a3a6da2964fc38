//! The verification evidence as a test: every case of the default tier (`verify`'s first run: the
//! quick cases and the default ones, every family and every kind of claim) runs and passes its gates, the timing cases aside (their verdicts are ratios of measured times,
//! not properties of the code under test). `cargo test` thus sees the exact, manufactured and
//! independent references of the suite, not only the unit tests — which is what a mutation of
//! the solver must get past (`reports/mutants.md`).

use contactlab_verify::core::case::Tier;
use contactlab_verify::core::context::RunContext;
use contactlab_verify::core::report::metadata::Metadata;
use contactlab_verify::registry;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

fn cases_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("cases")
}

/// `CONTACTLAB_EVIDENCE_FAIL_FAST=1` (set by the mutation campaign, `reports/mutants.md`): once a
/// case has failed, the cases not yet started are skipped — the verdict is the same, a caught
/// mutant costs seconds instead of the whole tier.
#[test]
fn every_default_tier_case_passes_its_gates() {
    let cases = registry::load_all(&cases_dir()).expect("the catalogue loads");
    let ctx = RunContext {
        out_dir: std::env::temp_dir().join(format!("contactlab-evidence-{}", std::process::id())),
        metadata: Metadata::collect("test"),
        progress: false,
        bars: None,
    };
    let fail_fast = std::env::var_os("CONTACTLAB_EVIDENCE_FAIL_FAST").is_some_and(|v| v == "1");
    // `CONTACTLAB_EVIDENCE_KINDS=multibody` (the campaign on src/model/multibody/, whose code only
    // the multibody cases reach): only the cases whose kind starts with one of the comma-separated
    // prefixes run. Unset: every case.
    let kinds: Option<Vec<String>> = std::env::var("CONTACTLAB_EVIDENCE_KINDS")
        .ok()
        .map(|v| v.split(',').map(str::trim).map(String::from).collect());
    let stop = AtomicBool::new(false);
    // The default tier holds every case the quick tier held when the last mutation campaign ran
    // (issue 13 moved the slowest of them to `default`), so the campaign's verdicts stand.
    let evidence: Vec<_> = cases
        .iter()
        .filter(|c| {
            c.header.tier.runs_in(Tier::Default)
                && !c.header.kind.ends_with("_performance")
                && kinds
                    .as_ref()
                    .is_none_or(|k| k.iter().any(|p| c.header.kind.starts_with(p.as_str())))
        })
        .collect();
    // The cases are independent (each writes under its own id): run them on all cores.
    let failed: Vec<String> = evidence
        .par_iter()
        .filter_map(|case| {
            if fail_fast && stop.load(Ordering::Relaxed) {
                return None;
            }
            let r = registry::run(case, &ctx);
            if r.passed {
                return None;
            }
            stop.store(true, Ordering::Relaxed);
            let gates: Vec<String> = r
                .gates
                .iter()
                .filter(|g| !g.passed)
                .map(|g| {
                    let checks: Vec<String> = g
                        .checks
                        .iter()
                        .filter(|c| !c.passed)
                        .map(|c| format!("{} = {:e} (limit {})", c.name, c.observed, c.limit))
                        .collect();
                    format!("{}: {}", g.name, checks.join("; "))
                })
                .collect();
            Some(format!(
                "{}: {}{}",
                r.id,
                r.failure.clone().unwrap_or_default(),
                gates.join(" | ")
            ))
        })
        .collect();
    let _ = std::fs::remove_dir_all(&ctx.out_dir);
    let least = if kinds.is_some() { 1 } else { 40 };
    assert!(evidence.len() >= least, "only {} cases", evidence.len());
    assert!(failed.is_empty(), "failing cases:\n{}", failed.join("\n"));
}
