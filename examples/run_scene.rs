//! Runs any scene file through the library alone — no `verify`:
//!
//! ```sh
//! cargo run --release --example run_scene -- examples/scenes/rod_paper_p0_6.toml
//! cargo run --release --example run_scene -- examples/scenes/moving_thick_string.toml --json out.json
//! ```
//!
//! Loads the scene with `contactlab::scene::Scene::load` (the `model` key decides which model),
//! runs it, and prints a one-line summary; with `--json FILE` it also writes the solution as JSON.
//! Errors (a missing file, a misspelt key, a failed step) are printed with their data and the
//! exit code is 1.

use std::path::PathBuf;
use std::process::ExitCode;

use contactlab::scene::Scene;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (file, json) = match args.as_slice() {
        [file] => (PathBuf::from(file), None),
        [file, flag, out] if flag == "--json" => (PathBuf::from(file), Some(PathBuf::from(out))),
        _ => {
            eprintln!("usage: run_scene SCENE.toml [--json OUT.json]");
            return ExitCode::from(2);
        }
    };
    let scene = match Scene::load(&file) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    let solution = match scene.run() {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {}: {e}", file.display());
            return ExitCode::from(1);
        }
    };
    let title = if scene.title().is_empty() {
        file.display().to_string()
    } else {
        scene.title().to_string()
    };
    println!("{title} ({}): {}", scene.model(), solution.summary());
    if let Some(out) = json {
        let text = match serde_json::to_string_pretty(&solution) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("error: serializing the solution: {e}");
                return ExitCode::from(1);
            }
        };
        if let Err(e) = std::fs::write(&out, text) {
            eprintln!("error: {}: {e}", out.display());
            return ExitCode::from(1);
        }
        println!("wrote {}", out.display());
    }
    ExitCode::SUCCESS
}
