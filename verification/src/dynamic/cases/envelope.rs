//! `dynamic_envelope`: the one-body dynamic family swept to the edges of its range on inputs not
//! shaped for a case (`docs/dynamic.md`, "Range"). Every point is a scene (a base table and
//! overrides) that must end in what the case declares: a correct answer, or a typed error whose
//! message names the limit. Three kinds of study:
//!
//! - `[[bar]]` — the free elastic bar hitting a rigid wall (`docs/dynamic.md` §5,
//!   [`BarWallImpact`]): for each point, the energy recomputed HERE from the final state with the
//!   P1 formulas of a uniform bar, E = Σ_e [ρAh/6 (a² + ab + b²) + EA/(2h) (u_b − u_a)²] (a, b the
//!   end velocities), must equal ½ ρAL v0² up to C ε (D E_0 + Σ_j s_j), s_j = E_0 + ‖K‖_∞ ‖u_j‖₂
//!   ‖d_j‖₂ with ‖K‖_∞ = 4EA/h, D the dofs and C = `energy_round_off` (the round-off model of
//!   `model::dynamic::audit`, recomputed here from the states the run passes through: the update
//!   δu_n = (2/k) d − δu_{n−1} rounds the velocity at the size of |K||u| |d|, which a translating
//!   bar makes far larger than E). The midpoint rule on a linear bar with the energy-consistent
//!   force conserves E + Φ exactly (BDS Prop. 1.1 with (1.46)), and Φ = 0 after the separation.
//!   The contact must have ended by T (its duration against 2L/c is reported: the release is
//!   smeared over h^{2/3}); along the points (a refinement ladder)
//!   the rebound error |P/(ρAL) − v0| / v0, P = Σ_e ρAh (a + b)/2, must fall at the rate the
//!   dispersion of the unloading front allows (2/3, `docs/dynamic.md` §5) within its tolerance.
//! - `[[ladder]]` — a body with no closed form (a Gmsh mesh with a hole): each point must pass
//!   the audit's identities and signs (BDS (1.48)/(1.49), HLT 3.7 where the combination
//!   conserves; friction and constraint work ≤ 0), and the centre-of-mass velocity at T, from
//!   the final state (Σ M v over a component / Σ M), must self-converge along the points: the
//!   observed order from the last three points at least `min_order`.
//! - `[[limit]]` — points past the range: each must stop with a typed error whose message
//!   contains `expect` (the key or the limit it names) — never a panic, never a quiet answer.
//!
//! Every run also meets the checks of every extreme run: no panic, nothing non-finite recorded,
//! a failure only as a typed error naming its step.

use serde::{Deserialize, Serialize};

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::{invalid, positive, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::dynamic::cases::extremes::common::{push_run_gate, run_one, Run};
use crate::dynamic::scene::scene_from_table;
use crate::exact::signorini_bar::BarWallImpact;

/// The case format of `dynamic_envelope` (unknown keys are errors).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeCase {
    #[serde(default)]
    pub bar: Vec<BarStudy>,
    #[serde(default)]
    pub ladder: Vec<LadderStudy>,
    #[serde(default)]
    pub limit: Vec<LimitStudy>,
}

fn yes() -> bool {
    true
}

/// A point of a study: a label and the overrides of the study's scene.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    pub label: String,
    #[serde(default)]
    pub set: toml::Table,
}

/// `[[bar]]`: points of a bar scene against the exact bar impact.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BarStudy {
    pub name: String,
    /// The bar's data for the exact solution (the scene must agree: the case checks it).
    pub length: f64,
    pub density: f64,
    pub young: f64,
    pub area: f64,
    /// Whether the points form a refinement ladder whose rebound error is rate-gated.
    #[serde(default)]
    pub ladder: bool,
    #[serde(default)]
    pub rebound_rate: f64,
    #[serde(default)]
    pub rate_tolerance: f64,
    /// C in |E_T − E_0| ≤ C ε (D E_0 + Σ_j s_j) (module docs).
    pub energy_round_off: f64,
    /// Whether the recomputed energy is gated at round-off (default true; false would leave the
    /// audit's identity, which adds the Newton work, as the energy gate).
    #[serde(default = "yes")]
    pub energy_gate: bool,
    pub note: String,
    pub scene: toml::Table,
    pub point: Vec<Point>,
}

/// `[[ladder]]`: points of a scene refined towards self-convergence.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LadderStudy {
    pub name: String,
    /// The velocity component (0: x, 1: y) of the centre of mass compared.
    pub component: usize,
    /// With `ratio` (the refinement ratio between consecutive points): the points form a
    /// refinement ladder whose observed order over the last three must be at least this.
    #[serde(default)]
    pub min_order: Option<f64>,
    #[serde(default)]
    pub ratio: Option<f64>,
    pub note: String,
    pub scene: toml::Table,
    pub point: Vec<Point>,
}

/// `[[limit]]`: points past the range, each with the text its typed error must contain.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LimitStudy {
    pub name: String,
    pub note: String,
    pub scene: toml::Table,
    pub point: Vec<LimitPoint>,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LimitPoint {
    pub label: String,
    #[serde(default)]
    pub set: toml::Table,
    pub expect: String,
}

/// The scene table with a relative Gmsh `body.file` made relative to the repository root (the
/// case files name `examples/meshes/…`).
fn rooted(scene: &toml::Table) -> toml::Table {
    let mut t = scene.clone();
    if let Some(toml::Value::Table(body)) = t.get_mut("body") {
        if let Some(toml::Value::String(file)) = body.get_mut("file") {
            let path = std::path::Path::new(file.as_str());
            if path.is_relative() {
                let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
                *file = root.join(path).display().to_string();
            }
        }
    }
    t
}

fn read_error(case: &Case, message: String) -> CaseError {
    CaseError::Read {
        path: case.path().display().to_string(),
        message,
    }
}

/// Checks the case format and that every answer point's scene is valid.
pub fn check(case: &Case) -> Result<(), CaseError> {
    let c: EnvelopeCase = case.body()?;
    if c.bar.is_empty() && c.ladder.is_empty() && c.limit.is_empty() {
        return Err(invalid(
            case.path(),
            "bar / ladder / limit",
            "(none)",
            "at least one study",
        ));
    }
    for (i, b) in c.bar.iter().enumerate() {
        let f = format!("bar[{i}]");
        for (k, v) in [
            ("length", b.length),
            ("density", b.density),
            ("young", b.young),
            ("area", b.area),
            ("energy_round_off", b.energy_round_off),
        ] {
            positive(case.path(), &format!("{f}.{k}"), v)?;
        }
        if b.ladder && (b.point.len() < 2 || b.rebound_rate <= 0.0 || b.rate_tolerance <= 0.0) {
            return Err(invalid(
                case.path(),
                &format!("{f}.ladder"),
                "true",
                "at least 2 points, rebound_rate > 0 and rate_tolerance > 0",
            ));
        }
        for (j, p) in b.point.iter().enumerate() {
            scene_from_table(&b.scene, &p.set, &format!("{f}.point[{j}]"))
                .map_err(|e| read_error(case, e))?;
        }
    }
    for (i, l) in c.ladder.iter().enumerate() {
        let f = format!("ladder[{i}]");
        let ladder = l.min_order.is_some() || l.ratio.is_some();
        let ratio_ok = l.ratio.is_some_and(|r| r > 1.0) && l.min_order.is_some();
        if (ladder && (!ratio_ok || l.point.len() < 3)) || l.point.is_empty() || l.component > 1 {
            return Err(invalid(
                case.path(),
                &f,
                format!("{} points, component {}", l.point.len(), l.component),
                "component 0 or 1, points, and for a ladder ratio > 1, min_order and 3 points",
            ));
        }
        for (j, p) in l.point.iter().enumerate() {
            scene_from_table(&rooted(&l.scene), &p.set, &format!("{f}.point[{j}]"))
                .map_err(|e| read_error(case, e))?;
        }
    }
    for (i, l) in c.limit.iter().enumerate() {
        if l.point.iter().any(|p| p.expect.trim().is_empty()) {
            return Err(invalid(
                case.path(),
                &format!("limit[{i}].point.expect"),
                "\"\"",
                "the text the typed error must contain",
            ));
        }
    }
    Ok(())
}

/// Runs the case.
pub fn run(case: &Case, _ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c: EnvelopeCase = case.body().map_err(|e| e.to_string())?;
    for b in &c.bar {
        run_bar(b, report)?;
    }
    for l in &c.ladder {
        run_ladder(l, report)?;
    }
    for l in &c.limit {
        run_limit(l, report)?;
    }
    Ok(())
}

/// The velocity (from the scheme's velocity at T) and the energy of a uniform free bar, from its
/// nodal state (the bar has no supports: free dof i is node i).
struct BarState {
    rebound: f64,
    energy: f64,
}

fn bar_state(b: &BarStudy, u: &[f64], v: &[f64]) -> BarState {
    let m = u.len().saturating_sub(1).max(1);
    let h = b.length / m as f64;
    let (mut p, mut e) = (0.0, 0.0);
    for i in 0..m {
        let (va, vb) = (v[i], v[i + 1]);
        p += b.density * b.area * h * (va + vb) / 2.0;
        e += b.density * b.area * h / 6.0 * (va * va + va * vb + vb * vb)
            + b.young * b.area / (2.0 * h) * (u[i + 1] - u[i]).powi(2);
    }
    BarState {
        rebound: p / (b.density * b.area * b.length),
        energy: e,
    }
}

fn run_bar(b: &BarStudy, report: &mut CaseReport) -> Result<(), String> {
    let exact = |v0: f64| BarWallImpact {
        length: b.length,
        density: b.density,
        young: b.young,
        area: b.area,
        speed: v0,
        gap: 0.0,
    };
    let mut rows = Vec::new();
    let mut ladder: Vec<(f64, f64)> = Vec::new();
    for p in &b.point {
        let label = format!("{} — {}", b.name, p.label);
        // Σ_j ‖u_j‖₂ ‖d_j‖₂ over the steps, from the states the run passes through
        let mut previous: Option<Vec<f64>> = None;
        let mut sum_ud = 0.0;
        let mut steps_seen = 0usize;
        let run = run_one(&label, &b.scene, &p.set, &mut |view| {
            let u = view.displacement;
            if let Some(prev) = &previous {
                let un: f64 = u.iter().map(|x| x * x).sum::<f64>().sqrt();
                let dn: f64 = u
                    .iter()
                    .zip(prev)
                    .map(|(a, b)| (a - b) * (a - b))
                    .sum::<f64>()
                    .sqrt();
                sum_ud += un * dn;
                steps_seen += 1;
            }
            previous = Some(u.to_vec());
        })?;
        let v0 = -run
            .scene
            .problem
            .initial_velocity
            .first()
            .copied()
            .unwrap_or(0.0);
        let dofs = run.scene.problem.initial_velocity.len();
        let h = b.length / dofs.saturating_sub(1).max(1) as f64;
        let mut checks = run.audit_checks();
        let mut row = vec![p.label.clone(), format!("{}", run.scene.problem.steps)];
        if let Ok(r) = &run.run {
            checks.push(Check::holds(
                &format!("{label}: the run completes"),
                r.result.is_ok(),
                "a solution",
            ));
            let s = bar_state(b, &r.displacement, &r.velocity);
            let ex = exact(v0);
            let e0 = 0.5 * b.density * b.area * b.length * v0 * v0;
            let de = (s.energy - e0).abs() / e0;
            let k_inf = 4.0 * b.young * b.area / h;
            let scale = dofs as f64 * e0 + steps_seen as f64 * e0 + k_inf * sum_ud;
            let bound = b.energy_round_off * f64::EPSILON * scale / e0;
            let rebound = (s.rebound - v0).abs() / v0;
            if b.energy_gate {
                checks.push(Check::at_most(
                    &format!("{label}: |E_T − ½ρALv0²| / E_0 (recomputed from the state)"),
                    de,
                    bound,
                ));
            }
            checks.push(Check::at_most(
                &format!("{label}: rebound velocity P/(ρAL) ≤ v0 (energy bound)"),
                s.rebound / v0 - 1.0,
                bound,
            ));
            let last_force = r.audit.records.last().map_or(0.0, |x| x.contact_force);
            checks.push(Check::at_most(
                &format!("{label}: contact force at T (the bar has left the wall)"),
                last_force,
                0.0,
            ));
            let duration = run.contact_interval().map_or(0.0, |(_, _, d)| d);
            ladder.push((run.scene.problem.steps as f64, rebound));
            row.extend([
                format!("{de:.2e} ({:.2})", de / bound),
                format!("{rebound:.3e}"),
                format!("{:.4}", duration / ex.contact_duration()),
                format!("{}", r.stats().newton_floor_stops),
            ]);
        }
        row.insert(2, run.outcome());
        rows.push(row);
        push_run_gate(report, "envelope", &run, checks, "answer", &b.note);
    }
    if b.ladder {
        let (first, last) = (ladder[0], ladder[ladder.len() - 1]);
        let rate = (first.1 / last.1).ln() / (last.0 / first.0).ln();
        report.gates.push(GateVerdict::from_checks(
            format!("{}: rebound error rate along the ladder", b.name),
            "extreme",
            vec![Check::at_least(
                &format!(
                    "{}: log(e_first/e_last)/log(N_last/N_first) ≥ {} − {}",
                    b.name, b.rebound_rate, b.rate_tolerance
                ),
                rate,
                b.rebound_rate - b.rate_tolerance,
            )],
            &b.note,
        ));
    }
    report.tables.push(Table {
        title: format!("envelope: {}", b.name),
        header: [
            "point",
            "steps",
            "outcome",
            "|E_T − E_0|/E_0 (/ bound)",
            "rebound error",
            "contact / (2L/c)",
            "floor stops",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
    Ok(())
}

/// Σ_i (M v)_i over the dofs of `component` / Σ_i (M 1)_i there: the centre-of-mass velocity
/// of a plane body whose free dofs interleave (x, y) (no supports).
fn centre_velocity(run: &Run, component: usize) -> f64 {
    let Ok(r) = &run.run else {
        return f64::NAN;
    };
    let body = &run.scene.problem.body;
    let n = body.dofs();
    let mut ones = vec![0.0; n];
    for (i, o) in ones.iter_mut().enumerate() {
        *o = if i % 2 == component { 1.0 } else { 0.0 };
    }
    let mut m1 = vec![0.0; n];
    body.pattern().symmetric_mul(body.mass(), &ones, &mut m1);
    let p: f64 = m1.iter().zip(&r.velocity).map(|(a, b)| a * b).sum();
    let m: f64 = m1.iter().zip(&ones).map(|(a, b)| a * b).sum();
    p / m
}

fn run_ladder(l: &LadderStudy, report: &mut CaseReport) -> Result<(), String> {
    let mut values = Vec::new();
    let mut rows = Vec::new();
    for p in &l.point {
        let label = format!("{} — {}", l.name, p.label);
        let run = run_one(&label, &rooted(&l.scene), &p.set, &mut |_| {})?;
        let mut checks = run.audit_checks();
        checks.push(Check::holds(
            &format!("{label}: the run completes"),
            run.completed(),
            "a solution",
        ));
        let v = centre_velocity(&run, l.component);
        values.push(v);
        rows.push(vec![
            p.label.clone(),
            format!("{}", run.scene.problem.steps),
            run.outcome(),
            format!("{v:.10e}"),
            format!("{:.2e}", run.max_relative_drift()),
            format!("{}", run.newton().0),
        ]);
        push_run_gate(report, "envelope", &run, checks, "answer", &l.note);
    }
    if let (Some(ratio), Some(min_order), true) = (l.ratio, l.min_order, values.len() >= 3) {
        let n = values.len();
        let (a, b, c) = (values[n - 3], values[n - 2], values[n - 1]);
        let order = ((a - b).abs() / (b - c).abs()).ln() / ratio.ln();
        report.gates.push(GateVerdict::from_checks(
            format!(
                "{}: self-convergence of the centre-of-mass velocity",
                l.name
            ),
            "extreme",
            vec![Check::at_least(
                &format!(
                    "{}: log(|v₁ − v₂| / |v₂ − v₃|) / log {ratio} over the last three points \
                     ({a:.10e}, {b:.10e}, {c:.10e})",
                    l.name
                ),
                order,
                min_order,
            )],
            &l.note,
        ));
    }
    report.tables.push(Table {
        title: format!("envelope: {}", l.name),
        header: [
            "point",
            "steps",
            "outcome",
            "centre-of-mass velocity at T",
            "max drift (1.49) / (E+Φ)_0",
            "Newton iterations",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
    Ok(())
}

fn run_limit(l: &LimitStudy, report: &mut CaseReport) -> Result<(), String> {
    let mut rows = Vec::new();
    for p in &l.point {
        let label = format!("{} — {}", l.name, p.label);
        // an input error is the typed error of a scene past the range: it is the outcome here
        let (outcome, message) = match scene_from_table(&rooted(&l.scene), &p.set, &label) {
            Err(e) => ("input error".to_string(), e),
            Ok(_) => {
                let run = run_one(&label, &rooted(&l.scene), &p.set, &mut |_| {})?;
                let message = match &run.run {
                    Ok(r) => r
                        .result
                        .as_ref()
                        .err()
                        .map_or(String::new(), |e| e.to_string()),
                    Err(e) => e.clone(),
                };
                let checks = vec![Check::holds(
                    &format!("{label}: a typed error containing \"{}\"", p.expect),
                    message.contains(&p.expect) && !message.contains("panicked"),
                    &format!("an error naming \"{}\"", p.expect),
                )];
                rows.push(vec![p.label.clone(), run.outcome(), p.expect.clone()]);
                push_run_gate(report, "envelope", &run, checks, "typed error", &l.note);
                continue;
            }
        };
        rows.push(vec![p.label.clone(), message.clone(), p.expect.clone()]);
        report.gates.push(GateVerdict::from_checks(
            format!("envelope: {label}"),
            "extreme",
            vec![Check::holds(
                &format!("{label} ({outcome}): {message}"),
                message.contains(&p.expect),
                &format!("an error naming \"{}\"", p.expect),
            )],
            &l.note,
        ));
    }
    report.tables.push(Table {
        title: format!("envelope: {}", l.name),
        header: ["point", "outcome", "must name"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
        rows,
    });
    Ok(())
}
