//! `verify scene` on multibody scenes (a dynamic scene of `[[body]]` sections): the block on the
//! block writes its solution (bodies, pairs, records, summary, snapshots with both bodies and the
//! contact states), its plots and, asked for, its ParaView series; a run that stops partway writes
//! `partial_solution.json` with the typed error; `--vtk` without output times is refused before
//! the run.

use std::path::{Path, PathBuf};

use contactlab_verify::registry::{run_scene, run_scene_with};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn json(path: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("contactlab-mb-{name}-{}", std::process::id()))
}

#[test]
fn block_on_block_writes_solution_plots_and_paraview_series() {
    let out = temp("blocks");
    let summary = run_scene_with(
        &root().join("examples/scenes/multibody_block_on_block.toml"),
        &out,
        true,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        summary.contains("2 bodies (lower, upper)") && summary.contains("friction work"),
        "{summary}"
    );
    // the foundation and gravity act along y: P_y is not claimed, P_x is
    assert!(
        summary.contains("P_y") && summary.contains("not conserved here"),
        "{summary}"
    );
    for f in [
        "solution.json",
        "audit.svg",
        "contact.svg",
        "snapshots.svg",
        "solution.pvd",
        "solution_0000.vtu",
        "solution_0003.vtu",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    assert!(!out.join("partial_solution.json").exists());
    let sol = json(&out.join("solution.json"));
    assert_eq!(sol["status"], "completed");
    assert_eq!(sol["steps_completed"], 300);
    assert_eq!(sol["records"].as_array().map(Vec::len), Some(301));
    assert_eq!(sol["history"].as_array().map(Vec::len), Some(301));
    // beside the raw force, the two-step mean and the step impulse of each section, in the JSON
    // and in history.csv (a header and one row per record)
    let h = &sol["history"][150];
    for key in ["normal_force", "normal_force_mean", "normal_impulse"] {
        assert_eq!(h[key].as_array().map(Vec::len), Some(2), "{key}");
    }
    let csv = std::fs::read_to_string(out.join("history.csv")).expect("history.csv");
    assert_eq!(csv.lines().count(), 302);
    assert!(csv.starts_with("step,time,pair0_normal_force_raw,pair0_normal_force_mean,"));
    assert_eq!(sol["bodies"].as_array().map(Vec::len), Some(2));
    assert_eq!(sol["pairs"].as_array().map(Vec::len), Some(2));
    assert_eq!(sol["claims"]["momentum"], serde_json::json!([true, false]));
    let snaps = sol["snapshots"].as_array().expect("snapshots");
    assert_eq!(snaps.len(), 4);
    let last = &snaps[3];
    assert_eq!(last["step"], 300);
    assert_eq!(last["bodies"].as_array().map(Vec::len), Some(2));
    // the upper block (6 × 4 nodes: 5 × 3 squares) and its contact states
    assert_eq!(
        last["bodies"][1]["displacement"].as_array().map(Vec::len),
        Some(2 * 24)
    );
    assert!(!last["contacts"].as_array().expect("contacts").is_empty());
    // the audit: P_x conserved to round-off, friction dissipates, the energy identity holds
    let s = &sol["summary"];
    for key in ["momentum_ratio_x", "identity_ratio", "friction_ratio"] {
        let r = s[key].as_f64().unwrap_or(f64::NAN);
        assert!(r <= 1.0, "{key} = {r}");
    }
    assert!(s["friction_work"].as_f64().unwrap() < 0.0);
    // friction slowed the upper block and dragged the lower one
    let v = &sol["history"][300]["velocities"];
    let (lower, upper) = (v[0][0].as_f64().unwrap(), v[1][0].as_f64().unwrap());
    assert!(upper < 0.95 && lower > 0.0, "lower {lower}, upper {upper}");
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn a_run_that_stops_writes_its_partial_solution_and_the_typed_error() {
    let dir = temp("stops");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(root().join("examples/scenes/multibody_rings.toml"))
        .unwrap()
        + "\n[solver]\nmax_iterations = 1\n";
    let scene = dir.join("rings.toml");
    std::fs::write(&scene, text).unwrap();
    let out = dir.join("out");
    let e = run_scene(&scene, &out).expect_err("one Newton iteration cannot converge");
    assert!(e.contains("the run stopped"), "{e}");
    assert!(!out.join("solution.json").exists());
    let sol = json(&out.join("partial_solution.json"));
    assert_eq!(sol["status"], "failed");
    assert_eq!(sol["error"]["kind"], "newton_not_converged");
    let step = sol["error"]["step"].as_u64().expect("the step");
    assert_eq!(sol["steps_completed"].as_u64(), Some(step - 1));
    assert_eq!(sol["last"]["step"].as_u64(), Some(step - 1));
    assert!(out.join("audit.svg").exists() && out.join("contact.svg").exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn vtk_without_output_times_is_refused_before_the_run() {
    let dir = temp("no-times");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(root().join("examples/scenes/multibody_rings.toml"))
        .unwrap()
        .replace("times = [0.0, 0.25, 0.5, 0.75, 1.0]", "times = []");
    let scene = dir.join("rings.toml");
    std::fs::write(&scene, text).unwrap();
    let e = run_scene_with(&scene, &dir.join("out"), true).expect_err("no output time");
    assert!(
        e.contains("output.vtk") && e.contains("[output] times"),
        "{e}"
    );
    assert!(!dir.join("out").exists());
    std::fs::remove_dir_all(&dir).ok();
}
