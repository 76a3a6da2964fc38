//! The `disc_particle` scene: the particle on the rotating disc, its analysed point and sweeps.

use serde::{Deserialize, Serialize};

use crate::error::{Error, InputError, SolveError};
use crate::model::moving::disc::DiscParticle;
use crate::model::moving::stability::{assess, StabilityAssessment, VerdictParams};
use crate::scene::moving::sections::{axis_values, verdict_params, AxisSection, StabilitySection};
use crate::solve::quadratic_eigen::{solve_quadratic_eigen, QuadraticEigenParams};

/// `[particle]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParticleSection {
    /// m > 0: the particle's mass (docs/moving_continua.md §4.2.3).
    pub mass: f64,
    /// c > 0: the radial spring, relaxed at radius r0.
    pub stiffness: f64,
    /// N ≥ 0: the force pressing the particle on the disc.
    pub normal_force: f64,
    /// μ ≥ 0: the Coulomb coefficient between particle and disc.
    pub friction_coefficient: f64,
    /// r0 > 0: the radius at which the spring is relaxed.
    pub radius: f64,
    /// Ω, finite and non-zero: the disc's angular speed (the linearization needs sliding, Ω r0 ≠
    /// 0).
    pub angular_speed: f64,
}

/// The file format of a `disc_particle` scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscSceneFile {
    /// `"disc_particle"`: the particle on a rotating disc, Hetzler (2009) §4.2.3, m Δr̈ + (μ N/(Ω
    /// r0)) Δṙ + c Δr = 0 (docs/moving_continua.md).
    pub model: String,
    /// A title for the reports and plots (default: none).
    #[serde(default)]
    pub title: String,
    /// `[particle]`: the particle, its spring, the contact and the disc's speed.
    pub particle: ParticleSection,
    /// `[stability]`: the verdict tolerances and the run options (default: all defaults).
    #[serde(default)]
    pub stability: StabilitySection,
    /// `[[sweep]]`: eigenvalue loci along one parameter, any number (default: none).
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

/// A validated disc scene.
#[derive(Debug, Clone)]
pub struct DiscScene {
    pub title: String,
    pub particle: DiscParticle,
    pub verdict: VerdictParams,
    pub sweeps: Vec<(DiscParameter, Vec<f64>)>,
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
            for (i, &v) in values.iter().enumerate() {
                crate::run_control::report_progress("sweep points", i as u64, values.len() as u64);
                crate::run_control::check(|| {
                    format!("point {} of {} of the sweep", i + 1, values.len())
                })?;
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
    //! Setting: a small disc scene. Goal: it recovers the friction damping.
    use crate::scene::moving::MovingScene;

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
