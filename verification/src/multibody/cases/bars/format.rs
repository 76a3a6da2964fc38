//! The case format of kind `multibody_bars` (unknown keys are errors) and its checks: every
//! invalid value is a [`CaseError`] naming its field.

use serde::Deserialize;

use contactlab::model::multibody::scheme::MultibodyScheme;

use crate::core::case::Case;
use crate::core::format::{invalid, positive, CaseError};
use crate::core::gate::RateGate;
use crate::exact::bar_impact::{HeadOnBars, StrikerTarget, TwoBarImpact};
use crate::multibody::cases::bars::measure::ERRORS;
use crate::multibody::cases::bars::setup::{Geometry, Level};
use crate::multibody::study::{LawName, MaterialSpec};

/// The case file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarsCase {
    /// The material of every run (a family may change the law).
    pub material: MaterialSpec,
    #[serde(rename = "configuration")]
    pub configurations: Vec<ConfigurationSpec>,
    #[serde(rename = "family")]
    pub families: Vec<FamilySpec>,
    #[serde(rename = "sweep")]
    pub sweeps: Vec<SweepSpec>,
    #[serde(rename = "gate", default)]
    pub gates: Vec<RateGate<Select>>,
    #[serde(rename = "ceiling", default)]
    pub ceilings: Vec<CeilingSpec>,
    /// Contact durations within a number of steps on every level.
    #[serde(rename = "duration", default)]
    pub durations: Vec<DurationSpec>,
    /// The finest level's error against the prediction of E = C h^p from the coarser levels.
    #[serde(rename = "prediction", default)]
    pub predictions: Vec<PredictionSpec>,
    /// The finest level's error within a tolerance of a value.
    #[serde(rename = "within", default)]
    pub withins: Vec<WithinSpec>,
}

/// Which impact a configuration is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Impact {
    /// Two bars of length L at ±v.
    HeadOn,
    /// A striker (left, L1, at v) hitting a target (right, L2 ≥ L1, at rest).
    Striker,
}

/// `[[configuration]]`: the two bars and their approach.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConfigurationSpec {
    pub name: String,
    pub impact: Impact,
    /// L1: the striker, or each bar of the head-on pair.
    pub striker_length: f64,
    /// L2 (striker only; a whole multiple of L1 / M on every level).
    pub target_length: Option<f64>,
    /// H: the section (per unit thickness).
    pub height: f64,
    pub density: f64,
    /// v: each bar's speed (head-on) or the striker's.
    pub speed: f64,
    /// g0 between the facing ends.
    pub gap: f64,
    /// T (rounded up to a whole step on each level).
    pub final_time: f64,
    /// Elements across the height.
    #[serde(default = "one")]
    pub rows: usize,
    /// The level whose histories are plotted.
    pub show: ShowSpec,
}

fn one() -> usize {
    1
}

/// `[configuration.show]`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShowSpec {
    pub elements: usize,
    pub courant: f64,
}

impl ConfigurationSpec {
    /// The target's length (L1 head-on).
    pub fn right_length(&self) -> f64 {
        match self.impact {
            Impact::HeadOn => self.striker_length,
            Impact::Striker => self.target_length.unwrap_or(f64::NAN),
        }
    }

    /// The geometry of the runs.
    pub fn geometry(&self) -> Geometry {
        Geometry {
            left_length: self.striker_length,
            right_length: self.right_length(),
            height: self.height,
            density: self.density,
            gap: self.gap,
            left_velocity: self.speed,
            right_velocity: match self.impact {
                Impact::HeadOn => -self.speed,
                Impact::Striker => 0.0,
            },
        }
    }

    /// The exact impact for Young's modulus `young`.
    pub fn exact(&self, young: f64) -> Box<dyn TwoBarImpact> {
        match self.impact {
            Impact::HeadOn => Box::new(HeadOnBars {
                length: self.striker_length,
                density: self.density,
                young,
                area: self.height,
                speed: self.speed,
                gap: self.gap,
            }),
            Impact::Striker => Box::new(StrikerTarget {
                striker_length: self.striker_length,
                target_length: self.right_length(),
                density: self.density,
                young,
                area: self.height,
                speed: self.speed,
                gap: self.gap,
            }),
        }
    }

    /// The level of M elements at Courant number `courant` (k = courant · h/c).
    pub fn level(&self, elements: usize, courant: f64, wave_speed: f64) -> Level {
        Level::with_courant(
            &self.geometry(),
            elements,
            self.rows,
            courant,
            wave_speed,
            self.final_time,
        )
    }
}

/// `[[family]]`: a scheme, one or two passes, optionally another law.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FamilySpec {
    pub name: String,
    pub scheme: MultibodyScheme,
    #[serde(default)]
    pub two_pass: bool,
    /// A law other than the material's (same constants).
    pub law: Option<LawName>,
}

impl FamilySpec {
    /// The family's material.
    pub fn material(&self, base: &MaterialSpec) -> MaterialSpec {
        MaterialSpec {
            law: self.law.unwrap_or(base.law),
            ..*base
        }
    }
}

/// `[[sweep]]`: levels of one configuration run by some families.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    pub name: String,
    pub configuration: String,
    pub families: Vec<String>,
    /// M along the left bar, coarse to fine.
    pub elements: Vec<usize>,
    /// k = courant · h / c on every level (one number), or one per level.
    pub courant: Vec<f64>,
    /// Errors plotted against h (or k when the courant numbers vary) besides the gated ones.
    #[serde(default)]
    pub plot: Vec<String>,
}

impl SweepSpec {
    /// The (M, courant) of each level.
    pub fn levels(&self) -> Vec<(usize, f64)> {
        let n = self.elements.len().max(self.courant.len());
        (0..n)
            .map(|i| {
                let m = self.elements[i.min(self.elements.len() - 1)];
                let c = self.courant[i.min(self.courant.len() - 1)];
                (m, c)
            })
            .collect()
    }

    /// Whether the sweep refines k at a fixed mesh (then rates are against k).
    pub fn against_k(&self) -> bool {
        self.elements.len() == 1 && self.courant.len() > 1
    }
}

/// What a `[[gate]]` selects.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Select {
    pub sweep: String,
    pub family: String,
    pub error: String,
}

/// `[[ceiling]]`: the finest level's error at most `ceiling`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CeilingSpec {
    pub sweep: String,
    pub family: String,
    pub error: String,
    pub ceiling: f64,
    pub note: String,
}

/// `[[duration]]`: on every level |T_c − (t_end − t_start)| / k ≤ widths · s_A + 1, s_A the
/// Airy width of the returning front in steps ([`airy_width_steps`]) and 1 the step's
/// quantization of the release.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DurationSpec {
    pub sweep: String,
    pub family: String,
    pub airy_widths: f64,
    pub note: String,
}

/// The width, in steps, of a front that travelled for `t` on P1 elements of size h with the
/// consistent mass and the midpoint rule at step k (docs/multibody.md, "the release").
///
/// The discrete dispersion relation: the consistent mass gives ω_h = cκ (1 + (κh)²/24 + …), the
/// midpoint rule ω = ω_h (1 − (ω_h k)²/12 + …), so ω = cκ − β κ³ with β = c h² (2C² − 1)/24,
/// C = ck/h. A jump carried for a time t becomes ∫ Ai over the width (3 |β| t)^{1/3}; in steps
/// s_A = (3 |β| t)^{1/3} / (c k). (At C = 1: s_A = (c t/(8h))^{1/3}.)
pub fn airy_width_steps(c: f64, h: f64, k: f64, t: f64) -> f64 {
    let courant = c * k / h;
    let beta = c * h * h * (2.0 * courant * courant - 1.0).abs() / 24.0;
    (3.0 * beta * t).cbrt() / (c * k)
}

/// `[[prediction]]`: the finest error ≤ factor × C h_f^p, C fitted (in the log) on the coarser
/// levels with the exponent p = `rate`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PredictionSpec {
    pub sweep: String,
    pub family: String,
    pub error: String,
    pub rate: f64,
    pub factor: f64,
    pub note: String,
}

/// `[[within]]`: the finest level's error in [value − tolerance, value + tolerance].
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WithinSpec {
    pub sweep: String,
    pub family: String,
    pub error: String,
    pub value: f64,
    pub tolerance: f64,
    pub note: String,
}

impl BarsCase {
    /// Parses and checks a case.
    pub fn from_case(case: &Case) -> Result<Self, CaseError> {
        let file: Self = case.body()?;
        file.validate(case.path())?;
        Ok(file)
    }

    /// The configuration named `name`.
    pub fn configuration(&self, name: &str) -> Option<&ConfigurationSpec> {
        self.configurations.iter().find(|c| c.name == name)
    }

    /// The family named `name`.
    pub fn family(&self, name: &str) -> Option<&FamilySpec> {
        self.families.iter().find(|f| f.name == name)
    }

    /// c = √(E/ρ) of a configuration (ν = 0: the plane-strain P-wave speed; checked).
    pub fn wave_speed(&self, c: &ConfigurationSpec) -> f64 {
        self.material.wave_speed(c.density)
    }

    fn validate(&self, path: &std::path::Path) -> Result<(), CaseError> {
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
        if self.configurations.is_empty() {
            return Err(invalid(path, "configuration", "(none)", "at least one"));
        }
        for (i, c) in self.configurations.iter().enumerate() {
            let f = |n: &str| format!("configuration[{i}].{n}");
            for (name, v) in [
                ("striker_length", c.striker_length),
                ("height", c.height),
                ("density", c.density),
                ("speed", c.speed),
                ("final_time", c.final_time),
                ("show.courant", c.show.courant),
            ] {
                positive(path, &f(name), v)?;
            }
            if !(c.gap.is_finite() && c.gap >= 0.0) {
                return Err(invalid(path, &f("gap"), c.gap, "a finite gap ≥ 0"));
            }
            match (c.impact, c.target_length) {
                (Impact::HeadOn, Some(l)) => {
                    return Err(invalid(
                        path,
                        &f("target_length"),
                        l,
                        "no target_length for a head-on pair (both bars are striker_length)",
                    ))
                }
                (Impact::Striker, None) => {
                    return Err(invalid(path, &f("target_length"), "(none)", "L2 ≥ L1"))
                }
                (Impact::Striker, Some(l)) if !(l.is_finite() && l >= c.striker_length) => {
                    return Err(invalid(path, &f("target_length"), l, "L2 ≥ L1"))
                }
                _ => {}
            }
            if c.rows == 0 {
                return Err(invalid(path, &f("rows"), 0, "at least 1"));
            }
            if c.show.elements == 0 {
                return Err(invalid(path, &f("show.elements"), 0, "at least 1"));
            }
            let exact = c.exact(m.young);
            // the measured release needs a few steps after it
            if c.final_time <= exact.contact_end() {
                return Err(invalid(
                    path,
                    &f("final_time"),
                    c.final_time,
                    &format!("a time after the release at {}", exact.contact_end()),
                ));
            }
            if self.configurations[..i].iter().any(|o| o.name == c.name) {
                return Err(invalid(path, &f("name"), &c.name, "a unique name"));
            }
        }
        for (i, fam) in self.families.iter().enumerate() {
            if self.families[..i].iter().any(|o| o.name == fam.name) {
                return Err(invalid(
                    path,
                    &format!("family[{i}].name"),
                    &fam.name,
                    "a unique name",
                ));
            }
        }
        for (i, s) in self.sweeps.iter().enumerate() {
            let f = |n: &str| format!("sweep[{i}].{n}");
            let Some(conf) = self.configuration(&s.configuration) else {
                return Err(invalid(
                    path,
                    &f("configuration"),
                    &s.configuration,
                    "a [[configuration]] name",
                ));
            };
            for fam in &s.families {
                if self.family(fam).is_none() {
                    return Err(invalid(path, &f("families"), fam, "a [[family]] name"));
                }
            }
            if s.elements.is_empty() || s.elements.contains(&0) {
                return Err(invalid(path, &f("elements"), "", "M ≥ 1 on every level"));
            }
            if s.courant.is_empty() || s.courant.iter().any(|c| !(c.is_finite() && *c > 0.0)) {
                return Err(invalid(path, &f("courant"), "", "numbers > 0"));
            }
            if s.elements.len() > 1 && s.courant.len() > 1 && s.elements.len() != s.courant.len() {
                return Err(invalid(
                    path,
                    &f("courant"),
                    s.courant.len(),
                    "one number, or one per level",
                ));
            }
            for e in &s.plot {
                if !ERRORS.contains(&e.as_str()) {
                    return Err(invalid(path, &f("plot"), e, &ERRORS.join(", ")));
                }
            }
            if conf.impact == Impact::Striker {
                for &m in &s.elements {
                    let ratio = conf.right_length() / conf.striker_length * m as f64;
                    if (ratio - ratio.round()).abs() > 1e-9 {
                        return Err(invalid(
                            path,
                            &f("elements"),
                            m,
                            "M with L2/L1 · M whole (the same h in both bars)",
                        ));
                    }
                }
            }
        }
        let known = |p: &str, i: usize, sweep: &str, family: &str| -> Result<(), CaseError> {
            let Some(s) = self.sweeps.iter().find(|s| s.name == sweep) else {
                return Err(invalid(
                    path,
                    &format!("{p}[{i}].sweep"),
                    sweep,
                    "a sweep name",
                ));
            };
            if !s.families.iter().any(|f| f == family) {
                return Err(invalid(
                    path,
                    &format!("{p}[{i}].family"),
                    family,
                    "a family of the sweep",
                ));
            }
            Ok(())
        };
        let error_name = |p: &str, i: usize, e: &str| -> Result<(), CaseError> {
            if ERRORS.contains(&e) {
                Ok(())
            } else {
                Err(invalid(
                    path,
                    &format!("{p}[{i}].error"),
                    e,
                    &ERRORS.join(", "),
                ))
            }
        };
        for (i, g) in self.gates.iter().enumerate() {
            known("gate", i, &g.select.sweep, &g.select.family)?;
            error_name("gate", i, &g.select.error)?;
            g.criteria.check(path, &format!("gate[{i}]"))?;
        }
        for (i, c) in self.ceilings.iter().enumerate() {
            known("ceiling", i, &c.sweep, &c.family)?;
            error_name("ceiling", i, &c.error)?;
            positive(path, &format!("ceiling[{i}].ceiling"), c.ceiling)?;
        }
        for (i, d) in self.durations.iter().enumerate() {
            known("duration", i, &d.sweep, &d.family)?;
            positive(path, &format!("duration[{i}].airy_widths"), d.airy_widths)?;
        }
        for (i, w) in self.withins.iter().enumerate() {
            known("within", i, &w.sweep, &w.family)?;
            error_name("within", i, &w.error)?;
            positive(path, &format!("within[{i}].tolerance"), w.tolerance)?;
            if !w.value.is_finite() {
                return Err(invalid(
                    path,
                    &format!("within[{i}].value"),
                    w.value,
                    "a number",
                ));
            }
        }
        for (i, p) in self.predictions.iter().enumerate() {
            known("prediction", i, &p.sweep, &p.family)?;
            error_name("prediction", i, &p.error)?;
            positive(path, &format!("prediction[{i}].rate"), p.rate)?;
            if !(p.factor > 1.0 && p.factor <= crate::core::gate::MAX_CEILING_FACTOR) {
                return Err(invalid(
                    path,
                    &format!("prediction[{i}].factor"),
                    p.factor,
                    "in (1, 3]",
                ));
            }
            let levels = self
                .sweeps
                .iter()
                .find(|s| s.name == p.sweep)
                .map_or(0, |s| s.levels().len());
            if levels < 3 {
                return Err(invalid(
                    path,
                    &format!("prediction[{i}].sweep"),
                    &p.sweep,
                    "a sweep of at least 3 levels",
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! The case format: the shipped cases parse; unknown keys, ν ≠ 0, a target shorter than the
    //! striker, a final time before the release, a mesh whose h differs between the bars and a
    //! gate on an unknown error are typed errors naming the field.
    use std::path::Path;

    use super::*;

    const MINIMAL: &str = r#"
id = "t"
title = "t"
kind = "multibody_bars"
explanation = "e"
[material]
law = "linear"
young = 9.0
poisson = 0.0
[[configuration]]
name = "s"
impact = "striker"
striker_length = 1.0
target_length = 2.0
height = 0.25
density = 4.0
speed = 0.1
gap = 0.01
final_time = 1.6
show = { elements = 10, courant = 1.0 }
[[family]]
name = "em"
scheme = "energy_momentum"
[[sweep]]
name = "d"
configuration = "s"
families = ["em"]
elements = [10, 20, 40]
courant = [1.0]
[[gate]]
sweep = "d"
family = "em"
error = "onset_work"
expected_rate = 1.0
tolerance = 0.02
ci_width = 0.02
"#;

    fn parse(text: &str) -> Result<BarsCase, CaseError> {
        BarsCase::from_case(&Case::from_text(Path::new("c.toml"), text)?)
    }

    fn error_of(text: &str) -> String {
        parse(text).expect_err("an invalid case").to_string()
    }

    #[test]
    fn minimal_and_shipped_cases_parse() {
        parse(MINIMAL).expect("minimal");
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
        for name in ["multibody_bars.toml", "multibody_bars_quick.toml"] {
            let case = Case::read(&dir.join(name)).expect("readable");
            BarsCase::from_case(&case).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }

    #[test]
    fn invalid_values_are_typed_errors_naming_the_field() {
        let e = error_of(&MINIMAL.replace("poisson = 0.0", "poisson = 0.3"));
        assert!(e.contains("material.poisson"), "{e}");
        let e = error_of(&MINIMAL.replace("target_length = 2.0", "target_length = 0.5"));
        assert!(e.contains("configuration[0].target_length"), "{e}");
        let e = error_of(&MINIMAL.replace("final_time = 1.6", "final_time = 1.0"));
        assert!(e.contains("configuration[0].final_time"), "{e}");
        let e = error_of(&MINIMAL.replace("target_length = 2.0", "target_length = 2.05"));
        assert!(e.contains("sweep[0].elements"), "{e}");
        let e = error_of(&MINIMAL.replace("error = \"onset_work\"", "error = \"nope\""));
        assert!(e.contains("gate[0].error"), "{e}");
        let e = error_of(&MINIMAL.replace("families = [\"em\"]", "families = [\"x\"]"));
        assert!(e.contains("sweep[0].families"), "{e}");
        let e = error_of(&MINIMAL.replace("gap = 0.01", "gap = 0.01\nstray = 1"));
        assert!(e.contains("stray"), "{e}");
    }
}
