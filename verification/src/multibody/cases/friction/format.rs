//! The case format of kind `multibody_friction` (unknown keys are errors) and its checks; errors
//! name the field as the case file writes it (`blocks.upper.size`, `sweep.steps`).

use std::path::Path;

use serde::Deserialize;

use contactlab::model::multibody::scheme::MultibodyScheme;

use crate::core::case::Case;
use crate::core::format::{at_least, invalid, positive, CaseError};
use crate::core::gate::RateGate;
use crate::exact::two_block_slide::TwoBlockSlide;
use crate::multibody::study::MaterialSpec;

/// The errors a `[[gate]]` may name (module docs of the kind).
pub const ERRORS: [&str; 3] = ["stop_time_error", "stop_velocity", "dissipation_error"];

/// A rectangle: lower-left corner, size, divisions.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RectSpec {
    pub origin: [f64; 2],
    pub size: [f64; 2],
    pub divisions: [usize; 2],
}

/// `[blocks]`: the two blocks, their material, the friction between them and the launch.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlocksSpec {
    /// The lower block (on the frictionless foundation y = its bottom).
    pub lower: RectSpec,
    /// The upper block (its bottom on the lower block's top).
    pub upper: RectSpec,
    pub density: f64,
    pub material: MaterialSpec,
    /// g (downwards, both blocks).
    pub gravity: f64,
    /// μ between the blocks.
    pub friction: f64,
    /// v₁(0), v₂(0) along x.
    pub upper_speed: f64,
    #[serde(default)]
    pub lower_speed: f64,
}

/// `[sweep]`: the levels in k at fixed mesh.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// T = duration × t* (> 1: past the stop).
    pub duration: f64,
    /// N per level (increasing; ≥ 3 levels for a rate gate).
    pub steps: Vec<usize>,
    /// The schemes gated (midpoint-type).
    pub schemes: Vec<MultibodyScheme>,
    /// The level whose histories are plotted (one of `steps`).
    pub show: usize,
    /// Also run Newmark at the shown level (reported, not gated).
    #[serde(default)]
    pub newmark: bool,
}

/// What a `[[gate]]` measures: one error of one scheme along the levels, against k.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GateSelect {
    pub scheme: MultibodyScheme,
    pub error: String,
}

/// `[limits]`: the ceilings of the per-level gates, each relative (the case file explains each
/// number: the elastic corrections it leaves room for and what was measured).
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Limits {
    /// |a_fit − a| / a over the sliding steps.
    pub deceleration: f64,
    /// max over the sliding steps of the upper and lower blocks' momentum invariants' drift,
    /// relative to |w₀|.
    pub invariant: f64,
    /// |D − D(t_s)| / D*: the dissipation against the scheme's rigid dissipation.
    pub dissipation: f64,
    /// |D − D_μ| / D*: the dissipation against μ Σ λ_N |slip|.
    pub friction_work: f64,
}

/// The body of a `multibody_friction` case.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionCase {
    pub blocks: BlocksSpec,
    pub sweep: SweepSpec,
    pub limits: Limits,
    #[serde(rename = "gate", default)]
    pub gates: Vec<RateGate<GateSelect>>,
}

impl BlocksSpec {
    /// m = ρ × area of a block.
    pub fn mass(&self, r: &RectSpec) -> f64 {
        self.density * r.size[0] * r.size[1]
    }

    /// The rigid two-block slide of these blocks.
    pub fn exact(&self) -> TwoBlockSlide {
        TwoBlockSlide {
            upper_mass: self.mass(&self.upper),
            lower_mass: self.mass(&self.lower),
            friction: self.friction,
            gravity: self.gravity,
            upper_speed: self.upper_speed,
            lower_speed: self.lower_speed,
        }
    }

    /// G = E/(2(1 + ν)) and E′ = E/(1 − ν²).
    pub fn moduli(&self) -> (f64, f64) {
        let (e, nu) = (self.material.young, self.material.poisson);
        (0.5 * e / (1.0 + nu), e / (1.0 - nu * nu))
    }

    /// δ_s: the upper block's quasi-static shear lag under the friction traction.
    pub fn shear_lag(&self) -> f64 {
        let (g, _) = self.moduli();
        self.exact()
            .shear_lag(self.upper.size[0], self.upper.size[1], g)
    }

    /// The blocks' compression under gravity (the scale of the vertical deformation).
    pub fn compression(&self) -> f64 {
        let (_, e) = self.moduli();
        self.exact()
            .compression(self.density, self.upper.size, self.lower.size[1], e)
    }

    /// The largest coordinate of the blocks (the round-off scale of the positions).
    pub fn extent(&self) -> f64 {
        [&self.lower, &self.upper]
            .iter()
            .flat_map(|r| [r.origin[0].abs() + r.size[0], r.origin[1].abs() + r.size[1]])
            .fold(0.0, f64::max)
    }
}

impl FrictionCase {
    /// Parses and checks a case of this kind.
    pub fn from_case(case: &Case) -> Result<Self, CaseError> {
        let file: Self = case.body()?;
        file.check(case.path())?;
        Ok(file)
    }

    fn check(&self, p: &Path) -> Result<(), CaseError> {
        let b = &self.blocks;
        for (k, v) in [
            ("blocks.density", b.density),
            ("blocks.gravity", b.gravity),
            ("blocks.friction", b.friction),
            ("blocks.material.young", b.material.young),
        ] {
            positive(p, k, v)?;
        }
        if !(b.material.poisson.is_finite() && (0.0..0.5).contains(&b.material.poisson)) {
            return Err(invalid(
                p,
                "blocks.material.poisson",
                b.material.poisson,
                "a Poisson ratio in [0, 1/2)",
            ));
        }
        for (name, r) in [("lower", &b.lower), ("upper", &b.upper)] {
            for c in 0..2 {
                positive(p, &format!("blocks.{name}.size[{c}]"), r.size[c])?;
                if !r.origin[c].is_finite() {
                    return Err(invalid(
                        p,
                        &format!("blocks.{name}.origin[{c}]"),
                        r.origin[c],
                        "a finite number",
                    ));
                }
                if r.divisions[c] == 0 {
                    return Err(invalid(
                        p,
                        &format!("blocks.{name}.divisions[{c}]"),
                        0,
                        "≥ 1",
                    ));
                }
            }
        }
        let (lo, up) = (&b.lower, &b.upper);
        let top = lo.origin[1] + lo.size[1];
        if up.origin[1] != top {
            return Err(invalid(
                p,
                "blocks.upper.origin[1]",
                up.origin[1],
                &format!("the lower block's top {top} (the upper block rests on it)"),
            ));
        }
        for (k, v) in [
            ("blocks.upper_speed", b.upper_speed),
            ("blocks.lower_speed", b.lower_speed),
        ] {
            if !v.is_finite() {
                return Err(invalid(p, k, v, "a finite speed"));
            }
        }
        let exact = b.exact();
        if exact.initial_relative_velocity() == 0.0 {
            return Err(invalid(
                p,
                "blocks.upper_speed",
                b.upper_speed,
                "a speed other than blocks.lower_speed (the blocks must slip)",
            ));
        }
        // the upper block must stay on the lower one until the stop: its left end moves by the
        // slip s(t) relative to the lower block
        let slip = exact.slip(exact.stop_time());
        let (left, right) = (
            up.origin[0] + slip.min(0.0),
            up.origin[0] + up.size[0] + slip.max(0.0),
        );
        if left < lo.origin[0] || right > lo.origin[0] + lo.size[0] {
            return Err(invalid(
                p,
                "blocks.upper",
                format!("[{left}, {right}] swept relative to the lower block"),
                "an upper block that stays on the lower block's top until the stop (a longer \
                 lower block, or a smaller speed)",
            ));
        }
        let l = &self.limits;
        for (k, v) in [
            ("limits.deceleration", l.deceleration),
            ("limits.invariant", l.invariant),
            ("limits.dissipation", l.dissipation),
            ("limits.friction_work", l.friction_work),
        ] {
            positive(p, k, v)?;
        }
        let s = &self.sweep;
        if !(s.duration.is_finite() && s.duration > 1.0) {
            return Err(invalid(
                p,
                "sweep.duration",
                s.duration,
                "a number > 1 (T past the stop)",
            ));
        }
        at_least(p, "sweep.steps", &s.steps, 1)?;
        if s.steps[0] == 0 || s.steps.windows(2).any(|w| w[1] <= w[0]) {
            return Err(invalid(
                p,
                "sweep.steps",
                format!("{:?}", s.steps),
                "increasing step counts ≥ 1",
            ));
        }
        let t_star = exact.stop_time();
        for (i, &n) in s.steps.iter().enumerate() {
            let theta = (n as f64 / s.duration).fract();
            if (theta - 0.5).abs() < 0.1 {
                return Err(invalid(
                    p,
                    &format!("sweep.steps[{i}]"),
                    n,
                    &format!(
                        "a step count whose phase θ = frac(t*/k) = frac(N/duration) = {theta:.3} \
                         is not within 0.1 of ½ (the rigid stop is then ambiguous; t* = {t_star})"
                    ),
                ));
            }
        }
        if !s.steps.contains(&s.show) {
            return Err(invalid(p, "sweep.show", s.show, "one of sweep.steps"));
        }
        at_least(p, "sweep.schemes", &s.schemes, 1)?;
        for (i, sc) in s.schemes.iter().enumerate() {
            if !sc.is_midpoint_type() {
                return Err(invalid(
                    p,
                    &format!("sweep.schemes[{i}]"),
                    sc.name(),
                    "\"midpoint\" or \"energy_momentum\" (the discrete stop is derived for the \
                     midpoint types; set sweep.newmark = true to report Newmark)",
                ));
            }
            if s.schemes[..i].contains(sc) {
                return Err(invalid(
                    p,
                    &format!("sweep.schemes[{i}]"),
                    sc.name(),
                    "each scheme once",
                ));
            }
        }
        for (i, g) in self.gates.iter().enumerate() {
            let field = format!("gate[{i}]");
            if !s.schemes.contains(&g.select.scheme) {
                return Err(invalid(
                    p,
                    &format!("{field}.scheme"),
                    g.select.scheme.name(),
                    "a scheme of sweep.schemes",
                ));
            }
            if !ERRORS.contains(&g.select.error.as_str()) {
                return Err(invalid(
                    p,
                    &format!("{field}.error"),
                    &g.select.error,
                    &format!("one of {}", ERRORS.join(", ")),
                ));
            }
            at_least(p, "sweep.steps", &s.steps, 3)?;
            g.criteria.check(p, &field)?;
        }
        Ok(())
    }
}
