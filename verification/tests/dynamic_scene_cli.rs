//! `verify scene` on dynamic scenes through the command line: a scene runs and writes its
//! solution, its energy audit and its plots; a run that stops partway still writes the audit of
//! the steps it computed, with the typed error and its data; a misspelt key is named.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn verify(scene: &Path, out: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .arg("scene")
        .arg(scene)
        .arg("--out")
        .arg(out)
        .output()
        .expect("the verify binary runs")
}

fn json(path: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("contactlab-dyn-{name}-{}", std::process::id()))
}

#[test]
fn bar_wall_scene_writes_solution_audit_and_plots() {
    let out = temp("bar-wall");
    let o = verify(&root().join("examples/scenes/dynamic_bar_wall.toml"), &out);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(stdout.contains("(1.49)"), "{stdout}");
    for f in [
        "solution.json",
        "energy_audit.json",
        "energy.svg",
        "identities.svg",
        "contact.svg",
        "snapshots.svg",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    let audit = json(&out.join("energy_audit.json"));
    assert_eq!(audit["status"], "completed");
    assert_eq!(audit["records"].as_array().map(|r| r.len()), Some(301));
    // the midpoint rule with the energy-consistent force: (1.49) at round-off
    let r149 = audit["summary"]["max_residual_1_49"].as_f64().unwrap();
    assert!(r149 < 1e-12, "{r149}");
    let sol = json(&out.join("solution.json"));
    assert_eq!(sol["status"], "completed");
    assert_eq!(sol["dimension"], "bar");
    assert_eq!(
        sol["final_displacement_nodal"].as_array().map(|u| u.len()),
        Some(101)
    );
    assert_eq!(sol["snapshots"].as_array().map(|s| s.len()), Some(4));
    assert_eq!(sol["stats"]["path"], "condensed");
    // the bar leaves the wall at (almost) its impact speed: wave theory
    let v = sol["final_velocity"].as_array().unwrap();
    let mean = v.iter().map(|x| x.as_f64().unwrap()).sum::<f64>() / v.len() as f64;
    assert!((mean - 1.0).abs() < 0.03, "{mean}");
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn a_failed_run_still_writes_its_energy_audit_and_the_typed_error() {
    let dir = temp("failing");
    std::fs::create_dir_all(&dir).unwrap();
    // one Newton iteration per step cannot resolve the contact of a stiff penalty
    let text = std::fs::read_to_string(root().join("examples/scenes/dynamic_bar_wall.toml"))
        .unwrap()
        .replace("stiffness = 1e2", "stiffness = 1e8")
        + "\n[solver]\nmax_iterations = 1\n";
    let scene = dir.join("failing.toml");
    std::fs::write(&scene, text).unwrap();
    let out = dir.join("out");
    let o = verify(&scene, &out);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("energy_audit.json"), "{stderr}");
    let audit = json(&out.join("energy_audit.json"));
    assert_eq!(audit["status"], "failed");
    assert_eq!(audit["error"]["kind"], "newton_not_converged");
    let step = audit["error"]["step"].as_u64().unwrap() as usize;
    assert!(step >= 1);
    // the initial record and every completed step
    assert_eq!(audit["records"].as_array().map(|r| r.len()), Some(step));
    assert_eq!(audit["steps_completed"].as_u64(), Some(step as u64 - 1));
    let sol = json(&out.join("solution.json"));
    assert_eq!(sol["status"], "failed");
    assert!(out.join("energy.svg").exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_misspelt_key_is_named() {
    let dir = temp("typo");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(root().join("examples/scenes/dynamic_bar_wall.toml"))
        .unwrap()
        .replace("stiffness = 1e2", "stifness = 1e2");
    let scene = dir.join("typo.toml");
    std::fs::write(&scene, text).unwrap();
    let o = verify(&scene, &dir.join("out"));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr.contains("stifness"), "{stderr}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn plane_scene_writes_deformed_snapshots() {
    let out = temp("ring");
    let o = verify(
        &root().join("examples/scenes/dynamic_spinning_ring.toml"),
        &out,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let sol = json(&out.join("solution.json"));
    assert_eq!(sol["dimension"], "plane");
    assert_eq!(sol["triangles"].as_array().map(|t| t.len()), Some(96));
    assert_eq!(sol["snapshots"].as_array().map(|s| s.len()), Some(4));
    let audit = json(&out.join("energy_audit.json"));
    // Gonzalez: energy conserved to round-off at 9 wave-crossing times per step
    let r148 = audit["summary"]["max_residual_1_48"].as_f64().unwrap();
    assert!(r148 < 1e-12, "{r148}");
    assert!(std::fs::read_to_string(out.join("snapshots.svg"))
        .unwrap()
        .contains("<svg"));
    std::fs::remove_dir_all(&out).ok();
}
