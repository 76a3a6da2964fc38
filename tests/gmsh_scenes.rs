//! Gmsh meshes in scenes. (1) The 8 × 8 unit square read from a `.msh` file (the rectangle's own
//! triangles, in Gmsh's node order, coordinates off by ≤ 2·10⁻¹²) gives the same nodal solution
//! as the generated rectangle, node by node (catches a mis-ordered node or element map, a group
//! on the wrong side). (2) A strip of two materials in series under a constant end traction
//! (plane strain, rollers on x = 0 and y = 0): the static solution is piecewise linear with its
//! kink on the interface x = 1, a mesh line, so it lies in V^h; with A = τ B in both materials
//! the implicit scheme's steps are u_n = (1 − r^n) u_s, r = τ/(τ + k), exactly (closed form
//! below) — any error above round-off means a wrong element → region map or law.

use contactlab::scene::plane::PlaneScene;

const SQUARE: &str = r#"
model = "plane"
[geometry]
GEOMETRY
[time]
final_time = 1.0
steps = 8
scheme = "midpoint"
[viscosity]
law = "paper"
mu = 30.0
eta = 20.0
[elasticity]
law = "plane_stress"
young = 100.0
poisson = 0.3
[[dirichlet]]
SIDES_LEFT
support = "clamped"
[[traction]]
SIDES_TOP
value = [0.0, "-10*(1 - x)*t"]
[contact]
SIDES_BOTTOM
law = "lubricated"
beta = 100.0
p0 = 2.0
[output]
times = [1.0]
"#;

#[test]
fn gmsh_unit_square_gives_the_rectangles_solution_node_by_node() {
    let rect = SQUARE
        .replace("GEOMETRY", "size = [1.0, 1.0]\ndivisions = [8, 8]")
        .replace("SIDES_LEFT", "sides = [\"left\", \"right\"]")
        .replace("SIDES_TOP", "sides = [\"top\"]")
        .replace("SIDES_BOTTOM", "sides = [\"bottom\"]");
    let a = PlaneScene::from_toml_str(&rect, "rect").unwrap();
    let sa = a.solve().unwrap();
    for file in [
        "unit_square_8.msh",
        "unit_square_8_binary.msh",
        "unit_square_8_v22.msh",
    ] {
        let text = SQUARE
            .replace(
                "GEOMETRY",
                &format!("shape = \"gmsh\"\nfile = \"examples/meshes/{file}\""),
            )
            .replace("SIDES_LEFT", "where = \"abs(x - 0.5) - 0.49\"")
            .replace("SIDES_TOP", "group = \"top\"")
            .replace("SIDES_BOTTOM", "group = \"bottom\"");
        let b = PlaneScene::from_toml_str(&text, file).unwrap();
        let sb = b.solve().unwrap();
        let (na, nb) = (a.problem.mesh.nodes(), b.problem.mesh.nodes());
        let scale = sa.snapshots[0].u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut worst = 0.0f64;
        for (j, q) in nb.iter().enumerate() {
            let i = na
                .iter()
                .position(|p| (p[0] - q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9)
                .expect("every Gmsh node is a rectangle node");
            for c in 0..2 {
                let d = (sa.snapshots[0].u[2 * i + c] - sb.snapshots[0].u[2 * j + c]).abs();
                worst = worst.max(d / scale);
            }
        }
        // The files' coordinates are off the grid by δ ≤ 2·10⁻¹² (h = 1/8): the solutions differ
        // by O(κ δ / h) ≈ 10⁻¹⁰ relative at most, with κ ≈ 4 n²/π² ≈ 26 the stiffness condition.
        eprintln!("{file}: relative nodal difference {worst:e}");
        assert!(worst < 1e-9, "{file}: relative nodal difference {worst:e}");
    }
}

const STRIP: &str = r#"
model = "plane"
[geometry]
shape = "gmsh"
file = "examples/meshes/bimaterial_strip.msh"
[time]
final_time = 1.0
steps = 10
scheme = "implicit"
[viscosity]
law = "isotropic"
a1 = 0.5
a2 = 1.0
[elasticity]
law = "isotropic"
a1 = 1.0
a2 = 2.0
[[region]]
group = "stiff"
viscosity = { law = "isotropic", a1 = 2.25, a2 = 1.5 }
elasticity = { law = "isotropic", a1 = 4.5, a2 = 3.0 }
[[dirichlet]]
group = "left"
support = "fix_x"
[[dirichlet]]
group = "bottom"
support = "fix_y"
[[traction]]
group = "right"
value = [0.6, 0.0]
[output]
times = [0.1, 0.5, 1.0]
"#;

#[test]
fn bimaterial_strip_matches_its_closed_form_to_round_off() {
    // σ = λ tr ε I + 2μ ε (a1 = λ, a2 = 2μ): soft λ = 1, μ = 1; stiff λ = 4.5, μ = 1.5; A = τ B,
    // τ = 1/2. Uniaxial stress σ_xx = t0, σ_yy = 0: ε_yy = −λ t0 / (4μ(λ + μ)) = −t0/8 in both,
    // ε_xx = (λ + 2μ) t0 / (4μ(λ + μ)) = 3 t0/8 (soft), 5 t0/24 (stiff).
    let t0 = 0.6;
    let (exx_soft, exx_stiff, eyy) = (3.0 * t0 / 8.0, 5.0 * t0 / 24.0, -t0 / 8.0);
    let u_static = |x: f64, y: f64| {
        let ux = if x <= 1.0 {
            exx_soft * x
        } else {
            exx_soft + exx_stiff * (x - 1.0)
        };
        [ux, eyy * y]
    };
    let scene = PlaneScene::from_toml_str(STRIP, "strip").unwrap();
    assert_eq!(scene.problem.regions.len(), 1);
    let sol = scene.solve().unwrap();
    let (tau, k) = (0.5, 0.1);
    let r: f64 = tau / (tau + k);
    let nodes = scene.problem.mesh.nodes();
    let umax = exx_soft + exx_stiff;
    for snap in &sol.snapshots {
        let n = snap.n as i32;
        let factor = 1.0 - r.powi(n);
        let mut worst = 0.0f64;
        for (i, p) in nodes.iter().enumerate() {
            for (c, u) in u_static(p[0], p[1]).into_iter().enumerate() {
                worst = worst.max((snap.u[2 * i + c] - factor * u).abs());
            }
        }
        // Round-off: 16 ε κ̂ n max|u| with κ̂ = 4/(π² h²) × 3 (stiffness contrast) ≈ 80 for
        // h ≈ 0.25, n ≤ 10 steps: ≈ 3·10⁻¹² × max|u|.
        let bound = 16.0 * f64::EPSILON * 80.0 * 10.0 * umax;
        eprintln!(
            "t = {}: max nodal error {worst:e} (bound {bound:e})",
            snap.t
        );
        assert!(
            worst <= bound,
            "t = {}: max nodal error {worst:e} > {bound:e}",
            snap.t
        );
    }
}

#[test]
fn a_group_the_file_lacks_is_named_with_the_files_groups() {
    let text = STRIP.replace("group = \"right\"", "group = \"lid\"");
    let e = PlaneScene::from_toml_str(&text, "strip")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("traction[0].group") && e.contains("\"bottom\", \"left\", \"right\", \"top\""),
        "{e}"
    );
    let text = STRIP.replace("group = \"stiff\"", "group = \"steel\"");
    let e = PlaneScene::from_toml_str(&text, "strip")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("region[0].group") && e.contains("\"soft\", \"stiff\""),
        "{e}"
    );
    let text = STRIP.replace("group = \"left\"", "group = \"left\"\nsides = [\"left\"]");
    let e = PlaneScene::from_toml_str(&text, "strip")
        .unwrap_err()
        .to_string();
    assert!(e.contains("exactly one of sides, where and group"), "{e}");
}
