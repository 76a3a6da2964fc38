//! The planner under test (docs/planner.md §4), for any family's [`Plannable`]: the case body
//! `[plan]` and its runner, shared by `rod_plan` and `plane_plan`.
//!
//! For each target the planner (cost = the family's deterministic work, with pilot rounds)
//! chooses (M, N, scheme) and runs it; the achieved error is measured against the exact
//! solution, which the planner's models never saw except through the pilots.
//!
//! Gates:
//! - the achieved error over the target in `ratio_range` for at least `min_fraction` of the
//!   targets, and never above `max_ratio`;
//! - with `[plan.exhaustive]`: for each of the first `max_targets` targets, a grid of (M, N) at
//!   ratio `ratio` spanning the choice by `span` either way, for every scheme, each run's error
//!   measured: the cheapest grid point that meets the target costs at least 1 / `max_cost_ratio`
//!   of the planner's choice;
//! - a target below float64's floor is refused with the floor (`floor_target`); a target the
//!   first pilots meet is answered by a pilot in one round, with no extrapolation
//!   (`loose_target`).

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Mutex;

use rayon::prelude::*;
use serde::Deserialize;

use crate::core::context::RunContext;
use crate::core::format::{invalid, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::plan::choose::STABILITY_MARGIN;
use crate::core::plan::{
    formal_order, plan, plan_with_base, CostMeasure, Decision, PlanRequest, PlanResult, Plannable,
    PLAN_TABLE_COLUMNS,
};
use crate::core::report::case_report::{CaseReport, Table};
use crate::core::study::Study;
use crate::core::sweep::Level;
use crate::plot::{Figure, Series};

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
    /// A target the first pilots meet (must be answered by a pilot).
    pub loose_target: Option<f64>,
    /// The schemes to choose among (default: all of the family's).
    pub schemes: Option<Vec<String>>,
    /// A first round whose pilots are pre-asymptotic (must be refused as such, one round).
    pub pre_asymptotic: Option<PreAsymptoticSpec>,
    /// A first round whose pilots look asymptotic but are not where the choice lies: the chosen
    /// run must contradict the model (one round: the decision `missed`).
    pub missed: Option<PreAsymptoticSpec>,
    /// The planner's whole bill against an oracle's over the box it searched
    /// ([`crate::core::plan::oracle`]).
    pub oracle: Option<crate::core::plan::oracle::OracleSpec>,
}

/// `[plan.pre_asymptotic]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PreAsymptoticSpec {
    pub target: f64,
    /// The finest pilot (M₀, N₀) of that round.
    pub base: [usize; 2],
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

impl PlanSpec {
    /// Checks the values of `[plan]` of the case file at `path`, naming the wrong field.
    pub fn check(&self, path: &Path) -> Result<(), CaseError> {
        let bad =
            |field: &str, value: String, expected: &str| Err(invalid(path, field, value, expected));
        if self.targets.is_empty() || self.targets.iter().any(|t| !(*t > 0.0 && t.is_finite())) {
            return bad(
                "plan.targets",
                format!("{:?}", self.targets),
                "positive errors",
            );
        }
        if self.base.contains(&0) {
            return bad("plan.base", format!("{:?}", self.base), "M₀, N₀ ≥ 1");
        }
        if self.rounds == 0 {
            return bad("plan.rounds", "0".into(), "≥ 1");
        }
        let [lo, hi] = self.ratio_range;
        if !(0.0 < lo && lo < hi) {
            return bad(
                "plan.ratio_range",
                format!("{:?}", self.ratio_range),
                "0 < lo < hi",
            );
        }
        if !(0.0..=1.0).contains(&self.min_fraction) {
            return bad(
                "plan.min_fraction",
                self.min_fraction.to_string(),
                "a fraction in [0, 1]",
            );
        }
        if let Some(e) = &self.exhaustive {
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
        if let Some(o) = &self.oracle {
            if o.targets.is_empty()
                || o.targets.iter().any(|t| !(*t > 0.0 && t.is_finite()))
                || !(o.ratio > 1.0 && o.max_cost_ratio >= 1.0)
            {
                return bad(
                    "plan.oracle",
                    format!(
                        "targets {:?}, ratio {}, max_cost_ratio {}",
                        o.targets, o.ratio, o.max_cost_ratio
                    ),
                    "positive targets, ratio > 1, max_cost_ratio ≥ 1",
                );
            }
        }
        Ok(())
    }

    /// [`Self::check`], and for a plan by self-convergence: a functional among `functionals`
    /// (the values the family records) and no grid search (it needs an exact solution).
    pub fn check_self(&self, path: &Path, functionals: &[&str]) -> Result<(), CaseError> {
        self.check(path)?;
        if !functionals.contains(&self.functional.as_str()) {
            return Err(invalid(
                path,
                "plan.functional",
                &self.functional,
                &functionals.join(", "),
            ));
        }
        let grid = [
            ("plan.exhaustive", self.exhaustive.is_some()),
            ("plan.oracle", self.oracle.is_some()),
        ];
        if let Some((key, _)) = grid.iter().find(|(_, set)| *set) {
            return Err(invalid(
                path,
                key,
                "(set)",
                "no grid search without an exact solution",
            ));
        }
        Ok(())
    }

    fn request(&self, target: f64) -> PlanRequest {
        PlanRequest {
            target,
            functional: self.functional.clone(),
            schemes: self.schemes.clone(),
            cost: CostMeasure::Work,
            rounds: self.rounds,
        }
    }
}

/// A [`Plannable`] whose runs are kept: the targets of a case share their pilots (the same
/// (M, N, scheme) gives the same bits, so a kept run is the run), and a reference run of one
/// target may be another's pilot.
struct Kept<'a, P: Plannable> {
    inner: &'a P,
    runs: Mutex<BTreeMap<(usize, usize, String), Level>>,
}

impl<'a, P: Plannable> Kept<'a, P> {
    fn new(inner: &'a P) -> Self {
        Self {
            inner,
            runs: Mutex::new(BTreeMap::new()),
        }
    }
}

impl<P: Plannable> Study for Kept<'_, P> {
    type Scheme = P::Scheme;

    fn default_scheme(&self) -> P::Scheme {
        self.inner.default_scheme()
    }

    fn run_level(
        &self,
        elements: usize,
        steps: usize,
        scheme: P::Scheme,
        time_error: bool,
    ) -> Result<Level, String> {
        let key = (elements, steps, scheme.to_string());
        let kept = |runs: &Mutex<BTreeMap<_, Level>>| {
            runs.lock()
                .map_err(|_| "a planner run panicked".to_string())
                .map(|r| r.get(&key).cloned())
        };
        if let Some(l) = kept(&self.runs)? {
            return Ok(l);
        }
        let l = self.inner.run_level(elements, steps, scheme, time_error)?;
        self.runs
            .lock()
            .map_err(|_| "a planner run panicked".to_string())?
            .insert(key, l.clone());
        Ok(l)
    }
}

impl<P: Plannable> Plannable for Kept<'_, P> {
    fn base(&self) -> (usize, usize) {
        self.inner.base()
    }
    fn final_time(&self) -> f64 {
        self.inner.final_time()
    }
    fn schemes(&self) -> Vec<P::Scheme> {
        self.inner.schemes()
    }
    fn stability_bound(&self, scheme: P::Scheme) -> Option<f64> {
        self.inner.stability_bound(scheme)
    }
    fn expected_orders(&self, scheme: P::Scheme, functional: &str) -> (Option<f64>, Option<f64>) {
        self.inner.expected_orders(scheme, functional)
    }
    fn floor(&self, functional: &str, pilots: &[Level]) -> f64 {
        self.inner.floor(functional, pilots)
    }
    fn seconds(&self, elements: usize, steps: usize, scheme: P::Scheme) -> Result<f64, String> {
        self.inner.seconds(elements, steps, scheme)
    }
    fn work(&self, elements: usize, steps: usize) -> f64 {
        self.inner.work(elements, steps)
    }
    fn work_label(&self) -> &'static str {
        self.inner.work_label()
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

/// A grid point of the exhaustive search that meets the target.
struct GridBest {
    scheme: String,
    elements: usize,
    steps: usize,
    error: f64,
    work: f64,
}

/// The cheapest grid point (by the family's work) meeting the target of `r`, each scheme's grid
/// spanning the choice's (M, N) by `span` either way (explicit steps above the bound left out).
fn exhaustive<P: Plannable>(
    p: &P,
    r: &PlanResult,
    e: &ExhaustiveSpec,
) -> Result<Option<GridBest>, String> {
    let (Decision::Chosen { choice } | Decision::PilotMeets { choice }) = &r.decision else {
        return Ok(None);
    };
    let (m, n) = (choice.elements as f64, choice.steps as f64);
    let ms = geometric(m / e.span, m * e.span, e.ratio);
    let ns = geometric(n / e.span, n * e.span, e.ratio);
    let mut jobs = Vec::new();
    for s in p.schemes() {
        if r.request
            .schemes
            .as_ref()
            .is_some_and(|names| !names.contains(&s.to_string()))
        {
            continue;
        }
        let bound = p.stability_bound(s);
        for &mi in &ms {
            for &ni in &ns {
                let k = p.final_time() / ni as f64;
                if bound.is_none_or(|b| k <= STABILITY_MARGIN * b) {
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
    let mut best: Option<GridBest> = None;
    for ((s, mi, ni), err) in jobs.into_iter().zip(errors) {
        let err = err?;
        let work = p.work(mi, ni);
        if err <= r.request.target && best.as_ref().is_none_or(|b| work < b.work) {
            best = Some(GridBest {
                scheme: s.to_string(),
                elements: mi,
                steps: ni,
                error: err,
                work,
            });
        }
    }
    Ok(best)
}

/// Runs the planner on every target of `spec` and gates it (module docs); the family's
/// `work_label` names its work in the tables and the figure.
pub fn run_targets<P: Plannable>(
    p: &P,
    spec: &PlanSpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let kept = Kept::new(p);
    let p = &kept;
    let work_label = p.work_label();
    let mut rows = Vec::new();
    let mut in_range = 0usize;
    let mut worst: f64 = 0.0;
    let mut cost_checks = Vec::new();
    let mut grid_rows = Vec::new();
    let mut achieved = Vec::new();
    let mut predicted = Vec::new();
    let mut targets = Vec::new();
    let mut grid_points = Vec::new();
    let mut first: Option<PlanResult> = None;
    for (i, &t) in spec.targets.iter().enumerate() {
        let r = plan(p, &spec.request(t))?;
        // a choice the run contradicted is a miss of the planner (its error is above the
        // target): a row, outside the range
        let (what, choice) = match &r.decision {
            Decision::Chosen { choice } => ("chosen", choice),
            Decision::PilotMeets { choice } => ("pilot", choice),
            Decision::Missed { choice, .. } => ("missed", choice),
            other => return Err(format!("target {t:e}: the planner refused ({other:?})")),
        };
        let x = r.executed.as_ref().ok_or("a chosen plan without its run")?;
        let ratio = x.error_ratio;
        if what != "missed" && spec.ratio_range[0] <= ratio && ratio <= spec.ratio_range[1] {
            in_range += 1;
        }
        worst = worst.max(ratio);
        rows.push(vec![
            format!("{t:.1e}"),
            what.to_string(),
            r.rounds.len().to_string(),
            choice.scheme.clone(),
            choice.elements.to_string(),
            choice.steps.to_string(),
            format!("{:.3e}", choice.predicted_error),
            format!("{:.3e}", x.achieved_error),
            format!("{ratio:.3}"),
            format!("{:.3e}", x.measured_cost),
        ]);
        achieved.push((x.measured_cost, x.achieved_error));
        predicted.push((choice.predicted_cost, choice.predicted_error));
        targets.push((x.measured_cost, t));
        if let Some(e) = spec.exhaustive.as_ref().filter(|e| i < e.max_targets) {
            let work = p.work(choice.elements, choice.steps);
            match exhaustive(p, &r, e)? {
                Some(g) => {
                    let ratio = work / g.work;
                    cost_checks.push(Check::at_most(
                        &format!(
                            "target {t:.1e}: the choice's work {work_label} over the grid's cheapest that meets it ({}, M = {}, N = {})",
                            g.scheme, g.elements, g.steps
                        ),
                        ratio,
                        e.max_cost_ratio,
                    ));
                    grid_rows.push(vec![
                        format!("{t:.1e}"),
                        format!("{}, {} × {}", choice.scheme, choice.elements, choice.steps),
                        format!("{}, {} × {}", g.scheme, g.elements, g.steps),
                        format!("{:.3e}", g.error),
                        format!("{ratio:.3}"),
                    ]);
                    grid_points.push((g.work, g.error));
                }
                None => cost_checks.push(Check::holds(
                    &format!("target {t:.1e}: a grid point meets it"),
                    false,
                    "found",
                )),
            }
        }
        if first.is_none() {
            first = Some(r);
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
    let mut header: Vec<String> = PLAN_TABLE_COLUMNS.iter().map(|s| s.to_string()).collect();
    if let Some(last) = header.last_mut() {
        *last = format!("work {work_label}");
    }
    report.tables.push(Table {
        title: format!(
            "The planner on {} targets (cost = work {work_label})",
            spec.targets.len()
        ),
        header,
        rows,
    });
    if let Some(r) = &first {
        report.tables.push(models_table(r));
    }
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
    // the work–precision figure of the plans: the first target's pilots per scheme, every
    // choice (predicted and achieved) and its target, and the grid's cheapest points
    let mut fig = Figure::new(format!(
        "Work–precision of the plans ({}): choices against their targets",
        spec.functional
    ))
    .log_log()
    .x_label(format!("work {work_label}"))
    .y_label(format!("error ({})", spec.functional));
    if let Some(r) = &first {
        for series in r.pilot_series("pilots of the first target") {
            fig = fig.series(series);
        }
    }
    fig = fig
        .series(Series::line("target (at the choice's work)", targets).color(3))
        .series(Series::markers("chosen: predicted", predicted).color(4))
        .series(Series::markers("chosen: achieved", achieved).color(5));
    if !grid_points.is_empty() {
        fig =
            fig.series(Series::markers("grid's cheapest meeting the target", grid_points).color(6));
    }
    ctx.plot(report, "plan_work_precision", &fig)?;
    if let Some(o) = &spec.oracle {
        crate::core::plan::oracle::run(p, spec, o, report)?;
    }
    extremes(p, spec, report)
}

/// Self-convergence under test: for each target of `spec`, the planner's choice (scheme, M, N)
/// is run again two levels finer, at (2M, 2N) and (4M, 4N); the achieved error is
/// |F(M, N) − F(4M, 4N)| and its band U the GCI of the finest of the three runs (ratio 2,
/// 95 % — the uncertainty of the reference value itself). Gates: the achieved error at most
/// hi · target + U for at least `min_fraction` of the targets, and never above
/// `max_ratio` · target + U; the extremes as in [`run_targets`]. The lower end of
/// `ratio_range` is reported, not gated: without an exact solution the planner predicts the
/// bound |a| h^p + |b| k^q, and where the space and time parts have opposite signs the achieved
/// error falls well below it (docs/planner.md §4).
pub fn run_targets_self<P: Plannable>(
    p: &P,
    spec: &PlanSpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let kept = Kept::new(p);
    let p = &kept;
    let work_label = p.work_label();
    let mut rows = Vec::new();
    let mut in_band = 0usize;
    let mut worst: f64 = f64::NEG_INFINITY;
    let mut achieved_pts = Vec::new();
    let mut estimated_pts = Vec::new();
    let mut predicted_pts = Vec::new();
    let mut targets = Vec::new();
    let mut first: Option<PlanResult> = None;
    for &t in &spec.targets {
        let r = plan(p, &spec.request(t))?;
        let (what, choice) = match &r.decision {
            Decision::Chosen { choice } => ("chosen", choice),
            Decision::PilotMeets { choice } => ("pilot", choice),
            Decision::Missed { choice, .. } => ("missed", choice),
            other => return Err(format!("target {t:e}: the planner refused ({other:?})")),
        };
        let x = r.executed.as_ref().ok_or("a chosen plan without its run")?;
        let f0 = x
            .value
            .ok_or("self-convergence: the chosen run has no value (an exact solution?)")?;
        let scheme = p
            .schemes()
            .into_iter()
            .find(|s| s.to_string() == choice.scheme)
            .ok_or("the chosen scheme vanished")?;
        let value_at = |m: usize, n: usize| -> Result<f64, String> {
            let l = p.run_level(m, n, scheme, false)?;
            match crate::core::plan::measure(&l, &spec.functional)? {
                crate::core::plan::Measure::Value(v) => Ok(v),
                crate::core::plan::Measure::Error(_) => Err("not a value".into()),
            }
        };
        let (m, n) = (choice.elements, choice.steps);
        let f1 = value_at(2 * m, 2 * n)?;
        let f2 = value_at(4 * m, 4 * n)?;
        let formal = formal_order(p.expected_orders(scheme, &spec.functional));
        let gci = crate::stats::gci::analyse(&[f0, f1, f2], 2.0, formal)
            .map_err(|e| format!("target {t:e}: GCI of the reference runs: {e}"))?;
        let band = gci.gci_fine_percent.unwrap_or(0.0) / 100.0 * f2.abs();
        let achieved = (f0 - f2).abs();
        // a choice the run contradicted (the model did not hold there) does not count as met
        if what != "missed" && achieved <= spec.ratio_range[1] * t + band {
            in_band += 1;
        }
        worst = worst.max((achieved - band) / t);
        rows.push(vec![
            format!("{t:.1e}"),
            what.to_string(),
            r.rounds.len().to_string(),
            choice.scheme.clone(),
            m.to_string(),
            n.to_string(),
            format!("{:.3e}", choice.predicted_error),
            format!("{:.3e}", x.achieved_error),
            format!("{f0:.9e}"),
            format!("{f2:.9e}"),
            format!("{achieved:.3e}"),
            format!("{band:.2e}"),
            gci.order.map_or("—".into(), |o| format!("{o:.2}")),
            format!("{:.3}", achieved / t),
        ]);
        achieved_pts.push((x.measured_cost, achieved));
        estimated_pts.push((x.measured_cost, x.achieved_error));
        predicted_pts.push((choice.predicted_cost, choice.predicted_error));
        targets.push((x.measured_cost, t));
        if first.is_none() {
            first = Some(r.clone());
        }
    }
    let n = spec.targets.len() as f64;
    report.gates.push(GateVerdict::from_checks(
        "planner (self-convergence): achieved error against a run two levels finer".into(),
        "ceiling",
        vec![
            Check::at_least(
                &format!(
                    "fraction of the {} targets with |F − F(4M, 4N)| ≤ {} · target + U",
                    spec.targets.len(),
                    spec.ratio_range[1]
                ),
                in_band as f64 / n,
                spec.min_fraction,
            ),
            Check::at_most(
                "max over the targets of (|F − F(4M, 4N)| − U) / target",
                worst,
                spec.max_ratio,
            ),
        ],
        "U is the GCI (95 %) of the reference run (4M, 4N) from the three runs (M, N), (2M, 2N), (4M, 4N): the uncertainty of the reference itself",
    ));
    report.tables.push(Table {
        title: format!(
            "The planner by self-convergence on {} targets (cost = work {work_label}); the reference runs two levels finer",
            spec.targets.len()
        ),
        header: [
            "target",
            "answer",
            "pilot rounds",
            "scheme",
            "M",
            "N",
            "predicted error",
            "estimated error (pilots' F*)",
            "F(M, N)",
            "F(4M, 4N)",
            "achieved error vs F(4M, 4N)",
            "band U",
            "observed order",
            "achieved / target",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
    if let Some(r) = &first {
        report.tables.push(models_table(r));
    }
    let fig = Figure::new(format!(
        "Self-convergence plans ({}): achieved against a run two levels finer",
        spec.functional
    ))
    .log_log()
    .x_label(format!("work {work_label}"))
    .y_label(format!("error ({})", spec.functional))
    .series(Series::line("target (at the choice's work)", targets).color(3))
    .series(Series::markers("predicted (|a| h^p + |b| k^q)", predicted_pts).color(2))
    .series(Series::markers("estimated by the pilots (|F − F*|)", estimated_pts).color(4))
    .series(Series::markers("achieved (against (4M, 4N))", achieved_pts).color(5));
    ctx.plot(report, "plan_self_convergence", &fig)?;
    extremes(p, spec, report)
}

/// The table of the first target's models: per scheme the error model with its observed orders
/// against the expected ones, the cost model, and whether the planner used it (else why not).
fn models_table(r: &PlanResult) -> Table {
    let o = |v: Option<f64>| v.map_or("—".to_string(), |x| format!("{x}"));
    Table {
        title: format!(
            "The first target's models (pilots at (M₀/4 … M₀) × (N₀/4 … N₀), (M₀, N₀) = ({}, {}))",
            r.base.0, r.base.1
        ),
        header: [
            "scheme",
            "error model",
            "expected (p, q)",
            "cost model",
            "used",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows: r
            .schemes
            .iter()
            .map(|m| {
                vec![
                    m.scheme.clone(),
                    m.error_model.as_ref().map_or("—".into(), |e| e.describe()),
                    format!("({}, {})", o(m.expected_orders.0), o(m.expected_orders.1)),
                    m.cost_model
                        .as_ref()
                        .map_or("—".into(), |c| format!("c M^{:.2} N^{:.2}", c.a, c.b)),
                    m.rejected.clone().unwrap_or_else(|| "yes".into()),
                ]
            })
            .collect(),
    }
}

/// The extremes of `spec`: a target below float64's floor is refused with the floor; a loose
/// target is met by a first-round pilot.
fn extremes<P: Plannable>(p: &P, spec: &PlanSpec, report: &mut CaseReport) -> Result<(), String> {
    let mut checks = Vec::new();
    if let Some(t) = spec.floor_target {
        let r = plan(p, &spec.request(t))?;
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
            p,
            &PlanRequest {
                rounds: 1,
                ..spec.request(t)
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
    if let Some(x) = &spec.pre_asymptotic {
        let r = plan_with_base(
            p,
            &PlanRequest {
                rounds: 1,
                ..spec.request(x.target)
            },
            (x.base[0], x.base[1]),
        )?;
        let reasons: Vec<String> = r
            .schemes
            .iter()
            .map(|s| format!("{}: {}", s.scheme, s.rejected.as_deref().unwrap_or("used")))
            .collect();
        checks.push(Check::holds(
            &format!(
                "target {:e} from pilots at ({}, {}): refused as pre-asymptotic ({})",
                x.target,
                x.base[0],
                x.base[1],
                reasons.join("; ")
            ),
            matches!(r.decision, Decision::PreAsymptotic { .. }) && r.executed.is_none(),
            "refused, nothing extrapolated",
        ));
    }
    if let Some(x) = &spec.missed {
        let r = plan_with_base(
            p,
            &PlanRequest {
                rounds: 1,
                ..spec.request(x.target)
            },
            (x.base[0], x.base[1]),
        )?;
        let what = match (&r.decision, &r.executed) {
            (Decision::Missed { choice, .. }, Some(e)) => format!(
                "{}, M = {}, N = {}: value {:.6e} against the model's {:.6e}, off by {:.2} × the predicted error",
                choice.scheme,
                choice.elements,
                choice.steps,
                e.value.unwrap_or(f64::NAN),
                e.predicted_value.unwrap_or(f64::NAN),
                e.deviation.unwrap_or(f64::NAN)
            ),
            (other, _) => format!("{other:?}"),
        };
        checks.push(Check::holds(
            &format!(
                "target {:e} from pilots at ({}, {}): the chosen run contradicts its model ({what})",
                x.target, x.base[0], x.base[1]
            ),
            matches!(r.decision, Decision::Missed { .. }) && r.executed.is_some(),
            "refused after the run",
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
