//! The dynamic Newton method's stopping test (`model::dynamic::newton`): a step has converged when
//! the sets are unchanged and ‖R‖_∞ ≤ tol · s, or when every free row is within its computed
//! round-off floor 32 ε Σ|terms of the row| — a stop that the run's statistics count.
//!
//! Setting: a steel block (neo-Hooke, E = 2e11, ρ = 7800) resting under gravity on a compliant
//! foundation, with tiny steps. The stress of a finite-strain law is computed from C − I and
//! carries an error ε (λ + 2μ) whatever the load, so the residual of a row cannot get below
//! ε (λ + 2μ) |∇φ| |e| while its largest term is the weight ρ g |e|: the relative floor
//! ε c² / (g h) ≈ 3e-8 lies four decades above the default tolerance 1e-12 and 300 times above
//! the band (100 × tol after stagnation) the previous test accepted, so the run used to stop with
//! "did not converge". Goal: it converges, at its floor, counted; and a step that genuinely does
//! not converge (one iteration allowed on an impact step) is still a typed error whose message
//! sets the relative residual beside the relative tolerance and the relative floor.

use contactlab::error::{Error, SolveError};
use contactlab::scene::dynamic::DynamicScene;

const STEEL_BLOCK: &str = r#"
model = "dynamic"
title = "steel block resting under gravity, tiny steps"

[body]
shape = "rectangle"
origin = [0.0, 0.0]
size = [0.1, 0.05]
divisions = [16, 8]
density = 7800.0

[material]
law = "neo_hooke"
young = 2e11
poisson = 0.3

[time]
final_time = 1e-4
steps = 20
scheme = "gonzalez"

[body_force]
value = [0.0, -76518.0]

[contact]
level = 0.0
sides = ["bottom"]
treatment = "energy_consistent"
stiffness = 1e13
"#;

#[test]
fn steel_block_at_rest_converges_at_its_round_off_floor_above_the_old_band() {
    let scene = DynamicScene::from_toml_str(STEEL_BLOCK, "steel_block").expect("valid scene");
    let sol = scene.solve().expect("the floor is convergence");
    let stats = &sol.stats;
    eprintln!(
        "floor stops {} of {} steps, max relative residual {:e}",
        stats.newton_floor_stops, stats.steps, stats.max_newton_residual
    );
    assert!(stats.newton_floor_stops > 0, "{stats:?}");
    // the previous test accepted at most 100 × 1e-12 (relative) after stagnation
    assert!(
        stats.max_newton_residual > 100.0 * 1e-12,
        "the old band would have accepted this run: {stats:?}"
    );
    // and the floor is what it should be: ε c² / (g h) within the floor factor and the row's term count
    let c2 = 2e11 * 0.7 / (1.3 * 0.4) / 7800.0;
    let predicted = f64::EPSILON * c2 / (9.81 * 0.1 / 16.0);
    assert!(
        stats.max_newton_residual < 16.0 * 8.0 * predicted,
        "residual {:e} against the predicted floor {predicted:e}",
        stats.max_newton_residual
    );
}

#[test]
fn one_iteration_on_an_impact_step_is_a_typed_error_comparing_relative_numbers() {
    let scene = STEEL_BLOCK.replace(
        "[body_force]\nvalue = [0.0, -76518.0]",
        "[initial]\nvelocity = [0.0, -1.0]",
    ) + "\n[solver]\nmax_iterations = 1\n";
    let scene = DynamicScene::from_toml_str(&scene, "impact").expect("valid scene");
    let err = scene
        .solve()
        .expect_err("one iteration cannot solve an impact step");
    let Error::Solve(SolveError::DynamicNewtonNotConverged {
        residual,
        tolerance,
        floor,
        excess,
        ..
    }) = &err
    else {
        panic!("expected DynamicNewtonNotConverged, got {err}");
    };
    assert!(*residual > *tolerance && *residual > *floor, "{err}");
    assert!(*excess > 1.0, "{err}");
    let message = err.to_string();
    eprintln!("{message}");
    for part in [
        "relative residual",
        "relative tolerance",
        "relative round-off floor",
    ] {
        assert!(message.contains(part), "{message}");
    }
}
