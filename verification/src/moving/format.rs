//! Shared pieces of the `moving_*` case formats: parsing with unknown keys as errors, the rate
//! gate, field checks, and the per-case `data.json`.

use std::path::Path;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::case::{Against, Case, CaseError, RateGateSpec};
use crate::gate::{evaluate_rate_gate, GateVerdict};
use crate::report::case_report::CaseReport;
use crate::run::RunContext;

/// Parses the whole case table into a kind's format (`deny_unknown_fields` there).
pub fn parse<T: DeserializeOwned>(case: &Case) -> Result<T, CaseError> {
    case.table
        .clone()
        .try_into()
        .map_err(|e: toml::de::Error| CaseError::Read {
            path: case.path.display().to_string(),
            message: e.to_string(),
        })
}

/// An invalid field of a case file.
pub fn invalid(
    path: &Path,
    field: &str,
    value: impl std::fmt::Display,
    expected: &str,
) -> CaseError {
    CaseError::Invalid {
        path: path.display().to_string(),
        field: field.to_string(),
        value: value.to_string(),
        expected: expected.to_string(),
    }
}

/// Checks that `v` is finite and > 0.
pub fn positive(path: &Path, field: &str, v: f64) -> Result<(), CaseError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(path, field, v, "a finite number > 0"))
    }
}

/// Checks that a list has at least `n` entries.
pub fn at_least<T>(path: &Path, field: &str, v: &[T], n: usize) -> Result<(), CaseError> {
    if v.len() >= n {
        Ok(())
    } else {
        Err(invalid(
            path,
            field,
            format!("{} entries", v.len()),
            &format!("at least {n} entries"),
        ))
    }
}

/// `[[gate]]` of the moving cases: a rate gate on a named series (scikit-fem's three numbers plus
/// the asymptotic pairwise check, as in `gate.rs`).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RateGate {
    /// The series, e.g. `sine/0.6` (basis/speed).
    pub series: String,
    pub expected_rate: f64,
    pub tolerance: f64,
    pub finest_levels: usize,
    pub ci_width: f64,
    pub ceiling: f64,
    pub asymptotic_tolerance: Option<f64>,
    #[serde(default)]
    pub note: String,
}

impl RateGate {
    /// Checks the numbers.
    pub fn check(&self, path: &Path, field: &str) -> Result<(), CaseError> {
        for (k, v) in [
            ("tolerance", self.tolerance),
            ("ci_width", self.ci_width),
            ("ceiling", self.ceiling),
        ] {
            positive(path, &format!("{field}.{k}"), v)?;
        }
        if self.finest_levels < 2 {
            return Err(invalid(
                path,
                &format!("{field}.finest_levels"),
                self.finest_levels,
                ">= 2",
            ));
        }
        Ok(())
    }

    /// Evaluates the gate on (parameter, error) pairs (`against` labels the parameter).
    pub fn evaluate(&self, name: String, param: &[f64], error: &[f64]) -> GateVerdict {
        let spec = RateGateSpec {
            sweep: self.series.clone(),
            scheme: None,
            error: "relative eigenvalue error".into(),
            against: Against::H,
            expected_rate: self.expected_rate,
            tolerance: self.tolerance,
            finest_levels: self.finest_levels,
            ci_width: self.ci_width,
            ceiling: self.ceiling,
            asymptotic_tolerance: self.asymptotic_tolerance,
            expected_in_ci: false,
            note: self.note.clone(),
        };
        evaluate_rate_gate(name, &spec, param, error)
    }
}

/// Writes `data` as `<out>/<case id>/data.json`.
pub fn write_data<T: Serialize>(
    ctx: &RunContext,
    report: &CaseReport,
    data: &T,
) -> Result<(), String> {
    let dir = ctx.case_dir(&report.id)?;
    let path = dir.join("data.json");
    let json = serde_json::to_string_pretty(data).map_err(|e| e.to_string())?;
    std::fs::write(&path, json).map_err(|e| format!("{}: {e}", path.display()))
}

/// A deterministic pseudo-random sequence in [−1, 1) (64-bit LCG, Knuth's MMIX constants).
#[derive(Debug, Clone)]
pub struct Lcg(pub u64);

impl Lcg {
    /// The next value in [−1, 1).
    pub fn next_signed(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        2.0 * ((self.0 >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }

    /// The next value in [0, 1).
    pub fn next_unit(&mut self) -> f64 {
        0.5 * (self.next_signed() + 1.0)
    }
}
