//! The data of the rotating annular Kirchhoff plate (Hetzler 2009, §4.1, (72)–(74)) and of the
//! stationary friction pad on it: what is fixed per model ([`PlateProperties`]) and what a sweep
//! or a map varies ([`PlateData`], [`PlateParameter`]).

use serde::{Deserialize, Serialize};

use crate::error::InputError;
use crate::model::moving::linearized::AxisParameter;

/// The condition at the outer edge r = b (the inner edge r = a is clamped; for a = 0 the paper's
/// centre conditions w(0) = 0, w_r(0) = 0 hold).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OuterEdge {
    /// M_r = V_r = 0 (natural: nothing is constrained).
    Free,
    /// w = w_r = 0.
    Clamped,
    /// w = 0, M_r = 0.
    SimplySupported,
}

impl OuterEdge {
    /// The scene's spelling.
    pub fn key(self) -> &'static str {
        match self {
            OuterEdge::Free => "free",
            OuterEdge::Clamped => "clamped",
            OuterEdge::SimplySupported => "simply_supported",
        }
    }
}

/// Geometry and material of the plate (fixed for a model).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlateProperties {
    /// a ≥ 0: the clamped inner radius (0: the full disc, clamped at its centre).
    pub inner_radius: f64,
    /// b > a.
    pub outer_radius: f64,
    /// D = E h³ / (12 (1 − ν²)).
    pub bending_stiffness: f64,
    /// ρh.
    pub mass_per_area: f64,
    /// ν in (−1, 0.5].
    pub poisson: f64,
    /// h: the moment arm h/2 of the pad's friction force about the mid-surface.
    pub thickness: f64,
    pub outer_edge: OuterEdge,
    /// Adds the geometric stiffness of the in-plane stress of the spinning disc (off in the
    /// paper's example).
    pub membrane_stiffening: bool,
}

impl Default for PlateProperties {
    fn default() -> Self {
        Self {
            inner_radius: 0.2,
            outer_radius: 1.0,
            bending_stiffness: 1.0,
            mass_per_area: 1.0,
            poisson: 0.3,
            thickness: 0.02,
            outer_edge: OuterEdge::Free,
            membrane_stiffening: false,
        }
    }
}

fn positive_finite(field: &str, v: f64) -> Result<(), InputError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(InputError::new(field, v, "a finite number > 0"))
    }
}

impl PlateProperties {
    /// Checks every field (names as the scene writes them).
    pub fn validate(&self) -> Result<(), InputError> {
        positive_finite("plate.outer_radius", self.outer_radius)?;
        if !(self.inner_radius.is_finite()
            && self.inner_radius >= 0.0
            && self.inner_radius < 0.999 * self.outer_radius)
        {
            return Err(InputError::new(
                "plate.inner_radius",
                self.inner_radius,
                format!(
                    "a number in [0, 0.999 b) with b = outer_radius = {}",
                    self.outer_radius
                ),
            ));
        }
        positive_finite("plate.bending_stiffness", self.bending_stiffness)?;
        positive_finite("plate.mass_per_area", self.mass_per_area)?;
        positive_finite("plate.thickness", self.thickness)?;
        if !(self.poisson > -1.0 && self.poisson <= 0.5) {
            return Err(InputError::new(
                "plate.poisson",
                self.poisson,
                "a Poisson ratio in (−1, 0.5]",
            ));
        }
        Ok(())
    }

    /// c = sqrt(D/ρh): ω = c β² for the wavenumber β.
    pub fn wave_constant(&self) -> f64 {
        (self.bending_stiffness / self.mass_per_area).sqrt()
    }
}

/// The stationary pad at (r_p, φ_p): a normal spring k_p and Coulomb friction μ acting on the
/// plate's upper surface (moment arm h/2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PadData {
    /// r_p in (a, b].
    pub radius: f64,
    /// φ_p (rad).
    pub angle: f64,
    /// k_p ≥ 0.
    pub stiffness: f64,
    /// μ ≥ 0.
    pub friction: f64,
}

/// What varies between the points of a sweep or map.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlateData {
    /// Ω (rad per unit time): the disc turns in +φ for Ω > 0.
    pub angular_speed: f64,
    /// α: mass-proportional damping (α M q̇).
    pub damping: f64,
    pub pad: Option<PadData>,
}

impl PlateData {
    /// Checks the data against the plate (the pad must sit on it).
    pub fn validate(&self, plate: &PlateProperties) -> Result<(), InputError> {
        if !self.angular_speed.is_finite() || self.angular_speed.abs() > 1e150 {
            return Err(InputError::new(
                "plate.angular_speed",
                self.angular_speed,
                "a finite number",
            ));
        }
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return Err(InputError::new(
                "plate.damping",
                self.damping,
                "a finite number ≥ 0",
            ));
        }
        if let Some(p) = &self.pad {
            if !(p.radius.is_finite()
                && p.radius > plate.inner_radius
                && p.radius <= plate.outer_radius)
            {
                return Err(InputError::new(
                    "pad.radius",
                    p.radius,
                    format!(
                        "a radius in (a, b] = ({}, {}]",
                        plate.inner_radius, plate.outer_radius
                    ),
                ));
            }
            if !p.angle.is_finite() {
                return Err(InputError::new("pad.angle", p.angle, "a finite angle"));
            }
            for (f, v) in [("pad.stiffness", p.stiffness), ("pad.friction", p.friction)] {
                if !(0.0..=1e150).contains(&v) {
                    return Err(InputError::new(f, v, "a finite number ≥ 0"));
                }
            }
        }
        Ok(())
    }
}

/// A parameter of [`PlateData`] that sweeps and maps vary.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PlateParameter {
    /// Ω.
    AngularSpeed,
    /// α.
    Damping,
    /// k_p (needs a pad).
    PadStiffness,
    /// μ (needs a pad).
    Friction,
}

impl AxisParameter for PlateParameter {
    fn key(self) -> &'static str {
        match self {
            PlateParameter::AngularSpeed => "angular_speed",
            PlateParameter::Damping => "damping",
            PlateParameter::PadStiffness => "pad_stiffness",
            PlateParameter::Friction => "friction",
        }
    }
}

impl PlateParameter {
    /// Every parameter, in a fixed order.
    pub const ALL: [PlateParameter; 4] = [
        PlateParameter::AngularSpeed,
        PlateParameter::Damping,
        PlateParameter::PadStiffness,
        PlateParameter::Friction,
    ];

    /// The symbol used in reports and plots.
    pub fn symbol(self) -> &'static str {
        match self {
            PlateParameter::AngularSpeed => "Ω",
            PlateParameter::Damping => "α",
            PlateParameter::PadStiffness => "k_p",
            PlateParameter::Friction => "μ",
        }
    }

    /// Sets the parameter in `data` (pad parameters need a pad).
    pub fn set(self, data: &mut PlateData, value: f64) -> Result<(), InputError> {
        let field = format!("parameter.{}", self.key());
        match self {
            PlateParameter::AngularSpeed => data.angular_speed = value,
            PlateParameter::Damping => data.damping = value,
            PlateParameter::PadStiffness | PlateParameter::Friction => {
                let Some(pad) = data.pad.as_mut() else {
                    return Err(InputError::new(
                        field,
                        self.key(),
                        "a scene with a [pad] section",
                    ));
                };
                if self == PlateParameter::PadStiffness {
                    pad.stiffness = value;
                } else {
                    pad.friction = value;
                }
            }
        }
        if !value.is_finite() {
            return Err(InputError::new(field, value, "a finite number"));
        }
        Ok(())
    }
}
