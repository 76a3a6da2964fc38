//! Same case, same bits: cases of every family run twice write deterministic report parts
//! (`<case>.json`) that are equal to the bit, whatever varies between the runs (timings, the
//! thread count) — which also checks that the split of `core::report::split` leaves no timing in
//! the deterministic part.

use contactlab_verify::core::context::RunContext;
use contactlab_verify::core::report::compare::check;
use contactlab_verify::core::report::metadata::Metadata;
use contactlab_verify::registry;

fn run_into(tag: &str, ids: &[&str], threads: usize) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
    let out = std::env::temp_dir().join(format!("contactlab-det-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&out).expect("out dir");
    let ctx = RunContext {
        out_dir: out.clone(),
        metadata: Metadata::collect("test"),
        progress: false,
        bars: None,
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("pool");
    for id in ids {
        let case = registry::load(&dir.join(format!("{id}.toml"))).expect("case loads");
        let r = pool.install(|| registry::run(&case, &ctx));
        r.write(&out).expect("writes");
    }
    out
}

#[test]
fn two_runs_write_the_same_deterministic_reports() {
    let ids = [
        "rod_schemes",
        "rod_performance",
        "plane_stability",
        "plane_paths",
        "dynamic_bar_wall_quick",
        "dynamic_ring_quick",
        "dynamic_extremes_quick",
        "moving_symmetry",
        "moving_oscillator",
        "moving_time_check",
    ];
    let a = run_into("a", &ids, 1);
    let b = run_into("b", &ids, 2);
    let ids: Vec<String> = ids.iter().map(|s| s.to_string()).collect();
    let c = check(&a, &b, &ids).expect("compares");
    assert!(c.same(), "{}", c.render());
    assert!(c.timing_leaves > 0, "the timings went somewhere");
    for d in [a, b] {
        let _ = std::fs::remove_dir_all(d);
    }
}
