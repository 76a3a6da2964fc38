//! Moving-continuum scenes: a linearized model, its discretization, the point to analyse, and
//! optional sweeps and a stability map. Two models:
//!
//! ```toml
//! model = "moving_string"      # the axially moving string of Hetzler (2009) §4.2.1–4.2.2
//! title = "Thick string with friction"
//!
//! [string]
//! speed = 0.3                  # v̄ (1 = the wave speed)
//! damping = 0.05               # ᾱ, mass-proportional (air drag)
//!
//! [oscillator]                 # optional: the oscillator in the bushing
//! stiffness = 2.0              # c̄
//! mass = 0.5                   # m̄
//! position = 0.3               # ā in (0, 1)
//! contact = "ideal"            # "ideal" (y_c = w(ā)) | "penalty" (massless bushing y_c)
//! penalty_stiffness = 100.0    # k̄_p, penalty contact only
//! friction = 0.1               # μ h̄ (thick string; 0: thin string), or instead:
//! # control_parameter = 0.2    # p = μ h̄ c̄ (ideal) or μ h̄ k̄_p (penalty)
//!
//! [discretization]
//! basis = "sine"               # "sine" | "p1" | "hermite"
//! modes = 20                   # sine: N
//! # elements = 40              # p1, hermite
//! condensation = "series_springs"   # penalty bushing: "series_springs" (exact) | "schur"
//!
//! [stability]                  # optional
//! relative_tolerance = 1e-6    # τ_rel of the verdicts (see model::moving::stability)
//! absolute_tolerance = 1e-12
//! threads = 0                  # 0: all cores (results do not depend on it)
//! eigenvectors = false         # also write the eigenvectors at the analysed point
//! map_kernel = "small_dense"   # the map's eigensolver: "small_dense" (fast) | "faer"
//!
//! [[sweep]]                    # any number: loci, Campbell diagram, verdicts along a parameter
//! parameter = "speed"          # speed, damping, oscillator_stiffness, oscillator_mass, position,
//! from = 0.0                   # penalty_stiffness, friction, control_parameter
//! to = 1.2
//! points = 121
//! scale = "linear"             # or "log" (geometric spacing, e.g. for penalty_stiffness)
//!
//! [map]                        # optional: verdicts on a grid
//! x = { parameter = "speed", from = 0.0, to = 0.99, points = 200 }
//! y = { parameter = "control_parameter", from = 0.0, to = 1.0, points = 200 }
//! ```
//!
//! ```toml
//! model = "disc_particle"      # the particle on the rotating disc, Hetzler (2009) §4.2.3
//! [particle]
//! mass = 1.0
//! stiffness = 100.0            # c
//! normal_force = 10.0          # N
//! friction_coefficient = 0.3   # μ
//! radius = 0.2                 # r0
//! angular_speed = 50.0         # Ω
//!
//! [[sweep]]
//! parameter = "angular_speed"  # angular_speed, normal_force, friction_coefficient, radius
//! from = 1.0
//! to = 100.0
//! points = 50
//! scale = "log"
//! ```
//!
//! Unknown keys are errors; every value is validated with an error naming its field.

use serde::{Deserialize, Serialize};

use crate::error::{Error, InputError, SolveError};
use crate::model::moving::disc::DiscParticle;
use crate::model::moving::finite_element_basis::ElementKind;
use crate::model::moving::stability::{assess, StabilityAssessment, VerdictParams};
use crate::model::moving::stability_map::{
    string_stability_map, GridAxis, StabilityMap, StabilityMapParams,
};
use crate::model::moving::string_data::{
    ContactModel, MovingStringData, OscillatorData, StringParameter,
};
use crate::model::moving::string_model::{
    MovingStringModel, MovingStringParams, PenaltyCondensation, StringDiscretization,
};
use crate::model::moving::sweep::{string_sweep, Sweep};
use crate::solve::quadratic_eigen::{solve_quadratic_eigen, EigenKernel, QuadraticEigenParams};

/// `[string]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StringSection {
    pub speed: f64,
    #[serde(default)]
    pub damping: f64,
}

/// `[oscillator]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OscillatorSection {
    pub stiffness: f64,
    pub mass: f64,
    pub position: f64,
    #[serde(default = "ideal")]
    pub contact: String,
    pub penalty_stiffness: Option<f64>,
    pub friction: Option<f64>,
    pub control_parameter: Option<f64>,
}

fn ideal() -> String {
    "ideal".into()
}

/// `[discretization]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscretizationSection {
    pub basis: String,
    pub modes: Option<usize>,
    pub elements: Option<usize>,
    #[serde(default)]
    pub condensation: PenaltyCondensation,
}

/// `[stability]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StabilitySection {
    pub relative_tolerance: Option<f64>,
    pub absolute_tolerance: Option<f64>,
    #[serde(default)]
    pub threads: usize,
    #[serde(default)]
    pub eigenvectors: bool,
    pub map_kernel: Option<EigenKernel>,
}

/// `[[sweep]]` and the axes of `[map]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisSection {
    pub parameter: String,
    pub from: f64,
    pub to: f64,
    pub points: usize,
    #[serde(default = "linear")]
    pub scale: String,
}

fn linear() -> String {
    "linear".into()
}

/// `[map]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapSection {
    pub x: AxisSection,
    pub y: AxisSection,
}

/// The file format of a `moving_string` scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MovingStringSceneFile {
    pub model: String,
    #[serde(default)]
    pub title: String,
    pub string: StringSection,
    pub oscillator: Option<OscillatorSection>,
    pub discretization: DiscretizationSection,
    #[serde(default)]
    pub stability: StabilitySection,
    #[serde(default)]
    pub sweep: Vec<AxisSection>,
    pub map: Option<MapSection>,
}

/// `[particle]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParticleSection {
    pub mass: f64,
    pub stiffness: f64,
    pub normal_force: f64,
    pub friction_coefficient: f64,
    pub radius: f64,
    pub angular_speed: f64,
}

/// The file format of a `disc_particle` scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscSceneFile {
    pub model: String,
    #[serde(default)]
    pub title: String,
    pub particle: ParticleSection,
    #[serde(default)]
    pub stability: StabilitySection,
    #[serde(default)]
    pub sweep: Vec<AxisSection>,
}

/// A parameter of the disc scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DiscParameter {
    AngularSpeed,
    NormalForce,
    FrictionCoefficient,
    Radius,
}

impl DiscParameter {
    fn parse(field: &str, s: &str) -> Result<Self, InputError> {
        Ok(match s {
            "angular_speed" => DiscParameter::AngularSpeed,
            "normal_force" => DiscParameter::NormalForce,
            "friction_coefficient" => DiscParameter::FrictionCoefficient,
            "radius" => DiscParameter::Radius,
            _ => {
                return Err(InputError::new(
                    field,
                    s,
                    "angular_speed, normal_force, friction_coefficient or radius",
                ))
            }
        })
    }

    /// Sets the parameter.
    pub fn set(self, p: &mut DiscParticle, value: f64) {
        match self {
            DiscParameter::AngularSpeed => p.angular_speed = value,
            DiscParameter::NormalForce => p.normal_force = value,
            DiscParameter::FrictionCoefficient => p.friction_coefficient = value,
            DiscParameter::Radius => p.radius = value,
        }
    }

    /// The scene key.
    pub fn key(self) -> &'static str {
        match self {
            DiscParameter::AngularSpeed => "angular_speed",
            DiscParameter::NormalForce => "normal_force",
            DiscParameter::FrictionCoefficient => "friction_coefficient",
            DiscParameter::Radius => "radius",
        }
    }
}

/// A validated string scene.
#[derive(Debug)]
pub struct MovingStringScene {
    pub title: String,
    pub model: MovingStringModel,
    pub data: MovingStringData,
    pub verdict: VerdictParams,
    pub threads: usize,
    pub eigenvectors: bool,
    pub map_kernel: EigenKernel,
    pub sweeps: Vec<GridAxis>,
    pub map: Option<(GridAxis, GridAxis)>,
}

/// A validated disc scene.
#[derive(Debug, Clone)]
pub struct DiscScene {
    pub title: String,
    pub particle: DiscParticle,
    pub verdict: VerdictParams,
    pub sweeps: Vec<(DiscParameter, Vec<f64>)>,
}

/// Either scene.
#[derive(Debug)]
pub enum MovingScene {
    String(Box<MovingStringScene>),
    Disc(DiscScene),
}

fn parse_parameter(field: &str, s: &str) -> Result<StringParameter, InputError> {
    Ok(match s {
        "speed" => StringParameter::Speed,
        "damping" => StringParameter::Damping,
        "oscillator_stiffness" => StringParameter::OscillatorStiffness,
        "oscillator_mass" => StringParameter::OscillatorMass,
        "position" => StringParameter::Position,
        "penalty_stiffness" => StringParameter::PenaltyStiffness,
        "friction" => StringParameter::Friction,
        "control_parameter" => StringParameter::ControlParameter,
        _ => {
            return Err(InputError::new(
                field,
                s,
                "speed, damping, oscillator_stiffness, oscillator_mass, position, \
                 penalty_stiffness, friction or control_parameter",
            ))
        }
    })
}

/// The values of an axis: `points` values from `from` to `to`, equally or geometrically spaced.
pub fn axis_values(field: &str, a: &AxisSection) -> Result<Vec<f64>, InputError> {
    if !(2..=100_000).contains(&a.points) {
        return Err(InputError::new(
            format!("{field}.points"),
            a.points,
            "2 to 100000 points",
        ));
    }
    for (k, v) in [("from", a.from), ("to", a.to)] {
        if !v.is_finite() {
            return Err(InputError::new(
                format!("{field}.{k}"),
                v,
                "a finite number",
            ));
        }
    }
    if a.from == a.to {
        return Err(InputError::new(
            format!("{field}.to"),
            a.to,
            format!("a number other than from = {}", a.from),
        ));
    }
    let n = a.points - 1;
    match a.scale.as_str() {
        "linear" => Ok((0..=n)
            .map(|i| a.from + (a.to - a.from) * i as f64 / n as f64)
            .collect()),
        "log" => {
            if !(a.from > 0.0 && a.to > 0.0) {
                return Err(InputError::new(
                    format!("{field}.from"),
                    a.from,
                    "positive from and to for scale = \"log\"",
                ));
            }
            let (l0, l1) = (a.from.ln(), a.to.ln());
            Ok((0..=n)
                .map(|i| (l0 + (l1 - l0) * i as f64 / n as f64).exp())
                .collect())
        }
        other => Err(InputError::new(
            format!("{field}.scale"),
            other,
            "\"linear\" or \"log\"",
        )),
    }
}

fn verdict_params(s: &StabilitySection) -> Result<VerdictParams, InputError> {
    let d = VerdictParams::default();
    let p = VerdictParams {
        relative_tolerance: s.relative_tolerance.unwrap_or(d.relative_tolerance),
        absolute_tolerance: s.absolute_tolerance.unwrap_or(d.absolute_tolerance),
    };
    p.validate()?;
    if s.threads > 1024 {
        return Err(InputError::new("stability.threads", s.threads, "0 to 1024"));
    }
    Ok(p)
}

fn scene_error(source_name: &str, e: toml::de::Error) -> Error {
    Error::Scene {
        source_name: source_name.to_string(),
        message: e.to_string(),
    }
}

impl MovingScene {
    /// Parses and validates a moving-continuum scene (`model = "moving_string"` or
    /// `"disc_particle"`); `source_name` labels errors.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Self, Error> {
        let table: toml::Table = text.parse().map_err(|e| scene_error(source_name, e))?;
        Self::from_table(table, source_name)
    }

    /// Validates a parsed scene table (read once).
    pub fn from_table(table: toml::Table, source_name: &str) -> Result<Self, Error> {
        let model = table
            .get("model")
            .and_then(|m| m.as_str())
            .unwrap_or("(missing)")
            .to_string();
        match model.as_str() {
            "moving_string" => {
                let f: MovingStringSceneFile =
                    table.try_into().map_err(|e| scene_error(source_name, e))?;
                Ok(MovingScene::String(Box::new(MovingStringScene::from_file(
                    f,
                )?)))
            }
            "disc_particle" => {
                let f: DiscSceneFile = table.try_into().map_err(|e| scene_error(source_name, e))?;
                Ok(MovingScene::Disc(DiscScene::from_file(f)?))
            }
            other => Err(
                InputError::new("model", other, "\"moving_string\" or \"disc_particle\"").into(),
            ),
        }
    }
}

impl MovingStringScene {
    /// Validates a parsed string scene.
    pub fn from_file(f: MovingStringSceneFile) -> Result<Self, Error> {
        let oscillator = match &f.oscillator {
            None => None,
            Some(o) => {
                let contact = match o.contact.as_str() {
                    "ideal" => {
                        if o.penalty_stiffness.is_some() {
                            return Err(InputError::new(
                                "oscillator.penalty_stiffness",
                                o.penalty_stiffness.unwrap_or_default(),
                                "no penalty stiffness with contact = \"ideal\"",
                            )
                            .into());
                        }
                        ContactModel::Ideal
                    }
                    "penalty" => ContactModel::Penalty {
                        stiffness: o.penalty_stiffness.ok_or_else(|| {
                            InputError::new(
                                "oscillator.penalty_stiffness",
                                "(missing)",
                                "k̄_p > 0 with contact = \"penalty\"",
                            )
                        })?,
                    },
                    other => {
                        return Err(InputError::new(
                            "oscillator.contact",
                            other,
                            "\"ideal\" or \"penalty\"",
                        )
                        .into())
                    }
                };
                let mut osc = OscillatorData {
                    stiffness: o.stiffness,
                    mass: o.mass,
                    position: o.position,
                    contact,
                    friction: 0.0,
                };
                osc.friction = match (o.friction, o.control_parameter) {
                    (Some(_), Some(p)) => {
                        return Err(InputError::new(
                            "oscillator.control_parameter",
                            p,
                            "either friction or control_parameter, not both",
                        )
                        .into())
                    }
                    (Some(mu_h), None) => mu_h,
                    (None, Some(p)) => {
                        crate::error::require_positive("oscillator.stiffness", o.stiffness)?;
                        p / osc.contact_stiffness()
                    }
                    (None, None) => 0.0,
                };
                Some(osc)
            }
        };
        let data = MovingStringData {
            speed: f.string.speed,
            damping: f.string.damping,
            oscillator,
        };
        data.validate()?;
        let d = &f.discretization;
        let discretization = match d.basis.as_str() {
            "sine" => {
                if d.elements.is_some() {
                    return Err(InputError::new(
                        "discretization.elements",
                        d.elements.unwrap_or_default(),
                        "modes (not elements) for basis = \"sine\"",
                    )
                    .into());
                }
                StringDiscretization::Sine {
                    modes: d.modes.ok_or_else(|| {
                        InputError::new("discretization.modes", "(missing)", "N ≥ 1 sine modes")
                    })?,
                }
            }
            "p1" | "hermite" => {
                if d.modes.is_some() {
                    return Err(InputError::new(
                        "discretization.modes",
                        d.modes.unwrap_or_default(),
                        "elements (not modes) for finite elements",
                    )
                    .into());
                }
                StringDiscretization::FiniteElements {
                    kind: if d.basis == "p1" {
                        ElementKind::P1
                    } else {
                        ElementKind::Hermite
                    },
                    elements: d.elements.ok_or_else(|| {
                        InputError::new(
                            "discretization.elements",
                            "(missing)",
                            "a number of elements",
                        )
                    })?,
                }
            }
            other => {
                return Err(InputError::new(
                    "discretization.basis",
                    other,
                    "\"sine\", \"p1\" or \"hermite\"",
                )
                .into())
            }
        };
        let dim = match discretization {
            StringDiscretization::Sine { modes } => modes,
            StringDiscretization::FiniteElements { elements, .. } => 2 * elements,
        };
        if dim > 400 {
            return Err(InputError::new(
                "discretization",
                dim,
                "at most 400 string coordinates (dense eigenproblems)",
            )
            .into());
        }
        let model = MovingStringModel::new(
            discretization,
            MovingStringParams {
                condensation: d.condensation,
            },
        )?;
        let verdict = verdict_params(&f.stability)?;
        let check_axis = |field: &str, a: &AxisSection| -> Result<GridAxis, Error> {
            let parameter = parse_parameter(&format!("{field}.parameter"), &a.parameter)?;
            let values = axis_values(field, a)?;
            for &v in [values[0], values[values.len() - 1]].iter() {
                let mut probe = data;
                parameter
                    .set(&mut probe, v)
                    .map_err(|e| InputError::new(format!("{field}.from/to"), v, e.to_string()))?;
            }
            Ok(GridAxis { parameter, values })
        };
        let mut sweeps = Vec::new();
        for (i, s) in f.sweep.iter().enumerate() {
            sweeps.push(check_axis(&format!("sweep[{i}]"), s)?);
        }
        let map = match &f.map {
            None => None,
            Some(m) => {
                let x = check_axis("map.x", &m.x)?;
                let y = check_axis("map.y", &m.y)?;
                if x.parameter == y.parameter {
                    return Err(InputError::new(
                        "map.y.parameter",
                        &m.y.parameter,
                        format!("a parameter other than map.x.parameter = {}", m.x.parameter),
                    )
                    .into());
                }
                Some((x, y))
            }
        };
        Ok(Self {
            title: f.title.clone(),
            model,
            data,
            verdict,
            threads: f.stability.threads,
            eigenvectors: f.stability.eigenvectors,
            map_kernel: f.stability.map_kernel.unwrap_or(EigenKernel::SmallDense),
            sweeps,
            map,
        })
    }

    /// Runs the scene: the analysed point, every sweep and the map.
    pub fn run(&self) -> Result<StringSceneResult, Error> {
        let system = self.model.system(&self.data)?;
        let eigen = system
            .eigen(QuadraticEigenParams {
                compute_eigenvectors: self.eigenvectors,
                ..Default::default()
            })
            .map_err(|source| SolveError::Eigenproblem {
                at: "the scene's point".into(),
                source,
            })?;
        let assessment = assess(&eigen.eigenvalues, &self.verdict);
        let mut sweeps = Vec::new();
        for axis in &self.sweeps {
            sweeps.push(string_sweep(
                &self.model,
                &self.data,
                axis,
                QuadraticEigenParams::default(),
                &self.verdict,
                self.threads,
            )?);
        }
        let map = match &self.map {
            None => None,
            Some((x, y)) => Some(string_stability_map(
                &self.model,
                &self.data,
                x,
                y,
                &StabilityMapParams {
                    threads: self.threads,
                    verdict: self.verdict,
                    eigen: QuadraticEigenParams {
                        kernel: self.map_kernel,
                        ..QuadraticEigenParams::default()
                    },
                },
            )?),
        };
        Ok(StringSceneResult {
            coordinates: system.coordinates.clone(),
            control_parameter: self.data.control_parameter(),
            eigenvalues: eigen.eigenvalues.iter().map(|l| [l.re, l.im]).collect(),
            eigenvectors: eigen.eigenvectors.as_ref().map(|x| {
                (0..x.ncols())
                    .map(|j| {
                        (0..x.nrows())
                            .map(|i| [x[(i, j)].re, x[(i, j)].im])
                            .collect()
                    })
                    .collect()
            }),
            assessment,
            stats: eigen.stats,
            sweeps,
            map,
        })
    }
}

/// What a string scene computes.
#[derive(Debug, Clone, Serialize)]
pub struct StringSceneResult {
    pub coordinates: Vec<String>,
    pub control_parameter: f64,
    /// [Re λ, Im λ].
    pub eigenvalues: Vec<[f64; 2]>,
    /// Per eigenvalue, the eigenvector x as [Re, Im] per coordinate.
    pub eigenvectors: Option<Vec<Vec<[f64; 2]>>>,
    pub assessment: StabilityAssessment,
    pub stats: crate::solve::quadratic_eigen::QuadraticEigenStats,
    pub sweeps: Vec<Sweep>,
    pub map: Option<StabilityMap>,
}

impl DiscScene {
    /// Validates a parsed disc scene.
    pub fn from_file(f: DiscSceneFile) -> Result<Self, Error> {
        let p = &f.particle;
        let particle = DiscParticle {
            mass: p.mass,
            stiffness: p.stiffness,
            normal_force: p.normal_force,
            friction_coefficient: p.friction_coefficient,
            radius: p.radius,
            angular_speed: p.angular_speed,
        };
        particle.validate()?;
        let verdict = verdict_params(&f.stability)?;
        let mut sweeps = Vec::new();
        for (i, s) in f.sweep.iter().enumerate() {
            let field = format!("sweep[{i}]");
            let parameter = DiscParameter::parse(&format!("{field}.parameter"), &s.parameter)?;
            let values = axis_values(&field, s)?;
            for &v in &values {
                let mut q = particle;
                parameter.set(&mut q, v);
                q.validate()
                    .map_err(|e| InputError::new(format!("{field}.from/to"), v, e.to_string()))?;
            }
            sweeps.push((parameter, values));
        }
        Ok(Self {
            title: f.title.clone(),
            particle,
            verdict,
            sweeps,
        })
    }

    /// The eigenvalues and verdict at the scene's point and along every sweep.
    pub fn run(&self) -> Result<DiscSceneResult, Error> {
        let point = |p: &DiscParticle| -> Result<DiscPoint, Error> {
            let s = p.system()?;
            let e = solve_quadratic_eigen(
                s.mass.as_ref(),
                s.damping.as_ref(),
                s.stiffness.as_ref(),
                QuadraticEigenParams::default(),
            )
            .map_err(|source| SolveError::Eigenproblem {
                at: format!("Ω = {}", p.angular_speed),
                source,
            })?;
            Ok(DiscPoint {
                friction_damping: p.friction_damping(),
                recovered_damping: -p.mass * e.eigenvalues.iter().map(|l| l.re).sum::<f64>(),
                eigenvalues: e.eigenvalues.iter().map(|l| [l.re, l.im]).collect(),
                assessment: assess(&e.eigenvalues, &self.verdict),
            })
        };
        let base = point(&self.particle)?;
        let mut sweeps = Vec::new();
        for (param, values) in &self.sweeps {
            let mut points = Vec::new();
            for &v in values {
                let mut p = self.particle;
                param.set(&mut p, v);
                points.push(point(&p)?);
            }
            sweeps.push(DiscSweep {
                parameter: *param,
                values: values.clone(),
                points,
            });
        }
        Ok(DiscSceneResult {
            point: base,
            sweeps,
        })
    }
}

/// One analysed point of the disc.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiscPoint {
    /// μN/(|Ω| r0) of (112).
    pub friction_damping: f64,
    /// −m (λ1 + λ2): the damping recovered from the eigenvalues.
    pub recovered_damping: f64,
    pub eigenvalues: Vec<[f64; 2]>,
    pub assessment: StabilityAssessment,
}

/// A disc sweep.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiscSweep {
    pub parameter: DiscParameter,
    pub values: Vec<f64>,
    pub points: Vec<DiscPoint>,
}

/// What a disc scene computes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiscSceneResult {
    pub point: DiscPoint,
    pub sweeps: Vec<DiscSweep>,
}

#[cfg(test)]
mod tests {
    //! Setting: small scenes. Goal: they run, and typos and bad values name their field.
    use super::*;

    const STRING: &str = r#"
model = "moving_string"
[string]
speed = 0.3
damping = 0.05
[oscillator]
stiffness = 2.0
mass = 0.5
position = 0.3
control_parameter = 0.02
[discretization]
basis = "sine"
modes = 6
[[sweep]]
parameter = "speed"
from = 0.0
to = 0.9
points = 10
[map]
x = { parameter = "speed", from = 0.0, to = 0.9, points = 4 }
y = { parameter = "control_parameter", from = 0.0, to = 1.0, points = 3 }
"#;

    #[test]
    fn string_scene_runs_sweeps_and_maps() {
        let MovingScene::String(s) = MovingScene::from_toml_str(STRING, "t.toml").unwrap() else {
            panic!("a string scene")
        };
        assert!((s.data.oscillator.unwrap().friction - 0.01).abs() < 1e-15);
        let r = s.run().unwrap();
        assert_eq!(r.eigenvalues.len(), 14);
        assert_eq!(r.sweeps[0].spectra.len(), 10);
        assert_eq!(r.map.unwrap().points.len(), 12);
    }

    #[test]
    fn misspelt_keys_and_bad_values_are_named() {
        let e =
            MovingScene::from_toml_str(&STRING.replace("damping", "dampng"), "t.toml").unwrap_err();
        assert!(e.to_string().contains("dampng"), "{e}");
        let e =
            MovingScene::from_toml_str(&STRING.replace("position = 0.3", "position = 1.3"), "t")
                .unwrap_err();
        assert!(e.to_string().contains("oscillator.position"), "{e}");
        let e =
            MovingScene::from_toml_str(&STRING.replace("\"speed\", from", "\"sped\", from"), "t")
                .unwrap_err();
        assert!(e.to_string().contains("map.x.parameter"), "{e}");
        let e = MovingScene::from_toml_str(&STRING.replace("modes = 6", "elements = 6"), "t")
            .unwrap_err();
        assert!(e.to_string().contains("discretization.elements"), "{e}");
    }

    #[test]
    fn disc_scene_recovers_the_friction_damping() {
        let text = r#"
model = "disc_particle"
[particle]
mass = 1.0
stiffness = 100.0
normal_force = 10.0
friction_coefficient = 0.3
radius = 0.2
angular_speed = 50.0
[[sweep]]
parameter = "angular_speed"
from = 1.0
to = 100.0
points = 5
scale = "log"
"#;
        let MovingScene::Disc(d) = MovingScene::from_toml_str(text, "d.toml").unwrap() else {
            panic!("a disc scene")
        };
        let r = d.run().unwrap();
        assert!((r.point.recovered_damping - 0.3).abs() < 1e-13);
        for p in &r.sweeps[0].points {
            assert!((p.recovered_damping - p.friction_damping).abs() < 1e-12 * p.friction_damping);
        }
    }
}
