//! `[plan.oracle]`: the planner's whole bill against an oracle's, over the whole box it searched
//! (docs/planner.md §4.3).
//!
//! For each target the planner runs as a user would run it — its pilots, its models, its choice
//! — once with the deterministic work as its cost and once with measured CPU seconds. The
//! oracle knows the answer: every (M, N) of a grid at ratio `ratio` over the box the planner
//! searched, M ∈ [M_min, X · M_max] and N ∈ [N_min, X · N_max] of its pilots (X the
//! extrapolation limit, [`EXTRAPOLATION`]), for every scheme (explicit steps above the stability
//! margin left out), is run and its error measured against the exact solution; the oracle's
//! cost is that of the cheapest grid point that meets the target. The oracle pays nothing for
//! finding it; the planner pays its pilots.
//!
//! Gates, per target:
//! - work: the choice's work W_c at most `max_cost_ratio` × the oracle's W_o (the price of
//!   aiming at 0.85 × target is (1/0.85)^(1/p + 1/q): 1.38 at p = q = 1, 1.28 at p = q = 2);
//! - work, pilots included: W_pilots + W_c at most `max_cost_ratio` × W_o + W_design, where
//!   W_design is the pilot design's work computed here from docs/planner.md §2 (the levels
//!   (M₀/4, M₀/2, M₀) × (N₀/4, N₀/2, N₀) of each round, every stable scheme) — a planner that
//!   runs more pilots than its design, or pays for them twice, fails it;
//! - aim: the achieved error over the target at most AIM × exp(3σ) (AIM = 0.85, σ the chosen
//!   scheme's error-model log residual at its pilots): a planner that chose for the target
//!   itself lands near 1 and fails it, where the [0.5, 1] band of `rod_plan` lets it pass;
//! - rounds: the pilot rounds run at most those the oracle's point needs — one when it lies in
//!   the first round's box, two otherwise ([`rounds_needed`]); a planner that picks a dearer
//!   scheme than its models' cheapest recovers its target through extra rounds, and fails here;
//! - CPU seconds (as a ratio): the seconds-mode choice's time at most `max_cost_ratio` × s × the
//!   oracle's fastest grid point's, the two timed in turn five times each (each side its min, the
//!   same moment's load on both), s ≥ 1 the larger of their spreads max/min — the timing's own
//!   resolution at that moment; the pilots' seconds (measured while planning) beside it.

use serde::Deserialize;

use crate::core::gate::{Check, GateVerdict};
use crate::core::plan::case::PlanSpec;
use crate::core::plan::choose::{AIM, EXTRAPOLATION, STABILITY_MARGIN};
use crate::core::plan::{
    pilot_levels, plan, CostMeasure, Decision, PlanRequest, PlanResult, Plannable,
};
use crate::core::report::case_report::{CaseReport, Table};

/// `[plan.oracle]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OracleSpec {
    /// The targets the bills are compared at (each runs the planner twice and the whole grid).
    pub targets: Vec<f64>,
    /// Consecutive M (and N) of the grid differ by this factor (> 1).
    pub ratio: f64,
    /// The price of aiming below the target, and of the model's fit (module docs).
    pub max_cost_ratio: f64,
}

/// A grid point the oracle ran.
struct Point {
    scheme: String,
    elements: usize,
    steps: usize,
    error: f64,
    work: f64,
}

/// Integers from `lo` to `hi` at ratio `ratio` (both ends included, repeats dropped).
fn geometric(lo: f64, hi: f64, ratio: f64) -> Vec<usize> {
    let mut out = Vec::new();
    let mut x = lo.max(1.0);
    while x <= hi * (1.0 + 1e-12) {
        let v = x.round() as usize;
        if out.last() != Some(&v) {
            out.push(v);
        }
        x *= ratio;
    }
    let top = hi.round() as usize;
    if out.last().is_some_and(|&v| v < top) {
        out.push(top);
    }
    out
}

/// The box the planner searched over all its rounds: from the coarsest pilot to X times the
/// finest, in M and in N — from the rounds' finest pilots and the pilot design
/// ([`pilot_levels`]), not from the pilots the planner reports.
fn searched_box(r: &PlanResult) -> ((f64, f64), (f64, f64)) {
    let levels: Vec<(usize, usize)> = r.rounds.iter().flat_map(|&b| pilot_levels(b)).collect();
    let lo_hi = |v: Vec<f64>| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(0.0, f64::max);
        (lo, EXTRAPOLATION * hi)
    };
    (
        lo_hi(levels.iter().map(|l| l.0 as f64).collect()),
        lo_hi(levels.iter().map(|l| l.1 as f64).collect()),
    )
}

/// The schemes of the request that are stable at `steps`, by name.
fn stable_schemes<P: Plannable>(p: &P, r: &PlanResult, steps: usize) -> Vec<P::Scheme> {
    p.schemes()
        .into_iter()
        .filter(|s| {
            r.request
                .schemes
                .as_ref()
                .is_none_or(|names| names.contains(&s.to_string()))
        })
        .filter(|&s| {
            let k = p.final_time() / steps as f64;
            p.stability_bound(s)
                .is_none_or(|b| k <= STABILITY_MARGIN * b)
        })
        .collect()
}

/// Every grid point of the searched box, run and measured.
fn grid<P: Plannable>(p: &P, r: &PlanResult, ratio: f64) -> Result<Vec<Point>, String> {
    use rayon::prelude::*;
    let ((m_lo, m_hi), (n_lo, n_hi)) = searched_box(r);
    let mut jobs = Vec::new();
    for n in geometric(n_lo, n_hi, ratio) {
        for s in stable_schemes(p, r, n) {
            for m in geometric(m_lo, m_hi, ratio) {
                jobs.push((s, m, n));
            }
        }
    }
    jobs.par_iter()
        .map(|&(s, m, n)| {
            let l = p.run_level(m, n, s, false)?;
            let error = *l
                .errors
                .get(&r.request.functional)
                .ok_or_else(|| format!("`{}` not measured", r.request.functional))?;
            Ok(Point {
                scheme: s.to_string(),
                elements: m,
                steps: n,
                error,
                work: p.work(m, n),
            })
        })
        .collect()
}

/// The pilot rounds a planner needs to reach the oracle's point `best`: one when it lies in the
/// box the first round's models are trusted over (its pilots' M and N up to X times the finest,
/// docs/planner.md §3), two otherwise — the second round's pilots are placed at half the point
/// the first round's models locate, which puts it inside their box. A further round is waste:
/// its pilots buy nothing the oracle needed.
fn rounds_needed(r: &PlanResult, best: &Point) -> usize {
    let Some(&first) = r.rounds.first() else {
        return 1;
    };
    let levels = pilot_levels(first);
    let inside = |v: usize, of: fn(&(usize, usize)) -> usize| {
        let lo = levels.iter().map(of).min().unwrap_or(1);
        let hi = levels.iter().map(of).max().unwrap_or(1) as f64 * EXTRAPOLATION;
        lo <= v && v as f64 <= hi
    };
    if inside(best.elements, |l| l.0) && inside(best.steps, |l| l.1) {
        1
    } else {
        2
    }
}

/// The pilot design's work for the rounds `r` ran (docs/planner.md §2), computed from the
/// rounds' finest pilots, not from the pilots the planner reports.
fn design_work<P: Plannable>(p: &P, r: &PlanResult) -> f64 {
    r.rounds
        .iter()
        .flat_map(|&base| pilot_levels(base))
        .map(|(m, n)| stable_schemes(p, r, n).len() as f64 * p.work(m, n))
        .sum()
}

/// The request of `spec` at `target` with `cost` as the planner's cost.
fn request(spec: &PlanSpec, target: f64, cost: CostMeasure) -> PlanRequest {
    PlanRequest {
        target,
        functional: spec.functional.clone(),
        schemes: spec.schemes.clone(),
        cost,
        rounds: spec.rounds,
    }
}

/// The choice (scheme, M, N) of a plan that chose; an error naming the decision otherwise.
fn choice_of(r: &PlanResult) -> Result<(String, usize, usize), String> {
    match &r.decision {
        Decision::Chosen { choice } | Decision::PilotMeets { choice } => {
            Ok((choice.scheme.clone(), choice.elements, choice.steps))
        }
        other => Err(format!(
            "target {:e}: the planner did not choose ({other:?})",
            r.request.target
        )),
    }
}

/// One target's bills: the checks and the table rows.
struct Bills {
    checks: Vec<Check>,
    row: Vec<String>,
}

/// The work bills of one target (plan in work, its box's grid, the design's pilots).
fn work_bills<P: Plannable>(
    p: &P,
    o: &OracleSpec,
    r: &PlanResult,
    points: &[Point],
) -> Result<(Bills, usize), String> {
    let t = r.request.target;
    let (scheme, m, n) = choice_of(r)?;
    let best = points
        .iter()
        .filter(|q| q.error <= t)
        .min_by(|a, b| a.work.total_cmp(&b.work))
        .ok_or_else(|| format!("target {t:e}: no grid point of the searched box meets it"))?;
    let w_choice = p.work(m, n);
    let w_pilots = r.pilots_cost;
    let w_design = design_work(p, r);
    let label = p.work_label();
    let mut checks = vec![
        Check::at_most(
            &format!(
                "target {t:.1e}: the choice's work {label} over the oracle's ({}, M = {}, N = {})",
                best.scheme, best.elements, best.steps
            ),
            w_choice / best.work,
            o.max_cost_ratio,
        ),
        Check::at_most(
            &format!(
                "target {t:.1e}: (pilots + choice) work over the oracle's, less the pilot design's {:.3e} / {:.3e}",
                w_design, best.work
            ),
            (w_pilots + w_choice - w_design) / best.work,
            o.max_cost_ratio,
        ),
    ];
    // the aim: the planner chooses for AIM × target, so its run lands there within its error
    // model's scatter at the pilots (3 σ of the log residual)
    let sigma = r
        .schemes
        .iter()
        .find(|x| x.scheme == scheme)
        .and_then(|x| x.error_model.as_ref())
        .map_or(f64::INFINITY, |e| e.residual_std());
    let achieved = r
        .executed
        .as_ref()
        .map(|x| x.achieved_error)
        .ok_or("a chosen plan without its run")?;
    checks.push(Check::at_most(
        &format!(
            "target {t:.1e}: achieved / target, against the aim {AIM} × exp(3 σ), σ = {sigma:.2e} the chosen scheme's log residual at its pilots"
        ),
        achieved / t,
        AIM * (3.0 * sigma).exp(),
    ));
    let needed = rounds_needed(r, best);
    checks.push(Check::at_most(
        &format!(
            "target {t:.1e}: pilot rounds run, against the rounds the oracle's point needs ({needed}: it lies {} the first round's box)",
            if needed == 1 { "inside" } else { "outside" }
        ),
        r.rounds.len() as f64,
        needed as f64,
    ));
    let row = vec![
        format!("{t:.1e}"),
        format!("{scheme}, {m} × {n}"),
        format!("{}, {} × {}", best.scheme, best.elements, best.steps),
        format!("{:.3}", w_choice / best.work),
        format!("{} ({needed})", r.rounds.len()),
        format!("{:.3e}", w_pilots),
        format!("{:.3}", (w_pilots + w_choice) / best.work),
    ];
    Ok((Bills { checks, row }, points.len()))
}

/// The seconds bills of one target: the planner in CPU-seconds mode against the fastest grid
/// point that meets the target, timed here.
fn seconds_bills<P: Plannable>(
    p: &P,
    o: &OracleSpec,
    r: &PlanResult,
    points: &[Point],
) -> Result<Bills, String> {
    let t = r.request.target;
    let (scheme, m, n) = choice_of(r)?;
    let by_name = |name: &str| p.schemes().into_iter().find(|s| s.to_string() == name);
    // the grid points that meet the target, timed one at a time (no other timing beside them)
    let mut fastest: Option<(f64, &Point)> = None;
    for q in points.iter().filter(|q| q.error <= t) {
        let s = by_name(&q.scheme).ok_or("a grid scheme vanished")?;
        let secs = p.seconds(q.elements, q.steps, s)?;
        if fastest.is_none_or(|(f, _)| secs < f) {
            fastest = Some((secs, q));
        }
    }
    let (_, best) = fastest.ok_or_else(|| format!("target {t:e}: no grid point meets it"))?;
    let s_best = by_name(&best.scheme).ok_or("a grid scheme vanished")?;
    let s_choice = by_name(&scheme).ok_or("the chosen scheme vanished")?;
    // the choice and the oracle's point timed in turn, five times each: both at the same
    // moment's load; each side's min, and the larger of their spreads max/min
    let (mut at_choice, mut at_best) = (Vec::with_capacity(5), Vec::with_capacity(5));
    for _ in 0..5 {
        at_choice.push(p.seconds(m, n, s_choice)?);
        at_best.push(p.seconds(best.elements, best.steps, s_best)?);
    }
    let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    let spread = (max(&at_choice) / min(&at_choice))
        .max(max(&at_best) / min(&at_best))
        .max(1.0);
    let (choice_secs, lo) = (min(&at_choice), min(&at_best));
    let pilots_secs = r.pilots_cost;
    let checks = vec![Check::at_most(
        &format!(
            "target {t:.1e}: the seconds-mode choice's CPU time over the oracle's fastest ({}, M = {}, N = {}; timing spread {spread:.3})",
            best.scheme, best.elements, best.steps
        ),
        choice_secs / lo,
        o.max_cost_ratio * spread,
    )];
    let row = vec![
        format!("{t:.1e}"),
        format!("{scheme}, {m} × {n}"),
        format!("{}, {} × {}", best.scheme, best.elements, best.steps),
        format!("{:.3}", choice_secs / lo),
        format!("{spread:.3}"),
        format!("{:.3}", (pilots_secs + choice_secs) / lo),
    ];
    Ok(Bills { checks, row })
}

/// Runs `[plan.oracle]` (module docs): two gates and two tables in `report`.
pub fn run<P: Plannable>(
    p: &P,
    spec: &PlanSpec,
    o: &OracleSpec,
    report: &mut CaseReport,
) -> Result<(), String> {
    let (mut work_checks, mut work_rows) = (Vec::new(), Vec::new());
    let (mut secs_checks, mut secs_rows) = (Vec::new(), Vec::new());
    let mut runs = 0;
    for &t in &o.targets {
        let r = plan(p, &request(spec, t, CostMeasure::Work))?;
        let points = grid(p, &r, o.ratio)?;
        let (b, n) = work_bills(p, o, &r, &points)?;
        runs += n;
        work_checks.extend(b.checks);
        work_rows.push(b.row);
        let rs = plan(p, &request(spec, t, CostMeasure::Seconds))?;
        let b = seconds_bills(p, o, &rs, &points)?;
        secs_checks.extend(b.checks);
        secs_rows.push(b.row);
    }
    let label = p.work_label();
    report.gates.push(GateVerdict::from_checks(
        "planner: its bill against the oracle's over the searched box (work)".into(),
        "ceiling",
        work_checks,
        "every grid point of the box the planner searched is run and measured against the exact solution; the oracle pays only its cheapest point that meets the target; the pilots' allowance is the design's work, computed from docs/planner.md §2",
    ));
    report.gates.push(GateVerdict::from_timing_checks(
        "planner: its bill against the oracle's over the searched box (CPU seconds)".into(),
        secs_checks,
        "the planner with measured CPU seconds as its cost against the fastest grid point that meets the target, timed here; the ceiling scales with the square of the timing's measured spread",
    ));
    let head = |cols: &[&str]| cols.iter().map(|s| s.to_string()).collect();
    report.tables.push(Table {
        title: format!(
            "The planner's bill in work {label} against the oracle's over the whole searched box ({runs} grid runs)"
        ),
        header: head(&[
            "target",
            "planner (scheme, M × N)",
            "oracle (scheme, M × N)",
            "choice / oracle",
            "rounds (needed)",
            "pilots' work",
            "(pilots + choice) / oracle",
        ]),
        rows: work_rows,
    });
    report.tables.push(Table {
        title: "The planner's bill in CPU seconds (its seconds mode) against the oracle's fastest point".into(),
        // every column but the target varies with the machine's timings (the seconds-mode
        // choice too): the headers say `timing`, the cells go to the report's varying part
        header: head(&[
            "target",
            "planner (scheme, M × N; timing)",
            "oracle (scheme, M × N; timing)",
            "choice / oracle (timing)",
            "timing spread",
            "(pilots + choice) / oracle (timing)",
        ]),
        rows: secs_rows,
    });
    Ok(())
}
