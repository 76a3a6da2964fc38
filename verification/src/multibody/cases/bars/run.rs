//! The runs of a `multibody_bars` case: one job per (sweep, family, level) and one per shown
//! (configuration, family), run in parallel (each job is independent and deterministic; the
//! results keep the jobs' order).

use rayon::prelude::*;

use contactlab::model::multibody::audit::{MultibodyRecord, MultibodySummary};

use crate::multibody::audit_state::StateAudit;
use crate::multibody::cases::bars::format::{BarsCase, SweepSpec};
use crate::multibody::cases::bars::measure::{measure, Measured};
use crate::multibody::cases::bars::setup::{build, Level, Treatment};
use crate::multibody::study::{Claims, StepHistory};

/// One run to do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Job {
    /// The sweep and its level (None: a shown run only).
    pub sweep: Option<(usize, usize)>,
    pub configuration: usize,
    pub family: usize,
    pub elements: usize,
    pub courant: f64,
    /// Keep the histories (the configuration's shown level).
    pub record: bool,
}

/// One run's outcome.
pub struct Outcome {
    pub job: Job,
    pub level: Level,
    /// h and k.
    pub h: f64,
    pub k: f64,
    pub measured: Measured,
    pub summary: MultibodySummary,
    /// The audit recomputed from the state.
    pub state: StateAudit,
    pub claims: Claims,
    pub newton_iterations: usize,
    /// The histories and audit records (recorded runs only).
    pub history: Option<(Vec<StepHistory>, Vec<MultibodyRecord>)>,
}

/// The jobs of a case: every sweep level of every family of the sweep, and the shown level of
/// every (configuration, family) that a sweep runs (marked `record` on the sweep's job when the
/// level is one of its levels, a job of its own otherwise).
pub fn jobs(file: &BarsCase) -> Vec<Job> {
    let conf_index = |name: &str| {
        file.configurations
            .iter()
            .position(|c| c.name == name)
            .unwrap_or(0)
    };
    let fam_index = |name: &str| {
        file.families
            .iter()
            .position(|f| f.name == name)
            .unwrap_or(0)
    };
    let mut jobs: Vec<Job> = Vec::new();
    for (s, sweep) in file.sweeps.iter().enumerate() {
        let configuration = conf_index(&sweep.configuration);
        for fam in &sweep.families {
            for (l, (elements, courant)) in sweep.levels().into_iter().enumerate() {
                jobs.push(Job {
                    sweep: Some((s, l)),
                    configuration,
                    family: fam_index(fam),
                    elements,
                    courant,
                    record: false,
                });
            }
        }
    }
    for (c, conf) in file.configurations.iter().enumerate() {
        let mut families: Vec<usize> = Vec::new();
        for sweep in file.sweeps.iter().filter(|s| s.configuration == conf.name) {
            for fam in &sweep.families {
                let f = fam_index(fam);
                if !families.contains(&f) {
                    families.push(f);
                }
            }
        }
        for f in families {
            let (m, courant) = (conf.show.elements, conf.show.courant);
            let same = |j: &Job| {
                j.configuration == c && j.family == f && j.elements == m && j.courant == courant
            };
            if let Some(j) = jobs.iter_mut().find(|j| same(j)) {
                j.record = true;
            } else {
                jobs.push(Job {
                    sweep: None,
                    configuration: c,
                    family: f,
                    elements: m,
                    courant,
                    record: true,
                });
            }
        }
    }
    jobs
}

/// Runs one job.
pub fn run_job(file: &BarsCase, job: &Job) -> Result<Outcome, String> {
    let conf = &file.configurations[job.configuration];
    let family = &file.families[job.family];
    let material = family.material(&file.material);
    let c = file.wave_speed(conf);
    let level = conf.level(job.elements, job.courant, c);
    let geometry = conf.geometry();
    let solver = build(
        &geometry,
        &material,
        &level,
        Treatment {
            scheme: family.scheme,
            two_pass: family.two_pass,
        },
    )?;
    let exact = conf.exact(material.young);
    let label = format!(
        "{} / {} (M = {}, courant {})",
        conf.name, family.name, job.elements, job.courant
    );
    let (run, measured) = measure(&solver, exact.as_ref(), conf.speed, &material)
        .map_err(|e| format!("{label}: {e}"))?;
    let claims = Claims::of(family.scheme, [true, true], material.is_objective());
    Ok(Outcome {
        job: *job,
        level,
        h: level.h(&geometry),
        k: level.step,
        measured,
        summary: run.summary,
        state: run.state,
        claims,
        newton_iterations: run.solution.stats.newton_iterations,
        history: job
            .record
            .then(|| (run.history, run.solution.records.clone())),
    })
}

/// Runs every job (in parallel; the outcomes in the jobs' order).
pub fn run_all(file: &BarsCase, jobs: &[Job]) -> Result<Vec<Outcome>, String> {
    jobs.par_iter().map(|j| run_job(file, j)).collect()
}

/// The outcomes of one (sweep, family), coarse to fine.
pub fn series<'a>(
    file: &BarsCase,
    outcomes: &'a [Outcome],
    sweep: &str,
    family: &str,
) -> Vec<&'a Outcome> {
    let Some(s) = file.sweeps.iter().position(|x| x.name == sweep) else {
        return Vec::new();
    };
    let mut v: Vec<&Outcome> = outcomes
        .iter()
        .filter(|o| {
            o.job.sweep.is_some_and(|(i, _)| i == s) && file.families[o.job.family].name == family
        })
        .collect();
    v.sort_by_key(|o| o.job.sweep.map_or(0, |(_, l)| l));
    v
}

/// The parameter a sweep's rates are taken against: h, or k for a sweep in k at fixed h.
pub fn parameter(sweep: &SweepSpec, o: &Outcome) -> f64 {
    if sweep.against_k() {
        o.k
    } else {
        o.h
    }
}
