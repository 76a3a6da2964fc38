//! Kind `plane_paper_test_2d`: the paper's Test 2D (Fernández & Sofonea 2004, §4.2;
//! docs/quasistatic.md, "Test 2D") under both readings of "the horizontal displacements on the
//! lateral surfaces vanish":
//!
//! - clamped sides (u = 0): well posed for every load;
//! - rollers (u_x = 0): the vertical translation is carried by the contact alone, and while the load
//!   180 t N is below p0 |Γ3| = 12 N no equilibrium exists (steps t ≤ 0.06 for k = 0.01). The plain
//!   scheme must stop there with a typed error; the documented variant starts at the first step
//!   that has an equilibrium.
//!
//! Each reading runs on a sequence of meshes (constant ratio) for every β at the paper's k and
//! scheme. The quantities of Figs 14–15 — the von Mises range and the contact line at T — are
//! analysed for mesh convergence with Roache's GCI and set beside the paper's values as what they
//! are; the gates are the quantities' own convergence (observed order, GCI bound, asymptotic
//! ratio; a singular quantity's growth), the typed error, the skipped steps and the rollers'
//! rigid sinking against its closed form — never agreement with the paper.

pub mod floating;
pub mod format;
pub mod gates;
pub mod report;
pub mod runs;

use rayon::prelude::*;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::report::case_report::CaseReport;
use crate::plane::scene::{variant, Variant};

pub use format::PaperTestCase;
use format::Reading;

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = PaperTestCase::parse(case).map_err(|e| e.to_string())?;
    let spec = &c.paper_test;
    let base = variant(&c.scene, Variant::default())?;
    let steps = base.grid.steps();
    let k = base.grid.k_max();
    let plan: Vec<(Reading, usize, f64)> = Reading::ALL
        .iter()
        .flat_map(|&r| {
            spec.meshes
                .iter()
                .flat_map(move |&n| spec.betas.iter().map(move |&b| (r, n, b)))
        })
        .collect();
    let bar = ctx.progress_bar(plan.len() as u64, &case.header.id);
    let outcomes: Result<Vec<_>, String> = plan
        .par_iter()
        .map(|&(reading, n, beta)| {
            let (run, sol) = runs::run_one(&c.scene, reading, n, beta)?;
            bar.inc(1);
            // keep the solutions the pictures need (figure mesh, finest mesh)
            let keep = n == spec.figure_mesh || Some(&n) == spec.meshes.last();
            Ok((run, keep.then_some((reading, beta, n, sol))))
        })
        .collect();
    bar.finish_and_clear();
    let (runs, figures): (Vec<_>, Vec<_>) = outcomes?.into_iter().unzip();
    let figures: Vec<_> = figures.into_iter().flatten().collect();

    let mut gates = vec![
        gates::plain_rollers_stop(&c.scene, spec)?,
        gates::skipped_steps(&runs, k, steps),
        gates::rigid_sinking(&runs, steps, spec.sinking_round_off_factor),
        floating::floating_laws(&c.scene, spec, steps)?,
    ];
    for g in &spec.gci {
        let values = gates::series(&runs, &spec.meshes, g.reading, g.beta, g.quantity);
        gates.push(gates::gci_gate(g, &values, spec.ratio()));
    }
    report.gates = gates;
    report::tables(report, spec, &runs);
    report::plots(ctx, report, spec, &runs, &figures)?;
    let data_path = ctx.case_dir(&report.id)?.join("runs.json");
    std::fs::write(
        &data_path,
        serde_json::to_string_pretty(&runs).map_err(|e| e.to_string())?,
    )
    .map_err(|e| format!("{}: {e}", data_path.display()))?;
    Ok(())
}
