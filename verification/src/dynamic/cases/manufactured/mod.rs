//! `dynamic_manufactured`: time and space rates of the 2D dynamic solver on the manufactured
//! solution of [`crate::manufactured::dynamic_plane`] (plane strain, clamped top, tractions on
//! the sides, Γ3 in persistent normal-compliance contact with the foundation {x2 ≤ 0}).
//!
//! Time study: one mesh, steps N_1 < … < N_L per (scheme, contact force); the error is the time
//! error alone, ‖u_N − u_N^ref‖_{L²} at T against a reference run on the same mesh with
//! N_ref ≫ N_L steps (the midpoint-type scheme with the energy-consistent force: second order, so
//! its own error is (N_L/N_ref)² of the finest error measured). Expected (persistent contact, so
//! the energy-consistent force of BDS (1.46) is r (p_n + p_{n−1})/2, the trapezoidal value at
//! t_{n−1/2}):
//!
//! | scheme            | force              | order in k | why |
//! |-------------------|--------------------|------------|-----|
//! | midpoint, gonzalez | energy_consistent | 2 | every term of the step equation at t_{n−1/2} (BDS (1.36), (1.41)) |
//! | midpoint, gonzalez | penalty           | 1 | r p_n at t_n in an equation collocated at t_{n−1/2}: an O(k) defect |
//! | newmark           | penalty            | 2 | the trapezoidal rule collocates every term, the penalty included, at t_n |
//!
//! Space study: n × n meshes with N = c·n steps (k ∝ h), midpoint-type scheme with the
//! energy-consistent force: ‖ε(u_N − u(T))‖ = O(h) and ‖u_N − u(T)‖_{L²} = O(h²) (P1; the O(k²)
//! time error is O(h²), below the energy error and of the L² error's order, so both rates hold).
//!
//! Every run is audited (BDS Propositions 1.1, 1.3; HLT Proposition 3.7): Gonzalez's scheme, and
//! the midpoint rule with the linear law, with the energy-consistent force satisfy the identities
//! at round-off, the body force and tractions doing work (the audit's external work dᵀ f(t_{n−1/2})
//! is the work of the load the scheme applies).

use std::path::Path;
use std::sync::Arc;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use contactlab::mesh::triangle::RectangleSide;
use contactlab::model::dynamic::audit::{AuditSummary, EnergyAudit};
use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::contact_model::{ContactModel, NormalTreatment};
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::{
    DynamicParams, DynamicProblem, DynamicSolver, DynamicStats,
};
use contactlab::model::quasistatic::plane::BoundarySelector;

use crate::core::case::Case;
use crate::core::format::CaseError;
use crate::core::sweep::Against;
use contactlab::model::dynamic::record::Conserving;

use crate::core::context::RunContext;
use crate::core::format::{at_least, invalid};
use crate::core::gate::{Check, GateVerdict, RateGate};
use crate::core::report::case_report::{CaseReport, Table};
use crate::dynamic::errors::{field_errors, FieldErrors};
use crate::dynamic::study::{audit_checks, audit_gate, plot_audits, AuditRun};
use crate::manufactured::dynamic_plane::{
    DynamicManufactured, ManufacturedLaw, MIN_EXACT_PENETRATION,
};
use crate::plot::{Figure, Series};
use contactlab::fem::norms::l2_difference;

/// The contact force of a run (the compliance r of the solution).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactForce {
    /// r (p_n)_+ at t_n (BDS (1.8)).
    Penalty,
    /// r [(p_n)_+² − (p_{n−1})_+²] / (2 (p_n − p_{n−1})) (BDS (1.46), HLT (3.68)).
    EnergyConsistent,
}

impl ContactForce {
    fn name(self) -> &'static str {
        match self {
            Self::Penalty => "penalty",
            Self::EnergyConsistent => "energy_consistent",
        }
    }

    fn treatment(self, stiffness: f64) -> NormalTreatment {
        match self {
            Self::Penalty => NormalTreatment::Penalty { stiffness },
            Self::EnergyConsistent => NormalTreatment::EnergyConsistent { stiffness },
        }
    }
}

/// A scheme with a contact force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Combination {
    pub scheme: DynamicScheme,
    pub treatment: ContactForce,
}

impl Combination {
    fn label(&self) -> String {
        format!("{} + {}", self.scheme.name(), self.treatment.name())
    }

    /// The identities this combination satisfies at round-off (see the module docs).
    fn conserving(&self, law: ManufacturedLaw) -> Conserving {
        let conserving_scheme = self.scheme == DynamicScheme::Gonzalez
            || (self.scheme == DynamicScheme::Midpoint && law == ManufacturedLaw::Linear);
        let consistent = self.treatment == ContactForce::EnergyConsistent;
        Conserving {
            balance: conserving_scheme,
            contact: conserving_scheme && consistent,
        }
    }
}

/// `[time_study]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TimeStudy {
    /// The mesh: n × n squares.
    pub divisions: usize,
    pub steps: Vec<usize>,
    /// Steps of the same-mesh reference run (midpoint-type, energy-consistent force).
    pub reference_steps: usize,
    pub runs: Vec<Combination>,
}

/// `[space_study]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpaceStudy {
    pub divisions: Vec<usize>,
    /// N = steps_per_division · n (k ∝ h).
    pub steps_per_division: usize,
    pub scheme: DynamicScheme,
    pub treatment: ContactForce,
}

/// Which study a gate reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Study {
    Time,
    Space,
}

/// The error a gate fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorName {
    /// time: ‖u_N − u_N^ref‖_{L²}; space: ‖u_N − u(T)‖_{L²}.
    L2,
    /// space: ‖ε(u_N − u(T))‖_{L²}.
    Energy,
}

/// What a `[[gate]]` measures: one error of one study (and, in time, one run).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeriesSelect {
    pub study: Study,
    /// The run of the time study (required there).
    pub scheme: Option<DynamicScheme>,
    pub treatment: Option<ContactForce>,
    pub error: ErrorName,
}

/// `[[gate]]`: a rate gate on one series.
pub type ManufacturedGate = RateGate<SeriesSelect>;

/// The case format of `dynamic_manufactured`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManufacturedCase {
    pub law: ManufacturedLaw,
    #[serde(default)]
    pub mass: MassMatrix,
    pub time_study: Option<TimeStudy>,
    pub space_study: Option<SpaceStudy>,
    #[serde(default)]
    pub gate: Vec<ManufacturedGate>,
}

fn check_combination(p: &Path, field: &str, c: &Combination) -> Result<(), CaseError> {
    if c.scheme == DynamicScheme::Newmark && c.treatment == ContactForce::EnergyConsistent {
        return Err(invalid(
            p,
            field,
            c.label(),
            "a midpoint-type scheme for the energy-consistent force (the solver rejects newmark)",
        ));
    }
    Ok(())
}

impl ManufacturedCase {
    /// Checks the numbers and the references between gates and studies.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        if self.time_study.is_none() && self.space_study.is_none() {
            return Err(invalid(
                p,
                "time_study",
                "(missing)",
                "a [time_study] or a [space_study]",
            ));
        }
        if let Some(t) = &self.time_study {
            at_least(p, "time_study.steps", &t.steps, 2)?;
            at_least(p, "time_study.runs", &t.runs, 1)?;
            let finest = t.steps.iter().copied().max().unwrap_or(0);
            if t.reference_steps < 8 * finest || t.divisions == 0 {
                return Err(invalid(
                    p,
                    "time_study.reference_steps",
                    t.reference_steps,
                    &format!(
                        "at least 8 × the finest steps ({finest}), on a mesh with divisions ≥ 1"
                    ),
                ));
            }
            for (i, c) in t.runs.iter().enumerate() {
                check_combination(p, &format!("time_study.runs[{i}]"), c)?;
            }
        }
        if let Some(s) = &self.space_study {
            at_least(p, "space_study.divisions", &s.divisions, 2)?;
            if s.steps_per_division == 0 || s.divisions.contains(&0) {
                return Err(invalid(
                    p,
                    "space_study.steps_per_division",
                    s.steps_per_division,
                    "≥ 1, with divisions ≥ 1",
                ));
            }
            check_combination(
                p,
                "space_study",
                &Combination {
                    scheme: s.scheme,
                    treatment: s.treatment,
                },
            )?;
        }
        for (i, g) in self.gate.iter().enumerate() {
            self.check_gate(p, i, g)?;
        }
        Ok(())
    }

    fn check_gate(&self, p: &Path, i: usize, gate: &ManufacturedGate) -> Result<(), CaseError> {
        let field = format!("gate[{i}]");
        gate.criteria.check(p, &field)?;
        let g = &gate.select;
        let levels = match g.study {
            Study::Time => {
                let t = self.time_study.as_ref().ok_or_else(|| {
                    invalid(p, &format!("{field}.study"), "time", "a [time_study]")
                })?;
                let c = match (g.scheme, g.treatment) {
                    (Some(scheme), Some(treatment)) => Combination { scheme, treatment },
                    _ => {
                        return Err(invalid(
                            p,
                            &format!("{field}.scheme"),
                            "(missing)",
                            "scheme and treatment of a time_study run",
                        ))
                    }
                };
                if !t.runs.contains(&c) {
                    return Err(invalid(
                        p,
                        &format!("{field}.scheme"),
                        c.label(),
                        "a run of [time_study]",
                    ));
                }
                if g.error != ErrorName::L2 {
                    return Err(invalid(
                        p,
                        &format!("{field}.error"),
                        "energy",
                        "l2 (the time error ‖u_N − u_N^ref‖_L²)",
                    ));
                }
                t.steps.len()
            }
            Study::Space => {
                let s = self.space_study.as_ref().ok_or_else(|| {
                    invalid(p, &format!("{field}.study"), "space", "a [space_study]")
                })?;
                if g.scheme.is_some() || g.treatment.is_some() {
                    return Err(invalid(
                        p,
                        &format!("{field}.scheme"),
                        "(given)",
                        "no scheme or treatment (the space study has one)",
                    ));
                }
                s.divisions.len()
            }
        };
        let finest = gate.criteria.finest_levels;
        if finest > levels {
            return Err(invalid(
                p,
                &format!("{field}.finest_levels"),
                finest,
                &format!("2 … {levels} (the levels of the study)"),
            ));
        }
        Ok(())
    }
}

/// Checks the case's format.
pub fn check(case: &Case) -> Result<(), CaseError> {
    case.body::<ManufacturedCase>()?.check(&case.path)
}

/// One run: its errors against the exact solution, its final state, audit and statistics.
#[derive(Debug, Clone)]
struct RunResult {
    combination: Combination,
    divisions: usize,
    steps: usize,
    errors: FieldErrors,
    final_nodal: Vec<f64>,
    nodes: Vec<[f64; 2]>,
    triangles: Vec<[usize; 3]>,
    /// min over steps and Γ3 nodes of p_i.
    min_penetration: f64,
    audit: EnergyAudit,
    stats: DynamicStats,
}

/// Runs the manufactured problem on n × n squares with N steps.
fn solve(
    m: &DynamicManufactured,
    mass: MassMatrix,
    divisions: usize,
    steps: usize,
    combination: Combination,
) -> Result<RunResult, String> {
    let body = Arc::new(m.body(divisions, mass)?);
    let contact = ContactModel::plane_half_space(
        &body,
        &BoundarySelector::side(RectangleSide::Bottom),
        0.0,
        combination.treatment.treatment(m.stiffness),
        None,
    )
    .map_err(|e| e.to_string())?;
    let nodes = body.data().mesh.nodes().to_vec();
    let problem = DynamicProblem {
        body: body.clone(),
        contact: Some(contact),
        scheme: combination.scheme,
        final_time: m.final_time,
        steps,
        initial_displacement: body.from_nodal(&m.nodal(&nodes, 0.0, false)),
        initial_velocity: body.from_nodal(&m.nodal(&nodes, 0.0, true)),
    };
    let solver =
        DynamicSolver::new(problem, DynamicParams::default()).map_err(|e| e.to_string())?;
    let mut min_penetration = f64::INFINITY;
    let sol = solver
        .solve_with(&mut |v| {
            for f in v.forces {
                min_penetration = min_penetration.min(f.p);
            }
        })
        .map_err(|e| {
            format!(
                "{} on {divisions}×{divisions}, N = {steps}: {e}",
                combination.label()
            )
        })?;
    let final_nodal = body.nodal(&sol.final_displacement);
    let triangles = body.data().mesh.triangles().to_vec();
    let errors = field_errors(&nodes, &triangles, &final_nodal, m.final_time)?;
    Ok(RunResult {
        combination,
        divisions,
        steps,
        errors,
        final_nodal,
        nodes,
        triangles,
        min_penetration,
        audit: sol.audit,
        stats: sol.stats,
    })
}

/// The reference combination of a law: the conserving midpoint-type scheme.
fn reference_combination(law: ManufacturedLaw) -> Combination {
    Combination {
        scheme: if law == ManufacturedLaw::Linear {
            DynamicScheme::Midpoint
        } else {
            DynamicScheme::Gonzalez
        },
        treatment: ContactForce::EnergyConsistent,
    }
}

/// ω_max of the linearized semi-discrete system at u = 0: the largest ω² = λ_max(M⁻¹ (K_T(0) +
/// K_c)), K_c = Σ_i r w_i e_{ν,i} e_{ν,i}ᵀ the compliance of the contact nodes, by 300 power
/// iterations with the Rayleigh quotient (a lower bound converging from below; accurate to a few
/// per cent, enough to place k ω_max). Modes with k ω_max ≳ 1 are integrated with an O(1) phase
/// error by the second-order schemes: the time error reaches its asymptotic k² behaviour only
/// once k ω_max ≲ 0.3 (see the case explanation).
fn max_frequency(
    m: &DynamicManufactured,
    mass: MassMatrix,
    divisions: usize,
) -> Result<f64, String> {
    use contactlab::model::dynamic::body::ElasticBody;
    use contactlab::solve::sparse_cholesky::SparseCholesky;
    let body = m.body(divisions, mass)?;
    let contact = ContactModel::plane_half_space(
        &body,
        &BoundarySelector::side(RectangleSide::Bottom),
        0.0,
        ContactForce::Penalty.treatment(m.stiffness),
        None,
    )
    .map_err(|e| e.to_string())?;
    let n = body.dofs();
    let pattern = body.pattern();
    let mut k = vec![0.0; pattern.nnz()];
    body.add_tangent(&vec![0.0; n], 1.0, &mut k);
    let mut chol =
        SparseCholesky::analyze(pattern, &[], "mass matrix").map_err(|e| e.to_string())?;
    chol.factor(pattern, body.mass())
        .map_err(|e| e.to_string())?;
    let mut ws = chol.workspace(1);
    let apply_k = |x: &[f64], y: &mut [f64]| {
        pattern.symmetric_mul(&k, x, y);
        for nd in &contact.nodes {
            y[nd.normal_dof] += m.stiffness * nd.weight * x[nd.normal_dof];
        }
    };
    // a deterministic start with every mode present
    let mut x: Vec<f64> = (0..n)
        .map(|i| 1.0 + ((i * 7919) % 97) as f64 / 97.0)
        .collect();
    let (mut kx, mut mx) = (vec![0.0; n], vec![0.0; n]);
    let mut lambda = 0.0;
    for _ in 0..300 {
        apply_k(&x, &mut kx);
        pattern.symmetric_mul(body.mass(), &x, &mut mx);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).sum::<f64>();
        lambda = dot(&x, &kx) / dot(&x, &mx);
        chol.solve_in_place(&mut kx, &mut ws);
        let norm = dot(&kx, &kx).sqrt();
        x = kx.iter().map(|v| v / norm).collect();
    }
    Ok(lambda.sqrt())
}

/// The time study's runs (in the order of `runs` × `steps`) and the reference, in parallel.
fn run_time_study(
    m: &DynamicManufactured,
    mass: MassMatrix,
    t: &TimeStudy,
    ctx: &RunContext,
    id: &str,
) -> Result<(Vec<RunResult>, RunResult), String> {
    let mut jobs: Vec<(Combination, usize)> = t
        .runs
        .iter()
        .flat_map(|c| t.steps.iter().map(move |&n| (*c, n)))
        .collect();
    jobs.push((reference_combination(m.law), t.reference_steps));
    let bar = ctx.progress_bar(jobs.len() as u64, id);
    let mut results = jobs
        .par_iter()
        .map(|&(c, n)| {
            let r = solve(m, mass, t.divisions, n, c);
            bar.inc(1);
            r
        })
        .collect::<Result<Vec<_>, _>>()?;
    bar.finish_and_clear();
    let reference = results.pop().ok_or("no reference run")?;
    Ok((results, reference))
}

/// The space study's runs, in parallel (ordered as the divisions).
fn run_space_study(
    m: &DynamicManufactured,
    mass: MassMatrix,
    s: &SpaceStudy,
    ctx: &RunContext,
    id: &str,
) -> Result<Vec<RunResult>, String> {
    let c = Combination {
        scheme: s.scheme,
        treatment: s.treatment,
    };
    let bar = ctx.progress_bar(s.divisions.len() as u64, id);
    let out = s
        .divisions
        .par_iter()
        .map(|&n| {
            let r = solve(m, mass, n, s.steps_per_division * n, c);
            bar.inc(1);
            r
        })
        .collect::<Result<Vec<_>, _>>();
    bar.finish_and_clear();
    out
}

/// A series of (parameter, error) points.
#[derive(Debug, Clone, Serialize)]
struct RateSeries {
    label: String,
    param: Vec<f64>,
    error: Vec<f64>,
}

/// The worst audit summary over runs (largest residuals and step works).
fn worst(summaries: impl Iterator<Item = AuditSummary>) -> AuditSummary {
    summaries.fold(
        AuditSummary {
            max_step_friction_work: f64::NEG_INFINITY,
            max_step_constraint_work: f64::NEG_INFINITY,
            ..Default::default()
        },
        |a, s| AuditSummary {
            energy_scale: a.energy_scale.max(s.energy_scale),
            max_residual_1_48: a.max_residual_1_48.max(s.max_residual_1_48),
            max_residual_1_49: a.max_residual_1_49.max(s.max_residual_1_49),
            max_residual_3_7: a.max_residual_3_7.max(s.max_residual_3_7),
            max_step_friction_work: a.max_step_friction_work.max(s.max_step_friction_work),
            max_step_constraint_work: a.max_step_constraint_work.max(s.max_step_constraint_work),
            drift_1_49: if a.drift_1_49.abs() > s.drift_1_49.abs() {
                a.drift_1_49
            } else {
                s.drift_1_49
            },
            steps: a.steps.max(s.steps),
        },
    )
}

/// Per-step cost and Newton statistics of a run.
fn cost_cells(s: &DynamicStats) -> [String; 3] {
    let steps = s.steps.max(1) as f64;
    [
        format!("{:.2}", s.newton_iterations as f64 / steps),
        format!("{}", s.max_newton_iterations),
        format!("{:.3e}", s.loop_seconds / steps),
    ]
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c: ManufacturedCase = case.body().map_err(|e| e.to_string())?;
    c.check(&case.path).map_err(|e| e.to_string())?;
    let m = DynamicManufactured::standard(c.law);
    let mut all_runs: Vec<RunResult> = Vec::new();
    let mut series: Vec<(Study, Option<Combination>, ErrorName, RateSeries)> = Vec::new();
    if let Some(t) = &c.time_study {
        let (runs, reference) = run_time_study(&m, c.mass, t, ctx, &case.header.id)?;
        let omega = max_frequency(&m, c.mass, t.divisions)?;
        time_outputs(ctx, report, &m, t, omega, &runs, &reference, &mut series)?;
        all_runs.extend(runs);
        all_runs.push(reference);
    }
    if let Some(s) = &c.space_study {
        let runs = run_space_study(&m, c.mass, s, ctx, &case.header.id)?;
        space_outputs(ctx, report, s, &runs, &mut series)?;
        all_runs.extend(runs);
    }
    for (i, g) in c.gate.iter().enumerate() {
        report.gates.push(rate_gate(i, g, &series)?);
    }
    report.gates.push(persistence_gate(&all_runs));
    audit_gates(report, &c, &all_runs);
    Ok(())
}

/// The rate gate `g` on its series.
fn rate_gate(
    i: usize,
    gate: &ManufacturedGate,
    series: &[(Study, Option<Combination>, ErrorName, RateSeries)],
) -> Result<GateVerdict, String> {
    let g = &gate.select;
    let wanted = match (g.scheme, g.treatment) {
        (Some(scheme), Some(treatment)) => Some(Combination { scheme, treatment }),
        _ => None,
    };
    let (_, _, _, s) = series
        .iter()
        .find(|(st, c, e, _)| *st == g.study && *c == wanted && *e == g.error)
        .ok_or_else(|| format!("gate[{i}]: no series for it"))?;
    let against = match g.study {
        Study::Time => Against::K,
        Study::Space => Against::H,
    };
    Ok(gate.criteria.evaluate(
        format!("{}: {:?} error vs {}", s.label, g.error, against.label()),
        &s.param,
        &s.error,
    ))
}

/// min p > 0 over every run and step: the contact stayed persistent, as the exact solution's.
fn persistence_gate(runs: &[RunResult]) -> GateVerdict {
    let min_p = runs
        .iter()
        .map(|r| r.min_penetration)
        .fold(f64::INFINITY, f64::min);
    GateVerdict::from_checks(
        "persistent contact: every Γ3 node penetrated at every step of every run".into(),
        "model",
        vec![
            Check {
                name: "exact min_{x,t} p(x, t) = min a(x, t)".into(),
                observed: MIN_EXACT_PENETRATION,
                limit: "> 0".into(),
                passed: MIN_EXACT_PENETRATION > 0.0,
            },
            Check {
                name: "computed min over runs, steps and Γ3 nodes of p_i".into(),
                observed: min_p,
                limit: "> 0".into(),
                passed: min_p > 0.0,
            },
        ],
        "with p > 0 throughout, the energy-consistent force is r (p_n + p_{n−1})/2 and no contact \
         switch limits the rates",
    )
}

/// One audit gate per combination: its worst summary over every level it ran.
fn audit_gates(report: &mut CaseReport, c: &ManufacturedCase, runs: &[RunResult]) {
    let mut combos: Vec<Combination> = Vec::new();
    for r in runs {
        if !combos.contains(&r.combination) {
            combos.push(r.combination);
        }
    }
    for combo in combos {
        let of_combo: Vec<&RunResult> = runs.iter().filter(|r| r.combination == combo).collect();
        let summary = worst(of_combo.iter().map(|r| r.audit.summary()));
        let conserving = combo.conserving(c.law);
        let label = combo.label();
        let note = if conserving.balance {
            "conserving scheme: the body force and the tractions do work; the audit's external \
             work dᵀ f(t_{n−1/2}) is the work of the load the scheme applies, so the identities \
             still hold to round-off"
        } else {
            "not a conserving combination: only the dissipation signs are gated; its residuals \
             are plotted"
        };
        report.gates.push(audit_gate(
            &format!(
                "energy audit, {label} ({} runs, worst over levels)",
                of_combo.len()
            ),
            audit_checks(&label, &summary, conserving),
            note,
        ));
    }
}

/// Time-study series, plots and table.
#[allow(clippy::too_many_arguments)]
fn time_outputs(
    ctx: &RunContext,
    report: &mut CaseReport,
    m: &DynamicManufactured,
    t: &TimeStudy,
    omega: f64,
    runs: &[RunResult],
    reference: &RunResult,
    series: &mut Vec<(Study, Option<Combination>, ErrorName, RateSeries)>,
) -> Result<(), String> {
    let mut fig = Figure::new(format!(
        "time error ‖u_N − u_N^ref‖_L² at T on {0}×{0} (reference: {1}, N = {2})",
        t.divisions,
        reference.combination.label(),
        t.reference_steps
    ))
    .x_label("k")
    .y_label("‖u_N − u_N^ref‖_L²")
    .log_log()
    .reference_slope(1.0, "slope 1")
    .reference_slope(2.0, "slope 2");
    let mut rows = Vec::new();
    for (i, combo) in t.runs.iter().enumerate() {
        let of: Vec<&RunResult> = runs.iter().filter(|r| r.combination == *combo).collect();
        let k: Vec<f64> = of.iter().map(|r| m.final_time / r.steps as f64).collect();
        let e: Vec<f64> = of
            .iter()
            .map(|r| {
                l2_difference(
                    &r.nodes,
                    &r.triangles,
                    &r.final_nodal,
                    &reference.final_nodal,
                )
            })
            .collect();
        for (j, r) in of.iter().enumerate() {
            let rate = if j > 0 {
                format!("{:.3}", (e[j - 1] / e[j]).ln() / (k[j - 1] / k[j]).ln())
            } else {
                "—".into()
            };
            let [mean_it, max_it, per_step] = cost_cells(&r.stats);
            rows.push(vec![
                combo.label(),
                r.steps.to_string(),
                format!("{:.4e}", k[j]),
                format!("{:.3}", k[j] * omega),
                format!("{:.4e}", e[j]),
                rate,
                format!("{:.4e}", r.errors.l2),
                mean_it,
                max_it,
                per_step,
            ]);
        }
        fig = fig.series(
            Series::line_markers(combo.label(), k.iter().copied().zip(e.iter().copied())).color(i),
        );
        series.push((
            Study::Time,
            Some(*combo),
            ErrorName::L2,
            RateSeries {
                label: format!("time, {}", combo.label()),
                param: k,
                error: e,
            },
        ));
    }
    ctx.plot(report, "time_rates", &fig)?;
    report.tables.push(Table {
        title: format!(
            "time study on {0}×{0} (ω_max = {3:.1}): time error against the reference ({1}, N = {2}), \
             total L² error against u(T), Newton iterations and cost per step",
            t.divisions,
            reference.combination.label(),
            t.reference_steps,
            omega
        ),
        header: [
            "run",
            "N",
            "k",
            "k ω_max",
            "‖u_N − u_N^ref‖_L²",
            "pairwise rate",
            "‖u_N − u(T)‖_L²",
            "Newton its/step",
            "max its",
            "s/step",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
    let finest = t.steps.iter().copied().max().unwrap_or(0);
    let audited: Vec<AuditRun<'_>> = runs
        .iter()
        .filter(|r| r.steps == finest)
        .map(|r| AuditRun {
            label: format!("{} (N = {})", r.combination.label(), r.steps),
            audit: &r.audit,
        })
        .collect();
    plot_audits(
        ctx,
        report,
        "time_audit",
        &format!("{0}×{0}, N = {finest}", t.divisions),
        &audited,
        None,
    )
}

/// Space-study series, plot and table.
fn space_outputs(
    ctx: &RunContext,
    report: &mut CaseReport,
    s: &SpaceStudy,
    runs: &[RunResult],
    series: &mut Vec<(Study, Option<Combination>, ErrorName, RateSeries)>,
) -> Result<(), String> {
    let label = Combination {
        scheme: s.scheme,
        treatment: s.treatment,
    }
    .label();
    let h: Vec<f64> = runs.iter().map(|r| 1.0 / r.divisions as f64).collect();
    let energy: Vec<f64> = runs.iter().map(|r| r.errors.energy).collect();
    let l2: Vec<f64> = runs.iter().map(|r| r.errors.l2).collect();
    let fig = Figure::new(format!(
        "errors at T against u(T), {label}, N = {} n (k ∝ h)",
        s.steps_per_division
    ))
    .x_label("h = 1/n")
    .y_label("error")
    .log_log()
    .series(
        Series::line_markers(
            "‖ε(u_N − u(T))‖",
            h.iter().copied().zip(energy.iter().copied()),
        )
        .color(0),
    )
    .series(
        Series::line_markers("‖u_N − u(T)‖_L²", h.iter().copied().zip(l2.iter().copied())).color(1),
    )
    .reference_slope(1.0, "slope 1")
    .reference_slope(2.0, "slope 2");
    ctx.plot(report, "space_rates", &fig)?;
    let pair = |v: &[f64], j: usize| {
        if j == 0 {
            "—".to_string()
        } else {
            format!("{:.3}", (v[j - 1] / v[j]).ln() / (h[j - 1] / h[j]).ln())
        }
    };
    report.tables.push(Table {
        title: format!("space study, {label}: errors at T, pairwise rates, Newton iterations and cost per step"),
        header: [
            "n × n",
            "N",
            "‖ε(u_N − u(T))‖",
            "rate",
            "‖u_N − u(T)‖_L²",
            "rate",
            "Newton its/step",
            "max its",
            "s/step",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows: runs
            .iter()
            .enumerate()
            .map(|(j, r)| {
                let [mean_it, max_it, per_step] = cost_cells(&r.stats);
                vec![
                    format!("{0}×{0}", r.divisions),
                    r.steps.to_string(),
                    format!("{:.4e}", energy[j]),
                    pair(&energy, j),
                    format!("{:.4e}", l2[j]),
                    pair(&l2, j),
                    mean_it,
                    max_it,
                    per_step,
                ]
            })
            .collect(),
    });
    series.push((
        Study::Space,
        None,
        ErrorName::Energy,
        RateSeries {
            label: format!("space, {label}, energy norm"),
            param: h.clone(),
            error: energy,
        },
    ));
    series.push((
        Study::Space,
        None,
        ErrorName::L2,
        RateSeries {
            label: format!("space, {label}, L²"),
            param: h,
            error: l2,
        },
    ));
    Ok(())
}

#[cfg(test)]
mod tests {
    //! The format: unknown keys, newmark with the energy-consistent force, and gates naming runs
    //! the case does not have are errors; a coarse run of the linear solution conserves energy to
    //! round-off and stays in persistent contact.
    use super::*;
    use std::path::PathBuf;

    const CASE: &str = r#"
id = "t"
title = "t"
kind = "dynamic_manufactured"
explanation = "x"
law = "linear"
[time_study]
divisions = 4
steps = [4, 8]
reference_steps = 64
runs = [{ scheme = "midpoint", treatment = "energy_consistent" }]
[[gate]]
study = "time"
scheme = "midpoint"
treatment = "energy_consistent"
error = "l2"
expected_rate = 2.0
tolerance = 0.1
finest_levels = 2
ci_width = 1.0
ceiling = 1.0
"#;

    fn load(text: &str) -> Result<ManufacturedCase, CaseError> {
        let path = PathBuf::from("t.toml");
        let case = Case::from_text(Path::new("t"), text)?;
        let c: ManufacturedCase = case.body()?;
        c.check(&path)?;
        Ok(c)
    }

    #[test]
    fn valid_case_parses() {
        load(CASE).unwrap();
    }

    #[test]
    fn unknown_key_is_an_error() {
        assert!(load(&CASE.replace("law = \"linear\"", "law = \"linear\"\nfoo = 1")).is_err());
    }

    #[test]
    fn newmark_with_energy_consistent_force_is_an_error() {
        let text = CASE.replace(
            "runs = [{ scheme = \"midpoint\"",
            "runs = [{ scheme = \"newmark\"",
        );
        let err = load(&text).unwrap_err().to_string();
        assert!(err.contains("time_study.runs[0]"), "{err}");
    }

    #[test]
    fn gate_on_a_missing_run_is_an_error() {
        let text = CASE.replace(
            "scheme = \"midpoint\"\ntreatment",
            "scheme = \"gonzalez\"\ntreatment",
        );
        assert!(load(&text).is_err());
    }

    #[test]
    fn coarse_linear_run_conserves_and_stays_in_contact() {
        let m = DynamicManufactured::standard(ManufacturedLaw::Linear);
        let c = Combination {
            scheme: DynamicScheme::Midpoint,
            treatment: ContactForce::EnergyConsistent,
        };
        let r = solve(&m, MassMatrix::Consistent, 4, 16, c).unwrap();
        let s = r.audit.summary();
        assert!(
            s.max_residual_1_48 < 1e-12 && s.max_residual_1_49 < 1e-12,
            "{s:?}"
        );
        assert!(r.min_penetration > 0.0);
        assert!(r.errors.l2 < 0.05, "{:?}", r.errors);
    }
}
