//! `dynamic_impact`: the impact tests of Barboteu–Danan–Sofonea §1.7 — a body thrown at the
//! foundation {x2 ≤ level}, run with several schemes and contact treatments, and a
//! self-convergence study (grid convergence index) of the quantities an experiment would report.
//!
//! Per run: the energy history and the per-step identity residuals (BDS Prop. 1.1 (1.48),
//! Prop. 1.3 (1.49), HLT Prop. 3.7), the total normal force Σ w N, the largest penetration
//! against the layer depth g, the centre-of-mass velocity (total momentum / total mass), and the
//! summary: contact interval (interpolated where max p changes sign), rebound velocity,
//! coefficient of restitution, energy change split into friction work W_τ and stage-(b) work D_b,
//! Newton iterations and cost per step. Deformed snapshots of the first run.
//!
//! Gates:
//! - energy audit (shared `audit_checks`): the identities at round-off for the conserving
//!   combinations (Gonzalez, or the midpoint rule with a linear law; (1.49) and HLT 3.7 with an
//!   energy-consistent or limited-penetration force); friction work and stage-(b) work ≤ 0 for all;
//! - energy over the run: (E + Φ)_N − (E + Φ)_0 = W_τ + D_b to N × round-off for those; a
//!   frictionless limited-penetration run loses at most `max_stage_b_loss` (stage (b) only
//!   dissipates, BDS §1.6.3);
//! - penetration: ≤ g (limited penetration) and ≤ round-off (Signorini); the plain penalty and the
//!   unlimited energy-consistent force exceed g (the limit is the method's doing);
//! - momentum: constant in flight (Σ F_int = 0 by translation invariance) to `momentum_tolerance`;
//! - every run separates before T (rebound and contact duration defined);
//! - self-convergence: GCI of the finest pair below a percentage, and the asymptotic ratio of
//!   [`crate::stats::gci`] within a tolerance (four levels or more).

pub mod format;
pub mod gci_report;
pub mod plots;
pub mod report;
pub mod runs;

use rayon::prelude::*;

use crate::core::case::Case;
use crate::core::format::CaseError;

use crate::core::context::RunContext;
use crate::core::report::case_report::CaseReport;
use crate::dynamic::cases::impact::format::{scene_file, ImpactCase, ImpactRun};
use crate::dynamic::cases::impact::report::{run_data, CaseData};
use runs::{run_job, Job, RunOutput};

/// Checks the case's format.
pub fn check(case: &Case) -> Result<(), CaseError> {
    case.body::<ImpactCase>()?.check(&case.path)
}

/// Every distinct job of the case: the runs first (in order), then the GCI levels not already
/// among them.
pub(crate) fn all_jobs(c: &ImpactCase) -> Vec<Job> {
    let mut jobs: Vec<Job> = c
        .runs
        .iter()
        .enumerate()
        .map(|(i, r)| c.job(r, i == 0))
        .collect();
    for g in &c.gci {
        if let Some(run) = c.run_by_label(&g.run) {
            for &f in &g.refinements {
                let job = Job {
                    factor: f,
                    snapshots: false,
                    ..c.job(run, false)
                };
                if !jobs.iter().any(|j| same_run(j, &job)) {
                    jobs.push(job);
                }
            }
        }
    }
    jobs
}

/// Two jobs that compute the same thing (snapshots aside).
pub(crate) fn same_run(a: &Job, b: &Job) -> bool {
    a.scheme == b.scheme && a.treatment == b.treatment && a.factor == b.factor && a.steps == b.steps
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c: ImpactCase = case.body().map_err(|e| e.to_string())?;
    c.check(&case.path).map_err(|e| e.to_string())?;
    let (_, source) = scene_file(&case.path, &c.scene)?;
    let jobs = all_jobs(&c);
    let bar = ctx.progress_bar(jobs.len() as u64, &case.header.id);
    let outputs: Vec<Result<RunOutput, String>> = jobs
        .par_iter()
        .map(|job| {
            let out = run_job(&source, job, &c.snapshot_times);
            bar.inc(1);
            out
        })
        .collect();
    bar.finish_and_clear();
    let find = |job: &Job| {
        jobs.iter()
            .position(|j| same_run(j, job))
            .map(|i| &outputs[i])
    };
    let runs: Vec<(String, &ImpactRun, &Result<RunOutput, String>)> = c
        .runs
        .iter()
        .enumerate()
        .filter_map(|(i, r)| find(&c.job(r, i == 0)).map(|o| (r.label(), r, o)))
        .collect();
    let ctx_data = CaseData {
        id: &case.header.id,
        case: &c,
        file: &source.file,
    };
    ctx_data.run_gates(report, &runs);
    ctx_data.run_outputs(ctx, report, &runs)?;
    for g in &c.gci {
        let Some(run) = c.run_by_label(&g.run) else {
            continue;
        };
        let levels: Vec<&Result<RunOutput, String>> = g
            .refinements
            .iter()
            .filter_map(|&f| {
                find(&Job {
                    factor: f,
                    snapshots: false,
                    ..c.job(run, false)
                })
            })
            .collect();
        ctx_data.gci_study(ctx, report, g, &levels)?;
    }
    ctx.write_data(report, &run_data(&jobs, &outputs))
}
