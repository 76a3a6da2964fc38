//! Convergence cases: sweeps in h and k against an exact solution, rate gates with confidence
//! intervals, joint error-model gates, pinned reference values, convergence plots and the paper's
//! figures.

use rayon::prelude::*;

use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::case::{Against, CaseFile, SweepSpec};
use crate::gate::{evaluate_model_gate, evaluate_rate_gate, Check, GateVerdict};
use crate::plot::{Figure, Series};
use crate::report::case_report::{CaseReport, SweepReport};
use crate::rod_study::LevelResult;
use crate::run::paper_figures;
use crate::run::RunContext;
use crate::study::Study;

/// The schemes a sweep runs (the study's scheme when the sweep names none).
fn schemes_of(sweep: &SweepSpec, study: &Study) -> Vec<TimeScheme> {
    if sweep.schemes.is_empty() {
        vec![study.scheme()]
    } else {
        sweep.schemes.clone()
    }
}

/// The parameter value of a level.
pub fn parameter(level: &LevelResult, against: Against) -> f64 {
    match against {
        Against::H => level.h,
        Against::K => level.k,
        Against::HPlusK => level.h + level.k,
    }
}

/// Runs the case's sweeps, gates, references and figures.
pub fn run(case: &CaseFile, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let study = Study::from_case(case)?;
    let total: usize = case
        .sweep
        .iter()
        .map(|s| s.levels().len() * schemes_of(s, &study).len())
        .sum();
    let bar = ctx.progress_bar(total as u64, &case.id);
    for sweep in &case.sweep {
        for scheme in schemes_of(sweep, &study) {
            let levels: Result<Vec<LevelResult>, String> = sweep
                .levels()
                .par_iter()
                .map(|&(m, n)| {
                    let r = study
                        .run_level(m, n, scheme, sweep.time_error)
                        .map_err(|e| {
                            format!("sweep `{}` ({scheme}, M = {m}, N = {n}): {e}", sweep.name)
                        });
                    bar.inc(1);
                    r
                })
                .collect();
            report.sweeps.push(SweepReport {
                name: sweep.name.clone(),
                scheme,
                levels: levels?,
            });
        }
    }
    bar.finish_and_clear();

    let find = |name: &str, scheme: Option<TimeScheme>| -> Result<&SweepReport, String> {
        let candidates: Vec<&SweepReport> =
            report.sweeps.iter().filter(|s| s.name == name).collect();
        match scheme {
            Some(s) => candidates
                .into_iter()
                .find(|r| r.scheme == s)
                .ok_or_else(|| format!("sweep `{name}` has no runs with scheme {s}")),
            None if candidates.len() == 1 => Ok(candidates[0]),
            None => Err(format!(
                "sweep `{name}` runs several schemes: the gate must name one"
            )),
        }
    };

    let mut gates = Vec::new();
    for g in &case.gate {
        let sweep = find(&g.sweep, g.scheme)?;
        let param: Vec<f64> = sweep
            .levels
            .iter()
            .map(|l| parameter(l, g.against))
            .collect();
        let error: Vec<f64> = sweep
            .levels
            .iter()
            .map(|l| l.errors.get(&g.error).copied().unwrap_or(f64::NAN))
            .collect();
        let name = format!(
            "{}/{}: {} vs {}",
            g.sweep,
            sweep.scheme,
            g.error,
            g.against.label()
        );
        gates.push(evaluate_rate_gate(name, g, &param, &error));
    }
    for g in &case.model_gate {
        let (mut h, mut k, mut e) = (Vec::new(), Vec::new(), Vec::new());
        for name in &g.sweeps {
            let sweep = find(name, g.scheme)?;
            for l in &sweep.levels {
                h.push(l.h);
                k.push(l.k);
                e.push(l.errors.get(&g.error).copied().unwrap_or(f64::NAN));
            }
        }
        let form = match g.combination {
            crate::stats::error_model::Combination::Sum => "C_h h^p + C_k k^q",
            crate::stats::error_model::Combination::Quadrature => "((C_h h^p)² + (C_k k^q)²)^½",
        };
        let name = format!("{}: {} ≈ {form}", g.sweeps.join(" + "), g.error);
        gates.push(evaluate_model_gate(name, g, &h, &k, &e));
    }
    for r in &case.reference {
        let level = study
            .run_level(r.elements, r.steps, r.scheme, false)
            .map_err(|e| format!("reference `{}`: {e}", r.name))?;
        let observed = if r.quantity == "u_end" {
            level.u_end
        } else {
            level.errors.get(&r.quantity).copied().unwrap_or(f64::NAN)
        };
        let rel = ((observed - r.value) / r.value).abs();
        let mut check = Check::at_most(
            &format!(
                "{} (M = {}, N = {}, {}): relative deviation from {:.12e}",
                r.quantity, r.elements, r.steps, r.scheme, r.value
            ),
            rel,
            r.relative_tolerance,
        );
        if !rel.is_finite() {
            check.passed = false;
        }
        let mut v = GateVerdict::from_checks(
            format!("reference: {}", r.name),
            "reference",
            vec![check],
            &format!("observed {observed:.12e}"),
        );
        v.passed = v.passed && rel.is_finite();
        gates.push(v);
    }
    report.gates = gates;

    convergence_plots(case, ctx, report)?;
    if let (Some(fig), Study::Rod(rod)) = (&case.figures, &study) {
        paper_figures::draw(fig, rod, ctx, report)?;
    }
    Ok(())
}

/// One log–log plot per (sweep, parameter) of the gated errors, with the expected slopes.
fn convergence_plots(
    case: &CaseFile,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let mut figures = Vec::new();
    for sweep in &case.sweep {
        let mut againsts: Vec<Against> = Vec::new();
        for g in case.gate.iter().filter(|g| g.sweep == sweep.name) {
            if !againsts.contains(&g.against) {
                againsts.push(g.against);
            }
        }
        for against in againsts {
            let gates: Vec<_> = case
                .gate
                .iter()
                .filter(|g| g.sweep == sweep.name && g.against == against)
                .collect();
            let mut errors: Vec<&str> = Vec::new();
            let mut slopes: Vec<f64> = Vec::new();
            for g in &gates {
                if !errors.contains(&g.error.as_str()) {
                    errors.push(&g.error);
                }
                if !slopes.iter().any(|s| (s - g.expected_rate).abs() < 1e-12) {
                    slopes.push(g.expected_rate);
                }
            }
            let mut fig = Figure::new(format!(
                "{}: sweep `{}`, errors against {}",
                case.id,
                sweep.name,
                against.label()
            ))
            .x_label(against.label())
            .y_label("error")
            .log_log();
            for s in report.sweeps.iter().filter(|s| s.name == sweep.name) {
                for e in &errors {
                    let pts: Vec<(f64, f64)> = s
                        .levels
                        .iter()
                        .filter_map(|l| l.errors.get(*e).map(|v| (parameter(l, against), *v)))
                        .collect();
                    if !pts.is_empty() {
                        fig = fig.series(Series::line_markers(format!("{e} ({})", s.scheme), pts));
                    }
                }
            }
            for s in slopes {
                fig = fig.reference_slope(s, format!("slope {s}"));
            }
            let name = format!(
                "{}_{}",
                sweep.name,
                match against {
                    Against::H => "h",
                    Against::K => "k",
                    Against::HPlusK => "h_plus_k",
                }
            );
            figures.push((name, fig));
        }
    }
    for (name, fig) in figures {
        ctx.plot(report, &name, &fig)?;
    }
    Ok(())
}
