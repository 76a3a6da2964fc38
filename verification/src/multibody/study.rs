//! What every multibody case shares: bodies built from a case's numbers, a run recorded step by
//! step (each body's centre-of-mass velocity, the contact forces), and the audit's gates and
//! plots.
//!
//! The audit gates read the solver's summary ([`MultibodySummary`]): every drift is divided by its
//! tolerance (round-off C ε Σ s_j plus what the Newton residual allows, module docs of
//! `contactlab::model::multibody::audit`), so a check passes at ≤ 1. What a run may claim
//! ([`Claims`]) follows from its scheme and its setting: the energy identity and the conservation
//! of energy between changes of the active set only for the energy–momentum scheme; linear
//! momentum when no load and no foundation acts along a component; angular momentum also needs
//! an objective law (St Venant–Kirchhoff or neo-Hooke: the linear law's stress is not
//! rotation invariant); friction's sign always.

use std::sync::Arc;

use serde::Serialize;

use contactlab::field::Field;
use contactlab::mesh::triangle::{Diagonal, TriangleMesh};
use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};
use contactlab::model::multibody::audit::{MultibodyRecord, MultibodySummary};
use contactlab::model::multibody::history::two_step_mean;
use contactlab::model::multibody::solver::{MultibodySolution, MultibodySolver};
use contactlab::model::quasistatic::plane::{DirichletPart, TractionPart};

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::multibody::audit_state::{StateAudit, StateAuditor};
use crate::multibody::errors::centre_velocity;
use crate::plot::{Figure, Series};

pub use crate::multibody::spec::{Claims, LawName, MaterialSpec};

/// A rectangular body with P1 triangles (consistent mass), its supports, tractions and body force.
#[allow(clippy::too_many_arguments)]
pub fn rectangle_body(
    origin: [f64; 2],
    size: [f64; 2],
    divisions: [usize; 2],
    density: f64,
    material: &MaterialSpec,
    dirichlet: Vec<DirichletPart>,
    traction: Vec<TractionPart>,
    body_force: [f64; 2],
) -> Result<Arc<PlaneBody>, String> {
    let mesh = TriangleMesh::rectangle(origin, size, divisions, Diagonal::Up)
        .map_err(|e| e.to_string())?;
    let body = PlaneBody::new(PlaneBodyData {
        mesh,
        density,
        law: material.law()?,
        dirichlet,
        traction,
        body_force: [
            Field::Constant(body_force[0]),
            Field::Constant(body_force[1]),
        ],
        mass: MassMatrix::Consistent,
        regions: vec![],
    })
    .map_err(|e| e.to_string())?;
    Ok(Arc::new(body))
}

/// One step of a recorded run.
#[derive(Debug, Clone, Default, Serialize)]
pub struct StepHistory {
    pub time: f64,
    /// Each body's centre-of-mass velocity.
    pub velocities: Vec<[f64; 2]>,
    /// Σ λ_N and Σ λ_T over the candidates.
    pub normal_force: f64,
    pub friction_force: f64,
    /// The two-step mean of Σ λ_N, (J_n + J_{n+1})/(2k) with J the step impulses: the accurate
    /// contact force, where the raw Σ λ_N alternates from step to step
    /// (`contactlab::model::multibody::history`).
    pub normal_force_mean: f64,
    /// Active, sticking and slipping constraints.
    pub active: usize,
    pub sticking: usize,
    pub slipping: usize,
}

/// A run with its step history.
#[derive(Debug, Clone)]
pub struct RecordedRun {
    pub solution: MultibodySolution,
    pub summary: MultibodySummary,
    pub history: Vec<StepHistory>,
    /// The audit recomputed from the state (`crate::multibody::audit_state`).
    pub state: StateAudit,
}

/// Solves `solver`'s problem, recording each body's centre-of-mass velocity and the contact
/// forces after every step, and auditing it from the state (body b of material `materials[b]`,
/// as the case built it).
pub fn run_recorded(
    solver: &MultibodySolver,
    materials: &[MaterialSpec],
) -> Result<RecordedRun, String> {
    let bodies = &solver.problem().bodies;
    let mut scratch = vec![0.0; bodies.dofs()];
    let mut history = Vec::new();
    let mut auditor = StateAuditor::new(solver.problem(), materials, &[])?;
    let solution = solver
        .solve_with(&mut |view| {
            auditor.observe(view);
            history.push(StepHistory {
                time: view.time,
                velocities: (0..bodies.len())
                    .map(|b| centre_velocity(bodies, b, view.velocity, &mut scratch))
                    .collect(),
                normal_force: view.record.normal_force,
                friction_force: view.record.friction_force,
                normal_force_mean: 0.0,
                active: view.record.active,
                sticking: view.record.sticking,
                slipping: view.record.slipping,
            });
        })
        .map_err(|e| e.to_string())?;
    let raw: Vec<f64> = history.iter().map(|h| h.normal_force).collect();
    let mean = two_step_mean(&raw, solver.problem().scheme, solver.step_size());
    for (h, m) in history.iter_mut().zip(mean) {
        h.normal_force_mean = m;
    }
    let summary = solution.summary();
    let state = auditor.finish()?;
    Ok(RecordedRun {
        solution,
        summary,
        history,
        state,
    })
}

/// The audit checks of a run: each claimed ratio ≤ 1 (module docs).
pub fn audit_checks(label: &str, s: &MultibodySummary, claims: Claims) -> Vec<Check> {
    let mut checks = Vec::new();
    if claims.identity {
        checks.push(Check::at_most(
            &format!("{label}: max_n |Σ_j (ΔE_j − W_j)| / tolerance (energy identity)"),
            s.identity_ratio,
            1.0,
        ));
    }
    if claims.unchanged {
        checks.push(Check::at_most(
            &format!(
                "{label}: max over steps without a set change of |ΔE − W_ext − W_T| / tolerance"
            ),
            s.unchanged_ratio,
            1.0,
        ));
    }
    for (c, name) in [(0, "P_x"), (1, "P_y")] {
        if claims.momentum[c] {
            let v = if c == 0 {
                s.momentum_ratio_x
            } else {
                s.momentum_ratio_y
            };
            checks.push(Check::at_most(
                &format!("{label}: max_n |{name}(t_n) − {name}(0)| / tolerance"),
                v,
                1.0,
            ));
        }
    }
    if claims.angular {
        checks.push(Check::at_most(
            &format!("{label}: max_n |J(t_n) − J(0)| / tolerance"),
            s.angular_ratio,
            1.0,
        ));
    }
    // a run whose friction did no work at all (a frictionless pair, or friction never acted)
    // has the ratio 0 identically: not applicable there, left out of the counts (a bug that
    // books friction work where there is none makes it nonzero, and the check is back)
    if claims.friction_sign && (s.friction_work != 0.0 || s.friction_ratio != 0.0) {
        checks.push(Check::at_most(
            &format!("{label}: max_n step friction work / tolerance (≤ 0 up to round-off)"),
            s.friction_ratio,
            1.0,
        ));
    }
    checks
}

/// A gate from audit checks.
pub fn audit_gate(name: &str, checks: Vec<Check>, note: &str) -> GateVerdict {
    GateVerdict::from_checks(name.to_string(), "energy audit", checks, note)
}

/// A run's records with its label, for the audit plots.
pub struct AuditRun<'a> {
    pub label: String,
    pub records: &'a [MultibodyRecord],
}

/// The audit figures: the total energy against t; the drift of the energy identity |Σ (ΔE − W)|
/// relative to E_0; the drifts of P and J relative to their scales (log axes; exact zeros drawn
/// at 1e-18).
pub fn audit_figures(title: &str, runs: &[AuditRun<'_>]) -> Vec<Figure> {
    let floor = |v: f64| v.max(1e-18);
    let mut energy = Figure::new(format!("{title}: total energy"))
        .x_label("t")
        .y_label("E = kinetic + stored (+ penalty)");
    let mut identity = Figure::new(format!("{title}: energy identity drift"))
        .x_label("t")
        .y_label("|Σ (ΔE − W_N − W_T − W_ext)| / E_0")
        .semilog_y();
    let mut momenta = Figure::new(format!("{title}: momentum drifts"))
        .x_label("t")
        .y_label("|P − P_0| / Σ|Mv|, |J − J_0| / Σ|x||Mv|")
        .semilog_y();
    for (i, run) in runs.iter().enumerate() {
        let Some(first) = run.records.first() else {
            continue;
        };
        let e0 = first.energy.abs().max(f64::MIN_POSITIVE);
        energy = energy.series(
            Series::line(
                run.label.clone(),
                run.records.iter().map(|r| (r.time, r.energy)),
            )
            .color(i),
        );
        let mut drift = 0.0;
        identity = identity.series(
            Series::line(
                run.label.clone(),
                run.records.iter().skip(1).map(|r| {
                    drift += r.identity_residual;
                    (r.time, floor(drift.abs() / e0))
                }),
            )
            .color(i),
        );
        momenta = momenta.series(
            Series::line(
                format!("{}: P", run.label),
                run.records.iter().skip(1).map(|r| {
                    let d = (r.momentum[0] - first.momentum[0])
                        .abs()
                        .max((r.momentum[1] - first.momentum[1]).abs());
                    (r.time, floor(d / r.momentum_scale.max(f64::MIN_POSITIVE)))
                }),
            )
            .color(i),
        );
        momenta = momenta.series(
            Series::line(
                format!("{}: J", run.label),
                run.records.iter().skip(1).map(|r| {
                    let d = (r.angular_momentum - first.angular_momentum).abs();
                    (r.time, floor(d / r.angular_scale.max(f64::MIN_POSITIVE)))
                }),
            )
            .color(i)
            .dashed(),
        );
    }
    vec![energy, identity, momenta]
}

/// Writes the audit figures of `runs` as one panel row into the report.
pub fn plot_audits(
    ctx: &RunContext,
    report: &mut CaseReport,
    name: &str,
    title: &str,
    runs: &[AuditRun<'_>],
) -> Result<(), String> {
    ctx.panels(
        report,
        &format!("{name}_audit"),
        &format!("{title}: the audit"),
        &audit_figures(title, runs),
        3,
    )
}
