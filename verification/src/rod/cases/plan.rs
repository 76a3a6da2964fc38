//! `rod_plan`: the planner itself under test (docs/planner.md §4). For each target the planner
//! (`core::plan`, cost = the deterministic work M·N, with pilot rounds) chooses (M, N, scheme) and
//! runs it; the achieved error is measured against the exact solution, which the planner's
//! models never saw except through the pilots.
//!
//! Gates:
//! - the achieved error over the target in `[ratio_range]` for at least `min_fraction` of the
//!   targets, and never above `max_ratio`;
//! - with `[exhaustive]`: for each target at most `exhaustive.max_targets`, a grid of (M, N) at
//!   ratio `exhaustive.ratio` over each scheme's range around the choice, every run's achieved
//!   error measured: the cheapest grid point that meets the target costs at least
//!   1 / `max_cost_ratio` of the planner's choice;
//! - a target below float64's floor is refused with the floor (`floor_target`); a target the
//!   coarsest pilots meet is answered by a pilot in one round, with no extrapolation
//!   (`loose_target`).

use rayon::prelude::*;
use serde::Deserialize;

use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::plan::{
    plan, CostMeasure, Decision, PlanRequest, PlanResult, Plannable, PLAN_TABLE_COLUMNS,
};
use crate::core::report::case_report::{CaseReport, Table};
use crate::core::study::Study;
use crate::rod::plan::RodPlan;
use crate::rod::study::{Discretization, ExactSpec, RodStudy};

/// The case body of `rod_plan`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanCase {
    pub scene: toml::Table,
    pub exact: ExactSpec,
    pub plan: PlanSpec,
}

/// `[plan]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSpec {
    pub functional: String,
    /// The first round's finest pilot (M₀, N₀).
    pub base: [usize; 2],
    pub rounds: usize,
    pub targets: Vec<f64>,
    /// Gate: achieved / target in this range for at least `min_fraction` of the targets.
    pub ratio_range: [f64; 2],
    pub min_fraction: f64,
    /// Gate: achieved / target never above this.
    pub max_ratio: f64,
    pub exhaustive: Option<ExhaustiveSpec>,
    /// A target below float64's floor (must be refused with the floor).
    pub floor_target: Option<f64>,
    /// A target the coarsest pilots meet (must be answered by a pilot).
    pub loose_target: Option<f64>,
}

/// `[plan.exhaustive]`: the grid search the choice is compared with.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExhaustiveSpec {
    /// Consecutive M (and N) of the grid differ by this factor (> 1).
    pub ratio: f64,
    /// The grid spans [choice / span, choice × span] in M and in N, per scheme.
    pub span: f64,
    /// Gate: the choice's work over the grid's cheapest that meets the target.
    pub max_cost_ratio: f64,
    /// Only the first this many targets (the grid runs are the cost).
    pub max_targets: usize,
}

impl PlanCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: PlanCase = case.body()?;
        let p = case.path();
        let bad = |field: &str, value: String, expected: &str| {
            Err(crate::core::format::invalid(p, field, value, expected))
        };
        if c.plan.targets.is_empty() || c.plan.targets.iter().any(|t| !(*t > 0.0 && t.is_finite()))
        {
            return bad(
                "plan.targets",
                format!("{:?}", c.plan.targets),
                "positive errors",
            );
        }
        if c.plan.base.contains(&0) {
            return bad("plan.base", format!("{:?}", c.plan.base), "M₀, N₀ ≥ 1");
        }
        if c.plan.rounds == 0 {
            return bad("plan.rounds", "0".into(), "≥ 1");
        }
        let [lo, hi] = c.plan.ratio_range;
        if !(0.0 < lo && lo < hi) {
            return bad(
                "plan.ratio_range",
                format!("{:?}", c.plan.ratio_range),
                "0 < lo < hi",
            );
        }
        if let Some(e) = &c.plan.exhaustive {
            if !(e.ratio > 1.0 && e.span > 1.0 && e.max_cost_ratio >= 1.0) {
                return bad(
                    "plan.exhaustive",
                    format!(
                        "ratio {}, span {}, max_cost_ratio {}",
                        e.ratio, e.span, e.max_cost_ratio
                    ),
                    "ratio > 1, span > 1, max_cost_ratio ≥ 1",
                );
            }
        }
        Ok(c)
    }
}

fn request(spec: &PlanSpec, target: f64) -> PlanRequest {
    PlanRequest {
        target,
        functional: spec.functional.clone(),
        schemes: None,
        cost: CostMeasure::Work,
        rounds: spec.rounds,
    }
}

fn geometric(lo: f64, hi: f64, ratio: f64) -> Vec<usize> {
    let mut out = Vec::new();
    let mut x = lo.max(1.0);
    while x <= hi {
        let v = x.round() as usize;
        if out.last() != Some(&v) {
            out.push(v);
        }
        x *= ratio;
    }
    out
}

/// The cheapest grid point (work M·N) meeting `target`, each scheme's grid spanning the choice's
/// (M, N) by `span` either way; returns (scheme, M, N, error) or None.
fn exhaustive(
    p: &RodPlan,
    r: &PlanResult,
    e: &ExhaustiveSpec,
) -> Result<Option<(String, usize, usize, f64)>, String> {
    let (Decision::Chosen { choice } | Decision::PilotMeets { choice }) = &r.decision else {
        return Ok(None);
    };
    let (m, n) = (choice.elements as f64, choice.steps as f64);
    let ms = geometric(m / e.span, m * e.span, e.ratio);
    let ns = geometric(n / e.span, n * e.span, e.ratio);
    let mut jobs = Vec::new();
    for s in TimeScheme::ALL {
        let bound = p.stability_bound(s);
        for &mi in &ms {
            for &ni in &ns {
                let k = p.final_time() / ni as f64;
                if bound.is_none_or(|b| k <= crate::core::plan::choose::STABILITY_MARGIN * b) {
                    jobs.push((s, mi, ni));
                }
            }
        }
    }
    let errors: Vec<Result<f64, String>> = jobs
        .par_iter()
        .map(|&(s, mi, ni)| {
            let l = p.run_level(mi, ni, s, false)?;
            l.errors
                .get(&r.request.functional)
                .copied()
                .ok_or_else(|| format!("`{}` not measured", r.request.functional))
        })
        .collect();
    let mut best: Option<(String, usize, usize, f64)> = None;
    for ((s, mi, ni), err) in jobs.into_iter().zip(errors) {
        let err = err?;
        if err <= r.request.target && best.as_ref().is_none_or(|b| (mi * ni) < b.1 * b.2) {
            best = Some((s.to_string(), mi, ni, err));
        }
    }
    Ok(best)
}

/// Runs the case.
pub fn run(case: &Case, _ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = PlanCase::parse(case).map_err(|e| e.to_string())?;
    let spec = &c.plan;
    let study = RodStudy::new(Some(&c.scene), Some(&c.exact), &Discretization::default())
        .map_err(|e| e.to_string())?;
    let p = RodPlan {
        study,
        base: (spec.base[0], spec.base[1]),
    };
    let mut rows = Vec::new();
    let mut in_range = 0usize;
    let mut worst: f64 = 0.0;
    let mut cost_checks = Vec::new();
    let mut grid_rows = Vec::new();
    for (i, &t) in spec.targets.iter().enumerate() {
        let r = plan(&p, &request(spec, t))?;
        let (what, choice) = match &r.decision {
            Decision::Chosen { choice } => ("chosen", choice),
            Decision::PilotMeets { choice } => ("pilot", choice),
            other => return Err(format!("target {t:e}: the planner refused ({other:?})")),
        };
        let (m, n, scheme, predicted) = (
            choice.elements,
            choice.steps,
            choice.scheme.clone(),
            choice.predicted_error,
        );
        let x = r.executed.as_ref().ok_or("a chosen plan without its run")?;
        let ratio = x.error_ratio;
        if spec.ratio_range[0] <= ratio && ratio <= spec.ratio_range[1] {
            in_range += 1;
        }
        worst = worst.max(ratio);
        rows.push(vec![
            format!("{t:.1e}"),
            what.to_string(),
            r.rounds.len().to_string(),
            scheme.clone(),
            m.to_string(),
            n.to_string(),
            format!("{predicted:.3e}"),
            format!("{:.3e}", x.achieved_error),
            format!("{ratio:.3}"),
            format!("{:.3e}", x.measured_cost),
        ]);
        if let Some(e) = spec.exhaustive.as_ref().filter(|e| i < e.max_targets) {
            match exhaustive(&p, &r, e)? {
                Some((gs, gm, gn, ge)) => {
                    let ratio = (m * n) as f64 / (gm * gn) as f64;
                    cost_checks.push(Check::at_most(
                        &format!("target {t:.1e}: the choice's work M·N over the grid's cheapest that meets it ({gs}, M = {gm}, N = {gn})"),
                        ratio,
                        e.max_cost_ratio,
                    ));
                    grid_rows.push(vec![
                        format!("{t:.1e}"),
                        format!("{scheme}, {m} × {n}"),
                        format!("{gs}, {gm} × {gn}"),
                        format!("{ge:.3e}"),
                        format!("{ratio:.3}"),
                    ]);
                }
                None => cost_checks.push(Check::holds(
                    &format!("target {t:.1e}: a grid point meets it"),
                    false,
                    "found",
                )),
            }
        }
    }
    let n = spec.targets.len() as f64;
    report.gates.push(GateVerdict::from_checks(
        "planner: achieved error against the target".into(),
        "ceiling",
        vec![
            Check::at_least(
                &format!(
                    "fraction of the {} targets with achieved / target in [{}, {}]",
                    spec.targets.len(),
                    spec.ratio_range[0],
                    spec.ratio_range[1]
                ),
                in_range as f64 / n,
                spec.min_fraction,
            ),
            Check::at_most("max over the targets of achieved / target", worst, spec.max_ratio),
        ],
        "the achieved error is measured against the exact solution; the planner aims at 0.85 × target (docs/planner.md §3)",
    ));
    report.tables.push(Table {
        title: format!(
            "The planner on {} targets (cost = work M·N)",
            spec.targets.len()
        ),
        header: PLAN_TABLE_COLUMNS.iter().map(|s| s.to_string()).collect(),
        rows,
    });
    if !cost_checks.is_empty() {
        report.gates.push(GateVerdict::from_checks(
            "planner: cost against an exhaustive grid search".into(),
            "ceiling",
            cost_checks,
            "the grid's runs are measured, not predicted: the cheapest that meets the target is the planner's benchmark",
        ));
        report.tables.push(Table {
            title: "Exhaustive grid search: the cheapest grid point that meets each target".into(),
            header: [
                "target",
                "planner (scheme, M × N)",
                "grid (scheme, M × N)",
                "grid error",
                "work ratio",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect(),
            rows: grid_rows,
        });
    }
    // the extremes
    let mut checks = Vec::new();
    if let Some(t) = spec.floor_target {
        let r = plan(&p, &request(spec, t))?;
        let floor = match r.decision {
            Decision::BelowFloor { floor } => floor,
            _ => f64::NAN,
        };
        checks.push(Check::holds(
            &format!("target {t:e} is refused below float64's floor (floor ≈ {floor:.2e})"),
            floor.is_finite() && t < floor,
            "refused with the floor",
        ));
    }
    if let Some(t) = spec.loose_target {
        // one round: the first pilots already meet it (with more rounds the planner may pilot
        // coarser still, where the models put the optimum)
        let r = plan(
            &p,
            &PlanRequest {
                rounds: 1,
                ..request(spec, t)
            },
        )?;
        checks.push(Check::holds(
            &format!(
                "target {t:e}: answered by a pilot, nothing extrapolated ({:?})",
                r.decision
            ),
            matches!(r.decision, Decision::PilotMeets { .. })
                && r.executed.as_ref().is_some_and(|x| x.achieved_error <= t),
            "a pilot meets it",
        ));
    }
    if !checks.is_empty() {
        report.gates.push(GateVerdict::from_checks(
            "planner: extremes".into(),
            "structure",
            checks,
            "a target float64 cannot reach is refused with the floor; a loose target is met by a pilot",
        ));
    }
    Ok(())
}
