//! The case format of `moving_penalty` and its checks: the model, the frictionless and friction
//! studies, the map, and their gates.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::core::format::CaseError;
use crate::core::format::{at_least, positive};
use crate::core::gate::RateGate;
use crate::moving::study::{Bushing, SeriesSelect};

/// The case format of `moving_penalty`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PenaltyCase {
    pub model: Model,
    pub frictionless: Frictionless,
    pub convergence_gate: RateGate<SeriesSelect>,
    pub friction: Friction,
    pub boundary_gate: RateGate<SeriesSelect>,
    pub map: PenaltyMap,
}

/// `[model]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Model {
    pub modes: usize,
    pub stiffness: f64,
    pub mass: f64,
    pub position: f64,
}

/// `[frictionless]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Frictionless {
    pub speed: f64,
    pub damping: f64,
    pub modes_checked: usize,
    pub penalties: Vec<f64>,
    /// C of the round-off bound of the three solution paths (QZ on the DAE, Schur, series):
    /// their relative eigenvalue difference at most C n ε (1 + k̄_p/c̄), n the order of the
    /// uncondensed companion pencil: the backward error n ε of each path, amplified by the
    /// cancellation of k̄_p against c̄ in the stiffness of the massless coordinate.
    pub agreement_round_off: f64,
    /// k̄_p up to which the paths are compared (the generic Schur complement loses
    /// log10(k̄_p/c̄) digits; see moving_extremes).
    pub agreement_up_to: f64,
}

/// `[friction]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Friction {
    pub damping: f64,
    pub speeds: Vec<f64>,
    pub penalties: Vec<f64>,
    /// The bisection stops at this relative width.
    pub bisection_tolerance: f64,
    /// Fitted log–log slope of the nominal p* against k̄_p (k̄_p ≥ 10 c̄) within this of 1.
    pub nominal_slope_tolerance: f64,
}

/// `[map]`: verdicts over (v̄, k̄_p) at a fixed friction product.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PenaltyMap {
    /// μh̄ as a multiple of the ideal model's critical μh̄ at `reference_speed`.
    pub friction_factor: f64,
    pub reference_speed: f64,
    pub speeds: usize,
    pub speed_to: f64,
    pub penalties: usize,
    pub penalty_from: f64,
    pub penalty_to: f64,
}

impl Model {
    /// The oscillator of the model.
    pub fn bushing(&self) -> Bushing {
        Bushing {
            stiffness: self.stiffness,
            mass: self.mass,
            position: self.position,
        }
    }
}

impl PenaltyCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        positive(p, "model.stiffness", self.model.stiffness)?;
        positive(p, "model.mass", self.model.mass)?;
        at_least(p, "frictionless.penalties", &self.frictionless.penalties, 3)?;
        at_least(p, "friction.speeds", &self.friction.speeds, 1)?;
        at_least(p, "friction.penalties", &self.friction.penalties, 3)?;
        self.convergence_gate
            .criteria
            .check(p, "convergence_gate")?;
        self.boundary_gate.criteria.check(p, "boundary_gate")?;
        positive(
            p,
            "friction.bisection_tolerance",
            self.friction.bisection_tolerance,
        )?;
        positive(
            p,
            "frictionless.agreement_round_off",
            self.frictionless.agreement_round_off,
        )?;
        positive(p, "map.friction_factor", self.map.friction_factor)?;
        positive(p, "map.penalty_from", self.map.penalty_from)?;
        Ok(())
    }
}
