//! Multibody scenes through `Scene::load`: the setting is the example scenes of `[[body]]`
//! sections; the goal is to pin that a file becomes the solver's two-body problem and runs with
//! the conservation the energy–momentum scheme promises (linear and angular momentum of two free
//! neo-Hookean rings to round-off, the energy identity), that a Gmsh body is read relative to the
//! scene file, and that the one-body examples stay one-body dynamic scenes.

use std::path::{Path, PathBuf};

use contactlab::scene::{Scene, Solution};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes")
        .join(name)
}

/// The example `name` with its text changed by `edit`, read as if it were the file.
fn edited(name: &str, edit: impl Fn(String) -> String) -> Scene {
    let path = example(name);
    let text = edit(std::fs::read_to_string(&path).expect("readable"));
    Scene::from_toml_str(&text, &path.display().to_string()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_rings_example_conserves_both_momenta_to_round_off_through_the_impact() {
    // the first 0.4 of the run: the rings meet at t ≈ 0.14
    let scene = edited("multibody_rings.toml", |t| {
        t.replace("final_time = 1.0", "final_time = 0.4")
            .replace("steps = 200", "steps = 80")
            .replace("times = [0.0, 0.25, 0.5, 0.75, 1.0]", "times = [0.4]")
    });
    assert_eq!(scene.model(), "multibody");
    let Solution::Multibody(sol) = scene.run().expect("runs") else {
        panic!("a multibody solution")
    };
    let s = sol.summary();
    assert!(s.steps_with_contact > 10, "{s:?}");
    for (name, r) in [
        ("P_x", s.momentum_ratio_x),
        ("P_y", s.momentum_ratio_y),
        ("J", s.angular_ratio),
        ("energy identity", s.identity_ratio),
        ("energy between set changes", s.unchanged_ratio),
    ] {
        assert!(r <= 1.0, "{name}: {r} (ratio to the round-off tolerance)");
    }
    // the only energy lost is the activation work −λ g₀ of the steps in which nodes touch down
    let (e0, en) = (sol.records[0].energy, sol.records[80].energy);
    let residual =
        en - e0 - s.activation_work - sol.records.iter().map(|r| r.switch_work).sum::<f64>();
    assert!(residual.abs() < 1e-6 * e0, "{residual}");
}

#[test]
fn the_block_on_block_example_keeps_its_horizontal_momentum_and_dissipates() {
    let scene = Scene::load(&example("multibody_block_on_block.toml")).expect("valid");
    let Solution::Multibody(sol) = scene.run().expect("runs") else {
        panic!("a multibody solution")
    };
    let s = sol.summary();
    assert!(s.momentum_ratio_x <= 1.0, "{}", s.momentum_ratio_x);
    assert!(s.friction_ratio <= 1.0 && s.friction_work < 0.0, "{s:?}");
    assert!(s.identity_ratio <= 1.0, "{}", s.identity_ratio);
}

#[test]
fn a_gmsh_body_is_read_relative_to_the_scene_file() {
    let Scene::Multibody(s) =
        Scene::load(&example("multibody_gmsh_o_ring_on_pad.toml")).expect("valid")
    else {
        panic!("a multibody scene")
    };
    assert_eq!(s.names, ["ring", "pad"]);
    let ring = s.problem.bodies.body(0);
    let r = ring
        .data()
        .mesh
        .nodes()
        .iter()
        .map(|x| (x[0] * x[0] + (x[1] - 0.51).powi(2)).sqrt())
        .fold(0.0, f64::max);
    // o_ring.msh (outer radius 0.005, centre (0, 0.0051)) scaled by 100
    assert!((r - 0.5).abs() < 1e-9, "{r}");
}

#[test]
fn the_one_body_examples_stay_one_body_dynamic_scenes() {
    for name in ["dynamic_block_drop.toml", "dynamic_ring_impact_mu1.toml"] {
        let scene = Scene::load(&example(name)).expect("valid");
        assert!(matches!(scene, Scene::Dynamic(_)), "{name}");
        assert_eq!(scene.model(), "dynamic");
    }
}
