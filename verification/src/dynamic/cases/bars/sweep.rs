//! The sweeps of the 1D kinds: the levels (M, N) a `[[sweep]]` asks for, the jobs they make with
//! the families, and what one run measured.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use contactlab::model::dynamic::audit::AuditSummary;
use contactlab::model::dynamic::solver::DynamicStats;

use crate::dynamic::cases::bars::family::{BarSetup, FamilySpec};

/// `[[sweep]]`: levels (M, N) run with each of its families.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    pub name: String,
    /// The families run (default: every family of the case).
    #[serde(default)]
    pub families: Vec<String>,
    /// M per level (or one value for every level).
    pub elements: Vec<usize>,
    /// N per level (or one value for every level); exclusive with `courant`.
    pub steps: Option<Vec<usize>>,
    /// k = courant · h / c for every level (N = T / k, rounded).
    pub courant: Option<f64>,
    /// T of this sweep's runs (default: the case's).
    pub final_time: Option<f64>,
    /// Errors plotted against h for this sweep besides the gated ones (every family of the
    /// sweep).
    #[serde(default)]
    pub plot: Vec<String>,
}

impl SweepSpec {
    /// Checks the levels; `field` names the sweep in errors.
    pub fn check(&self, field: &str) -> Result<(), (String, String, String)> {
        let bad = |f: &str, v: String, e: &str| Err((format!("{field}.{f}"), v, e.to_string()));
        if let Some(t) = self.final_time {
            if !(t.is_finite() && t > 0.0) {
                return bad("final_time", t.to_string(), "a finite T > 0");
            }
        }
        if self.elements.is_empty() || self.elements.contains(&0) {
            return bad(
                "elements",
                format!("{:?}", self.elements),
                "M ≥ 1 per level",
            );
        }
        match (&self.steps, self.courant) {
            (Some(_), Some(_)) | (None, None) => bad(
                "steps",
                "(steps and courant)".into(),
                "exactly one of steps and courant",
            ),
            (Some(s), None) => {
                if s.is_empty() || s.contains(&0) {
                    return bad("steps", format!("{s:?}"), "N ≥ 1 per level");
                }
                let (m, n) = (self.elements.len(), s.len());
                if m != n && m != 1 && n != 1 {
                    return bad(
                        "steps",
                        format!("{n} entries"),
                        &format!("one per level ({m}) or a single entry"),
                    );
                }
                Ok(())
            }
            (None, Some(c)) if !(c.is_finite() && c > 0.0) => {
                bad("courant", c.to_string(), "a finite number > 0")
            }
            _ => Ok(()),
        }
    }

    /// T of the sweep's runs, given the case's T.
    pub fn time(&self, case_final_time: f64) -> f64 {
        self.final_time.unwrap_or(case_final_time)
    }

    /// The (M, N) levels for a bar of length L, wave speed c and final time T.
    pub fn levels(&self, length: f64, wave_speed: f64, final_time: f64) -> Vec<(usize, usize)> {
        let count = self
            .elements
            .len()
            .max(self.steps.as_ref().map_or(1, Vec::len));
        (0..count)
            .map(|i| {
                let m = *self.elements.get(i).unwrap_or(&self.elements[0]);
                let n = match (&self.steps, self.courant) {
                    (Some(s), _) => *s.get(i).unwrap_or(&s[0]),
                    (None, Some(c)) => {
                        let k = c * length / m as f64 / wave_speed;
                        ((final_time / k).round() as usize).max(1)
                    }
                    (None, None) => 1,
                };
                (m, n)
            })
            .collect()
    }

    /// A one-level sweep (M, k = courant · h / c) of every family.
    pub fn single(elements: usize, courant: f64) -> Self {
        Self {
            name: String::new(),
            families: Vec::new(),
            elements: vec![elements],
            steps: None,
            courant: Some(courant),
            final_time: None,
            plot: Vec::new(),
        }
    }

    /// Whether the sweep runs the family.
    pub fn runs(&self, family: &str) -> bool {
        self.families.is_empty() || self.families.iter().any(|f| f == family)
    }
}

/// The measured quantities of one run (by error name), its audit summary and statistics.
#[derive(Debug, Clone)]
pub struct LevelOutcome {
    pub elements: usize,
    pub steps: usize,
    pub h: f64,
    pub k: f64,
    pub errors: BTreeMap<String, f64>,
    pub summary: AuditSummary,
    pub stats: DynamicStats,
    /// The time loop's wall time without the observer's (error evaluation) time (s).
    pub solver_seconds: f64,
}

impl LevelOutcome {
    /// The solver's cost per step (µs), the observer excluded.
    pub fn micros_per_step(&self) -> f64 {
        1e6 * self.solver_seconds / self.steps.max(1) as f64
    }
}

/// The runs of one sweep with one family, levels in the case file's order.
#[derive(Debug, Clone)]
pub struct SweepOutcome {
    pub sweep: String,
    pub family: String,
    pub levels: Vec<LevelOutcome>,
}

/// One run of a case: a level of a sweep with a family, or the shown level of a family
/// (`sweep = None`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Job {
    pub sweep: Option<usize>,
    pub family: usize,
    pub elements: usize,
    pub steps: usize,
    pub final_time: f64,
}

impl Job {
    /// The runs of a case in a fixed order (sweeps in file order, family-major, levels in file
    /// order; then the shown level of every family `shows` accepts), so that the results, collected
    /// in this order, do not depend on the thread count.
    pub fn list(
        sweeps: &[SweepSpec],
        families: &[FamilySpec],
        bar: &BarSetup,
        final_time: f64,
        show: (usize, f64),
        shows: impl Fn(&str) -> bool,
    ) -> Vec<Job> {
        let mut jobs = Vec::new();
        for (s, sweep) in sweeps.iter().enumerate() {
            let t = sweep.time(final_time);
            for (f, family) in families.iter().enumerate() {
                if !sweep.runs(&family.name) {
                    continue;
                }
                for (elements, steps) in sweep.levels(bar.length, bar.wave_speed(), t) {
                    jobs.push(Job {
                        sweep: Some(s),
                        family: f,
                        elements,
                        steps,
                        final_time: t,
                    });
                }
            }
        }
        let (elements, steps) =
            SweepSpec::single(show.0, show.1).levels(bar.length, bar.wave_speed(), final_time)[0];
        for (f, family) in families.iter().enumerate() {
            if shows(&family.name) {
                jobs.push(Job {
                    sweep: None,
                    family: f,
                    elements,
                    steps,
                    final_time,
                });
            }
        }
        jobs
    }
}

/// Groups the sweep runs' outcomes (aligned with `jobs`; shown runs are skipped) by (sweep,
/// family), levels in job order.
pub fn group_outcomes(
    jobs: &[Job],
    levels: Vec<LevelOutcome>,
    sweeps: &[SweepSpec],
    families: &[FamilySpec],
) -> Vec<SweepOutcome> {
    let mut outcomes: Vec<SweepOutcome> = Vec::new();
    for (job, level) in jobs.iter().zip(levels) {
        let Some(s) = job.sweep else { continue };
        let (sweep, family) = (&sweeps[s].name, &families[job.family].name);
        match outcomes
            .iter_mut()
            .find(|o| &o.sweep == sweep && &o.family == family)
        {
            Some(o) => o.levels.push(level),
            None => outcomes.push(SweepOutcome {
                sweep: sweep.clone(),
                family: family.clone(),
                levels: vec![level],
            }),
        }
    }
    outcomes
}
