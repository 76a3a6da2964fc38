//! The figures and tables of the patch test: the contact pressure along the interface, the
//! element stress error maps, the per-mesh table, the refinement and the pressure studies.

use crate::core::context::RunContext;
use crate::core::report::case_report::{CaseReport, Table};
use crate::exact::contact_patch::ContactPatch;
use crate::multibody::cases::patch::measure::PatchErrors;
use crate::multibody::cases::patch::setup::{Passes, PatchMesh, PatchRun};
use crate::plot::{Figure, Series, TriangleField, TriangleMeshPlot};

/// The errors drawn at this value when they are exactly zero (log axes).
const FLOOR: f64 = 1e-17;

/// A measured run (its errors) of one mesh and one enforcement.
pub struct Measured {
    pub mesh: PatchMesh,
    pub passes: Passes,
    pub errors: PatchErrors,
}

/// A table header cell: '|' would end a Markdown cell (headers are not escaped), so the bars of
/// |·| are drawn as '∣'.
fn header(s: &str) -> String {
    s.replace('|', "∣")
}

fn sci(v: f64) -> String {
    format!("{v:.2e}")
}

/// The per-mesh table: every enforcement's errors (relative: module docs of `measure`).
pub fn mesh_table(
    report: &mut CaseReport,
    runs: &[Measured],
    roundoff: &dyn Fn(&PatchMesh) -> f64,
) {
    let rows = runs
        .iter()
        .map(|m| {
            let e = &m.errors;
            vec![
                m.mesh.ratio(),
                m.passes.label().to_string(),
                sci(e.stress_max),
                sci(e.stress_l2),
                sci(e.displacement_max),
                sci(e.interface_force_max),
                e.pressure_max.map_or("—".into(), sci),
                sci(e.total_force),
                sci(e.gap_max),
                format!("{}", e.inactive),
                format!("{}", e.iterations),
                sci(roundoff(&m.mesh)),
            ]
        })
        .collect();
    report.tables.push(Table {
        title: "The patch test per mesh ratio n_A:n_B (same material): errors relative to p, to max|u| or to p L"
            .into(),
        header: [
            "n_A:n_B",
            "enforcement",
            "max |σ − σ*|/p",
            "‖σ − σ*‖_L2/p",
            "max |u − u*|/max|u*|",
            "max |f_i − p w_i|/(p w)",
            "max |λ_i/w_i − p|/p",
            "|Σλ − pL|/(pL)",
            "max |g|/max|u*|",
            "inactive",
            "Newton iterations",
            "round-off bound",
        ]
        .iter()
        .map(|s| header(s))
        .collect(),
        rows,
    });
}

/// The contact pressure along the interface on one mesh: λ_i/w_i of every pass (B's nodes
/// slaves on A: pass 1; A's on B: pass 2) and the nodal traction f_i/w_i assembled from them,
/// against p.
pub fn pressure_figures(patch: &ContactPatch, runs: &[&Measured]) -> Vec<Figure> {
    let p = patch.pressure;
    let mut multipliers = Figure::new("multipliers λ_i / w_i along the interface")
        .x_label("x (reference)")
        .y_label("λ_i / (w_i p)")
        .horizontal_line(1.0, "p");
    let mut tractions = Figure::new("nodal traction f_i / w_i assembled from the multipliers")
        .x_label("x (reference)")
        .y_label("f_i / (w_i p)")
        .horizontal_line(1.0, "p");
    for (i, m) in runs.iter().enumerate() {
        let label = m.passes.label();
        for pass in 0..2 {
            let mut pts: Vec<(f64, f64)> = m
                .errors
                .pressures
                .iter()
                .filter(|q| q.pair == pass)
                .map(|q| (q.x, q.pressure / p))
                .collect();
            if pts.is_empty() {
                continue;
            }
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let name = match m.passes {
                Passes::Two => format!("{label}: pass {}", pass + 1),
                _ => label.to_string(),
            };
            let s = Series::line_markers(name, pts).color(2 * i + pass);
            multipliers = multipliers.series(if pass == 1 { s.dashed() } else { s });
        }
        for (b, side) in ["A's top", "B's bottom"].iter().enumerate() {
            let mut pts: Vec<(f64, f64)> = m.errors.tractions[b]
                .iter()
                .map(|&(x, t)| (x, t / p))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let s = Series::line_markers(format!("{label}: {side}"), pts).color(2 * i + b);
            tractions = tractions.series(if b == 0 { s.dashed() } else { s });
        }
    }
    vec![multipliers, tractions]
}

/// The element stress error max |σ − σ*|/p of both blocks, log10, on the reference mesh (the
/// upper block drawn above the lower one).
pub fn stress_map(run: &PatchRun, errors: &PatchErrors, title: &str) -> TriangleMeshPlot {
    let bodies = &run.solver.problem().bodies;
    let mut nodes = Vec::new();
    let mut triangles = Vec::new();
    let mut values = Vec::new();
    for b in 0..2 {
        let mesh = &bodies.body(b).data().mesh;
        let offset = nodes.len();
        nodes.extend_from_slice(mesh.nodes());
        triangles.extend(
            mesh.triangles()
                .iter()
                .map(|t| [t[0] + offset, t[1] + offset, t[2] + offset]),
        );
        values.extend(
            errors.element_errors[b]
                .iter()
                .map(|v| v.max(FLOOR).log10()),
        );
    }
    TriangleMeshPlot::new(title, nodes, triangles)
        .field(TriangleField::per_triangle("log10 max|σ − σ*|/p", values))
        .wireframe(true)
}

/// Writes the pressure figures and the stress maps of the first mesh's runs.
pub fn plot_mesh(
    ctx: &RunContext,
    report: &mut CaseReport,
    patch: &ContactPatch,
    shown: &[(PatchRun, Measured)],
) -> Result<(), String> {
    let Some(first) = shown.first() else {
        return Ok(());
    };
    let ratio = first.1.mesh.ratio();
    let measured: Vec<&Measured> = shown.iter().map(|(_, m)| m).collect();
    ctx.panels(
        report,
        "pressure",
        &format!(
            "{ratio}: the contact pressure along the interface — the multipliers of each pass (left; two-pass: not unique at the two shared end nodes) and the nodal traction they assemble to (right; unique)"
        ),
        &pressure_figures(patch, &measured),
        2,
    )?;
    let maps: Vec<TriangleMeshPlot> = shown
        .iter()
        .map(|(run, m)| stress_map(run, &m.errors, m.passes.label()))
        .collect();
    ctx.triangle_panels(
        report,
        "stress_error",
        &format!("{ratio}: element stress error log10 max|σ − σ*|/p (A below, B above y = 1)"),
        &maps,
        maps.len(),
    )
}

/// Reads one error of a run.
type ErrorOf = fn(&PatchErrors) -> f64;

/// The refinement study's figure: each error of single-pass and two-pass against h.
pub fn refinement_figure(levels: &[(f64, Measured, Measured)]) -> Figure {
    let mut fig = Figure::new("refinement of both meshes at a fixed ratio")
        .x_label("h_min")
        .y_label("error")
        .log_log()
        .reference_slope(0.5, "h^1/2")
        .reference_slope(1.0, "h");
    let series: [(&str, ErrorOf); 4] = [
        ("max |σ − σ*|/p", |e| e.stress_max),
        ("‖σ − σ*‖_L2/p", |e| e.stress_l2),
        ("max |u − u*|/max|u*|", |e| e.displacement_max),
        ("max |λ_i/w_i − p|/p", |e| e.pressure_max.unwrap_or(0.0)),
    ];
    for (i, (name, f)) in series.iter().enumerate() {
        fig = fig.series(
            Series::line_markers(
                format!("single-pass: {name}"),
                levels.iter().map(|(h, s, _)| (*h, f(&s.errors).max(FLOOR))),
            )
            .color(i),
        );
        if i < 3 {
            fig = fig.series(
                Series::line_markers(
                    format!("two-pass: {name}"),
                    levels.iter().map(|(h, _, t)| (*h, f(&t.errors).max(FLOOR))),
                )
                .color(i)
                .dashed(),
            );
        }
    }
    fig
}

/// The refinement table.
pub fn refinement_table(report: &mut CaseReport, levels: &[(f64, Measured, Measured)]) {
    let rows = levels
        .iter()
        .map(|(h, s, t)| {
            vec![
                s.mesh.ratio(),
                format!("{h:.4}"),
                sci(s.errors.stress_max),
                sci(s.errors.stress_l2),
                sci(s.errors.displacement_max),
                s.errors.pressure_max.map_or("—".into(), sci),
                sci(t.errors.stress_max),
                sci(t.errors.displacement_max),
            ]
        })
        .collect();
    report.tables.push(Table {
        title: "Refinement of both meshes at a fixed ratio: single-pass (B slave) and two-pass"
            .into(),
        header: [
            "n_A:n_B",
            "h_min",
            "single: max |σ − σ*|/p",
            "single: ‖σ − σ*‖_L2/p",
            "single: max |u − u*|/max|u*|",
            "single: max |λ_i/w_i − p|/p",
            "two-pass: max |σ − σ*|/p",
            "two-pass: max |u − u*|/max|u*|",
        ]
        .iter()
        .map(|s| header(s))
        .collect(),
        rows,
    });
}

/// One pressure of the materials study: p, the lateral strain mismatch, and the two-pass errors
/// with the different materials and with equal lateral strains.
pub struct PressureLevel {
    pub pressure: f64,
    pub mismatch: f64,
    /// The round-off bound of the equal-lateral-strain run.
    pub equal_bound: f64,
    pub different: PatchErrors,
    pub equal: PatchErrors,
}

/// The materials study's figure and table.
pub fn materials_report(
    ctx: &RunContext,
    report: &mut CaseReport,
    levels: &[PressureLevel],
) -> Result<(), String> {
    let fig = Figure::new("two-pass with different materials: the error against p")
        .x_label("p")
        .y_label("max |σ − σ*|/p")
        .log_log()
        .reference_slope(1.0, "p¹")
        .series(
            Series::line_markers(
                "E, ν = (1, 0.3) below, (2, 0.2) above: different lateral strains",
                levels
                    .iter()
                    .map(|l| (l.pressure, l.different.stress_max.max(FLOOR))),
            )
            .color(0),
        )
        .series(
            Series::line_markers(
                "equal lateral strains ν(1 + ν)/E, different E",
                levels
                    .iter()
                    .map(|l| (l.pressure, l.equal.stress_max.max(FLOOR))),
            )
            .color(1),
        );
    ctx.plot(report, "materials", &fig)?;
    report.tables.push(Table {
        title: "Two-pass with different materials against p: the uniform state is exact for the small-strain problem, but the constraints see the traces stretched by 1 + ε_xx^A and 1 + ε_xx^B".into(),
        header: [
            "p",
            "ε_xx^B − ε_xx^A",
            "different: max |σ − σ*|/p",
            "different: max |σ − σ*|/(p |ε_xx^B − ε_xx^A|)",
            "different: max |u − u*|/max|u*|",
            "equal lateral strain: max |σ − σ*|/p",
            "equal lateral strain: max |u − u*|/max|u*|",
        ]
        .iter()
        .map(|s| header(s))
        .collect(),
        rows: levels
            .iter()
            .map(|l| {
                vec![
                    format!("{:e}", l.pressure),
                    sci(l.mismatch),
                    sci(l.different.stress_max),
                    format!("{:.4}", l.different.stress_max / l.mismatch.abs()),
                    sci(l.different.displacement_max),
                    sci(l.equal.stress_max),
                    sci(l.equal.displacement_max),
                ]
            })
            .collect(),
    });
    Ok(())
}
