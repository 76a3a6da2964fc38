#[path = "../benches/common/multibody_scenes.rs"]
mod multibody_scenes;

#[test]
#[ignore]
fn probe() {
    let which = std::env::var("PROBE").unwrap_or_default();
    let s = if which == "one" {
        multibody_scenes::one_ring_on_foundation(1).unwrap()
    } else {
        multibody_scenes::two_rings(1).unwrap()
    };
    let sol = s.solve().unwrap();
    println!("{which}: {:?}", sol.stats);
}
