//! Case kind `dynamic_friction`: Coulomb friction measured in size (`docs/dynamic.md` §6), in two
//! settings, for every `[[family]]` (a friction law of BDS (1.13) with a normal treatment):
//!
//! - `[slide]`, the block that reduces to one dimension
//!   ([`crate::exact::sliding_block::SlidingBlock`]): a stiff block squeezed into the foundation
//!   under frictionless rollers and launched along x decelerates at μ(η) N/m, stops at t*, s* and
//!   sticks. Each level (N steps to T = duration × t*) measures the stop time, the stop distance
//!   and the velocity after the stop against the closed form (rate gates in k, `[[gate]]`), and is
//!   gated automatically on the stop step of the midpoint rule on the rigid block (exactly the
//!   predicted step), on the stick after the stop (slip ≤ 2 δ_s, twice the block's shear lag,
//!   the elastic deformation a stop can release) and on the energy audit.
//! - `[loaded]`, a free block pressed by a pressure p and launched along x: it rocks and shears,
//!   its penetration varies along the bottom and in time. Each run (full solver path, default
//!   Newton tolerance) checks every step's equations with the laws written in the verification
//!   crate ([`residual`]) — each sliding node's friction −μ(p_n) N sign(slip), each sticking
//!   node's reaction within μ(p_n) N — and, for a constant μ, the momentum invariant
//!   P_x + μ P_y = P_x(0) − μ p L t of [`crate::exact::loaded_block`] while every node slides
//!   forward; the nodes must slide forward at least until half the rigid-limit stop time (the
//!   rocking and shear velocities are far below v0/2), and the energy audit holds.
//!
//! Why both: the sliding block has a closed form for the whole motion (rates in k, the stick/slip
//! transition), but its penetration is one number; the loaded block has no closed form for its
//! motion, but it exercises μ(η) over a range of penetrations that crosses the layer depth, on a
//! deforming body, at the time level and with the sign the discrete law (1.38) prescribes.

pub mod block;
pub mod format;
pub mod loaded;
pub mod report;
pub mod residual;
pub mod slide;

use rayon::prelude::*;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::dynamic::cases::friction::format::{FrictionCase, SlideSpec};
use crate::dynamic::cases::friction::loaded::LoadedRun;
use crate::dynamic::cases::friction::slide::SlideRun;
use crate::dynamic::study::audit_checks;
use contactlab::model::dynamic::record::Conserving;

/// The audit gates of the friction runs: the dissipative signs only. The identities (1.48) and
/// (1.49) are gated at 1e−12 E_ref per step elsewhere, a ceiling that presumes the Newton
/// residual's work dᵀR below it; on a sliding block it is τ Σ_i |d_i| s ≈ 4–8 × 1e−12 E_ref
/// (every row's increment carries the momentum term of size s), so the loaded block's steps are
/// checked row by row instead (residual.rs), which implies (1.48) within those allowances.
const SIGNS_ONLY: Conserving = Conserving {
    balance: false,
    contact: false,
    compliance: true,
};

const AUDIT_NOTE: &str = "friction work ≤ 0 every step (W_τ = Σ T_i d_i with T_i against the \
                          slip); the identities are implied by the loaded block's row check";

/// Checks the case's format.
pub fn check(case: &Case) -> Result<(), CaseError> {
    FrictionCase::from_case(case).map(|_| ())
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let file = FrictionCase::from_case(case).map_err(|e| e.to_string())?;
    let id = case.header.id.as_str();
    let slide_runs = match &file.slide {
        Some(spec) => {
            let jobs: Vec<(usize, usize)> = spec
                .runs(&file.families)
                .iter()
                .flat_map(|f| {
                    let i = file.families.iter().position(|g| g.name == f.name);
                    spec.steps.iter().map(move |&n| (i.unwrap_or(0), n))
                })
                .collect();
            let bar = ctx.progress_bar(jobs.len() as u64, id);
            let runs = jobs
                .par_iter()
                .map(|&(f, n)| {
                    let r = slide::run(spec, &file.families[f], n);
                    bar.inc(1);
                    r
                })
                .collect::<Result<Vec<_>, _>>()?;
            bar.finish_and_clear();
            slide_gates(&file, spec, &runs, report);
            runs
        }
        None => Vec::new(),
    };
    let loaded_runs = match &file.loaded {
        Some(spec) => {
            let jobs: Vec<(usize, usize)> = spec
                .runs(&file.families)
                .iter()
                .flat_map(|f| {
                    let i = file.families.iter().position(|g| g.name == f.name);
                    spec.steps.iter().map(move |&n| (i.unwrap_or(0), n))
                })
                .collect();
            let runs = jobs
                .par_iter()
                .map(|&(f, n)| loaded::run(spec, &file.families[f], n))
                .collect::<Result<Vec<_>, _>>()?;
            loaded_gates(&runs, report);
            runs
        }
        None => Vec::new(),
    };
    report::tables(&file, &slide_runs, &loaded_runs, report);
    report::plots(&file, ctx, report, &slide_runs, &loaded_runs)?;
    ctx.write_data(
        report,
        &serde_json::json!({ "slide": slide_runs, "loaded": loaded_runs }),
    )
}

/// The sliding block's gates: the `[[gate]]`s, and per family the stop step, the stick after
/// the stop and the audit.
fn slide_gates(file: &FrictionCase, spec: &SlideSpec, runs: &[SlideRun], report: &mut CaseReport) {
    for g in &file.gates {
        let sel = &g.select;
        let Some(family) = file.families.iter().find(|f| f.name == sel.family) else {
            continue;
        };
        let exact = spec.block(family);
        let of: Vec<&SlideRun> = runs.iter().filter(|r| r.family == sel.family).collect();
        let k: Vec<f64> = of.iter().map(|r| r.k).collect();
        let e: Vec<f64> = of.iter().map(|r| r.errors[&sel.error]).collect();
        // the stop distance cannot resolve the block's shear lag δ_s (the rigid model's error)
        let floor = if sel.error == "stop_distance_error" {
            exact.shear_lag() / exact.stop_distance()
        } else {
            0.0
        };
        report.gates.push(g.criteria.evaluate_with_floor(
            format!("slide/{}: {} vs k", sel.family, sel.error),
            &k,
            &e,
            floor,
        ));
    }
    for f in spec.runs(&file.families) {
        let exact = spec.block(f);
        let of: Vec<&SlideRun> = runs.iter().filter(|r| r.family == f.name).collect();
        let stop: Vec<Check> = of
            .iter()
            .map(|r| {
                Check::within(
                    &format!(
                        "N = {}: last sliding step {} − the rigid midpoint rule's {}",
                        r.steps, r.last_sliding_step, r.predicted.last_sliding_step
                    ),
                    r.errors["stop_step_offset"],
                    0.0,
                    0.0,
                )
            })
            .collect();
        report.gates.push(GateVerdict::from_checks(
            format!("slide/{}: the stop step", f.name),
            "exact",
            stop,
            "the midpoint rule with the backward-difference slip rate stops the rigid block at \
             the first step whose midpoint reaches t* (exact/sliding_block.rs)",
        ));
        let lag = 2.0 * exact.shear_lag();
        let stick: Vec<Check> = of
            .iter()
            .map(|r| {
                Check::at_most(
                    &format!("N = {}: max slip after the stop", r.steps),
                    r.errors["slip_after_stop"],
                    lag,
                )
            })
            .collect();
        report.gates.push(GateVerdict::from_checks(
            format!("slide/{}: stick after the stop", f.name),
            "exact",
            stick,
            "rigid: no slip after the stop; the elastic block can release at most its \
             deformation, 2 δ_s (twice the quasi-static shear lag, for a suddenly applied \
             friction)",
        ));
        let audit = of
            .iter()
            .flat_map(|r| audit_checks(&format!("N = {}", r.steps), &r.audit, SIGNS_ONLY))
            .collect();
        report.gates.push(GateVerdict::from_checks(
            format!("slide/{}: energy audit", f.name),
            "energy audit",
            audit,
            AUDIT_NOTE,
        ));
    }
}

/// The loaded block's gates per run: the step equations, the invariant (constant μ), the slide
/// window and the audit.
fn loaded_gates(runs: &[LoadedRun], report: &mut CaseReport) {
    for r in runs {
        let label = format!("loaded/{} (N = {})", r.family, r.steps);
        let mut checks = vec![Check::at_most(
            "max over steps and rows of |R_i| / (τ s + 64 ε A_i)",
            r.max_residual,
            1.0,
        )];
        if let Some(e) = r.max_stick_excess {
            checks.push(Check::at_most(
                "max over steps and sticking nodes of (|T| − μ(p) N) w / (64 ε A_i)",
                e,
                1.0,
            ));
        }
        report.gates.push(GateVerdict::from_checks(
            format!("{label}: each step's equations with the reference laws"),
            "exact",
            checks,
            "BDS (1.36) with N of (1.8)/(1.46), μ of (1.13), the friction at t_n against the \
             backward-difference slip (1.38): each row within the Newton tolerance τ s plus the \
             round-off 64 ε A_i of its terms (residual.rs)",
        ));
        let mut checks = vec![Check::at_least(
            "every node slides forward until (t)",
            r.all_slide_until,
            0.5 * r.rigid_stop_time,
        )];
        if let Some(ratio) = r.invariant_ratio {
            checks.push(Check::at_most(
                "max_n |J_n − J(t_n)| / its allowance at step n",
                ratio,
                1.0,
            ));
        }
        report.gates.push(GateVerdict::from_checks(
            format!("{label}: the slide and the momentum invariant"),
            "exact",
            checks,
            "J = P_x + μ P_y = P_x(0) − μ p L t while every node slides forward (constant μ; \
             exact/loaded_block.rs); the slide lasts at least half the rigid-limit stop time",
        ));
        report.gates.push(GateVerdict::from_checks(
            format!("{label}: energy audit"),
            "energy audit",
            audit_checks(&label, &r.audit, SIGNS_ONLY),
            AUDIT_NOTE,
        ));
    }
}

#[cfg(test)]
mod tests;
