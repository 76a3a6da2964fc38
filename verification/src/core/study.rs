//! The sweep driver: a [`Study`] runs one discretization level (M elements, N steps, a scheme) and
//! returns a [`Level`] with its error functionals; [`run_sweeps`] runs the levels of every
//! `[[sweep]]` of a case, in parallel, in a deterministic order.

use std::fmt::Display;

use rayon::prelude::*;
use serde::de::DeserializeOwned;

use crate::core::context::RunContext;
use crate::core::sweep::{Level, SweepReport, SweepSpec};

/// A model's convergence study: the problem, its exact solution and the discretization options
/// of a case.
pub trait Study: Sync {
    /// The model's time schemes, as case files name them.
    type Scheme: Copy + PartialEq + Display + Default + DeserializeOwned + Send + Sync;

    /// The scheme of sweeps that name none.
    fn default_scheme(&self) -> Self::Scheme;

    /// Runs one level and measures its errors (`time_error`: also the time error against a
    /// same-mesh reference run, where the study has one).
    fn run_level(
        &self,
        elements: usize,
        steps: usize,
        scheme: Self::Scheme,
        time_error: bool,
    ) -> Result<Level, String>;
}

/// Runs every sweep with each of its schemes; the levels of one sweep run in parallel, and the
/// results keep the case file's order (so the report does not depend on the thread count).
pub fn run_sweeps<T: Study>(
    study: &T,
    sweeps: &[SweepSpec<T::Scheme>],
    ctx: &RunContext,
    label: &str,
) -> Result<Vec<SweepReport>, String> {
    let total: usize = sweeps
        .iter()
        .map(|s| s.levels().len() * s.schemes_or(study.default_scheme()).len())
        .sum();
    let bar = ctx.progress_bar(total as u64, label);
    let mut reports = Vec::new();
    for sweep in sweeps {
        for scheme in sweep.schemes_or(study.default_scheme()) {
            let levels: Result<Vec<Level>, String> = sweep
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
            reports.push(SweepReport {
                name: sweep.name.clone(),
                scheme: scheme.to_string(),
                levels: levels?,
            });
        }
    }
    bar.finish_and_clear();
    Ok(reports)
}
