//! Multibody scenes: the setting is a dynamic scene of `[[body]]` sections and `[[contact_pair]]`
//! sections; the goal is to pin that the documented format parses into the solver's problem
//! (bodies, pairs with their passes, initial rigid motion, parameters), that a `[body]` table
//! stays the one-body scene, and that every invalid value is refused with an error naming the key
//! as written, the value and what was expected.

use crate::model::multibody::constraint::Enforcement;
use crate::model::multibody::scheme::MultibodyScheme;
use crate::model::multibody::solver::PairMaster;
use crate::scene::multibody::MultibodyScene;
use crate::scene::Scene;

/// Two small rectangles, the upper one thrown down-right onto the lower one, which rests on the
/// foundation.
const BLOCKS: &str = r#"
model = "dynamic"
title = "blocks"
[[body]]
name = "lower"
shape = "rectangle"
origin = [0.0, 0.0]
size = [2.0, 0.5]
divisions = [4, 1]
density = 1.0
material = { law = "st_venant_kirchhoff", young = 100.0, poisson = 0.3 }
body_force = [0.0, -1.0]
[[body]]
name = "upper"
shape = "rectangle"
origin = [0.5, 0.6]
size = [1.0, 0.5]
divisions = [2, 1]
density = 2.0
material = { law = "neo_hooke", young = 100.0, poisson = 0.3 }
velocity = [1.0, -1.0]
angular_velocity = 0.5
[[contact_pair]]
slave = { body = "upper", sides = ["bottom"] }
master = { body = "lower", sides = ["top"] }
friction = 0.2
[[contact_pair]]
slave = { body = "lower", sides = ["bottom"] }
foundation = { level = 0.0 }
[time]
final_time = 0.05
steps = 5
[output]
times = [0.0, 0.05]
"#;

fn load(text: &str) -> Result<Scene, String> {
    Scene::from_toml_str(text, "blocks.toml").map_err(|e| e.to_string())
}

fn multibody(text: &str) -> MultibodyScene {
    match load(text).unwrap_or_else(|e| panic!("valid: {e}")) {
        Scene::Multibody(s) => *s,
        other => panic!("a {} scene", other.model()),
    }
}

/// The error of `text`, which must name every one of `parts`.
fn refused(text: &str, parts: &[&str]) {
    let e = match load(text) {
        Ok(_) => panic!("accepted, expected an error naming {parts:?}"),
        Err(e) => e,
    };
    for p in parts {
        assert!(e.contains(p), "the error does not name {p:?}: {e}");
    }
}

#[test]
fn the_blocks_scene_becomes_the_solvers_problem() {
    let s = multibody(BLOCKS);
    assert_eq!(s.names, ["lower", "upper"]);
    assert_eq!(s.problem.bodies.len(), 2);
    assert_eq!(s.problem.scheme, MultibodyScheme::EnergyMomentum);
    assert_eq!(s.problem.pairs.len(), 2);
    let p0 = &s.problem.pairs[0];
    assert_eq!(p0.slave.body, 1);
    assert_eq!(p0.slave.nodes.len(), 3, "the upper block's bottom: 3 nodes");
    assert!(matches!(&p0.master, PairMaster::Surface(m) if m.body == 0 && m.segments.len() == 4));
    assert_eq!(p0.law.friction, 0.2);
    assert!(matches!(p0.law.enforcement, Enforcement::Lagrange));
    assert!(matches!(&s.problem.pairs[1].master, PairMaster::Foundation(f) if f.level == 0.0));
    assert_eq!(s.params.snapshot_times, [0.0, 0.05]);
    // the upper block's rigid motion about its centre of mass (1.0, 0.85): v + ω e_z × (X − c)
    let set = &s.problem.bodies;
    let corner = 0; // (0.5, 0.6)
    let v = |c| set.dof(1, corner, c).map(|d| s.problem.initial_velocity[d]);
    assert!((v(0).unwrap() - (1.0 - 0.5 * (0.6 - 0.85))).abs() < 1e-14);
    assert!((v(1).unwrap() - (-1.0 + 0.5 * (0.5 - 1.0))).abs() < 1e-14);
    assert!(s.problem.initial_velocity[set.range(0)]
        .iter()
        .all(|&x| x == 0.0));
}

#[test]
fn the_blocks_scene_runs_with_its_snapshots() {
    let scene = load(BLOCKS).expect("valid");
    assert_eq!(scene.model(), "multibody");
    let crate::scene::Solution::Multibody(sol) = scene.run().expect("runs") else {
        panic!("a multibody solution");
    };
    assert_eq!(sol.records.len(), 6);
    assert_eq!(sol.snapshots.len(), 2);
    assert_eq!(sol.snapshots[1].step, 5);
}

#[test]
fn a_body_table_stays_the_one_body_dynamic_scene() {
    let text = r#"
model = "dynamic"
[body]
shape = "rectangle"
size = [1.0, 0.5]
divisions = [2, 1]
density = 1.0
[material]
law = "linear"
young = 10.0
poisson = 0.3
[time]
final_time = 0.01
steps = 2
scheme = "midpoint"
"#;
    let scene = load(text).expect("valid");
    assert_eq!(scene.model(), "dynamic");
    let Scene::Dynamic(d) = &scene else {
        panic!("the one-body scene");
    };
    // its fast path: a linear body condenses
    assert_eq!(
        d.solver().expect("solver").path(),
        crate::model::dynamic::solver::DynamicPath::Condensed
    );
}

#[test]
fn a_two_pass_pair_becomes_two_pairs_with_the_roles_exchanged() {
    let text = BLOCKS.replace("friction = 0.2", "friction = 0.2\npass = \"two\"");
    let s = multibody(&text);
    assert_eq!(s.problem.pairs.len(), 3);
    assert_eq!(s.problem.pairs[1].slave.body, 0);
    assert!(matches!(&s.problem.pairs[1].master, PairMaster::Surface(m) if m.body == 1));
    assert!(s.origins[1].exchanged && s.origins[1].section == 0);
    assert_eq!(s.origins[2].section, 1);
}

#[test]
fn names_default_to_the_position_and_penalty_takes_its_stiffness() {
    let text = BLOCKS
        .replace("name = \"lower\"\n", "")
        .replace("name = \"upper\"\n", "")
        .replace("\"upper\"", "\"body 1\"")
        .replace("\"lower\"", "\"body 0\"")
        .replace(
            "friction = 0.2",
            "enforcement = \"penalty\"\nstiffness = 1e4",
        );
    let s = multibody(&text);
    assert_eq!(s.names, ["body 0", "body 1"]);
    assert!(matches!(
        s.problem.pairs[0].law.enforcement,
        Enforcement::Penalty { stiffness } if stiffness == 1e4
    ));
}

#[test]
fn compliant_takes_its_stiffness_and_keeps_friction() {
    let text = BLOCKS.replace(
        "friction = 0.2",
        "friction = 0.2\nenforcement = \"compliant\"\nstiffness = 1e5",
    );
    let s = multibody(&text);
    assert!(matches!(
        s.problem.pairs[0].law.enforcement,
        Enforcement::Compliant { stiffness } if stiffness == 1e5
    ));
    assert_eq!(s.problem.pairs[0].law.friction, 0.2);
    // without its stiffness: refused, naming the key
    refused(
        &BLOCKS.replace("friction = 0.2", "enforcement = \"compliant\""),
        &["stiffness"],
    );
}

#[test]
fn an_unknown_key_is_named() {
    refused(
        &BLOCKS.replace("density = 2.0", "density = 2.0\ncolour = \"red\""),
        &["colour"],
    );
    refused(
        &BLOCKS.replace("friction = 0.2", "friction = 0.2\nmu = 0.2"),
        &["mu"],
    );
}

#[test]
fn an_unknown_body_name_is_named_with_the_names() {
    refused(
        &BLOCKS.replace(
            "foundation = { level = 0.0 }",
            "master = { body = \"nobody\" }",
        ),
        &[
            "contact_pair[1].master.body",
            "\"nobody\"",
            "\"lower\", \"upper\"",
        ],
    );
    refused(
        &BLOCKS.replace("{ body = \"upper\", sides", "{ body = \"uper\", sides"),
        &["contact_pair[0].slave.body", "\"uper\""],
    );
}

#[test]
fn a_pair_of_a_body_with_itself_is_refused() {
    refused(
        &BLOCKS.replace(
            "master = { body = \"lower\", sides = [\"top\"] }",
            "master = { body = \"upper\", sides = [\"top\"] }",
        ),
        &["contact_pair[0].master.body", "\"upper\"", "self-contact"],
    );
}

#[test]
fn a_selection_of_no_edge_is_refused() {
    refused(
        &BLOCKS.replace(
            "slave = { body = \"upper\", sides = [\"bottom\"] }",
            "slave = { body = \"upper\", where = \"x - 10\" }",
        ),
        &["contact_pair[0].slave.where", "selects none"],
    );
    refused(
        &BLOCKS.replace(
            "master = { body = \"lower\", sides = [\"top\"] }",
            "master = { body = \"lower\", group = \"top\" }",
        ),
        &["contact_pair[0].master.group", "Gmsh"],
    );
    let held = BLOCKS.replace(
        "angular_velocity = 0.5",
        "angular_velocity = 0.5\n[[body.dirichlet]]\nwhere = \"-1\"\nsupport = \"clamped\"",
    );
    refused(&held, &["body[1].dirichlet[0].where", "selects none"]);
}

#[test]
fn penalty_needs_its_stiffness_and_refuses_friction() {
    refused(
        &BLOCKS.replace("friction = 0.2", "enforcement = \"penalty\""),
        &["contact_pair[0].stiffness", "(missing)", "ε > 0"],
    );
    refused(
        &BLOCKS.replace(
            "friction = 0.2",
            "friction = 0.2\nenforcement = \"penalty\"\nstiffness = 1e3",
        ),
        &["contact_pair[0].friction", "0.2", "lagrange"],
    );
    refused(
        &BLOCKS.replace("friction = 0.2", "stiffness = 1e3"),
        &["contact_pair[0].stiffness", "1000", "lagrange"],
    );
    refused(
        &BLOCKS.replace(
            "friction = 0.2",
            "enforcement = \"penalty\"\nstiffness = 0.0",
        ),
        &["contact_pair[0].stiffness", "0"],
    );
    refused(
        &BLOCKS.replace("friction = 0.2", "friction = -0.1"),
        &["contact_pair[0].friction", "-0.1"],
    );
}

#[test]
fn two_passes_with_the_foundation_and_a_master_beside_a_foundation_are_refused() {
    refused(
        &BLOCKS.replace(
            "foundation = { level = 0.0 }",
            "foundation = { level = 0.0 }\npass = \"two\"",
        ),
        &["contact_pair[1].pass", "\"two\"", "single"],
    );
    refused(
        &BLOCKS.replace(
            "foundation = { level = 0.0 }",
            "foundation = { level = 0.0 }\nmaster = { body = \"upper\" }",
        ),
        &["contact_pair[1].foundation", "either master"],
    );
    refused(
        &BLOCKS.replace("foundation = { level = 0.0 }\n", ""),
        &["contact_pair[1].master", "(missing)"],
    );
}

#[test]
fn a_node_constrained_twice_against_one_master_is_refused() {
    let twice = format!(
        "{BLOCKS}\n[[contact_pair]]\nslave = {{ body = \"upper\", where = \"0.7 - y\" }}\n\
         master = {{ body = \"lower\" }}\n"
    );
    refused(&twice, &["contact_pair[2].slave", "shares node"]);
    let reversed = BLOCKS.replace("friction = 0.2", "friction = 0.2\npass = \"two\"")
        + "\n[[contact_pair]]\nslave = { body = \"lower\", sides = [\"top\"] }\n\
           master = { body = \"upper\" }\n";
    refused(
        &reversed,
        &["contact_pair[2].slave", "contact_pair[0].pass"],
    );
}

#[test]
fn body_values_are_named_as_written() {
    refused(
        &BLOCKS.replace(
            "young = 100.0, poisson = 0.3 }\nbody_force",
            "young = 100.0, poisson = 0.5 }\nbody_force",
        ),
        &["body[0].material.poisson", "0.5"],
    );
    refused(
        &BLOCKS.replace("law = \"neo_hooke\"", "law = \"rubber\""),
        &["body[1].material.law", "\"rubber\"", "\"neo_hooke\""],
    );
    refused(
        &BLOCKS.replace("density = 2.0", "density = -2.0"),
        &["body[1].density", "-2"],
    );
    refused(
        &BLOCKS.replace("divisions = [2, 1]", "divisions = [2, 1]\nradius = 1.0"),
        &["body[1].radius", "shape = \"rectangle\""],
    );
    refused(
        &BLOCKS.replace("size = [1.0, 0.5]\n", ""),
        &["body[1].size", "(missing)"],
    );
    refused(
        &BLOCKS.replace(
            "shape = \"rectangle\"\norigin = [0.5",
            "shape = \"bar\"\norigin = [0.5",
        ),
        &["body[1].shape", "\"bar\"", "\"annulus\""],
    );
    refused(
        &BLOCKS.replace("name = \"upper\"", "name = \"lower\""),
        &["body[1].name", "\"lower\"", "body[0]"],
    );
    refused(
        &BLOCKS.replace("body_force = [0.0, -1.0]", "body_force = [0.0, \"-1 +\"]"),
        &["body[0].body_force[1]"],
    );
    refused(
        &BLOCKS.replace("velocity = [1.0, -1.0]", "velocity = [1.0, -1.0, 0.0]"),
        &["velocity", "expected exactly 2"],
    );
}

#[test]
fn non_finite_and_misplaced_values_are_named() {
    refused(
        &BLOCKS.replace("density = 2.0", "density = nan"),
        &["body[1].density", "NaN"],
    );
    refused(
        &BLOCKS.replace("level = 0.0", "level = inf"),
        &["contact_pair[1].foundation.level"],
    );
    refused(
        &BLOCKS.replace(
            "material = { law = \"neo_hooke\", young = 100.0, poisson = 0.3 }",
            "material = [\"neo_hooke\", 100.0, 0.3]",
        ),
        &["body[1].material", "a table"],
    );
    refused(
        &BLOCKS.replace(
            "slave = { body = \"upper\", sides = [\"bottom\"] }",
            "slave = \"upper\"",
        ),
        &["contact_pair[0].slave", "a table"],
    );
}

#[test]
fn time_output_and_solver_values_are_named() {
    refused(
        &BLOCKS.replace("times = [0.0, 0.05]", "times = [0.0, 0.5]"),
        &["output.times[1]", "0.5", "final_time"],
    );
    refused(&BLOCKS.replace("steps = 5", "steps = 0"), &["time.steps"]);
    refused(
        &BLOCKS.replace("final_time = 0.05", "final_time = -1.0"),
        &["time.final_time", "-1"],
    );
    refused(
        &BLOCKS.replace("steps = 5", "steps = 5\nscheme = \"gonzalez\""),
        &["gonzalez", "energy_momentum"],
    );
    refused(
        &format!("{BLOCKS}[solver]\ntolerance = 2.0\n"),
        &["solver.tolerance", "2", "(0, 1)"],
    );
    refused(
        &format!("{BLOCKS}[solver]\nmax_iterations = 0\n"),
        &["solver.max_iterations"],
    );
    refused(
        &format!("{BLOCKS}[solver]\nsearch_margin = 0.0\n"),
        &["solver.search_margin"],
    );
}

#[test]
fn an_oversized_scene_is_refused_before_its_mesh_is_built() {
    refused(
        &BLOCKS.replace("divisions = [4, 1]", "divisions = [1000000, 1000000]"),
        &["body[0].divisions", "[1000000, 1000000]", "fits in memory"],
    );
    refused(
        &BLOCKS.replace("steps = 5", "steps = 1000000000000"),
        &["time.steps", "fits in memory"],
    );
}

#[test]
fn no_body_and_the_model_multibody_are_refused() {
    refused(
        "model = \"dynamic\"\nbody = []\n[time]\nfinal_time = 1.0\nsteps = 1\n",
        &["body", "at least one"],
    );
    refused(
        &BLOCKS.replace("model = \"dynamic\"", "model = \"multibody\""),
        &["model", "\"dynamic\"", "[[body]]"],
    );
}
