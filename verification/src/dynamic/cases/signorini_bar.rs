//! Case kind `dynamic_signorini_bar`: the periodic Signorini bar of `docs/dynamic.md` §5
//! against its exact solution ([`crate::exact::signorini_bar::PeriodicSignoriniBar`]).
//!
//! The bar (0, 1), ρ = E = A = 1, held at x = 1, meets an obstacle at x = 0 (a wall at 0 against
//! its left end: p = −u(0, t)), u0 = (1 − x)/2, v0 = 0; P1 elements on M equal elements, N
//! uniform steps up to T. Each `[[family]]` (treatment × scheme × mass) runs along each
//! `[[sweep]]`; every run measures
//!
//! | error | definition |
//! |---|---|
//! | `contact_displacement_max` | max_n |u_h(0, t_n) − u(0, t_n)| |
//! | `displacement_l2_final` | ‖u_h(T) − u(T)‖_L² (exact integration, elements split at the kinks) |
//! | `displacement_l2_max` | max_n ‖u_h(t_n) − u(t_n)‖_L² |
//! | `energy_norm_final` | (‖v_h(T) − u_t(T)‖² + ‖u_h,x(T) − u_x(T)‖²)^½, v_h the scheme's velocity |
//! | `energy_final`, `energy_max` | |E_N − 1/8|, max_n |E_n − 1/8|, E_n = ½ v_nᵀ M v_n + ½ u_nᵀ K u_n |
//! | `energy_mean` | (1/T) Σ_{n ≥ 1} k |E_n − 1/8|, the time mean of the energy error (the maximum samples the peak of a chattering contact force at a phase that varies from level to level; the mean does not) |
//! | `total_energy_max` | max_n |E_n + Φ_n − 1/8| (Φ the penalty energy) |
//! | `impulse_max` | max_n |I_h(t_n) − I(t_n)|, I_h = Σ k N_j (midpoint type: the force at t_j acts over step j; Newmark: the trapezoidal mean), I(t) = ∫₀ᵗ −σ(0, s) ds |
//! | `penetration_max` | max_n (−u_h(0, t_n))_+ |
//!
//! and keeps its energy audit summary. Rate gates (`[[gate]]`), ceilings (`[[ceiling]]`), the
//! audit gate of every family (identities per [`FamilySpec::audit_checks`]), and identity gates
//! between two families on the shown level (`[[identical]]`, e.g. the HLT tilted force against
//! the energy-consistent force, which coincide against a plane wall) decide the case.

use serde::{Deserialize, Serialize};

use contactlab::model::dynamic::bar::BarSupports;
use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::dynamic::solver::StepView;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::dynamic::cases::bars::family::{BarSetup, FamilySpec};
use crate::dynamic::cases::bars::gates::{check_common, CeilingGate, RateGate};
use crate::dynamic::cases::bars::runs::{
    exact_history, history_panel, plot_convergence, plot_shown_audits, report_runs, run_jobs,
    solve_timed, step_impulse, RunOutput, ShownRun, WallRun,
};
use crate::dynamic::cases::bars::sweep::{Job, SweepOutcome, SweepSpec};
use crate::exact::signorini_bar::{PeriodicSignoriniBar, ENERGY};
use crate::plot::{Figure, Series};

/// The measured quantities (module docs).
pub const ERRORS: [&str; 10] = [
    "contact_displacement_max",
    "displacement_l2_final",
    "displacement_l2_max",
    "energy_norm_final",
    "energy_final",
    "energy_max",
    "energy_mean",
    "total_energy_max",
    "impulse_max",
    "penetration_max",
];

/// The bar of the benchmark: (0, 1), ρ = E = A = 1, held at x = 1.
const BAR: BarSetup = BarSetup {
    length: 1.0,
    density: 1.0,
    young: 1.0,
    area: 1.0,
    supports: BarSupports {
        left: false,
        right: true,
    },
};

/// The case format of kind `dynamic_signorini_bar` (unknown keys are errors).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SignoriniBarCase {
    /// T (the solution is 3-periodic).
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
    #[serde(rename = "identical", default)]
    pub identical: Vec<IdenticalSpec>,
}

/// `[show]`: one level run by every family with its histories recorded and plotted.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShowSpec {
    pub elements: usize,
    /// k = courant · h / c.
    pub courant: f64,
    /// The families shown (default: all).
    #[serde(default)]
    pub families: Vec<String>,
}

/// `[[identical]]`: two families whose trajectories on the shown level must agree to a relative
/// tolerance (max over steps and nodes of |u_a − u_b| / max |u_a|).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IdenticalSpec {
    pub families: [String; 2],
    pub tolerance: f64,
    #[serde(default)]
    pub note: String,
}

impl SignoriniBarCase {
    /// Parses and checks a case of this kind.
    pub fn from_case(case: &Case) -> Result<Self, CaseError> {
        let path = case.path().display().to_string();
        let file: Self = case.body()?;
        let invalid = |field: &str, value: String, expected: &str| CaseError::Invalid {
            path: path.clone(),
            field: field.into(),
            value,
            expected: expected.into(),
        };
        if !(file.final_time.is_finite() && file.final_time > 0.0) {
            return Err(invalid(
                "final_time",
                file.final_time.to_string(),
                "a finite T > 0",
            ));
        }
        if file.show.elements == 0 {
            return Err(invalid("show.elements", "0".into(), "M ≥ 1"));
        }
        if !(file.show.courant.is_finite() && file.show.courant > 0.0) {
            return Err(invalid(
                "show.courant",
                file.show.courant.to_string(),
                "a number > 0",
            ));
        }
        for f in &file.show.families {
            if !file.families.iter().any(|g| &g.name == f) {
                return Err(invalid("show.families", f.clone(), "names of [[family]]s"));
            }
        }
        for (i, s) in file.identical.iter().enumerate() {
            for f in &s.families {
                if !file.families.iter().any(|g| &g.name == f) || !file.shows(f) {
                    return Err(invalid(
                        &format!("identical[{i}].families"),
                        f.clone(),
                        "names of shown [[family]]s",
                    ));
                }
            }
            if !(s.tolerance.is_finite() && s.tolerance > 0.0) {
                return Err(invalid(
                    &format!("identical[{i}].tolerance"),
                    s.tolerance.to_string(),
                    "a number > 0",
                ));
            }
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

    fn shows(&self, family: &str) -> bool {
        self.show.families.is_empty() || self.show.families.iter().any(|f| f == family)
    }
}

/// Checks the case's format.
pub fn check(case: &Case) -> Result<(), CaseError> {
    SignoriniBarCase::from_case(case).map(|_| ())
}

/// The histories of a shown run.
#[derive(Debug, Clone, Default)]
struct History {
    time: Vec<f64>,
    contact_displacement: Vec<f64>,
    contact_force: Vec<f64>,
    energy: Vec<f64>,
    /// u_h at every node and step (for the identity gates).
    trajectory: Vec<f64>,
    final_nodal: Vec<f64>,
}

/// The running maxima of one run.
#[derive(Debug, Default)]
struct Accumulator {
    contact: f64,
    l2_max: f64,
    energy_max: f64,
    /// Σ_{n ≥ 1} k |E_n − 1/8|.
    energy_integral: f64,
    total_energy_max: f64,
    impulse: f64,
    impulse_max: f64,
    previous_force: f64,
    penetration: f64,
    last: Option<crate::exact::signorini_bar::FieldErrors>,
    energy_last: f64,
}

/// Runs one family on (M, N) up to T.
fn run_level(
    family: &FamilySpec,
    elements: usize,
    steps: usize,
    final_time: f64,
    record: bool,
) -> Result<RunOutput<History>, String> {
    let exact = PeriodicSignoriniBar;
    let h = BAR.length / elements as f64;
    let nodes: Vec<f64> = (0..=elements).map(|i| i as f64 * h).collect();
    let WallRun {
        body,
        solver,
        sign,
        k,
        midpoint,
        ..
    } = WallRun::new(&BAR, family, (elements, steps, final_time), 0.0, |body| {
        let u0 = body.from_nodal(&nodes.iter().map(|x| (1.0 - x) / 2.0).collect::<Vec<_>>());
        (u0, vec![0.0; body.dofs()])
    })?;
    let left = body.node_dof(0).ok_or("the left end must be free")?;
    let mut acc = Accumulator::default();
    let mut history = record.then(History::default);
    let (mut un, mut vn) = (vec![0.0; elements + 1], vec![0.0; elements + 1]);
    let label = format!("{} (M = {elements}, N = {steps})", family.name);
    let (solution, solver_seconds) = solve_timed(&solver, &label, |view: &StepView<'_>| {
        let t = view.time;
        fill_nodal(&body, view.displacement, &mut un);
        fill_nodal(&body, view.velocity, &mut vn);
        let u_left = view.displacement[left];
        acc.contact = acc
            .contact
            .max((u_left - exact.contact_displacement(t)).abs());
        acc.penetration = acc.penetration.max(-u_left);
        let fe = exact.field_errors(&nodes, &un, &vn, t);
        acc.l2_max = acc.l2_max.max(fe.displacement_l2);
        acc.last = Some(fe);
        let energy = view.record.energy();
        acc.energy_last = energy;
        acc.energy_max = acc.energy_max.max((energy - ENERGY).abs());
        if view.step > 0 {
            acc.energy_integral += k * (energy - ENERGY).abs();
        }
        acc.total_energy_max = acc
            .total_energy_max
            .max((energy + view.record.penalty - ENERGY).abs());
        let force = -sign * view.forces[0].force_nd;
        if view.step > 0 {
            acc.impulse += step_impulse(midpoint, k, force, acc.previous_force);
        }
        acc.previous_force = force;
        acc.impulse_max = acc
            .impulse_max
            .max((acc.impulse - exact.contact_impulse(t)).abs());
        if let Some(hist) = history.as_mut() {
            hist.time.push(t);
            hist.contact_displacement.push(u_left);
            hist.contact_force.push(force);
            hist.energy.push(energy);
            hist.trajectory.extend_from_slice(&un);
        }
    })?;
    let last = acc.last.unwrap_or_default();
    let errors = [
        ("contact_displacement_max", acc.contact),
        ("displacement_l2_final", last.displacement_l2),
        ("displacement_l2_max", acc.l2_max),
        ("energy_norm_final", last.energy_norm()),
        ("energy_final", (acc.energy_last - ENERGY).abs()),
        ("energy_max", acc.energy_max),
        ("energy_mean", acc.energy_integral / final_time),
        ("total_energy_max", acc.total_energy_max),
        ("impulse_max", acc.impulse_max),
        ("penetration_max", acc.penetration.max(0.0)),
    ];
    if let Some(hist) = history.as_mut() {
        hist.final_nodal = body.nodal(&solution.final_displacement);
    }
    Ok(RunOutput::new(
        (elements, steps, h, k),
        &errors,
        solution,
        solver_seconds,
        history,
        record,
    ))
}

/// Nodal values of a free-dof vector into `out` (0 at the held end).
fn fill_nodal(body: &contactlab::model::dynamic::bar::BarBody, u: &[f64], out: &mut [f64]) {
    for (i, o) in out.iter_mut().enumerate() {
        *o = body.node_dof(i).map_or(0.0, |d| u[d]);
    }
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let id = case.header.id.as_str();
    let file = SignoriniBarCase::from_case(case).map_err(|e| e.to_string())?;
    let jobs = Job::list(
        &file.sweeps,
        &file.families,
        &BAR,
        file.final_time,
        (file.show.elements, file.show.courant),
        |f| file.shows(f),
    );
    let (outcomes, shown) = run_jobs(ctx, id, &jobs, &file.sweeps, &file.families, |j| {
        run_level(
            &file.families[j.family],
            j.elements,
            j.steps,
            j.final_time,
            j.sweep.is_none(),
        )
    })?;
    report_runs(
        report,
        "every run: the measured errors",
        &ERRORS,
        &file.families,
        &file.gates,
        &file.ceilings,
        &outcomes,
    );
    report.gates.extend(identity_gates(&file, &shown));
    report.tables.push(shown_table(&file, &shown));
    plots(&file, ctx, report, &outcomes, &shown)
}

/// The identity gates between families on the shown level.
fn identity_gates(file: &SignoriniBarCase, shown: &[ShownRun<History>]) -> Vec<GateVerdict> {
    let trajectory = |name: &str| {
        shown
            .iter()
            .find(|o| file.families[o.family].name == name)
            .map(|o| &o.history.trajectory)
    };
    file.identical
        .iter()
        .map(|spec| {
            let [a, b] = &spec.families;
            let observed = match (trajectory(a), trajectory(b)) {
                (Some(x), Some(y)) if x.len() == y.len() => {
                    let scale = x.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
                    x.iter()
                        .zip(y)
                        .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()))
                        / scale
                }
                _ => f64::NAN,
            };
            let mut check = Check::at_most(
                &format!("max over steps and nodes |u_{a} − u_{b}| / max |u_{a}|"),
                observed,
                spec.tolerance,
            );
            check.passed &= observed.is_finite();
            GateVerdict::from_checks(
                format!("identical trajectories: {a} and {b}"),
                "identity",
                vec![check],
                &spec.note,
            )
        })
        .collect()
}

/// The shown runs' errors and statistics.
fn shown_table(file: &SignoriniBarCase, shown: &[ShownRun<History>]) -> Table {
    let rows = shown
        .iter()
        .map(|o| {
            let l = &o.level;
            let e = |n: &str| l.errors.get(n).map_or("–".into(), |v| format!("{v:.3e}"));
            vec![
                file.families[o.family].name.clone(),
                format!("{} / {}", l.elements, l.steps),
                e("contact_displacement_max"),
                e("displacement_l2_final"),
                e("energy_final"),
                e("impulse_max"),
                e("penetration_max"),
                format!("{:.3}", l.stats.newton_iterations as f64 / l.steps as f64),
                l.stats.max_newton_iterations.to_string(),
                format!("{:.2}", l.micros_per_step()),
            ]
        })
        .collect();
    Table {
        title: format!(
            "shown level (M = {}, k = {} h): errors and cost",
            file.show.elements, file.show.courant
        ),
        header: [
            "family",
            "M / N",
            "max |u_h(0) − u(0)|",
            "‖u_h(T) − u(T)‖",
            "|E_N − 1/8|",
            "impulse error",
            "max penetration",
            "Newton it./step",
            "max it.",
            "µs/step",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    }
}

/// Every plot of the case.
fn plots(
    file: &SignoriniBarCase,
    ctx: &RunContext,
    report: &mut CaseReport,
    outcomes: &[SweepOutcome],
    shown: &[ShownRun<History>],
) -> Result<(), String> {
    let id = report.id.clone();
    let id = id.as_str();
    let level = shown
        .first()
        .map(|o| format!("M = {}, N = {}", o.level.elements, o.level.steps))
        .unwrap_or_default();
    plot_shown_audits(ctx, report, id, &level, &file.families, shown, ENERGY)?;
    let histories: Vec<(&str, &History)> = shown
        .iter()
        .map(|o| (file.families[o.family].name.as_str(), &o.history))
        .collect();
    history_panels(file, ctx, report, &level, &histories)?;
    plot_convergence(ctx, report, id, &file.sweeps, &file.gates, outcomes)
}

/// One panel per shown family against the exact solution: u(0, t), the contact force, the
/// energy error E_n − 1/8 and u_h(x, T).
fn history_panels(
    file: &SignoriniBarCase,
    ctx: &RunContext,
    report: &mut CaseReport,
    level: &str,
    histories: &[(&str, &History)],
) -> Result<(), String> {
    let id = report.id.clone();
    let id = id.as_str();
    let exact = PeriodicSignoriniBar;
    let exact_series =
        |name: &str, f: &dyn Fn(f64) -> f64| exact_history(name, file.final_time, 3000, f);
    let columns = histories.len().clamp(1, 3);
    let figs: Vec<Figure> = histories
        .iter()
        .map(|(name, h)| {
            history_panel(
                name,
                "u(0, t)",
                &h.time,
                &h.contact_displacement,
                exact_series("exact", &|t| exact.contact_displacement(t)),
            )
        })
        .collect();
    ctx.panels(
        report,
        "contact_displacement",
        &format!("{} ({level}): u_h(0, t) against the exact u(0, t)", id),
        &figs,
        columns,
    )?;
    let figs: Vec<Figure> = histories
        .iter()
        .map(|(name, h)| {
            history_panel(
                name,
                "N(t)",
                &h.time,
                &h.contact_force,
                exact_series("exact −σ(0, t)", &|t| -exact.contact_stress(t)),
            )
        })
        .collect();
    ctx.panels(
        report,
        "contact_force",
        &format!(
            "{} ({level}): contact force N(t) against the exact −σ(0, t) = 1/2 on [1, 2] mod 3",
            id
        ),
        &figs,
        columns,
    )?;
    let figs: Vec<Figure> = histories
        .iter()
        .map(|(name, h)| {
            history_panel(
                name,
                "E_n − 1/8",
                &h.time,
                &h.energy.iter().map(|e| e - ENERGY).collect::<Vec<_>>(),
                exact_series("exact", &|_| 0.0),
            )
        })
        .collect();
    ctx.panels(
        report,
        "energy_error",
        &format!(
            "{} ({level}): energy error E_n − 1/8 (kinetic + elastic, without the penalty energy)",
            id
        ),
        &figs,
        columns,
    )?;
    let t = file.final_time;
    let figs: Vec<Figure> = histories
        .iter()
        .map(|(name, h)| {
            let m = h.final_nodal.len().saturating_sub(1).max(1);
            let xs: Vec<f64> = (0..=m).map(|j| j as f64 / m as f64).collect();
            Figure::new(*name)
                .x_label("x")
                .y_label("u(x, T)")
                .series(Series::from_xy("computed", &xs, &h.final_nodal).color(1))
                .series(
                    Series::line(
                        "exact",
                        (0..=1000).map(|j| {
                            let x = j as f64 / 1000.0;
                            (x, exact.displacement(x, t))
                        }),
                    )
                    .color(0)
                    .dashed(),
                )
        })
        .collect();
    ctx.panels(
        report,
        "final_displacement",
        &format!("{} ({level}): u_h(x, T) at T = {t} against the exact u", id),
        &figs,
        columns,
    )
}

#[cfg(test)]
mod tests {
    //! The case format: a minimal valid case parses; unknown keys, a missing stiffness, a
    //! Newmark energy-consistent family, unknown names in gates and bad numbers are typed
    //! errors naming the field. And one small run against the exact solution.
    use super::*;
    use std::path::Path;

    const MINIMAL: &str = r#"
id = "t"
title = "t"
kind = "dynamic_signorini_bar"
explanation = "e"
final_time = 3.0
[show]
elements = 10
courant = 1.0
[[family]]
name = "sig"
treatment = "signorini"
scheme = "midpoint"
[[sweep]]
name = "d"
elements = [10, 20, 40]
courant = 1.0
[[gate]]
sweep = "d"
family = "sig"
error = "contact_displacement_max"
against = "h"
expected_rate = 1.0
tolerance = 0.2
ci_width = 1.0
ceiling_factor = 2.0
"#;

    fn load(text: &str) -> Result<Case, CaseError> {
        let case = Case::from_text(Path::new("t.toml"), text)?;
        check(&case)?;
        Ok(case)
    }

    #[test]
    fn minimal_case_parses() {
        let case = load(MINIMAL).unwrap();
        let file = SignoriniBarCase::from_case(&case).unwrap();
        assert_eq!(file.families.len(), 1);
        assert_eq!(
            file.sweeps[0].levels(1.0, 1.0, 3.0),
            vec![(10, 30), (20, 60), (40, 120)]
        );
    }

    #[test]
    fn unknown_key_is_an_error() {
        let text = MINIMAL.replace("[show]", "typo = 1\n[show]");
        let e = load(&text).unwrap_err().to_string();
        assert!(e.contains("typo"), "{e}");
        let text = MINIMAL.replace("scheme = \"midpoint\"", "scheme = \"midpoint\"\nrr = 2");
        assert!(load(&text).unwrap_err().to_string().contains("rr"));
    }

    #[test]
    fn penalty_without_stiffness_is_an_error_naming_the_field() {
        let text = MINIMAL.replace("\"signorini\"", "\"penalty\"");
        let e = load(&text).unwrap_err().to_string();
        assert!(e.contains("family[0].stiffness"), "{e}");
    }

    #[test]
    fn newmark_energy_consistent_is_an_error() {
        let text = MINIMAL
            .replace("\"signorini\"", "\"energy_consistent\"\nstiffness = 10.0")
            .replace("\"midpoint\"", "\"newmark\"");
        let e = load(&text).unwrap_err().to_string();
        assert!(e.contains("family[0].scheme"), "{e}");
    }

    #[test]
    fn gate_names_and_numbers_are_checked() {
        let e = load(&MINIMAL.replace("family = \"sig\"", "family = \"nope\""))
            .unwrap_err()
            .to_string();
        assert!(e.contains("gate[0].family"), "{e}");
        let e = load(&MINIMAL.replace("\"contact_displacement_max\"", "\"typo\""))
            .unwrap_err()
            .to_string();
        assert!(e.contains("gate[0].error"), "{e}");
        let e = load(&MINIMAL.replace("ceiling_factor = 2.0", "ceiling_factor = -1.0"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("gate[0].ceiling_factor"), "{e}");
        let e = load(&MINIMAL.replace("courant = 1.0\n[[gate]]", "[[gate]]"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("sweep[0].steps"), "{e}");
        let e = load(&MINIMAL.replace("final_time = 3.0", "final_time = 0.0"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("final_time"), "{e}");
    }

    #[test]
    fn coarse_signorini_midpoint_run_tracks_the_exact_solution() {
        let family = SignoriniBarCase::from_case(&load(MINIMAL).unwrap())
            .unwrap()
            .families
            .remove(0);
        let out = run_level(&family, 40, 120, 3.0, true).unwrap();
        let e = &out.level.errors;
        assert!(e["contact_displacement_max"] < 0.05, "{e:?}");
        assert!(e["displacement_l2_final"] < 0.05, "{e:?}");
        assert!(e["energy_max"] < 0.01, "{e:?}");
        // the midpoint balance holds at round-off, the constraint dissipates
        let s = out.level.summary;
        assert!(s.max_drift_1_48 <= s.tolerance(), "{s:?}");
        assert!(s.constraint_work_ratio <= 1.0, "{s:?}");
        let h = out.history.unwrap();
        assert_eq!(h.time.len(), 121);
        assert_eq!(h.trajectory.len(), 121 * 41);
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
    fn dump_energy() {
        for (treat, r, mass) in [
            (
                TreatmentKind::EnergyConsistent,
                Some(10.0),
                MassMatrix::Consistent,
            ),
            (TreatmentKind::Penalty, Some(10.0), MassMatrix::Consistent),
            (TreatmentKind::Signorini, None, MassMatrix::Consistent),
            (TreatmentKind::Signorini, None, MassMatrix::Lumped),
        ] {
            let fam = FamilySpec {
                name: "x".into(),
                treatment: treat,
                scheme: DynamicScheme::Midpoint,
                mass,
                stiffness: r,
                stiffness_scaling: Scaling::Element,
                depth: None,
                depth_scaling: Scaling::Element,
                law: Default::default(),
                full_path: false,
            };
            let mut prev: Option<[f64; 4]> = None;
            for m in [50usize, 100, 200, 400, 800, 1600, 3200, 6400] {
                let out = run_level(&fam, m, 6 * m, 6.0, true).unwrap();
                let h = out.history.unwrap();
                let k = 6.0 / (6 * m) as f64;
                let mean = h
                    .energy
                    .iter()
                    .skip(1)
                    .map(|e| (e - ENERGY).abs())
                    .sum::<f64>()
                    * k
                    / 6.0;
                let signed_mean =
                    h.energy.iter().skip(1).map(|e| e - ENERGY).sum::<f64>() * k / 6.0;
                let l2 = (h
                    .energy
                    .iter()
                    .skip(1)
                    .map(|e| (e - ENERGY).powi(2))
                    .sum::<f64>()
                    * k
                    / 6.0)
                    .sqrt();
                let e = &out.level.errors;
                let v = [e["energy_max"], mean, l2, e["energy_final"]];
                let rates: Vec<String> = prev
                    .map(|p| {
                        (0..4)
                            .map(|i| format!("{:.3}", (p[i] / v[i]).log2()))
                            .collect()
                    })
                    .unwrap_or_default();
                println!("{treat:?} {mass:?} M={m} max {:.3e} mean {:.3e} l2 {:.3e} final {:.3e} signed {signed_mean:+.3e} rates {rates:?}", v[0], v[1], v[2], v[3]);
                prev = Some(v);
            }
        }
    }
}
