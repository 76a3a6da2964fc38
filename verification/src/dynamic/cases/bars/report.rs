//! What the 1D kinds show: one convergence figure per (sweep, error, parameter), the table of
//! errors per level, and the table of cost and audit per family.

use crate::core::report::case_report::Table;
use crate::core::sweep::Against;

use crate::dynamic::cases::bars::family::FamilySpec;
use crate::dynamic::cases::bars::gates::{worst_summary, RateGate};
use crate::dynamic::cases::bars::sweep::{LevelOutcome, SweepOutcome, SweepSpec};
use crate::plot::{Figure, Series};

/// One log–log figure per (sweep, gated or `plot`-listed error, parameter): every family the
/// sweep runs (the gated ones with markers, the others dashed, for comparison), with the gates'
/// expected slopes.
pub fn convergence_figures(
    case_id: &str,
    sweeps: &[SweepSpec],
    gates: &[RateGate],
    outcomes: &[SweepOutcome],
) -> Vec<(String, Figure)> {
    let mut keys: Vec<(String, String, Against)> = Vec::new();
    let listed = sweeps.iter().flat_map(|s| {
        s.plot
            .iter()
            .map(|e| (s.name.clone(), e.clone(), Against::H))
    });
    let gated = gates.iter().map(|g| {
        (
            g.select.sweep.clone(),
            g.select.error.clone(),
            g.select.against,
        )
    });
    for key in gated.chain(listed) {
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys.into_iter()
        .map(|(sweep, error, against)| {
            let mut fig = Figure::new(format!(
                "{case_id}: sweep `{sweep}`, {error} against {}",
                against.label()
            ))
            .x_label(against.label())
            .y_label(error.as_str())
            .log_log();
            let gated: Vec<&RateGate> = gates
                .iter()
                .filter(|g| {
                    let s = &g.select;
                    s.sweep == sweep && s.error == error && s.against == against
                })
                .collect();
            for (i, o) in outcomes.iter().filter(|o| o.sweep == sweep).enumerate() {
                let pts: Vec<(f64, f64)> = o
                    .levels
                    .iter()
                    .filter_map(|l| {
                        let p = if against == Against::K { l.k } else { l.h };
                        l.errors.get(&error).map(|e| (p, *e))
                    })
                    .collect();
                let series = if gated.iter().any(|g| g.select.family == o.family) {
                    Series::line_markers(format!("{} (gated)", o.family), pts)
                } else {
                    Series::line(o.family.clone(), pts).dashed()
                };
                fig = fig.series(series.color(i));
            }
            let mut slopes: Vec<f64> = Vec::new();
            for g in &gated {
                let rate = g.criteria.expected_rate;
                if !slopes.iter().any(|s| (s - rate).abs() < 1e-12) {
                    slopes.push(rate);
                }
            }
            for s in slopes {
                fig = fig.reference_slope(s, format!("slope {s:.3}"));
            }
            let suffix = if against == Against::K { "k" } else { "h" };
            (format!("convergence_{sweep}_{error}_{suffix}"), fig)
        })
        .collect()
}

/// The table of every run's measured quantities, one row per (sweep, family, level).
pub fn errors_table(title: &str, names: &[&str], outcomes: &[SweepOutcome]) -> Table {
    let mut header: Vec<String> = ["sweep", "family", "M", "N", "h", "k"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    header.extend(names.iter().map(|s| s.to_string()));
    header.extend(
        [
            "max |R(1.48)|/E_ref",
            "max |R(3.7)|/E_ref",
            "max |R(1.49)|/E_ref",
            "S/E_ref",
            "Newton it./step",
        ]
        .iter()
        .map(|s| s.to_string()),
    );
    let rows = outcomes
        .iter()
        .flat_map(|o| {
            o.levels.iter().map(move |l| {
                let mut row = vec![
                    o.sweep.clone(),
                    o.family.clone(),
                    l.elements.to_string(),
                    l.steps.to_string(),
                    format!("{:.4e}", l.h),
                    format!("{:.4e}", l.k),
                ];
                row.extend(names.iter().map(|n| {
                    l.errors
                        .get(*n)
                        .map_or("–".to_string(), |v| format!("{v:.4e}"))
                }));
                row.push(format!("{:.2e}", l.summary.max_drift_1_48));
                row.push(format!("{:.2e}", l.summary.max_drift_3_7));
                row.push(format!("{:.2e}", l.summary.max_drift_1_49));
                row.push(format!(
                    "{:.2e}",
                    l.summary.roundoff_scale / l.summary.energy_scale
                ));
                row.push(format!(
                    "{:.3}",
                    l.stats.newton_iterations as f64 / l.steps as f64
                ));
                row
            })
        })
        .collect();
    Table {
        title: title.to_string(),
        header,
        rows,
    }
}

/// Per family: the cost per step and the Newton iterations per step (mean over all its runs,
/// max over all steps), and the audit's worst drifts R_n of the identities.
pub fn cost_and_audit_table(families: &[FamilySpec], outcomes: &[SweepOutcome]) -> Table {
    let rows = families
        .iter()
        .filter_map(|f| {
            let levels: Vec<&LevelOutcome> = outcomes
                .iter()
                .filter(|o| o.family == f.name)
                .flat_map(|o| &o.levels)
                .collect();
            let finest = levels
                .iter()
                .min_by(|a, b| a.h.total_cmp(&b.h).then(a.k.total_cmp(&b.k)))?;
            let steps: usize = levels.iter().map(|l| l.steps).sum();
            let iterations: usize = levels.iter().map(|l| l.stats.newton_iterations).sum();
            let max_it = levels
                .iter()
                .map(|l| l.stats.max_newton_iterations)
                .max()
                .unwrap_or(0);
            let w = worst_summary(outcomes, &f.name)?;
            Some(vec![
                f.name.clone(),
                f.describe(),
                levels.len().to_string(),
                format!(
                    "{:.2} (M = {}, N = {})",
                    finest.micros_per_step(),
                    finest.elements,
                    finest.steps
                ),
                format!(
                    "{} ({} unknowns)",
                    finest.stats.factor_nnz, finest.stats.unknowns
                ),
                format!("{:.3}", iterations as f64 / steps as f64),
                max_it.to_string(),
                format!("{:.1e}", w.max_drift_1_48),
                format!("{:.1e}", w.max_drift_3_7),
                format!("{:.1e}", w.max_drift_1_49),
                format!("{:.1e}", w.max_step_constraint_work),
            ])
        })
        .collect();
    Table {
        title: "per family: solver cost per step (µs, the finest run, error evaluation excluded; \
                a shared machine: indicative), Newton iterations per step (mean over all runs, max \
                over all steps), worst audit over all runs"
            .into(),
        header: [
            "family",
            "treatment / scheme / mass",
            "runs",
            "µs per step",
            "factor nnz (finest)",
            "Newton it./step (mean)",
            "max it./step",
            "max |R(1.48)|/E_ref",
            "max |R(3.7)|/E_ref",
            "max |R(1.49)|/E_ref",
            "max step constraint work D_b",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    }
}
