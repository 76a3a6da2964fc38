//! What a plan shows: its pilots as work–precision markers, its figure and its Markdown summary
//! (`plan.svg`, `plan.md`).

use crate::core::plan::model::ErrorModel;
use crate::core::plan::{CostMeasure, Decision, PlanResult, VALIDATION_TOLERANCE};
use crate::plot::{Figure, Series};

impl PlanResult {
    /// The pilots as (cost, error) markers, one series per scheme labelled "`label`: scheme".
    pub fn pilot_series(&self, label: &str) -> Vec<Series> {
        self.schemes
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let pts: Vec<(f64, f64)> = self
                    .pilots
                    .iter()
                    .filter(|p| p.scheme == s.scheme)
                    .map(|p| (p.cost, p.error))
                    .collect();
                Series::markers(format!("{label}: {}", s.scheme), pts).color(i)
            })
            .collect()
    }

    /// The work–precision figure: the pilots per scheme, the chosen scheme's model along its
    /// cheapest path, the target and the chosen point (predicted and achieved).
    pub fn figure(&self, title: &str) -> Figure {
        let mut fig = Figure::new(format!(
            "{title}: plan for {} ≤ {:e}",
            self.request.functional, self.request.target
        ))
        .log_log()
        .x_label(match self.request.cost {
            CostMeasure::Seconds => "cost (CPU s)".to_string(),
            CostMeasure::Work => format!("cost (work: {})", self.work_label),
        })
        .y_label(format!("error ({})", self.request.functional));
        for series in self.pilot_series("pilots") {
            fig = fig.series(series);
        }
        fig = fig.horizontal_line(self.request.target, "target");
        if let Some(line) = self.model_line() {
            fig = fig.series(line);
        }
        if let Decision::Chosen { choice } | Decision::Missed { choice, .. } = &self.decision {
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
        if let Decision::PilotMeets { choice } = &self.decision {
            fig = fig.series(Series::markers(
                "chosen: a pilot that meets the target",
                [(choice.predicted_cost, choice.predicted_error)],
            ));
        }
        fig
    }

    /// The chosen scheme's models along the ray of the choice: (M s, N s) for s from the
    /// coarsest pilot to 4 × the finest, the predicted cost against the predicted error (None
    /// without a choice, or where the scheme has no models).
    fn model_line(&self) -> Option<Series> {
        let (Decision::Chosen { choice }
        | Decision::PilotMeets { choice }
        | Decision::Missed { choice, .. }) = &self.decision
        else {
            return None;
        };
        let s = self.schemes.iter().find(|s| s.scheme == choice.scheme)?;
        let (error, cost) = (s.error_model.as_ref()?, s.cost_model.as_ref()?);
        let own: Vec<_> = self
            .pilots
            .iter()
            .filter(|p| p.scheme == choice.scheme)
            .collect();
        let (m, n) = (choice.elements as f64, choice.steps as f64);
        let (hm, kn) = (choice.h * m, choice.k * n);
        let lo = own
            .iter()
            .map(|p| (p.elements as f64 / m).max(p.steps as f64 / n))
            .fold(f64::INFINITY, f64::min);
        let hi = 4.0
            * own
                .iter()
                .map(|p| (p.elements as f64 / m).min(p.steps as f64 / n))
                .fold(0.0, f64::max);
        if !(lo.is_finite() && hi > lo) {
            return None;
        }
        let points = (0..=40).map(|i| {
            let f = lo * (hi / lo).powf(i as f64 / 40.0);
            (
                cost.predict(m * f, n * f),
                error.predict(hm / (m * f), kn / (n * f)),
            )
        });
        Some(
            Series::line(
                format!("model ({}): M, N scaled with the choice", choice.scheme),
                points,
            )
            .dashed()
            .color(7),
        )
    }

    /// A cost in the request's unit, with the unit.
    fn cost_text(&self, cost: f64) -> String {
        match self.request.cost {
            CostMeasure::Seconds => format!("{cost:.3e} CPU s"),
            CostMeasure::Work => format!("{cost:.3e} work ({})", self.work_label),
        }
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
                    " (pilot rounds from {}; the decision is the round from ({}, {}))",
                    self.rounds
                        .iter()
                        .map(|(m, n)| format!("({m}, {n})"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    self.base.0,
                    self.base.1
                )
            } else {
                String::new()
            }
        );
        s.push_str(&format!(
            "The pilots of every round: {} runs, {} in all (the plan's own cost, beside the chosen run's).\n\n",
            self.pilot_runs,
            self.cost_text(self.pilots_cost)
        ));
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
            let cost = match &m.cost_note {
                Some(note) => format!("{cost}: {note}"),
                None => cost,
            };
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
        if self.pilots.iter().any(|x| x.value.is_some()) {
            s.push_str(
                "\nNo exact solution: self-convergence. Each scheme's pilot values are fitted by \
                 F ≈ F* + a h^p + b k^q; a pilot's error is |F − F*| and the predicted error \
                 |a| h^p + |b| k^q. The GCI of the diagonal pilots (ratio 2):\n\n\
                 | scheme | F* | GCI of the finest diagonal pilot | observed order | convergence |\n|---|---|---|---|---|\n",
            );
            for m in &self.schemes {
                let fstar = match &m.error_model {
                    Some(ErrorModel::Extrapolated(x)) => format!("{:.6e}", x.value),
                    _ => "—".into(),
                };
                let (gci, order, conv) = m.gci.as_ref().map_or(
                    ("—".to_string(), "—".to_string(), "—".to_string()),
                    |g| {
                        (
                            g.gci_fine_percent
                                .map_or("—".into(), |v| format!("{v:.3} %")),
                            g.order.map_or("—".into(), |o| format!("{o:.3}")),
                            format!("{:?}", g.convergence),
                        )
                    },
                );
                s.push_str(&format!(
                    "| {} | {fstar} | {gci} | {order} | {conv} |\n",
                    m.scheme
                ));
            }
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
            Decision::Missed {
                choice,
                proposed_pilot,
            } => s.push_str(&format!(
                "refused after the run: the choice **{}**, M = {}, N = {} (predicted error {:.3e}) contradicts the model that chose it (below); the pilots are pre-asymptotic there — run from M = {}, N = {}\n",
                choice.scheme,
                choice.elements,
                choice.steps,
                choice.predicted_error,
                proposed_pilot.0,
                proposed_pilot.1
            )),
            Decision::PilotsFailed { failures } => s.push_str(&format!(
                "refused: every scheme had a pilot that failed, nothing to model:\n\n{}\n",
                failures
                    .iter()
                    .map(|f| format!("- {f}"))
                    .collect::<Vec<_>>()
                    .join("\n")
            )),
        }
        if let Some(x) = &self.executed {
            match (x.value, x.reference_value) {
                (Some(v), Some(r)) => {
                    s.push_str(&format!(
                        "\nValue {v:.9e}; its error estimated against F* = {r:.9e}: {:.3e} ({:.2} × target); cost {:.3e} ({:.2} × predicted).\n",
                        x.achieved_error, x.error_ratio, x.measured_cost, x.cost_ratio
                    ));
                    if let (Some(f), Some(d)) = (x.predicted_value, x.deviation) {
                        s.push_str(&format!(
                            "The model predicted the value {f:.9e}: off by {d:.2} × the predicted error (the model holds at the choice where this is at most {VALIDATION_TOLERANCE}).\n"
                        ));
                    }
                }
                _ => s.push_str(&format!(
                    "\nAchieved error {:.3e} ({:.2} × target); cost {:.3e} ({:.2} × predicted).\n",
                    x.achieved_error, x.error_ratio, x.measured_cost, x.cost_ratio
                )),
            }
        }
        s
    }
}
