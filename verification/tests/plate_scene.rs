//! `verify scene` with the rotating plate (`model = "rotating_plate"`): the two example scenes run
//! and write `solution.json`, their sweeps and map with finite numbers. The Campbell example's
//! sweep is checked against the waves the plate's structure (72)–(74) predicts from the
//! non-rotating frequencies it writes: |Im λ| = ω_{n,m} + nΩ and |ω_{n,m} − nΩ| at every Ω, with
//! the backward wave of n = 2 standing still at its critical speed. The pad example's map, read
//! along μ by the rank-one line path, is checked point by point against faer.

use std::path::{Path, PathBuf};

use contactlab_verify::registry::run_scene;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn out_dir(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("contactlab-plate-{name}-{}", std::process::id()))
}

#[test]
fn campbell_example_follows_the_shifted_non_rotating_frequencies() {
    let out = out_dir("campbell");
    let summary = run_scene(
        &root().join("examples/scenes/rotating_plate_campbell.toml"),
        &out,
    )
    .unwrap();
    assert!(
        summary.contains("lowest critical speed ω_{2,0}/2"),
        "{summary}"
    );
    let solution = json(&out.join("solution.json"));
    let sweep = json(&out.join("sweep_0.json"));
    // (n, ω_{n,m}) of every retained mode: 3 radial modes of n = 0 … 4
    let modes: Vec<(f64, f64)> = solution["harmonics"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|h| {
            let n = h["n"].as_f64().unwrap();
            h["frequencies"]
                .as_array()
                .unwrap()
                .iter()
                .map(move |w| (n, w.as_f64().unwrap()))
                .collect::<Vec<_>>()
        })
        .collect();
    assert_eq!(modes.len(), 15);
    let values = sweep["values"].as_array().unwrap();
    assert_eq!(values.len(), 201);
    let mut worst = 0.0f64;
    for (om, spectrum) in values.iter().zip(sweep["spectra"].as_array().unwrap()) {
        let om = om.as_f64().unwrap();
        let mut computed: Vec<f64> = spectrum
            .as_array()
            .unwrap()
            .iter()
            .map(|l| l[1].as_f64().unwrap().abs())
            .collect();
        // n = 0: ±iω; n ≥ 1 (cos and sin): ±i(ω − nΩ), ±i(ω + nΩ) — every |Im λ| twice
        let mut predicted: Vec<f64> = modes
            .iter()
            .flat_map(|&(n, w)| {
                if n == 0.0 {
                    vec![w, w]
                } else {
                    vec![
                        w + n * om,
                        w + n * om,
                        (w - n * om).abs(),
                        (w - n * om).abs(),
                    ]
                }
            })
            .collect();
        computed.sort_by(f64::total_cmp);
        predicted.sort_by(f64::total_cmp);
        assert_eq!(computed.len(), predicted.len());
        for (c, p) in computed.iter().zip(&predicted) {
            worst = worst.max((c - p).abs() / (1.0 + p));
        }
    }
    // measured 3e-10: both sides come from eigenproblems whose radial mass matrix has condition
    // ≈ 4e5 (the Hermite slope functions), ε κ ≈ 1e-10 each
    assert!(worst < 1e-8, "largest relative deviation {worst:e}");
    // the backward wave of n = 2 stands still at ω_{2,0}/2 ≈ 3.2237: at Ω = 3.225 (the nearest
    // grid point) the smallest |Im λ| is |ω_{2,0} − 2Ω|
    let w20 = modes.iter().find(|m| m.0 == 2.0).unwrap().1;
    let i = values
        .iter()
        .position(|v| (v.as_f64().unwrap() - 3.225).abs() < 1e-12)
        .unwrap();
    let lowest = sweep["spectra"][i]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l[1].as_f64().unwrap().abs())
        .fold(f64::INFINITY, f64::min);
    assert!(
        (lowest - (w20 - 6.45).abs()).abs() < 1e-8,
        "{lowest} vs {w20}"
    );
    // undamped and padless: every point is marginal (purely imaginary spectrum)
    assert!(sweep["verdicts"]
        .as_array()
        .unwrap()
        .iter()
        .all(|v| v == "marginal"));
    for f in ["spectrum.svg", "sweep_0.svg"] {
        assert!(out.join(f).exists(), "{f}");
    }
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn pad_example_runs_and_its_rank_one_map_equals_faer_point_by_point() {
    let out = out_dir("pad");
    let summary = run_scene(
        &root().join("examples/scenes/rotating_plate_pad.toml"),
        &out,
    )
    .unwrap();
    assert!(summary.contains("stable at Ω = 2"), "{summary}");
    let solution = json(&out.join("solution.json"));
    assert_eq!(solution["discretization"]["coordinates"], 22);
    assert_eq!(solution["eigenvalues"].as_array().unwrap().len(), 44);
    let sweep = json(&out.join("sweep_0.json"));
    let verdicts = sweep["verdicts"].as_array().unwrap();
    assert_eq!(verdicts[0], "stable");
    assert_eq!(verdicts[verdicts.len() - 1], "flutter");
    let map = json(&out.join("map.json"));
    assert_eq!(map["verdict"].as_array().unwrap().len(), 3600);
    // the same scene with the map solved point by point by faer
    let dir = out_dir("pad-faer");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(root().join("examples/scenes/rotating_plate_pad.toml"))
        .unwrap()
        .replace("[map]", "[stability]\nmap_kernel = \"faer\"\n\n[map]");
    std::fs::write(dir.join("faer.toml"), text).unwrap();
    run_scene(&dir.join("faer.toml"), &dir.join("out")).unwrap();
    let faer = json(&dir.join("out/map.json"));
    assert_eq!(map["verdict"], faer["verdict"]);
    // each point's spectral scale ρ = max |λ| (map.json's spectral_scale)
    let scales = map["spectral_scale"].as_array().unwrap();
    let fast = map["max_real_part"].as_array().unwrap();
    let dense = faer["max_real_part"].as_array().unwrap();
    for ((a, b), t) in fast.iter().zip(dense).zip(scales) {
        // round-off of two eigensolvers on the same companion matrix: measured ≤ 7.5e-14 with
        // ρ ≈ 10², i.e. below ε ρ; bounded by 100 ε ρ
        let (a, b, rho) = (
            a.as_f64().unwrap(),
            b.as_f64().unwrap(),
            t.as_f64().unwrap(),
        );
        assert!((a - b).abs() < 100.0 * f64::EPSILON * rho, "{a} vs {b}");
    }
    std::fs::remove_dir_all(&out).ok();
    std::fs::remove_dir_all(&dir).ok();
}
