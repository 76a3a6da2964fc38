//! The verification evidence as a test: every case of the quick tier (the CI tier of `verify`)
//! runs and passes its gates, the timing cases aside (their verdicts are ratios of measured times,
//! not properties of the code under test). `cargo test` thus sees the exact, manufactured and
//! independent references of the suite, not only the unit tests — which is what a mutation of
//! the solver must get past (`reports/mutants.md`).

use contactlab_verify::core::case::Tier;
use contactlab_verify::core::context::RunContext;
use contactlab_verify::core::report::metadata::Metadata;
use contactlab_verify::registry;

fn cases_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("cases")
}

#[test]
fn every_quick_case_passes_its_gates() {
    let cases = registry::load_all(&cases_dir()).expect("the catalogue loads");
    let ctx = RunContext {
        out_dir: std::env::temp_dir().join(format!("contactlab-evidence-{}", std::process::id())),
        metadata: Metadata::collect("test"),
        progress: false,
    };
    let mut failed = Vec::new();
    let mut ran = 0;
    for case in cases
        .iter()
        .filter(|c| c.header.tier == Tier::Quick && !c.header.kind.ends_with("_performance"))
    {
        ran += 1;
        let r = registry::run(case, &ctx);
        if !r.passed {
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
            failed.push(format!(
                "{}: {}{}",
                r.id,
                r.failure.clone().unwrap_or_default(),
                gates.join(" | ")
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&ctx.out_dir);
    assert!(ran >= 20, "only {ran} quick cases");
    assert!(failed.is_empty(), "failing cases:\n{}", failed.join("\n"));
}
