//! The dimensionless data of the axially moving string with an attached oscillator
//! (Hetzler 2009, §4.2.1–4.2.2, (79)–(82)).
//!
//! With ξ = x/L, τ = ω t, ω² = P/(ρ A L²):
//! v̄ = v/(L ω) (transport speed; v̄ = 1 is the wave speed), ᾱ = α/ω (mass-proportional damping),
//! c̄ = c/(P/L) (bushing spring), m̄ = m/(ρ A L) (oscillator mass), ā = a/L (bushing position),
//! k̄_p = k_p/(P/L) (penalty contact stiffness), and for the thick string the friction product
//! μ h̄ (friction coefficient times thickness h/L), which gives the control parameter of the
//! circulatory terms p = μ c̄ h̄ (ideal contact, (103)) or p = μ k̄_p h̄ (penalty, (108)).

use serde::{Deserialize, Serialize};

use crate::error::{require_finite, require_nonnegative, require_positive, InputError};

/// How the normal contact in the bushing is enforced.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactModel {
    /// Kinematically exact: y_c = w(ā) (restricted function spaces, (75)).
    Ideal,
    /// Penalty: potential (k̄_p/2)(y_c − w(ā))² with a massless bushing coordinate y_c (87)–(91).
    Penalty {
        /// k̄_p > 0.
        stiffness: f64,
    },
}

/// The oscillator attached through the bushing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OscillatorData {
    /// c̄ > 0.
    pub stiffness: f64,
    /// m̄ > 0.
    pub mass: f64,
    /// ā ∈ (0, 1).
    pub position: f64,
    pub contact: ContactModel,
    /// μ h̄ ≥ 0: friction coefficient times the dimensionless thickness (0: the thin string of
    /// §4.2.1, on which friction does no virtual work).
    pub friction: f64,
    /// ε ≥ 0: the width of the contact patch centred at ā (0: the paper's point contact). With
    /// ε > 0 the bushing reads the patch mean of w and the friction moment acts on the mean slope
    /// (w(ā + ε/2) − w(ā − ε/2))/ε, both bounded on H¹ (docs/moving_continua.md).
    #[serde(default)]
    pub patch_width: f64,
}

/// The moving string and, optionally, its oscillator.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MovingStringData {
    /// v̄.
    pub speed: f64,
    /// ᾱ ≥ 0.
    pub damping: f64,
    pub oscillator: Option<OscillatorData>,
}

impl MovingStringData {
    /// The string alone.
    pub fn string(speed: f64, damping: f64) -> Self {
        Self {
            speed,
            damping,
            oscillator: None,
        }
    }

    /// Checks every value, naming the field of an invalid one.
    pub fn validate(&self) -> Result<(), InputError> {
        require_finite("string.speed", self.speed)?;
        require_nonnegative("string.damping", self.damping)?;
        if let Some(o) = &self.oscillator {
            require_positive("oscillator.stiffness", o.stiffness)?;
            require_positive("oscillator.mass", o.mass)?;
            if !(o.position.is_finite() && o.position > 0.0 && o.position < 1.0) {
                return Err(InputError::new(
                    "oscillator.position",
                    o.position,
                    "a number in (0, 1) (the guides are at 0 and 1)",
                ));
            }
            require_nonnegative("oscillator.friction", o.friction)?;
            require_nonnegative("oscillator.patch_width", o.patch_width)?;
            if !(o.position - 0.5 * o.patch_width > 0.0 && o.position + 0.5 * o.patch_width < 1.0) {
                return Err(InputError::new(
                    "oscillator.patch_width",
                    o.patch_width,
                    format!(
                        "a patch inside the string: ā ± ε/2 in (0, 1) with ā = {}",
                        o.position
                    ),
                ));
            }
            if let ContactModel::Penalty { stiffness } = o.contact {
                require_positive("oscillator.penalty_stiffness", stiffness)?;
            }
        }
        Ok(())
    }

    /// The control parameter of the circulatory terms: p = μ h̄ c̄ (ideal contact) or
    /// p = μ h̄ k̄_p (penalty); 0 without an oscillator.
    pub fn control_parameter(&self) -> f64 {
        match &self.oscillator {
            None => 0.0,
            Some(o) => o.friction * o.contact_stiffness(),
        }
    }
}

impl OscillatorData {
    /// The stiffness that multiplies the friction product in the control parameter: c̄ (ideal)
    /// or k̄_p (penalty).
    pub fn contact_stiffness(&self) -> f64 {
        match self.contact {
            ContactModel::Ideal => self.stiffness,
            ContactModel::Penalty { stiffness } => stiffness,
        }
    }
}

/// A parameter of [`MovingStringData`] that sweeps and maps vary.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StringParameter {
    /// v̄.
    Speed,
    /// ᾱ.
    Damping,
    /// c̄.
    OscillatorStiffness,
    /// m̄.
    OscillatorMass,
    /// ā.
    Position,
    /// k̄_p (penalty contact only).
    PenaltyStiffness,
    /// μ h̄.
    Friction,
    /// p = μ h̄ c̄ or μ h̄ k̄_p: sets μ h̄ = p / (c̄ or k̄_p).
    ControlParameter,
}

impl StringParameter {
    /// The symbol used in reports and plots.
    pub fn symbol(self) -> &'static str {
        match self {
            StringParameter::Speed => "v̄",
            StringParameter::Damping => "ᾱ",
            StringParameter::OscillatorStiffness => "c̄",
            StringParameter::OscillatorMass => "m̄",
            StringParameter::Position => "ā",
            StringParameter::PenaltyStiffness => "k̄_p",
            StringParameter::Friction => "μh̄",
            StringParameter::ControlParameter => "p",
        }
    }

    /// True when the parameter changes the mass matrix (a solver must refactor M).
    pub fn changes_mass(self) -> bool {
        matches!(self, StringParameter::OscillatorMass)
    }

    /// Sets the parameter in `data` (which must have an oscillator for the oscillator's
    /// parameters, and penalty contact for k̄_p); the result is validated.
    pub fn set(self, data: &mut MovingStringData, value: f64) -> Result<(), InputError> {
        let field = format!("parameter.{}", self.key());
        let need_osc = || {
            InputError::new(
                field.clone(),
                value,
                "a scene with an [oscillator] for this parameter",
            )
        };
        match self {
            StringParameter::Speed => data.speed = value,
            StringParameter::Damping => data.damping = value,
            _ => {
                let o = data.oscillator.as_mut().ok_or_else(need_osc)?;
                match self {
                    StringParameter::OscillatorStiffness => o.stiffness = value,
                    StringParameter::OscillatorMass => o.mass = value,
                    StringParameter::Position => o.position = value,
                    StringParameter::Friction => o.friction = value,
                    StringParameter::ControlParameter => {
                        o.friction = value / o.contact_stiffness();
                    }
                    StringParameter::PenaltyStiffness => match &mut o.contact {
                        ContactModel::Penalty { stiffness } => *stiffness = value,
                        ContactModel::Ideal => {
                            return Err(InputError::new(
                                field,
                                value,
                                "penalty contact for the parameter penalty_stiffness",
                            ))
                        }
                    },
                    StringParameter::Speed | StringParameter::Damping => {}
                }
            }
        }
        data.validate()
    }

    /// The scene key of the parameter.
    pub fn key(self) -> &'static str {
        match self {
            StringParameter::Speed => "speed",
            StringParameter::Damping => "damping",
            StringParameter::OscillatorStiffness => "oscillator_stiffness",
            StringParameter::OscillatorMass => "oscillator_mass",
            StringParameter::Position => "position",
            StringParameter::PenaltyStiffness => "penalty_stiffness",
            StringParameter::Friction => "friction",
            StringParameter::ControlParameter => "control_parameter",
        }
    }
}

#[cfg(test)]
mod tests {
    //! Setting: the data checks. Goal: each invalid value names its field; the control parameter
    //! follows the contact model.
    use super::*;

    fn osc(contact: ContactModel) -> MovingStringData {
        MovingStringData {
            speed: 0.3,
            damping: 0.01,
            oscillator: Some(OscillatorData {
                stiffness: 2.0,
                mass: 0.5,
                position: 0.3,
                contact,
                friction: 0.1,
                patch_width: 0.0,
            }),
        }
    }

    #[test]
    fn control_parameter_is_mu_h_times_contact_stiffness() {
        assert!((osc(ContactModel::Ideal).control_parameter() - 0.2).abs() < 1e-15);
        let pen = osc(ContactModel::Penalty { stiffness: 50.0 });
        assert!((pen.control_parameter() - 5.0).abs() < 1e-14);
        let mut d = pen;
        StringParameter::ControlParameter.set(&mut d, 10.0).unwrap();
        assert!((d.oscillator.unwrap().friction - 0.2).abs() < 1e-15);
    }

    #[test]
    fn invalid_values_name_their_field() {
        let mut d = osc(ContactModel::Ideal);
        d.oscillator.as_mut().unwrap().position = 1.0;
        assert_eq!(d.validate().unwrap_err().field, "oscillator.position");
        let mut d = osc(ContactModel::Penalty { stiffness: -1.0 });
        assert_eq!(
            d.validate().unwrap_err().field,
            "oscillator.penalty_stiffness"
        );
        d = MovingStringData::string(f64::NAN, 0.0);
        assert_eq!(d.validate().unwrap_err().field, "string.speed");
        // a patch reaching a guide, and a negative width
        for width in [2.0, -0.1, f64::NAN] {
            let mut d = osc(ContactModel::Ideal);
            d.oscillator.as_mut().unwrap().patch_width = width;
            assert_eq!(d.validate().unwrap_err().field, "oscillator.patch_width");
        }
        let e = StringParameter::PenaltyStiffness
            .set(&mut osc(ContactModel::Ideal), 3.0)
            .unwrap_err();
        assert_eq!(e.field, "parameter.penalty_stiffness");
        let e = StringParameter::Position
            .set(&mut MovingStringData::string(0.1, 0.0), 0.5)
            .unwrap_err();
        assert!(e.expected.contains("oscillator"));
    }
}
