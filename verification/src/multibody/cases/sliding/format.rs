//! The case format of `multibody_sliding` (unknown keys are errors) and its checks: every
//! invalid value is a [`CaseError`] naming its field.

use std::path::Path;

use serde::Deserialize;

use crate::core::case::Case;
use crate::core::format::{invalid, positive, CaseError};
use crate::multibody::study::{LawName, MaterialSpec};

/// The case file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlidingCase {
    /// The bodies' law (linear, ν = 0: the normal motion is exactly the 1D bar's).
    pub material: MaterialSpec,
    /// ρ of every body.
    pub density: f64,
    /// k = courant · h / c (h the element size along the normal).
    pub courant: f64,
    pub grazing: Option<GrazingSpec>,
    pub slide_off: Option<SlideOffSpec>,
}

/// `[grazing]`: a bar [0, W] × [g0, g0 + L] at (v_t, −v_n) onto the foundation {y ≤ 0}.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GrazingSpec {
    /// L: the bar's extent along the normal (y).
    pub length: f64,
    /// W: its extent along the wall (x): the section A.
    pub width: f64,
    /// Elements along the normal (h = L/elements) and across.
    pub elements: usize,
    pub columns: usize,
    /// v_t, fixed.
    pub tangential_speed: f64,
    /// v_n over decades (the ratio v_n/v_t is the grazing angle's tangent).
    pub normal_speeds: Vec<f64>,
    /// t0 = g0/v_n, the same at every angle.
    pub onset: f64,
    /// T (rounded up to a whole step).
    pub final_time: f64,
    /// max_n |v_cx(t_n) − v_t| / (ε v_t) at most this (P_x exactly conserved).
    pub centre_round_off: f64,
    /// max_{n,i} |v_x,i(t_n; v_t) − v_t − v_x,i(t_n; 0)| / (ε (v_t + v_n) · amplification) at most
    /// this, and the same for v_y (the tangential invariance of the discrete problem).
    pub invariance_round_off: f64,
    /// |e(θ) − e(θ_min)| at most this for the rebound and plateau errors (the normal problem is
    /// linear in v_n and independent of v_t).
    pub linearity: f64,
    /// |v_cy(T)/v_n − 1| at most this at every angle.
    pub rebound_ceiling: f64,
    /// max_{n,i} |v_x,i − v_t| / v_n at most this (the discrete transverse motion of the normal
    /// problem: independent of v_t).
    pub transverse_ceiling: f64,
    pub note: String,
}

/// One rectangle: its size and divisions.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    pub size: [f64; 2],
    pub divisions: [usize; 2],
}

/// `[slide_off]`: the master [0, L_m] × [−H_m, 0] at rest, the slave [x_s, x_s + L_s] × [0, H_s]
/// on it at (v_t, −v_a), frictionless, one pass (the slave's bottom on the master's top).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlideOffSpec {
    pub master: BlockSpec,
    pub slave: BlockSpec,
    /// x_s: the slave's left end.
    pub start: f64,
    pub tangential_speed: f64,
    /// v_a of the loaded variant (the unloaded one has v_a = 0).
    pub approach_speed: f64,
    pub final_time: f64,
    /// Unloaded: max_{n,i} |v_i(t_n) − v_i(0)| / (ε v_t) at most this.
    pub velocity_round_off: f64,
    /// Unloaded: max_n (stored energy) / (ε² E_0) at most this.
    pub stored_round_off: f64,
    /// Unloaded: max_n |Σ λ_N| / (ε A_s ρ c v_t) at most this (no contact force).
    pub force_round_off: f64,
    /// Both: max_n |P(t_n) − P_setup| / (ε m_s |v|) at most this.
    pub momentum_round_off: f64,
    /// Unloaded: max_n |E_n − E_0| / (ε E_0) at most this; both: the same for |ΔE| of the steps
    /// that release a node and neither activate nor switch one (the release does no work).
    pub energy_round_off: f64,
    pub note: String,
}

impl SlidingCase {
    /// Parses and checks a case.
    pub fn from_case(case: &Case) -> Result<Self, CaseError> {
        let file: Self = case.body()?;
        file.validate(case.path())?;
        Ok(file)
    }

    /// c = √(E/ρ) (ν = 0).
    pub fn wave_speed(&self) -> f64 {
        self.material.wave_speed(self.density)
    }

    fn validate(&self, path: &Path) -> Result<(), CaseError> {
        let m = &self.material;
        positive(path, "material.young", m.young)?;
        if m.poisson != 0.0 {
            return Err(invalid(
                path,
                "material.poisson",
                m.poisson,
                "0 (then the normal motion is exactly the 1D bar with c = √(E/ρ))",
            ));
        }
        if m.law != LawName::Linear {
            return Err(invalid(
                path,
                "material.law",
                format!("{:?}", m.law),
                "linear (the exact references need a solution linear in the speeds)",
            ));
        }
        positive(path, "density", self.density)?;
        positive(path, "courant", self.courant)?;
        if self.grazing.is_none() && self.slide_off.is_none() {
            return Err(invalid(
                path,
                "grazing",
                "(missing)",
                "a [grazing] or a [slide_off] section",
            ));
        }
        if let Some(g) = &self.grazing {
            self.validate_grazing(path, g)?;
        }
        if let Some(s) = &self.slide_off {
            validate_slide_off(path, s)?;
        }
        Ok(())
    }

    fn validate_grazing(&self, path: &Path, g: &GrazingSpec) -> Result<(), CaseError> {
        for (name, v) in [
            ("grazing.length", g.length),
            ("grazing.width", g.width),
            ("grazing.tangential_speed", g.tangential_speed),
            ("grazing.onset", g.onset),
            ("grazing.final_time", g.final_time),
            ("grazing.centre_round_off", g.centre_round_off),
            ("grazing.invariance_round_off", g.invariance_round_off),
            ("grazing.linearity", g.linearity),
            ("grazing.rebound_ceiling", g.rebound_ceiling),
            ("grazing.transverse_ceiling", g.transverse_ceiling),
        ] {
            positive(path, name, v)?;
        }
        for (name, v) in [
            ("grazing.elements", g.elements),
            ("grazing.columns", g.columns),
        ] {
            if v == 0 {
                return Err(invalid(path, name, v, "at least 1"));
            }
        }
        if g.normal_speeds.len() < 2 {
            return Err(invalid(
                path,
                "grazing.normal_speeds",
                format!("{} entries", g.normal_speeds.len()),
                "at least two",
            ));
        }
        for (i, v) in g.normal_speeds.iter().enumerate() {
            positive(path, &format!("grazing.normal_speeds[{i}]"), *v)?;
        }
        let release = g.onset + 2.0 * g.length / self.wave_speed();
        if g.final_time <= 1.1 * release {
            return Err(invalid(
                path,
                "grazing.final_time",
                g.final_time,
                &format!("after the release t0 + 2L/c = {release} (by 10 %)"),
            ));
        }
        Ok(())
    }
}

fn validate_slide_off(path: &Path, s: &SlideOffSpec) -> Result<(), CaseError> {
    for (name, b) in [
        ("slide_off.master", &s.master),
        ("slide_off.slave", &s.slave),
    ] {
        for c in 0..2 {
            positive(path, &format!("{name}.size[{c}]"), b.size[c])?;
            if b.divisions[c] == 0 {
                return Err(invalid(
                    path,
                    &format!("{name}.divisions[{c}]"),
                    0,
                    "at least 1",
                ));
            }
        }
    }
    for (name, v) in [
        ("slide_off.tangential_speed", s.tangential_speed),
        ("slide_off.approach_speed", s.approach_speed),
        ("slide_off.final_time", s.final_time),
        ("slide_off.velocity_round_off", s.velocity_round_off),
        ("slide_off.stored_round_off", s.stored_round_off),
        ("slide_off.force_round_off", s.force_round_off),
        ("slide_off.momentum_round_off", s.momentum_round_off),
        ("slide_off.energy_round_off", s.energy_round_off),
    ] {
        positive(path, name, v)?;
    }
    if !(s.start.is_finite() && s.start >= 0.0 && s.start + s.slave.size[0] <= s.master.size[0]) {
        return Err(invalid(
            path,
            "slide_off.start",
            s.start,
            "x_s ≥ 0 with the slave on the master at t = 0 (x_s + L_s ≤ L_m)",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    //! The case format: the shipped cases parse; unknown keys, ν ≠ 0, a nonlinear law, a final
    //! time before the release, one normal speed and a slave off the master are typed errors
    //! naming the field.
    use std::path::Path;

    use super::*;

    const MINIMAL: &str = r#"
id = "t"
title = "t"
kind = "multibody_sliding"
explanation = "e"
density = 4.0
courant = 1.0
[material]
law = "linear"
young = 9.0
poisson = 0.0
[grazing]
length = 1.0
width = 0.25
elements = 10
columns = 1
tangential_speed = 0.1
normal_speeds = [0.1, 0.01]
onset = 0.1
final_time = 1.6
centre_round_off = 1.0
invariance_round_off = 1.0
linearity = 1e-9
rebound_ceiling = 0.1
transverse_ceiling = 0.1
note = "n"
[slide_off]
master = { size = [1.0, 0.5], divisions = [16, 8] }
slave = { size = [0.5, 0.5], divisions = [8, 8] }
start = 0.3
tangential_speed = 0.3
approach_speed = 0.01
final_time = 1.0
velocity_round_off = 1.0
stored_round_off = 1.0
force_round_off = 1.0
momentum_round_off = 1.0
energy_round_off = 1.0
note = "n"
"#;

    fn parse(text: &str) -> Result<SlidingCase, CaseError> {
        SlidingCase::from_case(&Case::from_text(Path::new("c.toml"), text)?)
    }

    fn error_of(text: &str) -> String {
        parse(text).expect_err("an invalid case").to_string()
    }

    #[test]
    fn minimal_and_shipped_cases_parse() {
        parse(MINIMAL).expect("minimal");
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
        for name in ["multibody_sliding.toml", "multibody_sliding_quick.toml"] {
            let case = Case::read(&dir.join(name)).expect("readable");
            SlidingCase::from_case(&case).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }

    #[test]
    fn invalid_values_are_typed_errors_naming_the_field() {
        let e = error_of(&MINIMAL.replace("poisson = 0.0", "poisson = 0.3"));
        assert!(e.contains("material.poisson"), "{e}");
        let e = error_of(&MINIMAL.replace("law = \"linear\"", "law = \"neo_hooke\""));
        assert!(e.contains("material.law"), "{e}");
        let e = error_of(&MINIMAL.replace("final_time = 1.6", "final_time = 1.0"));
        assert!(e.contains("grazing.final_time"), "{e}");
        let e = error_of(&MINIMAL.replace("[0.1, 0.01]", "[0.1]"));
        assert!(e.contains("grazing.normal_speeds"), "{e}");
        let e = error_of(&MINIMAL.replace("[0.1, 0.01]", "[0.1, -0.01]"));
        assert!(e.contains("grazing.normal_speeds[1]"), "{e}");
        let e = error_of(&MINIMAL.replace("start = 0.3", "start = 0.7"));
        assert!(e.contains("slide_off.start"), "{e}");
        let e = error_of(&MINIMAL.replace("[8, 8]", "[0, 8]"));
        assert!(e.contains("slide_off.slave.divisions[0]"), "{e}");
        let e = error_of(&MINIMAL.replace("onset = 0.1", "onset = 0.1\nstray = 1"));
        assert!(e.contains("stray"), "{e}");
    }
}
