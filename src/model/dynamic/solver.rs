//! The time loop of a dynamic contact problem: scheme, contact treatment (with the two stages of
//! the improved penalized method), energy audit, outputs.
//!
//! The solver path is chosen from the problem (never by the user): a linear body factors
//! α M + θ K once and condenses every step onto its contact dofs ([`CondensedStep`]); a
//! hyperelastic body runs the full semismooth Newton method with one symbolic analysis and a
//! numeric refactorization per iteration ([`FullStep`]). No friction code runs when μ = 0.

use std::sync::Arc;
use std::time::Instant;

use serde::Serialize;

use crate::contact::compliance::penalty;
use crate::error::{require_positive, Error, InputError, SolveError};
use crate::model::dynamic::audit::{AuditRecord, EnergyAudit, NodeStep, StepInput};
use crate::model::dynamic::body::{stiffness_at_rest, ElasticBody};
use crate::model::dynamic::contact_model::{ContactModel, NormalTreatment};
use crate::model::dynamic::newton::{
    solve_stage, NewtonParams, NewtonWorkspace, NodeForces, NodeLaw, NodeState, StageNode, StepAt,
};
use crate::model::dynamic::scheme::DynamicScheme;
use crate::model::dynamic::step_operator::{CondensedStep, FullStep, StepOperator};
use crate::solve::sparse_cholesky::SparseCholesky;

/// A dynamic problem: body, foundation, scheme, time interval and initial state (free dofs).
#[derive(Debug, Clone)]
pub struct DynamicProblem {
    pub body: Arc<dyn ElasticBody>,
    pub contact: Option<ContactModel>,
    pub scheme: DynamicScheme,
    pub final_time: f64,
    pub steps: usize,
    pub initial_displacement: Vec<f64>,
    pub initial_velocity: Vec<f64>,
}

/// Which linear-algebra path a run takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DynamicPath {
    /// Linear body: factored once, condensed onto the contact dofs.
    Condensed,
    /// Full semismooth Newton on all dofs.
    Full,
}

/// Parameters of a run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DynamicParams {
    pub newton: NewtonParams,
    /// Force the full path even for a linear body (for comparisons).
    pub force_full_path: bool,
    /// Times at which to keep the displacement (nearest step).
    pub snapshot_times: Vec<f64>,
}

/// Statistics of a run.
#[derive(Debug, Clone, Default, Serialize)]
pub struct DynamicStats {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path: Option<DynamicPath>,
    pub steps: usize,
    pub unknowns: usize,
    pub contact_nodes: usize,
    pub newton_iterations: usize,
    pub max_newton_iterations: usize,
    pub factorizations: usize,
    /// Of those, factorizations of an indefinite Jacobian (LBLᵀ fallback; full path only).
    pub indefinite_factorizations: usize,
    pub backtracks: usize,
    /// Newton solves accepted at their computed round-off floor (every free row within
    /// `newton::FLOOR_FACTOR` ε Σ|terms|) rather than at the requested tolerance.
    pub newton_floor_stops: usize,
    pub stage_b_steps: usize,
    /// Largest final relative residual of a Newton solve.
    pub max_newton_residual: f64,
    /// Wall time of the time loop (setup excluded) and of the setup.
    pub loop_seconds: f64,
    pub setup_seconds: f64,
    pub factor_nnz: usize,
}

/// What an observer sees after each step.
#[derive(Debug)]
pub struct StepView<'a> {
    pub step: usize,
    pub time: f64,
    /// u_n and the scheme's velocity at t_n (δu_n or v_n), free dofs.
    pub displacement: &'a [f64],
    pub velocity: &'a [f64],
    /// The contact nodes' forces (per node of the contact model).
    pub forces: &'a [NodeForces],
    pub record: &'a AuditRecord,
}

/// The result of a run.
#[derive(Debug, Clone, Default, Serialize)]
pub struct DynamicSolution {
    pub audit: EnergyAudit,
    /// (time, u) at the requested snapshot times.
    pub snapshots: Vec<(f64, Vec<f64>)>,
    pub final_displacement: Vec<f64>,
    pub final_velocity: Vec<f64>,
    pub stats: DynamicStats,
}

/// The solver of a dynamic problem.
#[derive(Debug)]
pub struct DynamicSolver {
    problem: DynamicProblem,
    params: DynamicParams,
}

/// The linear-algebra path with its operator.
enum Operator {
    Condensed(CondensedStep),
    Full(FullStep),
}

impl DynamicSolver {
    /// Validates the problem.
    pub fn new(problem: DynamicProblem, params: DynamicParams) -> Result<Self, Error> {
        let n = problem.body.dofs();
        require_positive("time.final_time", problem.final_time)?;
        if problem.steps == 0 {
            return Err(InputError::new("time.steps", 0, "at least 1 step").into());
        }
        params.newton.validate()?;
        for (name, v) in [
            ("initial.displacement", &problem.initial_displacement),
            ("initial.velocity", &problem.initial_velocity),
        ] {
            if v.len() != n {
                return Err(InputError::new(
                    name,
                    format!("{} values", v.len()),
                    format!("{n} values (one per free dof)"),
                )
                .into());
            }
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Err(
                    InputError::new(format!("{name}[{i}]"), v[i], "a finite number").into(),
                );
            }
        }
        if let Some(c) = &problem.contact {
            c.treatment.validate("contact.treatment")?;
            if problem.scheme == DynamicScheme::Newmark && c.treatment.is_energy_consistent() {
                return Err(InputError::new(
                    "scheme",
                    "newmark",
                    format!(
                        "a midpoint-type scheme (midpoint or gonzalez) for the {} contact force, \
                         whose exact discrete work is defined for the midpoint relation (1.31)",
                        c.treatment.name()
                    ),
                )
                .into());
            }
        }
        Ok(Self { problem, params })
    }

    /// The problem.
    pub fn problem(&self) -> &DynamicProblem {
        &self.problem
    }

    /// The path the problem takes.
    pub fn path(&self) -> DynamicPath {
        if self.problem.body.is_linear() && !self.params.force_full_path {
            DynamicPath::Condensed
        } else {
            DynamicPath::Full
        }
    }

    /// Runs the time loop.
    pub fn solve(&self) -> Result<DynamicSolution, Error> {
        self.solve_with(&mut |_| {})
    }

    /// Runs the time loop, calling `observer` after each step (and once for the initial state).
    pub fn solve_with(
        &self,
        observer: &mut dyn FnMut(&StepView<'_>),
    ) -> Result<DynamicSolution, Error> {
        let setup_start = Instant::now();
        let pb = &self.problem;
        let body = &pb.body;
        let n = body.dofs();
        let k = pb.final_time / pb.steps as f64;
        let scheme = pb.scheme;
        let pattern = body.pattern();
        let no_nodes: Vec<crate::model::dynamic::contact_model::ContactNode> = Vec::new();
        let (nodes, treatment) = match &pb.contact {
            Some(c) => (&c.nodes, Some(c.treatment)),
            None => (&no_nodes, None),
        };
        let friction = pb.contact.as_ref().and_then(|c| c.friction);
        let contact_dofs = pb.contact.as_ref().map(|c| c.dofs()).unwrap_or_default();
        let path = self.path();
        let mut op = match path {
            DynamicPath::Condensed => {
                Operator::Condensed(CondensedStep::new(body.clone(), scheme, k, &contact_dofs)?)
            }
            DynamicPath::Full => {
                Operator::Full(FullStep::new(body.clone(), scheme, k, &contact_dofs)?)
            }
        };
        // operator index of a dof
        let index_of: Vec<usize> = match &op {
            Operator::Condensed(c) => {
                let mut v = vec![usize::MAX; n];
                for (i, &g) in c.gamma().iter().enumerate() {
                    v[g] = i;
                }
                v
            }
            Operator::Full(_) => (0..n).collect(),
        };
        let op_len = match &op {
            Operator::Condensed(c) => c.len(),
            Operator::Full(f) => f.len(),
        };
        let mut stats = DynamicStats {
            path: Some(path),
            unknowns: n,
            contact_nodes: nodes.len(),
            factor_nnz: match &op {
                Operator::Condensed(c) => c.factor_nnz(),
                Operator::Full(f) => f.factor_nnz(),
            },
            ..Default::default()
        };

        // state
        let mut u = pb.initial_displacement.clone();
        let mut v = pb.initial_velocity.clone();
        let mut a = vec![0.0; n];
        let mut q: Vec<f64> = nodes
            .iter()
            .map(|nd| nd.offset + nd.sign * u[nd.normal_dof])
            .collect();
        let mut f_prev = vec![0.0; n];
        let mut f_now = vec![0.0; n];
        let mut f_int = vec![0.0; n];
        let mut mv = vec![0.0; n];
        let mut b = vec![0.0; n];
        let mut d = vec![0.0; n];
        let mut d_op = vec![0.0; op_len];
        let mut forces = vec![NodeForces::default(); nodes.len()];
        let mut forces_prev = vec![NodeForces::default(); nodes.len()];
        let mut state = vec![NodeState::default(); nodes.len()];
        let mut stage_nodes: Vec<StageNode> = Vec::with_capacity(nodes.len());
        let mut ws = NewtonWorkspace::default();
        body.load_into(0.0, &mut f_prev);
        // initial contact forces: the compliance at u0 (a constraint carries none initially)
        for (i, nd) in nodes.iter().enumerate() {
            let nf = match treatment {
                Some(NormalTreatment::Signorini) | None => 0.0,
                Some(t) => penalty(t.stiffness().unwrap_or(0.0), q[i]).value,
            };
            forces_prev[i] = NodeForces {
                p: q[i],
                normal: nf,
                force_nd: -nd.sign * nd.weight * nf,
                compliance_nd: -nd.sign * nd.weight * nf,
                ..Default::default()
            };
        }
        if scheme == DynamicScheme::Newmark {
            // a0 = M⁻¹ (f(0) + ξ(u0) − F_int(u0))
            if !body.internal_force(&u, &mut f_int) {
                return Err(InputError::new(
                    "initial.displacement",
                    "(inadmissible)",
                    "a displacement with det F > 0 in every element",
                )
                .into());
            }
            let mut rhs: Vec<f64> = f_prev.iter().zip(&f_int).map(|(f, g)| f - g).collect();
            for (i, nd) in nodes.iter().enumerate() {
                rhs[nd.normal_dof] += forces_prev[i].force_nd;
            }
            let mut mchol = SparseCholesky::analyze(pattern, &[], "mass matrix M")?;
            mchol.factor(pattern, body.mass())?;
            let mut mws = mchol.workspace(1);
            mchol.solve_in_place(&mut rhs, &mut mws);
            a.copy_from_slice(&rhs);
        }
        let mut audit = EnergyAudit {
            dofs: n,
            ..Default::default()
        };
        // ‖K‖_∞ of the stiffness at rest: the round-off scale of the internal force (`audit`)
        let stiffness_norm = {
            let abs: Vec<f64> = stiffness_at_rest(body.as_ref())
                .iter()
                .map(|v| v.abs())
                .collect();
            let mut rows = vec![0.0; n];
            pattern.symmetric_mul(&abs, &vec![1.0; n], &mut rows);
            rows.iter().fold(0.0, |m: f64, v| m.max(*v))
        };
        let norm = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>().sqrt();
        let kinetic = |v: &[f64], mv: &mut [f64]| {
            pattern.symmetric_mul(body.mass(), v, mv);
            0.5 * v.iter().zip(mv.iter()).map(|(x, y)| x * y).sum::<f64>()
        };
        // the audit's penetrations p = o + s u_ν, from the displacements (docs of `audit`)
        let stiffness = treatment.and_then(|t| t.stiffness());
        let penetrations = |u: &[f64]| -> Vec<f64> {
            nodes
                .iter()
                .map(|nd| nd.offset + nd.sign * u[nd.normal_dof])
                .collect()
        };
        let mut p_audit = penetrations(&u);
        let mut audit_nodes: Vec<NodeStep> = nodes
            .iter()
            .zip(&p_audit)
            .map(|(nd, &p)| NodeStep {
                weight: nd.weight,
                sign: nd.sign,
                stiffness,
                penetration: [p, p],
                ..Default::default()
            })
            .collect();
        let mut rec = AuditRecord {
            contact_force: forces_prev
                .iter()
                .zip(nodes)
                .map(|(f, nd)| nd.weight * f.normal)
                .sum(),
            max_penetration: q.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            ..AuditRecord::initial(kinetic(&v, &mut mv), body.stored_energy(&u), &audit_nodes)
        };
        if nodes.is_empty() {
            rec.max_penetration = 0.0;
        }
        audit.records.push(rec);
        let mut snapshots: Vec<(f64, Vec<f64>)> = Vec::new();
        let mut next_snapshot = 0;
        let mut snap_times = self.params.snapshot_times.clone();
        snap_times.sort_by(f64::total_cmp);
        let mut take_snapshots = |step: usize, t: f64, u: &[f64], next: &mut usize| {
            while *next < snap_times.len() && snap_times[*next] <= t + 0.5 * k {
                // a time written twice (or two times of one step) is recorded once
                let fresh = snapshots.last().is_none_or(|(last, _)| *last != t);
                if (snap_times[*next] > t - 0.5 * k || step == 0) && fresh {
                    snapshots.push((t, u.to_vec()));
                }
                *next += 1;
            }
        };
        take_snapshots(0, 0.0, &u, &mut next_snapshot);
        observer(&StepView {
            step: 0,
            time: 0.0,
            displacement: &u,
            velocity: &v,
            forces: &forces_prev,
            record: &audit.records[0],
        });
        stats.setup_seconds = setup_start.elapsed().as_secs_f64();
        let loop_start = Instant::now();
        let alpha = scheme.alpha(k);
        let load_varies = body.load_depends_on_time();
        for step in 1..=pb.steps {
            crate::run_control::check(|| {
                format!("step {step} of {} (t = {})", pb.steps, k * step as f64)
            })?;
            crate::run_control::report_progress("steps", step as u64, pb.steps as u64);
            let t = k * step as f64;
            let at = StepAt { step, time: t };
            // the step's load and constant data b
            let t_load = if scheme.is_midpoint_type() {
                t - 0.5 * k
            } else {
                t
            };
            if load_varies || step == 1 {
                body.load_into(t_load, &mut f_now);
            }
            match scheme {
                DynamicScheme::Newmark => {
                    pattern.symmetric_mul(body.mass(), &v, &mut mv);
                    let mut ma = vec![0.0; 0];
                    std::mem::swap(&mut ma, &mut f_int);
                    pattern.symmetric_mul(body.mass(), &a, &mut ma);
                    for i in 0..n {
                        b[i] = alpha * k * mv[i] + ma[i] + f_now[i];
                    }
                    std::mem::swap(&mut ma, &mut f_int);
                }
                _ => {
                    pattern.symmetric_mul(body.mass(), &v, &mut mv);
                    for i in 0..n {
                        b[i] = alpha * k * mv[i] + f_now[i];
                    }
                }
            }
            match &mut op {
                Operator::Condensed(c) => c.prepare(&u, &b),
                Operator::Full(f) => f.prepare(&u, &b),
            }
            // predictor d = k v
            for (i, g) in index_of.iter().enumerate() {
                if *g != usize::MAX {
                    d_op[*g] = k * v[i];
                }
            }
            // stage (a)
            stage_nodes.clear();
            for (i, nd) in nodes.iter().enumerate() {
                let law = match treatment {
                    Some(NormalTreatment::Penalty { stiffness }) => {
                        NodeLaw::Penalty { r: stiffness }
                    }
                    Some(NormalTreatment::EnergyConsistent { stiffness })
                    | Some(NormalTreatment::LimitedPenetration { stiffness, .. }) => {
                        NodeLaw::EnergyConsistent { r: stiffness }
                    }
                    Some(NormalTreatment::HauretLeTallecTilted { stiffness }) => {
                        NodeLaw::Tilted { r: stiffness }
                    }
                    Some(NormalTreatment::Signorini) | None => NodeLaw::Constrained {
                        gap: 0.0,
                        stiffness: 0.0,
                    },
                };
                stage_nodes.push(StageNode {
                    nd: index_of[nd.normal_dof],
                    td: nd.tangent_dof.map(|t| index_of[t]),
                    sign: nd.sign,
                    weight: nd.weight,
                    q: q[i],
                    law,
                    friction: friction
                        .map(|f| (f, false))
                        .filter(|_| nd.tangent_dof.is_some()),
                });
            }
            let op_ref: &mut dyn StepOperator = match &mut op {
                Operator::Condensed(c) => c,
                Operator::Full(f) => f,
            };
            // stage (a), then, for the limited penetration, stage (b) of the IPM (BDS (1.45)):
            // nodes that reached the depth g are held at g with the compliance L g; continued
            // while stage (b) pushes further nodes past g
            let mut iterations = 0;
            let mut stage_b = false;
            let mut residual_norm;
            loop {
                let s = solve_stage(
                    op_ref,
                    &stage_nodes,
                    &mut state,
                    &mut d_op,
                    &mut forces,
                    &self.params.newton,
                    &mut ws,
                    at,
                )?;
                iterations += s.iterations;
                residual_norm = s.residual_norm;
                stats.backtracks += s.backtracks;
                stats.newton_floor_stops += usize::from(s.at_floor);
                stats.max_newton_residual = stats.max_newton_residual.max(s.residual);
                let Some(NormalTreatment::LimitedPenetration { stiffness, depth }) = treatment
                else {
                    break;
                };
                let mut added = false;
                for (i, sn) in stage_nodes.iter_mut().enumerate() {
                    if forces[i].p >= depth && !matches!(sn.law, NodeLaw::Constrained { .. }) {
                        sn.law = NodeLaw::Constrained {
                            gap: depth,
                            stiffness,
                        };
                        state[i].active = true;
                        sn.friction = sn.friction.map(|(f, _)| (f, true));
                        added = true;
                    }
                }
                if !added {
                    break;
                }
                stage_b = true;
            }
            if stage_b {
                stats.stage_b_steps += 1;
            }
            // the full increment
            match &mut op {
                Operator::Condensed(c) => c.finish(&d_op, &mut d),
                Operator::Full(_) => d.copy_from_slice(&d_op),
            }
            if let Some(i) = d.iter().position(|x| !x.is_finite()) {
                return Err(SolveError::NonFinite {
                    step,
                    time: t,
                    quantity: format!("displacement increment (dof {i})"),
                    value: d[i],
                    hint: String::new(),
                }
                .into());
            }
            // update u, v (, a)
            match scheme {
                DynamicScheme::Newmark => {
                    for i in 0..n {
                        let a_new = alpha * (d[i] - k * v[i]) - a[i];
                        v[i] += 0.5 * k * (a[i] + a_new);
                        a[i] = a_new;
                        u[i] += d[i];
                    }
                }
                _ => {
                    for i in 0..n {
                        v[i] = 2.0 / k * d[i] - v[i];
                        u[i] += d[i];
                    }
                }
            }
            // audit: the forces applied over the step (Newmark: the trapezoidal mean), the
            // penetrations from the displacements
            let prev = *audit.records.last().unwrap_or(&AuditRecord::default());
            let w_ext = if scheme == DynamicScheme::Newmark {
                d.iter()
                    .zip(f_prev.iter().zip(&f_now))
                    .map(|(x, (a, b))| x * 0.5 * (a + b))
                    .sum::<f64>()
            } else {
                d.iter().zip(&f_now).map(|(x, y)| x * y).sum::<f64>()
            };
            let p_now = penetrations(&u);
            let avg = |now: f64, before: f64| {
                if scheme == DynamicScheme::Newmark {
                    0.5 * (now + before)
                } else {
                    now
                }
            };
            for (i, nd) in nodes.iter().enumerate() {
                let (f, b) = (&forces[i], &forces_prev[i]);
                audit_nodes[i] = NodeStep {
                    penetration: [p_audit[i], p_now[i]],
                    increment: [d[nd.normal_dof], nd.tangent_dof.map_or(0.0, |t| d[t])],
                    compliance: [
                        avg(f.compliance_nd, b.compliance_nd),
                        avg(f.compliance_td, b.compliance_td),
                    ],
                    multiplier: avg(f.multiplier, b.multiplier),
                    friction: avg(f.friction_td, b.friction_td),
                    ..audit_nodes[i]
                };
            }
            let rec = AuditRecord {
                contact_force: forces
                    .iter()
                    .zip(nodes)
                    .map(|(f, nd)| nd.weight * f.normal)
                    .sum(),
                friction_force: forces
                    .iter()
                    .zip(nodes)
                    .map(|(f, nd)| nd.weight * f.tangential)
                    .sum(),
                max_penetration: forces.iter().map(|f| f.p).fold(
                    if nodes.is_empty() {
                        0.0
                    } else {
                        f64::NEG_INFINITY
                    },
                    f64::max,
                ),
                newton_iterations: iterations,
                stage_b,
                active_nodes: state
                    .iter()
                    .zip(&stage_nodes)
                    .filter(|(s, sn)| s.active && matches!(sn.law, NodeLaw::Constrained { .. }))
                    .count(),
                ..prev.after(&StepInput {
                    step,
                    time: t,
                    kinetic: kinetic(&v, &mut mv),
                    elastic: body.stored_energy(&u),
                    external_work: w_ext,
                    stiffness_work: stiffness_norm * norm(&u) * norm(&d),
                    newton_work: d_op.iter().map(|x| x.abs()).sum::<f64>() * residual_norm,
                    nodes: &audit_nodes,
                })
            };
            if let Some((quantity, value)) = rec.first_non_finite() {
                // the likely cause: the data at the first step, else the scheme
                let hint = if step == 1 {
                    " — the first step's values overflow: the magnitudes of the loads, initial \
                     velocities, moduli or contact stiffness in the scene are too large (or too \
                     small) for each other"
                } else if scheme == DynamicScheme::Gonzalez {
                    " — Gonzalez's scheme conserves energy, so the growth comes from the data \
                     (loads, contact stiffness) or from a step too large for its Newton method: \
                     try a smaller step"
                } else {
                    " — the scheme lost stability (try gonzalez or a smaller step)"
                };
                return Err(SolveError::NonFinite {
                    step,
                    time: t,
                    quantity: format!("{quantity} in the energy audit"),
                    value,
                    hint: hint.into(),
                }
                .into());
            }
            audit.records.push(rec);
            stats.newton_iterations += iterations;
            stats.max_newton_iterations = stats.max_newton_iterations.max(iterations);
            for (qi, f) in q.iter_mut().zip(forces.iter()) {
                *qi = f.p;
            }
            p_audit = p_now;
            forces_prev.copy_from_slice(&forces);
            std::mem::swap(&mut f_prev, &mut f_now);
            if !load_varies {
                f_now.copy_from_slice(&f_prev);
            }
            take_snapshots(step, t, &u, &mut next_snapshot);
            observer(&StepView {
                step,
                time: t,
                displacement: &u,
                velocity: &v,
                forces: &forces,
                record: audit.records.last().unwrap_or(&AuditRecord::default()),
            });
        }
        stats.steps = pb.steps;
        stats.loop_seconds = loop_start.elapsed().as_secs_f64();
        stats.factorizations = match &op {
            Operator::Condensed(c) => c.factorizations(),
            Operator::Full(f) => f.factorizations(),
        };
        stats.indefinite_factorizations = match &op {
            Operator::Condensed(c) => c.indefinite_factorizations(),
            Operator::Full(f) => f.indefinite_factorizations(),
        };
        Ok(DynamicSolution {
            audit,
            snapshots,
            final_displacement: u,
            final_velocity: v,
            stats,
        })
    }
}
