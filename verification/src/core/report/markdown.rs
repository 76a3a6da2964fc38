//! `report.md`: every case's verdict, gates, fitted rates, level tables and plots, readable on a
//! code-hosting site.

use std::fmt::Write;

use serde::{Deserialize, Serialize};

use crate::core::report::case_report::CaseReport;
use crate::core::report::metadata::Metadata;

pub fn sci(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.3e}")
    } else {
        format!("{v}")
    }
}

fn verdict(passed: bool) -> &'static str {
    if passed {
        "PASS"
    } else {
        "**FAIL**"
    }
}

/// Escapes `|` for table cells.
pub fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// The headline result of a case, for the summary table.
fn headline(r: &CaseReport) -> String {
    if let Some(f) = &r.failure {
        return format!("failed to run: {}", cell(f));
    }
    let rates: Vec<String> = r
        .gates
        .iter()
        .filter_map(|g| {
            g.rate_fit.as_ref().map(|f| {
                format!(
                    "{}: {:.3} [{:.3}, {:.3}]",
                    g.name, f.rate, f.ci_low, f.ci_high
                )
            })
        })
        .take(3)
        .collect();
    if !rates.is_empty() {
        return cell(&rates.join("; "));
    }
    let passed = r.gates.iter().filter(|g| g.passed).count();
    format!("{passed}/{} gates", r.gates.len())
}

/// One case's part of the report: its summary row and its section, rendered once by the run
/// that computed it (a shard keeps them in its `run.json`, so `verify merge` joins the report
/// without the typed data the sections come from).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseMarkdown {
    pub id: String,
    pub passed: bool,
    pub wall_seconds: f64,
    /// The summary table's row.
    pub row: String,
    /// The case's section.
    pub section: String,
}

impl CaseMarkdown {
    pub fn of(r: &CaseReport) -> Self {
        let mut section = String::new();
        case_section(&mut section, r);
        Self {
            id: r.id.clone(),
            passed: r.passed,
            wall_seconds: r.wall_seconds,
            row: format!(
                "| [{}](#{}) | {} | {} | {} | {:.2} |",
                r.id,
                r.id,
                r.kind,
                verdict(r.passed),
                headline(r),
                r.wall_seconds
            ),
            section,
        }
    }
}

/// The command that runs a tier (for the report's first line).
fn command_of(tier: &str) -> String {
    match tier {
        "quick" | "full" => format!("cargo run --release --bin verify -- --{tier}"),
        _ => "cargo run --release --bin verify".to_string(),
    }
}

/// Renders the whole report.
pub fn render(reports: &[CaseReport], metadata: &Metadata, total_seconds: f64) -> String {
    let cases: Vec<CaseMarkdown> = reports.iter().map(CaseMarkdown::of).collect();
    assemble(&cases, metadata, total_seconds, 1)
}

/// The report of `cases` (in catalogue order) run in `shards` shards whose wall times add up to
/// `total_seconds`.
pub fn assemble(
    cases: &[CaseMarkdown],
    metadata: &Metadata,
    total_seconds: f64,
    shards: usize,
) -> String {
    let mut s = String::new();
    let all = cases.iter().all(|r| r.passed);
    let _ = writeln!(s, "# contactlab verification report\n");
    let _ = writeln!(
        s,
        "Produced by `{}`{} — tier **{}**, {} case(s), {:.1} s. Overall: **{}**.\n",
        command_of(&metadata.tier),
        if shards > 1 {
            format!(" in {shards} shards joined by `verify merge` (the time is their sum)")
        } else {
            String::new()
        },
        metadata.tier,
        cases.len(),
        total_seconds,
        if all { "all gates pass" } else { "GATES FAIL" }
    );
    let _ = writeln!(
        s,
        "contactlab {} · commit `{}`{} · {} · {} · {} ({} CPUs, {} threads) · {}\n",
        metadata.contactlab_version,
        &metadata.git_commit[..metadata.git_commit.len().min(12)],
        if metadata.git_dirty {
            " (modified)"
        } else {
            ""
        },
        metadata.rustc,
        metadata.host,
        metadata.os,
        metadata.cpus,
        metadata.threads,
        metadata.date
    );
    let _ = writeln!(
        s,
        "Each case's full data (every level, fit, gate and the metadata) is in `<case id>.json`; \
         the fields are documented in [README.md](README.md).\n"
    );
    let _ = writeln!(s, "## Summary\n");
    let _ = writeln!(s, "| case | kind | verdict | headline | time (s) |");
    let _ = writeln!(s, "|---|---|---|---|---|");
    for r in cases {
        let _ = writeln!(s, "{}", r.row);
    }
    for r in cases {
        s.push_str(&r.section);
    }
    s
}

fn case_section(s: &mut String, r: &CaseReport) {
    let _ = writeln!(s, "\n## {}\n", r.id);
    let _ = writeln!(
        s,
        "**{}** — {} ({:.2} s)\n",
        r.title,
        verdict(r.passed),
        r.wall_seconds
    );
    if !r.explanation.is_empty() {
        let _ = writeln!(s, "{}\n", r.explanation);
    }
    if let Some(f) = &r.failure {
        let _ = writeln!(s, "> **Failed to run:** {}\n", f);
    }
    if !r.gates.is_empty() {
        let _ = writeln!(s, "### Gates\n");
        let _ = writeln!(s, "| gate | check | observed | limit | ok |");
        let _ = writeln!(s, "|---|---|---|---|---|");
        for g in &r.gates {
            for (i, c) in g.checks.iter().enumerate() {
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {} | {} |",
                    if i == 0 { cell(&g.name) } else { String::new() },
                    cell(&c.name),
                    sci(c.observed),
                    cell(&c.limit),
                    if c.passed { "yes" } else { "**no**" }
                );
            }
        }
        let notes: Vec<&str> = r
            .gates
            .iter()
            .map(|g| g.note.as_str())
            .filter(|n| !n.is_empty())
            .collect();
        if !notes.is_empty() {
            let _ = writeln!(s);
            for g in r.gates.iter().filter(|g| !g.note.is_empty()) {
                let _ = writeln!(s, "- *{}*: {}", g.name, g.note);
            }
        }
        let fits: Vec<_> = r
            .gates
            .iter()
            .filter(|g| g.rate_fit.is_some() || g.model_fit.is_some())
            .collect();
        if !fits.is_empty() {
            let _ = writeln!(s, "\n### Fitted rates (95% confidence intervals)\n");
            let _ = writeln!(
                s,
                "| gate | rate | CI | levels fitted | pairwise rates (coarse → fine) |"
            );
            let _ = writeln!(s, "|---|---|---|---|---|");
            for g in fits {
                if let Some(f) = &g.rate_fit {
                    let pw: Vec<String> = f
                        .pairwise
                        .iter()
                        .map(|p| format!("{:.3}", p.rate))
                        .collect();
                    let _ = writeln!(
                        s,
                        "| {} | {:.4} | [{:.4}, {:.4}] | {} | {} |",
                        cell(&g.name),
                        f.rate,
                        f.ci_low,
                        f.ci_high,
                        f.points_used,
                        pw.join(", ")
                    );
                }
                if let Some(m) = &g.model_fit {
                    let _ = writeln!(
                        s,
                        "| {} | p = {:.4}, q = {:.4} | p: [{:.4}, {:.4}], q: [{:.4}, {:.4}] | {} | C_h = {}, C_k = {} |",
                        cell(&g.name),
                        m.p,
                        m.q,
                        m.p_ci.0,
                        m.p_ci.1,
                        m.q_ci.0,
                        m.q_ci.1,
                        m.points_used,
                        sci(m.c_h),
                        sci(m.c_k)
                    );
                }
            }
        }
    }
    for sw in &r.sweeps {
        let mut names: Vec<&String> = Vec::new();
        for l in &sw.levels {
            for k in l.errors.keys() {
                if !names.contains(&k) {
                    names.push(k);
                }
            }
        }
        let _ = writeln!(s, "\n### Sweep `{}` — {}\n", sw.name, sw.scheme);
        let mut header = "| M | N | h | k |".to_string();
        let mut rule = "|---|---|---|---|".to_string();
        for n in &names {
            header.push_str(&format!(" {n} |"));
            rule.push_str("---|");
        }
        header.push_str(" u_h(L,T) | CPU s | Newton max |");
        rule.push_str("---|---|---|");
        let _ = writeln!(s, "{header}\n{rule}");
        for l in &sw.levels {
            let mut row = format!(
                "| {} | {} | {} | {} |",
                l.elements,
                l.steps,
                sci(l.h),
                sci(l.k)
            );
            for n in &names {
                row.push_str(&format!(
                    " {} |",
                    l.errors.get(*n).map(|v| sci(*v)).unwrap_or_default()
                ));
            }
            row.push_str(&format!(
                " {:.12} | {:.4} | {} |",
                l.u_end,
                l.cpu_seconds,
                l.stats
                    .get("max_newton_iterations")
                    .map(|v| v.to_string())
                    .unwrap_or_default()
            ));
            let _ = writeln!(s, "{row}");
        }
    }
    for sec in &r.sections {
        let _ = write!(s, "\n### {}\n\n{}", sec.title, sec.body);
    }
    if !r.extremes.is_empty() {
        let _ = writeln!(s, "\n### Runs at the extremes\n");
        let _ = writeln!(s, "| run | expected | outcome |");
        let _ = writeln!(s, "|---|---|---|");
        for e in &r.extremes {
            let _ = writeln!(
                s,
                "| {} | {} | {} |",
                cell(&e.name),
                e.expect,
                cell(&e.outcome)
            );
        }
    }
    if let Some(wp) = &r.work_precision {
        let _ = writeln!(s, "\n### Work–precision data ({})\n", wp.error);
        let _ = writeln!(s, "| scheme | M | N | error | CPU s | M·N |");
        let _ = writeln!(s, "|---|---|---|---|---|---|");
        for p in &wp.points {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {:.5} | {:.0} |",
                p.scheme,
                p.elements,
                p.steps,
                sci(p.error),
                p.cpu_seconds,
                p.dof_steps
            );
        }
    }
    if let Some(perf) = &r.performance {
        let _ = writeln!(s, "\n### Timings (minimum over repeats)\n");
        let _ = writeln!(s, "| M | N | M·N | seconds | ns per dof-step |");
        let _ = writeln!(s, "|---|---|---|---|---|");
        for p in &perf.points {
            let _ = writeln!(
                s,
                "| {} | {} | {:.0} | {:.5} | {:.3} |",
                p.elements, p.steps, p.dof_steps, p.seconds, p.ns_per_dof_step
            );
        }
    }
    for t in &r.tables {
        let _ = writeln!(s, "\n### {}\n", t.title);
        let _ = writeln!(s, "| {} |", t.header.join(" | "));
        let _ = writeln!(s, "|{}", "---|".repeat(t.header.len()));
        for row in &t.rows {
            let cells: Vec<String> = row.iter().map(|c| cell(c)).collect();
            let _ = writeln!(s, "| {} |", cells.join(" | "));
        }
    }
    if !r.plots.is_empty() {
        let _ = writeln!(s, "\n### Plots\n");
        for p in &r.plots {
            let _ = writeln!(s, "![{}]({})\n", cell(&p.title), p.file);
        }
    }
}
