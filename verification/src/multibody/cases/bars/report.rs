//! What a `multibody_bars` case shows: the exact impacts, every run's errors and audit, the
//! shown runs' contact force and centre velocities against the exact histories, the convergence
//! plots with the gates' slopes, and the audit panels.

use crate::core::context::RunContext;
use crate::core::report::case_report::{CaseReport, Table};
use crate::multibody::cases::bars::format::BarsCase;
use crate::multibody::cases::bars::measure::ERRORS;
use crate::multibody::cases::bars::run::{parameter, series, Outcome};
use crate::multibody::study::{plot_audits, AuditRun};
use crate::plot::{Figure, Series};

/// The exact values of every configuration.
pub fn exact_table(file: &BarsCase) -> Table {
    let rows = file
        .configurations
        .iter()
        .map(|c| {
            let e = c.exact(file.material.young);
            let v0 = e.centre_velocities(0.0);
            let v1 = e.centre_velocities(f64::INFINITY);
            vec![
                c.name.clone(),
                format!("{}", e.wave_speed()),
                format!("{}", e.contact_start()),
                format!("{}", e.contact_end() - e.contact_start()),
                format!("{}", e.contact_stress()),
                format!("{}", e.area() * e.contact_stress()),
                format!("({}, {}) → ({}, {})", v0[0], v0[1], v1[0], v1[1]),
                format!("{}", e.energy()),
            ]
        })
        .collect();
    Table {
        title: "the exact impacts (verification/src/exact/bar_impact.rs)".into(),
        header: [
            "configuration",
            "c = √(E/ρ)",
            "contact from t0",
            "duration",
            "stress σ_c",
            "force A σ_c",
            "centre velocities before → after",
            "energy",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    }
}

/// Every sweep run: its level, errors and audit ratios.
pub fn runs_table(file: &BarsCase, outcomes: &[Outcome]) -> Table {
    let mut header: Vec<String> = ["sweep", "family", "M", "N", "h", "k"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    header.extend(ERRORS.iter().map(|s| s.to_string()));
    header.extend(
        [
            "identity ratio",
            "unchanged ratio",
            "P_x ratio",
            "P_y ratio",
            "J ratio",
            "Newton its",
        ]
        .iter()
        .map(|s| s.to_string()),
    );
    let mut rows = Vec::new();
    for sweep in &file.sweeps {
        for fam in &sweep.families {
            for o in series(file, outcomes, &sweep.name, fam) {
                let s = &o.summary;
                let mut row = vec![
                    sweep.name.clone(),
                    fam.clone(),
                    o.level.elements.to_string(),
                    o.level.steps.to_string(),
                    format!("{:.4e}", o.h),
                    format!("{:.4e}", o.k),
                ];
                row.extend(o.measured.errors.iter().map(|e| format!("{e:.3e}")));
                row.extend(
                    [
                        s.identity_ratio,
                        s.unchanged_ratio,
                        s.momentum_ratio_x,
                        s.momentum_ratio_y,
                        s.angular_ratio,
                    ]
                    .iter()
                    .map(|r| format!("{r:.2e}")),
                );
                row.push(o.newton_iterations.to_string());
                rows.push(row);
            }
        }
    }
    Table {
        title: "every run: errors relative to the exact impact (measure.rs) and the audit ratios"
            .into(),
        header,
        rows,
    }
}

/// The shown runs' histories and audits, one row of panels per configuration.
pub fn plot_histories(
    file: &BarsCase,
    ctx: &RunContext,
    report: &mut CaseReport,
    outcomes: &[Outcome],
) -> Result<(), String> {
    for (c, conf) in file.configurations.iter().enumerate() {
        let shown: Vec<&Outcome> = outcomes
            .iter()
            .filter(|o| o.job.record && o.job.configuration == c)
            .collect();
        if shown.is_empty() {
            continue;
        }
        let young = file.material.young;
        let exact = conf.exact(young);
        let t_end = shown
            .iter()
            .map(|o| o.level.final_time())
            .fold(0.0, f64::max);
        let fine: Vec<f64> = (0..=2000).map(|i| t_end * i as f64 / 2000.0).collect();
        let mut force = Vec::new();
        let mut velocity = Vec::new();
        let mut audits = Vec::new();
        for o in &shown {
            let Some((history, records)) = &o.history else {
                continue;
            };
            let fam = &file.families[o.job.family];
            let title = format!(
                "{} (M = {}, N = {})",
                fam.name, o.level.elements, o.level.steps
            );
            force.push(
                Figure::new(title.clone())
                    .x_label("t")
                    .y_label("N(t) = Σ λ_N: two-step mean (line), raw (markers)")
                    .series(
                        Series::line(
                            "computed, two-step mean",
                            history.iter().map(|h| (h.time, h.normal_force_mean)),
                        )
                        .color(1),
                    )
                    .series(
                        Series::markers(
                            "computed, raw (alternates)",
                            history.iter().map(|h| (h.time, h.normal_force)),
                        )
                        .color(2),
                    )
                    .series(
                        Series::line(
                            "exact A σ_c on (t0, t_end)",
                            fine.iter().map(|&t| (t, exact.contact_force(t))),
                        )
                        .color(0)
                        .dashed(),
                    ),
            );
            let mut fig = Figure::new(title.clone())
                .x_label("t")
                .y_label("centre velocities v_1, v_2 (x)");
            for b in 0..2 {
                fig = fig
                    .series(
                        Series::line(
                            format!("bar {} computed", b + 1),
                            history.iter().map(|h| (h.time, h.velocities[b][0])),
                        )
                        .color(1 + b),
                    )
                    .series(
                        Series::line(
                            format!("bar {} exact", b + 1),
                            fine.iter().map(|&t| (t, exact.centre_velocities(t)[b])),
                        )
                        .color(0)
                        .dashed(),
                    );
            }
            velocity.push(fig);
            audits.push(AuditRun {
                label: format!("{} M = {}", fam.name, o.level.elements),
                records: records.as_slice(),
            });
        }
        let columns = force.len().clamp(1, 3);
        let id = report.id.clone();
        ctx.panels(
            report,
            &format!("{}_contact_force", conf.name),
            &format!("{id} / {}: contact force against the exact", conf.name),
            &force,
            columns,
        )?;
        ctx.panels(
            report,
            &format!("{}_centre_velocity", conf.name),
            &format!(
                "{id} / {}: centre-of-mass velocities against the exact",
                conf.name
            ),
            &velocity,
            columns,
        )?;
        plot_audits(
            ctx,
            report,
            &conf.name,
            &format!("{id} / {}", conf.name),
            &audits,
        )?;
    }
    Ok(())
}

/// One log–log figure per (sweep, gated or listed error): every family of the sweep, the gates'
/// expected slopes.
pub fn plot_convergence(
    file: &BarsCase,
    ctx: &RunContext,
    report: &mut CaseReport,
    outcomes: &[Outcome],
) -> Result<(), String> {
    let mut keys: Vec<(String, String)> = Vec::new();
    let gated = file
        .gates
        .iter()
        .map(|g| (g.select.sweep.clone(), g.select.error.clone()));
    let listed = file
        .sweeps
        .iter()
        .flat_map(|s| s.plot.iter().map(|e| (s.name.clone(), e.clone())));
    for key in gated.chain(listed) {
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    let id = report.id.clone();
    for (sweep_name, error) in keys {
        let Some(sweep) = file.sweeps.iter().find(|s| s.name == sweep_name) else {
            continue;
        };
        let against = if sweep.against_k() { "k" } else { "h" };
        let mut fig = Figure::new(format!(
            "{id}: sweep `{sweep_name}`, {error} against {against}"
        ))
        .x_label(against)
        .y_label(error.as_str())
        .log_log();
        for (i, fam) in sweep.families.iter().enumerate() {
            let pts: Vec<(f64, f64)> = series(file, outcomes, &sweep_name, fam)
                .iter()
                .filter_map(|o| {
                    let e = o.measured.error(&error)?;
                    (e > 0.0).then_some((parameter(sweep, o), e))
                })
                .collect();
            fig = fig.series(Series::line_markers(fam.clone(), pts).color(i));
        }
        let mut slopes: Vec<f64> = Vec::new();
        for g in file
            .gates
            .iter()
            .filter(|g| g.select.sweep == sweep_name && g.select.error == error)
        {
            let r = g.criteria.expected_rate;
            if !slopes.iter().any(|s| (s - r).abs() < 1e-12) {
                slopes.push(r);
                fig = fig.reference_slope(r, format!("slope {r:.3}"));
            }
        }
        ctx.plot(report, &format!("convergence_{sweep_name}_{error}"), &fig)?;
    }
    Ok(())
}
