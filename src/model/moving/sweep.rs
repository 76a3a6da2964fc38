//! One-parameter sweeps: the spectrum, the verdict and the eigenvalue branches at every value of
//! a parameter (eigenvalue loci, Campbell diagrams, stability boundaries).

use faer::c64;
use serde::Serialize;

use crate::error::Error;
use crate::model::moving::branches::{track_branches, EigenBranches};
use crate::model::moving::linearized::{assess_point, LinearizedModel};
use crate::model::moving::stability::{StabilityAssessment, VerdictParams};
use crate::model::moving::stability_map::{parallel_rows, EigenWorkspace, GridAxis};
use crate::model::moving::string_data::MovingStringData;
use crate::model::moving::string_model::MovingStringModel;
use crate::solve::quadratic_eigen::QuadraticEigenParams;

/// The result of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sweep<P = crate::model::moving::string_data::StringParameter> {
    pub axis: GridAxis<P>,
    /// The eigenvalues at every point, in the solver's order ([Re, Im] pairs in JSON).
    #[serde(serialize_with = "crate::model::moving::serialize_complex_rows")]
    pub spectra: Vec<Vec<c64>>,
    pub assessments: Vec<StabilityAssessment>,
    /// The tracked branches.
    pub branches: EigenBranches,
}

/// Sweeps `axis` of the string model from `base` (every point parallel, deterministic).
pub fn string_sweep(
    model: &MovingStringModel,
    base: &MovingStringData,
    axis: &GridAxis,
    eigen: QuadraticEigenParams,
    verdict: &VerdictParams,
    threads: usize,
) -> Result<Sweep, Error> {
    sweep(model, base, axis, eigen, verdict, threads)
}

/// Sweeps `axis` of any linearized model from `base` (every point parallel, deterministic).
pub fn sweep<Mo: LinearizedModel>(
    model: &Mo,
    base: &Mo::Data,
    axis: &GridAxis<Mo::Parameter>,
    eigen: QuadraticEigenParams,
    verdict: &VerdictParams,
    threads: usize,
) -> Result<Sweep<Mo::Parameter>, Error> {
    verdict.validate()?;
    model.validate_data(base)?;
    let (points, _) = parallel_rows(
        axis.values.len(),
        threads,
        || EigenWorkspace::new(model, base),
        |i, ws: &mut EigenWorkspace| -> Result<(Vec<c64>, StabilityAssessment), Error> {
            let mut d = *base;
            model.set(axis.parameter, &mut d, axis.values[i])?;
            let ev = ws.eigenvalues(model, &d, eigen)?.to_vec();
            let a = assess_point(model, &d, &ev, verdict);
            Ok((ev, a))
        },
    )?;
    let (spectra, assessments): (Vec<_>, Vec<_>) = points.into_iter().unzip();
    let branches = track_branches(&axis.values, &spectra)?;
    Ok(Sweep {
        axis: axis.clone(),
        spectra,
        assessments,
        branches,
    })
}
