//! Regression cases of the robustness issue ("no scene can crash, hang or lie"): example scenes
//! changed the way a careless or hostile user would, each run through `verify scene` with a time
//! bound. Each must end — a hang fails the test — with the outcome named here: an error that names
//! the offending key or condition, or a run whose outputs are finite.

use std::path::PathBuf;
use std::sync::mpsc;
use std::time::Duration;

use contactlab_verify::registry::run_scene;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The example `name` with the dotted keys of `set` replaced (TOML values written as text).
fn mutated(name: &str, set: &[(&str, &str)]) -> String {
    let text = std::fs::read_to_string(root().join("examples/scenes").join(name)).unwrap();
    let mut table: toml::Table = text.parse().unwrap();
    for (key, value) in set {
        let parts: Vec<&str> = key.split('.').collect();
        let mut t = &mut table;
        for p in &parts[..parts.len() - 1] {
            t = t
                .entry(p.to_string())
                .or_insert_with(|| toml::Value::Table(Default::default()))
                .as_table_mut()
                .unwrap();
        }
        let v: toml::Table = format!("v = {value}").parse().unwrap();
        t.insert(parts[parts.len() - 1].to_string(), v["v"].clone());
    }
    toml::to_string(&table).unwrap()
}

/// Runs the scene text in a fresh directory within `seconds`; a run that does not answer in time
/// fails the test (the thread is left behind).
fn run_bounded(
    id: &str,
    scene: String,
    out: Option<PathBuf>,
    seconds: u64,
) -> Result<String, String> {
    let dir =
        std::env::temp_dir().join(format!("contactlab-robustness-{id}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("scene.toml");
    std::fs::write(&file, scene).unwrap();
    let out = out.unwrap_or_else(|| dir.join("out"));
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(run_scene(&file, &out));
    });
    rx.recv_timeout(Duration::from_secs(seconds))
        .unwrap_or_else(|_| panic!("{id}: no answer within {seconds} s (a hang)"))
}

/// Runs the scene text past the file loader's magnitude check (`Scene::from_table`, the path the
/// verification cases take), within `seconds`: the solvers themselves must answer extreme data.
fn run_table_bounded(id: &str, scene: String, seconds: u64) -> Result<String, String> {
    let out = std::env::temp_dir().join(format!(
        "contactlab-robustness-t-{id}-{}",
        std::process::id()
    ));
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let r = (|| {
            let table: toml::Table = scene.parse().map_err(|e| format!("{e}"))?;
            let scene = contactlab::scene::Scene::from_table(table, "scene.toml")
                .map_err(|e| e.to_string())?;
            let family = contactlab_verify::registry::FAMILIES
                .iter()
                .find(|f| f.models().contains(&scene.model()))
                .ok_or("no family")?;
            family.write_scene(&scene, "scene.toml", &out)
        })();
        let _ = tx.send(r);
    });
    rx.recv_timeout(Duration::from_secs(seconds))
        .unwrap_or_else(|_| panic!("{id}: no answer within {seconds} s (a hang)"))
}

fn expect_error(id: &str, scene: String, needles: &[&str]) {
    match run_bounded(id, scene, None, 120) {
        Ok(summary) => panic!("{id}: ran, expected an error naming {needles:?}: {summary}"),
        Err(e) => {
            for n in needles {
                assert!(e.contains(n), "{id}: the error does not name {n:?}: {e}");
            }
        }
    }
}

#[test]
fn a_rod_whose_exact_solution_is_not_finite_is_an_error_not_a_perfect_agreement() {
    // Once: "paper E = 0.000000e0" — the NaN errors were dropped by f64::max.
    expect_error(
        "rod-viscosity",
        mutated("rod_paper_p0_2.toml", &[("rod.viscosity", "1e-6")]),
        &["exact solution", "not finite"],
    );
}

#[test]
fn a_rod_oil_pressure_in_x_is_an_error_naming_foundation_p0() {
    expect_error(
        "rod-p0-x",
        mutated("rod_paper_p0_2.toml", &[("foundation.p0", "\"x\"")]),
        &["foundation.p0", "t alone"],
    );
}

#[test]
fn zero_graded_rod_elements_name_mesh_elements() {
    // Once: "invalid mesh.grading = 0".
    expect_error(
        "rod-elements",
        mutated(
            "rod_paper_p0_2.toml",
            &[("mesh.elements", "0"), ("mesh.grading", "2.0")],
        ),
        &["mesh.elements"],
    );
}

#[test]
fn a_section_written_as_an_array_is_an_error() {
    // Once: `string = [0.5, 0.05]` was read as the fields of [string] in order, silently.
    expect_error(
        "section-array",
        mutated("moving_thick_string.toml", &[("string", "[0.5, 0.05]")]),
        &["invalid string", "a table"],
    );
}

#[test]
fn fixed_size_pairs_with_extra_values_are_errors() {
    expect_error(
        "plane-size",
        mutated(
            "plane_paper_test_2d.toml",
            &[("geometry.size", "[2.0, 1.0, 99.0]")],
        ),
        &["size", "expected exactly 2"],
    );
    expect_error(
        "plane-divisions",
        mutated(
            "plane_paper_test_2d.toml",
            &[("geometry.divisions", "[24, 12, -5]")],
        ),
        &["divisions"],
    );
}

#[test]
fn a_plane_run_that_skips_every_step_is_an_error() {
    // Once: exit 0 after "100 steps (100 skipped for lack of equilibrium)", all zero.
    expect_error(
        "plane-skipped",
        mutated(
            "plane_paper_test_2d.toml",
            &[("contact.p0", "\"ln(-t)\""), ("time.steps", "10")],
        ),
        &["no step of the run has an equilibrium"],
    );
}

#[test]
fn a_tiny_young_modulus_answers() {
    // Once: the dense tridiagonal QR of the explicit bound's eigenproblem never ended. A scene
    // file with it is refused up front (the key named); the solver path must still answer.
    let scene = mutated(
        "plane_paper_test_2d.toml",
        &[
            ("elasticity.young", "1e-308"),
            ("geometry.divisions", "[6, 6]"),
            ("time.steps", "5"),
        ],
    );
    let e = run_bounded("plane-young", scene.clone(), None, 120).unwrap_err();
    assert!(
        e.contains("elasticity.young") && e.contains("1e-150"),
        "{e}"
    );
    if let Err(e) = run_table_bounded("plane-young", scene, 120) {
        assert!(!e.contains("panicked"), "{e}");
    }
}

#[test]
fn a_disc_particle_of_extreme_mass_answers() {
    // Once: the balancing before the eigenvalue solve never ended (inf >= 2 inf).
    for mass in ["1e308", "1e-308", "5e-324"] {
        let scene = mutated("moving_disc_particle.toml", &[("particle.mass", mass)]);
        let e = run_bounded(&format!("disc-mass-{mass}"), scene.clone(), None, 120).unwrap_err();
        assert!(
            e.contains("particle.mass"),
            "a scene file is refused up front: {e}"
        );
        let r = run_table_bounded(&format!("disc-mass-{mass}"), scene, 120);
        if let Err(e) = r {
            assert!(
                e.contains("particle.mass") || e.contains("finite"),
                "mass {mass}: {e}"
            );
        }
    }
}

#[test]
fn an_unwritable_out_is_refused_before_solving() {
    // Once: a ring impact spent 36 s and then failed to write. The scene here would fail after
    // solving (its exact solution is not finite): the error must be the --out one.
    let e = run_bounded(
        "out",
        mutated("rod_paper_p0_2.toml", &[("rod.viscosity", "1e-6")]),
        Some(PathBuf::from("/proc/contactlab-out")),
        120,
    )
    .unwrap_err();
    assert!(e.contains("--out") && !e.contains("exact solution"), "{e}");
}

#[test]
fn a_selector_that_selects_nothing_is_an_error() {
    // Once: `[[dirichlet]] sides = ["top"]` on a disk clamped nothing, silently.
    let text =
        std::fs::read_to_string(root().join("examples/scenes/dynamic_ball_impact.toml")).unwrap();
    let scene = format!("{text}\n[[dirichlet]]\nsides = [\"top\"]\nsupport = \"clamped\"\n");
    expect_error("disk-sides", scene, &["dirichlet[0].sides", "selects none"]);
}

#[test]
fn an_incompressible_plane_strain_poisson_ratio_names_poisson() {
    // Once: "invalid elasticity.a1 = inf".
    expect_error(
        "plane-poisson",
        mutated(
            "plane_paper_test_2d.toml",
            &[
                ("elasticity.law", "\"plane_strain\""),
                ("elasticity.poisson", "0.5"),
            ],
        ),
        &["elasticity.poisson", "incompressible"],
    );
}

/// (test id, example, keys set, key the error must name).
type CountCase = (
    &'static str,
    &'static str,
    &'static [(&'static str, &'static str)],
    &'static str,
);

#[test]
fn absurd_counts_are_refused_before_allocating() {
    // Once: "capacity overflow" panics and allocation aborts.
    let cases: [CountCase; 4] = [
        (
            "rod-elements-max",
            "rod_paper_p0_2.toml",
            &[("mesh.elements", "9223372036854775807")],
            "mesh.elements",
        ),
        (
            "rod-steps-max",
            "rod_paper_p0_2.toml",
            &[("time.steps", "9223372036854775807")],
            "time.steps",
        ),
        (
            "plane-divisions",
            "plane_paper_test_2d.toml",
            &[("geometry.divisions", "[100000, 100000]")],
            "geometry.divisions",
        ),
        (
            "dynamic-rings",
            "dynamic_ball_impact.toml",
            &[("body.rings", "1000000000")],
            "rings",
        ),
    ];
    for (id, example, set, key) in cases {
        expect_error(id, mutated(example, set), &[key]);
    }
}

#[test]
fn gonzalez_runs_through_a_step_of_three_contact_durations() {
    // Once: "singular or indefinite dynamic step Jacobian αM + θK_T at step 1" — the symmetric
    // part of the discrete-gradient tangent is indefinite at k = 5e-2 (α = 800, E = 1e8), and
    // the Cholesky factorization refused it. Now the exact tangent's LU takes over.
    // the spinning-ring example moved to the foundation: E = 1e8, thrown at (2, −5) m/s, r = 1e10
    let scene = mutated(
        "dynamic_spinning_ring.toml",
        &[
            ("body.center", "[0.0, 0.5]"),
            ("material.young", "1e8"),
            ("time.final_time", "0.05"),
            ("time.steps", "1"),
            ("initial.velocity", "[2.0, -5.0]"),
            ("output.times", "[0.0]"),
            ("contact.level", "0.0"),
            ("contact.where", "\"0.5 - y\""),
            ("contact.treatment", "\"energy_consistent\""),
            ("contact.stiffness", "1e10"),
        ],
    );
    let summary = run_bounded("gonzalez-large-step", scene, None, 120)
        .unwrap_or_else(|e| panic!("the run must complete: {e}"));
    assert!(summary.contains("1 of 1 steps"), "{summary}");
    let number_after = |key: &str| -> f64 {
        let at = summary
            .find(key)
            .unwrap_or_else(|| panic!("no {key:?} in {summary}"));
        summary[at + key.len()..]
            .split([',', ' ', ';', '('])
            .find(|t| !t.is_empty())
            .and_then(|t| t.parse().ok())
            .unwrap_or_else(|| panic!("no number after {key:?} in {summary}"))
    };
    // the energy identity (1.48) at round-off of the step, relative to E_ref
    assert!(number_after("(1.48) ") < 1e-12, "{summary}");
    // the fallback did the work: some factorizations were of an indefinite Jacobian
    let at = summary
        .find(" of an indefinite")
        .expect("the statistic is reported");
    let count: usize = summary[..at]
        .rsplit('(')
        .next()
        .and_then(|t| t.trim().parse().ok())
        .expect("a count");
    assert!(count > 0, "{summary}");
}

#[test]
fn a_block_resting_under_gravity_converges_at_its_round_off_floor() {
    // Once: "semismooth Newton did not converge in 60 iterations (residual 1.46e-12, tolerance
    // 1e-12)" at step 1 — the stress round-off ε(λ + 2μ) sets a floor above 1e-12 s.
    let scene = mutated(
        "dynamic_block_drop.toml",
        &[("initial.velocity", "[0.0, 0.0]")],
    );
    let summary = run_bounded("block-at-rest", scene, None, 120)
        .unwrap_or_else(|e| panic!("the run must complete: {e}"));
    assert!(summary.contains("100 of 100 steps"), "{summary}");
    let at = summary
        .find(" stopped at the residual's round-off floor")
        .expect("the statistic is reported");
    let floor_stops: usize = summary[..at]
        .rsplit(' ')
        .next()
        .and_then(|t| t.parse().ok())
        .expect("a count");
    assert!(floor_stops > 0, "{summary}");
    // the energy identity still holds at round-off
    let key = "(1.48) ";
    let i = summary.find(key).expect("(1.48)") + key.len();
    let drift: f64 = summary[i..]
        .split([',', ' ', ';'])
        .next()
        .and_then(|t| t.parse().ok())
        .expect("a number");
    assert!(drift < 1e-12, "{summary}");
}

#[test]
fn files_of_an_earlier_run_are_removed_and_foreign_files_refused() {
    // Once: an old errors.json or map.json stayed beside the new results without a word.
    let dir = std::env::temp_dir().join(format!("contactlab-stale-out-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.join("out");
    let first = run_bounded(
        "stale-1",
        mutated("rod_paper_p0_2.toml", &[]),
        Some(out.clone()),
        120,
    )
    .expect("the rod runs");
    assert!(!first.contains("removed"), "{first}");
    assert!(out.join("errors.json").exists());
    // a second scene without an exact solution: the old errors.json must go
    let second = run_bounded(
        "stale-2",
        mutated("rod_sand_foundation.toml", &[]),
        Some(out.clone()),
        120,
    )
    .expect("the rod runs");
    assert!(
        second.contains("errors.json"),
        "the summary lists what it removed: {second}"
    );
    assert!(
        !out.join("errors.json").exists(),
        "the stale errors.json stayed"
    );
    assert!(out.join("solution.json").exists());
    // a directory with someone else's files is refused, with their names
    let foreign = dir.join("foreign");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("thesis.tex"), "").unwrap();
    let e = run_bounded(
        "stale-3",
        mutated("rod_paper_p0_2.toml", &[]),
        Some(foreign),
        120,
    )
    .unwrap_err();
    assert!(e.contains("--out") && e.contains("thesis.tex"), "{e}");
}

#[test]
fn every_message_names_the_key_as_written_and_stays_readable() {
    // Once: mesh.width for size, elasticity = a1 …, a2 … for young, output.times for a negative
    // final_time, 309 digits for 1e308, a whole 50 000-term expression echoed back.
    // (example, changed keys, what the message must contain)
    type MessageCase<'a> = (&'a str, &'a [(&'a str, &'a str)], &'a [&'a str]);
    let cases: [MessageCase; 9] = [
        (
            "plane_nonlinear_block.toml",
            &[("geometry.size", "[-1.0, 1.0]")],
            &["geometry.size[0]"],
        ),
        (
            "plane_paper_test_2d.toml",
            &[("elasticity.young", "-5.0")],
            &["elasticity.young"],
        ),
        (
            "dynamic_block_drop.toml",
            &[("body.size", "[0.0, 0.2]")],
            &["body.size[0]"],
        ),
        (
            "dynamic_block_drop.toml",
            &[("time.final_time", "-5.0")],
            &["time.final_time = -5"],
        ),
        (
            "dynamic_ball_impact.toml",
            &[("body.radius", "-1.0")],
            &["body.radius"],
        ),
        (
            "moving_penalty_bushing.toml",
            &[("discretization.modes", "100000")],
            &["discretization.modes"],
        ),
        (
            "rod_paper_p0_2.toml",
            &[("rod.length", "-1e308")],
            &["rod.length = -1e308"],
        ),
        (
            "dynamic_ball_impact.toml",
            &[("contact.stiffness", "1e300")],
            &["contact.stiffness", "1e300"],
        ),
        (
            "rod_paper_p0_2.toml",
            &[("rod.viscosity", "1e-300")],
            &["rod.viscosity = 1e-300"],
        ),
    ];
    let long = format!("\"{}\"", vec!["x"; 2001].join("+"));
    let e = run_bounded(
        "messages-long",
        mutated("rod_sand_foundation.toml", &[("rod.load", &long)]),
        None,
        120,
    )
    .expect_err("an expression of 4001 characters is refused");
    assert!(e.contains("rod.load") && e.contains("characters"), "{e}");
    assert!(e.len() < 800, "{} characters: {e}", e.len());
    for (i, (example, set, needles)) in cases.iter().enumerate() {
        let e = run_bounded(&format!("messages-{i}"), mutated(example, set), None, 120)
            .expect_err("an error");
        for n in *needles {
            assert!(
                e.contains(n),
                "{example} {set:?}: the error does not name {n:?}: {e}"
            );
        }
        assert!(
            e.len() < 800,
            "{example} {set:?}: {} characters: {e}",
            e.len()
        );
    }
}

#[test]
fn a_stopped_rod_or_plane_run_writes_what_it_computed() {
    // A run stopped at its first step (a time limit of zero) writes the steps recorded before,
    // every number finite, and says where.
    for (i, example) in ["rod_paper_p0_2.toml", "plane_nonlinear_block.toml"]
        .iter()
        .enumerate()
    {
        let dir =
            std::env::temp_dir().join(format!("contactlab-partial-{i}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("scene.toml");
        std::fs::write(&file, mutated(example, &[])).unwrap();
        let out = dir.join("out");
        let e = contactlab::run_control::with_time_limit(Duration::ZERO, || run_scene(&file, &out))
            .expect_err("stopped");
        assert!(
            e.contains("time limit") && e.contains("partial_solution.json"),
            "{e}"
        );
        let text = std::fs::read_to_string(out.join("partial_solution.json")).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert!(!text.contains("null"), "{example}: a null in {v}");
    }
}

// issue 32: expressions, messages in the user's words, Gmsh sections

/// The example `name` with the text `from` replaced by `to` (for keys inside arrays of tables).
fn replaced(name: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(root().join("examples/scenes").join(name)).unwrap();
    assert!(text.contains(from), "{name} has no `{from}`");
    text.replacen(from, to, 1)
}

#[test]
fn scientific_notation_in_expressions_runs_and_a_slip_names_its_position() {
    for load in ["\"1e-3*t + 10\"", "\"10 + 2.5e2*t\"", "\"10 + 1E-3*t\""] {
        run_bounded(
            "sci-notation",
            mutated("rod_sand_foundation.toml", &[("rod.load", load)]),
            None,
            120,
        )
        .unwrap_or_else(|e| panic!("{load}: {e}"));
    }
    let e = run_bounded(
        "sci-slip",
        mutated("rod_paper_p0_2.toml", &[("rod.load", "\"10 + 2e*t\"")]),
        None,
        120,
    )
    .expect_err("an exponent without digits");
    assert!(e.contains("rod.load") && e.contains("position 6"), "{e}");
    assert!(!e.contains("node") && !e.contains(" op"), "{e}");
}

#[test]
fn inputs_that_pass_validation_but_fail_later_name_the_key_as_written() {
    type Named<'a> = (&'a str, String, &'a [&'a str]);
    let cases: [Named; 6] = [
        (
            "grading past round-off",
            mutated(
                "rod_paper_p0_2.toml",
                &[("mesh.elements", "100"), ("mesh.grading", "10.0")],
            ),
            &["mesh.grading = 10", "100 elements"],
        ),
        (
            "negative control parameter",
            mutated(
                "moving_thick_string.toml",
                &[("oscillator.control_parameter", "-1.0")],
            ),
            &["oscillator.control_parameter = -1"],
        ),
        (
            "an indefinite viscosity",
            mutated(
                "plane_paper_test_2d.toml",
                &[("viscosity.mu", "0.0"), ("viscosity.eta", "0.0")],
            ),
            &["viscosity.eta = 0"],
        ),
        (
            "a body 1e12 high",
            mutated("dynamic_block_drop.toml", &[("body.size", "[0.4, 1e12]")]),
            &["body.size"],
        ),
        (
            "a foundation level far above the body",
            mutated("dynamic_block_drop.toml", &[("contact.level", "1e3")]),
            &["contact.level = 1000", "below the level"],
        ),
        (
            "two rings overlapping at the start",
            replaced(
                "multibody_rings.toml",
                "center = [1.1, 0.5]",
                "center = [0.7, 0.5]",
            )
            .replace("(x - 1.1)^2", "(x - 0.7)^2"),
            &["overlap"],
        ),
    ];
    for (i, (what, scene, needles)) in cases.into_iter().enumerate() {
        let e = run_bounded(&format!("named-{i}"), scene, None, 120)
            .expect_err(&format!("{what}: an error"));
        for n in needles {
            assert!(e.contains(n), "{what}: the error does not name {n:?}: {e}");
        }
        assert!(
            !e.contains("triangles[") && !e.contains("nodes["),
            "{what}: {e}"
        );
    }
}

// issue 32: memory, planner, stop

/// `verify ARGS` as a child process: its output and its peak resident size in bytes (the
/// child's own `ru_maxrss` from `wait4`).
fn verify_child(args: &[&str]) -> (std::process::Output, f64) {
    use std::os::unix::process::ExitStatusExt;
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the verify binary runs");
    let pid = child.id() as libc::pid_t;
    // read the pipes on threads (a full pipe would block the child), then reap it with wait4
    let mut child = child;
    let mut so = child.stdout.take().unwrap();
    let mut se = child.stderr.take().unwrap();
    let read = |r: &mut dyn std::io::Read| {
        let mut v = Vec::new();
        let _ = r.read_to_end(&mut v);
        v
    };
    let (stdout, stderr) = std::thread::scope(|s| {
        let a = s.spawn(|| read(&mut so));
        let b = s.spawn(|| read(&mut se));
        (a.join().unwrap(), b.join().unwrap())
    });
    let mut status = 0;
    // SAFETY: rusage is plain data, zero is a valid value; wait4 fills it for our own child
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let r = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    assert_eq!(r, pid, "wait4");
    let output = std::process::Output {
        status: std::process::ExitStatus::from_raw(status),
        stdout,
        stderr,
    };
    (output, usage.ru_maxrss as f64 * 1024.0)
}

/// A scene file of the example `name` with `set` applied, in a fresh directory.
fn scene_file(id: &str, name: &str, set: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("contactlab-i32-{id}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("scene.toml");
    std::fs::write(&file, mutated(name, set)).unwrap();
    file
}

/// The bytes of "needs about 93.6 MiB" (or "writes about …") in a refusal.
fn estimate_in(message: &str, verb: &str) -> f64 {
    let at = message
        .find(verb)
        .unwrap_or_else(|| panic!("no `{verb}` in {message}"));
    let mut words = message[at + verb.len()..].split_whitespace();
    let v: f64 = words.next().unwrap().parse().unwrap();
    let unit = words.next().unwrap();
    let p = ["B", "KiB", "MiB", "GiB", "TiB"]
        .iter()
        .position(|u| unit.starts_with(u))
        .unwrap();
    v * 1024f64.powi(p as i32)
}

fn times(list: impl Iterator<Item = f64>) -> String {
    format!(
        "[{}]",
        list.map(|t| format!("{t:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    )
}

#[test]
fn output_times_repeated_twenty_thousand_times_are_recorded_once() {
    // The block drop with 20 000 output times all equal to T: one snapshot (it aborted with
    // `memory allocation of 4096 bytes failed` at 100 000, after a 1 GB snapshots.svg at 20 000).
    let file = scene_file(
        "repeated",
        "dynamic_block_drop.toml",
        &[("output.times", &times(std::iter::repeat_n(0.2, 20_000)))],
    );
    let out = file.with_file_name("out");
    let (o, _) = verify_child(&[
        "scene",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("solution.json")).unwrap()).unwrap();
    assert_eq!(v["snapshots"].as_array().map(Vec::len), Some(1));
}

#[test]
fn files_above_the_disk_limit_are_refused_naming_output_times_and_the_limit() {
    // 401 distinct output times of the 306-dof block: about 4.7 MiB of text, refused under
    // --max-disk 1M before the run, naming output.times, the estimate and the limit.
    let file = scene_file(
        "disk",
        "dynamic_block_drop.toml",
        &[
            ("time.steps", "400"),
            (
                "output.times",
                &times((0..=400).map(|i| 0.2 * i as f64 / 400.0)),
            ),
        ],
    );
    let out = file.with_file_name("out");
    let (o, _) = verify_child(&[
        "scene",
        file.to_str().unwrap(),
        "--max-disk",
        "1M",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("output.times")
            && err.contains("401 distinct times")
            && err.contains("1.0 MiB")
            && err.contains("--max-disk"),
        "{err}"
    );
    assert!(!out.join("solution.json").exists());
}

#[test]
fn measured_peaks_stay_below_the_memory_estimate() {
    // Each scene's estimate (read from its refusal under a 1 KiB limit) against the peak
    // resident size of its run, one or more scenes per model (multibody, dynamic, plane, plate,
    // moving string, rod), each scaled past the 16 MiB base so the counted terms dominate: the estimate must hold — peak ≤ estimate × (1 + 5 %), the
    // margin covering the one-decimal rounding of the message and the allocator's pages.
    type Keys = Vec<(&'static str, String)>;
    let scenes: [(&str, &str, Keys); 7] = [
        (
            "mb-outputs",
            "multibody_rings.toml",
            vec![
                ("time.steps", "1000".into()),
                ("output.times", times((0..=1000).map(|i| i as f64 / 1000.0))),
            ],
        ),
        (
            "mb-steps",
            "multibody_rings.toml",
            vec![("time.steps", "2000".into())],
        ),
        (
            "dyn-outputs",
            "dynamic_block_drop.toml",
            vec![
                ("time.steps", "400".into()),
                (
                    "output.times",
                    times((0..=400).map(|i| 0.2 * i as f64 / 400.0)),
                ),
            ],
        ),
        ("plane", "plane_paper_test_2d.toml", vec![]),
        // the plate's operators grow as R² and n² (radial functions, coordinates)
        (
            "plate-operators",
            "rotating_plate_campbell.toml",
            vec![
                ("discretization.elements", "120".into()),
                ("discretization.radial_modes", "40".into()),
                (
                    "sweep",
                    r#"[{ parameter = "angular_speed", from = 0.0, to = 5.0, points = 3 }]"#.into(),
                ),
            ],
        ),
        // a stability map's records grow with its points: 150 × 150 of the thick string
        (
            "string-map",
            "moving_thick_string.toml",
            vec![
                ("map.x.points", "150".into()),
                ("map.y.points", "150".into()),
            ],
        ),
        // the rod's history grows with elements × (6 + probes)
        (
            "rod-elements",
            "rod_general_data.toml",
            vec![
                ("mesh.elements", "20000".into()),
                ("time.steps", "200".into()),
            ],
        ),
    ];
    let mut texts: Vec<(&str, String)> = scenes
        .iter()
        .map(|(id, name, set)| {
            let set: Vec<(&str, &str)> = set.iter().map(|(k, v)| (*k, v.as_str())).collect();
            (*id, mutated(name, &set))
        })
        .collect();
    // the slenderest mesh measured: a ring one cell across and 3 000 around (the step's LU
    // factor holds ~ c n √n numbers, docs/multibody.md "Memory"), one step
    let thin =
        std::fs::read_to_string(root().join("examples/scenes/multibody_rings_friction.toml"))
            .unwrap()
            .replacen("around = 36", "around = 3000", 1)
            .replace("radial = 2", "radial = 1")
            .replace("around = 36", "around = 12")
            .replace("final_time = 1.0", "final_time = 0.01")
            .replace("steps = 200", "steps = 1")
            .replace("times = [0.0, 0.25, 0.5, 0.75, 1.0]", "times = [0.0, 0.01]");
    texts.push(("mb-thin-ring", thin));
    for (id, text) in &texts {
        let dir = std::env::temp_dir().join(format!("contactlab-i32-{id}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("scene.toml");
        std::fs::write(&file, text).unwrap();
        let out = file.with_file_name("out");
        let (path, out) = (file.to_str().unwrap(), out.to_str().unwrap());
        let (refused, _) = verify_child(&["scene", path, "--max-memory", "1K", "--out", out]);
        let estimate = estimate_in(&String::from_utf8_lossy(&refused.stderr), "needs about ");
        let peak = peak_in_small_process(&["scene", path, "--out", out]);
        assert!(
            peak <= 1.05 * estimate,
            "{id}: peak {:.1} MiB above the estimate {:.1} MiB",
            peak / 1048576.0,
            estimate / 1048576.0
        );
    }
}

/// The peak resident size of `verify ARGS`, spawned from a fresh small process (this test
/// binary running [`peak_helper`]): a child's `ru_maxrss` starts from its parent's resident size
/// at the spawn (Linux keeps the larger of the old and new image's high-water marks across
/// exec), and this test process holds the other tests' memory.
fn peak_in_small_process(args: &[&str]) -> f64 {
    let o = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "peak_helper",
            "--ignored",
            "--nocapture",
            "--test-threads",
            "1",
        ])
        .env("CONTACTLAB_PEAK_ARGS", args.join("\u{1f}"))
        .output()
        .expect("the test binary runs");
    let text = String::from_utf8_lossy(&o.stdout);
    text.lines()
        .find_map(|l| l.split("PEAK ").nth(1))
        .and_then(|v| v.split_whitespace().next()?.parse().ok())
        .unwrap_or_else(|| panic!("no peak: {text}{}", String::from_utf8_lossy(&o.stderr)))
}

/// Not a test: run by [`peak_in_small_process`] with `CONTACTLAB_PEAK_ARGS`; prints the peak
/// resident bytes of `verify ARGS` (it must succeed).
#[test]
#[ignore]
fn peak_helper() {
    let Ok(args) = std::env::var("CONTACTLAB_PEAK_ARGS") else {
        return;
    };
    let args: Vec<&str> = args.split('\u{1f}').collect();
    let (o, peak) = verify_child(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    println!("PEAK {peak}");
}

#[test]
fn a_rod_plan_beyond_memory_names_base_instead_of_aborting() {
    let scene = root().join("examples/scenes/rod_paper_p0_2.toml");
    let out = std::env::temp_dir().join(format!("contactlab-i32-plan-{}", std::process::id()));
    let (o, _) = verify_child(&[
        "plan",
        scene.to_str().unwrap(),
        "--target",
        "1e-3",
        "--base",
        "1000000000000,1000000000000",
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert_ne!(o.status.code(), Some(101), "a panic: {text}");
    assert!(
        o.status.code().is_some(),
        "killed by a signal (an abort): {text}"
    );
    assert!(text.contains("--base") && text.contains("limit"), "{text}");
}

#[test]
fn a_plan_whose_explicit_pilots_are_all_unstable_rejects_the_scheme_without_nan() {
    let scene = root().join("examples/scenes/plane_paper_test_2d.toml");
    let out = std::env::temp_dir().join(format!("contactlab-i32-plan11-{}", std::process::id()));
    let (o, _) = verify_child(&[
        "plan",
        scene.to_str().unwrap(),
        "--target",
        "1e-3",
        "--base",
        "1,1",
        "--cost",
        "work",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_ne!(
        o.status.code(),
        Some(101),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let md = std::fs::read_to_string(out.join("plan.md")).unwrap();
    let json = std::fs::read_to_string(out.join("plan.json")).unwrap();
    assert!(!md.contains("NaN"), "{md}");
    assert!(!json.contains("\"value\": null"), "{json}");
    assert!(md.contains("beyond the stability bound"), "{md}");
}

#[test]
fn zero_plan_rounds_are_refused_naming_rounds() {
    let scene = root().join("examples/scenes/rod_paper_p0_2.toml");
    let (o, _) = verify_child(&[
        "plan",
        scene.to_str().unwrap(),
        "--target",
        "1e-3",
        "--rounds",
        "0",
        "--out",
        std::env::temp_dir()
            .join("contactlab-i32-rounds")
            .to_str()
            .unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--rounds = 0") && err.contains("at least 1"),
        "{err}"
    );
}

#[test]
fn a_plate_stopped_between_its_eigen_solves_says_so_within_one_solve() {
    // The rotating plate with 400 radial elements and 6 harmonics: its model solves one dense
    // radial eigenproblem per harmonic (≈ 0.1 s each here) before the sweep. A time limit of
    // 0.2 s stops it between two of them: the error is the stop (it was reported as "invalid
    // plate … beyond the range of doubles" before), at a harmonic before the last (not after all
    // solves), honoured at the first check that found the limit passed (the limit's clock,
    // contactlab::run_control).
    let dir = std::env::temp_dir().join(format!("contactlab-plate-stop-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("scene.toml");
    let scene = replaced("rotating_plate_pad.toml", "elements = 20", "elements = 400");
    std::fs::write(&file, scene).unwrap();
    let out = dir.join("out");
    let (r, timing) =
        contactlab::run_control::with_time_limit_measured(Duration::from_millis(200), || {
            run_scene(&file, &out)
        });
    let e = r.expect_err("stopped");
    assert!(
        e.contains("the time limit of 0.2 s") && e.contains("radial modes of harmonic n = "),
        "{e}"
    );
    assert!(!e.contains("invalid plate"), "{e}");
    assert!(
        !e.contains("harmonic n = 5"),
        "stopped only after the last solve: {e}"
    );
    assert_eq!((timing.fired_checks, timing.threads), (1, 1), "{timing:?}");
}

#[test]
fn a_solver_failure_names_the_inputs_that_set_the_step_and_off_grid_times_name_the_grid() {
    // The block drop with a penalty 10¹³: the first step's Newton method does not converge. The
    // message ends with the keys that set the step's scales, as written (it ended with the
    // residual and the audit's file only).
    let e = run_bounded(
        "likely-inputs",
        mutated("dynamic_block_drop.toml", &[("contact.stiffness", "1e13")]),
        None,
        120,
    )
    .expect_err("the Newton method fails");
    assert!(
        e.contains("check these first")
            && e.contains("contact.stiffness = 10000000000000")
            && e.contains("time.steps = 100"),
        "{e}"
    );
    // A rod whose final time moved away from its output times: the error names the grid's keys.
    let e = run_bounded(
        "off-grid",
        mutated("rod_paper_p0_2.toml", &[("rod.final_time", "2.0")]),
        None,
        120,
    )
    .expect_err("an output time off the grid");
    assert!(
        e.contains("output.times") && e.contains("time.steps") && e.contains("final_time = 2"),
        "{e}"
    );
}

#[test]
fn an_exact_solution_beyond_doubles_names_the_rod_data_it_was_evaluated_with() {
    // Found by the structural mutations (rod.final_time exchanged with rod.length, or
    // rod.elasticity = 1e5): "the exact solution … is not finite at t = …" named no key.
    let file = scene_file(
        "exact-overflow",
        "rod_paper_p0_2.toml",
        &[("rod.elasticity", "1e5")],
    );
    let out = file.with_file_name("out");
    let (o, _) = verify_child(&[
        "scene",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("not finite") && err.contains("rod.elasticity = 100000"),
        "{err}"
    );
}

#[test]
fn a_plane_body_without_its_load_names_the_traction_and_support_sections() {
    // Found by the structural mutations (`traction: [0] dropped`): the step failure listed the
    // material and contact keys but not what holds and loads the body.
    let text =
        std::fs::read_to_string(root().join("examples/scenes/plane_paper_test_2d.toml")).unwrap();
    let mut table: toml::Table = text.parse().unwrap();
    table.remove("traction");
    let dir = std::env::temp_dir().join(format!("contactlab-i34-traction-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("scene.toml");
    std::fs::write(&file, toml::to_string(&table).unwrap()).unwrap();
    let (o, _) = verify_child(&[
        "scene",
        file.to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("[[traction]] = 0 section(s)") && err.contains("[[dirichlet]] = 1 section(s)"),
        "{err}"
    );
}
