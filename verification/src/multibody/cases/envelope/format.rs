//! The case format of kind `multibody_envelope` (unknown keys are errors) and its checks: every
//! invalid value is a [`CaseError`] naming its field.

use serde::Deserialize;

use contactlab::model::multibody::scheme::MultibodyScheme;

use crate::core::case::Case;
use crate::core::format::{invalid, positive, CaseError};
use crate::core::gate::RateGate;

/// The outcomes a point past the range may end with (module docs of [`super`]).
pub const OUTCOMES: [&str; 7] = [
    "EnergyGain",
    "ActiveSetCycle",
    "NewtonNotConverged",
    "NoEquilibrium",
    "newmark_warning",
    "audit_flag",
    "overlap_error",
];

/// The case file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeCase {
    pub bars: BarsSpec,
    #[serde(rename = "sweep")]
    pub sweeps: Vec<SweepSpec>,
    #[serde(rename = "rate", default)]
    pub rates: Vec<RateSpec>,
    #[serde(rename = "overlap", default)]
    pub overlaps: Vec<OverlapSpec>,
    /// C in the energy's round-off floor (module docs of [`super::energy`]).
    pub energy_round_off: f64,
    /// C in the momentum's round-off floor (module docs of [`super::energy`]).
    pub momentum_round_off: f64,
}

/// `[bars]`: the head-on bars every point runs (two bars [−g0/2 − L, −g0/2] and [g0/2, g0/2 + L]
/// × [0, H] at ±v, linear law, k = courant · h / c).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarsSpec {
    pub length: f64,
    pub height: f64,
    pub density: f64,
    pub young: f64,
    pub poisson: f64,
    pub courant: f64,
    /// t0 = g0/(2v) = onset_steps · k: the gap g0 = 2 v onset_steps k scales with v (the
    /// continuum problem is then homogeneous of degree one in v) and the onset's phase in the
    /// step is the same on every level.
    pub onset_steps: f64,
    /// The run ends this long after the exact release t0 + 2L/c.
    pub after_release: f64,
}

impl BarsSpec {
    /// c = √(E(1 − ν)/((1 + ν)(1 − 2ν)) / ρ) (plane strain; √(E/ρ) at ν = 0).
    pub fn wave_speed(&self) -> f64 {
        let (e, nu) = (self.young, self.poisson);
        (e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)) / self.density).sqrt()
    }

    /// h = L/M.
    pub fn h(&self, elements: usize) -> f64 {
        self.length / elements as f64
    }

    /// k = courant · h / c.
    pub fn step(&self, elements: usize) -> f64 {
        self.courant * self.h(elements) / self.wave_speed()
    }

    /// g0 = 2 v onset_steps k.
    pub fn gap(&self, speed: f64, elements: usize) -> f64 {
        2.0 * speed * self.onset_steps * self.step(elements)
    }

    /// N = ⌈(t0 + 2L/c + after_release)/k⌉, t0 = g0/(2v) the exact onset.
    pub fn steps(&self, elements: usize, gap: f64, speed: f64) -> usize {
        let k = self.step(elements);
        let t = 0.5 * gap / speed + 2.0 * self.length / self.wave_speed() + self.after_release;
        (t / k - 1e-9).ceil().max(1.0) as usize
    }
}

/// The layout across the height.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Cells {
    /// One element across.
    OneRow,
    /// Square cells: H/h rows.
    Square,
}

impl Cells {
    /// The rows across H for M elements along L.
    pub fn rows(self, bars: &BarsSpec, elements: usize) -> usize {
        match self {
            Cells::OneRow => 1,
            Cells::Square => ((bars.height / bars.h(elements)).round() as usize).max(1),
        }
    }
}

/// `[[sweep]]`: speeds × meshes with one treatment.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    pub name: String,
    pub cells: Cells,
    pub scheme: MultibodyScheme,
    #[serde(default)]
    pub two_pass: bool,
    /// v/c.
    pub speeds: Vec<f64>,
    pub elements: Vec<usize>,
    /// Inside the range (every point completes and passes the gates) or past it (every point
    /// ends with one of `expect`).
    pub inside: bool,
    #[serde(default)]
    pub expect: Vec<String>,
    /// A fixed initial gap g0 instead of [`BarsSpec::gap`] (the onset's phase in the step then
    /// varies with v and h).
    #[serde(default)]
    pub gap: Option<f64>,
}

/// `[[rate]]`: the rebound error's rate in h over the levels of a sweep, at each of its speeds.
pub type RateSpec = RateGate<RateSelect>;

/// The keys of a `[[rate]]` besides the [`crate::core::gate::RateCriteria`].
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RateSelect {
    pub sweep: String,
}

/// `[[overlap]]`: the bars started `depth` into each other (M elements, one row, ±v).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OverlapSpec {
    pub name: String,
    pub depth: f64,
    pub speed: f64,
    pub elements: usize,
    /// `initial_overlap = "resolve"` in the pair: the run must complete and pass the energy and
    /// momentum gates; otherwise the scene must be refused with a message containing `expect`.
    #[serde(default)]
    pub resolve: bool,
    #[serde(default)]
    pub expect: Vec<String>,
}

impl EnvelopeCase {
    /// Reads and checks the case.
    pub fn from_case(case: &Case) -> Result<Self, CaseError> {
        let c: Self = case.body()?;
        c.check(case)?;
        Ok(c)
    }

    fn check(&self, case: &Case) -> Result<(), CaseError> {
        let path = case.path();
        let b = &self.bars;
        for (k, v) in [
            ("bars.length", b.length),
            ("bars.height", b.height),
            ("bars.density", b.density),
            ("bars.young", b.young),
            ("bars.courant", b.courant),
            ("bars.onset_steps", b.onset_steps),
            ("bars.after_release", b.after_release),
            ("energy_round_off", self.energy_round_off),
            ("momentum_round_off", self.momentum_round_off),
        ] {
            positive(path, k, v)?;
        }
        if b.poisson != 0.0 {
            return Err(invalid(
                path,
                "bars.poisson",
                b.poisson,
                "0 (with ν = 0 the plane-strain bars are exactly the 1D bar of the exact rebound)",
            ));
        }
        for (i, s) in self.sweeps.iter().enumerate() {
            let f = format!("sweep[{i}]");
            if s.speeds.is_empty() || s.speeds.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
                return Err(invalid(
                    path,
                    &format!("{f}.speeds"),
                    format!("{:?}", s.speeds),
                    "speeds v/c > 0",
                ));
            }
            if s.elements.is_empty() || s.elements.contains(&0) {
                return Err(invalid(
                    path,
                    &format!("{f}.elements"),
                    format!("{:?}", s.elements),
                    "element counts > 0",
                ));
            }
            check_expect(path, &format!("{f}.expect"), s.inside, &s.expect)?;
            if let Some(g) = s.gap {
                positive(path, &format!("{f}.gap"), g)?;
            }
        }
        for (i, r) in self.rates.iter().enumerate() {
            let f = format!("rate[{i}]");
            r.criteria.check(path, &f)?;
            let name = &r.select.sweep;
            let Some(s) = self.sweeps.iter().find(|s| &s.name == name) else {
                return Err(invalid(path, &format!("{f}.sweep"), name, "a sweep's name"));
            };
            if !s.inside || s.elements.len() < 3 {
                return Err(invalid(
                    path,
                    &format!("{f}.sweep"),
                    name,
                    "a sweep inside the range with at least 3 meshes",
                ));
            }
        }
        for (i, o) in self.overlaps.iter().enumerate() {
            let f = format!("overlap[{i}]");
            positive(path, &format!("{f}.depth"), o.depth)?;
            positive(path, &format!("{f}.speed"), o.speed)?;
            if o.elements == 0 {
                return Err(invalid(path, &format!("{f}.elements"), 0, "> 0"));
            }
            if !o.resolve && o.expect.is_empty() {
                return Err(invalid(
                    path,
                    &format!("{f}.expect"),
                    "[]",
                    "the texts the overlap error must name",
                ));
            }
        }
        Ok(())
    }
}

fn check_expect(
    path: &std::path::Path,
    field: &str,
    inside: bool,
    expect: &[String],
) -> Result<(), CaseError> {
    let known = expect.iter().all(|e| OUTCOMES.contains(&e.as_str()));
    if inside != expect.is_empty() || !known {
        return Err(invalid(
            path,
            field,
            format!("{expect:?}"),
            &format!(
                "empty for a sweep inside the range, else some of {}",
                OUTCOMES.join(", ")
            ),
        ));
    }
    Ok(())
}
