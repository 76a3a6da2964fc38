//! The case format of kind `dynamic_friction` (unknown keys are errors) and its checks; errors
//! name the field as the case file writes it (`family[1].depth`, `slide.steps`).

use std::path::Path;

use serde::Deserialize;

use contactlab::model::dynamic::scheme::DynamicScheme;

use crate::core::case::Case;
use crate::core::format::{at_least, invalid, positive, CaseError};
use crate::core::gate::RateGate;
use crate::exact::coulomb_friction::{Compliance, Coulomb, FrictionLaw};
use crate::exact::loaded_block::LoadedBlock;
use crate::exact::sliding_block::{BlockFoundation, SlidingBlock};

/// The errors of the sliding block a `[[gate]]` may name (see the kind's docs).
pub const SLIDE_ERRORS: [&str; 3] = [
    "stop_time_error",
    "stop_distance_error",
    "post_stop_velocity",
];

/// The normal treatment of a family.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Treatment {
    Penalty,
    EnergyConsistent,
    LimitedPenetration,
}

/// `[[family]]`: a friction law with a normal treatment.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FamilySpec {
    pub name: String,
    pub law: FrictionLaw,
    pub mu0: f64,
    /// g of (1.13) (growing and decreasing laws).
    pub depth: Option<f64>,
    pub treatment: Treatment,
    /// g_b, the depth of the rigid base (limited_penetration only).
    pub base: Option<f64>,
}

impl FamilySpec {
    /// μ(η) of the family, written in the verification crate.
    pub fn coulomb(&self) -> Coulomb {
        Coulomb {
            law: self.law,
            mu0: self.mu0,
            depth: self.depth.unwrap_or(f64::INFINITY),
        }
    }
}

/// `[slide]`: the stiff block under rollers (a linear elastic material).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlideSpec {
    pub length: f64,
    pub height: f64,
    pub divisions: [usize; 2],
    pub density: f64,
    pub young: f64,
    pub poisson: f64,
    /// r.
    pub stiffness: f64,
    /// η_c.
    pub penetration: f64,
    /// v0.
    pub speed: f64,
    /// T = duration × t* of each family (> 1).
    pub duration: f64,
    /// N per level (≥ 3 levels, increasing).
    pub steps: Vec<usize>,
    #[serde(default = "midpoint")]
    pub scheme: DynamicScheme,
    /// The Newton tolerance (default 1e-12).
    pub tolerance: Option<f64>,
    /// The families run (default: all).
    pub families: Option<Vec<String>>,
}

/// `[loaded]`: the free block under a pressure (a linear elastic material: the check of its
/// steps bounds the round-off of K u, see `residual.rs`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadedSpec {
    pub length: f64,
    pub height: f64,
    pub divisions: [usize; 2],
    pub density: f64,
    pub young: f64,
    pub poisson: f64,
    pub stiffness: f64,
    pub pressure: f64,
    pub speed: f64,
    /// T = duration × the rigid-limit stop time of each family.
    pub duration: f64,
    /// N per run (≥ 1 runs).
    pub steps: Vec<usize>,
    #[serde(default = "midpoint")]
    pub scheme: DynamicScheme,
    pub families: Option<Vec<String>>,
}

fn midpoint() -> DynamicScheme {
    DynamicScheme::Midpoint
}

/// What a `[[gate]]` measures: one error of one family along the sliding block's levels, against
/// k.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlideSelect {
    pub family: String,
    pub error: String,
}

/// The body of a `dynamic_friction` case.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionCase {
    #[serde(rename = "family")]
    pub families: Vec<FamilySpec>,
    pub slide: Option<SlideSpec>,
    pub loaded: Option<LoadedSpec>,
    #[serde(rename = "gate", default)]
    pub gates: Vec<RateGate<SlideSelect>>,
}

impl SlideSpec {
    /// The sliding block of family `f`.
    pub fn block(&self, f: &FamilySpec) -> SlidingBlock {
        SlidingBlock {
            length: self.length,
            height: self.height,
            density: self.density,
            young: self.young,
            poisson: self.poisson,
            foundation: match (f.treatment, f.base) {
                (Treatment::LimitedPenetration, Some(depth)) => {
                    BlockFoundation::LimitedPenetration {
                        stiffness: self.stiffness,
                        depth,
                    }
                }
                _ => BlockFoundation::Compliance {
                    stiffness: self.stiffness,
                },
            },
            penetration: self.penetration,
            speed: self.speed,
            friction: f.coulomb(),
        }
    }

    /// The families this setting runs, in case order.
    pub fn runs<'a>(&self, families: &'a [FamilySpec]) -> Vec<&'a FamilySpec> {
        selected(&self.families, families)
    }

    /// The Newton tolerance.
    pub fn tolerance(&self) -> f64 {
        self.tolerance.unwrap_or(1e-12)
    }
}

impl LoadedSpec {
    /// The loaded block.
    pub fn block(&self) -> LoadedBlock {
        LoadedBlock {
            length: self.length,
            height: self.height,
            density: self.density,
            young: self.young,
            poisson: self.poisson,
            stiffness: self.stiffness,
            pressure: self.pressure,
            speed: self.speed,
        }
    }

    /// The reference compliance of family `f` (penalty or energy-consistent).
    pub fn compliance(&self, f: &FamilySpec) -> Compliance {
        match f.treatment {
            Treatment::Penalty => Compliance::Penalty {
                stiffness: self.stiffness,
            },
            _ => Compliance::EnergyConsistent {
                stiffness: self.stiffness,
            },
        }
    }

    /// The families this setting runs, in case order.
    pub fn runs<'a>(&self, families: &'a [FamilySpec]) -> Vec<&'a FamilySpec> {
        selected(&self.families, families)
    }
}

fn selected<'a>(names: &Option<Vec<String>>, families: &'a [FamilySpec]) -> Vec<&'a FamilySpec> {
    families
        .iter()
        .filter(|f| names.as_ref().is_none_or(|n| n.contains(&f.name)))
        .collect()
}

/// Checks that `names` (a setting's `families`) name families of the case.
fn check_names(
    path: &Path,
    field: &str,
    names: &Option<Vec<String>>,
    families: &[FamilySpec],
) -> Result<(), CaseError> {
    for (i, n) in names.iter().flatten().enumerate() {
        if !families.iter().any(|f| &f.name == n) {
            return Err(invalid(
                path,
                &format!("{field}.families[{i}]"),
                n,
                "the name of a [[family]]",
            ));
        }
    }
    Ok(())
}

impl FrictionCase {
    /// Parses and checks a case of this kind.
    pub fn from_case(case: &Case) -> Result<Self, CaseError> {
        let file: Self = case.body()?;
        file.check(case.path())?;
        Ok(file)
    }

    fn check(&self, p: &Path) -> Result<(), CaseError> {
        at_least(p, "family", &self.families, 1)?;
        for (i, f) in self.families.iter().enumerate() {
            let field = |k: &str| format!("family[{i}].{k}");
            if self.families[..i].iter().any(|g| g.name == f.name) {
                return Err(invalid(p, &field("name"), &f.name, "a unique name"));
            }
            positive(p, &field("mu0"), f.mu0)?;
            match (f.law, f.depth) {
                (FrictionLaw::Constant, Some(d)) => {
                    return Err(invalid(
                        p,
                        &field("depth"),
                        d,
                        "no depth for law = \"constant\"",
                    ))
                }
                (FrictionLaw::Constant, None) => {}
                (_, Some(d)) => positive(p, &field("depth"), d)?,
                (_, None) => {
                    return Err(invalid(
                        p,
                        &field("depth"),
                        "(missing)",
                        "the depth g of (1.13) for the growing and decreasing laws",
                    ))
                }
            }
            match (f.treatment, f.base) {
                (Treatment::LimitedPenetration, Some(b)) => positive(p, &field("base"), b)?,
                (Treatment::LimitedPenetration, None) => {
                    return Err(invalid(
                        p,
                        &field("base"),
                        "(missing)",
                        "the depth g_b of the rigid base for limited_penetration",
                    ))
                }
                (_, Some(b)) => {
                    return Err(invalid(
                        p,
                        &field("base"),
                        b,
                        "no base but for limited_penetration",
                    ))
                }
                (_, None) => {}
            }
        }
        if self.slide.is_none() && self.loaded.is_none() {
            return Err(invalid(
                p,
                "slide",
                "(missing)",
                "a [slide] or a [loaded] section",
            ));
        }
        if let Some(s) = &self.slide {
            self.check_slide(p, s)?;
        }
        if let Some(l) = &self.loaded {
            self.check_loaded(p, l)?;
        }
        for (i, g) in self.gates.iter().enumerate() {
            let field = format!("gate[{i}]");
            let Some(s) = &self.slide else {
                return Err(invalid(p, &field, "(given)", "a [slide] section to gate"));
            };
            if !s
                .runs(&self.families)
                .iter()
                .any(|f| f.name == g.select.family)
            {
                return Err(invalid(
                    p,
                    &format!("{field}.family"),
                    &g.select.family,
                    "a [[family]] that [slide] runs",
                ));
            }
            if !SLIDE_ERRORS.contains(&g.select.error.as_str()) {
                return Err(invalid(
                    p,
                    &format!("{field}.error"),
                    &g.select.error,
                    &format!("one of {}", SLIDE_ERRORS.join(", ")),
                ));
            }
            g.criteria.check(p, &field)?;
        }
        Ok(())
    }

    fn check_slide(&self, p: &Path, s: &SlideSpec) -> Result<(), CaseError> {
        for (k, v) in [
            ("length", s.length),
            ("height", s.height),
            ("density", s.density),
            ("young", s.young),
            ("stiffness", s.stiffness),
            ("penetration", s.penetration),
            ("speed", s.speed),
        ] {
            positive(p, &format!("slide.{k}"), v)?;
        }
        check_poisson(p, "slide.poisson", s.poisson)?;
        check_divisions(p, "slide.divisions", s.divisions)?;
        if !(s.duration.is_finite() && s.duration > 1.0) {
            return Err(invalid(
                p,
                "slide.duration",
                s.duration,
                "a number > 1 (T past the stop)",
            ));
        }
        at_least(p, "slide.steps", &s.steps, 3)?;
        if s.steps.windows(2).any(|w| w[1] <= w[0]) || s.steps[0] == 0 {
            return Err(invalid(
                p,
                "slide.steps",
                format!("{:?}", s.steps),
                "increasing step counts ≥ 1",
            ));
        }
        if let Some(t) = s.tolerance {
            if !(t > 0.0 && t < 1e-6) {
                return Err(invalid(
                    p,
                    "slide.tolerance",
                    t,
                    "a Newton tolerance in (0, 1e-6)",
                ));
            }
        }
        check_scheme(p, "slide.scheme", s.scheme)?;
        check_names(p, "slide", &s.families, &self.families)?;
        for f in s.runs(&self.families) {
            if s.block(f).friction_coefficient() <= 0.0 {
                return Err(invalid(
                    p,
                    "slide",
                    &f.name,
                    "families with friction at the block's penetration",
                ));
            }
        }
        Ok(())
    }

    fn check_loaded(&self, p: &Path, l: &LoadedSpec) -> Result<(), CaseError> {
        for (k, v) in [
            ("length", l.length),
            ("height", l.height),
            ("density", l.density),
            ("young", l.young),
            ("stiffness", l.stiffness),
            ("pressure", l.pressure),
            ("speed", l.speed),
            ("duration", l.duration),
        ] {
            positive(p, &format!("loaded.{k}"), v)?;
        }
        check_poisson(p, "loaded.poisson", l.poisson)?;
        check_divisions(p, "loaded.divisions", l.divisions)?;
        at_least(p, "loaded.steps", &l.steps, 1)?;
        if l.steps.contains(&0) {
            return Err(invalid(p, "loaded.steps", 0, "step counts ≥ 1"));
        }
        check_scheme(p, "loaded.scheme", l.scheme)?;
        check_names(p, "loaded", &l.families, &self.families)?;
        for f in l.runs(&self.families) {
            if f.treatment == Treatment::LimitedPenetration {
                return Err(invalid(
                    p,
                    "loaded.families",
                    &f.name,
                    "families with a penalty or energy_consistent treatment (the check of each \
                     step's equations needs the normal force as a law of the penetrations)",
                ));
            }
        }
        Ok(())
    }
}

fn check_poisson(p: &Path, field: &str, v: f64) -> Result<(), CaseError> {
    if v.is_finite() && (0.0..0.5).contains(&v) {
        Ok(())
    } else {
        Err(invalid(p, field, v, "a Poisson ratio in [0, 1/2)"))
    }
}

fn check_divisions(p: &Path, field: &str, d: [usize; 2]) -> Result<(), CaseError> {
    if d[0] >= 1 && d[1] >= 1 {
        Ok(())
    } else {
        Err(invalid(p, field, format!("{d:?}"), "[n_x, n_y] ≥ 1"))
    }
}

fn check_scheme(p: &Path, field: &str, s: DynamicScheme) -> Result<(), CaseError> {
    if s.is_midpoint_type() {
        Ok(())
    } else {
        Err(invalid(
            p,
            field,
            s.name(),
            "\"midpoint\" or \"gonzalez\" (the friction force at t_n with the backward-difference \
             slip rate, BDS (1.36)–(1.38))",
        ))
    }
}
