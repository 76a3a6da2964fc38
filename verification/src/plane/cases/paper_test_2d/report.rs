//! The tables and pictures of `plane_paper_test_2d`: every run's numbers, the GCI analysis of
//! every quantity, our mesh-converged values beside the paper's Figs 14–15, the deformed meshes
//! (cf. Figs 11–13), the von Mises field (cf. Fig 14) and the contact lines (cf. Fig 15).

use contactlab::model::quasistatic::plane_output::PlaneSolution;

use super::format::{PaperTestSpec, Quantity, Reading};
use super::gates::{gci_of, series};
use super::runs::PaperTestRun;
use crate::core::context::RunContext;
use crate::core::report::case_report::{CaseReport, Table};
use crate::plot::{Figure, Outline, Series, TriangleField, TriangleMeshPlot};
use crate::stats::gci::GciResult;

/// A quantity whose values are all this small (m or N/m²) has no relative GCI.
const NEGLIGIBLE: f64 = 1e-6;

/// Formal order used for the tables' GCI (first order: the element stresses and, conservatively,
/// the contact line; the gates state their own).
const TABLE_ORDER: f64 = 1.0;

/// The GCI of one series, or why there is none.
fn analysis(values: &[f64], ratio: f64) -> Result<GciResult, String> {
    if values.iter().all(|v| v.abs() < NEGLIGIBLE) {
        return Err(format!("≈ 0 on every mesh (|f| < {NEGLIGIBLE:e})"));
    }
    gci_of(values, ratio, TABLE_ORDER)
}

/// "finest (extrapolated ± GCI band)" or the reason there is no limit.
fn converged(values: &[f64], ratio: f64) -> String {
    let finest = values.last().copied().unwrap_or(f64::NAN);
    match analysis(values, ratio) {
        Ok(r) => match (r.extrapolated, r.gci_fine_percent) {
            (Some(x), Some(g)) if r.convergence != crate::stats::gci::Convergence::Divergent => {
                format!("{finest:.4} (limit ≈ {x:.4}, GCI {g:.2}%)")
            }
            _ => format!("{finest:.4} (no mesh limit: {:?})", r.convergence),
        },
        Err(e) => format!("{finest:.4} ({e})"),
    }
}

/// The tables.
pub fn tables(report: &mut CaseReport, spec: &PaperTestSpec, runs: &[PaperTestRun]) {
    let ratio = spec.ratio();
    report.tables.push(Table {
        title: "Test 2D at T, every run (k = 0.01, explicit scheme as in the paper; the rollers' closed form of the mean sinking: see the gate)".into(),
        header: [
            "reading", "mesh", "β", "skipped steps", "von Mises min", "von Mises max",
            "contact line min", "contact line max", "mean u_y on Γ3", "closed form",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows: runs
            .iter()
            .map(|r| {
                vec![
                    r.reading.name().to_string(),
                    format!("{0}×{0}", r.divisions),
                    format!("{}", r.beta),
                    format!("{}", r.skipped_steps.len()),
                    format!("{:.4}", r.von_mises_min),
                    format!("{:.4}", r.von_mises_max),
                    format!("{:.5}", r.contact_line_min),
                    format!("{:.5}", r.contact_line_max),
                    format!("{:.8}", r.contact_line_mean),
                    r.sinking_closed_form.map_or("—".into(), |c| format!("{c:.8}")),
                ]
            })
            .collect(),
    });
    let opt = |v: Option<f64>, d: usize| v.map_or("—".into(), |v| format!("{v:.d$}"));
    let mut rows = Vec::new();
    for reading in Reading::ALL {
        for &beta in &spec.betas {
            for q in Quantity::ALL {
                let values = series(runs, &spec.meshes, reading, beta, q);
                let mut row = vec![
                    reading.name().to_string(),
                    format!("{beta}"),
                    q.name().to_string(),
                    values
                        .iter()
                        .map(|v| format!("{v:.4}"))
                        .collect::<Vec<_>>()
                        .join(", "),
                ];
                match analysis(&values, ratio) {
                    Ok(r) => row.extend([
                        format!("{:?}", r.convergence),
                        opt(r.order, 3),
                        opt(r.coarse_order, 3),
                        opt(r.extrapolated, 5),
                        opt(r.gci_fine_percent, 3),
                        opt(r.asymptotic_ratio, 3),
                    ]),
                    Err(e) => row.extend([
                        e,
                        "—".into(),
                        "—".into(),
                        "—".into(),
                        "—".into(),
                        "—".into(),
                    ]),
                }
                rows.push(row);
            }
        }
    }
    report.tables.push(Table {
        title: format!(
            "mesh convergence of every quantity (meshes {:?}, ratio {ratio}): observed order p (finest three), p_c (next three), Richardson limit, GCI of the finest mesh (F_s = 1.25 with p when p ∈ [½, 2], else the formal order 1 with F_s = 3), asymptotic ratio A",
            spec.meshes
        ),
        header: [
            "reading", "β", "quantity", "values (coarse → fine)", "convergence", "p", "p_c",
            "limit", "GCI_fine (%)", "A",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
    // beside the paper
    let vb = spec.von_mises_beta;
    let mut rows = vec![
        vec![
            format!("von Mises max at T, β = {vb} (Fig 14)"),
            format!("{}", spec.paper_von_mises[1]),
            converged(
                &series(
                    runs,
                    &spec.meshes,
                    Reading::Rollers,
                    vb,
                    Quantity::VonMisesMax,
                ),
                ratio,
            ),
            converged(
                &series(
                    runs,
                    &spec.meshes,
                    Reading::Clamped,
                    vb,
                    Quantity::VonMisesMax,
                ),
                ratio,
            ),
        ],
        vec![
            format!("von Mises min at T, β = {vb} (Fig 14)"),
            format!("{}", spec.paper_von_mises[0]),
            converged(
                &series(
                    runs,
                    &spec.meshes,
                    Reading::Rollers,
                    vb,
                    Quantity::VonMisesMin,
                ),
                ratio,
            ),
            converged(
                &series(
                    runs,
                    &spec.meshes,
                    Reading::Clamped,
                    vb,
                    Quantity::VonMisesMin,
                ),
                ratio,
            ),
        ],
    ];
    for &beta in &spec.betas {
        rows.push(vec![
            format!("lowest point of the contact line at T, β = {beta} (Fig 15)"),
            format!(
                "lowest line ≈ {} (β not legible)",
                spec.paper_contact_lowest
            ),
            converged(
                &series(
                    runs,
                    &spec.meshes,
                    Reading::Rollers,
                    beta,
                    Quantity::ContactLineMin,
                ),
                ratio,
            ),
            converged(
                &series(
                    runs,
                    &spec.meshes,
                    Reading::Clamped,
                    beta,
                    Quantity::ContactLineMin,
                ),
                ratio,
            ),
        ]);
    }
    report.tables.push(Table {
        title: "beside the paper: our values on the finest mesh with their mesh limit and GCI, under each reading of Γ1 (not gated against the paper; the differences are discussed in the explanation)".into(),
        header: ["quantity", "paper", "rollers (u_x = 0)", "clamped (u = 0)"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
        rows,
    });
}

/// The pictures: deformed meshes and the von Mises field on `figure_mesh`, contact lines on the
/// finest mesh, and the compared quantities against the mesh with the paper's values.
pub fn plots(
    ctx: &RunContext,
    report: &mut CaseReport,
    spec: &PaperTestSpec,
    runs: &[PaperTestRun],
    figures: &[(Reading, f64, usize, PlaneSolution)],
) -> Result<(), String> {
    let find = |reading: Reading, beta: f64, n: usize| {
        figures
            .iter()
            .find(|(r, b, m, _)| *r == reading && *b == beta && *m == n)
            .map(|f| &f.3)
    };
    let finest = *spec.meshes.last().unwrap_or(&spec.figure_mesh);
    for reading in Reading::ALL {
        let label = match reading {
            Reading::Rollers => "rollers (u_x = 0 on the sides)",
            Reading::Clamped => "clamped sides",
        };
        let n = spec.figure_mesh;
        let mut panels = Vec::new();
        for &beta in &[10.0, 100.0, 1000.0] {
            if let Some(sol) = find(reading, beta, n) {
                let snap = &sol.snapshots[0];
                panels.push(
                    TriangleMeshPlot::new(
                        format!("β = {beta}: deformed mesh at T"),
                        sol.deformed(snap),
                        sol.triangles.clone(),
                    )
                    .wireframe(true)
                    .outline(
                        Outline::new(
                            "initial boundary",
                            [[0.0, 0.0], [6.0, 0.0], [6.0, 6.0], [0.0, 6.0]],
                        )
                        .closed()
                        .dashed(),
                    ),
                );
            }
        }
        if !panels.is_empty() {
            ctx.triangle_panels(
                report,
                &format!("deformed_{}", reading.name()),
                &format!(
                    "{label}, {n}×{n}: initial boundary and deformed meshes at T (cf. Figs 11–13)"
                ),
                &panels,
                3,
            )?;
        }
        if let Some(sol) = find(reading, spec.von_mises_beta, n) {
            let snap = &sol.snapshots[0];
            let plot = TriangleMeshPlot::new(
                format!(
                    "{label}, {n}×{n}, β = {}: von Mises norm at T on the deformed body (cf. Fig 14: {}–{})",
                    spec.von_mises_beta, spec.paper_von_mises[0], spec.paper_von_mises[1]
                ),
                sol.deformed(snap),
                sol.triangles.clone(),
            )
            .field(TriangleField::per_triangle("|σ| (N/m²)", snap.von_mises.iter().copied()));
            ctx.triangle_panels(
                report,
                &format!("von_mises_{}", reading.name()),
                &plot.title.clone(),
                &[plot],
                1,
            )?;
        }
        let mut fig = Figure::new(format!(
            "{label}, {finest}×{finest}: contact boundary at T (cf. Fig 15)"
        ))
        .x_label("x (m)")
        .y_label("u_y on Γ3 (m)")
        .horizontal_line(spec.paper_contact_lowest, "the paper's lowest line");
        for (i, &beta) in spec.betas.iter().enumerate() {
            if let Some(sol) = find(reading, beta, finest) {
                let snap = &sol.snapshots[0];
                let mut pts: Vec<(f64, f64)> = sol
                    .contact_nodes
                    .iter()
                    .map(|&k| (sol.nodes[k][0], snap.u[2 * k + 1]))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                fig = fig.series(Series::line_markers(format!("β = {beta}"), pts).color(i));
            }
        }
        ctx.plot(report, &format!("contact_lines_{}", reading.name()), &fig)?;
    }
    // the von Mises range against the mesh, beside Fig 14
    for (q, paper) in [
        (Quantity::VonMisesMax, spec.paper_von_mises[1]),
        (Quantity::VonMisesMin, spec.paper_von_mises[0]),
    ] {
        let mut fig = Figure::new(format!(
            "{} at T (β = {}) against the mesh, beside the paper's Fig 14",
            q.name(),
            spec.von_mises_beta
        ))
        .x_label("squares per side")
        .y_label("N/m²")
        .horizontal_line(paper, "paper, Fig 14");
        for (i, reading) in Reading::ALL.iter().enumerate() {
            let values = series(runs, &spec.meshes, *reading, spec.von_mises_beta, q);
            let pts: Vec<(f64, f64)> = spec.meshes.iter().map(|&n| n as f64).zip(values).collect();
            fig = fig.series(Series::line_markers(reading.name(), pts).color(i));
        }
        ctx.plot(
            report,
            &format!("{}_vs_mesh", q.name().replace(' ', "_")),
            &fig,
        )?;
    }
    Ok(())
}
