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
//! 5. **Run.** The choice is run: predicted against achieved error and cost.

pub mod choose;
pub mod model;

use rayon::prelude::*;
use serde::Serialize;

use crate::core::study::Study;
use crate::core::sweep::Level;
use crate::plot::{Figure, Series};
use choose::{choose, unsupported, Choice, SchemeModels};
use model::{fit_cost, fit_error, ErrorModel};

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

/// One pilot run.
#[derive(Debug, Clone, Serialize)]
pub struct Pilot {
    pub scheme: String,
    pub elements: usize,
    pub steps: usize,
    pub h: f64,
    pub k: f64,
    pub error: f64,
    /// The cost the model is fitted on (`PlanRequest::cost`).
    pub cost: f64,
}

/// One scheme's models and whether the planner trusts them.
#[derive(Debug, Clone, Serialize)]
pub struct SchemeSummary {
    pub scheme: String,
    pub error_model: Option<ErrorModel>,
    pub cost_model: Option<crate::stats::cost_model::CostModelFit>,
    pub expected_orders: (Option<f64>, Option<f64>),
    pub stability_bound: Option<f64>,
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
    pub schemes: Vec<SchemeSummary>,
    pub decision: Decision,
    pub executed: Option<Executed>,
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

fn error_of(level: &Level, functional: &str) -> Result<f64, String> {
    level.errors.get(functional).copied().ok_or_else(|| {
        format!(
            "the functional `{functional}` is not measured; known: {}",
            level.errors.keys().cloned().collect::<Vec<_>>().join(", ")
        )
    })
}

/// Plans (and runs) the cheapest discretization meeting `request` (module docs).
///
/// # Errors
/// A scheme name the family does not have, an unknown functional, a non-positive target, a
/// failed pilot or the failed chosen run.
pub fn plan<P: Plannable>(p: &P, request: &PlanRequest) -> Result<PlanResult, String> {
    let mut base = p.base();
    let mut rounds = Vec::new();
    loop {
        let mut r = plan_from(p, request, base)?;
        rounds.push(base);
        let next = match &r.decision {
            Decision::BeyondPilots { needed: Some(c) } => Some((c.elements.max(4), c.steps.max(4))),
            Decision::PreAsymptotic { proposed_pilot } => Some(*proposed_pilot),
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
            Some(b) if rounds.len() < request.rounds.max(1) && !rounds.contains(&b) => base = b,
            _ => {
                r.rounds = rounds;
                return Ok(r);
            }
        }
    }
}

/// One round of [`plan`] with its finest pilot at `base`.
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
    let cost_of = |m: usize, n: usize, s: P::Scheme| -> Result<f64, String> {
        Ok(match request.cost {
            CostMeasure::Seconds => p.seconds(m, n, s)?.max(1e-9),
            CostMeasure::Work => p.work(m, n),
        })
    };
    let measured: Vec<Result<(Level, f64), String>> = jobs
        .par_iter()
        .map(|&(s, m, n)| {
            let l = p.run_level(m, n, s, false)?;
            Ok((l, cost_of(m, n, s)?))
        })
        .collect();
    let mut levels = Vec::new();
    let mut pilots = Vec::new();
    for (r, &(s, m, n)) in measured.into_iter().zip(&jobs) {
        let (l, cost) = r.map_err(|e| format!("pilot ({s}, M = {m}, N = {n}): {e}"))?;
        pilots.push(Pilot {
            scheme: l.scheme.clone(),
            elements: l.elements,
            steps: l.steps,
            h: l.h,
            k: l.k,
            error: error_of(&l, &request.functional)?,
            cost,
        });
        levels.push(l);
    }
    // 2–3. models and their checks
    let mut summaries = Vec::new();
    let mut usable = Vec::new();
    for &s in &schemes {
        let name = s.to_string();
        let own: Vec<&Pilot> = pilots.iter().filter(|x| x.scheme == name).collect();
        let col = |f: fn(&Pilot) -> f64| own.iter().map(|x| f(x)).collect::<Vec<f64>>();
        let (h, k, e) = (col(|x| x.h), col(|x| x.k), col(|x| x.error));
        let (m, n, t) = (
            col(|x| x.elements as f64),
            col(|x| x.steps as f64),
            col(|x| x.cost),
        );
        let expected = p.expected_orders(s, &request.functional);
        let bound = p.stability_bound(s);
        let error_model = fit_error(&h, &k, &e);
        let cost_model = fit_cost(&m, &n, &t);
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
            });
        }
        summaries.push(SchemeSummary {
            scheme: name,
            error_model: error_model.ok(),
            cost_model: cost_model.ok(),
            expected_orders: expected,
            stability_bound: bound,
            rejected,
        });
    }
    // 4. the decision
    let floor = p.floor(&request.functional, &levels);
    let pilot_choice = pilots
        .iter()
        .filter(|x| x.error <= request.target)
        .min_by(|a, b| a.cost.total_cmp(&b.cost))
        .map(|x| Choice {
            scheme: x.scheme.clone(),
            elements: x.elements,
            steps: x.steps,
            h: x.h,
            k: x.k,
            predicted_error: x.error,
            predicted_cost: x.cost,
        });
    let decision = if request.target < floor {
        Decision::BelowFloor { floor }
    } else if usable.is_empty() {
        match pilot_choice {
            Some(choice) => Decision::PilotMeets { choice },
            None => Decision::PreAsymptotic {
                proposed_pilot: (2 * base.0, 2 * base.1),
            },
        }
    } else {
        match (choose(&usable, request.target), pilot_choice) {
            // a pilot as cheap as the choice (to round-off of the cost model) is measured, not
            // predicted: it wins
            (Some(c), Some(pc)) if pc.predicted_cost <= c.predicted_cost * (1.0 + 1e-9) => {
                Decision::PilotMeets { choice: pc }
            }
            (Some(choice), _) => Decision::Chosen { choice },
            (None, Some(choice)) => Decision::PilotMeets { choice },
            (None, None) => Decision::BeyondPilots {
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
            let achieved = error_of(&l, &request.functional)?;
            let cost = cost_of(choice.elements, choice.steps, s)?;
            Some(Executed {
                achieved_error: achieved,
                measured_cost: cost,
                error_ratio: achieved / request.target,
                cost_ratio: cost / choice.predicted_cost,
            })
        }
        Decision::PilotMeets { choice } => Some(Executed {
            achieved_error: choice.predicted_error,
            measured_cost: choice.predicted_cost,
            error_ratio: choice.predicted_error / request.target,
            cost_ratio: 1.0,
        }),
        _ => None,
    };
    Ok(PlanResult {
        request: request.clone(),
        base,
        rounds: vec![base],
        unconstrained: unsupported(&usable, request.target),
        pilots,
        schemes: summaries,
        decision,
        executed,
    })
}

fn minmax(v: impl Iterator<Item = usize>) -> (usize, usize) {
    v.fold((usize::MAX, 0), |(lo, hi), x| (lo.min(x), hi.max(x)))
}

impl PlanResult {
    /// The work–precision figure: the pilots per scheme, the chosen scheme's model along its
    /// cheapest path, the target and the chosen point (predicted and achieved).
    pub fn figure(&self, title: &str) -> Figure {
        let mut fig = Figure::new(format!(
            "{title}: plan for {} ≤ {:e}",
            self.request.functional, self.request.target
        ))
        .log_log()
        .x_label(match self.request.cost {
            CostMeasure::Seconds => "cost (CPU s)",
            CostMeasure::Work => "cost (work: M·N)",
        })
        .y_label(format!("error ({})", self.request.functional));
        for (i, s) in self.schemes.iter().enumerate() {
            let pts: Vec<(f64, f64)> = self
                .pilots
                .iter()
                .filter(|p| p.scheme == s.scheme)
                .map(|p| (p.cost, p.error))
                .collect();
            fig = fig.series(Series::markers(format!("pilots: {}", s.scheme), pts).color(i));
        }
        fig = fig.horizontal_line(self.request.target, "target");
        if let Decision::Chosen { choice } = &self.decision {
            fig = fig.series(Series::markers(
                "chosen (predicted)",
                [(choice.predicted_cost, choice.predicted_error)],
            ));
            if let Some(x) = &self.executed {
                fig = fig.series(Series::markers(
                    "chosen (achieved)",
                    [(x.measured_cost, x.achieved_error)],
                ));
            }
        }
        fig
    }

    /// A Markdown summary: the request, the models, the decision and the run.
    pub fn markdown(&self) -> String {
        let mut s = format!(
            "# Plan: {} ≤ {:e}\n\nPilots: {} runs at (M₀/4 … M₀) × (N₀/4 … N₀), (M₀, N₀) = ({}, {}){}.\n\n",
            self.request.functional,
            self.request.target,
            self.pilots.len(),
            self.base.0,
            self.base.1,
            if self.rounds.len() > 1 {
                format!(
                    " (round {} of the pilots; earlier rounds from {})",
                    self.rounds.len(),
                    self.rounds[..self.rounds.len() - 1]
                        .iter()
                        .map(|(m, n)| format!("({m}, {n})"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            } else {
                String::new()
            }
        );
        s.push_str("| scheme | error model | cost model | expected (p, q) | stability bound | used |\n|---|---|---|---|---|---|\n");
        for m in &self.schemes {
            let cost = m.cost_model.as_ref().map_or("—".into(), |c| {
                format!(
                    "t = {:.2e} M^{:.2} N^{:.2} (a ∈ [{:.2}, {:.2}], b ∈ [{:.2}, {:.2}])",
                    c.log_constant.exp(),
                    c.a,
                    c.b,
                    c.a_ci.0,
                    c.a_ci.1,
                    c.b_ci.0,
                    c.b_ci.1
                )
            });
            let o = |v: Option<f64>| v.map_or("—".into(), |x| format!("{x}"));
            s.push_str(&format!(
                "| {} | {} | {} | ({}, {}) | {} | {} |\n",
                m.scheme,
                m.error_model.as_ref().map_or("—".into(), |e| e.describe()),
                cost,
                o(m.expected_orders.0),
                o(m.expected_orders.1),
                m.stability_bound
                    .map_or("—".into(), |b| format!("k ≤ {b:.4}")),
                m.rejected.as_deref().unwrap_or("yes")
            ));
        }
        s.push_str("\n## Decision\n\n");
        match &self.decision {
            Decision::Chosen { choice } | Decision::PilotMeets { choice } => {
                let what = if matches!(self.decision, Decision::Chosen { .. }) {
                    "chosen"
                } else {
                    "a pilot already meets the target"
                };
                s.push_str(&format!(
                    "{what}: **{}**, M = {}, N = {} (h = {:.4e}, k = {:.4e}); predicted error {:.3e}, predicted cost {:.3e}\n",
                    choice.scheme, choice.elements, choice.steps, choice.h, choice.k,
                    choice.predicted_error, choice.predicted_cost
                ));
            }
            Decision::BelowFloor { floor } => s.push_str(&format!(
                "refused: the target is below the float64 floor of this functional, ≈ {floor:.2e}\n"
            )),
            Decision::BeyondPilots { needed } => s.push_str(&match needed {
                Some(c) => format!(
                    "refused: the target needs M = {}, N = {} ({}), beyond what the pilots support; run the planner again from that resolution\n",
                    c.elements, c.steps, c.scheme
                ),
                None => "refused: no resolution within 1000× the pilots meets the target\n".into(),
            }),
            Decision::PreAsymptotic { proposed_pilot } => s.push_str(&format!(
                "refused: no scheme's model describes its pilots (pre-asymptotic, table above); run from M = {}, N = {}\n",
                proposed_pilot.0, proposed_pilot.1
            )),
        }
        if let Some(x) = &self.executed {
            s.push_str(&format!(
                "\nAchieved error {:.3e} ({:.2} × target); cost {:.3e} ({:.2} × predicted).\n",
                x.achieved_error, x.error_ratio, x.measured_cost, x.cost_ratio
            ));
        }
        s
    }
}
