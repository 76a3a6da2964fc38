//! The case format of `moving_extremes` and its checks.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::core::format::{invalid, positive, CaseError};
use crate::core::gate::RateGate;
use crate::moving::study::SeriesSelect;

/// The case format of `moving_extremes`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtremesCase {
    pub critical_speed: CriticalSpeed,
    pub critical_speed_gate: RateGate<SeriesSelect>,
    pub stiff_penalty: StiffPenalty,
    pub undamped: Undamped,
    pub near_defective: NearDefective,
    pub onset_gate: RateGate<SeriesSelect>,
}

/// `[critical_speed]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CriticalSpeed {
    pub modes: usize,
    /// δ = 1 − v̄, decades (so successive differences are 0.9 C δ).
    pub distances: Vec<f64>,
    /// Below this δ the differences are round-off: checked against ε/δ instead.
    pub round_off_below: f64,
    /// |Δr| ≤ this × ε/δ there.
    pub conditioning_factor: f64,
}

/// `[stiff_penalty]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StiffPenalty {
    pub modes: usize,
    pub penalties: Vec<f64>,
    /// C of the round-off bound of the series springs against the independent sine-Galerkin
    /// model (`exact::thick_string_galerkin`) with the spring c_eff = c̄k̄_p/(c̄ + k̄_p) and the
    /// friction μh̄ c_eff, and at the largest k̄_p against ideal contact (spring c̄): every
    /// eigenvalue within C κ(λ) (n ε ‖A‖_F + ‖A(c_eff) − A(c̄)‖_F) (`moving::bounds::agreement`).
    pub series_round_off: f64,
    /// The Schur error's log–log slope against k̄_p must lie within this of 1.
    pub schur_slope_tolerance: f64,
}

/// `[undamped]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Undamped {
    pub modes: usize,
    pub points: usize,
    pub speed_range: [f64; 2],
    pub control_range: [f64; 2],
    /// |Σ Re λ| at most this × n ε max |λ| (n eigenvalues): the computed eigenvalues sum to the
    /// trace of a backward-perturbed matrix.
    pub trace_round_off: f64,
    /// The same points with this damping (reported: damping can stabilize).
    pub damping: f64,
}

/// `[near_defective]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct NearDefective {
    /// Relative distances (p − p*)/p* approached from both sides.
    pub distances: Vec<f64>,
    pub string_modes: usize,
}

impl ExtremesCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        self.critical_speed_gate
            .criteria
            .check(p, "critical_speed_gate")?;
        self.onset_gate.criteria.check(p, "onset_gate")?;
        positive(
            p,
            "stiff_penalty.series_round_off",
            self.stiff_penalty.series_round_off,
        )?;
        positive(p, "undamped.trace_round_off", self.undamped.trace_round_off)?;
        if self.undamped.points == 0 || self.near_defective.distances.len() < 3 {
            return Err(invalid(
                p,
                "undamped.points",
                self.undamped.points,
                ">= 1 (and >= 3 distances)",
            ));
        }
        Ok(())
    }
}
