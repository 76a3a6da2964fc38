//! The O-ring example (`examples/scenes/dynamic_gmsh_o_ring.toml`) is the ParaView walk-through
//! of the README: its output times must show the impact. The contact lasts from about 6e-5 to
//! 9.8e-4; frames at 0, 1e-3, … only would all have zero contact arrays. Goal: at least
//! [`MIN_FRAMES_IN_CONTACT`] of the example's output frames carry a non-zero contact pressure
//! (the `contact_pressure` array of the `.vtu` files is the contact nodes' normal force N per
//! weight, recorded beside each snapshot).

use std::path::PathBuf;

use contactlab::model::dynamic::record::run_recorded;
use contactlab::scene::any::Scene;

const MIN_FRAMES_IN_CONTACT: usize = 8;

#[test]
fn o_ring_example_writes_frames_inside_the_contact() {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/dynamic_gmsh_o_ring.toml");
    let Scene::Dynamic(scene) = Scene::load(&path).expect("the example loads") else {
        panic!("the O-ring example is a one-body dynamic scene");
    };
    let times = scene.params.snapshot_times.clone();
    let solver = scene.solver().expect("solver");
    let run = run_recorded(&solver, &times);
    run.result.as_ref().expect("the example runs");
    assert_eq!(run.snapshot_states.len(), times.len());
    let in_contact: Vec<f64> = run
        .snapshots
        .iter()
        .zip(&run.snapshot_states)
        .filter(|(_, s)| s.forces.iter().any(|f| f.normal > 0.0))
        .map(|((t, _), _)| *t)
        .collect();
    assert!(
        in_contact.len() >= MIN_FRAMES_IN_CONTACT,
        "frames with contact pressure at {in_contact:?} of {times:?}"
    );
}
