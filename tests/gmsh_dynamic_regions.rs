//! Dynamic scenes with `[[region]]`: a Gmsh body whose 2D physical groups carry their own density
//! and law. The body is the strip (0, 2) × (0, 1) of examples/meshes/bimaterial_strip.msh: region
//! "soft" = (0, 1) × (0, 1), region "stiff" = (1, 2) × (0, 1), both of area 1 exactly (every
//! boundary node lies on the squares' sides, so the triangles tile them).
//!
//! (1) An affine initial displacement u = (F − I) X has F_e = F on every element, so the stored
//! energy at t = 0 is Σ_r W_r(F) · area_r with the laws' energy densities written below (linear,
//! St Venant–Kirchhoff, neo-Hooke in plane strain): any element given the other region's law moves
//! it by |W_soft − W_stiff| |e|, far above round-off. (2) A rigid translation with velocity v has
//! kinetic energy Σ_r ρ_r area_r |v|²/2 and momentum Σ_r ρ_r area_r v, exactly, for the consistent
//! and the lumped mass: catches a wrong density map. (3) The energy identity BDS (1.48) of
//! Gonzalez's scheme (and of the midpoint rule on a linear body, condensed onto its contact dofs)
//! holds to the audit's round-off tolerance on two-region bodies: it fails when the internal force
//! or the stiffness uses another element → law map than the stored energy. (4) The typed errors.

use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::dynamic::solver::DynamicPath;
use contactlab::scene::dynamic::{DynamicScene, SceneBody};

const STRIP: &str = r#"
model = "dynamic"
[body]
shape = "gmsh"
file = "examples/meshes/bimaterial_strip.msh"
density = 1000.0
mass = "MASS"
[material]
MATERIAL
[time]
final_time = 0.001
steps = STEPS
scheme = "SCHEME"
[initial]
displacement = DISPLACEMENT
velocity = VELOCITY
REGIONS
"#;

/// The strip scene with `material` (the `[material]` keys), `regions` (the `[[region]]` tables)
/// and the initial state.
fn strip(material: &str, regions: &str, displacement: &str, velocity: &str) -> String {
    STRIP
        .replace("MASS", "consistent")
        .replace("MATERIAL", material)
        .replace("REGIONS", regions)
        .replace("DISPLACEMENT", displacement)
        .replace("VELOCITY", velocity)
        .replace("STEPS", "1")
        .replace("SCHEME", "gonzalez")
}

/// Lamé constants of plane strain from E and ν.
fn lame(young: f64, poisson: f64) -> (f64, f64) {
    (
        young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)),
        young / (2.0 * (1.0 + poisson)),
    )
}

type M2 = [[f64; 2]; 2];

fn ddot(a: &M2, b: &M2) -> f64 {
    a[0][0] * b[0][0] + a[0][1] * b[0][1] + a[1][0] * b[1][0] + a[1][1] * b[1][1]
}

/// W(F) of the plane-strain law `law` with (E, ν), written from the definitions:
/// linear W = λ/2 (tr ε)² + μ ε:ε, ε = sym(F) − I; St Venant–Kirchhoff W = λ/2 (tr E)² + μ E:E,
/// E = (FᵀF − I)/2; neo-Hooke W = μ/2 (tr FᵀF − 2 − 2 ln J) + λ/2 (ln J)², J = det F.
fn energy_density(law: &str, young: f64, poisson: f64, f: &M2) -> f64 {
    let (lambda, mu) = lame(young, poisson);
    let c = [
        [
            f[0][0] * f[0][0] + f[1][0] * f[1][0],
            f[0][0] * f[0][1] + f[1][0] * f[1][1],
        ],
        [
            f[0][1] * f[0][0] + f[1][1] * f[1][0],
            f[0][1] * f[0][1] + f[1][1] * f[1][1],
        ],
    ];
    match law {
        "linear" => {
            let s = 0.5 * (f[0][1] + f[1][0]);
            let eps = [[f[0][0] - 1.0, s], [s, f[1][1] - 1.0]];
            let tr = eps[0][0] + eps[1][1];
            0.5 * lambda * tr * tr + mu * ddot(&eps, &eps)
        }
        "st_venant_kirchhoff" => {
            let e = [
                [0.5 * (c[0][0] - 1.0), 0.5 * c[0][1]],
                [0.5 * c[1][0], 0.5 * (c[1][1] - 1.0)],
            ];
            let tr = e[0][0] + e[1][1];
            0.5 * lambda * tr * tr + mu * ddot(&e, &e)
        }
        "neo_hooke" => {
            let ln_j = (f[0][0] * f[1][1] - f[0][1] * f[1][0]).ln();
            0.5 * mu * (c[0][0] + c[1][1] - 2.0 - 2.0 * ln_j) + 0.5 * lambda * ln_j * ln_j
        }
        other => panic!("no law {other}"),
    }
}

/// F = I + ∇u of the affine initial displacement used below.
const F: M2 = [[1.1, 0.2], [-0.05, 0.95]];
const AFFINE: &str = r#"["0.1*x + 0.2*y", "-0.05*x - 0.05*y"]"#;

#[test]
fn stored_energy_of_an_affine_state_is_the_sum_of_the_regions_closed_forms() {
    // (body law for "soft", region law for "stiff"): the three laws, each region a different
    // one; the stiff region's `poisson` is left out in the first case (the body's applies).
    let cases = [
        (
            ("neo_hooke", 1.0e3, 0.3),
            "material = { law = \"st_venant_kirchhoff\", young = 3.0e3 }",
            ("st_venant_kirchhoff", 3.0e3, 0.3),
        ),
        (
            ("st_venant_kirchhoff", 2.0e3, 0.25),
            "material = { law = \"linear\", young = 7.0e3, poisson = 0.4 }",
            ("linear", 7.0e3, 0.4),
        ),
        (
            ("linear", 5.0e2, 0.2),
            "material = { law = \"neo_hooke\", young = 4.0e3, poisson = 0.35 }",
            ("neo_hooke", 4.0e3, 0.35),
        ),
    ];
    for ((law, e, nu), region, (law_r, e_r, nu_r)) in cases {
        let text = strip(
            &format!("law = \"{law}\"\nyoung = {e:e}\npoisson = {nu}"),
            &format!("[[region]]\ngroup = \"stiff\"\n{region}"),
            AFFINE,
            "[0.0, 0.0]",
        );
        let scene = DynamicScene::from_toml_str(&text, "strip").expect("valid scene");
        let sol = scene.solve().expect("runs");
        // area_soft = area_stiff = 1
        let (w_soft, w_stiff) = (
            energy_density(law, e, nu, &F),
            energy_density(law_r, e_r, nu_r, &F),
        );
        let expected = w_soft + w_stiff;
        let recorded = sol.audit.records[0].elastic;
        // Round-off: each element's F_e (P1 gradients of an affine field) and W_e(F_e) carry a
        // relative error of a few ε (|∂W/∂F| |F| / W ≲ 10 here), summed over N ≈ 60 elements:
        // |error| ≤ 10 · N ε Σ_r |W_r| area_r. A misassigned element moves the sum by
        // |W_soft − W_stiff| |e| ≳ 10⁻³ of it. Measured: 6.4e-14, 1.4e-14, 2.3e-13 (≤ 0.03 of
        // the bound).
        let n = match &scene.body {
            SceneBody::Plane(p) => p.elements().len() as f64,
            SceneBody::Bar(_) => unreachable!(),
        };
        let bound = 10.0 * n * f64::EPSILON * (w_soft.abs() + w_stiff.abs());
        let error = (recorded - expected).abs();
        eprintln!(
            "{law}/{law_r}: W = {recorded:e}, closed form {expected:e}, error {error:e} (bound \
             {bound:e}); W_soft = {w_soft:e}, W_stiff = {w_stiff:e}"
        );
        assert!(error <= bound, "{law}/{law_r}: error {error:e} > {bound:e}");
        assert!((w_soft - w_stiff).abs() > 1e6 * bound);
    }
}

#[test]
fn rigid_translation_has_the_kinetic_energy_and_momentum_of_the_regions_densities() {
    // body ρ = 1000 on "soft"; "stiff" ρ = 3000 with the body's material (left out)
    let v = [0.3, -0.7];
    let (rho_soft, rho_stiff) = (1000.0, 3000.0);
    for mass in ["consistent", "lumped"] {
        let text = strip(
            "law = \"neo_hooke\"\nyoung = 1e3\npoisson = 0.3",
            "[[region]]\ngroup = \"stiff\"\ndensity = 3000.0",
            "[0.0, 0.0]",
            &format!("[{}, {}]", v[0], v[1]),
        )
        .replace("mass = \"consistent\"", &format!("mass = \"{mass}\""));
        let scene = DynamicScene::from_toml_str(&text, "strip").expect("valid scene");
        let sol = scene.solve().expect("runs");
        let total_mass = rho_soft * 1.0 + rho_stiff * 1.0;
        let kinetic = 0.5 * total_mass * (v[0] * v[0] + v[1] * v[1]);
        let SceneBody::Plane(p) = &scene.body else {
            unreachable!()
        };
        let nodes = p.data().mesh.nodes().len();
        let vel = p.from_nodal(&(0..nodes).flat_map(|_| v).collect::<Vec<f64>>());
        let mut mv = vec![0.0; vel.len()];
        p.pattern().symmetric_mul(p.mass(), &vel, &mut mv);
        let momentum = (0..nodes).fold([0.0, 0.0], |m, i| {
            [
                m[0] + p.dof(i, 0).map_or(0.0, |d| mv[d]),
                m[1] + p.dof(i, 1).map_or(0.0, |d| mv[d]),
            ]
        });
        // Round-off: sums of ≈ 60 element masses (each ρ|e|/12 or ρ|e|/3) and ≈ 1000 products:
        // 4 · 1000 ε times the total.
        let tol = 4.0e3 * f64::EPSILON;
        let recorded = sol.audit.records[0].kinetic;
        eprintln!(
            "{mass}: kinetic {recorded:e} (closed form {kinetic:e}), momentum {momentum:?} \
             (closed form {:?})",
            [total_mass * v[0], total_mass * v[1]]
        );
        assert!((recorded - kinetic).abs() <= tol * kinetic, "{mass}");
        for c in 0..2 {
            let exact = total_mass * v[c];
            assert!(
                (momentum[c] - exact).abs() <= tol * exact.abs(),
                "{mass}: {c}"
            );
        }
        // the body's density alone would give 2000 |v|²/2: far off
        assert!((recorded - 0.5 * 2000.0 * 0.58).abs() > 0.1 * kinetic);
    }
}

#[test]
fn energy_identity_holds_to_round_off_on_two_region_bodies() {
    // neo-Hooke body ("soft") and a St Venant–Kirchhoff region ("stiff"), Gonzalez, no contact;
    // a linear body with a stiffer linear region, the midpoint rule, frictionless Signorini
    // contact on the bottom (the condensed path: K assembled once with each element's law).
    let nonlinear = strip(
        "law = \"neo_hooke\"\nyoung = 1e4\npoisson = 0.3",
        "[[region]]\ngroup = \"stiff\"\ndensity = 2500.0\nmaterial = { law = \"st_venant_kirchhoff\", young = 4e4 }",
        r#"["0.05*x*y", "-0.04*x"]"#,
        r#"["2*y", "-3*x + 1"]"#,
    )
    .replace("steps = 1", "steps = 50")
    .replace("final_time = 0.001", "final_time = 0.5");
    let linear = strip(
        "law = \"linear\"\nyoung = 1e4\npoisson = 0.3",
        "[[region]]\ngroup = \"stiff\"\ndensity = 2500.0\nmaterial = { young = 4e4 }\n\
         [contact]\nlevel = 0.0\ngroup = \"bottom\"\ntreatment = \"signorini\"",
        r#"["0.0", "0.001 + 0.01*x*(2 - x)"]"#,
        r#"["0.0", "-1"]"#,
    )
    .replace("steps = 1", "steps = 50")
    .replace("final_time = 0.001", "final_time = 0.5")
    .replace("scheme = \"gonzalez\"", "scheme = \"midpoint\"");
    for (name, text, path) in [
        ("neo-Hooke/SVK, Gonzalez", nonlinear, DynamicPath::Full),
        ("linear/linear, midpoint", linear, DynamicPath::Condensed),
    ] {
        let scene = DynamicScene::from_toml_str(&text, name).expect("valid scene");
        let sol = scene.solve().expect("runs");
        assert_eq!(sol.stats.path, Some(path), "{name}");
        let s = sol.audit.summary();
        let records = &sol.audit.records;
        let exchange =
            (records.last().unwrap().kinetic - records[0].kinetic).abs() / s.energy_scale;
        eprintln!(
            "{name}: drift (1.48) {:.2} of its tolerance ({:e} E_ref), kinetic ↔ elastic exchange \
             {exchange:.3} E_ref",
            s.drift_ratio_1_48, s.max_drift_1_48
        );
        assert!(s.drift_ratio_1_48 <= 1.0, "{name}: {s:?}");
        assert!(s.drift_ratio_1_49 <= 1.0, "{name}: {s:?}");
        // the run exchanges energy between its forms: the identity is not trivially met
        assert!(exchange > 1e-3, "{name}: exchange {exchange:e}");
    }
}

#[test]
fn region_errors_are_typed_and_named() {
    let material = "law = \"neo_hooke\"\nyoung = 1e3\npoisson = 0.3";
    let err = |regions: &str| {
        DynamicScene::from_toml_str(&strip(material, regions, "[0.0, 0.0]", "[0.0, 0.0]"), "x")
            .unwrap_err()
            .to_string()
    };
    // an unknown group lists the file's regions
    let e = err("[[region]]\ngroup = \"steel\"\ndensity = 2.0");
    assert!(
        e.contains("region[0].group") && e.contains("\"soft\", \"stiff\""),
        "{e}"
    );
    // overlapping regions name both
    let e = err("[[region]]\ngroup = \"stiff\"\n[[region]]\ngroup = \"soft\"\n[[region]]\ngroup = \"stiff\"\ndensity = 2.0");
    assert!(
        e.contains("region[2].group") && e.contains("region[0] (\"stiff\")"),
        "{e}"
    );
    // the region's own values are checked under its name
    let e = err("[[region]]\ngroup = \"stiff\"\ndensity = -1.0");
    assert!(e.contains("region[0].density"), "{e}");
    let e = err("[[region]]\ngroup = \"stiff\"\nmaterial = { law = \"mooney\" }");
    assert!(e.contains("region[0].material.law"), "{e}");
    let e = err("[[region]]\ngroup = \"stiff\"\nmaterial = { poisson = 0.5 }");
    assert!(e.contains("region[0].material.poisson"), "{e}");
    let e = err("[[region]]\ngroup = \"stiff\"\nmaterial = { shear = 1.0 }");
    assert!(e.contains("shear"), "{e}");
    // a body not read from a Gmsh file has no groups
    let rect = strip(
        material,
        "[[region]]\ngroup = \"stiff\"",
        "[0.0, 0.0]",
        "[0.0, 0.0]",
    )
    .replace(
        "shape = \"gmsh\"\nfile = \"examples/meshes/bimaterial_strip.msh\"",
        "shape = \"rectangle\"\nsize = [2.0, 1.0]\ndivisions = [4, 2]",
    );
    let e = DynamicScene::from_toml_str(&rect, "x")
        .unwrap_err()
        .to_string();
    assert!(e.contains("region[0].group") && e.contains("Gmsh"), "{e}");
    let bar = "model = \"dynamic\"\n[body]\nshape = \"bar\"\nlength = 1.0\nelements = 4\n\
               density = 1.0\n[material]\nlaw = \"linear\"\nyoung = 1.0\n[time]\nfinal_time = 1.0\n\
               steps = 2\nscheme = \"midpoint\"\n[[region]]\ngroup = \"core\"\n";
    let e = DynamicScene::from_toml_str(bar, "bar")
        .unwrap_err()
        .to_string();
    assert!(e.contains("region[0].group") && e.contains("Gmsh"), "{e}");
}

#[test]
fn one_material_body_is_unchanged_by_a_region_with_the_bodys_own_values() {
    // A region that restates the body's density and law gives the same bits as no region: the
    // element → material table only selects, it does not recompute.
    let material = "law = \"neo_hooke\"\nyoung = 1e4\npoisson = 0.3";
    let run = |regions: &str| {
        let text = strip(material, regions, AFFINE, r#"["2*y", "-3*x"]"#)
            .replace("steps = 1", "steps = 5");
        let sol = DynamicScene::from_toml_str(&text, "x")
            .unwrap()
            .solve()
            .unwrap();
        (
            sol.final_displacement,
            sol.audit.records.last().unwrap().elastic,
        )
    };
    let plain = run("");
    let restated = run(
        "[[region]]\ngroup = \"stiff\"\ndensity = 1000.0\nmaterial = { law = \"neo_hooke\", young = 1e4, poisson = 0.3 }",
    );
    assert_eq!(plain, restated);
}
