//! The `moving_string` scene: the axially moving string with an optional oscillator in the
//! bushing, its discretization, the analysed point, sweeps and a stability map.

use serde::{Deserialize, Serialize};

use crate::error::{Error, InputError, SolveError};
use crate::model::moving::finite_element_basis::ElementKind;
use crate::model::moving::linearized::assess_point;
use crate::model::moving::stability::{StabilityAssessment, VerdictParams};
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
use crate::scene::moving::sections::{
    axis_values, sweeps_and_map, verdict_params, AxisSection, MapSection, StabilitySection,
};
use crate::solve::quadratic_eigen::{EigenKernel, QuadraticEigenParams};

/// `[string]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StringSection {
    /// v̄: the transport speed over the wave speed (79)–(82), finite (1: the undamped string
    /// diverges) (docs/moving_continua.md §4.2.1).
    pub speed: f64,
    /// ᾱ ≥ 0: mass-proportional (air-drag) damping of the weak form (83) (default 0).
    #[serde(default)]
    pub damping: f64,
}

/// `[oscillator]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OscillatorSection {
    /// c̄ > 0: the oscillator spring (83).
    pub stiffness: f64,
    /// m̄ > 0: the oscillator mass (83).
    pub mass: f64,
    /// ā in (0, 1): the bushing position between the guides at 0 and 1.
    pub position: f64,
    /// `"ideal"` (the bushing follows the string, y_c = w(ā)) or `"penalty"` (a massless bushing
    /// y_c on a spring k̄_p, (87)–(91)) (default `"ideal"`).
    #[serde(default = "ideal")]
    pub contact: String,
    /// k̄_p > 0: the contact spring of `contact = "penalty"` (required there, refused for
    /// `"ideal"`).
    pub penalty_stiffness: Option<f64>,
    /// μ h̄ ≥ 0: friction coefficient times thickness of the thick string (99) (absent, with no
    /// `control_parameter`: 0, the thin string).
    pub friction: Option<f64>,
    /// Instead of `friction`: p = μ h̄ c̄ (ideal contact, (103)) or μ h̄ k̄_p (penalty,
    /// (105)–(108)).
    pub control_parameter: Option<f64>,
    /// ε: the width of the contact patch (0: point contact, the paper's).
    #[serde(default)]
    pub patch_width: f64,
}

fn ideal() -> String {
    "ideal".into()
}

/// `[discretization]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscretizationSection {
    /// The Ritz basis (84): `"sine"` (`modes`), `"p1"` or `"hermite"` finite elements (`elements`);
    /// at most 400 string coordinates.
    pub basis: String,
    /// N ≥ 1 sine functions, basis `"sine"` only.
    pub modes: Option<usize>,
    /// The number of finite elements, bases `"p1"` and `"hermite"` only.
    pub elements: Option<usize>,
    /// How the massless penalty bushing is eliminated (90)–(91) (default `"series_springs"`).
    #[serde(default)]
    pub condensation: PenaltyCondensation,
}

/// The file format of a `moving_string` scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MovingStringSceneFile {
    /// `"moving_string"`: the axially moving string with an oscillator in a bushing, Hetzler (2009)
    /// §4.2.1–4.2.2 (docs/moving_continua.md).
    pub model: String,
    /// A title for the reports and plots (default: none).
    #[serde(default)]
    pub title: String,
    /// `[string]`: the string's speed and damping.
    pub string: StringSection,
    /// `[oscillator]`: the oscillator in the bushing and its contact (absent: the bare string).
    pub oscillator: Option<OscillatorSection>,
    /// `[discretization]`: the Ritz basis of the string.
    pub discretization: DiscretizationSection,
    /// `[stability]`: the verdict tolerances and the run options (default: all defaults).
    #[serde(default)]
    pub stability: StabilitySection,
    /// `[[sweep]]`: eigenvalue loci along one parameter, any number (default: none).
    #[serde(default)]
    pub sweep: Vec<AxisSection>,
    /// `[map]`: verdicts on a grid of two parameters (absent: none).
    pub map: Option<MapSection>,
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

/// The string parameter named `s`; `field` names the key in errors.
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
                    patch_width: o.patch_width,
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
                        crate::error::require_nonnegative("oscillator.control_parameter", p)?;
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
            let (key, written) = match discretization {
                StringDiscretization::Sine { modes } => ("discretization.modes", modes),
                StringDiscretization::FiniteElements { elements, .. } => {
                    ("discretization.elements", elements)
                }
            };
            return Err(InputError::new(
                key,
                written,
                format!("at most 400 string coordinates (dense eigenproblems); this gives {dim}"),
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
        let (sweeps, map) = sweeps_and_map(&f.sweep, f.map.as_ref(), check_axis)?;
        // memory: each sweep point keeps its 2·dim eigenvalues (and the tracked branches), each
        // map point its assessment; each worker a dense eigenproblem of order 2·dim
        let coords = dim as f64 + 2.0;
        let sweep_points: f64 = sweeps.iter().map(|a| a.values.len() as f64).sum();
        let map_points = map
            .as_ref()
            .map_or(0.0, |(x, y)| x.values.len() as f64 * y.values.len() as f64);
        let estimate = sweep_points * 2.0 * coords * 16.0 * 3.0
            + map_points * 256.0
            + 16.0 * (2.0 * coords).powi(2) * 8.0 * 4.0;
        let (field, written) = if map_points > sweep_points {
            ("map.x.points × map.y.points", format!("{map_points}"))
        } else {
            ("sweep[].points", format!("{sweep_points}"))
        };
        let results = estimate - 16.0 * (2.0 * coords).powi(2) * 8.0 * 4.0;
        // each result is written as text too (about 40 B a number, 5 times its doubles)
        crate::scene::memory::require_memory(
            field,
            &written,
            crate::scene::memory::PROGRAM_BYTES + estimate + 5.0 * results,
            "16 MiB + 6 × (48 B × 2(N + 2) per sweep point + 256 B per map point) with the \
             results' text + dense eigen workspaces",
        )?;
        crate::scene::memory::require_disk(
            field,
            written,
            5.0 * results,
            "5 × (48 B × 2(N + 2) per sweep point + 256 B per map point): the results as text",
        )?;
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
        let assessment = assess_point(&self.model, &self.data, &eigen.eigenvalues, &self.verdict);
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
    #[serde(skip_serializing_if = "Option::is_none")]
    pub eigenvectors: Option<Vec<Vec<[f64; 2]>>>,
    pub assessment: StabilityAssessment,
    pub stats: crate::solve::quadratic_eigen::QuadraticEigenStats,
    pub sweeps: Vec<Sweep>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub map: Option<StabilityMap>,
}

#[cfg(test)]
mod tests {
    //! Setting: small string scenes. Goal: they run, and typos and bad values name their field.
    use crate::scene::moving::MovingScene;

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
}
