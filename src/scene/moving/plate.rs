//! The `rotating_plate` scene: the rotating annular Kirchhoff plate of Hetzler (2009) §4.1 with an
//! optional stationary friction pad, its Ritz discretization (Fourier harmonics × radial Hermite
//! elements, optionally reduced to the lowest radial modes of each harmonic), the analysed point,
//! sweeps and a stability map. The run is in `plate_run.rs`.

use serde::{Deserialize, Serialize};

use crate::error::{Error, InputError, SolveError};
use crate::model::moving::plate::angular::AngularBasis;
use crate::model::moving::plate::model::MAX_COORDINATES;
use crate::model::moving::plate::radial::RadialBasis;
use crate::model::moving::plate::{
    OuterEdge, PadData, PlateData, PlateDiscretization, PlateParameter, PlateProperties,
    RotatingPlateModel,
};
use crate::model::moving::stability::VerdictParams;
use crate::model::moving::stability_map::{resolve_threads, GridAxis};
use crate::scene::moving::sections::{
    axis_values, sweeps_and_map, verdict_params, AxisSection, MapSection, StabilitySection,
};
use crate::solve::quadratic_eigen::EigenKernel;

/// `[plate]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlateSection {
    /// a in [0, 0.999 b): the clamped inner radius (0: the full disc clamped at its centre,
    /// w = w_r = 0) (docs/moving_continua.md §4.1).
    pub inner_radius: f64,
    /// b > 0: the outer radius.
    pub outer_radius: f64,
    /// D > 0: the bending stiffness of the Kirchhoff plate.
    pub bending_stiffness: f64,
    /// ρh > 0: the mass per unit area.
    pub mass_per_area: f64,
    /// ν in (−1, 0.5]: Poisson's ratio.
    pub poisson: f64,
    /// h > 0: the thickness, the pad friction's moment arm h/2.
    pub thickness: f64,
    /// The outer edge r = b: `"free"`, `"clamped"` or `"simply_supported"` (default `"free"`).
    #[serde(default = "free")]
    pub outer_edge: String,
    /// Add the geometric stiffness of the spinning disc's in-plane stress (default false, off in
    /// the paper).
    #[serde(default)]
    pub membrane_stiffening: bool,
    /// Ω, finite: the angular speed of the plate.
    pub angular_speed: f64,
    /// α ≥ 0: mass-proportional damping (default 0).
    #[serde(default)]
    pub damping: f64,
}

fn free() -> String {
    "free".into()
}

/// `[pad]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PadSection {
    /// r_p in (a, b]: the radius at which the pad touches the plate.
    pub radius: f64,
    /// φ_p, finite: the pad's angle (default 0).
    #[serde(default)]
    pub angle: f64,
    /// k_p ≥ 0: the pad's normal spring.
    pub stiffness: f64,
    /// μ ≥ 0: the Coulomb coefficient between pad and plate (default 0).
    #[serde(default)]
    pub friction: f64,
}

/// `[discretization]` of the plate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlateDiscretizationSection {
    /// N in 0 … 64: harmonics 1, cos nφ, sin nφ for n = 1 … N (2N + 1 angular functions).
    pub harmonics: usize,
    /// The number of radial Hermite elements on [a, b].
    pub elements: usize,
    /// The lowest radial modes kept per angular function, 1 to the radial functions (absent:
    /// the full radial basis).
    pub radial_modes: Option<usize>,
}

/// The file format of a `rotating_plate` scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotatingPlateSceneFile {
    /// `"rotating_plate"`: the rotating annular Kirchhoff plate with an optional friction pad,
    /// Hetzler (2009) §4.1 (docs/moving_continua.md).
    pub model: String,
    /// A title for the reports and plots (default: none).
    #[serde(default)]
    pub title: String,
    /// `[plate]`: the plate, its outer edge, speed and damping.
    pub plate: PlateSection,
    /// `[pad]`: a stationary pad on the upper surface, a normal spring with Coulomb friction
    /// (absent: no pad).
    pub pad: Option<PadSection>,
    /// `[discretization]`: Fourier harmonics × radial Hermite elements; at most `MAX_COORDINATES`
    /// coordinates.
    pub discretization: PlateDiscretizationSection,
    /// `[stability]`: the verdict tolerances and the run options (default: all defaults).
    #[serde(default)]
    pub stability: StabilitySection,
    /// `[[sweep]]`: eigenvalue loci along one parameter, any number (default: none).
    #[serde(default)]
    pub sweep: Vec<AxisSection>,
    /// `[map]`: verdicts on a grid of two parameters (absent: none).
    pub map: Option<MapSection>,
}

/// A validated plate scene.
#[derive(Debug)]
pub struct RotatingPlateScene {
    pub title: String,
    pub model: RotatingPlateModel,
    pub data: PlateData,
    pub verdict: VerdictParams,
    pub threads: usize,
    pub eigenvectors: bool,
    pub map_kernel: EigenKernel,
    pub sweeps: Vec<GridAxis<PlateParameter>>,
    pub map: Option<(GridAxis<PlateParameter>, GridAxis<PlateParameter>)>,
}

/// The plate parameter named `s`; `field` names the key in errors.
fn parse_parameter(field: &str, s: &str) -> Result<PlateParameter, InputError> {
    Ok(match s {
        "angular_speed" => PlateParameter::AngularSpeed,
        "damping" => PlateParameter::Damping,
        "pad_stiffness" => PlateParameter::PadStiffness,
        "friction" => PlateParameter::Friction,
        _ => {
            return Err(InputError::new(
                field,
                s,
                "angular_speed, damping, pad_stiffness or friction",
            ))
        }
    })
}

/// The outer edge named `s`.
fn parse_edge(s: &str) -> Result<OuterEdge, InputError> {
    Ok(match s {
        "free" => OuterEdge::Free,
        "clamped" => OuterEdge::Clamped,
        "simply_supported" => OuterEdge::SimplySupported,
        other => {
            return Err(InputError::new(
                "plate.outer_edge",
                other,
                "\"free\", \"clamped\" or \"simply_supported\"",
            ))
        }
    })
}

/// Bytes of one f64.
const F64: f64 = 8.0;

impl RotatingPlateScene {
    /// Validates a parsed plate scene: every value with an error naming its key, the sizes and
    /// the memory before anything large is allocated.
    pub fn from_file(f: RotatingPlateSceneFile) -> Result<Self, Error> {
        let p = &f.plate;
        let props = PlateProperties {
            inner_radius: p.inner_radius,
            outer_radius: p.outer_radius,
            bending_stiffness: p.bending_stiffness,
            mass_per_area: p.mass_per_area,
            poisson: p.poisson,
            thickness: p.thickness,
            outer_edge: parse_edge(&p.outer_edge)?,
            membrane_stiffening: p.membrane_stiffening,
        };
        props.validate()?;
        let data = PlateData {
            angular_speed: p.angular_speed,
            damping: p.damping,
            pad: f.pad.as_ref().map(|q| PadData {
                radius: q.radius,
                angle: q.angle,
                stiffness: q.stiffness,
                friction: q.friction,
            }),
        };
        data.validate(&props)?;
        let d = &f.discretization;
        let angular = AngularBasis::Periodic {
            harmonics: d.harmonics,
        };
        angular.validate()?;
        // the radial basis is O(elements); the dense matrices come after the size checks
        let radial = RadialBasis::uniform(
            props.inner_radius,
            props.outer_radius,
            d.elements,
            props.outer_edge,
        )?
        .len();
        let block = match d.radial_modes {
            None => radial,
            Some(m) if (1..=radial).contains(&m) => m,
            Some(m) => {
                return Err(InputError::new(
                    "discretization.radial_modes",
                    m,
                    format!(
                        "1 to {radial} (the radial functions of {} elements)",
                        d.elements
                    ),
                )
                .into())
            }
        };
        let dim = angular.len() * block;
        if dim > MAX_COORDINATES {
            let (key, written) = match d.radial_modes {
                Some(m) => ("discretization.radial_modes", m),
                None => ("discretization.elements", d.elements),
            };
            return Err(InputError::new(
                key,
                written,
                format!(
                    "at most {MAX_COORDINATES} coordinates (dense eigenproblems); (2N + 1) × {} \
                     = {} × {block} = {dim} with N = discretization.harmonics = {}",
                    if d.radial_modes.is_some() {
                        "radial_modes"
                    } else {
                        "radial functions"
                    },
                    angular.len(),
                    d.harmonics
                ),
            )
            .into());
        }
        let verdict = verdict_params(&f.stability)?;
        let check_axis = |field: &str,
                          a: &AxisSection|
         -> Result<GridAxis<PlateParameter>, Error> {
            let parameter = parse_parameter(&format!("{field}.parameter"), &a.parameter)?;
            if data.pad.is_none()
                && matches!(
                    parameter,
                    PlateParameter::PadStiffness | PlateParameter::Friction
                )
            {
                return Err(InputError::new(
                    format!("{field}.parameter"),
                    &a.parameter,
                    "a scene with a [pad] section (pad_stiffness and friction are the pad's)",
                )
                .into());
            }
            let values = axis_values(field, a)?;
            for &v in [values[0], values[values.len() - 1]].iter() {
                let mut probe = data;
                parameter
                    .set(&mut probe, v)
                    .and_then(|()| probe.validate(&props))
                    .map_err(|e| InputError::new(format!("{field}.from/to"), v, e.to_string()))?;
            }
            Ok(GridAxis { parameter, values })
        };
        let (sweeps, map) = sweeps_and_map(&f.sweep, f.map.as_ref(), check_axis)?;
        Self::check_memory(&f, radial, dim, &sweeps, map.as_ref())?;
        // M is positive definite for every valid plate: a solver failure here means numbers
        // beyond the range of doubles (e.g. the mass of the slope functions ∝ ρh b⁴)
        let model = RotatingPlateModel::new(
            props,
            PlateDiscretization {
                angular,
                elements: d.elements,
                radial_modes: d.radial_modes,
            },
        )
        .map_err(|e| match e {
            // a stop request is not the plate's fault: it passes through as it is
            Error::Solve(s) if !matches!(s, SolveError::Stopped { .. }) => InputError::new(
                "plate",
                format!(
                    "(b = {}, D = {}, ρh = {})",
                    p.outer_radius, p.bending_stiffness, p.mass_per_area
                ),
                format!(
                    "a plate whose radial matrices stay within the range of doubles \
                     (plate.outer_radius, plate.inner_radius, plate.bending_stiffness, \
                     plate.mass_per_area): {s}"
                ),
            )
            .into(),
            other => other,
        })?;
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

    /// The memory of the run from the counts alone: the radial matrices and the radial
    /// eigenproblems (≈ 13 R² doubles for R radial functions), the model's operators (6 n²
    /// for n coordinates), a dense quadratic eigenproblem of order 2n per worker (16 (2n)²), each
    /// sweep point's spectrum and branch (2n complex numbers, thrice) and 256 B per map point.
    fn check_memory(
        f: &RotatingPlateSceneFile,
        radial: usize,
        dim: usize,
        sweeps: &[GridAxis<PlateParameter>],
        map: Option<&(GridAxis<PlateParameter>, GridAxis<PlateParameter>)>,
    ) -> Result<(), Error> {
        let (r, n) = (radial as f64, dim as f64 + 2.0);
        let sweep_points: f64 = sweeps.iter().map(|a| a.values.len() as f64).sum();
        let map_points = map.map_or(0.0, |(x, y)| x.values.len() as f64 * y.values.len() as f64);
        let work = sweeps
            .iter()
            .map(|a| a.values.len())
            .chain(map.map(|(x, y)| x.values.len().max(y.values.len())))
            .max()
            .unwrap_or(1);
        let workers = resolve_threads(f.stability.threads, work) as f64;
        let operators =
            (13.0 * r * r + 6.0 * n * n) * F64 + workers * 16.0 * (2.0 * n).powi(2) * F64;
        let results = sweep_points * 2.0 * n * 16.0 * 3.0 + map_points * 256.0;
        let (field, written) = if results <= operators {
            (
                "discretization.elements",
                format!(
                    "{} ({} radial functions, {dim} coordinates)",
                    f.discretization.elements, radial
                ),
            )
        } else if map_points > sweep_points {
            ("map.x.points × map.y.points", format!("{map_points}"))
        } else {
            ("sweep[].points", format!("{sweep_points}"))
        };
        // each result is written as text too (about 40 B a number, 5 times its doubles)
        crate::scene::memory::require_memory(
            field,
            &written,
            crate::scene::memory::PROGRAM_BYTES + operators + 6.0 * results,
            "16 MiB + 13 R² + 6 n² doubles of operators, 16 (2n)² per worker, 6 × (48 B × 2n \
             per sweep point + 256 B per map point) with the results' text",
        )?;
        crate::scene::memory::require_disk(
            field,
            written,
            5.0 * results,
            "5 × (48 B × 2n per sweep point + 256 B per map point): the results as text",
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! Setting: a small annular plate (a = 0.2, b = 1, free outer edge, N = 2, 4 elements) with a
    //! pad. Goal: it runs (point, sweep, map); misspelt keys and bad values are named as written.
    use crate::scene::moving::MovingScene;

    pub(crate) const PLATE: &str = r#"
model = "rotating_plate"
title = "small plate"
[plate]
inner_radius = 0.2
outer_radius = 1.0
bending_stiffness = 1.0
mass_per_area = 1.0
poisson = 0.3
thickness = 0.02
outer_edge = "free"
angular_speed = 2.0
damping = 0.0
[pad]
radius = 0.9
angle = 0.0
stiffness = 50.0
friction = 0.3
[discretization]
harmonics = 2
elements = 4
radial_modes = 2
[[sweep]]
parameter = "angular_speed"
from = 0.0
to = 5.0
points = 6
[map]
x = { parameter = "angular_speed", from = 0.0, to = 5.0, points = 4 }
y = { parameter = "friction", from = 0.0, to = 1.0, points = 3 }
"#;

    fn err(text: &str) -> String {
        MovingScene::from_toml_str(text, "t.toml")
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn plate_scene_runs_point_sweep_and_map() {
        let MovingScene::Plate(s) = MovingScene::from_toml_str(PLATE, "t.toml").unwrap() else {
            panic!("a plate scene")
        };
        let r = s.run().unwrap();
        // (2N + 1) angular functions × 2 radial modes, two eigenvalues per coordinate
        assert_eq!(r.eigenvalues.len(), 2 * 5 * 2);
        assert_eq!(r.sweeps[0].spectra.len(), 6);
        assert_eq!(r.map.as_ref().unwrap().points.len(), 12);
        assert_eq!(r.harmonics.len(), 3);
        // the predicted waves of n = 1 at Ω = 2: ω ± 2, and the critical speed ω/1
        let h1 = &r.harmonics[1];
        assert!((h1.forward[0] - h1.frequencies[0] - 2.0).abs() < 1e-12);
        assert!((h1.backward[0] - (h1.frequencies[0] - 2.0).abs()).abs() < 1e-12);
        assert_eq!(h1.critical_speeds[0], h1.frequencies[0]);
        assert!(r.harmonics[0].critical_speeds.is_empty());
        let json = serde_json::to_string(&r).unwrap();
        assert!(!json.contains("null"), "non-finite numbers in the JSON");
    }

    #[test]
    fn misspelt_keys_and_bad_values_are_named() {
        let e = err(&PLATE.replace("poisson", "poison"));
        assert!(e.contains("poison"), "{e}");
        for (from, to, key) in [
            ("poisson = 0.3", "poisson = 0.7", "plate.poisson"),
            ("radius = 0.9", "radius = 1.9", "pad.radius"),
            (
                "harmonics = 2",
                "harmonics = 100",
                "discretization.harmonics",
            ),
            (
                "radial_modes = 2",
                "radial_modes = 0",
                "discretization.radial_modes",
            ),
            ("elements = 4", "elements = 0", "discretization.elements"),
            ("\"free\"", "\"loose\"", "plate.outer_edge"),
            ("\"friction\", from", "\"frictin\", from", "map.y.parameter"),
            (
                "\"friction\", from",
                "\"angular_speed\", from",
                "map.y.parameter",
            ),
            ("stiffness = 50.0", "stiffness = -50.0", "pad.stiffness"),
            (
                "to = 5.0\npoints = 6",
                "to = 5.0\npoints = 1",
                "sweep[0].points",
            ),
        ] {
            let e = err(&PLATE.replace(from, to));
            assert!(e.contains(key), "{from} → {to}: {e}");
        }
    }

    #[test]
    fn pad_parameters_without_a_pad_and_oversized_discretizations_are_refused() {
        let no_pad = PLATE.replace(
            "[pad]\nradius = 0.9\nangle = 0.0\nstiffness = 50.0\nfriction = 0.3\n",
            "",
        );
        let e = err(&no_pad);
        assert!(e.contains("map.y.parameter") && e.contains("[pad]"), "{e}");
        let huge = PLATE
            .replace("harmonics = 2", "harmonics = 60")
            .replace("elements = 4", "elements = 20")
            .replace("radial_modes = 2\n", "");
        let e = err(&huge);
        assert!(
            e.contains("discretization.elements") && e.contains("2400"),
            "{e}"
        );
    }
}
