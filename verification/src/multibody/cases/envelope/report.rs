//! What a `multibody_envelope` case shows: every point's outcome with its recomputed energy,
//! momentum and rebound (and the solver's own E_N/E_0 beside them), the rebound error against M
//! per speed, and E(T)/E_0 per point.

use crate::core::context::RunContext;
use crate::core::report::case_report::{CaseReport, Table};
use crate::multibody::cases::envelope::energy::{energy_floor, momentum_floor};
use crate::multibody::cases::envelope::format::EnvelopeCase;
use crate::multibody::cases::envelope::gates::inside;
use crate::multibody::cases::envelope::points::{Ending, PointRun, Source};
use crate::plot::{Figure, Series};

fn opt(x: Option<f64>, digits: usize) -> String {
    x.map_or("—".into(), |v| format!("{v:.digits$e}"))
}

/// One row per point.
pub fn points_table(file: &EnvelopeCase, runs: &[PointRun]) -> Table {
    let rows = runs
        .iter()
        .map(|r| {
            let (de, dp) = match (&r.start, &r.end) {
                (Some(a), Some(b)) => {
                    let dp = (b.momentum[0] - a.momentum[0])
                        .abs()
                        .max((b.momentum[1] - a.momentum[1]).abs());
                    (
                        Some(
                            (b.energy - a.energy)
                                / energy_floor(file.energy_round_off, a, b, r.steps),
                        ),
                        Some(dp / momentum_floor(file.momentum_round_off, a, b, r.steps)),
                    )
                }
                _ => (None, None),
            };
            let outcome = match &r.ending {
                Ending::Completed => r.outcomes().join(", "),
                Ending::Failed { kind, message } => {
                    let short: String = message.chars().take(140).collect();
                    format!("{kind}: {short}…")
                }
            };
            vec![
                r.label.clone(),
                if inside(file, r) { "inside" } else { "past" }.into(),
                r.steps.to_string(),
                outcome,
                r.energy_ratio().map_or("—".into(), |x| format!("{x:.9}")),
                r.solver_ratio.map_or("—".into(), |x| format!("{x:.9}")),
                opt(de, 2),
                opt(dp, 2),
                opt(r.rebound_error(), 3),
                if r.flagged_steps > 0 {
                    format!("{:.2e} ({} steps)", r.flagged_work, r.flagged_steps)
                } else {
                    "—".into()
                },
            ]
        })
        .collect();
    Table {
        title: "Every point: outcome, E(T)/E_0 recomputed from the final state (and the solver's \
                own E_N/E_0, not gated), (E_T − E_0)/floor and |P_T − P_0|/floor (≤ 1 passes; \
                negative: energy lost), the rebound error against the exact swap ±v → ∓v, and \
                the positive set-change work the audit flagged (/E_0)"
            .into(),
        header: [
            "point",
            "range",
            "steps",
            "outcome",
            "E(T)/E_0",
            "solver E_N/E_0",
            "(E_T − E_0)/floor",
            "|ΔP|/floor",
            "rebound error",
            "flagged work",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

/// The (M, rebound error) of each (sweep, speed) inside the range.
fn rebound_series(file: &EnvelopeCase, runs: &[PointRun]) -> Vec<(String, Vec<(f64, f64)>)> {
    let mut out: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for (s, sweep) in file.sweeps.iter().enumerate().filter(|(_, s)| s.inside) {
        for &speed in &sweep.speeds {
            let pts: Vec<(f64, f64)> = runs
                .iter()
                .filter_map(|r| match r.source {
                    Source::Sweep {
                        sweep: i,
                        speed: v,
                        elements,
                        ..
                    } if i == s && v == speed => Some((elements as f64, r.rebound_error()?)),
                    _ => None,
                })
                .filter(|(_, e)| *e > 0.0)
                .collect();
            if pts.len() > 1 {
                out.push((format!("{}, v/c = {speed}", sweep.name), pts));
            }
        }
    }
    out
}

/// The rebound error against M per speed, and E(T)/E_0 per point.
pub fn plots(
    file: &EnvelopeCase,
    ctx: &RunContext,
    report: &mut CaseReport,
    runs: &[PointRun],
) -> Result<(), String> {
    let id = report.id.clone();
    let mut fig = Figure::new(format!(
        "{id}: rebound error |v(T) − v_exact|/v against the elements along M"
    ))
    .x_label("M (elements along each bar)")
    .y_label("rebound error")
    .log_log();
    for (i, (name, pts)) in rebound_series(file, runs).into_iter().enumerate() {
        fig = fig.series(Series::line_markers(name, pts).color(i));
    }
    for r in &file.rates {
        // slope −p in M for the rate p in h
        fig = fig.reference_slope(
            -r.criteria.expected_rate,
            format!("M^-{:.3}", r.criteria.expected_rate),
        );
    }
    ctx.plot(report, "rebound_error", &fig)?;
    let mut fig = Figure::new(format!(
        "{id}: E(T)/E_0 recomputed from the final state, every completed point (index as in \
         the table)"
    ))
    .x_label("point")
    .y_label("E(T)/E_0")
    .horizontal_line(1.0, "E_0");
    let (mut inside_pts, mut past_pts) = (Vec::new(), Vec::new());
    for (i, r) in runs.iter().enumerate() {
        if let Some(x) = r.energy_ratio() {
            if inside(file, r) {
                inside_pts.push((i as f64, x));
            } else {
                past_pts.push((i as f64, x));
            }
        }
    }
    fig = fig
        .series(Series::markers("inside the range", inside_pts).color(0))
        .series(Series::markers("past the range (completed with a warning)", past_pts).color(1));
    ctx.plot(report, "energy_ratio", &fig)
}
