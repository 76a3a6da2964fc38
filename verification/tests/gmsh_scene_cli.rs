//! `verify scene --vtk` on the shipped Gmsh examples, and on broken mesh files.
//!
//! Setting: the notched block (plane) and the O-ring (dynamic) of examples/scenes, whose meshes are
//! Gmsh files; then the same plane scene pointed at a truncated file, a file with a second-order
//! triangle, and a missing file. Goal: the examples write their solution and a ParaView series
//! (one .vtu per output time, a .pvd listing them); a broken or unsupported mesh is a clear error
//! (exit 2) that names the file and what is wrong, and writes no output at all.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn scene(path: &Path, out: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .arg("scene")
        .arg(path)
        .arg("--out")
        .arg(out)
        .arg("--vtk")
        .output()
        .expect("the verify binary runs")
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("contactlab-gmsh-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn files_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|r| {
            r.filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn both_gmsh_examples_write_a_paraview_series_per_output_time() {
    for (name, frames) in [("plane_gmsh_notched_block", 2), ("dynamic_gmsh_o_ring", 14)] {
        let out = temp(name);
        let o = scene(&root().join(format!("examples/scenes/{name}.toml")), &out);
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let files = files_in(&out);
        let vtu = files.iter().filter(|f| f.ends_with(".vtu")).count();
        assert_eq!(vtu, frames, "{name}: {files:?}");
        let pvd = std::fs::read_to_string(out.join("solution.pvd")).expect("solution.pvd");
        assert_eq!(pvd.matches("<DataSet").count(), frames, "{pvd}");
        let _ = std::fs::remove_dir_all(&out);
    }
}

#[test]
fn a_broken_or_unsupported_mesh_is_a_clear_error_and_writes_nothing() {
    let base = temp("broken");
    std::fs::create_dir_all(&base).expect("tmp");
    let example = root().join("examples/scenes/plane_gmsh_notched_block.toml");
    let text = std::fs::read_to_string(&example).expect("the example");
    let good = std::fs::read_to_string(root().join("examples/meshes/notched_block.msh"))
        .expect("the mesh");
    // a file cut in the middle of its element block
    let truncated = &good[..good.rfind("$Elements").expect("elements") + 40];
    // a 2.2 file holding a 6-node second-order triangle (Gmsh type 9)
    let second_order = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n\
                        4 0.5 0 0\n5 0.5 0.5 0\n6 0 0.5 0\n$EndNodes\n$Elements\n1\n1 9 2 1 1 1 2 3 4 5 6\n\
                        $EndElements\n";
    let cases: [(&str, Option<&str>, &[&str]); 3] = [
        ("truncated", Some(truncated), &["truncated.msh"]),
        (
            "second_order",
            Some(second_order),
            &["second_order.msh", "6-node"],
        ),
        ("missing", None, &["missing.msh"]),
    ];
    for (name, content, expected) in cases {
        let mesh = base.join(format!("{name}.msh"));
        if let Some(c) = content {
            std::fs::write(&mesh, c).expect("write the mesh");
        }
        let scene_path = base.join(format!("{name}.toml"));
        std::fs::write(
            &scene_path,
            text.replace("../meshes/notched_block.msh", &format!("{name}.msh")),
        )
        .expect("write the scene");
        let out = base.join(format!("out_{name}"));
        let o = scene(&scene_path, &out);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        for e in expected {
            assert!(err.contains(e), "{name}: `{e}` not in {err}");
        }
        assert!(
            err.len() < 800,
            "{name}: the message stays readable ({} chars)",
            err.len()
        );
        let written: Vec<String> = files_in(&out)
            .into_iter()
            .filter(|f| !f.starts_with('.'))
            .collect();
        assert!(written.is_empty(), "{name}: wrote {written:?}");
    }
    let _ = std::fs::remove_dir_all(&base);
}

#[test]
fn a_dynamic_gmsh_body_is_sized_against_the_memory_limit_before_its_operators() {
    // The O-ring (236 nodes) under a 10 KiB limit: refused naming body.file and its node count;
    // with 10¹³ steps under the default limit: refused naming time.steps. Nothing is written.
    let example = root().join("examples/scenes/dynamic_gmsh_o_ring.toml");
    let out = temp("memory");
    let o = Command::new(env!("CARGO_BIN_EXE_verify"))
        .arg("scene")
        .arg(&example)
        .args(["--max-memory", "10K", "--out"])
        .arg(&out)
        .output()
        .expect("the verify binary runs");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("body.file") && err.contains("236 nodes"),
        "{err}"
    );
    let base = temp("steps");
    std::fs::create_dir_all(&base).expect("tmp");
    let text = std::fs::read_to_string(&example).expect("the example");
    let scene_path = base.join("many_steps.toml");
    let steps = text
        .lines()
        .find(|l| l.trim_start().starts_with("steps"))
        .expect("a steps line")
        .to_string();
    std::fs::write(
        &scene_path,
        text.replace(&steps, "steps = 10000000000000").replace(
            "../meshes/",
            &format!("{}/", root().join("examples/meshes").display()),
        ),
    )
    .expect("write the scene");
    let o = scene(&scene_path, &base.join("out"));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("time.steps"), "{err}");
    assert!(files_in(&base.join("out"))
        .iter()
        .all(|f| f.starts_with('.')));
    let _ = std::fs::remove_dir_all(&base);
    let _ = std::fs::remove_dir_all(&out);
}
