//! What every dynamic case shares: plots of the energy audit of its runs (energies, works, the
//! drifts of the identities) and the audit gates (identities at round-off for the conserving
//! combinations, dissipative sign of friction and constraint work).
//!
//! The gates read the drifts R_n = Σ_{j≤n} r_j of the identities (the balance since t = 0):
//! |R_n| ≤ C ε Σ_{j≤n} s_j at every step, with s_j the round-off scale of step j and C =
//! [`contactlab::model::dynamic::audit::ROUND_OFF_CONSTANT`] (the derivation is at
//! [`contactlab::model::dynamic::audit`]). A step's dissipated work (friction, constraint) must be ≤ C ε s_n (one step's round-off). The
//! plots show |R_n| / E_ref with the tolerance.

use contactlab::model::dynamic::audit::{AuditSummary, EnergyAudit};
use contactlab::model::dynamic::record::Conserving;

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::plot::{Figure, Series};

/// One run's audit with its label.
pub struct AuditRun<'a> {
    pub label: String,
    pub audit: &'a EnergyAudit,
}

/// Energy history E_n + Φ_n (and E_n) of each run, against time.
pub fn energy_figure(title: &str, runs: &[AuditRun<'_>], reference: Option<f64>) -> Figure {
    let mut fig = Figure::new(title).x_label("t").y_label("energy");
    for (i, run) in runs.iter().enumerate() {
        fig = fig.series(
            Series::line(
                format!("{} (E + Φ)", run.label),
                run.audit
                    .records
                    .iter()
                    .map(|r| (r.time, r.energy() + r.penalty)),
            )
            .color(i),
        );
    }
    if let Some(e) = reference {
        fig = fig.horizontal_line(e, "exact");
    }
    fig
}

/// The drifts of the identities, |R_n| / E_ref on a log axis: (1.48), (1.49), HLT 3.7, each with
/// its run's tolerance (C ε Σ_{j≤n} s_j + Σ_{j≤n} ν_j) / E_ref (dashed).
pub fn residual_figures(runs: &[AuditRun<'_>]) -> Vec<Figure> {
    let names = [
        ("BDS Prop. 1.1 (1.48): |R_n| / E_ref", 0usize),
        ("BDS Prop. 1.3 (1.49): |R_n| / E_ref", 1),
        ("HLT Prop. 3.7 (compliance work): |R_n| / E_ref", 2),
    ];
    names
        .iter()
        .map(|(title, which)| {
            let mut fig = Figure::new(*title)
                .x_label("step n")
                .y_label("|drift| / E_ref")
                .semilog_y();
            for (i, run) in runs.iter().enumerate() {
                let scale = run.audit.energy_scale();
                let tolerances = run.audit.drift_tolerances();
                fig = fig.series(
                    Series::line(
                        format!("{}: tolerance", run.label),
                        run.audit
                            .records
                            .iter()
                            .zip(&tolerances)
                            .skip(1)
                            .map(|(r, t)| (r.step as f64, t / scale)),
                    )
                    .color(i)
                    .dashed(),
                );
                fig = fig.series(
                    Series::line(
                        run.label.clone(),
                        run.audit.records.iter().skip(1).map(|r| {
                            let v = match which {
                                0 => r.drift_1_48,
                                1 => r.drift_1_49,
                                _ => r.drift_3_7,
                            };
                            // exact zeros cannot be drawn on a log axis: floor at 1e-18
                            (r.step as f64, (v.abs() / scale).max(1e-18))
                        }),
                    )
                    .color(i),
                );
            }
            fig
        })
        .collect()
}

/// Writes the energy history and the residual panels of `runs` into the report.
pub fn plot_audits(
    ctx: &RunContext,
    report: &mut CaseReport,
    name: &str,
    title: &str,
    runs: &[AuditRun<'_>],
    reference_energy: Option<f64>,
) -> Result<(), String> {
    ctx.plot(
        report,
        &format!("{name}_energy"),
        &energy_figure(&format!("{title}: energy history"), runs, reference_energy),
    )?;
    ctx.panels(
        report,
        &format!("{name}_identities"),
        &format!("{title}: drift of the discrete energy identities"),
        &residual_figures(runs),
        3,
    )
}

/// The audit checks of a run (or of the worst of several runs, [`AuditSummary::worst`]): the
/// drift of each identity it claims (see [`Conserving`]) at most C ε Σ_{j≤n} s_j + Σ_{j≤n} ν_j
/// at every step, and the dissipative sign of each step's friction and constraint work (where
/// the run has any: a positive step work above C ε s_n + ν_n fails). Each check reads the quantity as a fraction of
/// its tolerance.
pub fn audit_checks(label: &str, summary: &AuditSummary, conserving: Conserving) -> Vec<Check> {
    let mut checks = Vec::new();
    let mut drift = |name: &str, value: f64| {
        checks.push(Check::at_most(
            &format!("{label}: max_n |R_n({name})| / (C ε Σ_{{j≤n}} s_j + Σ_{{j≤n}} ν_j)"),
            value,
            1.0,
        ))
    };
    if conserving.balance {
        drift("1.48", summary.drift_ratio_1_48);
    }
    if conserving.claims_3_7() {
        drift("HLT 3.7", summary.drift_ratio_3_7);
    }
    if conserving.claims_1_49() {
        drift("1.49", summary.drift_ratio_1_49);
    }
    // a sign law with no step work to test (no friction, no stage (b): W_τ or D_b exactly 0 in
    // every step) cannot fail in the run and is left out of its counts; a bug that books a
    // work where there is none brings it back
    if summary.friction_steps > 0 {
        checks.push(Check::at_most(
            &format!(
                "{label}: max_n step friction work W_τ / (C ε s_n + ν_n) (≤ 0 up to round-off)"
            ),
            summary.friction_work_ratio,
            1.0,
        ));
    }
    if summary.constraint_steps > 0 {
        checks.push(Check::at_most(
            &format!(
                "{label}: max_n step constraint work D_b / (C ε s_n + ν_n) (≤ 0 up to round-off)"
            ),
            summary.constraint_work_ratio,
            1.0,
        ));
    }
    checks
}

/// A gate from audit checks.
pub fn audit_gate(name: &str, checks: Vec<Check>, note: &str) -> GateVerdict {
    GateVerdict::from_checks(name.to_string(), "energy audit", checks, note)
}
