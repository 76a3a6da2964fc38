//! Case kind `dynamic_bar_wall`: a free elastic bar hitting a rigid wall (`docs/dynamic.md`
//! §5), against [`crate::exact::signorini_bar::BarWallImpact`].
//!
//! The bar (0, L), no supports, moves with u_t = −v0 towards a wall at x = −g0 (its left end
//! meets it at t0 = g0/v0). Exact: contact lasts 2L/c (c = √(E/ρ)), the contact force is
//! A ρ c v0 throughout, the bar leaves with +v0 and all the energy ½ ρ A L v0² is kinetic again.
//! Each `[[family]]` runs along each `[[sweep]]` up to T (past the separation); every run
//! measures, relative to the exact values,
//!
//! | error | definition |
//! |---|---|
//! | `duration_error` | |T_c − 2L/c| / (2L/c), T_c = k × (last − first step with N > 0, + 1) |
//! | `plateau_stress_error` | |⟨N⟩/A − ρ c v0| / (ρ c v0), ⟨N⟩ the mean force over the steps in the middle half of the exact contact interval |
//! | `mean_stress_error` | |I/(A T_c) − ρ c v0| / (ρ c v0), I = Σ k N_n the impulse (Newmark: trapezoidal) |
//! | `rebound_velocity_error` | |P_N/m − v0| / v0, P = 1ᵀ M v the momentum at T, m = ρ A L |
//! | `energy_error` | |E_N − ½ m v0²| / (½ m v0²), E = kinetic + elastic at T (Φ = 0 after separation) |
//! | `centre_velocity_max` | max_n |P_n/m − v_cm(t_n)| / v0, v_cm the exact centre-of-mass velocity |
//! | `penetration_max` | max_n p_n / (v0 · 2L/c) (the penetration relative to the distance the bar would travel during contact) |
//!
//! A run whose contact has not ended by T (force at the last step) is an error.

use serde::{Deserialize, Serialize};

use contactlab::model::dynamic::bar::BarSupports;
use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::dynamic::solver::StepView;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::{CaseReport, Table};
use crate::dynamic::cases::bars::family::{BarSetup, FamilySpec};
use crate::dynamic::cases::bars::gates::{check_common, CeilingGate, RateGate};
use crate::dynamic::cases::bars::runs::{
    exact_history, history_panel, plot_convergence, plot_shown_audits, report_runs, run_jobs,
    solve_timed, step_impulse, RunOutput, ShownRun, WallRun,
};
use crate::dynamic::cases::bars::sweep::{Job, SweepOutcome, SweepSpec};
use crate::exact::signorini_bar::BarWallImpact;

/// The measured quantities (module docs).
pub const ERRORS: [&str; 7] = [
    "duration_error",
    "plateau_stress_error",
    "mean_stress_error",
    "rebound_velocity_error",
    "energy_error",
    "centre_velocity_max",
    "penetration_max",
];

/// The case format of kind `dynamic_bar_wall` (unknown keys are errors).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarWallCase {
    pub bar: BarSpec,
    /// T (after the separation at g0/v0 + 2L/c).
    pub final_time: f64,
    /// The level whose histories are plotted.
    pub show: ShowSpec,
    #[serde(rename = "family")]
    pub families: Vec<FamilySpec>,
    #[serde(rename = "sweep", default)]
    pub sweeps: Vec<SweepSpec>,
    #[serde(rename = "gate", default)]
    pub gates: Vec<RateGate>,
    #[serde(rename = "ceiling", default)]
    pub ceilings: Vec<CeilingGate>,
}

/// `[bar]`: the bar and its approach.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarSpec {
    pub length: f64,
    pub density: f64,
    pub young: f64,
    pub area: f64,
    /// v0 > 0: the bar moves with −v0.
    pub speed: f64,
    /// g0 ≥ 0: the initial distance from the left end to the wall.
    pub gap: f64,
}

impl BarSpec {
    fn exact(&self) -> BarWallImpact {
        BarWallImpact {
            length: self.length,
            density: self.density,
            young: self.young,
            area: self.area,
            speed: self.speed,
            gap: self.gap,
        }
    }

    fn setup(&self) -> BarSetup {
        BarSetup {
            length: self.length,
            density: self.density,
            young: self.young,
            area: self.area,
            supports: BarSupports::default(),
        }
    }
}

/// `[show]`: one level run by every family with its histories recorded and plotted.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShowSpec {
    pub elements: usize,
    /// k = courant · h / c.
    pub courant: f64,
}

impl BarWallCase {
    /// Parses and checks a case of this kind.
    pub fn from_case(case: &Case) -> Result<Self, CaseError> {
        let path = case.path().display().to_string();
        let file: Self = case.body()?;
        let invalid = |field: &str, value: f64, expected: &str| CaseError::Invalid {
            path: path.clone(),
            field: field.into(),
            value: value.to_string(),
            expected: expected.into(),
        };
        let b = &file.bar;
        for (name, v) in [
            ("bar.length", b.length),
            ("bar.density", b.density),
            ("bar.young", b.young),
            ("bar.area", b.area),
            ("bar.speed", b.speed),
            ("final_time", file.final_time),
            ("show.courant", file.show.courant),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(name, v, "a finite number > 0"));
            }
        }
        if !(b.gap.is_finite() && b.gap >= 0.0) {
            return Err(invalid("bar.gap", b.gap, "a finite gap ≥ 0"));
        }
        let exact = b.exact();
        let release = exact.contact_start() + exact.contact_duration();
        let mut times = vec![("final_time".to_string(), file.final_time)];
        for (i, s) in file.sweeps.iter().enumerate() {
            if let Some(t) = s.final_time {
                times.push((format!("sweep[{i}].final_time"), t));
            }
        }
        for (field, t) in times {
            if t <= release {
                return Err(invalid(
                    &field,
                    t,
                    &format!("a time after the separation at g0/v0 + 2L/c = {release}"),
                ));
            }
        }
        if file.show.elements == 0 {
            return Err(invalid("show.elements", 0.0, "M ≥ 1"));
        }
        check_common(
            case,
            &file.families,
            &file.sweeps,
            &file.gates,
            &file.ceilings,
            &ERRORS,
        )?;
        Ok(file)
    }
}

/// Checks the case's format.
pub fn check(case: &Case) -> Result<(), CaseError> {
    BarWallCase::from_case(case).map(|_| ())
}

/// The histories of a shown run.
#[derive(Debug, Clone, Default)]
struct History {
    time: Vec<f64>,
    contact_force: Vec<f64>,
    centre_velocity: Vec<f64>,
}

/// The running measurements of one run.
#[derive(Debug, Default)]
struct Accumulator {
    first_contact: Option<usize>,
    last_contact: Option<usize>,
    impulse: f64,
    previous_force: f64,
    plateau_sum: f64,
    plateau_count: usize,
    centre_max: f64,
    penetration: f64,
    last_force: f64,
    momentum: f64,
    energy: f64,
}

/// P = 1ᵀ M v = Σ_e ρ A h_e (v_a + v_b)/2 (the rows of the consistent and the lumped mass both
/// sum to the lumped masses).
fn momentum(bar: &BarSpec, h: f64, v: &[f64]) -> f64 {
    bar.density * bar.area * h * v.windows(2).map(|w| 0.5 * (w[0] + w[1])).sum::<f64>()
}

/// Runs one family on (M, N) up to T.
fn run_level(
    bar: &BarSpec,
    family: &FamilySpec,
    elements: usize,
    steps: usize,
    final_time: f64,
    record: bool,
) -> Result<RunOutput<History>, String> {
    let exact = bar.exact();
    let WallRun {
        solver,
        sign,
        h,
        k,
        midpoint,
        ..
    } = WallRun::new(
        &bar.setup(),
        family,
        (elements, steps, final_time),
        -bar.gap,
        |body| {
            let dofs = body.dofs();
            (vec![0.0; dofs], vec![-bar.speed; dofs])
        },
    )?;
    let (t0, tc) = (exact.contact_start(), exact.contact_duration());
    let mass = exact.mass();
    let mut acc = Accumulator::default();
    let mut history = record.then(History::default);
    let label = format!("{} (M = {elements}, N = {steps})", family.name);
    let (solution, solver_seconds) = solve_timed(&solver, &label, |view: &StepView<'_>| {
        let t = view.time;
        // every node is free: the free-dof vector is the nodal vector
        let force = -sign * view.forces[0].force_nd;
        if view.step > 0 {
            acc.impulse += step_impulse(midpoint, k, force, acc.previous_force);
            if force > 0.0 {
                acc.first_contact.get_or_insert(view.step);
                acc.last_contact = Some(view.step);
            }
            if (t0 + 0.25 * tc..=t0 + 0.75 * tc).contains(&t) {
                acc.plateau_sum += force;
                acc.plateau_count += 1;
            }
        }
        acc.previous_force = force;
        acc.last_force = force;
        acc.momentum = momentum(bar, h, view.velocity);
        let v_cm = acc.momentum / mass;
        acc.centre_max = acc
            .centre_max
            .max((v_cm - exact.centre_velocity(t)).abs() / bar.speed);
        acc.penetration = acc.penetration.max(view.forces[0].p);
        acc.energy = view.record.energy();
        if let Some(hist) = history.as_mut() {
            hist.time.push(t);
            hist.contact_force.push(force);
            hist.centre_velocity.push(v_cm);
        }
    })?;
    if acc.last_force > 0.0 {
        return Err(format!(
            "{label}: the bar is still in contact at T = {final_time}"
        ));
    }
    let (Some(first), Some(last)) = (acc.first_contact, acc.last_contact) else {
        return Err(format!("{label}: the bar never touched the wall"));
    };
    let duration = k * (last - first + 1) as f64;
    let stress = exact.contact_stress();
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
    let errors = [
        ("duration_error", rel(duration, tc)),
        (
            "plateau_stress_error",
            rel(
                acc.plateau_sum / acc.plateau_count.max(1) as f64 / bar.area,
                stress,
            ),
        ),
        (
            "mean_stress_error",
            rel(acc.impulse / (bar.area * duration), stress),
        ),
        (
            "rebound_velocity_error",
            rel(acc.momentum / mass, exact.rebound_velocity()),
        ),
        ("energy_error", rel(acc.energy, exact.energy())),
        ("centre_velocity_max", acc.centre_max),
        (
            "penetration_max",
            acc.penetration.max(0.0) / (bar.speed * tc),
        ),
    ];
    Ok(RunOutput::new(
        (elements, steps, h, k),
        &errors,
        solution,
        solver_seconds,
        history,
        record,
    ))
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let id = case.header.id.as_str();
    let file = BarWallCase::from_case(case).map_err(|e| e.to_string())?;
    let setup = file.bar.setup();
    let jobs = Job::list(
        &file.sweeps,
        &file.families,
        &setup,
        file.final_time,
        (file.show.elements, file.show.courant),
        |_| true,
    );
    let (outcomes, shown) = run_jobs(ctx, id, &jobs, &file.sweeps, &file.families, |j| {
        run_level(
            &file.bar,
            &file.families[j.family],
            j.elements,
            j.steps,
            j.final_time,
            j.sweep.is_none(),
        )
    })?;
    report_runs(
        report,
        "every run: the measured relative errors",
        &ERRORS,
        &file.families,
        &file.gates,
        &file.ceilings,
        &outcomes,
    );
    report.tables.push(exact_table(&file));
    plots(&file, ctx, report, &outcomes, &shown)
}

/// The exact values of the case.
fn exact_table(file: &BarWallCase) -> Table {
    let e = file.bar.exact();
    Table {
        title: "the exact impact (docs/dynamic.md §5)".into(),
        header: [
            "c = √(E/ρ)",
            "contact from t0 = g0/v0",
            "duration 2L/c",
            "stress ρ c v0",
            "force A ρ c v0",
            "rebound velocity",
            "energy ½ m v0²",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows: vec![vec![
            format!("{}", e.wave_speed()),
            format!("{}", e.contact_start()),
            format!("{}", e.contact_duration()),
            format!("{}", e.contact_stress()),
            format!("{}", e.area * e.contact_stress()),
            format!("{}", e.rebound_velocity()),
            format!("{}", e.energy()),
        ]],
    }
}

/// Every plot of the case.
fn plots(
    file: &BarWallCase,
    ctx: &RunContext,
    report: &mut CaseReport,
    outcomes: &[SweepOutcome],
    shown: &[ShownRun<History>],
) -> Result<(), String> {
    let id = report.id.clone();
    let id = id.as_str();
    let exact = file.bar.exact();
    let level = {
        let setup = file.bar.setup();
        let s = SweepSpec::single(file.show.elements, file.show.courant);
        let (m, n) = s.levels(setup.length, setup.wave_speed(), file.final_time)[0];
        format!("M = {m}, N = {n}")
    };
    plot_shown_audits(
        ctx,
        report,
        id,
        &level,
        &file.families,
        shown,
        exact.energy(),
    )?;
    let columns = shown.len().clamp(1, 3);
    let panels = |pick: &dyn Fn(&History) -> &Vec<f64>, y: &str, f: &dyn Fn(f64) -> f64| {
        shown
            .iter()
            .map(|o| {
                history_panel(
                    &file.families[o.family].name,
                    y,
                    &o.history.time,
                    pick(&o.history),
                    exact_history("exact", file.final_time, 4000, f),
                )
            })
            .collect::<Vec<_>>()
    };
    ctx.panels(
        report,
        "contact_force",
        &format!(
            "{} ({level}): contact force against the exact A ρ c v0 on [t0, t0 + 2L/c]",
            id
        ),
        &panels(&|h| &h.contact_force, "N(t)", &|t| exact.contact_force(t)),
        columns,
    )?;
    ctx.panels(
        report,
        "centre_velocity",
        &format!(
            "{} ({level}): velocity of the centre of mass P(t)/m against the exact",
            id
        ),
        &panels(&|h| &h.centre_velocity, "v_cm(t)", &|t| {
            exact.centre_velocity(t)
        }),
        columns,
    )?;
    plot_convergence(ctx, report, id, &file.sweeps, &file.gates, outcomes)
}

#[cfg(test)]
mod tests {
    //! The case format (unknown keys, a final time before the separation, a negative gap are
    //! typed errors naming the field) and one small run against the exact impact.
    use super::*;
    use std::path::Path;

    const MINIMAL: &str = r#"
id = "t"
title = "t"
kind = "dynamic_bar_wall"
explanation = "e"
final_time = 3.0
[bar]
length = 1.0
density = 1.0
young = 1.0
area = 1.0
speed = 1.0
gap = 0.1
[show]
elements = 10
courant = 1.0
[[family]]
name = "ec"
treatment = "energy_consistent"
scheme = "midpoint"
stiffness = 10.0
[[sweep]]
name = "d"
elements = [20, 40, 80]
courant = 1.0
[[ceiling]]
sweep = "d"
family = "ec"
error = "energy_error"
ceiling = 1e-12
"#;

    fn load(text: &str) -> Result<Case, CaseError> {
        let case = Case::from_text(Path::new("t.toml"), text)?;
        check(&case)?;
        Ok(case)
    }

    #[test]
    fn minimal_case_parses_and_bad_input_is_a_typed_error() {
        assert!(load(MINIMAL).is_ok());
        let e = load(&MINIMAL.replace("gap = 0.1", "gap = 0.1\ncolour = 2"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("colour"), "{e}");
        let e = load(&MINIMAL.replace("gap = 0.1", "gap = -0.1"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("bar.gap"), "{e}");
        let e = load(&MINIMAL.replace("final_time = 3.0", "final_time = 2.0"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("final_time"), "{e}");
        let e = load(&MINIMAL.replace("error = \"energy_error\"", "error = \"nope\""))
            .unwrap_err()
            .to_string();
        assert!(e.contains("ceiling[0].error"), "{e}");
    }

    #[test]
    fn energy_consistent_impact_conserves_energy_and_rebounds() {
        let file = BarWallCase::from_case(&load(MINIMAL).unwrap()).unwrap();
        let out = run_level(&file.bar, &file.families[0], 40, 120, 3.0, false).unwrap();
        let e = &out.level.errors;
        // E + Φ is conserved exactly and Φ = 0 after the separation
        assert!(e["energy_error"] < 1e-12, "{e:?}");
        assert!(e["duration_error"] < 0.1, "{e:?}");
        assert!(e["rebound_velocity_error"] < 0.1, "{e:?}");
        assert!(e["plateau_stress_error"] < 0.1, "{e:?}");
    }
}

#[cfg(test)]
mod scratch {
    use super::*;
    use crate::dynamic::cases::bars::family::{Scaling, TreatmentKind};
    use contactlab::model::dynamic::bar::MassMatrix;
    use contactlab::model::dynamic::scheme::DynamicScheme;

    #[test]
    #[ignore]
    fn dump_rebound() {
        let bar = BarSpec {
            length: 2.0,
            density: 4.0,
            young: 9.0,
            area: 0.5,
            speed: 0.3,
            gap: 0.06,
        };
        for (treat, r) in [
            (TreatmentKind::EnergyConsistent, Some(10.0)),
            (TreatmentKind::Signorini, None),
            (TreatmentKind::Penalty, Some(100.0)),
        ] {
            let fam = FamilySpec {
                name: "x".into(),
                treatment: treat,
                scheme: DynamicScheme::Midpoint,
                mass: MassMatrix::Consistent,
                stiffness: r,
                stiffness_scaling: Scaling::Element,
                depth: None,
                depth_scaling: Scaling::Element,
                law: Default::default(),
                full_path: false,
            };
            let mut prev: Option<(f64, f64)> = None;
            for m in [50usize, 100, 200, 400, 800, 1600, 3200, 6400, 12800] {
                let n = (3.6f64 / (2.0 / m as f64 / 1.5)).round() as usize;
                let out = run_level(&bar, &fam, m, n, 3.6, false).unwrap();
                let e = &out.level.errors;
                let v = e["rebound_velocity_error"];
                let rate = prev
                    .map(|(h0, e0)| (e0 / v).ln() / (h0 / (2.0 / m as f64)).ln())
                    .unwrap_or(f64::NAN);
                println!("{treat:?} M={m} rebound {v:.4e} rate {rate:.3} energy {:.3e} dur {:.3e} cv {:.3e}", e["energy_error"], e["duration_error"], e["centre_velocity_max"]);
                prev = Some((2.0 / m as f64, v));
            }
        }
    }
}
