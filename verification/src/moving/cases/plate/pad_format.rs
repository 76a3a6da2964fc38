//! The format of `moving_plate_pad` (the stationary pad on the rotating plate).

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::core::format::{invalid, positive, CaseError};
use crate::moving::cases::plate::common::{PadSection, PlateSection};

/// The case format of `moving_plate_pad`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PadCase {
    pub plate: PlateSection,
    pub pad: PadSection,
    /// The basis of the maps, the time checks and the virtual-work check.
    pub basis: BasisSection,
    pub spring: SpringSection,
    pub friction: FrictionSection,
    pub time_check: TimeCheckSection,
    pub onset: OnsetSection,
    pub stiff_pad: StiffPadSection,
    pub harmonics: HarmonicsSection,
}

/// `[basis]`.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BasisSection {
    pub harmonics: usize,
    pub elements: usize,
    pub radial_modes: usize,
    /// C of the round-off bound C n ε (n: the terms of an entry) of exact identities.
    pub round_off: f64,
}

/// `[spring]`: the frictionless pad's (Ω, k_p) map.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpringSection {
    /// Ω from 0 to this × the lowest critical speed Ω_c.
    pub speed_factor_to: f64,
    pub speeds: usize,
    pub stiffness_to: f64,
    pub stiffnesses: usize,
}

/// `[friction]`: the (Ω, μ) map with damping α.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSection {
    pub damping: f64,
    pub speed_from: f64,
    pub speed_to: f64,
    pub speeds: usize,
    pub friction_to: f64,
    pub frictions: usize,
    /// |max Re λ (rank-one lines) − max Re λ (faer, point by point)| ≤ this × 2n ε ρ.
    pub kernel_round_off: f64,
}

/// `[time_check]`: every point of a coarse (Ω, μ) grid integrated in time.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TimeCheckSection {
    pub speeds: usize,
    pub frictions: usize,
    /// The shortest run.
    pub duration: f64,
    /// The longest run.
    pub max_duration: f64,
    /// The run lasts separation / gap (gap: max Re λ minus the next distinct real part), so
    /// that the other modes' share has decayed by e^{−separation} relative to the critical one.
    pub separation: f64,
    pub absolute_tolerance: f64,
    pub relative_tolerance: f64,
}

/// `[onset]`: the flutter onset μ* converged in the basis.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OnsetSection {
    pub speeds: Vec<f64>,
    /// (harmonics, radial modes), in the order of growing basis.
    pub bases: Vec<[usize; 2]>,
    pub elements: usize,
    /// Relative change of μ* between the two largest bases.
    pub converged_to: f64,
}

/// `[stiff_pad]`: k_p → ∞ against the point constraint w(r_p, φ_p) = 0.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StiffPadSection {
    /// Ω as a fraction of the lowest critical speed.
    pub speed_factor: f64,
    pub stiffnesses: Vec<f64>,
    /// Stiffer pads, checked for their verdict (no false instability) and conditioning only.
    pub extreme_stiffnesses: Vec<f64>,
    /// The lowest frequencies compared.
    pub frequencies: usize,
    pub expected_rate: f64,
    pub tolerance: f64,
    pub ci_width: f64,
}

/// `[harmonics]`: many harmonics, no false verdicts.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct HarmonicsSection {
    pub harmonics: usize,
    pub radial_modes: usize,
    pub speeds: usize,
    /// Ω up to this × the largest critical speed ω_{N,0}/N.
    pub speed_factor_to: f64,
}

impl PadCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        self.plate.check(p)?;
        positive(p, "pad.stiffness", self.pad.stiffness)?;
        if !(self.pad.radius > self.plate.inner_radius
            && self.pad.radius <= self.plate.outer_radius)
        {
            return Err(invalid(
                p,
                "pad.radius",
                self.pad.radius,
                "a radius in (a, b]",
            ));
        }
        positive(p, "basis.round_off", self.basis.round_off)?;
        positive(p, "spring.speed_factor_to", self.spring.speed_factor_to)?;
        positive(p, "spring.stiffness_to", self.spring.stiffness_to)?;
        positive(p, "friction.damping", self.friction.damping)?;
        positive(p, "friction.speed_from", self.friction.speed_from)?;
        positive(p, "friction.friction_to", self.friction.friction_to)?;
        positive(
            p,
            "friction.kernel_round_off",
            self.friction.kernel_round_off,
        )?;
        positive(p, "time_check.duration", self.time_check.duration)?;
        positive(p, "time_check.separation", self.time_check.separation)?;
        if self.time_check.max_duration.is_nan()
            || self.time_check.max_duration < self.time_check.duration
        {
            return Err(invalid(
                p,
                "time_check.max_duration",
                self.time_check.max_duration,
                "at least time_check.duration",
            ));
        }
        positive(p, "onset.converged_to", self.onset.converged_to)?;
        positive(p, "stiff_pad.speed_factor", self.stiff_pad.speed_factor)?;
        if self.stiff_pad.speed_factor >= 1.0 {
            return Err(invalid(
                p,
                "stiff_pad.speed_factor",
                self.stiff_pad.speed_factor,
                "a fraction < 1 of the critical speed",
            ));
        }
        for (f, n) in [
            ("spring.speeds", self.spring.speeds),
            ("spring.stiffnesses", self.spring.stiffnesses),
            ("friction.speeds", self.friction.speeds),
            ("friction.frictions", self.friction.frictions),
            ("time_check.speeds", self.time_check.speeds),
            ("time_check.frictions", self.time_check.frictions),
            ("harmonics.speeds", self.harmonics.speeds),
        ] {
            if n < 2 {
                return Err(invalid(p, f, n, "at least 2 points"));
            }
        }
        if self.onset.bases.len() < 3 {
            return Err(invalid(
                p,
                "onset.bases",
                self.onset.bases.len(),
                "at least 3 bases",
            ));
        }
        if self.stiff_pad.stiffnesses.len() < 3 {
            return Err(invalid(
                p,
                "stiff_pad.stiffnesses",
                self.stiff_pad.stiffnesses.len(),
                "at least 3 stiffnesses",
            ));
        }
        Ok(())
    }
}
