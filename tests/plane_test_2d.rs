//! The paper's Test 2D (Fernández & Sofonea 2004, §4.2): the library's constructor gives the
//! problem the example scene describes (rollers, β = 1000, 24 × 24): the same run, to the last
//! bit.

use contactlab::model::quasistatic::plane::{PlaneProblem, Support, Test2dParams};
use contactlab::model::quasistatic::plane_solver::PlaneSolver;
use contactlab::scene::plane::PlaneScene;

#[test]
fn the_constructor_and_the_example_scene_give_the_same_run() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/plane_paper_test_2d.toml"
    );
    let text = std::fs::read_to_string(path).expect("example scene");
    let scene = PlaneScene::from_toml_str(&text, path).expect("valid scene");
    let p = PlaneProblem::fernandez_sofonea_test_2d(Test2dParams {
        divisions: 24,
        support: Support::FixX,
        ..Default::default()
    })
    .expect("valid problem");
    let run = |problem: &PlaneProblem| {
        let mut s = PlaneSolver::new(problem, scene.grid.clone(), scene.scheme, scene.params)
            .expect("solver");
        s.solve(&scene.output).expect("runs")
    };
    let (a, b) = (run(&scene.problem), run(&p));
    assert_eq!(a.snapshots.len(), b.snapshots.len());
    for (x, y) in a.snapshots.iter().zip(&b.snapshots) {
        assert!(x
            .u
            .iter()
            .zip(&y.u)
            .all(|(p, q)| p.to_bits() == q.to_bits()));
    }
}
