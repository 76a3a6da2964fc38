//! `dynamic_extremes`: stability of the dynamic contact solver at the extremes of its data
//! (Barboteu–Danan–Sofonea, "BDS"; Hauret–Le Tallec, "HLT"; `shared/spec/dynamic.md` §§1–3).
//! Every run must give a correct solution or stop with a typed error that carries its data —
//! never a panic, never a NaN in what it recorded. Four studies, each a list in the case file:
//!
//! - `[[blow_up]]` — the midpoint rule against Gonzalez's scheme on a hyperelastic body with a
//!   large step. The midpoint rule evaluates F_int at u_{n−1/2}, whose work over the step is not
//!   𝒲(u_n) − 𝒲(u_{n−1}) for a nonlinear law, so (1.48) fails and the energy can grow without
//!   bound (BDS §1.6; EM paper §4); Gonzalez's discrete gradient (BDS (1.41)–(1.43)) makes
//!   Π^algo : (∇u_n − ∇u_{n−1}) = W̃(C_n) − W̃(C_{n−1}) exact, so the energy is conserved to
//!   round-off without contact and the identities (1.48)/(1.49)/HLT 3.7 hold with an
//!   energy-consistent contact force.
//! - `[[penalty]]` — the penalty stiffness r over many decades on an impact: the condition of
//!   the step Jacobian J = α M + θ K + Σ_i w_i N_i′(p_i) e_i e_iᵀ (full path) and of its Schur
//!   complement on the contact dofs (condensed path) by a dense symmetric eigen-decomposition,
//!   Newton iterations and backtracks, the largest penetration and its asymptotic slope in r,
//!   and the energy identities.
//! - `[[speed]]` — impact speeds over decades: the identities at round-off, and the trends of
//!   penetration and contact time: exact homogeneity (a linear body with zero initial gap: u
//!   scales with v), wave theory for a bar (contact time 2L/c, rebound at v, mean contact force
//!   ρ c A v), Hertz-like stiffening for a curved body (sublinear penetration, non-increasing
//!   contact time).
//! - `[[large_step]]` — time steps from resolved to far above the wave-crossing time h_min/c and
//!   the contact duration: the conserving combinations stay bounded with the identities at
//!   round-off; the others (Newmark, the midpoint rule on a hyperelastic body, the plain
//!   penalty force) are reported.

use std::fmt::Write as _;

use nalgebra::{DMatrix, SymmetricEigen};
use serde::{Deserialize, Serialize};

use contactlab::contact::compliance::{energy_consistent, penalty};
use contactlab::model::dynamic::contact_model::NormalTreatment;
use contactlab::model::dynamic::newton::NodeForces;
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::StepView;
use contactlab::scene::dynamic::{DynamicScene, SceneBody};

use crate::case::{Case, CaseError, Tier};
use crate::dynamic::audit::{audit_checks, plot_audits, AuditRun, ROUND_OFF_LEVEL};
use crate::gate::{Check, GateVerdict};
use crate::plot::{Figure, Series};
use crate::report::case_report::{CaseReport, ExtremeReport, Table};
use crate::run::RunContext;
use crate::scene_dynamic::{
    audit_is_finite, balance_drift, conserving, run_recorded_with, scene_from_table, RecordedRun,
};

/// The case format of `dynamic_extremes` (unknown keys are errors).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ExtremesCase {
    pub id: String,
    pub title: String,
    pub kind: String,
    #[serde(default)]
    pub tier: Tier,
    pub explanation: String,
    #[serde(default)]
    pub blow_up: Vec<BlowUpSpec>,
    #[serde(default)]
    pub penalty: Vec<PenaltySpec>,
    #[serde(default)]
    pub speed: Vec<SpeedSpec>,
    #[serde(default)]
    pub large_step: Vec<LargeStepSpec>,
}

/// `[[blow_up]]`: one scene run with a scheme that does not conserve energy and one that does.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BlowUpSpec {
    pub name: String,
    /// The dynamic scene (inline; `model = "dynamic"` implied); `time.scheme` is set per run.
    pub scene: toml::Table,
    /// The scheme expected to violate (1.48) (the midpoint rule on a hyperelastic body).
    pub unstable: DynamicScheme,
    /// The conserving scheme (Gonzalez).
    pub stable: DynamicScheme,
    /// The least largest relative energy error max_n |(E + Φ)_n − (E + Φ)_0 − W_n| / (E + Φ)_0
    /// the unstable scheme must show before it stops or ends (the blow-up made visible).
    pub min_energy_error: f64,
    #[serde(default)]
    pub note: String,
}

/// `[[penalty]]`: one impact run with each penalty stiffness r (and each solver path).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PenaltySpec {
    pub name: String,
    pub scene: toml::Table,
    /// The values of `contact.stiffness`.
    pub stiffness: Vec<f64>,
    /// `auto` (the model's path) and/or `full` (the full Newton path, for comparison).
    #[serde(default = "default_paths")]
    pub paths: Vec<String>,
    /// Largest number of dofs for which the condition numbers are computed (dense eigenvalues).
    #[serde(default = "default_condition_dofs")]
    pub condition_max_dofs: usize,
    /// The slope of ln(max penetration) against ln r is fitted on the runs with r ≥ this.
    pub slope_from: f64,
    pub expected_slope: f64,
    pub slope_tolerance: f64,
    /// The slope of ln κ(J) (worst case) against ln r, fitted on the runs with
    /// r ≥ `condition_slope_from` (κ ∝ r once r w_i dominates λ_max(α M + θ K)).
    pub expected_condition_slope: Option<f64>,
    pub condition_slope_from: Option<f64>,
    /// Largest Newton iteration count of one step allowed.
    pub max_newton_iterations: usize,
    /// Largest relative difference of the largest penetration between the paths, checked for
    /// r ≤ `path_agreement_up_to` (the resolved regime; beyond, the chattering contact nodes
    /// amplify round-off and the difference is reported only).
    pub path_agreement: Option<f64>,
    pub path_agreement_up_to: Option<f64>,
    #[serde(default)]
    pub note: String,
}

fn default_paths() -> Vec<String> {
    vec!["auto".into()]
}

fn default_condition_dofs() -> usize {
    1200
}

/// `[[speed]]`: one impact at each speed.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedSpec {
    pub name: String,
    pub scene: toml::Table,
    /// Impact speeds |v| (m/s); the initial velocity is v · direction.
    pub speeds: Vec<f64>,
    /// Unit direction of the throw: one component for a bar, two in 2D.
    pub direction: Vec<f64>,
    /// The problem is positively homogeneous in (u, v) (linear body, zero initial gap, no load):
    /// p_max/v, F_max/v, contact time and rebound coefficient must agree across speeds to this
    /// relative tolerance.
    pub homogeneity_tolerance: Option<f64>,
    /// A bar: contact time against 2L/c, rebound coefficient against 1 and mean contact force
    /// against ρ c A v, each to this relative tolerance (wave theory of the free bar).
    pub wave_theory_tolerance: Option<f64>,
    /// Every pairwise exponent d ln p_max / d ln v must lie in this interval.
    pub penetration_exponent: Option<[f64; 2]>,
    /// The contact time must not increase with the speed (by more than one step).
    #[serde(default)]
    pub contact_time_nonincreasing: bool,
    #[serde(default)]
    pub note: String,
}

/// `[[large_step]]`: variants of one scene run with steps from resolved to far too large.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LargeStepSpec {
    pub name: String,
    pub scene: toml::Table,
    /// Numbers of steps over the scene's final time (k = T / N), finest first.
    pub steps: Vec<usize>,
    pub variant: Vec<VariantSpec>,
    /// The largest step must be at least this many wave-crossing times h_min / c …
    pub min_wave_crossings: f64,
    /// … and at least this fraction of the contact duration (measured on the finest run of the
    /// first conserving variant).
    pub min_contact_fraction: f64,
    #[serde(default)]
    pub note: String,
}

/// `[[large_step.variant]]`: scheme, law and contact treatment of one variant.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct VariantSpec {
    pub label: String,
    /// Dotted scene keys and values (`"time.scheme" = "gonzalez"`).
    #[serde(default)]
    pub set: toml::Table,
}

fn invalid(case: &Case, field: &str, value: impl std::fmt::Display, expected: &str) -> CaseError {
    CaseError::Invalid {
        path: case.path.display().to_string(),
        field: field.to_string(),
        value: value.to_string(),
        expected: expected.to_string(),
    }
}

fn parse(case: &Case) -> Result<ExtremesCase, CaseError> {
    case.table
        .clone()
        .try_into()
        .map_err(|e: toml::de::Error| CaseError::Read {
            path: case.path.display().to_string(),
            message: e.to_string(),
        })
}

fn positive(case: &Case, field: &str, v: f64) -> Result<(), CaseError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(case, field, v, "a finite number > 0"))
    }
}

/// Validates a scene table now (its errors name the case file and the study).
fn check_scene(case: &Case, field: &str, scene: &toml::Table) -> Result<(), CaseError> {
    scene_from_table(scene, &toml::Table::new(), field)
        .map(|_| ())
        .map_err(|e| CaseError::Read {
            path: case.path.display().to_string(),
            message: e,
        })
}

/// Checks the case's format: known keys only, valid scenes, sensible numbers.
pub fn check(case: &Case) -> Result<(), CaseError> {
    let c = parse(case)?;
    if c.blow_up.is_empty() && c.penalty.is_empty() && c.speed.is_empty() && c.large_step.is_empty()
    {
        return Err(invalid(
            case,
            "blow_up / penalty / speed / large_step",
            "(none)",
            "at least one study",
        ));
    }
    for (i, b) in c.blow_up.iter().enumerate() {
        let f = format!("blow_up[{i}]");
        check_scene(case, &format!("{f}.scene"), &b.scene)?;
        positive(case, &format!("{f}.min_energy_error"), b.min_energy_error)?;
        if b.unstable == b.stable {
            return Err(invalid(
                case,
                &format!("{f}.stable"),
                b.stable.name(),
                "a scheme other than `unstable`",
            ));
        }
    }
    for (i, p) in c.penalty.iter().enumerate() {
        let f = format!("penalty[{i}]");
        check_scene(case, &format!("{f}.scene"), &p.scene)?;
        if p.stiffness.len() < 3 {
            return Err(invalid(
                case,
                &format!("{f}.stiffness"),
                format!("{} values", p.stiffness.len()),
                "at least 3 values",
            ));
        }
        for (j, r) in p.stiffness.iter().enumerate() {
            positive(case, &format!("{f}.stiffness[{j}]"), *r)?;
        }
        if p.stiffness.iter().filter(|&&r| r >= p.slope_from).count() < 2 {
            return Err(invalid(
                case,
                &format!("{f}.slope_from"),
                p.slope_from,
                "a value with at least two stiffnesses at or above it",
            ));
        }
        for path in &p.paths {
            if path != "auto" && path != "full" {
                return Err(invalid(
                    case,
                    &format!("{f}.paths"),
                    path,
                    "\"auto\" or \"full\"",
                ));
            }
        }
        positive(case, &format!("{f}.slope_tolerance"), p.slope_tolerance)?;
    }
    for (i, s) in c.speed.iter().enumerate() {
        let f = format!("speed[{i}]");
        check_scene(case, &format!("{f}.scene"), &s.scene)?;
        if s.speeds.len() < 2 {
            return Err(invalid(
                case,
                &format!("{f}.speeds"),
                format!("{} values", s.speeds.len()),
                "at least 2 speeds",
            ));
        }
        for (j, v) in s.speeds.iter().enumerate() {
            positive(case, &format!("{f}.speeds[{j}]"), *v)?;
        }
        let norm: f64 = s.direction.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(s.direction.len() == 1 || s.direction.len() == 2) || (norm - 1.0).abs() > 1e-12 {
            return Err(invalid(
                case,
                &format!("{f}.direction"),
                format!("{:?}", s.direction),
                "a unit vector of 1 (bar) or 2 components",
            ));
        }
    }
    for (i, l) in c.large_step.iter().enumerate() {
        let f = format!("large_step[{i}]");
        check_scene(case, &format!("{f}.scene"), &l.scene)?;
        if l.steps.len() < 2 || l.steps.contains(&0) {
            return Err(invalid(
                case,
                &format!("{f}.steps"),
                format!("{:?}", l.steps),
                "at least 2 step counts ≥ 1",
            ));
        }
        if l.variant.is_empty() {
            return Err(invalid(
                case,
                &format!("{f}.variant"),
                "(none)",
                "at least one [[large_step.variant]]",
            ));
        }
        for (j, v) in l.variant.iter().enumerate() {
            scene_from_table(&l.scene, &v.set, &format!("{f}.variant[{j}]")).map_err(|e| {
                CaseError::Read {
                    path: case.path.display().to_string(),
                    message: e,
                }
            })?;
        }
    }
    Ok(())
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = parse(case).map_err(|e| e.to_string())?;
    for (i, spec) in c.blow_up.iter().enumerate() {
        run_blow_up(i, spec, ctx, report)?;
    }
    for (i, spec) in c.penalty.iter().enumerate() {
        run_penalty(i, spec, ctx, report)?;
    }
    for (i, spec) in c.speed.iter().enumerate() {
        run_speed(i, spec, ctx, report)?;
    }
    for (i, spec) in c.large_step.iter().enumerate() {
        run_large_step(i, spec, ctx, report)?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Shared pieces.

/// observed ≥ limit.
fn at_least(name: &str, observed: f64, limit: f64) -> Check {
    Check {
        name: name.to_string(),
        observed,
        limit: format!(">= {limit:.3e}"),
        passed: observed >= limit,
    }
}

fn set1(key: &str, value: impl Into<toml::Value>) -> toml::Table {
    let mut t = toml::Table::new();
    t.insert(key.to_string(), value.into());
    t
}

/// One run of a study: the scene, its recorded run (or why it could not run), a label.
struct Run {
    label: String,
    scene: DynamicScene,
    run: Result<RecordedRun, String>,
}

impl Run {
    fn k(&self) -> f64 {
        self.scene.problem.final_time / self.scene.problem.steps as f64
    }

    /// `solution` or the error message.
    fn outcome(&self) -> String {
        match &self.run {
            Ok(r) => match &r.result {
                Ok(_) => "solution".into(),
                Err(e) => format!(
                    "typed error after {} steps: {e}",
                    r.audit.records.len().saturating_sub(1)
                ),
            },
            Err(e) => format!("no run: {e}"),
        }
    }

    fn completed(&self) -> bool {
        matches!(&self.run, Ok(r) if r.result.is_ok())
    }

    /// The checks every run meets whatever it is: no panic, the recorded audit finite, and a
    /// failure (if any) a typed error naming its step.
    fn sanity_checks(&self) -> Vec<Check> {
        let mut checks = Vec::new();
        match &self.run {
            Err(e) => checks.push(Check::holds(
                &format!("runs without a panic ({e})"),
                false,
                "a solution or a typed error",
            )),
            Ok(r) => {
                checks.push(Check::holds(
                    "no NaN or ∞ in any recorded audit value",
                    audit_is_finite(&r.audit)
                        && r.displacement
                            .iter()
                            .chain(&r.velocity)
                            .all(|v| v.is_finite()),
                    "all finite",
                ));
                if let Err(e) = &r.result {
                    let msg = e.to_string();
                    checks.push(Check::holds(
                        &format!("the failure is a typed error naming its step or operator: {msg}"),
                        msg.contains("step"),
                        "a typed error with its data",
                    ));
                }
            }
        }
        checks
    }

    /// The audit checks of a completed run (identities at round-off where the combination
    /// conserves, dissipative signs always).
    fn audit_checks(&self) -> Vec<Check> {
        match &self.run {
            Ok(r) => audit_checks(&self.label, &r.summary(), conserving(&self.scene.problem)),
            Err(_) => Vec::new(),
        }
    }

    fn records(&self) -> &[contactlab::model::dynamic::audit::AuditRecord] {
        match &self.run {
            Ok(r) => &r.audit.records,
            Err(_) => &[],
        }
    }

    /// max_n |drift_n| / (E + Φ)_0 of the balance (1.49).
    fn max_relative_drift(&self) -> f64 {
        let Ok(r) = &self.run else {
            return f64::NAN;
        };
        let e0 = r
            .audit
            .records
            .first()
            .map_or(f64::NAN, |f| f.energy() + f.penalty);
        balance_drift(&r.audit)
            .iter()
            .map(|(_, d)| d.abs())
            .fold(0.0, f64::max)
            / e0
    }

    fn newton(&self) -> (usize, usize) {
        let recs = self.records();
        (
            recs.iter().map(|r| r.newton_iterations).sum(),
            recs.iter().map(|r| r.newton_iterations).max().unwrap_or(0),
        )
    }

    fn max_penetration(&self) -> f64 {
        self.records()
            .iter()
            .map(|r| r.max_penetration)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    fn max_contact_force(&self) -> f64 {
        self.records()
            .iter()
            .map(|r| r.contact_force)
            .fold(0.0, f64::max)
    }

    /// (t_first, t_last, duration = t_last − t_first + k) of the steps with a contact force.
    fn contact_interval(&self) -> Option<(f64, f64, f64)> {
        let recs = self.records();
        let first = recs.iter().find(|r| r.contact_force > 0.0)?;
        let last = recs.iter().rev().find(|r| r.contact_force > 0.0)?;
        Some((first.time, last.time, last.time - first.time + self.k()))
    }

    /// Σ_n k F_n: the normal impulse of the foundation.
    fn impulse(&self) -> f64 {
        self.records()
            .iter()
            .skip(1)
            .map(|r| r.contact_force * self.k())
            .sum()
    }

    fn backtracks(&self) -> usize {
        match &self.run {
            Ok(r) => r.stats().backtracks,
            Err(_) => 0,
        }
    }

    fn summary_value(
        &self,
        f: impl Fn(&contactlab::model::dynamic::audit::AuditSummary) -> f64,
    ) -> f64 {
        match &self.run {
            Ok(r) => f(&r.summary()),
            Err(_) => f64::NAN,
        }
    }
}

/// Builds the scene with `set` and runs it with `extra` observing every step.
fn run_one(
    label: &str,
    table: &toml::Table,
    set: &toml::Table,
    extra: &mut dyn FnMut(&StepView<'_>),
) -> Result<Run, String> {
    let scene = scene_from_table(table, set, label)?;
    let run = match scene.solver() {
        Err(e) => Err(format!("{label}: {e}")),
        Ok(solver) => std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            run_recorded_with(&solver, &[], extra)
        }))
        .map_err(|_| format!("{label}: the solver panicked")),
    };
    Ok(Run {
        label: label.to_string(),
        scene,
        run,
    })
}

fn slug(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect::<String>()
        .split('_')
        .filter(|p| !p.is_empty())
        .collect::<Vec<_>>()
        .join("_")
}

fn push_run_gate(
    report: &mut CaseReport,
    study: &str,
    run: &Run,
    mut checks: Vec<Check>,
    expect: &str,
    note: &str,
) {
    let mut all = run.sanity_checks();
    all.append(&mut checks);
    report.gates.push(GateVerdict::from_checks(
        format!("{study}: {}", run.label),
        "extreme",
        all.clone(),
        note,
    ));
    report.extremes.push(ExtremeReport {
        name: format!("{study}: {}", run.label),
        expect: expect.to_string(),
        outcome: run.outcome(),
        checks: all,
        note: note.to_string(),
    });
}

fn header(cols: &[&str]) -> Vec<String> {
    cols.iter().map(|s| s.to_string()).collect()
}

/// A dashed power law y = y0 (x/x0)^slope from x0 to x1.
fn slope_line(name: &str, (x0, y0): (f64, f64), x1: f64, slope: f64) -> Series {
    Series::line(
        name.to_string(),
        [(x0, y0), (x1, y0 * (x1 / x0).powf(slope))],
    )
    .color(7)
    .dashed()
}

/// Least-squares slope of ln y against ln x.
fn log_slope(points: &[(f64, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    sxy / sxx
}

// ---------------------------------------------------------------------------------------------
// (a) blow-up.

fn run_blow_up(
    index: usize,
    spec: &BlowUpSpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let study = format!("blow-up: {}", spec.name);
    let mut runs = Vec::new();
    for scheme in [spec.unstable, spec.stable] {
        runs.push(run_one(
            scheme.name(),
            &spec.scene,
            &set1("time.scheme", scheme.name()),
            &mut |_| {},
        )?);
    }
    let mut rows = Vec::new();
    for (i, run) in runs.iter().enumerate() {
        let drift = run.max_relative_drift();
        let (its, max_it) = run.newton();
        let mut checks = Vec::new();
        let expect;
        if i == 0 {
            expect = format!(
                "energy error ≥ {:.1e} (a solution or a typed error)",
                spec.min_energy_error
            );
            checks.push(at_least(
                &format!(
                    "{}: largest relative energy error max_n |drift_n| / (E + Φ)_0",
                    run.label
                ),
                drift,
                spec.min_energy_error,
            ));
        } else {
            expect = "a solution conserving energy to round-off".into();
            checks.push(Check::holds(
                &format!("{}: the run completes", run.label),
                run.completed(),
                "a solution",
            ));
            checks.extend(run.audit_checks());
            let steps = run.scene.problem.steps as f64;
            checks.push(Check::at_most(
                &format!("{}: largest relative balance drift over the run", run.label),
                drift,
                steps * ROUND_OFF_LEVEL,
            ));
        }
        push_run_gate(report, &study, run, checks, &expect, &spec.note);
        let recs = run.records();
        let e0 = recs.first().map_or(f64::NAN, |r| r.energy() + r.penalty);
        let emax = recs
            .iter()
            .map(|r| r.energy() + r.penalty)
            .fold(f64::NEG_INFINITY, f64::max);
        rows.push(vec![
            run.label.clone(),
            run.outcome(),
            format!("{}", recs.len().saturating_sub(1)),
            format!("{:.3e}", run.k()),
            format!(
                "{:.2}",
                run.k() * run.scene.problem.body.wave_speed() / run.scene.problem.body.h_min()
            ),
            format!("{e0:.6e}"),
            format!("{:.6e}", emax),
            format!("{drift:.3e}"),
            format!("{:.2e}", run.summary_value(|s| s.max_residual_1_48)),
            format!("{its} / {max_it}"),
            format!("{}", run.backtracks()),
        ]);
    }
    report.tables.push(Table {
        title: format!("{study} ({})", runs[0].scene.problem.body.describe()),
        header: header(&[
            "scheme",
            "outcome",
            "steps done",
            "k",
            "k c / h_min",
            "(E + Φ)_0",
            "max (E + Φ)_n",
            "max |drift| / E_0",
            "max |r(1.48)| / E_ref",
            "Newton its (total / max)",
            "backtracks",
        ]),
        rows,
    });
    let audits: Vec<AuditRun<'_>> = runs
        .iter()
        .filter_map(|r| {
            r.run.as_ref().ok().map(|rec| AuditRun {
                label: r.label.clone(),
                audit: &rec.audit,
            })
        })
        .collect();
    plot_audits(
        ctx,
        report,
        &format!("blow_up_{index}_{}", slug(&spec.name)),
        &spec.name,
        &audits,
        None,
    )
}

// ---------------------------------------------------------------------------------------------
// (b) penalty stiffness.

/// The state of the step with the largest contact force: u_{n−1}, u_n and each contact node's
/// p_{n−1}, p_n.
#[derive(Debug, Clone, Default)]
struct PeakState {
    force: f64,
    u_prev: Vec<f64>,
    u_now: Vec<f64>,
    p_prev: Vec<f64>,
    p_now: Vec<f64>,
}

/// Tracks [`PeakState`] along a run.
#[derive(Debug, Default)]
struct PeakTracker {
    u_last: Vec<f64>,
    p_last: Vec<f64>,
    peak: PeakState,
}

impl PeakTracker {
    fn observe(&mut self, v: &StepView<'_>) {
        let p: Vec<f64> = v.forces.iter().map(|f: &NodeForces| f.p).collect();
        if v.step > 0 && v.record.contact_force > self.peak.force {
            self.peak = PeakState {
                force: v.record.contact_force,
                u_prev: self.u_last.clone(),
                u_now: v.displacement.to_vec(),
                p_prev: self.p_last.clone(),
                p_now: p.clone(),
            };
        }
        self.u_last.clear();
        self.u_last.extend_from_slice(v.displacement);
        self.p_last = p;
    }
}

/// Condition numbers of the step Jacobian, λ_max/λ_min (∞ when not positive definite).
#[derive(Debug, Clone, Copy)]
struct Conditions {
    /// J at the peak state, and its Schur complement on the contact dofs.
    peak: f64,
    peak_schur: f64,
    /// J with every contact node in contact over the whole step (the law's full slope on every
    /// Γ3 normal dof): the worst case of the run.
    worst: f64,
    worst_schur: f64,
}

/// The condition numbers of the step Jacobian J = α M + θ K(u) + Σ_i w_i N_i′ e_{ν,i} e_{ν,i}ᵀ
/// and of its Schur complement S = J_ΓΓ − J_ΓI J_II⁻¹ J_IΓ on the contact dofs Γ (what the
/// condensed path factors), (i) at the peak state, N_i′ the slope of the node's compliance law
/// at (p_{n−1}, p_n) there, and (ii) in the worst case, every node in contact at both ends of
/// the step (N′ = r for the penalty force, r/2 for the energy-consistent one). For
/// r w_i ≫ λ_max(α M + θ K) the largest eigenvalue is ≈ r max_i w_i and κ grows like r.
fn conditions(scene: &DynamicScene, peak: &PeakState) -> Option<Conditions> {
    let (peak_full, peak_schur) = condition_numbers(scene, peak, false)?;
    let (worst, worst_schur) = condition_numbers(scene, peak, true)?;
    Some(Conditions {
        peak: peak_full,
        peak_schur,
        worst,
        worst_schur,
    })
}

fn condition_numbers(scene: &DynamicScene, peak: &PeakState, worst: bool) -> Option<(f64, f64)> {
    let pb = &scene.problem;
    let body = &pb.body;
    let contact = pb.contact.as_ref()?;
    let n = body.dofs();
    let k = pb.final_time / pb.steps as f64;
    let alpha = pb.scheme.alpha(k);
    let pattern = body.pattern();
    let mut values: Vec<f64> = body.mass().iter().map(|m| alpha * m).collect();
    let u_prev = if peak.u_prev.len() == n {
        peak.u_prev.clone()
    } else {
        vec![0.0; n]
    };
    let u_now = if peak.u_now.len() == n {
        peak.u_now.clone()
    } else {
        vec![0.0; n]
    };
    match (body.linear_stiffness(), pb.scheme) {
        (Some(kv), s) => {
            let theta = if s == DynamicScheme::Newmark {
                1.0
            } else {
                0.5
            };
            for (v, kk) in values.iter_mut().zip(kv) {
                *v += theta * kk;
            }
        }
        (None, DynamicScheme::Newmark) => body.add_tangent(&u_now, 1.0, &mut values),
        (None, DynamicScheme::Midpoint) => {
            let mid: Vec<f64> = u_prev
                .iter()
                .zip(&u_now)
                .map(|(a, b)| 0.5 * (a + b))
                .collect();
            body.add_tangent(&mid, 0.5, &mut values);
        }
        (None, DynamicScheme::Gonzalez) => {
            body.add_discrete_gradient_tangent(&u_prev, &u_now, 1.0, &mut values)
        }
    }
    let mut j = DMatrix::<f64>::zeros(n, n);
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    for col in 0..n {
        for s in cp[col]..cp[col + 1] {
            j[(ri[s], col)] = values[s];
            j[(col, ri[s])] = values[s];
        }
    }
    for (i, nd) in contact.nodes.iter().enumerate() {
        let (q, p) = if worst {
            (1e-3, 2e-3)
        } else {
            (
                peak.p_prev.get(i).copied().unwrap_or(0.0),
                peak.p_now.get(i).copied().unwrap_or(0.0),
            )
        };
        let slope = match contact.treatment {
            NormalTreatment::Penalty { stiffness } => penalty(stiffness, p).slope,
            NormalTreatment::EnergyConsistent { stiffness }
            | NormalTreatment::HauretLeTallecTilted { stiffness }
            | NormalTreatment::LimitedPenetration { stiffness, .. } => {
                energy_consistent(stiffness, q, p).slope
            }
            NormalTreatment::Signorini => 0.0,
        };
        j[(nd.normal_dof, nd.normal_dof)] += nd.weight * slope;
    }
    let kappa = |m: DMatrix<f64>| -> f64 {
        let ev = SymmetricEigen::new(m).eigenvalues;
        let (lo, hi) = ev
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        if lo > 0.0 {
            hi / lo
        } else {
            f64::INFINITY
        }
    };
    let gamma = contact.dofs();
    let mut is_gamma = vec![false; n];
    for &g in &gamma {
        is_gamma[g] = true;
    }
    let interior: Vec<usize> = (0..n).filter(|&i| !is_gamma[i]).collect();
    let jii = j.select_rows(&interior).select_columns(&interior);
    let jig = j.select_rows(&interior).select_columns(&gamma);
    let jgg = j.select_rows(&gamma).select_columns(&gamma);
    let schur = match jii.cholesky() {
        Some(ch) => {
            let x = ch.solve(&jig);
            let s = &jgg - jig.transpose() * x;
            kappa(0.5 * (&s + s.transpose()))
        }
        None => f64::INFINITY,
    };
    Some((kappa(j), schur))
}

fn run_penalty(
    index: usize,
    spec: &PenaltySpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let study = format!("penalty: {}", spec.name);
    struct Point {
        r: f64,
        path: String,
        run: Run,
        kappa: Option<Conditions>,
    }
    let mut points: Vec<Point> = Vec::new();
    for path in &spec.paths {
        for &r in &spec.stiffness {
            let mut set = set1("contact.stiffness", r);
            set.insert("solver.path".into(), path.clone().into());
            let mut tracker = PeakTracker::default();
            let run = run_one(
                &format!("r = {r:.0e}, {path} path"),
                &spec.scene,
                &set,
                &mut |v| tracker.observe(v),
            )?;
            let kappa =
                if path == "auto" && run.scene.problem.body.dofs() <= spec.condition_max_dofs {
                    conditions(&run.scene, &tracker.peak)
                } else {
                    None
                };
            points.push(Point {
                r,
                path: path.clone(),
                run,
                kappa,
            });
        }
    }
    let mut rows = Vec::new();
    for p in &points {
        let (its, max_it) = p.run.newton();
        let mut checks = Vec::new();
        if p.run.completed() {
            checks.extend(p.run.audit_checks());
            checks.push(Check::at_most(
                &format!("{}: Newton iterations of the worst step", p.run.label),
                max_it as f64,
                spec.max_newton_iterations as f64,
            ));
        }
        push_run_gate(
            report,
            &study,
            &p.run,
            checks,
            "a correct run (identities at round-off) or a typed error",
            &spec.note,
        );
        let steps = p.run.records().len().saturating_sub(1).max(1);
        let difference = points
            .iter()
            .find(|q| q.r == p.r && q.path == spec.paths[0])
            .map(|q| {
                let (a, b) = (q.run.max_penetration(), p.run.max_penetration());
                (a - b).abs() / a.abs().max(b.abs())
            })
            .unwrap_or(f64::NAN);
        rows.push(vec![
            format!("{:.0e}", p.r),
            p.path.clone(),
            format!("{difference:.1e}"),
            p.run.outcome(),
            p.kappa.map_or("—".into(), |k| format!("{:.3e}", k.peak)),
            p.kappa
                .map_or("—".into(), |k| format!("{:.3e}", k.peak_schur)),
            p.kappa.map_or("—".into(), |k| format!("{:.3e}", k.worst)),
            p.kappa
                .map_or("—".into(), |k| format!("{:.3e}", k.worst_schur)),
            format!("{:.4e}", p.run.max_penetration()),
            format!("{:.4e}", p.run.max_contact_force()),
            format!("{:.2} / {max_it}", its as f64 / steps as f64),
            format!("{}", p.run.backtracks()),
            format!("{:.2e}", p.run.summary_value(|s| s.max_residual_1_48)),
            format!("{:.2e}", p.run.summary_value(|s| s.max_residual_1_49)),
            format!("{:.2e}", p.run.summary_value(|s| s.max_residual_3_7)),
        ]);
    }
    // study-level gates on the model's own path
    let auto: Vec<&Point> = points.iter().filter(|p| p.path == spec.paths[0]).collect();
    let tail: Vec<(f64, f64)> = auto
        .iter()
        .filter(|p| p.r >= spec.slope_from && p.run.completed())
        .map(|p| (p.r, p.run.max_penetration()))
        .collect();
    let slope = log_slope(&tail);
    let mut checks = vec![Check::within(
        &format!(
            "slope of ln(max penetration) against ln r for r ≥ {:.0e} ({} path)",
            spec.slope_from, spec.paths[0]
        ),
        slope,
        spec.expected_slope,
        spec.slope_tolerance,
    )];
    let decreasing = auto
        .windows(2)
        .all(|w| w[1].run.max_penetration() < w[0].run.max_penetration());
    checks.push(Check::holds(
        "max penetration decreases strictly with r",
        decreasing,
        "monotone",
    ));
    if let Some(expected) = spec.expected_condition_slope {
        let from = spec.condition_slope_from.unwrap_or(spec.slope_from);
        let kp: Vec<(f64, f64)> = auto
            .iter()
            .filter(|p| p.r >= from)
            .filter_map(|p| p.kappa.map(|k| (p.r, k.worst)))
            .collect();
        checks.push(Check::holds(
            "the step Jacobian and its Schur complement are positive definite, at the peak and in the worst case (finite κ)",
            auto.iter().all(|p| {
                p.kappa.is_none_or(|k| {
                    [k.peak, k.peak_schur, k.worst, k.worst_schur]
                        .iter()
                        .all(|v| v.is_finite())
                })
            }),
            "λ_min > 0",
        ));
        checks.push(Check::within(
            &format!("slope of ln κ(J) (worst case) against ln r for r ≥ {from:.0e}"),
            log_slope(&kp),
            expected,
            spec.slope_tolerance,
        ));
    }
    if let (Some(tol), true) = (spec.path_agreement, spec.paths.len() > 1) {
        let mut worst: f64 = 0.0;
        let up_to = spec.path_agreement_up_to.unwrap_or(f64::INFINITY);
        for p in auto.iter().filter(|p| p.r <= up_to && p.run.completed()) {
            for q in points
                .iter()
                .filter(|q| q.path != p.path && q.r == p.r && q.run.completed())
            {
                let (a, b) = (p.run.max_penetration(), q.run.max_penetration());
                worst = worst.max((a - b).abs() / a.abs().max(b.abs()));
            }
        }
        checks.push(Check::at_most(
            &format!(
                "largest relative difference of the max penetration between the paths (completed runs, r ≤ {up_to:.0e})"
            ),
            worst,
            tol,
        ));
    }
    report.gates.push(GateVerdict::from_checks(
        format!("{study}: trends in r"),
        "extreme",
        checks,
        &spec.note,
    ));
    report.tables.push(Table {
        title: format!("{study} ({})", points[0].run.scene.problem.body.describe()),
        header: header(&[
            "r",
            "path",
            "Δp_max vs first path",
            "outcome",
            "κ(J) at peak",
            "κ(S_Γ) at peak",
            "κ(J) worst",
            "κ(S_Γ) worst",
            "max penetration",
            "max contact force",
            "Newton its per step (mean / max)",
            "backtracks",
            "max |r(1.48)|/E_ref",
            "max |r(1.49)|/E_ref",
            "max |r(3.7)|/E_ref",
        ]),
        rows,
    });
    // plots
    let mut pen = Figure::new(format!("{}: largest penetration against r", spec.name))
        .x_label("penalty stiffness r")
        .y_label("max_n max_i p_i")
        .log_log();
    let mut its = Figure::new("Newton iterations per step")
        .x_label("penalty stiffness r")
        .y_label("iterations")
        .semilog_x();
    let mut cond = Figure::new("condition at the peak of the impact")
        .x_label("penalty stiffness r")
        .y_label("κ = λ_max / λ_min")
        .log_log();
    for (c, path) in spec.paths.iter().enumerate() {
        let pts: Vec<&Point> = points.iter().filter(|p| &p.path == path).collect();
        pen = pen.series(
            Series::line_markers(
                format!("{path} path"),
                pts.iter().map(|p| (p.r, p.run.max_penetration())),
            )
            .color(c),
        );
        its = its
            .series(
                Series::line_markers(
                    format!("{path}: mean"),
                    pts.iter().map(|p| {
                        let n = p.run.records().len().saturating_sub(1).max(1);
                        (p.r, p.run.newton().0 as f64 / n as f64)
                    }),
                )
                .color(c),
            )
            .series(
                Series::line_markers(
                    format!("{path}: max"),
                    pts.iter().map(|p| (p.r, p.run.newton().1 as f64)),
                )
                .color(c)
                .dashed(),
            );
    }
    // reference power laws over the asymptotic ranges, anchored a factor 2 below the data
    let r_max = spec.stiffness.iter().copied().fold(0.0, f64::max);
    if let Some(p0) = auto
        .iter()
        .find(|p| p.r >= spec.slope_from && p.run.completed())
    {
        let y0 = 0.5 * p0.run.max_penetration();
        pen = pen
            .series(slope_line(
                &format!("slope {}", spec.expected_slope),
                (p0.r, y0),
                r_max,
                spec.expected_slope,
            ))
            .series(slope_line("slope −1", (p0.r, y0), r_max, -1.0).color(6));
    }
    cond = cond
        .series(
            Series::line_markers(
                "κ(J) worst case",
                points
                    .iter()
                    .filter_map(|p| p.kappa.map(|k| (p.r, k.worst))),
            )
            .color(0),
        )
        .series(
            Series::line_markers(
                "κ(S_Γ) worst case",
                points
                    .iter()
                    .filter_map(|p| p.kappa.map(|k| (p.r, k.worst_schur))),
            )
            .color(1),
        )
        .series(
            Series::line_markers(
                "κ(J) at the peak",
                points.iter().filter_map(|p| p.kappa.map(|k| (p.r, k.peak))),
            )
            .color(0)
            .dashed(),
        )
        .series(
            Series::line_markers(
                "κ(S_Γ) at the peak",
                points
                    .iter()
                    .filter_map(|p| p.kappa.map(|k| (p.r, k.peak_schur))),
            )
            .color(1)
            .dashed(),
        );
    let from = spec.condition_slope_from.unwrap_or(spec.slope_from);
    if let Some(k0) = auto
        .iter()
        .find(|p| p.r >= from)
        .and_then(|p| p.kappa.map(|k| (p.r, k.worst)))
    {
        cond = cond.series(slope_line("slope 1", (k0.0, 0.5 * k0.1), r_max, 1.0));
    }
    ctx.panels(
        report,
        &format!("penalty_{index}_{}", slug(&spec.name)),
        &format!(
            "{}: penetration, Newton iterations and condition against r",
            spec.name
        ),
        &[pen, its, cond],
        3,
    )
}

// ---------------------------------------------------------------------------------------------
// (c) impact speed.

fn velocity_value(direction: &[f64], v: f64) -> toml::Value {
    if direction.len() == 1 {
        toml::Value::Float(v * direction[0])
    } else {
        toml::Value::Array(
            direction
                .iter()
                .map(|d| toml::Value::Float(v * d))
                .collect(),
        )
    }
}

/// The rigid translation along `direction` as a free-dof vector.
fn translation(scene: &DynamicScene, direction: &[f64]) -> Vec<f64> {
    match &scene.body {
        SceneBody::Bar(b) => b.from_nodal(&vec![direction[0]; b.data().mesh.nodes().len()]),
        SceneBody::Plane(p) => {
            let nodes = p.data().mesh.nodes().len();
            let d = [direction[0], *direction.get(1).unwrap_or(&0.0)];
            p.from_nodal(&(0..2 * nodes).map(|i| d[i % 2]).collect::<Vec<_>>())
        }
    }
}

/// The rigid-body velocity of `v` along the translation `e`: eᵀ M v / eᵀ M e.
fn rigid_velocity(scene: &DynamicScene, e: &[f64], v: &[f64]) -> f64 {
    let body = &scene.problem.body;
    let mut me = vec![0.0; e.len()];
    body.pattern().symmetric_mul(body.mass(), e, &mut me);
    let num: f64 = me.iter().zip(v).map(|(a, b)| a * b).sum();
    let den: f64 = me.iter().zip(e).map(|(a, b)| a * b).sum();
    num / den
}

fn run_speed(
    index: usize,
    spec: &SpeedSpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let study = format!("speed: {}", spec.name);
    let mut runs = Vec::new();
    for &v in &spec.speeds {
        runs.push(run_one(
            &format!("v = {v} m/s"),
            &spec.scene,
            &set1("initial.velocity", velocity_value(&spec.direction, v)),
            &mut |_| {},
        )?);
    }
    struct Measured {
        v: f64,
        pen: f64,
        force: f64,
        contact: f64,
        rebound: f64,
        mean_force: f64,
    }
    let mut measured = Vec::new();
    let mut rows = Vec::new();
    for (run, &v) in runs.iter().zip(&spec.speeds) {
        let mut checks = vec![Check::holds(
            &format!("{}: the run completes", run.label),
            run.completed(),
            "a solution",
        )];
        checks.extend(run.audit_checks());
        push_run_gate(
            report,
            &study,
            run,
            checks,
            "a solution with the identities at round-off",
            &spec.note,
        );
        let e = translation(&run.scene, &spec.direction);
        let rebound = match &run.run {
            Ok(r) => -rigid_velocity(&run.scene, &e, &r.velocity) / v,
            Err(_) => f64::NAN,
        };
        let contact = run.contact_interval().map_or(f64::NAN, |c| c.2);
        let m = Measured {
            v,
            pen: run.max_penetration(),
            force: run.max_contact_force(),
            contact,
            rebound,
            mean_force: run.impulse() / contact,
        };
        let (its, max_it) = run.newton();
        rows.push(vec![
            format!("{v}"),
            run.outcome(),
            format!("{:.6e}", m.pen),
            format!("{:.6e}", m.pen / v),
            format!("{:.6e}", m.force / v),
            format!("{:.6e}", m.mean_force / v),
            format!("{:.6e}", m.contact),
            format!("{:.6}", m.rebound),
            format!("{:.2e}", run.summary_value(|s| s.max_residual_1_48)),
            format!("{:.2e}", run.summary_value(|s| s.max_residual_1_49)),
            format!("{its} / {max_it}"),
        ]);
        measured.push(m);
    }
    let k = runs[0].k();
    let mut checks = Vec::new();
    if let Some(tol) = spec.homogeneity_tolerance {
        let base = &measured[0];
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs().max(f64::MIN_POSITIVE);
        let worst = |f: &dyn Fn(&Measured) -> f64| {
            measured
                .iter()
                .map(|m| rel(f(m), f(base)))
                .fold(0.0, f64::max)
        };
        checks.push(Check::at_most(
            "homogeneity: p_max / v across speeds (relative spread)",
            worst(&|m| m.pen / m.v),
            tol,
        ));
        checks.push(Check::at_most(
            "homogeneity: F_max / v across speeds",
            worst(&|m| m.force / m.v),
            tol,
        ));
        checks.push(Check::at_most(
            "homogeneity: contact time across speeds",
            worst(&|m| m.contact),
            tol,
        ));
        checks.push(Check::at_most(
            "homogeneity: rebound coefficient across speeds",
            worst(&|m| m.rebound),
            tol,
        ));
    }
    if let Some(tol) = spec.wave_theory_tolerance {
        match &runs[0].scene.body {
            SceneBody::Bar(b) => {
                let d = b.data();
                let c = runs[0].scene.problem.body.wave_speed();
                let t_exact = 2.0 * d.mesh.length() / c;
                for m in &measured {
                    checks.push(Check::within(
                        &format!("v = {}: contact time / (2L/c)", m.v),
                        m.contact / t_exact,
                        1.0,
                        tol,
                    ));
                    checks.push(Check::within(
                        &format!("v = {}: rebound velocity / v", m.v),
                        m.rebound,
                        1.0,
                        tol,
                    ));
                    checks.push(Check::within(
                        &format!("v = {}: mean contact force / (ρ c A v)", m.v),
                        m.mean_force / (d.density * c * d.area * m.v),
                        1.0,
                        tol,
                    ));
                }
            }
            SceneBody::Plane(_) => {
                return Err(format!("{study}: wave_theory_tolerance is for bars"));
            }
        }
    }
    if let Some([lo, hi]) = spec.penetration_exponent {
        for w in measured.windows(2) {
            let e = (w[1].pen / w[0].pen).ln() / (w[1].v / w[0].v).ln();
            checks.push(Check {
                name: format!(
                    "exponent d ln p_max / d ln v between v = {} and {}",
                    w[0].v, w[1].v
                ),
                observed: e,
                limit: format!("in [{lo}, {hi}]"),
                passed: (lo..=hi).contains(&e),
            });
        }
    }
    if spec.contact_time_nonincreasing {
        for w in measured.windows(2) {
            checks.push(Check::at_most(
                &format!(
                    "contact time at v = {} minus at v = {} (≤ one step)",
                    w[1].v, w[0].v
                ),
                w[1].contact - w[0].contact,
                k * (1.0 + 1e-9),
            ));
        }
    }
    if !checks.is_empty() {
        report.gates.push(GateVerdict::from_checks(
            format!("{study}: trends in the speed"),
            "extreme",
            checks,
            &spec.note,
        ));
    }
    report.tables.push(Table {
        title: format!("{study} ({})", runs[0].scene.problem.body.describe()),
        header: header(&[
            "v",
            "outcome",
            "max penetration",
            "p_max / v",
            "F_max / v",
            "mean force / v",
            "contact time",
            "rebound v_N / v",
            "max |r(1.48)|/E_ref",
            "max |r(1.49)|/E_ref",
            "Newton its (total / max)",
        ]),
        rows,
    });
    let pen = Figure::new(format!("{}: largest penetration", spec.name))
        .x_label("impact speed v")
        .y_label("max penetration")
        .log_log()
        .series(Series::line_markers(
            "p_max",
            measured.iter().map(|m| (m.v, m.pen)),
        ));
    let pen = match (measured.first(), measured.last()) {
        (Some(a), Some(b)) => pen
            .series(slope_line("slope 1", (a.v, 0.5 * a.pen), b.v, 1.0))
            .series(slope_line("slope 1/2", (a.v, 0.5 * a.pen), b.v, 0.5).color(6)),
        _ => pen,
    };
    let tc = Figure::new("contact time")
        .x_label("impact speed v")
        .y_label("t_last − t_first + k")
        .semilog_x()
        .series(Series::line_markers(
            "contact time",
            measured.iter().map(|m| (m.v, m.contact)),
        ));
    let mut hist = Figure::new("normal contact force / v against t")
        .x_label("t")
        .y_label("Σ w_i N_i / v");
    for (i, (run, &v)) in runs.iter().zip(&spec.speeds).enumerate() {
        hist = hist.series(
            Series::line(
                format!("v = {v}"),
                run.records().iter().map(|r| (r.time, r.contact_force / v)),
            )
            .color(i),
        );
    }
    ctx.panels(
        report,
        &format!("speed_{index}_{}", slug(&spec.name)),
        &format!(
            "{}: penetration, contact time and contact force against the speed",
            spec.name
        ),
        &[pen, tc, hist],
        3,
    )
}

// ---------------------------------------------------------------------------------------------
// (d) large steps.

fn run_large_step(
    index: usize,
    spec: &LargeStepSpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let study = format!("large step: {}", spec.name);
    let mut grid: Vec<Vec<Run>> = Vec::new();
    for variant in &spec.variant {
        let mut row = Vec::new();
        for &n in &spec.steps {
            let mut set = variant.set.clone();
            set.insert("time.steps".into(), toml::Value::Integer(n as i64));
            let mut run = run_one(
                &format!("{}, N = {n}", variant.label),
                &spec.scene,
                &set,
                &mut |_| {},
            )?;
            run.label = format!("{}, k = {:.2e}", variant.label, run.k());
            row.push(run);
        }
        grid.push(row);
    }
    // the contact duration: the finest run of the first conserving variant
    let reference = grid
        .iter()
        .find(|row| {
            let c = conserving(&row[0].scene.problem);
            c.balance && c.contact
        })
        .unwrap_or(&grid[0]);
    let t_contact = reference[0].contact_interval().map_or(f64::NAN, |c| c.2);
    let wave = {
        let b = &reference[0].scene.problem.body;
        b.h_min() / b.wave_speed()
    };
    let mut rows = Vec::new();
    for row in &grid {
        for run in row {
            let cons = conserving(&run.scene.problem);
            let drift = run.max_relative_drift();
            let mut checks = Vec::new();
            let expect = if cons.balance && cons.contact {
                checks.push(Check::holds(
                    &format!("{}: the run completes", run.label),
                    run.completed(),
                    "a solution",
                ));
                checks.extend(run.audit_checks());
                checks.push(Check::at_most(
                    &format!("{}: bounded energy: max |drift| / (E + Φ)_0", run.label),
                    drift,
                    run.scene.problem.steps as f64 * ROUND_OFF_LEVEL,
                ));
                "conserving: a solution, bounded energy, identities at round-off"
            } else {
                "not conserving: reported (a solution or a typed error, nothing non-finite)"
            };
            push_run_gate(report, &study, run, checks, expect, &spec.note);
            let (its, max_it) = run.newton();
            rows.push(vec![
                run.label.clone(),
                if cons.balance && cons.contact {
                    "yes"
                } else {
                    "no"
                }
                .into(),
                run.outcome(),
                format!("{:.2}", run.k() / wave),
                format!("{:.3}", run.k() / t_contact),
                format!("{drift:.3e}"),
                format!("{:.2e}", run.summary_value(|s| s.max_residual_1_48)),
                format!("{:.2e}", run.summary_value(|s| s.max_residual_1_49)),
                format!("{:.2e}", run.summary_value(|s| s.max_residual_3_7)),
                format!("{:.4e}", run.max_penetration()),
                format!("{its} / {max_it}"),
                format!("{}", run.backtracks()),
            ]);
        }
    }
    let k_max = grid[0].iter().map(|r| r.k()).fold(0.0, f64::max);
    report.gates.push(GateVerdict::from_checks(
        format!("{study}: the steps reach the extremes claimed"),
        "extreme",
        vec![
            at_least(
                "largest k / (h_min / c)",
                k_max / wave,
                spec.min_wave_crossings,
            ),
            at_least(
                "largest k / contact duration (finest conserving run)",
                k_max / t_contact,
                spec.min_contact_fraction,
            ),
        ],
        &spec.note,
    ));
    report.tables.push(Table {
        title: format!(
            "{study} ({}; h_min/c = {wave:.3e}, contact duration {t_contact:.3e})",
            grid[0][0].scene.problem.body.describe()
        ),
        header: header(&[
            "run",
            "conserving",
            "outcome",
            "k c / h_min",
            "k / contact time",
            "max |drift| / E_0",
            "max |r(1.48)|/E_ref",
            "max |r(1.49)|/E_ref",
            "max |r(3.7)|/E_ref",
            "max penetration",
            "Newton its (total / max)",
            "backtracks",
        ]),
        rows,
    });
    let mut drift_fig = Figure::new(format!("{}: energy error against the step", spec.name))
        .x_label("k / (h_min / c)")
        .y_label("max_n |drift_n| / (E + Φ)_0 (floored at 1e-17)")
        .log_log()
        .horizontal_line(ROUND_OFF_LEVEL, "round-off gate (per step)");
    for (c, (row, variant)) in grid.iter().zip(&spec.variant).enumerate() {
        drift_fig = drift_fig.series(
            Series::line_markers(
                variant.label.clone(),
                row.iter()
                    .filter(|r| r.run.is_ok())
                    .map(|r| (r.k() / wave, r.max_relative_drift().max(1e-17))),
            )
            .color(c),
        );
    }
    ctx.plot(
        report,
        &format!("large_step_{index}_{}_drift", slug(&spec.name)),
        &drift_fig,
    )?;
    // the energy histories at the largest step that still has a history (≥ 8 steps)
    let shown = spec
        .steps
        .iter()
        .rposition(|&n| n >= 8)
        .unwrap_or(spec.steps.len() - 1);
    let last: Vec<AuditRun<'_>> = grid
        .iter()
        .zip(&spec.variant)
        .filter_map(|(row, v)| {
            let run = row.get(shown)?;
            run.run.as_ref().ok().map(|r| AuditRun {
                label: format!("{} (k = {:.2e})", v.label, run.k()),
                audit: &r.audit,
            })
        })
        .collect();
    let mut title = String::new();
    let _ = write!(title, "{} at N = {} steps", spec.name, spec.steps[shown]);
    plot_audits(
        ctx,
        report,
        &format!("large_step_{index}_{}", slug(&spec.name)),
        &title,
        &last,
        None,
    )
}
