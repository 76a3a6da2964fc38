//! The recorded contact force of the multibody solver: the setting is the head-on bars
//! (two linear plane-strain bars 1 × 0.1, ν = 0, E = ρ = 1 so c = 1, at ±v with v/c = 0.1, one row
//! of elements, k = h/c, the energy–momentum scheme with multipliers); the goal is to pin that the
//! raw Σ λ_N alternates from step to step about the exact force ρ c v A (d'Alembert,
//! `exact::bar_impact`) by a swing that does not shrink with h, while the two-step mean
//! F̄_n = (J_n + J_{n+1})/(2k) written beside it (`model::multibody::history`) is within the
//! discretization error of the exact force over the contact's plateau (from the onset to two
//! widths (h² 2L)^{1/3}/c of the dispersive release front before the exact release): its error
//! is below the raw force's swing by an order of magnitude and shrinks under refinement.

use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab_verify::exact::bar_impact::{HeadOnBars, TwoBarImpact};
use contactlab_verify::multibody::cases::bars::setup::{build, Geometry, Level, Treatment};
use contactlab_verify::multibody::study::{run_recorded, LawName, MaterialSpec};

/// The bars' material (linear, E = 1, ν = 0).
const MATERIAL: MaterialSpec = MaterialSpec {
    law: LawName::Linear,
    young: 1.0,
    poisson: 0.0,
};

/// The head-on bars (L = 1, H = 0.1, ρ = E = 1) at ±`v` on `elements` per bar, onset a third
/// into a step, run to a quarter past the exact contact's end.
fn bars(
    elements: usize,
    v: f64,
) -> (
    contactlab::model::multibody::solver::MultibodySolver,
    HeadOnBars,
    Level,
) {
    let h = 1.0 / elements as f64;
    // t0 = g0/(2v) = (2 + 1/3) k with k = h/c
    let gap = 2.0 * v * (7.0 / 3.0) * h;
    let g = Geometry {
        left_length: 1.0,
        right_length: 1.0,
        height: 0.1,
        density: 1.0,
        gap,
        left_velocity: v,
        right_velocity: -v,
    };
    let material = MATERIAL;
    let exact = HeadOnBars {
        length: 1.0,
        density: 1.0,
        young: 1.0,
        area: 0.1,
        speed: v,
        gap,
    };
    let level = Level::with_courant(
        &g,
        elements,
        1,
        1.0,
        exact.wave_speed(),
        exact.contact_end() + 0.25,
    );
    let treatment = Treatment {
        scheme: MultibodyScheme::EnergyMomentum,
        two_pass: false,
    };
    let solver = build(&g, &material, &level, treatment).expect("the bars");
    (solver, exact, level)
}

/// The bars at v/c = 0.1 on `elements` per bar; returns (the largest relative error of the raw
/// force, that of the two-step mean) over the plateau — the records whose two-step window
/// [t_{n−1}, t_{n+1}] lies inside the exact contact interval less the smeared release — and the
/// count of those records.
fn force_errors(elements: usize) -> (f64, f64, usize) {
    let v = 0.1;
    let (solver, exact, level) = bars(elements, v);
    let end = exact.contact_end();
    let run = run_recorded(&solver, &[MATERIAL; 2]).expect("the run");
    let force = exact.area() * exact.contact_stress();
    assert!((force - 1.0 * 1.0 * v * 0.1).abs() < 1e-15, "ρ c v A");
    let k = level.step;
    // the middle half of the exact contact interval (as multibody_bars' plateau): away from the
    // onset front's ringing and from the returning unloading front, which P1 elements with a
    // midpoint-type rule smear over (h² c t)^{1/3}
    let (start, span) = (exact.contact_start(), end - exact.contact_start());
    let (start, end) = (start + 0.25 * span, start + 0.75 * span);
    let (mut raw, mut mean, mut count) = (0.0f64, 0.0f64, 0);
    for hst in &run.history {
        let t = hst.time;
        if t - k > start && t + k < end {
            raw = raw.max((hst.normal_force / force - 1.0).abs());
            mean = mean.max((hst.normal_force_mean / force - 1.0).abs());
            count += 1;
        }
    }
    (raw, mean, count)
}

#[test]
fn the_two_step_mean_force_of_the_head_on_bars_is_the_exact_force_where_the_raw_one_swings() {
    let (raw20, mean20, n20) = force_errors(20);
    let (raw40, mean40, n40) = force_errors(40);
    println!(
        "M = 20: raw force swing max |F_n/F − 1| = {raw20:.3e}, two-step mean error {mean20:.3e} \
         over {n20} steps; M = 40: raw {raw40:.3e}, mean {mean40:.3e} over {n40} steps"
    );
    assert!(
        n20 >= 18 && n40 >= 38,
        "the plateau's records: {n20}, {n40}"
    );
    // the raw force swings by a fraction of the force that does not shrink with h
    assert!(
        raw20 > 0.1 && raw40 > 0.5 * raw20,
        "raw swing {raw20}, {raw40}"
    );
    // the mean: an order of magnitude below the swing, and shrinking under refinement (the
    // ringing behind the dispersive onset front, the discretization's error)
    assert!(mean20 < 0.1 * raw20, "mean {mean20} vs swing {raw20}");
    assert!(mean40 < 0.1 * raw40, "mean {mean40} vs swing {raw40}");
    assert!(
        mean40 < mean20,
        "mean {mean40} (M = 40) vs {mean20} (M = 20)"
    );
}

/// The range of the head-on bars as measured (docs/multibody.md §13): E(T)/E_0, the rebound's
/// error |v_b(T) + v|/v and the two-step mean force's error, or the typed error, over v/c and M.
/// Run with `--ignored --nocapture`.
#[test]
#[ignore = "a measurement for the docs' Range section (about a minute)"]
fn head_on_bars_range_sweep() {
    for v in [0.001, 0.01, 0.03, 0.1, 0.2] {
        for m in [10, 20, 40, 80] {
            let (solver, exact, _) = bars(m, v);
            match run_recorded(&solver, &[MATERIAL; 2]) {
                Ok(run) => {
                    let r = &run.solution.records;
                    let (e0, en) = (r[0].energy, r[r.len() - 1].energy);
                    let last = run.history.last().expect("a step");
                    let rebound = (last.velocities[0][0] + v)
                        .abs()
                        .max((last.velocities[1][0] - v).abs())
                        / v;
                    let force = exact.area() * exact.contact_stress();
                    let k = solver.step_size();
                    // the middle half of the exact contact interval
                    let (t0, span) = (
                        exact.contact_start(),
                        exact.contact_end() - exact.contact_start(),
                    );
                    let mean = run
                        .history
                        .iter()
                        .filter(|h| h.time - k > t0 + 0.25 * span && h.time + k < t0 + 0.75 * span)
                        .map(|h| (h.normal_force_mean / force - 1.0).abs())
                        .fold(0.0, f64::max);
                    println!("v/c = {v}, M = {m}: E(T)/E0 = {:.4}, rebound error {rebound:.3e}, mean force error {mean:.3e}, activation {:.3e} E0", en / e0, run.summary.activation_work / e0);
                }
                Err(e) => println!("v/c = {v}, M = {m}: {e}"),
            }
        }
    }
}
