//! One run of the two blocks (a scheme at one step count) and what it measures against
//! [`crate::exact::two_block_slide::TwoBlockSlide`].
//!
//! | quantity | definition |
//! |---|---|
//! | `stop_time_error` | \|t_s − t*\| / t*, t_s = t_{n_s − 1}, n_s the first step in which no interface node slips by more than the threshold ([`slip_threshold`]) |
//! | `stop_step_offset` | (n_s − 1) minus the last sliding step of the scheme on the rigid blocks |
//! | `stop_velocity` | max over n ≥ n_s of \|w_n\| / \|w₀\|: the relative velocity that alternates after the stop (rigid: \|w(t_s)\| = φ a k) |
//! | `deceleration_error` | \|a_fit − a\| / a, a_fit the least-squares slope of −σ w_n over the sliding steps 0 … n_s − 1 |
//! | `velocity_error` | max over the sliding steps and both blocks of \|v_{i,n} − v_i(t_n)\| / \|w₀\|, v the rigid velocities (the scheme's are exact up to the stop) |
//! | `dissipation_error` | \|D − D*\| / D*, D = E_0 − E_N + Σ W_ext (energies from the states, W_ext gravity's work) |
//! | `dissipation_discrete` | \|D − D(t_s)\| / D*, D(t_s) = F \|s(t_s)\| the scheme's rigid dissipation |
//! | `dissipation_friction` | \|D − D_μ\| / D*, D_μ = Σ_n Σ_slipping μ λ_N \|τ₁ − τ₀\| |
//! | `slip_after_stop` | max over n ≥ n_s and the interface nodes of \|τ₁ − τ₀\| (the elastic blocks' shakedown: edge nodes may slip by a few δ_s while the alternating stick force settles) |
//! | `partial_slip_steps` | steps before n_s in which some active interface node sticks |
//! | `vertical_velocity` | max over the sliding steps of \|v_{y,1,n}\| / \|w₀\|: the upper block's vertical centre velocity (the normal force's departure from m₁ g integrates to it) |
//! | `invariant_error` | max over the sliding steps of the drifts of I₁ = v_{x,1} + σ μ v_{y,1} + σ μ g t and I₂ = v_{x,2} − σ μ (m₁/m₂) (v_{y,1} + g t), relative to \|w₀\| |
//! | `settled_step` | the first step from which no interface node is in slip (the elastic shakedown after the stop) |
//! | `slip_after_settling` | max over n ≥ `settled_step` and the interface nodes of \|τ₁ − τ₀\| |
//!
//! **The momentum invariants.** While every interface node slips (with σ, and the interface
//! flat to its deflection), the upper block receives −σ μ λ_N along x and λ_N along y from each
//! node, and gravity: m₁ Δv_{x,1} = −σ μ Σ_n k N_n and m₁ Δv_{y,1} = Σ_n k N_n − m₁ g t, N_n the
//! step's total normal force. Eliminating it, I₁ = v_{x,1} + σ μ v_{y,1} + σ μ g t is constant,
//! and the lower block (friction +σ μ N_n, the foundation frictionless) keeps I₂ constant. These
//! hold for the elastic blocks whatever their ringing does to N_n: they test Coulomb's law at its
//! size and sign, at the step's normal force, and the reaction on the master — not the rigid
//! model. The relative velocity then departs from the rigid w₀ − σ a t by exactly
//! −σ μ (1 + m₁/m₂) (v_{y,1} − v_{y,1}(0)), the vertical ringing.

use std::collections::BTreeMap;

use serde::Serialize;

use contactlab::model::multibody::audit::MultibodySummary;
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{MultibodySolution, MultibodyStats};

use crate::exact::two_block_slide::{TwoBlockSlide, TwoBlockStop};
use crate::multibody::audit_state::{StateAudit, StateAuditor};
use crate::multibody::cases::friction::setup::{Setting, BASE, INTERFACE, LOWER, UPPER};
use crate::multibody::errors::centre_velocity;

/// One step of a run.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct StepRow {
    pub time: f64,
    /// Centre velocities [x, y] of the upper and the lower block.
    pub upper: [f64; 2],
    pub lower: [f64; 2],
    /// Σ λ_N and Σ λ_T over the interface; Σ λ_N over the foundation.
    pub normal: f64,
    pub tangential: f64,
    pub base_normal: f64,
    /// Active interface nodes that slip and that stick.
    pub slipping: usize,
    pub sticking: usize,
    /// max |τ₁ − τ₀| over the interface nodes.
    pub max_slip: f64,
    /// Σ over slipping interface nodes of μ λ_N |τ₁ − τ₀| (the step's dissipation by the law).
    pub dissipation: f64,
    /// Σ λ_T (τ₁ − τ₀) over the interface (the step's friction work, ≤ 0).
    pub friction_work: f64,
    /// kinetic + stored energy after the step, and the loads' work of the step.
    pub energy: f64,
    pub external_work: f64,
}

/// One run.
#[derive(Debug, Clone, Serialize)]
pub struct Run {
    pub scheme: MultibodyScheme,
    pub steps: usize,
    pub k: f64,
    pub predicted: TwoBlockStop,
    /// The slip above which a step slides ([`slip_threshold`]).
    pub threshold: f64,
    /// n_s − 1 observed (N when the blocks still slip at T).
    pub last_sliding_step: usize,
    pub errors: BTreeMap<String, f64>,
    /// The fitted deceleration.
    pub deceleration: f64,
    /// D, D_μ.
    pub dissipation: f64,
    pub friction_dissipation: f64,
    pub audit: MultibodySummary,
    /// The audit recomputed from the state (`crate::multibody::audit_state`).
    #[serde(skip)]
    pub state: StateAudit,
    pub stats: MultibodyStats,
    pub seconds: f64,
    #[serde(skip)]
    pub rows: Vec<StepRow>,
    #[serde(skip)]
    pub records: Vec<contactlab::model::multibody::audit::MultibodyRecord>,
}

/// Runs `scheme` with N = `steps` up to T = duration × t*.
pub fn run(
    setting: &Setting,
    exact: &TwoBlockSlide,
    mu: f64,
    scheme: MultibodyScheme,
    duration: f64,
    steps: usize,
) -> Result<Run, String> {
    let final_time = duration * exact.stop_time();
    let solver = setting.solver(scheme, final_time, steps)?;
    let k = solver.step_size();
    let bodies = &setting.bodies;
    let mut scratch = vec![0.0; bodies.dofs()];
    let mut rows: Vec<StepRow> = Vec::with_capacity(steps + 1);
    let materials = vec![setting.material; bodies.len()];
    let mut auditor = StateAuditor::new(solver.problem(), &materials, &[])?;
    let start = std::time::Instant::now();
    let solution: MultibodySolution = solver
        .solve_with(&mut |view| {
            auditor.observe(view);
            let mut row = StepRow {
                time: view.time,
                upper: centre_velocity(bodies, UPPER, view.velocity, &mut scratch),
                lower: centre_velocity(bodies, LOWER, view.velocity, &mut scratch),
                energy: view.record.energy,
                external_work: view.record.external_work,
                ..Default::default()
            };
            for c in view.contacts {
                if c.pair == BASE {
                    row.base_normal += c.lambda_n;
                    continue;
                }
                if c.pair != INTERFACE {
                    continue;
                }
                row.normal += c.lambda_n;
                row.tangential += c.lambda_t;
                row.max_slip = row.max_slip.max(c.slip.abs());
                row.friction_work += c.lambda_t * c.slip;
                if c.active {
                    if c.stick {
                        row.sticking += 1;
                    } else {
                        row.slipping += 1;
                        row.dissipation += mu * c.lambda_n * c.slip.abs();
                    }
                }
            }
            rows.push(row);
        })
        .map_err(|e| format!("{} (N = {steps}): {e}", scheme.name()))?;
    let seconds = start.elapsed().as_secs_f64();
    let audit = solution.summary();
    let state = auditor.finish()?;
    let predicted = exact.discrete_stop(k);
    let threshold = slip_threshold(exact, k);
    // n_s: the first step in which no interface node slips by more than the threshold
    let n_s = (1..rows.len())
        .find(|&n| rows[n].max_slip <= threshold)
        .unwrap_or(steps);
    // the shakedown: the last step in which the solver has a node in slip
    let settled = (1..rows.len())
        .rev()
        .find(|&n| rows[n].slipping > 0)
        .map_or(1, |n| n + 1);
    let last_sliding_step = n_s.saturating_sub(1);
    let w0 = exact.initial_relative_velocity();
    let sigma = w0.signum();
    let t_star = exact.stop_time();
    let a = exact.relative_deceleration();
    let mut errors = BTreeMap::new();
    errors.insert(
        "stop_time_error".to_string(),
        (last_sliding_step as f64 * k - t_star).abs() / t_star,
    );
    errors.insert(
        "stop_step_offset".to_string(),
        last_sliding_step as f64 - predicted.last_sliding_step as f64,
    );
    let w = |r: &StepRow| r.upper[0] - r.lower[0];
    errors.insert(
        "stop_velocity".to_string(),
        rows.iter()
            .skip(n_s)
            .map(|r| w(r).abs())
            .fold(0.0, f64::max)
            / w0.abs(),
    );
    // least-squares slope over the sliding steps 0 … n_s − 1
    let fit: Vec<(f64, f64)> = rows[..n_s.min(rows.len())]
        .iter()
        .map(|r| (r.time, sigma * w(r)))
        .collect();
    let deceleration = -slope(&fit);
    errors.insert(
        "deceleration_error".to_string(),
        (deceleration - a).abs() / a,
    );
    let velocity_error = rows[..n_s.min(rows.len())]
        .iter()
        .enumerate()
        .map(|(n, r)| {
            let [e1, e2] = exact.discrete_velocities(k, n);
            (r.upper[0] - e1).abs().max((r.lower[0] - e2).abs())
        })
        .fold(0.0, f64::max)
        / w0.abs();
    errors.insert("velocity_error".to_string(), velocity_error);
    let d_star = exact.total_dissipation();
    let (first, last) = (rows[0], rows[rows.len() - 1]);
    let external: f64 = rows[1..].iter().map(|r| r.external_work).sum();
    let dissipation = first.energy - last.energy + external;
    let friction_dissipation: f64 = rows[1..].iter().map(|r| r.dissipation).sum();
    errors.insert(
        "dissipation_error".to_string(),
        (dissipation - d_star).abs() / d_star,
    );
    errors.insert(
        "dissipation_discrete".to_string(),
        (dissipation - predicted.dissipation).abs() / d_star,
    );
    errors.insert(
        "dissipation_friction".to_string(),
        (dissipation - friction_dissipation).abs() / d_star,
    );
    errors.insert(
        "slip_after_stop".to_string(),
        rows.iter()
            .skip(n_s)
            .map(|r| r.max_slip)
            .fold(0.0, f64::max),
    );
    errors.insert(
        "partial_slip_steps".to_string(),
        rows[1..n_s.min(rows.len())]
            .iter()
            .filter(|r| r.sticking > 0)
            .count() as f64,
    );
    errors.insert(
        "vertical_velocity".to_string(),
        rows[..n_s.min(rows.len())]
            .iter()
            .map(|r| r.upper[1].abs())
            .fold(0.0, f64::max)
            / w0.abs(),
    );
    let (m1, m2) = (exact.upper_mass, exact.lower_mass);
    let mg = mu * exact.gravity;
    let inv1 = |r: &StepRow| r.upper[0] + sigma * mu * r.upper[1] + sigma * mg * r.time;
    let inv2 =
        |r: &StepRow| r.lower[0] - sigma * mu * m1 / m2 * (r.upper[1] + exact.gravity * r.time);
    errors.insert(
        "invariant_error".to_string(),
        rows[..n_s.min(rows.len())]
            .iter()
            .map(|r| {
                (inv1(r) - inv1(&first))
                    .abs()
                    .max((inv2(r) - inv2(&first)).abs())
            })
            .fold(0.0, f64::max)
            / w0.abs(),
    );
    errors.insert("settled_step".to_string(), settled as f64);
    errors.insert(
        "slip_after_settling".to_string(),
        rows.iter()
            .skip(settled)
            .map(|r| r.max_slip)
            .fold(0.0, f64::max),
    );
    Ok(Run {
        scheme,
        steps,
        k,
        predicted,
        threshold,
        last_sliding_step,
        errors,
        deceleration,
        dissipation,
        friction_dissipation,
        audit,
        state,
        stats: solution.stats.clone(),
        seconds,
        rows,
        records: solution.records,
    })
}

/// The slip above which a step counts as sliding: a tenth of the rigid blocks' smallest slide,
/// a k² |θ − ½| (the last sliding step's mean relative velocity is a (t* − t_{n−1/2}) ≥
/// a k |θ − ½|, exact/two_block_slide.rs). The elastic blocks' micro-slips at the stop (a few
/// δ_s, the case files give the numbers) lie far below it on every level of the cases.
pub fn slip_threshold(exact: &TwoBlockSlide, k: f64) -> f64 {
    let theta = (exact.stop_time() / k).fract();
    0.1 * exact.relative_deceleration() * k * k * (theta - 0.5).abs()
}

/// The least-squares slope of y against t (0 for fewer than two points).
pub fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    if points.len() < 2 {
        return 0.0;
    }
    let tm = points.iter().map(|p| p.0).sum::<f64>() / n;
    let ym = points.iter().map(|p| p.1).sum::<f64>() / n;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for &(t, y) in points {
        sxy += (t - tm) * (y - ym);
        sxx += (t - tm) * (t - tm);
    }
    sxy / sxx
}
