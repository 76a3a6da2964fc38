//! What every dynamic case shares: plots of the energy audit of its runs (energies, works, the
//! identity residuals per step) and the audit gates (identities at round-off for the conserving
//! combinations, dissipative sign of friction and constraint work).
//!
//! Residuals are scaled by the run's energy scale E_ref (see
//! [`contactlab::model::dynamic::audit::EnergyAudit::energy_scale`]). The round-off gate is
//! |r_n| / E_ref ≤ C ε_mach N_steps^{1/2}·(a safety factor): each step's identity is computed
//! from O(1) sums of terms of size ≤ E_ref, so a per-step residual is O(ε E_ref), while the
//! Newton tolerance (1e−12 relative to the largest term of the step equation) contributes
//! dᵀR ≤ 1e−12 × (work of the largest force over the step).

use contactlab::model::dynamic::audit::{AuditSummary, EnergyAudit};
use contactlab::model::dynamic::record::Conserving;

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::plot::{Figure, Series};

/// The round-off level of a per-step identity residual relative to E_ref: a few hundred ε.
pub const ROUND_OFF_LEVEL: f64 = 1e-12;

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

/// The identity residuals per step, |r_n| / E_ref on a log axis: (1.48), (1.49), HLT 3.7.
pub fn residual_figures(runs: &[AuditRun<'_>]) -> Vec<Figure> {
    let names = [
        ("BDS Prop. 1.1 (1.48): |r_n| / E_ref", 0usize),
        ("BDS Prop. 1.3 (1.49): |r_n| / E_ref", 1),
        ("HLT Prop. 3.7 (contact work): |r_n| / E_ref", 2),
    ];
    names
        .iter()
        .map(|(title, which)| {
            let mut fig = Figure::new(*title)
                .x_label("step n")
                .y_label("|residual| / E_ref")
                .semilog_y();
            for (i, run) in runs.iter().enumerate() {
                let scale = run.audit.energy_scale();
                fig = fig.series(
                    Series::line(
                        run.label.clone(),
                        run.audit.records.iter().skip(1).map(|r| {
                            let v = match which {
                                0 => r.residual_1_48,
                                1 => r.residual_1_49,
                                _ => r.residual_3_7,
                            };
                            // exact zeros cannot be drawn on a log axis: floor at 1e-18
                            (r.step as f64, (v.abs() / scale).max(1e-18))
                        }),
                    )
                    .color(i),
                );
            }
            fig.horizontal_line(ROUND_OFF_LEVEL, "round-off gate")
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
        &format!("{title}: discrete energy identities per step"),
        &residual_figures(runs),
        3,
    )
}

/// The audit checks of one run: the identities it must satisfy at round-off, and the dissipative
/// sign of friction and constraint work (always; a positive step work above round-off fails).
pub fn audit_checks(label: &str, summary: &AuditSummary, conserving: Conserving) -> Vec<Check> {
    let mut checks = Vec::new();
    if conserving.balance {
        checks.push(Check::at_most(
            &format!("{label}: max |r(1.48)| / E_ref"),
            summary.max_residual_1_48,
            ROUND_OFF_LEVEL,
        ));
    }
    if conserving.contact {
        checks.push(Check::at_most(
            &format!("{label}: max |r(1.49)| / E_ref"),
            summary.max_residual_1_49,
            ROUND_OFF_LEVEL,
        ));
        checks.push(Check::at_most(
            &format!("{label}: max |r(HLT 3.7)| / E_ref"),
            summary.max_residual_3_7,
            ROUND_OFF_LEVEL,
        ));
    }
    let tol = ROUND_OFF_LEVEL * summary.energy_scale;
    checks.push(Check::at_most(
        &format!("{label}: max step friction work (≤ 0)"),
        summary.max_step_friction_work,
        tol,
    ));
    checks.push(Check::at_most(
        &format!("{label}: max step constraint work (≤ 0)"),
        summary.max_step_constraint_work,
        tol,
    ));
    checks
}

/// A gate from audit checks.
pub fn audit_gate(name: &str, checks: Vec<Check>, note: &str) -> GateVerdict {
    GateVerdict::from_checks(name.to_string(), "energy audit", checks, note)
}
