//! What the sweeps and maps need of a linearized moving-continuum model: assemble
//! M q̈ + C q̇ + K q = 0 at a data point, set one parameter, and, when the stiffness is affine and
//! rank one along a parameter (friction, pad stiffness), say so for the shared-Hessenberg fast
//! path. The string (`string_model`) and the rotating plate (`plate`) implement it, so one map
//! and one sweep driver serve both.

use crate::error::Error;
use crate::model::moving::resolution::{model_resolution_limit, supercritical_speed};
use crate::model::moving::stability::{assess_resolved, StabilityAssessment, VerdictParams};
use crate::model::moving::string_data::{MovingStringData, StringParameter};
use crate::model::moving::string_model::MovingStringModel;
use crate::model::moving::system::MovingSystem;

/// A parameter that sweeps and maps vary: its key as a scene writes it.
pub trait AxisParameter: Copy + PartialEq + std::fmt::Debug + serde::Serialize {
    /// The key (`speed`, `angular_speed`, …).
    fn key(self) -> &'static str;
}

impl AxisParameter for StringParameter {
    fn key(self) -> &'static str {
        StringParameter::key(self)
    }
}

/// A short description of a string data point for error messages.
pub fn describe(data: &MovingStringData) -> String {
    let mut s = format!("v̄ = {}, ᾱ = {}", data.speed, data.damping);
    if let Some(o) = &data.oscillator {
        s.push_str(&format!(
            ", c̄ = {}, m̄ = {}, ā = {}, μh̄ = {}, {:?}",
            o.stiffness, o.mass, o.position, o.friction, o.contact
        ));
    }
    s
}

/// A linearized model whose stability a sweep or a map reads.
pub trait LinearizedModel: Sync {
    /// The data of one point (every parameter a sweep or map may vary).
    type Data: Copy + Send + Sync;
    /// The parameters that sweeps and maps vary.
    type Parameter: AxisParameter + Send + Sync;

    /// Checks a point's data.
    fn validate_data(&self, data: &Self::Data) -> Result<(), Error>;
    /// Sets `parameter` to `value` in `data` (validated).
    fn set(
        &self,
        parameter: Self::Parameter,
        data: &mut Self::Data,
        value: f64,
    ) -> Result<(), Error>;
    /// The coordinates' names (their number is the system's dimension).
    fn coordinates(&self, data: &Self::Data) -> Vec<String>;
    /// Assembles the system at `data` into `out` (shaped by `coordinates`).
    fn assemble_into(&self, data: &Self::Data, out: &mut MovingSystem) -> Result<(), Error>;
    /// The assembled system at `data`.
    fn system(&self, data: &Self::Data) -> Result<MovingSystem, Error> {
        let mut s = MovingSystem::zeros(self.coordinates(data));
        self.assemble_into(data, &mut s)?;
        Ok(s)
    }
    /// A number that changes whenever the mass matrix does (a solver refactors M then).
    fn mass_key(&self, data: &Self::Data) -> f64;
    /// K_total(t) = K_total(0) + t · coefficient · r sᵀ along `parameter`, as (r, s,
    /// coefficient), when the stiffness is affine and rank one along it; `None` otherwise.
    fn rank_one(
        &self,
        data: &Self::Data,
        parameter: Self::Parameter,
    ) -> Option<(Vec<f64>, Vec<f64>, f64)>;
    /// The resolution limit ω_res of the verdicts (`resolution.rs`; ∞: every eigenvalue).
    fn resolution_limit(&self, data: &Self::Data) -> f64;
    /// `Some(speed)` when the verdict at `data` is the discrete model's and not the
    /// continuum's: the string past its critical speed (`resolution.rs`). None by default.
    fn supercritical_speed(&self, _data: &Self::Data) -> Option<f64> {
        None
    }
    /// A short description of the point for error messages.
    fn describe(&self, data: &Self::Data) -> String;
}

/// The verdict of `model` at `data` from its `eigenvalues`: [`assess_resolved`] below the
/// model's resolution limit, with the supercritical warning when the model has one there.
pub fn assess_point<Mo: LinearizedModel + ?Sized>(
    model: &Mo,
    data: &Mo::Data,
    eigenvalues: &[faer::c64],
    params: &VerdictParams,
) -> StabilityAssessment {
    let mut a = assess_resolved(eigenvalues, params, model.resolution_limit(data));
    if let Some(speed) = model.supercritical_speed(data) {
        a.flag_supercritical(speed, eigenvalues, params);
    }
    a
}

impl LinearizedModel for MovingStringModel {
    type Data = MovingStringData;
    type Parameter = StringParameter;

    fn validate_data(&self, data: &MovingStringData) -> Result<(), Error> {
        Ok(data.validate()?)
    }

    fn set(
        &self,
        parameter: StringParameter,
        data: &mut MovingStringData,
        value: f64,
    ) -> Result<(), Error> {
        Ok(parameter.set(data, value)?)
    }

    fn coordinates(&self, data: &MovingStringData) -> Vec<String> {
        MovingStringModel::coordinates(self, data)
    }

    fn assemble_into(&self, data: &MovingStringData, out: &mut MovingSystem) -> Result<(), Error> {
        Ok(MovingStringModel::assemble_into(self, data, out)?)
    }

    fn system(&self, data: &MovingStringData) -> Result<MovingSystem, Error> {
        Ok(MovingStringModel::system(self, data)?)
    }

    fn mass_key(&self, data: &MovingStringData) -> f64 {
        data.oscillator.map_or(0.0, |o| o.mass)
    }

    fn rank_one(
        &self,
        data: &MovingStringData,
        parameter: StringParameter,
    ) -> Option<(Vec<f64>, Vec<f64>, f64)> {
        if !matches!(
            parameter,
            StringParameter::Friction | StringParameter::ControlParameter
        ) {
            return None;
        }
        self.friction_rank_one(data, parameter)
    }

    fn resolution_limit(&self, data: &MovingStringData) -> f64 {
        model_resolution_limit(self, data.speed)
    }

    fn supercritical_speed(&self, data: &MovingStringData) -> Option<f64> {
        supercritical_speed(data.speed)
    }

    fn describe(&self, data: &MovingStringData) -> String {
        describe(data)
    }
}
