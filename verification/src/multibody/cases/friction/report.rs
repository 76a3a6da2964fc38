//! The friction case's tables and plots: the closed form and the elastic scales, every level,
//! the Newmark run; the velocities against the closed form, the slipping and sticking node
//! counts, the dissipated energy against μ N s, the errors against k and the audit.

use contactlab::model::multibody::scheme::MultibodyScheme;

use crate::core::context::RunContext;
use crate::core::report::case_report::{CaseReport, Table};
use crate::multibody::cases::friction::format::FrictionCase;
use crate::multibody::cases::friction::run::Run;
use crate::multibody::cases::friction::setup::Setting;
use crate::multibody::study::{plot_audits, AuditRun};
use crate::plot::{Figure, Series};

fn strings<const N: usize>(v: [&str; N]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

/// The case's tables.
pub fn tables(
    file: &FrictionCase,
    setting: &Setting,
    runs: &[Run],
    newmark: Option<&Result<Run, String>>,
    report: &mut CaseReport,
) {
    let b = &file.blocks;
    let e = b.exact();
    report.tables.push(Table {
        title: "the rigid two-block slide (exact/two_block_slide.rs) and the elastic scales".into(),
        header: strings([
            "m₁",
            "m₂",
            "μ",
            "w₀",
            "a = μ g (1 + m₁/m₂)",
            "t*",
            "s*",
            "D* = ½ m_r w₀²",
            "δ_s (shear lag)",
            "compression",
            "static Newton it.",
        ]),
        rows: vec![vec![
            format!("{}", e.upper_mass),
            format!("{}", e.lower_mass),
            format!("{}", e.friction),
            format!("{}", e.initial_relative_velocity()),
            format!("{}", e.relative_deceleration()),
            format!("{}", e.stop_time()),
            format!("{}", e.stop_distance()),
            format!("{}", e.total_dissipation()),
            format!("{:.3e}", b.shear_lag()),
            format!("{:.3e}", b.compression()),
            setting.static_iterations.to_string(),
        ]],
    });
    let row = |r: &Run| {
        let x = |k: &str| format!("{:.3e}", r.errors[k]);
        vec![
            r.scheme.name().to_string(),
            r.steps.to_string(),
            format!("{:.4e}", r.k),
            format!("{:.4}", r.predicted.phase),
            r.predicted.last_sliding_step.to_string(),
            r.last_sliding_step.to_string(),
            x("stop_time_error"),
            x("stop_velocity"),
            x("deceleration_error"),
            x("invariant_error"),
            x("velocity_error"),
            x("vertical_velocity"),
            x("dissipation_error"),
            x("dissipation_discrete"),
            x("dissipation_friction"),
            format!(
                "{:.2}",
                r.errors["slip_after_stop"] / file.blocks.shear_lag()
            ),
            format!("{}", r.errors["settled_step"]),
            x("slip_after_settling"),
            format!(
                "{:.2}",
                r.stats.newton_iterations as f64 / r.stats.steps.max(1) as f64
            ),
            r.stats.floor_stops.to_string(),
            format!("{:.2}", r.seconds),
        ]
    };
    let header = strings([
        "scheme",
        "N",
        "k",
        "θ",
        "stop step (rigid)",
        "stop step",
        "stop_time_error",
        "stop_velocity",
        "deceleration_error",
        "invariant_error",
        "velocity_error",
        "vertical_velocity",
        "dissipation_error",
        "dissipation_discrete",
        "dissipation_friction",
        "slip_after_stop / δ_s",
        "settled step",
        "slip_after_settling",
        "Newton it./step",
        "floor stops",
        "CPU (s)",
    ]);
    report.tables.push(Table {
        title: "every level (errors defined in run.rs; the stop steps are n_s − 1)".into(),
        header: header.clone(),
        rows: runs.iter().map(row).collect(),
    });
    if let Some(n) = newmark {
        let rows = match n {
            Ok(r) => vec![row(r)],
            Err(e) => vec![vec![format!("newmark: {e}")]],
        };
        report.tables.push(Table {
            title: "Newmark at the shown level (reported, not gated): its initial acceleration \
                    M⁻¹(f − F_int(u₀)) leaves out the equilibrium's contact forces, and the \
                    trapezoidal rule carries that error undamped (the normal force alternates)"
                .into(),
            header,
            rows,
        });
    }
}

/// The case's plots.
pub fn plots(
    file: &FrictionCase,
    ctx: &RunContext,
    report: &mut CaseReport,
    runs: &[Run],
) -> Result<(), String> {
    let id = report.id.clone();
    let exact = file.blocks.exact();
    let shown: Vec<&Run> = runs.iter().filter(|r| r.steps == file.sweep.show).collect();
    let t_end = file.sweep.duration * exact.stop_time();
    let ts: Vec<f64> = (0..=400).map(|i| t_end * i as f64 / 400.0).collect();
    let t_star = exact.stop_time();
    // velocities against the closed form
    let mut rel = Figure::new("relative velocity w = v₁ − v₂")
        .x_label("t")
        .y_label("w")
        .vertical_line(t_star, "t*");
    let mut each = Figure::new("centre velocities")
        .x_label("t")
        .y_label("v_x")
        .vertical_line(t_star, "t*");
    let mut counts = Figure::new("interface nodes")
        .x_label("t")
        .y_label("slipping / sticking nodes")
        .vertical_line(t_star, "t*");
    let mut diss = Figure::new("dissipated energy")
        .x_label("t")
        .y_label("D")
        .vertical_line(t_star, "t*");
    for (i, r) in shown.iter().enumerate() {
        let name = format!("{} (N = {})", r.scheme.name(), r.steps);
        let dashed = |s: Series| if i > 0 { s.dashed() } else { s };
        rel = rel.series(dashed(
            Series::line(
                name.clone(),
                r.rows.iter().map(|x| (x.time, x.upper[0] - x.lower[0])),
            )
            .color(2 * i),
        ));
        each = each
            .series(dashed(
                Series::line(
                    format!("{name}: upper"),
                    r.rows.iter().map(|x| (x.time, x.upper[0])),
                )
                .color(2 * i),
            ))
            .series(dashed(
                Series::line(
                    format!("{name}: lower"),
                    r.rows.iter().map(|x| (x.time, x.lower[0])),
                )
                .color(2 * i + 1),
            ));
        counts = counts
            .series(dashed(
                Series::line(
                    format!("{name}: slipping"),
                    r.rows.iter().skip(1).map(|x| (x.time, x.slipping as f64)),
                )
                .color(2 * i),
            ))
            .series(dashed(
                Series::line(
                    format!("{name}: sticking"),
                    r.rows.iter().skip(1).map(|x| (x.time, x.sticking as f64)),
                )
                .color(2 * i + 1),
            ));
        let e0 = r.rows[0].energy;
        let mut w = 0.0;
        let mut acc = 0.0;
        let cumulative: Vec<(f64, f64)> = r
            .rows
            .iter()
            .map(|x| {
                acc += x.dissipation;
                (x.time, acc)
            })
            .collect();
        diss = diss
            .series(dashed(
                Series::line(
                    format!("{name}: E₀ − E + W_g"),
                    r.rows.iter().map(|x| {
                        w += x.external_work;
                        (x.time, e0 - x.energy + w)
                    }),
                )
                .color(2 * i),
            ))
            .series(
                Series::markers(
                    format!("{name}: μ Σ λ_N |slip|"),
                    cumulative.iter().step_by((r.steps / 40).max(1)).copied(),
                )
                .color(2 * i + 1),
            );
    }
    rel = rel.series(
        Series::line("exact", ts.iter().map(|&t| (t, exact.relative_velocity(t))))
            .color(6)
            .dashed(),
    );
    each = each
        .series(
            Series::line(
                "exact: upper",
                ts.iter().map(|&t| (t, exact.velocities(t)[0])),
            )
            .color(6)
            .dashed(),
        )
        .series(
            Series::line(
                "exact: lower",
                ts.iter().map(|&t| (t, exact.velocities(t)[1])),
            )
            .color(7)
            .dashed(),
        );
    diss = diss.series(
        Series::line(
            "μ N s(t) (exact)",
            ts.iter().map(|&t| (t, exact.dissipation(t))),
        )
        .color(6)
        .dashed(),
    );
    ctx.panels(
        report,
        "histories",
        &format!(
            "{id}: the shown level against the closed form (velocities, node states, dissipation)"
        ),
        &[rel, each, counts, diss],
        2,
    )?;
    // convergence in k
    let errors: Vec<Figure> = [("stop_time_error", 1.0), ("dissipation_error", 2.0)]
        .iter()
        .map(|&(e, slope)| {
            let mut fig = Figure::new(e).x_label("k").y_label(e).log_log();
            for (i, &s) in file.sweep.schemes.iter().enumerate() {
                let pts: Vec<(f64, f64)> = runs
                    .iter()
                    .filter(|r| r.scheme == s)
                    .map(|r| (r.k, r.errors[e]))
                    .collect();
                let series = Series::line_markers(s.name().to_string(), pts).color(i);
                fig = fig.series(if s == MultibodyScheme::Midpoint {
                    series.dashed()
                } else {
                    series
                });
            }
            fig.reference_slope(slope, format!("slope {slope}"))
        })
        .collect();
    ctx.panels(
        report,
        "convergence",
        &format!("{id}: the stop time and the dissipation against k"),
        &errors,
        2,
    )?;
    let audits: Vec<AuditRun<'_>> = shown
        .iter()
        .map(|r| AuditRun {
            label: format!("{} (N = {})", r.scheme.name(), r.steps),
            records: &r.records,
        })
        .collect();
    plot_audits(ctx, report, "friction", &id, &audits)
}
