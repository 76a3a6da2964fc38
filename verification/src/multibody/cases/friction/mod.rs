//! Case kind `multibody_friction`: a block sliding on a larger block with Coulomb friction
//! (docs/multibody.md), against [`crate::exact::two_block_slide::TwoBlockSlide`].
//!
//! The lower block rests on the frictionless rigid foundation, the upper one on the lower one
//! (slave: the upper block's bottom; master: the lower block's top; friction μ, Lagrange
//! multipliers), both under gravity, stiff, starting from their static equilibrium
//! (`MultibodySolver::solve_static`) with the upper block launched along x. Each `[sweep]`
//! level (a scheme at N steps up to T = duration × t*) is measured by [`run`] and gated:
//!
//! | gate | what it checks | a bug it catches |
//! |---|---|---|
//! | the stop step (exact) | n_s − 1 = the last sliding step of the scheme on the rigid blocks, ⌈t*/k + ½⌉ − 1 | a wrong μ or normal force (t* moves by many steps), the friction bound at t_n (no friction in the first step: one step late), an explicit slip direction (chatter at the stop) |
//! | `[[gate]]` rates | \|t_s − t*\| / t* ∝ k (exactly φ k/t*, φ = ⅓), the dissipation's error ∝ k² (exactly ½ m_r (φ a k)²/D*) | a stop that is not the midpoint rule's (another phase, another order) |
//! | slide | the fitted deceleration of w against a = μ g (1 + m₁/m₂); the momentum invariants I₁, I₂ while slipping; every interface node slips before the stop | μ used as 2μ (a doubles), the normal force of the foundation pair (a × 5), τ without the length ℓ (a × 1/ℓ), the reaction missing on the master (I₂), the bound at t_n (I₁ off by μ g k from the first step) |
//! | dissipation | D = E₀ − E_N + W_g against μ Σ λ_N \|slip\| and against the scheme's rigid F \|s(t_s)\| | μ wrong in the slip force but not in the bound (D_μ ≠ D), energy created by the contact forces |
//! | stick | after the stop no step slides (every slip below a tenth of the rigid blocks' smallest slide), the elastic shakedown ends within T and the slip is then at round-off | a stick state that creeps, a stick/slip cycle |
//! | audit | P_x at round-off every step, friction's step work ≤ 0; the energy–momentum scheme's energy identity | friction that is not internal (P_x), friction that pumps energy (sign) |
//!
//! Newmark runs at the shown level when `sweep.newmark` is set: reported, not gated (its
//! initial acceleration ignores the equilibrium's contact forces, see the case files).

pub mod format;
pub mod report;
pub mod run;
pub mod setup;

use rayon::prelude::*;

use contactlab::model::multibody::scheme::MultibodyScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::multibody::audit_state::{state_audit_checks, state_audit_gate};
use crate::multibody::cases::friction::format::FrictionCase;
use crate::multibody::cases::friction::run::Run;
use crate::multibody::cases::friction::setup::Setting;
use crate::multibody::study::{audit_checks, audit_gate, Claims};

/// Checks a case of this kind.
pub fn check(case: &Case) -> Result<(), CaseError> {
    FrictionCase::from_case(case).map(|_| ())
}

/// Runs a case of this kind.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let file = FrictionCase::from_case(case).map_err(|e| e.to_string())?;
    let id = case.header.id.as_str();
    let setting = Setting::new(&file.blocks)?;
    let exact = file.blocks.exact();
    let sweep = &file.sweep;
    let mut jobs: Vec<(MultibodyScheme, usize)> = sweep
        .schemes
        .iter()
        .flat_map(|&s| sweep.steps.iter().map(move |&n| (s, n)))
        .collect();
    if sweep.newmark {
        jobs.push((MultibodyScheme::Newmark, sweep.show));
    }
    let bar = ctx.progress_bar(jobs.len() as u64, id);
    let outcomes: Vec<Result<Run, String>> = jobs
        .par_iter()
        .map(|&(scheme, n)| {
            let r = run::run(
                &setting,
                &exact,
                file.blocks.friction,
                scheme,
                sweep.duration,
                n,
            );
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    let mut runs = Vec::new();
    let mut newmark = None;
    for (o, &(scheme, _)) in outcomes.into_iter().zip(&jobs) {
        if scheme == MultibodyScheme::Newmark {
            newmark = Some(o);
        } else {
            runs.push(o?);
        }
    }
    gates(&file, &runs, report);
    report::tables(&file, &setting, &runs, newmark.as_ref(), report);
    report::plots(&file, ctx, report, &runs)?;
    ctx.write_data(
        report,
        &serde_json::json!({
            "exact": exact,
            "shear_lag": file.blocks.shear_lag(),
            "compression": file.blocks.compression(),
            "runs": runs,
            "newmark": newmark.map(|o| o.map_err(|e| e.to_string())),
        }),
    )
}

/// The round-off of a slip: 16 ε times the largest coordinate (the solver's constraint rows hold
/// c (τ₁ − τ₀) to 16 ε c |x| plus the Newton tolerance's far smaller share).
fn slip_round_off(file: &FrictionCase) -> f64 {
    16.0 * f64::EPSILON * file.blocks.extent()
}

/// Every gate of the case (module docs).
fn gates(file: &FrictionCase, runs: &[Run], report: &mut CaseReport) {
    let exact = file.blocks.exact();
    let limits = file.limits;
    for g in &file.gates {
        let of: Vec<&Run> = runs
            .iter()
            .filter(|r| r.scheme == g.select.scheme)
            .collect();
        let k: Vec<f64> = of.iter().map(|r| r.k).collect();
        let e: Vec<f64> = of.iter().map(|r| r.errors[&g.select.error]).collect();
        report.gates.push(g.criteria.evaluate(
            format!("{}: {} vs k", g.select.scheme.name(), g.select.error),
            &k,
            &e,
        ));
    }
    let round_off = slip_round_off(file);
    for &scheme in &file.sweep.schemes {
        let of: Vec<&Run> = runs.iter().filter(|r| r.scheme == scheme).collect();
        let name = scheme.name();
        let label = |r: &Run| format!("N = {}", r.steps);
        let mut stop = Vec::new();
        for r in &of {
            stop.push(Check::within(
                &format!(
                    "{}: last sliding step {} − the rigid scheme's {} (θ = {:.4})",
                    label(r),
                    r.last_sliding_step,
                    r.predicted.last_sliding_step,
                    r.predicted.phase
                ),
                r.errors["stop_step_offset"],
                0.0,
                0.0,
            ));
            stop.push(Check::at_most(
                &format!(
                    "{}: |t_s − t*| / k (≤ ½: the stop is within half a step)",
                    label(r)
                ),
                r.errors["stop_time_error"] * exact.stop_time() / r.k,
                0.5,
            ));
        }
        report.gates.push(GateVerdict::from_checks(
            format!("{name}: the stop step"),
            "exact",
            stop,
            "a midpoint-type step slides iff its mean relative velocity w(t_{n+1/2}) keeps the \
             sign of w₀; the first step with t_{n−1/2} ≥ t* sticks (exact/two_block_slide.rs); a \
             step slides when some interface node's |τ₁ − τ₀| exceeds a tenth of the rigid blocks' \
             smallest slide, a k² |θ − ½| / 10 (run.rs)",
        ));
        let mut slide = Vec::new();
        for r in &of {
            slide.push(Check::at_most(
                &format!(
                    "{}: |a_fit − a| / a, a = μ g (1 + m₁/m₂) = {}",
                    label(r),
                    exact.relative_deceleration()
                ),
                r.errors["deceleration_error"],
                limits.deceleration,
            ));
            slide.push(Check::at_most(
                &format!(
                    "{}: max drift of the momentum invariants I₁, I₂ / |w₀|",
                    label(r)
                ),
                r.errors["invariant_error"],
                limits.invariant,
            ));
            slide.push(Check::within(
                &format!(
                    "{}: steps before the stop with a sticking interface node",
                    label(r)
                ),
                r.errors["partial_slip_steps"],
                0.0,
                0.0,
            ));
        }
        report.gates.push(GateVerdict::from_checks(
            format!("{name}: the slide (deceleration, momentum invariants)"),
            "exact",
            slide,
            "a from the closed form; I₁ = v_x1 + σμ v_y1 + σμ g t and I₂ = v_x2 − σμ (m₁/m₂)(v_y1 \
             + g t) hold while every node slips (run.rs): Coulomb's law at its size, sign and \
             time level with the reaction on the master",
        ));
        let mut diss = Vec::new();
        for r in &of {
            diss.push(Check::at_most(
                &format!("{}: |D − μ Σ λ_N |slip|| / D*", label(r)),
                r.errors["dissipation_friction"],
                limits.friction_work,
            ));
            diss.push(Check::at_most(
                &format!(
                    "{}: |D − F |s(t_s)|| / D* (the scheme's rigid dissipation)",
                    label(r)
                ),
                r.errors["dissipation_discrete"],
                limits.dissipation,
            ));
        }
        report.gates.push(GateVerdict::from_checks(
            format!("{name}: the dissipated energy"),
            "exact",
            diss,
            "D = E₀ − E_N + gravity's work from the states; F |s(t_s)| = ½ m_r (w₀² − w(t_s)²) \
             (exact/two_block_slide.rs)",
        ));
        let mut stick = Vec::new();
        for r in &of {
            stick.push(Check::at_most(
                &format!(
                    "{}: max |τ₁ − τ₀| after the stop (≤ the threshold a k² |θ − ½| / 10)",
                    label(r)
                ),
                r.errors["slip_after_stop"],
                r.threshold,
            ));
            stick.push(Check::at_most(
                &format!("{}: the step from which no node is in slip (≤ N)", label(r)),
                r.errors["settled_step"],
                r.steps as f64,
            ));
            stick.push(Check::at_most(
                &format!("{}: max |τ₁ − τ₀| from then on (≤ 16 ε max|x|)", label(r)),
                r.errors["slip_after_settling"],
                round_off,
            ));
        }
        report.gates.push(GateVerdict::from_checks(
            format!("{name}: stick after the stop"),
            "exact",
            stick,
            "the rigid blocks stick for ever; the elastic ones let edge nodes slip by a few δ_s \
             (their deformation, far below a slide) while the alternating stick force settles (a \
             shakedown), then every node sticks to round-off",
        ));
        let claims = Claims::of(scheme, [true, false], file.blocks.material.is_objective());
        let audit = of
            .iter()
            .flat_map(|r| audit_checks(&label(r), &r.audit, claims))
            .collect();
        let state = of
            .iter()
            .flat_map(|r| state_audit_checks(&label(r), &r.state, claims))
            .collect();
        report.gates.push(state_audit_gate(
            &format!("{name}: state-recomputed audit"),
            state,
        ));
        report.gates.push(audit_gate(
            &format!("{name}: audit"),
            audit,
            "P_x: no horizontal external force (gravity vertical, the foundation frictionless); \
             friction's step work ≤ 0; the energy identity for the energy–momentum scheme",
        ));
    }
}
