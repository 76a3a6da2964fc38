//! The case format of `multibody_extremes` (unknown keys are errors) and its checks: every
//! invalid value is a [`CaseError`] naming its field.

use std::path::Path;

use serde::Deserialize;

use contactlab::model::multibody::scheme::MultibodyScheme;

use crate::core::case::Case;
use crate::core::format::{invalid, positive, CaseError};
use crate::core::gate::RateCriteria;
use crate::exact::bar_impact::HeadOnBars;
use crate::multibody::study::MaterialSpec;

/// The case file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtremesCase {
    /// The bars' law (linear, ν = 0: exactly the 1D bar).
    pub material: MaterialSpec,
    pub bars: BarsSpec,
    /// Penalty → ∞ against the multipliers.
    pub penalty: Option<PenaltySpec>,
    /// The impact speed over decades.
    pub speeds: Option<SpeedsSpec>,
    /// Steps of several contact durations.
    pub large_steps: Option<LargeStepsSpec>,
}

/// `[bars]`: two identical bars head-on (the `head_on` configuration of `multibody_bars`).
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarsSpec {
    /// L, H and ρ of each bar.
    pub length: f64,
    pub height: f64,
    pub density: f64,
    /// Elements along each bar (M) and across (rows).
    pub elements: usize,
    #[serde(default = "one")]
    pub rows: usize,
    /// k = courant · h / c of the runs at ordinary steps.
    pub courant: f64,
    /// Each bar's speed v (the speed study overrides it).
    pub speed: f64,
    /// The first contact t0 = g0/(2v): the gap is 2 v t0 at every speed.
    pub onset: f64,
    /// T (rounded up to a whole step).
    pub final_time: f64,
}

fn energy_momentum() -> MultibodyScheme {
    MultibodyScheme::EnergyMomentum
}

fn one() -> usize {
    1
}

impl BarsSpec {
    /// h = L/M.
    pub fn h(&self) -> f64 {
        self.length / self.elements as f64
    }

    /// The exact head-on impact at speed `speed` (the gap 2 v t0).
    pub fn exact(&self, young: f64, speed: f64) -> HeadOnBars {
        HeadOnBars {
            length: self.length,
            density: self.density,
            young,
            area: self.height,
            speed,
            gap: 2.0 * speed * self.onset,
        }
    }
}

/// `[penalty]`: ε = factor × E (H/rows)/h (the axial stiffness of one element row's end, per
/// slave node) against the Lagrange run of the same mesh and step: the compliant multiplier at
/// `factors` (the rate study) and the conserving penalty at `conserving.factors`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PenaltySpec {
    /// The compliant multiplier's factors (λ_N = ε g₋ at t_(n+1)).
    pub factors: Vec<f64>,
    /// The scheme of the penalty and the Lagrange runs.
    #[serde(default = "energy_momentum")]
    pub scheme: MultibodyScheme,
    /// The rate of |v_ε(T) − v_λ(T)|/v against 1/ε (compliant multiplier).
    pub rate: RateCriteria,
    /// |⟨Σ ε g₋⟩ / (A σ_c) − 1| on the plateau, at most this on every ε (compliant multiplier).
    pub force_tolerance: f64,
    pub force_note: String,
    /// The conserving penalty P = (ε/2)(g₋)².
    pub conserving: Option<ConservingSpec>,
}

/// `[penalty.conserving]`: the energy–momentum scheme with the conserving penalty.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConservingSpec {
    pub factors: Vec<f64>,
    /// max_n |E_n − E_0| / E_0, E_0 = ρ L H v² from the setup, at most this.
    pub energy_tolerance: f64,
    /// The rate of the largest penetration against 1/ε (½: the contact nodes' kinetic energy
    /// stored in the spring, g ≈ v_rel √(m/ε)).
    pub penetration_rate: RateCriteria,
    pub note: String,
    /// The same penalty with these schemes too (the force P′(g) ∇g at the scheme's evaluation
    /// point: not a discrete gradient): the momenta gated as above, and the energy's failure.
    #[serde(default)]
    pub other_schemes: Vec<MultibodyScheme>,
    /// Their factors (≥ 3 when `other_schemes` names any): the Newton iteration of a force with a
    /// kink at g = 0 stops converging at a lower stiffness than the secant form's
    /// (docs/multibody.md §10).
    #[serde(default)]
    pub other_factors: Vec<f64>,
    /// Gate: each other scheme's largest E(T)/E_0 − 1 over its factors at least this (the energy
    /// a force evaluated at a point puts into the contact: the failure the secant form removes).
    #[serde(default)]
    pub other_min_energy_gain: f64,
}

/// `[speeds]`: the head-on bars at each speed (the gap ∝ v: the same onset).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedsSpec {
    pub speeds: Vec<f64>,
    /// |e(v) − e(v_min)| / (v/c) at most this for the rebound, duration and plateau errors:
    /// the problem is linear in v up to the gap's geometric nonlinearity, O(v/c).
    pub nonlinearity: f64,
    /// Each speed's rebound error |v(T)/v ± 1| at most this.
    pub rebound_ceiling: f64,
    pub note: String,
}

/// `[large_steps]`: k = multiple × 2L/c with the energy–momentum scheme (gated) and the
/// midpoint rule (reported).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LargeStepsSpec {
    pub multiples: Vec<f64>,
    /// Steps per run at least (T = max(bars.final_time, steps · k)).
    pub min_steps: usize,
    /// max_n (E_n − E_0)/E_0 at most this (EM: the activation work is a loss).
    pub energy_rise: f64,
    /// max_n max(−g)/(v k) at most this (the multipliers' constraint to the Newton tolerance).
    pub penetration: f64,
    pub note: String,
}

impl ExtremesCase {
    /// Parses and checks a case.
    pub fn from_case(case: &Case) -> Result<Self, CaseError> {
        let file: Self = case.body()?;
        file.validate(case.path())?;
        Ok(file)
    }

    /// c = √(E/ρ).
    pub fn wave_speed(&self) -> f64 {
        self.material.wave_speed(self.bars.density)
    }

    fn validate(&self, path: &Path) -> Result<(), CaseError> {
        let m = &self.material;
        positive(path, "material.young", m.young)?;
        if m.poisson != 0.0 {
            return Err(invalid(
                path,
                "material.poisson",
                m.poisson,
                "0 (then plane strain is exactly the 1D bar with c = √(E/ρ))",
            ));
        }
        if m.law != crate::multibody::study::LawName::Linear {
            return Err(invalid(
                path,
                "material.law",
                format!("{:?}", m.law),
                "linear (the speed study needs a solution linear in v)",
            ));
        }
        let b = &self.bars;
        for (name, v) in [
            ("bars.length", b.length),
            ("bars.height", b.height),
            ("bars.density", b.density),
            ("bars.courant", b.courant),
            ("bars.speed", b.speed),
            ("bars.onset", b.onset),
            ("bars.final_time", b.final_time),
        ] {
            positive(path, name, v)?;
        }
        for (name, v) in [("bars.elements", b.elements), ("bars.rows", b.rows)] {
            if v == 0 {
                return Err(invalid(path, name, v, "at least 1"));
            }
        }
        let release = b.onset + 2.0 * b.length / self.wave_speed();
        if b.final_time <= 1.1 * release {
            return Err(invalid(
                path,
                "bars.final_time",
                b.final_time,
                &format!("after the release t0 + 2L/c = {release} (by 10 %)"),
            ));
        }
        if let Some(p) = &self.penalty {
            if p.factors.len() < 3 {
                return Err(invalid(path, "penalty.factors", p.factors.len(), "≥ 3"));
            }
            for (i, f) in p.factors.iter().enumerate() {
                positive(path, &format!("penalty.factors[{i}]"), *f)?;
            }
            p.rate.check(path, "penalty.rate")?;
            positive(path, "penalty.force_tolerance", p.force_tolerance)?;
            if let Some(c) = &p.conserving {
                for (i, f) in c.factors.iter().enumerate() {
                    positive(path, &format!("penalty.conserving.factors[{i}]"), *f)?;
                }
                positive(
                    path,
                    "penalty.conserving.energy_tolerance",
                    c.energy_tolerance,
                )?;
                c.penetration_rate
                    .check(path, "penalty.conserving.penetration_rate")?;
                if !c.other_schemes.is_empty() && c.other_factors.len() < 3 {
                    return Err(invalid(
                        path,
                        "penalty.conserving.other_factors",
                        c.other_factors.len(),
                        "≥ 3 (other_schemes is not empty)",
                    ));
                }
                if !c.other_schemes.is_empty() {
                    positive(
                        path,
                        "penalty.conserving.other_min_energy_gain",
                        c.other_min_energy_gain,
                    )?;
                }
                for (i, f) in c.other_factors.iter().enumerate() {
                    positive(path, &format!("penalty.conserving.other_factors[{i}]"), *f)?;
                }
                if let Some(s) = c.other_schemes.iter().find(|&&s| s == p.scheme) {
                    return Err(invalid(
                        path,
                        "penalty.conserving.other_schemes",
                        s.name(),
                        "schemes other than penalty.scheme",
                    ));
                }
                if c.factors.len() < 3 {
                    return Err(invalid(
                        path,
                        "penalty.conserving.factors",
                        c.factors.len(),
                        "≥ 3",
                    ));
                }
            }
        }
        if let Some(s) = &self.speeds {
            if s.speeds.is_empty() {
                return Err(invalid(path, "speeds.speeds", "[]", "at least one"));
            }
            for (i, v) in s.speeds.iter().enumerate() {
                positive(path, &format!("speeds.speeds[{i}]"), *v)?;
            }
            positive(path, "speeds.nonlinearity", s.nonlinearity)?;
            if s.speeds.len() < 2 {
                return Err(invalid(
                    path,
                    "speeds.speeds",
                    s.speeds.len(),
                    "at least two",
                ));
            }
            positive(path, "speeds.rebound_ceiling", s.rebound_ceiling)?;
        }
        if let Some(l) = &self.large_steps {
            if l.multiples.is_empty() {
                return Err(invalid(path, "large_steps.multiples", "[]", "at least one"));
            }
            for (i, v) in l.multiples.iter().enumerate() {
                positive(path, &format!("large_steps.multiples[{i}]"), *v)?;
            }
            if l.min_steps == 0 {
                return Err(invalid(path, "large_steps.min_steps", 0, "at least 1"));
            }
            positive(path, "large_steps.energy_rise", l.energy_rise)?;
            positive(path, "large_steps.penetration", l.penetration)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! The case format: the shipped cases parse; unknown keys, ν ≠ 0, a nonlinear law, a final
    //! time before the release, too few penalty levels and a non-positive speed are typed errors
    //! naming the field.
    use std::path::Path;

    use super::*;

    const MINIMAL: &str = r#"
id = "t"
title = "t"
kind = "multibody_extremes"
explanation = "e"
[material]
law = "linear"
young = 9.0
poisson = 0.0
[bars]
length = 1.0
height = 0.25
density = 4.0
elements = 10
courant = 1.0
speed = 0.1
onset = 0.1
final_time = 1.6
[penalty]
factors = [1.0, 10.0, 100.0]
force_tolerance = 1e-2
force_note = "n"
rate = { expected_rate = 1.0, tolerance = 0.1, ci_width = 0.2 }
[speeds]
speeds = [1e-3, 1e-2]
nonlinearity = 1e-2
rebound_ceiling = 0.1
note = "n"
"#;

    fn parse(text: &str) -> Result<ExtremesCase, CaseError> {
        ExtremesCase::from_case(&Case::from_text(Path::new("c.toml"), text)?)
    }

    fn error_of(text: &str) -> String {
        parse(text).expect_err("an invalid case").to_string()
    }

    #[test]
    fn minimal_and_shipped_cases_parse() {
        parse(MINIMAL).expect("minimal");
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
        for name in ["multibody_extremes.toml", "multibody_extremes_quick.toml"] {
            let case = Case::read(&dir.join(name)).expect("readable");
            ExtremesCase::from_case(&case).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }

    #[test]
    fn invalid_values_are_typed_errors_naming_the_field() {
        let e = error_of(&MINIMAL.replace("poisson = 0.0", "poisson = 0.3"));
        assert!(e.contains("material.poisson"), "{e}");
        let e = error_of(&MINIMAL.replace("law = \"linear\"", "law = \"neo_hooke\""));
        assert!(e.contains("material.law"), "{e}");
        let e = error_of(&MINIMAL.replace("final_time = 1.6", "final_time = 1.0"));
        assert!(e.contains("bars.final_time"), "{e}");
        let e = error_of(&MINIMAL.replace("[1.0, 10.0, 100.0]", "[1.0, 10.0]"));
        assert!(e.contains("penalty.factors"), "{e}");
        let e = error_of(&MINIMAL.replace("[1e-3, 1e-2]", "[1e-3, -1e-2]"));
        assert!(e.contains("speeds.speeds[1]"), "{e}");
        let e = error_of(&MINIMAL.replace("onset = 0.1", "onset = 0.1\nstray = 1"));
        assert!(e.contains("stray"), "{e}");
    }
}
