//! The overlap check at t = 0: the setting is the issue's head-on bars (two linear bars 1 × 0.1,
//! ν = 0, 10 elements along, the left bar's right end the slave against the right bar's left end)
//! started overlapping, touching or apart; the goal is to pin that an overlap by more than the
//! round-off tolerance is a typed error naming the pair as written and the depth, whatever the
//! velocities, that touching (g = 0) and separated starts are accepted, and that
//! `initial_overlap = "resolve"` starts with the slave nodes on the master and runs.

use crate::scene::multibody::{overlaps, MultibodyScene};
use crate::scene::Scene;

/// The bars with their facing ends `overlap` apart inwards (negative: a gap), the left bar at
/// `vl`, the right at `vr`, and `extra` lines appended to the contact pair.
fn bars(overlap: f64, vl: f64, vr: f64, extra: &str) -> String {
    format!(
        r#"
model = "dynamic"
[[body]]
name = "left"
shape = "rectangle"
origin = [{lx}, 0.0]
size = [1.0, 0.1]
divisions = [10, 1]
density = 1.0
material = {{ law = "linear", young = 1.0, poisson = 0.0 }}
velocity = [{vl}, 0.0]
[[body]]
name = "right"
shape = "rectangle"
origin = [{rx}, 0.0]
size = [1.0, 0.1]
divisions = [10, 1]
density = 1.0
material = {{ law = "linear", young = 1.0, poisson = 0.0 }}
velocity = [{vr}, 0.0]
[[contact_pair]]
slave = {{ body = "left", sides = ["right"] }}
master = {{ body = "right", sides = ["left"] }}
{extra}
[time]
final_time = 0.2
steps = 20
"#,
        lx = -1.0 + 0.5 * overlap,
        rx = -0.5 * overlap,
    )
}

fn refused(text: &str) -> String {
    match Scene::from_toml_str(text, "bars.toml") {
        Ok(_) => panic!("an overlapping start was accepted"),
        Err(e) => e.to_string(),
    }
}

fn accepted(text: &str) -> MultibodyScene {
    match Scene::from_toml_str(text, "bars.toml") {
        Ok(Scene::Multibody(s)) => *s,
        Ok(other) => panic!("a {} scene", other.model()),
        Err(e) => panic!("refused: {e}"),
    }
}

/// The error names the section, both bodies as written and the depth (parsed back from the
/// message: the deepest node's depth within round-off of the overlap written).
fn names_pair_and_depth(message: &str, depth: f64) {
    for part in [
        "contact_pair[0]",
        "\"left\"",
        "\"right\"",
        "initial_overlap = \"resolve\"",
    ] {
        assert!(message.contains(part), "{part:?} not in: {message}");
    }
    let shown: f64 = message
        .split(" lies ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no depth in: {message}"));
    // the positions −1 + δ/2 + 1 and −δ/2 carry the round-off of coordinates of size 1
    let round_off = 1e-12 * depth + 8.0 * f64::EPSILON;
    assert!(
        (shown - depth).abs() <= round_off,
        "depth {shown} for {depth}: {message}"
    );
}

#[test]
fn bars_overlapping_by_a_hundredth_while_approaching_are_refused() {
    names_pair_and_depth(&refused(&bars(0.01, 0.1, -0.1, "")), 0.01);
}

#[test]
fn bars_overlapping_by_two_thousandths_while_separating_are_refused() {
    names_pair_and_depth(&refused(&bars(0.002, -0.1, 0.1, "")), 0.002);
}

#[test]
fn bars_overlapping_at_rest_are_refused() {
    names_pair_and_depth(&refused(&bars(0.01, 0.0, 0.0, "")), 0.01);
}

#[test]
fn bars_touching_exactly_or_apart_are_accepted() {
    for gap in [0.0, -0.01, -1e-9] {
        let s = accepted(&bars(gap, 0.1, -0.1, ""));
        assert!(s.problem.initial_displacement.iter().all(|&x| x == 0.0));
    }
}

#[test]
fn an_overlap_of_round_off_size_is_accepted_and_one_above_it_refused() {
    // h = 0.1: the tolerance is 1e-13 + 8 ε X ≈ 1.02e-13
    accepted(&bars(5e-14, 0.1, -0.1, ""));
    names_pair_and_depth(&refused(&bars(1e-9, 0.1, -0.1, "")), 1e-9);
}

#[test]
fn a_resolved_start_moves_the_slave_nodes_onto_the_master_and_runs() {
    let s = accepted(&bars(0.01, 0.1, -0.1, "initial_overlap = \"resolve\""));
    let u = &s.problem.initial_displacement;
    assert!(overlaps(&s.problem.bodies, &s.problem.pairs, u).is_empty());
    // the left bar's end nodes (x = 0.005) moved to the right bar's face (x = −0.005)
    let set = &s.problem.bodies;
    let moved: Vec<f64> = s.problem.pairs[0]
        .slave
        .nodes
        .iter()
        .map(|&n| set.position(0, n, u)[0])
        .collect();
    assert_eq!(moved.len(), 2);
    assert!(moved.iter().all(|x| (x + 0.005).abs() < 1e-15), "{moved:?}");
    let sol = s.solve().expect("the resolved start runs");
    assert_eq!(sol.records.len(), 21);
}

#[test]
fn an_unknown_overlap_mode_is_refused_naming_the_key() {
    let e = refused(&bars(0.0, 0.1, -0.1, "initial_overlap = \"ignore\""));
    assert!(e.contains("ignore") && e.contains("resolve"), "{e}");
}

#[test]
fn a_block_sunk_into_the_foundation_is_refused_naming_it() {
    let text = r#"
model = "dynamic"
[[body]]
name = "block"
shape = "rectangle"
origin = [0.0, -0.003]
size = [1.0, 0.5]
divisions = [2, 1]
density = 1.0
material = { law = "linear", young = 1.0, poisson = 0.3 }
[[contact_pair]]
slave = { body = "block", sides = ["bottom"] }
foundation = { level = 0.0 }
[time]
final_time = 0.1
steps = 2
"#;
    let e = refused(text);
    assert!(
        e.contains("contact_pair[0]") && e.contains("foundation"),
        "{e}"
    );
    assert!(
        e.contains("3e-3") || e.contains("2.99") || e.contains("3.0000"),
        "{e}"
    );
    let resolved = text.replace(
        "foundation = { level = 0.0 }",
        "foundation = { level = 0.0 }\ninitial_overlap = \"resolve\"",
    );
    let s = accepted(&resolved);
    assert!(overlaps(
        &s.problem.bodies,
        &s.problem.pairs,
        &s.problem.initial_displacement
    )
    .is_empty());
}

#[test]
fn every_multibody_example_scene_starts_without_overlap() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).expect("the examples") {
        let path = entry.expect("an entry").path();
        let text = std::fs::read_to_string(&path).expect("readable");
        if !text.contains("[[contact_pair]]") {
            continue;
        }
        let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let Scene::Multibody(s) = scene else {
            panic!("{}: a multibody scene", path.display());
        };
        assert!(s.problem.initial_displacement.iter().all(|&x| x == 0.0));
        seen += 1;
    }
    assert!(seen >= 4, "{seen} multibody examples");
}
