//! The friction case's tables and plots: the closed-form values of each family, every level of
//! the sliding block and every run of the loaded block; the slip and velocity histories against
//! the exact ones, the errors against k, and the per-step checks of the loaded block.

use crate::core::context::RunContext;
use crate::core::report::case_report::{CaseReport, Table};
use crate::dynamic::cases::friction::format::FrictionCase;
use crate::dynamic::cases::friction::loaded::{LoadedRun, TOLERANCE};
use crate::dynamic::cases::friction::slide::SlideRun;
use crate::plot::{Figure, Series};

fn strings<const N: usize>(v: [&str; N]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

/// The case's tables.
pub fn tables(
    file: &FrictionCase,
    slide: &[SlideRun],
    loaded: &[LoadedRun],
    report: &mut CaseReport,
) {
    if let Some(spec) = &file.slide {
        let rows = spec
            .runs(&file.families)
            .iter()
            .map(|f| {
                let b = spec.block(f);
                vec![
                    f.name.clone(),
                    format!("{}", b.equilibrium_penetration()),
                    format!("{}", b.friction_coefficient()),
                    format!("{}", b.normal_force()),
                    format!("{}", b.deceleration()),
                    format!("{}", b.stop_time()),
                    format!("{}", b.stop_distance()),
                    format!("{:e}", b.shear_lag()),
                ]
            })
            .collect();
        report.tables.push(Table {
            title: "sliding block: the closed form per family (exact/sliding_block.rs)".into(),
            header: strings(["family", "η", "μ(η)", "N", "a = μN/m", "t*", "s*", "δ_s"]),
            rows,
        });
        report.tables.push(Table {
            title: "sliding block: every level (θ = frac(t*/k); the stop steps are n_s − 1)".into(),
            header: strings([
                "family",
                "N",
                "k",
                "θ",
                "stop step (rigid midpoint)",
                "stop step",
                "stop_time_error",
                "stop_distance_error",
                "post_stop_velocity",
                "slip_after_stop",
                "slide_velocity_error",
                "penetration_deviation",
                "Newton it./step",
            ]),
            rows: slide
                .iter()
                .map(|r| {
                    let e = |k: &str| format!("{:.3e}", r.errors[k]);
                    vec![
                        r.family.clone(),
                        r.steps.to_string(),
                        format!("{:.4e}", r.k),
                        format!("{:.4}", r.predicted.phase),
                        r.predicted.last_sliding_step.to_string(),
                        r.last_sliding_step.to_string(),
                        e("stop_time_error"),
                        e("stop_distance_error"),
                        e("post_stop_velocity"),
                        e("slip_after_stop"),
                        e("slide_velocity_error"),
                        e("penetration_deviation"),
                        format!(
                            "{:.2}",
                            r.stats.newton_iterations as f64 / r.stats.steps.max(1) as f64
                        ),
                    ]
                })
                .collect(),
        });
    }
    if !loaded.is_empty() {
        let opt = |v: Option<f64>| v.map_or("—".to_string(), |x| format!("{x:.3e}"));
        report.tables.push(Table {
            title: format!(
                "loaded block: every run (|R_i| / (τ s + 64 ε A_i) ≤ 1 per row, τ = {TOLERANCE:e})"
            ),
            header: strings([
                "family",
                "N",
                "k",
                "rigid t*",
                "max R_i / (τ s + 64 ε A_i)",
                "stick excess",
                "slides forward until",
                "max J error / (m v0)",
                "its allowance",
                "penetration range",
                "Newton it./step",
            ]),
            rows: loaded
                .iter()
                .map(|r| {
                    vec![
                        r.family.clone(),
                        r.steps.to_string(),
                        format!("{:.4e}", r.k),
                        format!("{:.4}", r.rigid_stop_time),
                        format!("{:.3e}", r.max_residual),
                        opt(r.max_stick_excess),
                        format!("{:.4}", r.all_slide_until),
                        opt(r.invariant_error),
                        opt(r.invariant_allowance),
                        format!(
                            "[{:.4e}, {:.4e}]",
                            r.penetration_range[0], r.penetration_range[1]
                        ),
                        format!(
                            "{:.2}",
                            r.stats.newton_iterations as f64 / r.stats.steps.max(1) as f64
                        ),
                    ]
                })
                .collect(),
        });
    }
}

/// The case's plots.
pub fn plots(
    file: &FrictionCase,
    ctx: &RunContext,
    report: &mut CaseReport,
    slide: &[SlideRun],
    loaded: &[LoadedRun],
) -> Result<(), String> {
    let id = report.id.clone();
    if let Some(spec) = &file.slide {
        let families = spec.runs(&file.families);
        let mut histories = Vec::new();
        for f in &families {
            let b = spec.block(f);
            let Some(r) = slide
                .iter()
                .filter(|r| r.family == f.name)
                .max_by_key(|r| r.steps)
            else {
                continue;
            };
            let t_end = r.history.last().map_or(0.0, |h| h[0]);
            let exact_t: Vec<f64> = (0..=400).map(|i| t_end * i as f64 / 400.0).collect();
            histories.push(
                Figure::new(format!("{} (N = {}): slip", f.name, r.steps))
                    .x_label("t")
                    .y_label("mean slip of the contact nodes")
                    .series(Series::line(
                        "computed",
                        r.history.iter().map(|h| (h[0], h[1])),
                    ))
                    .series(
                        Series::line("exact", exact_t.iter().map(|&t| (t, b.slip(t))))
                            .dashed()
                            .color(1),
                    ),
            );
            histories.push(
                Figure::new(format!("{} (N = {}): velocity", f.name, r.steps))
                    .x_label("t")
                    .y_label("P_x / m")
                    .series(Series::line(
                        "computed",
                        r.history.iter().map(|h| (h[0], h[2])),
                    ))
                    .series(
                        Series::line("exact", exact_t.iter().map(|&t| (t, b.velocity(t))))
                            .dashed()
                            .color(1),
                    ),
            );
        }
        ctx.panels(
            report,
            "slide_histories",
            &format!("{id}: the sliding block at its finest level against the closed form"),
            &histories,
            2,
        )?;
        let errors: Vec<Figure> = [
            "stop_time_error",
            "stop_distance_error",
            "post_stop_velocity",
        ]
        .iter()
        .map(|e| {
            let mut fig = Figure::new(*e).x_label("k").y_label(*e).log_log();
            for (i, f) in families.iter().enumerate() {
                fig = fig.series(
                    Series::line_markers(
                        f.name.clone(),
                        slide
                            .iter()
                            .filter(|r| r.family == f.name)
                            .map(|r| (r.k, r.errors[*e])),
                    )
                    .color(i),
                );
            }
            fig.reference_slope(
                if *e == "stop_distance_error" {
                    2.0
                } else {
                    1.0
                },
                "",
            )
        })
        .collect();
        ctx.panels(
            report,
            "slide_convergence",
            &format!("{id}: the sliding block's errors against k"),
            &errors,
            3,
        )?;
    }
    if !loaded.is_empty() {
        let mut fig = Figure::new("max_i |R_i| / (τ s + 64 ε A_i) per step")
            .x_label("t")
            .y_label("residual / allowance")
            .semilog_y();
        for (i, r) in loaded.iter().enumerate() {
            fig = fig.series(
                Series::line(
                    format!("{} (N = {})", r.family, r.steps),
                    r.history.iter().map(|h| (h[0], h[1].max(1e-18))),
                )
                .color(i),
            );
        }
        let mut figures = vec![fig.horizontal_line(1.0, "allowance")];
        let mut j = Figure::new("|J_n − J(t_n)| / (m v0) while every node slides forward")
            .x_label("t")
            .y_label("error")
            .semilog_y();
        let mut any = false;
        for (i, r) in loaded.iter().enumerate() {
            if r.invariant_error.is_some() {
                any = true;
                j = j.series(
                    Series::line(
                        format!("{} (N = {})", r.family, r.steps),
                        r.history
                            .iter()
                            .filter(|h| h[0] <= r.all_slide_until)
                            .map(|h| (h[0], h[2].max(1e-18))),
                    )
                    .color(i),
                );
            }
        }
        if any {
            figures.push(j);
        }
        ctx.panels(
            report,
            "loaded_checks",
            &format!("{id}: the loaded block, step by step"),
            &figures,
            2,
        )?;
    }
    Ok(())
}
