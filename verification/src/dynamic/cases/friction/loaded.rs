//! The loaded block's runs (`[loaded]`): one family at one step count on the full solver path,
//! each step checked with the reference laws ([`super::residual`]) and, for a constant μ, the
//! momentum invariant J = P_x + μ P_y = J(0) − μ p L t of
//! [`crate::exact::loaded_block::LoadedBlock`] while every contact node slides forward.
//!
//! The invariant's allowance: the sum of the x rows of (1.36) plus μ times the sum of the y rows
//! is (ΔJ_n + μ p L k)/k (the internal forces cancel: K maps a translation to zero), so
//! |J_n − J(t_n)| ≤ Σ_{m ≤ n} k (Σ_{x rows} a_i + μ Σ_{y rows} a_i) with a_i = τ s + 64 ε A_i
//! what each row may leave (residual.rs).

use serde::Serialize;

use contactlab::model::dynamic::audit::AuditSummary;
use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::dynamic::solver::{DynamicStats, StepView};

use crate::dynamic::cases::friction::block::{build, momentum, Hold, Shape};
use crate::dynamic::cases::friction::format::{FamilySpec, LoadedSpec};
use crate::dynamic::cases::friction::residual::StepEquations;
use crate::exact::coulomb_friction::FrictionLaw;

/// The Newton tolerance of the loaded runs (the solver's default).
pub const TOLERANCE: f64 = 1e-12;

/// One run of the loaded block.
#[derive(Debug, Clone, Serialize)]
pub struct LoadedRun {
    pub family: String,
    pub steps: usize,
    pub k: f64,
    /// The rigid-limit stop time of the family (the runs last `duration` of it).
    pub rigid_stop_time: f64,
    /// max over steps and rows of |R_i| / (τ s + 64 ε A_i) (≤ 1; residual.rs).
    pub max_residual: f64,
    /// max over steps and sticking nodes of (|T| − μN) w / (64 ε A_i) (≤ 1); None if no node
    /// stuck.
    pub max_stick_excess: Option<f64>,
    /// The end of the run of steps from t = 0 in which every contact node slides forward.
    pub all_slide_until: f64,
    /// For a constant μ: max |J_n − J(t_n)| / (m v0) over that run, and its allowance.
    pub invariant_error: Option<f64>,
    pub invariant_allowance: Option<f64>,
    /// max over that run of |J_n − J(t_n)| over its allowance at step n (≤ 1).
    pub invariant_ratio: Option<f64>,
    /// min and max over steps and nodes of the penetration (the rocking).
    pub penetration_range: [f64; 2],
    pub audit: AuditSummary,
    pub stats: DynamicStats,
    /// (t, residual ratio, |J error| / (m v0)) per step.
    #[serde(skip)]
    pub history: Vec<[f64; 3]>,
}

/// Runs family `f` with N = `steps` (T = duration × the rigid-limit stop time).
pub fn run(spec: &LoadedSpec, f: &FamilySpec, steps: usize) -> Result<LoadedRun, String> {
    run_with_reference(spec, f, f, steps)
}

/// Runs family `f` and checks it against the laws of family `reference` (the same family in a
/// case; another one in the tests, to see the check fail).
pub fn run_with_reference(
    spec: &LoadedSpec,
    f: &FamilySpec,
    reference: &FamilySpec,
    steps: usize,
) -> Result<LoadedRun, String> {
    let exact = spec.block();
    let coulomb = reference.coulomb();
    let rigid = exact.rigid_stop_time(f.coulomb().mu(exact.penetration()));
    let final_time = spec.duration * rigid;
    let k = final_time / steps as f64;
    let shape = Shape {
        size: [spec.length, spec.height],
        divisions: spec.divisions,
        density: spec.density,
        law: "linear",
        young: spec.young,
        poisson: spec.poisson,
    };
    let v0 = spec.speed;
    let built = build(
        &shape,
        &Hold::Pressure {
            pressure: spec.pressure,
        },
        f,
        spec.stiffness,
        spec.scheme,
        (final_time, steps),
        TOLERANCE,
        &|x, y| (exact.static_displacement(x, y), [v0, 0.0]),
        true,
    )?;
    let body = &built.body;
    let n = body.dofs();
    // the component of each free dof
    let mut component = vec![0usize; n];
    for node in 0..body.data().mesh.nodes().len() {
        for c in 0..2 {
            if let Some(d) = body.dof(node, c) {
                component[d] = c;
            }
        }
    }
    let equations = StepEquations::new(
        body,
        &built.contact,
        (coulomb, spec.compliance(reference)),
        k,
        TOLERANCE,
    )
    .ok_or("the loaded block's check needs a linear body")?;
    let constant = (reference.law == FrictionLaw::Constant).then_some(reference.mu0);
    let momentum0 = exact.mass() * v0;
    let (mut u_prev, mut v_prev) = (vec![0.0; n], vec![0.0; n]);
    let mut scratch = vec![0.0; n];
    let mut run = LoadedRun {
        family: f.name.clone(),
        steps,
        k,
        rigid_stop_time: rigid,
        max_residual: 0.0,
        max_stick_excess: None,
        all_slide_until: 0.0,
        invariant_error: constant.map(|_| 0.0),
        invariant_allowance: constant.map(|_| 0.0),
        invariant_ratio: constant.map(|_| 0.0),
        penetration_range: [f64::INFINITY, f64::NEG_INFINITY],
        audit: AuditSummary::default(),
        stats: DynamicStats::default(),
        history: Vec::new(),
    };
    let mut sliding = true;
    let mut allowance = 0.0;
    let label = format!("{} (N = {steps})", f.name);
    let solution = built
        .solver
        .solve_with(&mut |view: &StepView<'_>| {
            for fc in view.forces {
                run.penetration_range[0] = run.penetration_range[0].min(fc.p);
                run.penetration_range[1] = run.penetration_range[1].max(fc.p);
            }
            let mut j_error = 0.0;
            if view.step > 0 {
                let c = equations.check(view.time, (&u_prev, &v_prev), view.velocity);
                let ratio = c.residual;
                run.max_residual = run.max_residual.max(ratio);
                if let Some(e) = c.stick_excess {
                    run.max_stick_excess = Some(run.max_stick_excess.map_or(e, |m: f64| m.max(e)));
                }
                sliding &= c.all_slide_forward;
                if sliding {
                    run.all_slide_until = view.time;
                    if let Some(mu) = constant {
                        let p = momentum(body, view.velocity, &mut scratch);
                        let j = p[0] + mu * p[1];
                        j_error = (j - exact.invariant(mu, view.time)).abs() / momentum0;
                        allowance += k * c
                            .allowance
                            .iter()
                            .zip(&component)
                            .map(|(a, &comp)| if comp == 0 { *a } else { mu * a })
                            .sum::<f64>()
                            / momentum0;
                        run.invariant_error = run.invariant_error.map(|m| m.max(j_error));
                        run.invariant_allowance = Some(allowance);
                        run.invariant_ratio =
                            run.invariant_ratio.map(|m| m.max(j_error / allowance));
                    }
                }
                run.history.push([view.time, ratio, j_error]);
            }
            u_prev.copy_from_slice(view.displacement);
            v_prev.copy_from_slice(view.velocity);
        })
        .map_err(|e| format!("{label}: {e}"))?;
    run.audit = solution.audit.summary();
    run.stats = solution.stats;
    Ok(run)
}
