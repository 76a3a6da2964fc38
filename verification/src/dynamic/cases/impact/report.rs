//! What a `dynamic_impact` case reports: the gates of each run (audit, energy over the run,
//! penetration, momentum, separation, cost), the plots and tables of the runs, the
//! self-convergence studies, and `data.json`.

use serde::Serialize;

use contactlab::model::dynamic::record::Conserving;
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::scene::dynamic::DynamicSceneFile;

use crate::dynamic::audit_state::{state_audit_checks, state_audit_gate};
use crate::dynamic::study::{audit_checks, audit_gate, plot_audits, AuditRun};

use super::plots::{
    contact_force_figure, gci_figures, penetration_figure, snapshot_plots, velocity_figures,
    Labelled,
};
use super::runs::{Job, RunOutput, RunSummary, StepRecord, Treatment};
use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::dynamic::cases::impact::format::{
    refinement_ratio, GciStudy, ImpactCase, ImpactRun, Quantity,
};
use crate::dynamic::cases::impact::gci_report::{gci_gate, gci_table, levels_table};
use crate::stats::gci::{analyse, GciResult};

/// One run in `data.json`: its job, summary or error, and its history.
#[derive(Debug, Serialize)]
pub(crate) struct RunData {
    scheme: DynamicScheme,
    treatment: Treatment,
    refinement: f64,
    steps: Option<usize>,
    outcome: Result<RunSummary, String>,
    history: Vec<StepRecord>,
}

pub(crate) fn run_data(jobs: &[Job], outputs: &[Result<RunOutput, String>]) -> Vec<RunData> {
    jobs.iter()
        .zip(outputs)
        .map(|(j, o)| RunData {
            scheme: j.scheme,
            treatment: j.treatment,
            refinement: j.factor,
            steps: o.as_ref().ok().map(|o| o.steps),
            outcome: o.as_ref().map(|o| o.summary()).map_err(|e| e.clone()),
            history: o
                .as_ref()
                .map_or_else(|_| Vec::new(), |o| o.history.clone()),
        })
        .collect()
}

/// The case with its scene file.
pub(crate) struct CaseData<'a> {
    pub(crate) id: &'a str,
    pub(crate) case: &'a ImpactCase,
    pub(crate) file: &'a DynamicSceneFile,
}

pub(crate) type LabelledResult<'a> = (String, &'a ImpactRun, &'a Result<RunOutput, String>);

impl CaseData<'_> {
    pub(crate) fn depth(&self) -> Option<f64> {
        self.file.contact.as_ref().and_then(|c| c.depth)
    }

    pub(crate) fn frictionless(&self) -> bool {
        self.file
            .contact
            .as_ref()
            .is_none_or(|c| c.friction.as_ref().is_none_or(|f| f.mu0 == 0.0))
    }

    pub(crate) fn conserving(&self, job: &Job) -> Conserving {
        let linear = self.file.material.law == "linear";
        let balance = job.scheme == DynamicScheme::Gonzalez
            || (job.scheme == DynamicScheme::Midpoint && linear);
        let compliance = job.treatment != Treatment::Signorini;
        Conserving {
            balance,
            contact: !compliance || job.treatment.is_energy_consistent(),
            compliance,
        }
    }

    /// Every gate on the runs at the report's resolution.
    pub(crate) fn run_gates(&self, report: &mut CaseReport, runs: &[LabelledResult<'_>]) {
        let mut completion = Vec::new();
        let mut separation = Vec::new();
        let mut penetration = Vec::new();
        let mut momentum = Vec::new();
        let mut energy = Vec::new();
        let mut state = Vec::new();
        for (label, spec, out) in runs {
            let out = match out {
                Ok(o) => o,
                Err(e) => {
                    completion.push(Check::holds(
                        &format!("{label}: {e}"),
                        spec.allow_failure,
                        "completes (or allow_failure = true, the failure shown)",
                    ));
                    continue;
                }
            };
            completion.push(Check::holds(
                &format!("{label}: completed"),
                true,
                "completes",
            ));
            match &out.state {
                Ok(a) => state.extend(state_audit_checks(label, a, out.claims)),
                Err(e) => state.push(Check::holds(
                    &format!("{label}: {e}"),
                    false,
                    "the state audit runs",
                )),
            }
            let s = out.summary();
            let audit = out.audit.summary();
            let conserving = self.conserving(&out.job);
            let mut checks = audit_checks(label, &audit, conserving);
            let note = if out.job.scheme == DynamicScheme::Newmark {
                // the trapezoidal rule applies the mean of the t_{n−1} and t_n friction forces
                // over the step: its work has no sign (reported in the runs table)
                checks.retain(|c| !c.name.contains("friction work"));
                "Newmark: residuals plotted; its friction work, the mean of the t_{n−1} and t_n \
                 forces times the slip increment, has no sign (not gated, see the runs table)"
            } else if conserving.total() {
                "conserving scheme with an energy-consistent force: identities at round-off"
            } else if conserving.balance {
                "conserving scheme, contact force without exact work: (1.48) at round-off"
            } else {
                "not conserving: residuals plotted, dissipation signs gated"
            };
            // Newmark with a penalty and no friction claims nothing of its record audit: no
            // identity, no step work with a sign (its state audit above still compares records)
            if !checks.is_empty() {
                report
                    .gates
                    .push(audit_gate(&format!("energy audit, {label}"), checks, note));
            }
            separation.push(Check::holds(
                &format!(
                    "{label}: contact interval {}",
                    s.contact
                        .map_or("— (no separation before T)".into(), |(a, b)| format!(
                            "[{a:.5}, {b:.5}] s"
                        ))
                ),
                s.contact.is_some(),
                "touches and leaves the foundation before T",
            ));
            self.penetration_checks(label, out, &s, &mut penetration);
            momentum.push(Check::at_most(
                &format!("{label}: max |Δ(centre-of-mass velocity)| / |v| in flight"),
                s.momentum_drift,
                self.case.momentum_tolerance,
            ));
            if conserving.total() {
                energy.push(Check::at_most(
                    &format!(
                        "{label}: |(E + Φ)_N − (E + Φ)_0 − W_τ − D_b| / E_ref over the run \
                         (C ε √N, N = {})",
                        audit.steps
                    ),
                    audit.drift_1_49.abs() / audit.energy_scale,
                    audit.tolerance(),
                ));
                if self.frictionless() && out.job.treatment == Treatment::LimitedPenetration {
                    if let Some(max_loss) = self.case.max_stage_b_loss {
                        energy.push(Check::at_most(
                            &format!("{label}: stage-(b) energy loss −D_b / E_0"),
                            -s.constraint_work,
                            max_loss,
                        ));
                    }
                }
            }
        }
        let gates = [
            ("runs complete", "completion", completion, ""),
            (
                "every run touches and leaves the foundation before T",
                "model",
                separation,
                "the rebound velocity and the contact duration need a separation",
            ),
            (
                "penetration against the layer depth g",
                "model",
                penetration,
                "limited penetration holds p ≤ g (stage (b), BDS (1.45)); Signorini p ≤ 0; the \
                 plain penalty and the unlimited energy-consistent force go beyond g",
            ),
            (
                "momentum conserved in flight",
                "model",
                momentum,
                "without contact Σ F_int = 0 (translation invariance), so every scheme keeps M v \
                 constant: any drift is the Newton tolerance",
            ),
            (
                "energy over the whole run",
                "energy audit",
                energy,
                "(E + Φ)_N − (E + Φ)_0 = W_τ + D_b exactly for the conserving combinations \
                 (the sum of the per-step identities: N × round-off); stage (b) only dissipates",
            ),
        ];
        for (name, kind, checks, note) in gates {
            if !checks.is_empty() {
                report
                    .gates
                    .push(GateVerdict::from_checks(name.into(), kind, checks, note));
            }
        }
        if !state.is_empty() {
            report
                .gates
                .push(state_audit_gate("audit recomputed from the state", state));
        }
    }

    pub(crate) fn penetration_checks(
        &self,
        label: &str,
        out: &RunOutput,
        s: &RunSummary,
        checks: &mut Vec<Check>,
    ) {
        let Some(g) = self.depth() else {
            return;
        };
        match out.job.treatment {
            Treatment::LimitedPenetration => checks.push(Check::at_most(
                &format!("{label}: max penetration"),
                s.max_penetration,
                g * (1.0 + 1e-12),
            )),
            Treatment::Signorini => checks.push(Check::at_most(
                &format!("{label}: max penetration"),
                s.max_penetration,
                1e-12 * g,
            )),
            Treatment::Penalty | Treatment::EnergyConsistent | Treatment::HauretLeTallecTilted => {
                checks.push(Check {
                    name: format!("{label}: max penetration exceeds g = {g:e}"),
                    observed: s.max_penetration,
                    limit: format!("> {g:.3e}"),
                    passed: s.max_penetration > g,
                })
            }
        }
    }

    /// Plots and the runs table.
    pub(crate) fn run_outputs(
        &self,
        ctx: &RunContext,
        report: &mut CaseReport,
        runs: &[LabelledResult<'_>],
    ) -> Result<(), String> {
        let done: Vec<(&str, &RunOutput)> = runs
            .iter()
            .filter_map(|(l, _, o)| o.as_ref().ok().map(|o| (l.as_str(), o)))
            .collect();
        if done.is_empty() {
            return Err("no run completed".into());
        }
        let title = if self.file.title.is_empty() {
            self.id.to_string()
        } else {
            self.file.title.clone()
        };
        let audits: Vec<AuditRun<'_>> = done
            .iter()
            .map(|(l, o)| AuditRun {
                label: l.to_string(),
                audit: &o.audit,
            })
            .collect();
        let e0 = done[0].1.summary().initial_energy;
        plot_audits(ctx, report, "energy", &title, &audits, Some(e0))?;
        let labelled: Vec<Labelled<'_>> = done
            .iter()
            .map(|(l, o)| Labelled { label: l, run: o })
            .collect();
        ctx.plot(
            report,
            "contact_force",
            &contact_force_figure(&title, &labelled),
        )?;
        ctx.plot(
            report,
            "penetration",
            &penetration_figure(&title, &labelled, self.depth()),
        )?;
        ctx.panels(
            report,
            "velocity",
            &format!("{title}: centre-of-mass velocity"),
            &velocity_figures(&title, &labelled),
            2,
        )?;
        if let Some((l, first)) = done.first().filter(|(_, o)| !o.snapshots.is_empty()) {
            let level = self
                .file
                .contact
                .as_ref()
                .and_then(|c| c.level)
                .unwrap_or(0.0);
            ctx.triangle_panels(
                report,
                "snapshots",
                &format!("{title}, {l}: deformed body (colour: Green–Lagrange strain norm |E|)"),
                &snapshot_plots(first, level),
                3,
            )?;
        }
        report.tables.push(self.runs_table(runs));
        Ok(())
    }

    pub(crate) fn runs_table(&self, runs: &[LabelledResult<'_>]) -> Table {
        let g = self.depth();
        let header = [
            "run",
            "steps",
            "k (s)",
            "dofs",
            "contact (s)",
            "duration (s)",
            "rebound (m/s)",
            "e = v_y/|v_y0|",
            "max p (m)",
            "max p / g",
            "max Σ w N (N/m)",
            "ΔE/E_0",
            "W_τ/E_0",
            "D_b/E_0",
            "max step W_τ (J)",
            "stage-b steps",
            "max |E| (snapshots)",
            "Newton its/step (max)",
            "loop (s)",
            "s/step",
        ];
        let rows = runs
            .iter()
            .map(|(label, _, out)| match out {
                Err(e) => {
                    let mut row = vec![label.clone(), format!("stopped: {e}")];
                    row.resize(header.len(), "—".into());
                    row
                }
                Ok(o) => {
                    let s = o.summary();
                    let steps = o.steps.max(1) as f64;
                    let strain = o
                        .snapshots
                        .iter()
                        .map(|(_, u)| o.max_green_strain(u))
                        .fold(f64::NAN, f64::max);
                    vec![
                        label.clone(),
                        o.steps.to_string(),
                        format!("{:.3e}", o.final_time / steps),
                        o.stats.unknowns.to_string(),
                        s.contact
                            .map_or("—".into(), |(a, b)| format!("[{a:.5}, {b:.5}]")),
                        s.contact_duration.map_or("—".into(), |d| format!("{d:.5}")),
                        format!("({:.4}, {:.4})", s.final_velocity[0], s.final_velocity[1]),
                        format!("{:.4}", s.final_velocity[1] / s.initial_velocity[1].abs()),
                        format!("{:.4e}", s.max_penetration),
                        g.map_or("—".into(), |g| format!("{:.3}", s.max_penetration / g)),
                        format!("{:.4e}", s.max_normal_force),
                        format!("{:+.4e}", s.energy_change),
                        format!("{:+.4e}", s.friction_work),
                        format!("{:+.4e}", s.constraint_work),
                        format!("{:+.3e}", o.audit.summary().max_step_friction_work),
                        s.stage_b_steps.to_string(),
                        if strain.is_nan() {
                            "—".into()
                        } else {
                            format!("{strain:.3}")
                        },
                        format!(
                            "{:.2} ({})",
                            o.stats.newton_iterations as f64 / steps,
                            o.stats.max_newton_iterations
                        ),
                        format!("{:.2}", o.stats.loop_seconds),
                        format!("{:.3e}", o.stats.loop_seconds / steps),
                    ]
                }
            })
            .collect();
        Table {
            title: "runs at the report's resolution: contact, rebound (centre-of-mass velocity at \
                    T), penetration, energy split (ΔE = W_τ + D_b for the conserving \
                    combinations), Newton iterations and cost"
                .into(),
            header: header.iter().map(|s| s.to_string()).collect(),
            rows,
        }
    }

    /// The self-convergence study `g` on its levels (coarsest first).
    pub(crate) fn gci_study(
        &self,
        ctx: &RunContext,
        report: &mut CaseReport,
        g: &GciStudy,
        levels: &[&Result<RunOutput, String>],
    ) -> Result<(), String> {
        let name = format!("self-convergence of {}", g.run);
        let ok: Result<Vec<&RunOutput>, String> = levels
            .iter()
            .map(|r| r.as_ref().map_err(|e| e.clone()))
            .collect();
        let outs = match ok {
            Ok(o) if o.len() == g.refinements.len() => o,
            Ok(_) => return Err(format!("{name}: a level is missing")),
            Err(e) => {
                report.gates.push(GateVerdict::from_checks(
                    format!("{name}: GCI"),
                    "gci",
                    vec![Check::holds(
                        &format!("a level stopped: {e}"),
                        false,
                        "every level runs",
                    )],
                    "",
                ));
                return Ok(());
            }
        };
        let ratio =
            refinement_ratio(&g.refinements).ok_or("refinements without a constant ratio")?;
        let summaries: Vec<RunSummary> = outs.iter().map(|o| o.summary()).collect();
        let speed = summaries
            .first()
            .map_or(1.0, |s| s.initial_velocity[0].hypot(s.initial_velocity[1]));
        let analysed: Vec<(Quantity, Result<GciResult, String>, Vec<f64>)> = Quantity::ALL
            .iter()
            .map(|&q| {
                let values: Vec<f64> = summaries
                    .iter()
                    .map(|s| q.of(s).unwrap_or(f64::NAN))
                    .collect();
                let formal = g
                    .gate
                    .iter()
                    .find(|gate| gate.quantity == q)
                    .map_or(1.0, |gate| gate.formal_order);
                let scale = match q {
                    Quantity::ReboundVelocityX | Quantity::ReboundVelocityY => speed,
                    _ => 1.0,
                };
                let result = if values.iter().all(|v| v.abs() <= 1e-9 * scale) {
                    Err("≈ 0 on every level (symmetry or round-off): no relative GCI".into())
                } else {
                    analyse(&values, ratio, formal).map_err(|e| e.to_string())
                };
                (q, result, values)
            })
            .collect();
        for gate in &g.gate {
            if let Some((_, res, _)) = analysed.iter().find(|(q, _, _)| *q == gate.quantity) {
                report.gates.push(gci_gate(&name, gate, res));
            }
        }
        let fig_data: Vec<(String, Option<GciResult>, Vec<f64>)> = analysed
            .iter()
            .map(|(q, r, v)| (q.name().to_string(), r.as_ref().ok().cloned(), v.clone()))
            .collect();
        let slug: String = g
            .run
            .chars()
            .map(|ch| if ch.is_ascii_alphanumeric() { ch } else { '_' })
            .collect();
        ctx.panels(
            report,
            &format!("gci_{slug}"),
            &format!("{name}: levels and Richardson extrapolation"),
            &gci_figures(&g.run, &g.refinements, &fig_data),
            3,
        )?;
        report
            .tables
            .push(levels_table(&name, &g.refinements, &outs, &summaries));
        report.tables.push(gci_table(&name, ratio, &analysed));
        Ok(())
    }
}
