//! The speed–accuracy planner: from a target error to the cheapest (h, k, scheme), with the
//! evidence of the choice (docs/planner.md).
//!
//! 1. **Pilots.** For each candidate scheme, the scene's own resolution (M₀, N₀) and its halves
//!    and quarters in M and in N: 9 runs at (M₀/4 … M₀) × (N₀/4 … N₀), in parallel, their errors
//!    measured against the scene's exact solution; an explicit scheme's pilots above its
//!    stability bound are left out.
//! 2. **Models.** Per scheme, the error model E² = (C_h h^p)² + (C_k k^q)² of the functional and
//!    the cost model t = c M^a N^b of the pilots' run times ([`model`]).
//! 3. **Checks.** A model that misses its pilots by more than [`MAX_MODEL_RESIDUAL`] in log
//!    space, or whose orders leave the expected ones by more than [`ORDER_TOLERANCE`] of them, is
//!    *pre-asymptotic*: it is reported and not extrapolated. A target below the functional's
//!    float64 floor is refused with the floor.
//! 4. **Choice** ([`choose`]): the cheapest (M, N, scheme) whose predicted error is at most
//!    0.85 × target, inside what the pilots support and below each scheme's stability bound — or
//!    the cheapest pilot that already meets the target; else a refusal that names the resolution
//!    the models say is needed, as the next pilot.
//! 5. **Run.** The choice is run: predicted against achieved error and cost. The run lies
//!    outside the pilots, so it tests the model: an error above the target, or (self-convergence)
//!    a value off the model's prediction by more than [`VALIDATION_TOLERANCE`] of the predicted
//!    error, is a miss ([`Decision::Missed`]), and the next round (if any) pilots one level finer.
//!
//! A pilot that fails takes its scheme out of the plan, with the failure as the reason; a model
//! whose fitted order lies on the edge of the orders searched is pre-asymptotic. Rounds
//! ([`plan_with_base`]) run the pilots again where a round refused, missed, or chose against the
//! pilots' limits. [`render`] draws and writes a plan, [`refine`] scales the counts of a scene's
//! generated shapes, [`case`] runs the planner's own verification cases.

pub mod case;
pub mod choose;
pub mod impact;
pub mod model;
pub mod oracle;
pub mod refine;
pub mod render;

use rayon::prelude::*;
use serde::Serialize;

use crate::core::study::Study;
use crate::core::sweep::Level;
use choose::{choose, unsupported, Choice, SchemeModels};
use model::{fit_cost, fit_error, ErrorModel};

use crate::stats::extrapolation::{fit_extrapolation, Extrapolation};
use crate::stats::gci::{analyse, GciResult};

/// The largest log-space residual standard deviation of an error model the planner extrapolates
/// (≈ 15 % relative misfit over the pilots).
pub const MAX_MODEL_RESIDUAL: f64 = 0.15;
/// The columns of a planner case's table of targets (the README's `rod_plan` block reads them).
pub const PLAN_TABLE_COLUMNS: [&str; 10] = [
    "target",
    "answer",
    "pilot rounds",
    "scheme",
    "M",
    "N",
    "predicted error",
    "achieved error",
    "achieved / target",
    "work M·N",
];

/// A further pilot round is run (where rounds remain) when the models' optimum outside the
/// pilots' limits costs less than this fraction of the choice inside them.
pub const UNCONSTRAINED_GAIN: f64 = 0.9;
/// An observed order may leave the expected one by this fraction of it.
pub const ORDER_TOLERANCE: f64 = 0.3;
/// Self-convergence: the chosen run's value must agree with the model's prediction of it to
/// this fraction of the predicted error (the run lies outside the pilots' box: it tests the
/// extrapolation).
pub const VALIDATION_TOLERANCE: f64 = 0.3;

/// A model family's study that the planner can drive.
pub trait Plannable: Study {
    /// The scene's own resolution (M₀, N₀): the finest pilot.
    fn base(&self) -> (usize, usize);
    /// T (k = T/N).
    fn final_time(&self) -> f64;
    /// The schemes a plan may choose among.
    fn schemes(&self) -> Vec<Self::Scheme>;
    /// The largest stable step of `scheme` (explicit schemes), None where there is none.
    fn stability_bound(&self, scheme: Self::Scheme) -> Option<f64>;
    /// The orders (p in h, q in k) the theory gives for `functional` with `scheme`, where known
    /// (None for a term: not checked).
    fn expected_orders(&self, scheme: Self::Scheme, functional: &str)
        -> (Option<f64>, Option<f64>);
    /// The smallest error of `functional` float64 can resolve for this problem, from the pilots.
    fn floor(&self, functional: &str, pilots: &[Level]) -> f64;
    /// The CPU seconds of a run at (M, N, scheme) (the family's timing, e.g. min of repeats).
    fn seconds(&self, elements: usize, steps: usize, scheme: Self::Scheme) -> Result<f64, String>;
    /// The deterministic work of a run (e.g. M·N for a solver whose step costs O(M)).
    fn work(&self, elements: usize, steps: usize) -> f64;

    /// How the work is counted, for tables and figures (e.g. `M·N`).
    fn work_label(&self) -> &'static str {
        "M·N"
    }

    /// The CPU seconds of the run `level` itself, for a family whose runs are long enough to be
    /// timed once (None: [`Plannable::seconds`] times the run again).
    fn run_seconds(&self, _level: &Level) -> Option<f64> {
        None
    }
}

/// A family's study with the resolution of the first round's finest pilot: the [`Study`] part
/// of a [`Plannable`] (each family implements the rest for its own `Based<…Study>`).
pub struct Based<S> {
    pub study: S,
    /// (M₀, N₀).
    pub base: (usize, usize),
}

impl<S: Study> Study for Based<S> {
    type Scheme = S::Scheme;

    fn default_scheme(&self) -> S::Scheme {
        self.study.default_scheme()
    }

    fn run_level(
        &self,
        elements: usize,
        steps: usize,
        scheme: S::Scheme,
        time_error: bool,
    ) -> Result<Level, String> {
        self.study.run_level(elements, steps, scheme, time_error)
    }
}

/// The formal order of a functional from its expected orders (p, q): the smaller of the two
/// declared, 1 where none is.
pub fn formal_order((p, q): (Option<f64>, Option<f64>)) -> f64 {
    match (p, q) {
        (Some(p), Some(q)) => p.min(q),
        (Some(o), None) | (None, Some(o)) => o,
        (None, None) => 1.0,
    }
}

/// What the cost model is fitted on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CostMeasure {
    /// The pilots' measured CPU time (s; the family's timing, min of repeats).
    #[default]
    Seconds,
    /// The family's deterministic work count (e.g. M·N): a choice that does not depend on the
    /// machine's load — the planner's gated cases use it.
    Work,
}

/// What the user asks.
#[derive(Debug, Clone, Serialize)]
pub struct PlanRequest {
    pub target: f64,
    pub functional: String,
    /// Scheme names (None: every scheme of the family).
    pub schemes: Option<Vec<String>>,
    pub cost: CostMeasure,
    /// Pilot rounds (≥ 1): when the models need more than the pilots support (or the pilots
    /// are pre-asymptotic) and rounds remain, the pilots run again from the resolution the
    /// refusal proposes.
    pub rounds: usize,
}

impl PlanRequest {
    /// Checks the rounds the user asked for: at least one pilot round (`--rounds`; the target
    /// is checked with the functional, in the first round).
    ///
    /// # Errors
    /// A message naming the option, its value and what is expected.
    pub fn validate(&self) -> Result<(), String> {
        if self.rounds == 0 {
            return Err(format!(
                "invalid --rounds = {}: expected at least 1 pilot round",
                self.rounds
            ));
        }
        Ok(())
    }
}

/// One pilot run.
#[derive(Debug, Clone, Serialize)]
pub struct Pilot {
    pub scheme: String,
    pub elements: usize,
    pub steps: usize,
    pub h: f64,
    pub k: f64,
    /// Against the exact solution; with self-convergence, |F − F*| against the scheme's
    /// extrapolated value F* (or, where its model is rejected, against its finest pilot).
    pub error: f64,
    /// The functional's value (self-convergence; None with an exact solution).
    pub value: Option<f64>,
    /// The cost the model is fitted on (`PlanRequest::cost`).
    pub cost: f64,
}

/// One scheme's models and whether the planner trusts them.
#[derive(Debug, Clone, Serialize)]
pub struct SchemeSummary {
    pub scheme: String,
    pub error_model: Option<ErrorModel>,
    pub cost_model: Option<crate::stats::cost_model::CostModelFit>,
    /// Why the cost model is not the pilots' own fit (an overhead-dominated timing replaced by
    /// the work's exponents, [`model::calibrated_to_work`]); None: the fit.
    pub cost_note: Option<String>,
    pub expected_orders: (Option<f64>, Option<f64>),
    pub stability_bound: Option<f64>,
    /// Self-convergence: the GCI of the diagonal pilots (M₀/4, N₀/4), (M₀/2, N₀/2), (M₀, N₀)
    /// (ratio 2, h and k refined together), with its observed order.
    pub gci: Option<GciResult>,
    /// Why the scheme's model is not used (None: used).
    pub rejected: Option<String>,
}

/// What the planner decided.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Decision {
    /// The cheapest discretization the models predict meets the target.
    Chosen { choice: Choice },
    /// A pilot already meets the target (the cheapest such pilot): nothing to extrapolate.
    PilotMeets { choice: Choice },
    /// The target is below what float64 resolves for this functional.
    BelowFloor { floor: f64 },
    /// The models need more than the pilots support: the resolution they predict, as the next
    /// pilot to run (None: not even there).
    BeyondPilots { needed: Option<Choice> },
    /// No scheme's model describes its pilots (pre-asymptotic): a finer pilot is proposed.
    PreAsymptotic { proposed_pilot: (usize, usize) },
    /// The chosen run contradicts the model that chose it: its error above the target (against
    /// the exact solution), or (self-convergence) its value off the model's prediction by more
    /// than [`VALIDATION_TOLERANCE`] of the predicted error, or its estimated error above the
    /// target. The pilots were pre-asymptotic where the choice lies: the next round pilots one
    /// level finer.
    Missed {
        choice: Choice,
        proposed_pilot: (usize, usize),
    },
    /// Every scheme had a pilot that failed (a Newton method that did not converge, a rebound
    /// not reached by T, …): nothing to model; the failures, one per scheme.
    PilotsFailed { failures: Vec<String> },
}

/// The chosen run, executed.
#[derive(Debug, Clone, Serialize)]
pub struct Executed {
    pub achieved_error: f64,
    /// In the units of `PlanRequest::cost`.
    pub measured_cost: f64,
    /// achieved / target and measured / predicted cost.
    pub error_ratio: f64,
    pub cost_ratio: f64,
    /// Self-convergence: the run's value of the functional and the extrapolated value F* its
    /// error is estimated against (the achieved error is then an estimate: `plane_plan_self`
    /// measures it against a run two levels finer).
    pub value: Option<f64>,
    pub reference_value: Option<f64>,
    /// Self-convergence: the model's prediction F* + a h^p + b k^q of the run's value, and
    /// |F − that| over the predicted error (at most [`VALIDATION_TOLERANCE`] where the model
    /// holds at the choice).
    pub predicted_value: Option<f64>,
    pub deviation: Option<f64>,
}

/// The plan and its evidence.
#[derive(Debug, Clone, Serialize)]
pub struct PlanResult {
    pub request: PlanRequest,
    /// The finest pilot of the last round.
    pub base: (usize, usize),
    /// The finest pilot of every round, in order.
    pub rounds: Vec<(usize, usize)>,
    /// The cheapest choice the models predict without the pilots' limits (where another round
    /// of pilots would go).
    pub unconstrained: Option<Choice>,
    pub pilots: Vec<Pilot>,
    /// Every pilot of every round the plan ran (`pilots` holds the deciding round's only): their
    /// count and their summed cost in the request's unit — the planner's own share of the bill.
    pub pilot_runs: usize,
    pub pilots_cost: f64,
    pub schemes: Vec<SchemeSummary>,
    pub decision: Decision,
    pub executed: Option<Executed>,
    /// How the work is counted (`Plannable::work_label`).
    pub work_label: String,
}

/// The pilot levels of a base resolution: (M₀/4, M₀/2, M₀) × (N₀/4, N₀/2, N₀), each ≥ 1.
pub fn pilot_levels((m0, n0): (usize, usize)) -> Vec<(usize, usize)> {
    let div = |v: usize, d: usize| (v / d).max(1);
    let ms = [div(m0, 4), div(m0, 2), m0];
    let ns = [div(n0, 4), div(n0, 2), n0];
    let mut out = Vec::new();
    for &m in &ms {
        for &n in &ns {
            if !out.contains(&(m, n)) {
                out.push((m, n));
            }
        }
    }
    out
}

/// 100 ε times the largest magnitude of `functional`'s values over the pilots: the float64 floor
/// of a value measured by self-convergence (differences of values below it are round-off).
pub fn value_floor(functional: &str, pilots: &[Level]) -> f64 {
    let scale = pilots
        .iter()
        .filter_map(|l| l.values.get(functional))
        .fold(0.0f64, |m, v| m.max(v.abs()));
    100.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE)
}

/// What a run measured of the functional: its error against an exact solution, or its value
/// (self-convergence).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Measure {
    Error(f64),
    Value(f64),
}

impl Measure {
    fn amount(self) -> f64 {
        match self {
            Measure::Error(v) | Measure::Value(v) => v,
        }
    }
}

/// The functional of a run: an error (`Level::errors`) or a value (`Level::values`).
pub fn measure(level: &Level, functional: &str) -> Result<Measure, String> {
    if let Some(e) = level.errors.get(functional) {
        return Ok(Measure::Error(*e));
    }
    if let Some(v) = level.values.get(functional) {
        return Ok(Measure::Value(*v));
    }
    Err(format!(
        "the functional `{functional}` is not measured; known: {}",
        level
            .errors
            .keys()
            .chain(level.values.keys())
            .cloned()
            .collect::<Vec<_>>()
            .join(", ")
    ))
}

/// Plans (and runs) the cheapest discretization meeting `request` (module docs).
///
/// # Errors
/// A scheme name the family does not have, an unknown functional, a non-positive target, a
/// failed pilot or the failed chosen run.
pub fn plan<P: Plannable>(p: &P, request: &PlanRequest) -> Result<PlanResult, String> {
    plan_with_base(p, request, p.base())
}

/// [`plan`] with the first round's finest pilot at `base` instead of the scene's own.
///
/// # Errors
/// As [`plan`].
pub fn plan_with_base<P: Plannable>(
    p: &P,
    request: &PlanRequest,
    base: (usize, usize),
) -> Result<PlanResult, String> {
    request.validate()?;
    let mut base = base;
    let mut rounds = Vec::new();
    let mut earlier: Option<PlanResult> = None;
    // every round's pilots, whichever round decides
    let (mut pilot_runs, mut pilots_cost) = (0, 0.0);
    loop {
        let mut r = plan_from(p, request, base)?;
        pilot_runs += r.pilot_runs;
        pilots_cost += r.pilots_cost;
        // a round that refuses after an earlier round chose: the earlier choice stands (the
        // further round only looked for a cheaper one)
        if !matches!(
            r.decision,
            Decision::Chosen { .. } | Decision::PilotMeets { .. }
        ) {
            if let Some(mut e) = earlier.take() {
                rounds.push(base);
                e.rounds = rounds;
                (e.pilot_runs, e.pilots_cost) = (pilot_runs, pilots_cost);
                return Ok(e);
            }
        }
        rounds.push(base);
        let next = match &r.decision {
            Decision::BeyondPilots { needed: Some(c) } => {
                Some(next_base((c.elements, c.steps), base))
            }
            Decision::PreAsymptotic { proposed_pilot }
            | Decision::Missed { proposed_pilot, .. } => Some(*proposed_pilot),
            // the choice pressed against the pilots' limits: the models put the optimum
            // outside, at least 10 % cheaper — pilot again around it
            Decision::Chosen { choice } | Decision::PilotMeets { choice } => r
                .unconstrained
                .as_ref()
                .filter(|u| u.predicted_cost < UNCONSTRAINED_GAIN * choice.predicted_cost)
                .map(|u| (u.elements.max(4), u.steps.max(4))),
            _ => None,
        };
        match next {
            Some(b) if rounds.len() < request.rounds.max(1) && !rounds.contains(&b) => {
                if matches!(
                    r.decision,
                    Decision::Chosen { .. } | Decision::PilotMeets { .. }
                ) {
                    earlier = Some(r);
                }
                base = b;
            }
            _ => {
                r.rounds = rounds;
                (r.pilot_runs, r.pilots_cost) = (pilot_runs, pilots_cost);
                return Ok(r);
            }
        }
    }
}

/// The finest pilot of the round after a refusal beyond the pilots of `base`: in each of M and N,
/// half the `needed` count where that is more than twice the pilots' (the needed point then lies
/// at twice the new finest pilot, inside the [`choose::EXTRAPOLATION`] the models are trusted
/// over, and the round's pilots cost about one chosen run instead of several), else the needed
/// count; at least 4.
fn next_base(needed: (usize, usize), base: (usize, usize)) -> (usize, usize) {
    let at = |n: usize, b: usize| if n > 2 * b { n.div_ceil(2) } else { n }.max(4);
    (at(needed.0, base.0), at(needed.1, base.1))
}

/// Why a scheme has no pilot: each pilot's step k = T/N (N ≤ N₀ of `base`) is above the
/// margin × its stability bound.
fn unstable_pilots(final_time: f64, base: (usize, usize), bound: Option<f64>) -> String {
    let k_min = final_time / base.1.max(1) as f64;
    match bound {
        Some(b) => format!(
            "every pilot is beyond the stability bound: the finest pilot's step k = T/N₀ = \
             {k_min:.3e} (N₀ = {}) is above {} × k_max = {:.3e}; a base with N₀ ≥ {:.0} pilots \
             this scheme",
            base.1,
            choose::STABILITY_MARGIN,
            choose::STABILITY_MARGIN * b,
            (4.0 * final_time / (choose::STABILITY_MARGIN * b)).ceil()
        ),
        None => "no pilot ran".to_string(),
    }
}

/// One round of [`plan`] with its finest pilot at `base`.
/// Timing passes over the pilots in seconds mode ([`pilot_costs`]).
pub const PILOT_TIMING_PASSES: usize = 3;

/// The cost of each pilot run (docs/planner.md §2): its work; in seconds mode its own time where
/// the family times its runs (a long run), else the family's timing taken after the parallel
/// runs, one pilot at a time and in turn across every scheme and level, [`PILOT_TIMING_PASSES`]
/// passes, each pilot its min — so that a load that comes and goes weighs on every scheme alike
/// rather than on the scheme that happened to be timed under it (timed in parallel, a scheme's
/// finest pilot read 1.6 × its time under a second process and the plan chose the wrong scheme).
fn pilot_costs<P: Plannable>(
    p: &P,
    cost: CostMeasure,
    jobs: &[(P::Scheme, usize, usize)],
    runs: &[Result<Level, String>],
) -> Vec<Result<f64, String>> {
    let mut costs: Vec<Result<f64, String>> = runs
        .iter()
        .map(|r| match (cost, r) {
            (_, Err(_)) => Ok(f64::NAN),
            (CostMeasure::Work, Ok(l)) => Ok(p.work(l.elements, l.steps)),
            (CostMeasure::Seconds, Ok(l)) => Ok(p.run_seconds(l).unwrap_or(f64::INFINITY)),
        })
        .collect();
    if cost == CostMeasure::Seconds {
        for _ in 0..PILOT_TIMING_PASSES {
            for (c, (&(s, m, n), r)) in costs.iter_mut().zip(jobs.iter().zip(runs)) {
                if r.is_err() || p.run_seconds(r.as_ref().unwrap()).is_some() {
                    continue;
                }
                if let Ok(best) = c {
                    *c = p.seconds(m, n, s).map(|t| best.min(t));
                }
            }
        }
    }
    costs
        .into_iter()
        .map(|c| {
            c.map(|t| {
                if cost == CostMeasure::Seconds {
                    t.max(1e-9)
                } else {
                    t
                }
            })
        })
        .collect()
}

fn plan_from<P: Plannable>(
    p: &P,
    request: &PlanRequest,
    base: (usize, usize),
) -> Result<PlanResult, String> {
    if !(request.target.is_finite() && request.target > 0.0) {
        return Err(format!(
            "--target = {}: expected a positive error",
            request.target
        ));
    }
    let all = p.schemes();
    let schemes: Vec<P::Scheme> = match &request.schemes {
        None => all.clone(),
        Some(names) => names
            .iter()
            .map(|n| {
                all.iter()
                    .copied()
                    .find(|s| s.to_string() == *n)
                    .ok_or_else(|| {
                        format!(
                            "--schemes: `{n}` is not a scheme of this model; known: {}",
                            all.iter()
                                .map(|s| s.to_string())
                                .collect::<Vec<_>>()
                                .join(", ")
                        )
                    })
            })
            .collect::<Result<_, _>>()?,
    };
    // 1. pilots (parallel; the order of the jobs is kept)
    let mut jobs = Vec::new();
    for &s in &schemes {
        let bound = p.stability_bound(s);
        for (m, n) in pilot_levels(base) {
            let stable = bound.is_none_or(|b| {
                let k = p.final_time() / n as f64;
                k <= choose::STABILITY_MARGIN * b
            });
            if stable {
                jobs.push((s, m, n));
            }
        }
    }
    // the runs in parallel; their cost after (`pilot_costs`)
    let runs: Vec<Result<Level, String>> = jobs
        .par_iter()
        .map(|&(s, m, n)| p.run_level(m, n, s, false))
        .collect();
    let costs = pilot_costs(p, request.cost, &jobs, &runs);
    let measured = runs
        .into_iter()
        .zip(costs)
        .map(|(r, c)| r.and_then(|l| Ok((l, c?))));
    let mut levels = Vec::new();
    let mut pilots = Vec::new();
    // a scheme with a failed pilot is not modelled (its first failure says why); the plan goes
    // on with the other schemes
    let mut failed: Vec<(String, String)> = Vec::new();
    for (r, &(s, m, n)) in measured.zip(&jobs) {
        let (l, cost) = match r {
            Ok(x) => x,
            Err(e) => {
                let name = s.to_string();
                if !failed.iter().any(|(f, _)| *f == name) {
                    failed.push((name, format!("pilot (M = {m}, N = {n}) failed: {e}")));
                }
                continue;
            }
        };
        let x = measure(&l, &request.functional)?;
        pilots.push(Pilot {
            scheme: l.scheme.clone(),
            elements: l.elements,
            steps: l.steps,
            h: l.h,
            k: l.k,
            // a value's error is set once its scheme's extrapolation is known
            error: x.amount(),
            value: matches!(x, Measure::Value(_)).then_some(x.amount()),
            cost,
        });
        levels.push(l);
    }
    let self_convergence = pilots.iter().any(|x| x.value.is_some());
    let floor = p.floor(&request.functional, &levels);
    // 2–3. models and their checks
    let mut summaries = Vec::new();
    let mut usable = Vec::new();
    for &s in &schemes {
        let name = s.to_string();
        if let Some((_, why)) = failed.iter().find(|(f, _)| *f == name) {
            summaries.push(SchemeSummary {
                scheme: name,
                error_model: None,
                cost_model: None,
                cost_note: None,
                expected_orders: p.expected_orders(s, &request.functional),
                stability_bound: p.stability_bound(s),
                gci: None,
                rejected: Some(why.clone()),
            });
            continue;
        }
        let own: Vec<&Pilot> = pilots.iter().filter(|x| x.scheme == name).collect();
        if own.is_empty() {
            // every pilot beyond the stability bound: no value to model (a mean of no values
            // would be NaN in the plan)
            let bound = p.stability_bound(s);
            summaries.push(SchemeSummary {
                scheme: name,
                error_model: None,
                cost_model: None,
                cost_note: None,
                expected_orders: p.expected_orders(s, &request.functional),
                stability_bound: bound,
                gci: None,
                rejected: Some(unstable_pilots(p.final_time(), base, bound)),
            });
            continue;
        }
        let col = |f: fn(&Pilot) -> f64| own.iter().map(|x| f(x)).collect::<Vec<f64>>();
        let (h, k, e) = (col(|x| x.h), col(|x| x.k), col(|x| x.error));
        let values: Vec<f64> = own.iter().filter_map(|x| x.value).collect();
        let (m, n, t) = (
            col(|x| x.elements as f64),
            col(|x| x.steps as f64),
            col(|x| x.cost),
        );
        let expected = p.expected_orders(s, &request.functional);
        let bound = p.stability_bound(s);
        let spread = values.iter().fold(f64::NEG_INFINITY, |m, v| m.max(*v))
            - values.iter().fold(f64::INFINITY, |m, v| m.min(*v));
        let error_model = if self_convergence && spread <= floor {
            // the values agree to round-off: the functional does not depend on (h, k) here
            // (e.g. a contact force fixed by global equilibrium)
            Ok(ErrorModel::Extrapolated(Extrapolation::constant(
                values.iter().sum::<f64>() / values.len() as f64,
                values.len(),
            )))
        } else if self_convergence {
            fit_extrapolation(&h, &k, &values).map(ErrorModel::Extrapolated)
        } else {
            fit_error(&h, &k, &e)
        };
        let gci = self_convergence
            .then(|| diagonal_gci(&own, base, expected))
            .flatten();
        let finest = own
            .iter()
            .max_by(|x, y| {
                p.work(x.elements, x.steps)
                    .total_cmp(&p.work(y.elements, y.steps))
            })
            .map(|x| (x.elements as f64, x.steps as f64, x.cost));
        let (cost_model, cost_note) = match (fit_cost(&m, &n, &t), finest) {
            (Ok(fit), Some(f)) if request.cost == CostMeasure::Seconds => {
                let (fit, note) = model::calibrated_to_work(fit, f, |m, n| {
                    p.work(m.round() as usize, n.round() as usize)
                });
                (Ok(fit), note)
            }
            (fit, _) => (fit, None),
        };
        let mut rejected = None;
        match (&error_model, &cost_model) {
            (Err(err), _) => rejected = Some(format!("error model: {err}")),
            (_, Err(err)) => rejected = Some(format!("cost model: {err}")),
            (Ok(em), Ok(_)) => {
                if em.residual_std() > MAX_MODEL_RESIDUAL {
                    rejected = Some(format!(
                        "pre-asymptotic: the model misses its pilots by {:.0} % (log residual {:.3} > {MAX_MODEL_RESIDUAL})",
                        100.0 * (em.residual_std().exp() - 1.0),
                        em.residual_std()
                    ));
                }
                if let ErrorModel::Extrapolated(x) = em {
                    if let Some((label, o)) = x.order_at_search_bound() {
                        rejected = Some(format!(
                            "pre-asymptotic: observed {label} = {o:.3} on the edge of the orders searched, [0.2, 5]: not determined by the pilots"
                        ));
                    }
                }
                let (po, qo) = em.orders();
                for (label, observed, exp) in [("p", po, expected.0), ("q", qo, expected.1)] {
                    if let (Some(o), Some(x)) = (observed, exp) {
                        if (o - x).abs() > ORDER_TOLERANCE * x {
                            rejected = Some(format!(
                                "pre-asymptotic: observed {label} = {o:.3}, expected {x} (± {:.0} %)",
                                100.0 * ORDER_TOLERANCE
                            ));
                        }
                    }
                }
            }
        }
        if let (None, Ok(em), Ok(cm)) = (&rejected, &error_model, &cost_model) {
            let mean = |v: Vec<f64>| v.iter().sum::<f64>() / v.len() as f64;
            usable.push(SchemeModels {
                scheme: name.clone(),
                error: em.clone(),
                cost: cm.clone(),
                hm: mean(own.iter().map(|x| x.h * x.elements as f64).collect()),
                kn: mean(own.iter().map(|x| x.k * x.steps as f64).collect()),
                m_range: minmax(own.iter().map(|x| x.elements)),
                n_range: minmax(own.iter().map(|x| x.steps)),
                stability_bound: bound,
                held: (
                    expected.0.is_some() && em.orders().0.is_none(),
                    expected.1.is_some() && em.orders().1.is_none(),
                ),
            });
        }
        summaries.push(SchemeSummary {
            scheme: name,
            error_model: error_model.ok(),
            cost_model: cost_model.ok(),
            cost_note,
            expected_orders: expected,
            stability_bound: bound,
            gci,
            rejected,
        });
    }
    // self-convergence: each pilot's error against its scheme's extrapolated value (or, where
    // the model is rejected, against the scheme's finest pilot: a diagnostic only)
    if self_convergence {
        for s in &summaries {
            let reference = match (&s.error_model, &s.rejected) {
                (Some(ErrorModel::Extrapolated(x)), None) => Some(x.value),
                _ => pilots
                    .iter()
                    .filter(|x| x.scheme == s.scheme)
                    .max_by_key(|x| (x.elements, x.steps))
                    .and_then(|x| x.value),
            };
            for x in pilots.iter_mut().filter(|x| x.scheme == s.scheme) {
                if let (Some(v), Some(r)) = (x.value, reference) {
                    x.error = (v - r).abs();
                }
            }
        }
    }
    // 4. the decision
    let trusted = |scheme: &str| !self_convergence || usable.iter().any(|u| u.scheme == scheme);
    // a pilot's error: measured against the exact solution; with self-convergence only
    // estimated, so the larger of |F − F*| and the model's bound |a| h^p + |b| k^q (the two
    // parts may cancel at the pilot's (h, k), and the estimate would then promise an error a
    // finer reference does not confirm)
    let claimed = |x: &Pilot| -> f64 {
        if !self_convergence {
            return x.error;
        }
        let bound = usable
            .iter()
            .find(|u| u.scheme == x.scheme)
            .map_or(f64::INFINITY, |u| u.error.predict(x.h, x.k));
        x.error.max(bound)
    };
    // a pilot as a choice: measured, its error claimed as above
    let pilot_as_choice = |x: &Pilot| Choice {
        scheme: x.scheme.clone(),
        elements: x.elements,
        steps: x.steps,
        h: x.h,
        k: x.k,
        predicted_error: claimed(x),
        predicted_cost: x.cost,
    };
    let pilot_choice = pilots
        .iter()
        .filter(|x| trusted(&x.scheme))
        .filter(|x| claimed(x) <= request.target)
        .min_by(|a, b| a.cost.total_cmp(&b.cost))
        .map(pilot_as_choice);
    let decision = if request.target < floor {
        Decision::BelowFloor { floor }
    } else if usable.is_empty() {
        match pilot_choice {
            Some(choice) => Decision::PilotMeets { choice },
            None if failed.len() == schemes.len() => Decision::PilotsFailed {
                failures: failed
                    .iter()
                    .map(|(s, why)| format!("{s}: {why}"))
                    .collect(),
            },
            None => Decision::PreAsymptotic {
                proposed_pilot: (2 * base.0, 2 * base.1),
            },
        }
    } else {
        // a choice that is itself a pilot meeting the target is that pilot, measured
        let as_pilot = |c: &Choice| {
            pilots
                .iter()
                .filter(|x| trusted(&x.scheme) && claimed(x) <= request.target)
                .find(|x| x.scheme == c.scheme && x.elements == c.elements && x.steps == c.steps)
                .map(pilot_as_choice)
        };
        let chosen = choose(&usable, request.target);
        match (chosen.as_ref().and_then(as_pilot), chosen, pilot_choice) {
            // a pilot as cheap as the choice (to round-off of the cost model) is measured, not
            // predicted: it wins
            (_, Some(c), Some(pc)) if pc.predicted_cost <= c.predicted_cost * (1.0 + 1e-9) => {
                Decision::PilotMeets { choice: pc }
            }
            (Some(pilot), _, _) => Decision::PilotMeets { choice: pilot },
            (None, Some(choice), _) => Decision::Chosen { choice },
            (None, None, Some(choice)) => Decision::PilotMeets { choice },
            (None, None, None) => Decision::BeyondPilots {
                needed: unsupported(&usable, request.target),
            },
        }
    };
    // 5. the run
    let executed = match &decision {
        Decision::Chosen { choice } => {
            let s = schemes
                .iter()
                .copied()
                .find(|s| s.to_string() == choice.scheme)
                .ok_or("the chosen scheme vanished")?;
            let l = p
                .run_level(choice.elements, choice.steps, s, false)
                .map_err(|e| {
                    format!(
                        "the chosen run ({s}, M = {}, N = {}): {e}",
                        choice.elements, choice.steps
                    )
                })?;
            let (achieved, value, reference, predicted) = match measure(&l, &request.functional)? {
                Measure::Error(e) => (e, None, None, None),
                Measure::Value(v) => {
                    let x = extrapolation(&summaries, &choice.scheme)
                        .ok_or("the chosen scheme has no extrapolated value")?;
                    (
                        (v - x.value).abs(),
                        Some(v),
                        Some(x.value),
                        Some(x.predict(choice.h, choice.k)),
                    )
                }
            };
            let cost =
                pilot_costs(p, request.cost, &[(s, l.elements, l.steps)], &[Ok(l)]).remove(0)?;
            Some(Executed {
                achieved_error: achieved,
                measured_cost: cost,
                error_ratio: achieved / request.target,
                cost_ratio: cost / choice.predicted_cost,
                value,
                reference_value: reference,
                predicted_value: predicted,
                deviation: value
                    .zip(predicted)
                    .map(|(v, f)| (v - f).abs() / choice.predicted_error.max(f64::MIN_POSITIVE)),
            })
        }
        Decision::PilotMeets { choice } => {
            let pilot = pilots.iter().find(|x| {
                x.scheme == choice.scheme
                    && x.elements == choice.elements
                    && x.steps == choice.steps
            });
            let value = pilot.and_then(|x| x.value);
            Some(Executed {
                achieved_error: choice.predicted_error,
                measured_cost: choice.predicted_cost,
                error_ratio: choice.predicted_error / request.target,
                cost_ratio: 1.0,
                value,
                reference_value: value
                    .and(extrapolation(&summaries, &choice.scheme).map(|x| x.value)),
                predicted_value: None,
                deviation: None,
            })
        }
        _ => None,
    };
    // the chosen run lies outside the pilots: it tests the model that chose it
    let decision = match (decision, &executed) {
        (Decision::Chosen { choice }, Some(x))
            if x.achieved_error > request.target
                || x.deviation.is_some_and(|d| d > VALIDATION_TOLERANCE) =>
        {
            Decision::Missed {
                choice,
                proposed_pilot: (2 * base.0, 2 * base.1),
            }
        }
        (d, _) => d,
    };
    Ok(PlanResult {
        request: request.clone(),
        base,
        rounds: vec![base],
        unconstrained: unsupported(&usable, request.target),
        pilot_runs: pilots.len(),
        pilots_cost: pilots.iter().map(|x| x.cost).sum(),
        pilots,
        schemes: summaries,
        decision,
        executed,
        work_label: p.work_label().to_string(),
    })
}

/// The self-convergence model of a scheme whose model is used.
fn extrapolation<'a>(summaries: &'a [SchemeSummary], scheme: &str) -> Option<&'a Extrapolation> {
    summaries
        .iter()
        .find_map(|s| match (&s.error_model, &s.rejected) {
            (Some(ErrorModel::Extrapolated(x)), None) if s.scheme == scheme => Some(x),
            _ => None,
        })
}

/// The GCI of a scheme's diagonal pilots (M₀/4, N₀/4), (M₀/2, N₀/2), (M₀, N₀) (None unless M₀
/// and N₀ are multiples of 4, so that the ratio is exactly 2, or a pilot is missing).
fn diagonal_gci(
    own: &[&Pilot],
    (m0, n0): (usize, usize),
    (p, q): (Option<f64>, Option<f64>),
) -> Option<GciResult> {
    if m0 % 4 != 0 || n0 % 4 != 0 {
        return None;
    }
    let values: Option<Vec<f64>> = [4, 2, 1]
        .iter()
        .map(|d| {
            own.iter()
                .find(|x| x.elements == m0 / d && x.steps == n0 / d)
                .and_then(|x| x.value)
        })
        .collect();
    analyse(&values?, 2.0, formal_order((p, q))).ok()
}

fn minmax(v: impl Iterator<Item = usize>) -> (usize, usize) {
    v.fold((usize::MAX, 0), |(lo, hi), x| (lo.min(x), hi.max(x)))
}

#[cfg(test)]
mod tests {
    //! The planner's rounds on a synthetic study whose values follow F = 1 + 1/M exactly inside
    //! the pilots' box: a choice beyond the box is tested by its own run (a jump there is a
    //! miss, and the next round pilots one level finer), and a refusal beyond the pilots
    //! proposes a next round at half the needed resolution.
    use super::*;
    use contactlab::model::quasistatic::scheme::TimeScheme;
    use std::collections::BTreeMap;

    /// F(M, N) = 1 + 1/M, plus `jump` beyond M = 8 (an effect the pilots at M ≤ 8 cannot see).
    struct Synthetic {
        jump: f64,
    }

    impl Study for Synthetic {
        type Scheme = TimeScheme;
        fn default_scheme(&self) -> TimeScheme {
            TimeScheme::Implicit
        }
        fn run_level(&self, m: usize, n: usize, s: TimeScheme, _: bool) -> Result<Level, String> {
            let mut values = BTreeMap::new();
            let jump = if m > 8 { self.jump } else { 0.0 };
            values.insert("F".to_string(), 1.0 + 1.0 / m as f64 + jump);
            Ok(Level {
                elements: m,
                steps: n,
                h: 1.0 / m as f64,
                k: 1.0 / n as f64,
                scheme: s.to_string(),
                errors: BTreeMap::new(),
                values,
                u_end: 0.0,
                cpu_seconds: 0.0,
                thread_seconds: 0.0,
                stats: serde_json::Value::Null,
            })
        }
    }

    impl Plannable for Synthetic {
        fn base(&self) -> (usize, usize) {
            (8, 8)
        }
        fn final_time(&self) -> f64 {
            1.0
        }
        fn schemes(&self) -> Vec<TimeScheme> {
            vec![TimeScheme::Implicit]
        }
        fn stability_bound(&self, _: TimeScheme) -> Option<f64> {
            None
        }
        fn expected_orders(&self, _: TimeScheme, _: &str) -> (Option<f64>, Option<f64>) {
            (None, None)
        }
        fn floor(&self, f: &str, pilots: &[Level]) -> f64 {
            value_floor(f, pilots)
        }
        fn seconds(&self, _: usize, _: usize, _: TimeScheme) -> Result<f64, String> {
            Ok(1.0)
        }
        fn work(&self, m: usize, n: usize) -> f64 {
            (m * n) as f64
        }
    }

    fn request(target: f64, rounds: usize) -> PlanRequest {
        PlanRequest {
            target,
            functional: "F".into(),
            schemes: None,
            cost: CostMeasure::Work,
            rounds,
        }
    }

    #[test]
    fn a_choice_its_run_confirms_is_chosen() {
        let r = plan(&Synthetic { jump: 0.0 }, &request(0.06, 1)).unwrap();
        let Decision::Chosen { choice } = &r.decision else {
            panic!("{:?}", r.decision)
        };
        // 1/M ≤ 0.85 × 0.06: M = 20, beyond the pilots (M ≤ 8), inside 4× them
        assert_eq!(choice.elements, 20);
        let x = r.executed.as_ref().unwrap();
        assert!(x.deviation.unwrap() < 1e-6, "{x:?}");
    }

    #[test]
    fn a_choice_its_run_contradicts_is_missed_and_piloted_again_one_level_finer() {
        let study = Synthetic { jump: 0.05 };
        let r = plan(&study, &request(0.06, 1)).unwrap();
        let Decision::Missed {
            choice,
            proposed_pilot,
        } = &r.decision
        else {
            panic!("{:?}", r.decision)
        };
        assert_eq!((choice.elements, *proposed_pilot), (20, (16, 16)));
        // the run gave 1 + 1/20 + 0.05 where the model said 1 + 1/20: off by 1 × the error
        let d = r.executed.as_ref().unwrap().deviation.unwrap();
        assert!((d - 1.0).abs() < 1e-6, "{d}");
        // with a second round the pilots at M = 4 … 16 see the jump: the choice is not the
        // missed one
        let r = plan(&study, &request(0.06, 2)).unwrap();
        assert_eq!(r.rounds, vec![(8, 8), (16, 16)]);
        assert!(!matches!(r.decision, Decision::Chosen { ref choice } if choice.elements == 20));
    }

    #[test]
    fn the_round_after_a_refusal_beyond_the_pilots_starts_at_half_the_needed_resolution() {
        // M needed 100 from pilots at 8: the next round's finest pilot at 50 (the needed point
        // at twice it); N needed 12 from pilots at 8: within twice them, kept
        assert_eq!(next_base((100, 12), (8, 8)), (50, 12));
        assert_eq!(next_base((3, 3), (8, 8)), (4, 4));
    }
}
