//! The case format of `moving_flutter` and its checks.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::core::format::{at_least, invalid, positive, CaseError};
use crate::core::gate::RateGate;
use crate::exact::thick_string_galerkin::ThickString;
use crate::moving::study::SeriesSelect;

/// The case format of `moving_flutter`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlutterCase {
    /// The parameter sets (each with its name).
    pub set: Vec<ParameterSet>,
    /// The equal-discretization comparison (none: not part of this case).
    #[serde(default)]
    pub discrete: Option<Discrete>,
    pub continuum: Continuum,
    /// Rate gates on the series `basis/set` (eigenvalues against the continuum) and
    /// `onset/set` (the resolved sine onset against the continuum's).
    #[serde(default)]
    pub gate: Vec<RateGate<SeriesSelect>>,
}

/// `[[set]]`: the thick string with its oscillator in ideal contact.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterSet {
    pub name: String,
    pub speed: f64,
    pub damping: f64,
    pub stiffness: f64,
    pub mass: f64,
    pub position: f64,
    /// Sine sizes compared with the continuum (eigenvalues and onsets), each with N·ā an
    /// integer: the bushing then sits at a node of the last sine function, the same place in
    /// every basis (otherwise the error oscillates with the fractional part of Nā); none or ≥ 3.
    #[serde(default)]
    pub sine_modes: Vec<usize>,
    /// P1 meshes compared with the continuum (ā must be a node of each: the jump and the kink
    /// sit on a node); none by default.
    #[serde(default)]
    pub p1_elements: Vec<usize>,
    /// Hermite meshes compared with the continuum (ā a node of each); none by default.
    #[serde(default)]
    pub hermite_elements: Vec<usize>,
    /// P1 meshes whose flutter onset (from resolved eigenvalues) is compared with the
    /// continuum's (ā a node of each); none by default.
    #[serde(default)]
    pub onset_p1_elements: Vec<usize>,
    /// Hermite meshes whose onset is compared with the continuum's; none by default.
    #[serde(default)]
    pub onset_hermite_elements: Vec<usize>,
    /// ε: the width of the contact patch (0: the paper's point contact).
    #[serde(default)]
    pub patch_width: f64,
}

impl ParameterSet {
    /// The data at the control parameter p = μ c̄ h̄ = `control`.
    pub fn at(&self, control: f64) -> ThickString {
        ThickString {
            speed: self.speed,
            damping: self.damping,
            stiffness: self.stiffness,
            mass: self.mass,
            position: self.position,
            control,
            patch: self.patch_width,
        }
    }
}

/// `[discrete]`: the program against the independent sine-Galerkin model at equal N.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Discrete {
    /// Sine basis sizes compared.
    pub modes: Vec<usize>,
    /// Control parameters p at which every set is compared.
    pub controls: Vec<f64>,
    /// Matrices: |Δ entry| ≤ this × ε × max |entry| of the matrix.
    pub matrix_round_off: f64,
    /// Eigenvalues: |Δλ| ≤ this × n ε ‖A‖_F κ(λ) (n the order of the first-order matrix A).
    pub eigen_round_off: f64,
    /// Sizes whose flutter onsets are compared.
    pub onset_modes: Vec<usize>,
    /// Relative width of the bisection brackets of the onsets.
    pub bisection_tolerance: f64,
}

/// `[continuum]`: the program's resolved eigenvalues and onsets against the continuum.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Continuum {
    /// The control parameter at which the eigenvalues are compared.
    pub control: f64,
    /// The lowest roots compared (their largest relative error is the series' error).
    pub modes_checked: usize,
    /// The continuum's branches followed from p = 0 (the lowest ones) for the onset.
    pub onset_branches: usize,
    /// The onset is searched in (0, onset_max].
    pub onset_max: f64,
}

impl FlutterCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        at_least(p, "set", &self.set, 1)?;
        for (i, s) in self.set.iter().enumerate() {
            positive(p, &format!("set[{i}].stiffness"), s.stiffness)?;
            positive(p, &format!("set[{i}].mass"), s.mass)?;
            if !(s.speed.is_finite() && s.speed.abs() < 1.0) {
                return Err(invalid(p, &format!("set[{i}].speed"), s.speed, "|v̄| < 1"));
            }
            if !(s.damping.is_finite() && s.damping >= 0.0) {
                return Err(invalid(p, &format!("set[{i}].damping"), s.damping, ">= 0"));
            }
            if !(s.position > 0.0 && s.position < 1.0) {
                return Err(invalid(
                    p,
                    &format!("set[{i}].position"),
                    s.position,
                    "in (0, 1)",
                ));
            }
            for (field, sizes) in [
                (format!("set[{i}].sine_modes"), &s.sine_modes),
                (format!("set[{i}].p1_elements"), &s.p1_elements),
                (format!("set[{i}].hermite_elements"), &s.hermite_elements),
                (format!("set[{i}].onset_p1_elements"), &s.onset_p1_elements),
                (
                    format!("set[{i}].onset_hermite_elements"),
                    &s.onset_hermite_elements,
                ),
            ] {
                if !sizes.is_empty() && sizes.len() < 3 {
                    return Err(invalid(p, &field, sizes.len(), "none or >= 3 meshes"));
                }
                for &m in sizes.iter() {
                    let x = s.position * m as f64;
                    if (x - x.round()).abs() > 1e-9 {
                        return Err(invalid(
                            p,
                            &field,
                            m,
                            &format!(
                                "sizes with ā·M an integer (ā = {} in set {})",
                                s.position, s.name
                            ),
                        ));
                    }
                }
            }
        }
        if let Some(d) = &self.discrete {
            at_least(p, "discrete.modes", &d.modes, 1)?;
            at_least(p, "discrete.controls", &d.controls, 1)?;
            positive(p, "discrete.matrix_round_off", d.matrix_round_off)?;
            positive(p, "discrete.eigen_round_off", d.eigen_round_off)?;
            positive(p, "discrete.bisection_tolerance", d.bisection_tolerance)?;
        }
        let c = &self.continuum;
        positive(p, "continuum.control", c.control)?;
        positive(p, "continuum.onset_max", c.onset_max)?;
        if c.modes_checked == 0 || c.onset_branches == 0 {
            return Err(invalid(
                p,
                "continuum.modes_checked",
                c.modes_checked,
                ">= 1 (and >= 1 onset branch)",
            ));
        }
        for (i, g) in self.gate.iter().enumerate() {
            g.criteria.check(p, &format!("gate[{i}]"))?;
            let ok = g.select.series.split_once('/').is_some_and(|(b, s)| {
                [
                    "sine",
                    "p1",
                    "hermite",
                    "onset",
                    "onset_p1",
                    "onset_hermite",
                ]
                .contains(&b)
                    && self.set.iter().any(|x| x.name == s)
            });
            if !ok {
                return Err(invalid(
                    p,
                    &format!("gate[{i}].series"),
                    &g.select.series,
                    "basis/set with basis sine, p1, hermite or onset and the name of a [[set]]",
                ));
            }
        }
        Ok(())
    }
}
