//! `dynamic_impact`: the impact tests of Barboteu–Danan–Sofonea §1.7 — a body thrown at the
//! foundation {x2 ≤ level}, run with several schemes and contact treatments, and a
//! self-convergence study (grid convergence index) of the quantities an experiment would report.
//!
//! Per run: the energy history and the per-step identity residuals (BDS Prop. 1.1 (1.48),
//! Prop. 1.3 (1.49), HLT Prop. 3.7), the total normal force Σ w N, the largest penetration
//! against the layer depth g, the centre-of-mass velocity (total momentum / total mass), and the
//! summary: contact interval (interpolated where max p changes sign), rebound velocity,
//! coefficient of restitution, energy change split into friction work W_τ and stage-(b) work D_b,
//! Newton iterations and cost per step. Deformed snapshots of the first run.
//!
//! Gates:
//! - energy audit (shared `audit_checks`): the identities at round-off for the conserving
//!   combinations (Gonzalez, or the midpoint rule with a linear law; (1.49) and HLT 3.7 with an
//!   energy-consistent or limited-penetration force); friction work and stage-(b) work ≤ 0 for all;
//! - energy over the run: (E + Φ)_N − (E + Φ)_0 = W_τ + D_b to N × round-off for those; a
//!   frictionless limited-penetration run loses at most `max_stage_b_loss` (stage (b) only
//!   dissipates, BDS §1.6.3);
//! - penetration: ≤ g (limited penetration) and ≤ round-off (Signorini); the plain penalty and the
//!   unlimited energy-consistent force exceed g (the limit is the method's doing);
//! - momentum: constant in flight (Σ F_int = 0 by translation invariance) to `momentum_tolerance`;
//! - every run separates before T (rebound and contact duration defined);
//! - cost: each run's time loop at the report's resolution within `budget_seconds`;
//! - self-convergence: GCI of the finest pair below a percentage, and the asymptotic ratio of
//!   [`crate::dynamic::impact_gci`] within a tolerance (four levels or more).

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use contactlab::model::dynamic::record::Conserving;
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::scene::dynamic::{DynamicScene, DynamicSceneFile};

use crate::core::case::Case;
use crate::core::format::CaseError;
use crate::dynamic::study::{audit_checks, audit_gate, plot_audits, AuditRun, ROUND_OFF_LEVEL};
pub mod gci;
pub mod plots;
pub mod runs;

use crate::core::context::RunContext;
use crate::core::format::{at_least, invalid, positive};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use gci::{analyse, GciResult};
use plots::{
    contact_force_figure, gci_figures, penetration_figure, snapshot_plots, velocity_figures,
    Labelled,
};
use runs::{run_job, Job, RunOutput, RunSummary, SceneSource, StepRecord, Treatment};

/// `[[run]]`: a scheme and a contact treatment on the scene (its resolution, or `steps`).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ImpactRun {
    pub label: Option<String>,
    pub scheme: DynamicScheme,
    pub treatment: Treatment,
    /// Steps instead of the scene's (a larger step for a scheme comparison).
    pub steps: Option<usize>,
    /// The run may stop with a typed error (shown, and not a failure of the case).
    #[serde(default)]
    pub allow_failure: bool,
}

impl ImpactRun {
    fn label(&self) -> String {
        self.label.clone().unwrap_or_else(|| {
            let base = format!("{} + {}", self.scheme.name(), self.treatment.name());
            match self.steps {
                Some(n) => format!("{base} (N = {n})"),
                None => base,
            }
        })
    }
}

/// A quantity of the self-convergence study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Centre-of-mass velocity at T (after separation), x and y.
    ReboundVelocityX,
    ReboundVelocityY,
    /// t_end − t_start of the contact interval.
    ContactDuration,
    /// max over steps and nodes of p_i.
    MaxPenetration,
    /// −((E + Φ)_N − (E + Φ)_0)/(E + Φ)_0: friction and stage-(b) losses.
    EnergyLoss,
}

impl Quantity {
    const ALL: [Quantity; 5] = [
        Self::ReboundVelocityX,
        Self::ReboundVelocityY,
        Self::ContactDuration,
        Self::MaxPenetration,
        Self::EnergyLoss,
    ];

    fn name(self) -> &'static str {
        match self {
            Self::ReboundVelocityX => "rebound v_x (m/s)",
            Self::ReboundVelocityY => "rebound v_y (m/s)",
            Self::ContactDuration => "contact duration (s)",
            Self::MaxPenetration => "max penetration (m)",
            Self::EnergyLoss => "energy loss / E_0",
        }
    }

    fn of(self, s: &RunSummary) -> Option<f64> {
        match self {
            Self::ReboundVelocityX => s.contact.map(|_| s.final_velocity[0]),
            Self::ReboundVelocityY => s.contact.map(|_| s.final_velocity[1]),
            Self::ContactDuration => s.contact_duration,
            Self::MaxPenetration => Some(s.max_penetration),
            Self::EnergyLoss => Some(-s.energy_change),
        }
    }
}

/// `[[gci.gate]]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GciGate {
    pub quantity: Quantity,
    /// The order the quantity should show (the fallback of an unverified observed order).
    pub formal_order: f64,
    /// GCI of the finest pair, in per cent.
    pub max_percent: f64,
    /// |A − 1| (needs four levels or more).
    pub asymptotic_tolerance: Option<f64>,
    #[serde(default)]
    pub note: String,
}

/// `[[gci]]`: a self-convergence study of one run's scheme and treatment.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GciStudy {
    /// The label of a `[[run]]` (its scheme and treatment; the scene's steps).
    pub run: String,
    /// Multiples of the scene's resolution (mesh divisions and steps together), ascending with a
    /// constant ratio.
    pub refinements: Vec<f64>,
    #[serde(default)]
    pub gate: Vec<GciGate>,
}

/// The case format of `dynamic_impact`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ImpactCase {
    /// The scene (`model = "dynamic"`), relative to the case file.
    pub scene: String,
    /// The report's resolution as a multiple of the scene's (mesh divisions and steps; default 1).
    pub resolution: Option<f64>,
    /// Times of the deformed snapshots of the first run.
    #[serde(default)]
    pub snapshot_times: Vec<f64>,
    /// Largest relative change of the centre-of-mass velocity in flight.
    pub momentum_tolerance: f64,
    /// Largest wall time of a run's time loop at the report's resolution (s).
    pub budget_seconds: Option<f64>,
    /// Largest relative energy loss of a frictionless limited-penetration run.
    pub max_stage_b_loss: Option<f64>,
    #[serde(rename = "run")]
    pub runs: Vec<ImpactRun>,
    #[serde(default)]
    pub gci: Vec<GciStudy>,
}

/// The scene file named by a case.
fn scene_file(case_path: &Path, scene: &str) -> Result<(PathBuf, SceneSource), String> {
    let path = case_path
        .parent()
        .unwrap_or_else(|| Path::new("."))
        .join(scene);
    let text =
        std::fs::read_to_string(&path).map_err(|e| format!("scene {}: {e}", path.display()))?;
    let table: toml::Table = text
        .parse()
        .map_err(|e| format!("scene {}: {e}", path.display()))?;
    let file: DynamicSceneFile = table
        .clone()
        .try_into()
        .map_err(|e| format!("scene {}: {e}", path.display()))?;
    Ok((path, SceneSource { table, file }))
}

/// The ratio of consecutive refinements, if constant.
fn refinement_ratio(r: &[f64]) -> Option<f64> {
    let q = r.get(1)? / r.first()?;
    let constant = r.windows(2).all(|w| ((w[1] / w[0]) / q - 1.0).abs() < 1e-9);
    (constant && q > 1.0).then_some(q)
}

impl ImpactCase {
    /// The runs' jobs at the report's resolution.
    fn job(&self, run: &ImpactRun, snapshots: bool) -> Job {
        Job {
            scheme: run.scheme,
            treatment: run.treatment,
            factor: self.resolution.unwrap_or(1.0),
            steps: run.steps,
            snapshots,
        }
    }

    fn run_by_label(&self, label: &str) -> Option<&ImpactRun> {
        self.runs.iter().find(|r| r.label() == label)
    }

    /// Checks the case, its scene and every run and level it asks for.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        let bad = |field: &str, value: &str, expected: &str| invalid(p, field, value, expected);
        positive(p, "momentum_tolerance", self.momentum_tolerance)?;
        if let Some(r) = self.resolution {
            positive(p, "resolution", r)?;
        }
        if let Some(b) = self.budget_seconds {
            positive(p, "budget_seconds", b)?;
        }
        if let Some(b) = self.max_stage_b_loss {
            positive(p, "max_stage_b_loss", b)?;
        }
        at_least(p, "run", &self.runs, 1)?;
        let (path, source) =
            scene_file(p, &self.scene).map_err(|e| bad("scene", &self.scene, &e))?;
        let file = &source.file;
        if !file.dirichlet.is_empty() {
            return Err(bad(
                "scene",
                &path.display().to_string(),
                "a free body (no [[dirichlet]]): momentum and rebound velocity need one",
            ));
        }
        for (i, t) in self.snapshot_times.iter().enumerate() {
            if !(t.is_finite() && *t >= 0.0 && *t <= file.time.final_time) {
                return Err(invalid(
                    p,
                    &format!("snapshot_times[{i}]"),
                    t,
                    "a time in [0, the scene's final_time]",
                ));
            }
        }
        for (i, r) in self.runs.iter().enumerate() {
            if self.runs[..i].iter().any(|q| q.label() == r.label()) {
                return Err(bad(
                    &format!("run[{i}].label"),
                    &r.label(),
                    "a label no other run has",
                ));
            }
            let f = source
                .variant(&self.job(r, false), &[])
                .map_err(|e| bad(&format!("run[{i}]"), &r.label(), &e))?;
            DynamicScene::from_file(f)
                .map_err(|e| bad(&format!("run[{i}]"), &r.label(), &e.to_string()))?;
        }
        for (i, g) in self.gci.iter().enumerate() {
            self.check_gci(p, i, g, &source)?;
        }
        Ok(())
    }

    fn check_gci(
        &self,
        p: &Path,
        i: usize,
        g: &GciStudy,
        source: &SceneSource,
    ) -> Result<(), CaseError> {
        let field = format!("gci[{i}]");
        let run = self
            .run_by_label(&g.run)
            .ok_or_else(|| invalid(p, &format!("{field}.run"), &g.run, "the label of a [[run]]"))?;
        if run.steps.is_some() {
            return Err(invalid(
                p,
                &format!("{field}.run"),
                &g.run,
                "a run at the scene's steps (the levels refine the scene)",
            ));
        }
        at_least(p, &format!("{field}.refinements"), &g.refinements, 3)?;
        if refinement_ratio(&g.refinements).is_none() {
            return Err(invalid(
                p,
                &format!("{field}.refinements"),
                format!("{:?}", g.refinements),
                "ascending multiples with a constant ratio > 1",
            ));
        }
        for &f in &g.refinements {
            let job = Job {
                factor: f,
                ..self.job(run, false)
            };
            source
                .variant(&job, &[])
                .map_err(|e| invalid(p, &format!("{field}.refinements"), f, &e))?;
        }
        for (j, gate) in g.gate.iter().enumerate() {
            positive(
                p,
                &format!("{field}.gate[{j}].max_percent"),
                gate.max_percent,
            )?;
            positive(
                p,
                &format!("{field}.gate[{j}].formal_order"),
                gate.formal_order,
            )?;
            if let Some(t) = gate.asymptotic_tolerance {
                positive(p, &format!("{field}.gate[{j}].asymptotic_tolerance"), t)?;
                if g.refinements.len() < 4 {
                    return Err(invalid(
                        p,
                        &format!("{field}.gate[{j}].asymptotic_tolerance"),
                        t,
                        "four refinements or more (with three, the ratio is f1/f2 by construction)",
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Checks the case's format.
pub fn check(case: &Case) -> Result<(), CaseError> {
    case.body::<ImpactCase>()?.check(&case.path)
}

/// Every distinct job of the case: the runs first (in order), then the GCI levels not already
/// among them.
fn all_jobs(c: &ImpactCase) -> Vec<Job> {
    let mut jobs: Vec<Job> = c
        .runs
        .iter()
        .enumerate()
        .map(|(i, r)| c.job(r, i == 0))
        .collect();
    for g in &c.gci {
        if let Some(run) = c.run_by_label(&g.run) {
            for &f in &g.refinements {
                let job = Job {
                    factor: f,
                    snapshots: false,
                    ..c.job(run, false)
                };
                if !jobs.iter().any(|j| same_run(j, &job)) {
                    jobs.push(job);
                }
            }
        }
    }
    jobs
}

/// Two jobs that compute the same thing (snapshots aside).
fn same_run(a: &Job, b: &Job) -> bool {
    a.scheme == b.scheme && a.treatment == b.treatment && a.factor == b.factor && a.steps == b.steps
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c: ImpactCase = case.body().map_err(|e| e.to_string())?;
    c.check(&case.path).map_err(|e| e.to_string())?;
    let (_, source) = scene_file(&case.path, &c.scene)?;
    let jobs = all_jobs(&c);
    let bar = ctx.progress_bar(jobs.len() as u64, &case.header.id);
    let outputs: Vec<Result<RunOutput, String>> = jobs
        .par_iter()
        .map(|job| {
            let out = run_job(&source, job, &c.snapshot_times);
            bar.inc(1);
            out
        })
        .collect();
    bar.finish_and_clear();
    let find = |job: &Job| {
        jobs.iter()
            .position(|j| same_run(j, job))
            .map(|i| &outputs[i])
    };
    let runs: Vec<(String, &ImpactRun, &Result<RunOutput, String>)> = c
        .runs
        .iter()
        .enumerate()
        .filter_map(|(i, r)| find(&c.job(r, i == 0)).map(|o| (r.label(), r, o)))
        .collect();
    let ctx_data = CaseData {
        id: &case.header.id,
        case: &c,
        file: &source.file,
    };
    ctx_data.run_gates(report, &runs);
    ctx_data.run_outputs(ctx, report, &runs)?;
    for g in &c.gci {
        let Some(run) = c.run_by_label(&g.run) else {
            continue;
        };
        let levels: Vec<&Result<RunOutput, String>> = g
            .refinements
            .iter()
            .filter_map(|&f| {
                find(&Job {
                    factor: f,
                    snapshots: false,
                    ..c.job(run, false)
                })
            })
            .collect();
        ctx_data.gci_study(ctx, report, g, &levels)?;
    }
    ctx.write_data(report, &run_data(&jobs, &outputs))
}

/// One run in `data.json`: its job, summary or error, and its history.
#[derive(Debug, Serialize)]
struct RunData {
    scheme: DynamicScheme,
    treatment: Treatment,
    refinement: f64,
    steps: Option<usize>,
    outcome: Result<RunSummary, String>,
    history: Vec<StepRecord>,
}

fn run_data(jobs: &[Job], outputs: &[Result<RunOutput, String>]) -> Vec<RunData> {
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
struct CaseData<'a> {
    id: &'a str,
    case: &'a ImpactCase,
    file: &'a DynamicSceneFile,
}

type LabelledResult<'a> = (String, &'a ImpactRun, &'a Result<RunOutput, String>);

impl CaseData<'_> {
    fn depth(&self) -> Option<f64> {
        self.file.contact.as_ref().and_then(|c| c.depth)
    }

    fn frictionless(&self) -> bool {
        self.file
            .contact
            .as_ref()
            .is_none_or(|c| c.friction.as_ref().is_none_or(|f| f.mu0 == 0.0))
    }

    fn conserving(&self, job: &Job) -> Conserving {
        let linear = self.file.material.law == "linear";
        let balance = job.scheme == DynamicScheme::Gonzalez
            || (job.scheme == DynamicScheme::Midpoint && linear);
        Conserving {
            balance,
            contact: balance && job.treatment.is_energy_consistent(),
        }
    }

    /// Every gate on the runs at the report's resolution.
    fn run_gates(&self, report: &mut CaseReport, runs: &[LabelledResult<'_>]) {
        let mut completion = Vec::new();
        let mut separation = Vec::new();
        let mut penetration = Vec::new();
        let mut momentum = Vec::new();
        let mut energy = Vec::new();
        let mut budget = Vec::new();
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
            } else if conserving.contact {
                "conserving scheme with an energy-consistent force: identities at round-off"
            } else if conserving.balance {
                "conserving scheme, contact force without exact work: (1.48) at round-off"
            } else {
                "not conserving: residuals plotted, dissipation signs gated"
            };
            report
                .gates
                .push(audit_gate(&format!("energy audit, {label}"), checks, note));
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
            if conserving.contact {
                let steps = audit.steps.max(1) as f64;
                energy.push(Check::at_most(
                    &format!("{label}: |(E + Φ)_N − (E + Φ)_0 − W_τ − D_b| / E_ref over the run"),
                    audit.drift_1_49.abs() / audit.energy_scale,
                    steps * ROUND_OFF_LEVEL,
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
            if let Some(b) = self.case.budget_seconds {
                budget.push(Check::at_most(
                    &format!(
                        "{label}: time loop ({} steps, {} dofs)",
                        out.steps, out.stats.unknowns
                    ),
                    out.stats.loop_seconds,
                    b,
                ));
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
            (
                "cost at the report's resolution",
                "performance",
                budget,
                "wall time of each run's time loop on this machine",
            ),
        ];
        for (name, kind, checks, note) in gates {
            if !checks.is_empty() {
                report
                    .gates
                    .push(GateVerdict::from_checks(name.into(), kind, checks, note));
            }
        }
    }

    fn penetration_checks(
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
            Treatment::Penalty | Treatment::EnergyConsistent => checks.push(Check {
                name: format!("{label}: max penetration exceeds g = {g:e}"),
                observed: s.max_penetration,
                limit: format!("> {g:.3e}"),
                passed: s.max_penetration > g,
            }),
        }
    }

    /// Plots and the runs table.
    fn run_outputs(
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

    fn runs_table(&self, runs: &[LabelledResult<'_>]) -> Table {
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
    fn gci_study(
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

/// The gate of one GCI quantity.
fn gci_gate(study: &str, gate: &GciGate, res: &Result<GciResult, String>) -> GateVerdict {
    let q = gate.quantity.name();
    let mut checks = Vec::new();
    match res {
        Err(e) => checks.push(Check::holds(
            &format!("{q}: {e}"),
            false,
            "an analysable sequence",
        )),
        Ok(r) => {
            let how = if r.order_verified {
                format!("observed p = {:.3}, F_s = 1.25", r.order_used)
            } else {
                format!(
                    "{:?}, observed p = {}: not verified, formal p = {} with F_s = 3",
                    r.convergence,
                    r.order.map_or("—".into(), |p| format!("{p:.3}")),
                    r.order_used
                )
            };
            checks.push(Check::at_most(
                &format!("{q}: GCI_fine (%), {how}"),
                r.gci_fine_percent.unwrap_or(f64::INFINITY),
                gate.max_percent,
            ));
            if let Some(tol) = gate.asymptotic_tolerance {
                checks.push(Check::within(
                    &format!(
                        "{q}: asymptotic ratio A = GCI_coarse/(r^p_c GCI_fine), p = {}, p_c = {}",
                        r.order.map_or("—".into(), |p| format!("{p:.3}")),
                        r.coarse_order.map_or("—".into(), |p| format!("{p:.3}"))
                    ),
                    r.asymptotic_ratio.unwrap_or(f64::INFINITY),
                    1.0,
                    tol,
                ));
            }
        }
    }
    GateVerdict::from_checks(format!("{study}: {q}"), "gci", checks, &gate.note)
}

fn levels_table(name: &str, factors: &[f64], outs: &[&RunOutput], s: &[RunSummary]) -> Table {
    Table {
        title: format!("{name}: levels (mesh and step refined together)"),
        header: [
            "refinement",
            "dofs",
            "steps",
            "rebound (m/s)",
            "contact duration (s)",
            "max p (m)",
            "energy loss / E_0",
            "Newton its/step (max)",
            "loop (s)",
        ]
        .iter()
        .map(|h| h.to_string())
        .collect(),
        rows: outs
            .iter()
            .zip(s)
            .zip(factors)
            .map(|((o, s), f)| {
                vec![
                    format!("{f}"),
                    o.stats.unknowns.to_string(),
                    o.steps.to_string(),
                    format!("({:.5}, {:.5})", s.final_velocity[0], s.final_velocity[1]),
                    s.contact_duration.map_or("—".into(), |d| format!("{d:.6}")),
                    format!("{:.5e}", s.max_penetration),
                    format!("{:.4e}", -s.energy_change),
                    format!(
                        "{:.2} ({})",
                        o.stats.newton_iterations as f64 / o.steps.max(1) as f64,
                        o.stats.max_newton_iterations
                    ),
                    format!("{:.2}", o.stats.loop_seconds),
                ]
            })
            .collect(),
    }
}

fn gci_table(
    name: &str,
    ratio: f64,
    analysed: &[(Quantity, Result<GciResult, String>, Vec<f64>)],
) -> Table {
    let opt = |v: Option<f64>, digits: usize| v.map_or("—".into(), |v| format!("{v:.digits$}"));
    Table {
        title: format!(
            "{name}: observed order (finest three levels; coarser three: p_c), Richardson \
             extrapolation, GCI (r = {ratio}; F_s = 1.25 with the observed p when it is within \
             [p_f/2, 2 p_f], else F_s = 3 with the formal p_f: the gate's, or 1), asymptotic ratio \
             A = (f1/f2) r^(p − p_c)"
        ),
        header: [
            "quantity",
            "finest value",
            "convergence",
            "p",
            "p_c",
            "p, F_s used",
            "extrapolated",
            "GCI_fine (%)",
            "GCI_coarse (%)",
            "A",
        ]
        .iter()
        .map(|h| h.to_string())
        .collect(),
        rows: analysed
            .iter()
            .map(|(q, r, v)| match r {
                Err(e) => vec![q.name().into(), format!("{:?}", v.last()), e.clone()],
                Ok(r) => vec![
                    q.name().into(),
                    format!("{:.6e}", v.last().copied().unwrap_or(f64::NAN)),
                    format!("{:?}", r.convergence),
                    opt(r.order, 3),
                    opt(r.coarse_order, 3),
                    format!("{:.3}, {}", r.order_used, r.safety_factor),
                    opt(r.extrapolated, 6),
                    opt(r.gci_fine_percent, 4),
                    opt(r.gci_coarse_percent, 4),
                    opt(r.asymptotic_ratio, 4),
                ],
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    //! The format: unknown keys, labels that do not exist, refinements without a constant ratio
    //! or not giving whole meshes, and asymptotic checks on three levels are errors.
    use super::*;

    const CASE: &str = r#"
id = "t"
title = "t"
kind = "dynamic_impact"
explanation = "x"
scene = "../../examples/scenes/dynamic_ball_impact.toml"
momentum_tolerance = 1e-12
[[run]]
scheme = "gonzalez"
treatment = "limited_penetration"
[[gci]]
run = "gonzalez + limited_penetration"
refinements = [0.5, 1.0, 2.0, 4.0]
[[gci.gate]]
quantity = "rebound_velocity_y"
formal_order = 1.0
max_percent = 1.0
asymptotic_tolerance = 0.1
"#;

    fn load(text: &str) -> Result<ImpactCase, CaseError> {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/t.toml");
        let case = Case::from_text(Path::new("t"), text)?;
        let c: ImpactCase = case.body()?;
        c.check(&path)?;
        Ok(c)
    }

    #[test]
    fn valid_case_parses() {
        load(CASE).unwrap();
    }

    #[test]
    fn unknown_key_is_an_error() {
        assert!(
            load(&CASE.replace("explanation = \"x\"", "explanation = \"x\"\nfoo = 1")).is_err()
        );
    }

    #[test]
    fn gci_of_an_unknown_run_is_an_error() {
        let err = load(&CASE.replace("run = \"gonzalez", "run = \"midpoint")).unwrap_err();
        assert!(err.to_string().contains("gci[0].run"), "{err}");
    }

    #[test]
    fn refinements_must_have_a_constant_ratio_and_whole_meshes() {
        assert!(load(&CASE.replace("[0.5, 1.0, 2.0, 4.0]", "[0.5, 1.0, 3.0, 4.0]")).is_err());
        assert!(load(&CASE.replace("[0.5, 1.0, 2.0, 4.0]", "[0.1, 0.2, 0.4, 0.8]")).is_err());
    }

    #[test]
    fn asymptotic_check_needs_four_levels() {
        let err = load(&CASE.replace("[0.5, 1.0, 2.0, 4.0]", "[1.0, 2.0, 4.0]")).unwrap_err();
        assert!(err.to_string().contains("asymptotic_tolerance"), "{err}");
    }

    #[test]
    fn newmark_with_limited_penetration_is_an_error() {
        let text = CASE.replace("scheme = \"gonzalez\"", "scheme = \"newmark\"");
        let err = load(&text).unwrap_err();
        assert!(err.to_string().contains("run[0]"), "{err}");
    }
}
