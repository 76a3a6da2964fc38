//! Runs a selection: case after case (each case's sweeps use every core), a bar over the whole
//! run whose ETA comes from the run times recorded in `reports/`, a line per finished case, the
//! case files, `report.md` and `run.json`, and the final summary table.

use std::fmt::Write;
use std::time::Instant;

use indicatif::{MultiProgress, ProgressBar, ProgressStyle};

use crate::core::context::RunContext;
use crate::core::report::case_report::CaseReport;
use crate::core::report::manifest::RunManifest;
use crate::core::report::markdown::CaseMarkdown;
use crate::core::shard::Shard;
use crate::registry;
use crate::suite::select::Selection;

/// What a run did.
#[derive(Debug)]
pub struct Outcome {
    pub reports: Vec<CaseReport>,
    pub total_seconds: f64,
    pub report_path: std::path::PathBuf,
}

/// The bar over the run: its length is the expected seconds (in ms) of the cases.
fn run_bar(bars: &MultiProgress, expected_ms: u64) -> ProgressBar {
    let bar = bars.add(ProgressBar::new(expected_ms.max(1)));
    if let Ok(style) = ProgressStyle::with_template(
        "{prefix:>12} {msg:<36} [{bar:30}] {percent:>3}% {elapsed} (eta {eta})",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// Runs the cases of `selection` (this shard's) with `ctx`, writes every case's files, `report.md`
/// and `run.json` into `ctx.out_dir`.
pub fn run(
    selection: &Selection,
    ctx: &mut RunContext,
    tier: &str,
    shard: Shard,
) -> Result<Outcome, String> {
    let out = ctx.out_dir.clone();
    let bars = ctx.progress.then(MultiProgress::new);
    ctx.bars = bars.clone();
    let expected_ms: Vec<u64> = selection
        .expected
        .iter()
        .map(|s| (s * 1000.0).round() as u64)
        .collect();
    let bar = bars.as_ref().map(|m| run_bar(m, expected_ms.iter().sum()));
    let say = |line: String| match &bars {
        Some(m) => {
            let _ = m.println(line);
        }
        None => println!("{line}"),
    };
    let start = Instant::now();
    let mut reports = Vec::with_capacity(selection.mine.len());
    let n = selection.mine.len();
    for (i, case) in selection.mine.iter().enumerate() {
        if let Some(b) = &bar {
            b.set_prefix(format!("[{}/{n}]", i + 1));
            b.set_message(case.header.id.clone());
        }
        let report = registry::run(case, ctx);
        if let Some(b) = &bar {
            b.inc(expected_ms[i]);
        }
        say(format!(
            "{:<36} {:<5} {:>7.2} s  {}",
            report.id,
            if report.passed { "PASS" } else { "FAIL" },
            report.wall_seconds,
            report.failure.clone().unwrap_or_default()
        ));
        for g in report.gates.iter().filter(|g| !g.passed) {
            for c in g.checks.iter().filter(|c| !c.passed) {
                say(format!(
                    "    gate `{}`: {} = {:.6e}, expected {}",
                    g.name, c.name, c.observed, c.limit
                ));
            }
        }
        report
            .write(&out)
            .map_err(|e| format!("writing the report: {e}"))?;
        reports.push(report);
    }
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let total_seconds = start.elapsed().as_secs_f64();
    let manifest = RunManifest {
        tier: tier.to_string(),
        shard_index: shard.index,
        shard_count: shard.count,
        selection: selection.all.iter().map(|c| c.header.id.clone()).collect(),
        cases: reports.iter().map(CaseMarkdown::of).collect(),
        metadata: ctx.metadata.clone(),
        total_seconds,
    };
    let report_path = manifest.write(&out)?;
    Ok(Outcome {
        reports,
        total_seconds,
        report_path,
    })
}

/// The final summary: every case with its verdict, its time and the time recorded before, the
/// slowest first, and the totals.
pub fn summary_table(reports: &[CaseReport], expected: &[f64], shard: Shard) -> String {
    let mut rows: Vec<(&CaseReport, f64)> = reports.iter().zip(expected.iter().copied()).collect();
    rows.sort_by(|a, b| {
        b.0.wall_seconds
            .total_cmp(&a.0.wall_seconds)
            .then_with(|| a.0.id.cmp(&b.0.id))
    });
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\n{:<36} {:<8} {:<7} {:>9} {:>12}",
        "case", "tier", "verdict", "time (s)", "recorded (s)"
    );
    for (r, e) in &rows {
        let _ = writeln!(
            s,
            "{:<36} {:<8} {:<7} {:>9.2} {:>12.2}",
            r.id,
            r.tier.name(),
            if r.passed { "PASS" } else { "FAIL" },
            r.wall_seconds,
            e
        );
    }
    let failed = reports.iter().filter(|r| !r.passed).count();
    let total: f64 = reports.iter().map(|r| r.wall_seconds).sum();
    let _ = writeln!(
        s,
        "{} case(s){}, {} failed, {:.1} s in the cases",
        reports.len(),
        if shard.count > 1 {
            format!(" (shard {shard})")
        } else {
            String::new()
        },
        failed,
        total
    );
    s
}
