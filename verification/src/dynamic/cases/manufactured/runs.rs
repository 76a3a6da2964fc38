//! The runs of `dynamic_manufactured`: one solve of the manufactured problem with its sources,
//! the highest frequency ω_max of the mesh, and the time study (affine field) and space study
//! (smooth field).

use std::sync::Arc;

use rayon::prelude::*;

use contactlab::mesh::triangle::RectangleSide;
use contactlab::model::dynamic::audit::EnergyAudit;
use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::contact_model::ContactModel;
use contactlab::model::dynamic::record::{conserving, Conserving};
use contactlab::model::dynamic::solver::{
    DynamicParams, DynamicProblem, DynamicSolver, DynamicStats,
};
use contactlab::model::quasistatic::plane::BoundarySelector;

use crate::core::context::RunContext;
use crate::dynamic::audit_state::geometry::Gamma3;
use crate::dynamic::audit_state::run::Foundation;
use crate::dynamic::audit_state::{AuditSpec, StateAudit, StateAuditor};
use crate::dynamic::cases::manufactured::format::{
    Combination, ContactForce, SpaceStudy, TimeStudy,
};
use crate::dynamic::errors::{field_errors, FieldErrors};
use crate::manufactured::dynamic_plane::ManufacturedLaw;
use crate::manufactured::dynamic_plane::{DynamicManufactured, ManufacturedField};
use crate::manufactured::strain_energy::{PlaneLaw, StrainEnergy};

/// One run: its errors against the exact solution, its final state, audit and statistics.
#[derive(Debug, Clone)]
pub(crate) struct RunResult {
    pub(crate) combination: Combination,
    pub(crate) divisions: usize,
    pub(crate) steps: usize,
    pub(crate) errors: FieldErrors,
    /// min over steps and Γ3 nodes of p_i.
    pub(crate) min_penetration: f64,
    pub(crate) audit: EnergyAudit,
    pub(crate) stats: DynamicStats,
    /// The audit recomputed from the state, and the identities the problem claims.
    pub(crate) state: Result<StateAudit, String>,
    pub(crate) claims: Conserving,
}

/// What the state audit reads of the manufactured problem: its density and Lamé constants, the
/// mass kind, and the foundation {y ≤ 0} under the bottom side with the stiffness r.
fn audit_spec(m: &DynamicManufactured, mass: MassMatrix) -> AuditSpec {
    let law = match m.law {
        ManufacturedLaw::Linear => StrainEnergy::Linear,
        ManufacturedLaw::StVenantKirchhoff => StrainEnergy::StVenantKirchhoff,
        ManufacturedLaw::NeoHooke => StrainEnergy::NeoHooke,
    };
    AuditSpec {
        density: m.density,
        lumped: mass == MassMatrix::Lumped,
        law: PlaneLaw {
            law,
            lambda: m.lambda,
            mu: m.mu,
        },
        foundation: Some(Foundation {
            level: 0.0,
            gamma3: Gamma3::Sides(vec![RectangleSide::Bottom]),
            stiffness: Some(m.stiffness),
            tilted: false,
        }),
    }
}

/// Runs the manufactured problem on n × n squares with N steps.
pub(crate) fn solve(
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
    let params = DynamicParams {
        force_full_path: combination.full_path,
        ..DynamicParams::default()
    };
    let claims = conserving(&problem);
    let mut auditor = StateAuditor::new(&body, &problem, audit_spec(m, mass));
    let solver = DynamicSolver::new(problem, params).map_err(|e| e.to_string())?;
    let mut min_penetration = f64::INFINITY;
    let sol = solver
        .solve_with(&mut |v| {
            if let Ok(a) = &mut auditor {
                a.observe(v);
            }
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
    let errors = field_errors(m.field, &nodes, &triangles, &final_nodal, m.final_time)?;
    let state = auditor.and_then(StateAuditor::finish);
    Ok(RunResult {
        combination,
        divisions,
        steps,
        errors,
        min_penetration,
        audit: sol.audit,
        stats: sol.stats,
        state,
        claims,
    })
}

/// ω_max of the linearized semi-discrete system at u = 0: the largest ω² = λ_max(M⁻¹ (K_T(0) +
/// K_c)), K_c = Σ_i r w_i e_{ν,i} e_{ν,i}ᵀ the compliance of the contact nodes, by 300 power
/// iterations with the Rayleigh quotient (a lower bound converging from below; accurate to a few
/// per cent, enough to place k ω_max). Modes with k ω_max ≳ 1 are integrated with an O(1) phase
/// error by the second-order schemes: the time error reaches its asymptotic k² behaviour only
/// once k ω_max ≲ 0.3 (see the case explanation).
pub(crate) fn max_frequency(
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

/// The time study's runs (in the order of `runs` × `steps`), in parallel, on the affine field
/// (the time error alone: see [`crate::manufactured::dynamic_plane::ManufacturedField::Affine`]).
pub(crate) fn run_time_study(
    m: &DynamicManufactured,
    mass: MassMatrix,
    t: &TimeStudy,
    ctx: &RunContext,
    id: &str,
) -> Result<Vec<RunResult>, String> {
    let affine = m.with_field(ManufacturedField::Affine);
    let jobs: Vec<(Combination, usize)> = t
        .runs
        .iter()
        .flat_map(|c| t.steps.iter().map(move |&n| (*c, n)))
        .collect();
    let bar = ctx.progress_bar(jobs.len() as u64, id);
    let results = jobs
        .par_iter()
        .map(|&(c, n)| {
            let r = solve(&affine, mass, t.divisions, n, c);
            bar.inc(1);
            r
        })
        .collect::<Result<Vec<_>, _>>()?;
    bar.finish_and_clear();
    Ok(results)
}

/// The space study's runs, in parallel (ordered as the divisions).
pub(crate) fn run_space_study(
    m: &DynamicManufactured,
    mass: MassMatrix,
    s: &SpaceStudy,
    ctx: &RunContext,
    id: &str,
) -> Result<Vec<RunResult>, String> {
    let c = Combination {
        scheme: s.scheme,
        treatment: s.treatment,
        full_path: false,
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
