//! Moving-continuum scenes: a linearized model, its discretization, the point to analyse, and
//! optional sweeps and a stability map. Three models:
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
//! # patch_width = 0.05         # ε: contact on a patch [ā − ε/2, ā + ε/2] (0: point contact)
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
//! ```toml
//! model = "rotating_plate"     # the rotating annular Kirchhoff plate, Hetzler (2009) §4.1
//! title = "Brake disc with a pad"
//!
//! [plate]
//! inner_radius = 0.2           # a, clamped (0: the full disc clamped at its centre, w = w_r = 0)
//! outer_radius = 1.0           # b
//! bending_stiffness = 1.0      # D
//! mass_per_area = 1.0          # ρh
//! poisson = 0.3                # ν in (−1, 0.5]
//! thickness = 0.02             # h: the pad friction's moment arm h/2
//! outer_edge = "free"          # "free" | "clamped" | "simply_supported"
//! membrane_stiffening = false  # the spinning disc's in-plane stress (off in the paper)
//! angular_speed = 2.0          # Ω
//! damping = 0.0                # α, mass-proportional
//!
//! [pad]                        # optional: a stationary pad on the upper surface
//! radius = 0.9                 # r_p in (a, b]
//! angle = 0.0                  # φ_p
//! stiffness = 50.0             # k_p ≥ 0 (normal spring)
//! friction = 0.3               # μ ≥ 0 (Coulomb)
//!
//! [discretization]
//! harmonics = 5                # N: 1, cos nφ, sin nφ for n = 1 … N (2N + 1 functions, N ≤ 64)
//! elements = 20                # radial Hermite elements
//! radial_modes = 2             # optional: the lowest radial modes kept per angular function
//!
//! [stability]                  # optional, as for the string
//!
//! [[sweep]]                    # any number
//! parameter = "angular_speed"  # angular_speed, damping, pad_stiffness, friction (the last two
//! from = 0.0                   # need a [pad])
//! to = 6.0
//! points = 200
//!
//! [map]                        # optional
//! x = { parameter = "angular_speed", from = 0.0, to = 6.0, points = 60 }
//! y = { parameter = "friction", from = 0.0, to = 1.0, points = 60 }
//! ```
//!
//! The coordinates, (2N + 1) × (radial functions or `radial_modes`), are at most
//! `model::moving::plate::model::MAX_COORDINATES`. Besides the eigenvalues and verdicts, a plate
//! scene reports the non-rotating frequencies ω_{n,m} of its discretization and the spatial-frame
//! waves they predict, ω_{n,m} + n|Ω| and |ω_{n,m} − n|Ω|| (critical speeds ω_{n,m}/n).
//!
//! Unknown keys are errors; every value is validated with an error naming its field.
//!
//! `string` holds the `moving_string` scene, `disc` the `disc_particle` scene, `plate` and
//! `plate_run` the `rotating_plate` scene, `sections` the sections they share.

mod disc;
mod plate;
mod plate_run;
mod sections;
mod string;

use crate::error::{Error, InputError};
use crate::scene::common::scene_error;

pub use disc::{
    DiscParameter, DiscPoint, DiscScene, DiscSceneFile, DiscSceneResult, DiscSweep, ParticleSection,
};
pub use plate::{
    PadSection, PlateDiscretizationSection, PlateSection, RotatingPlateScene,
    RotatingPlateSceneFile,
};
pub use plate_run::{HarmonicWaves, PlateSceneResult};
pub use sections::{axis_values, AxisSection, MapSection, StabilitySection};
pub use string::{
    DiscretizationSection, MovingStringScene, MovingStringSceneFile, OscillatorSection,
    StringSceneResult, StringSection,
};

/// Any moving-continuum scene.
#[derive(Debug)]
pub enum MovingScene {
    String(Box<MovingStringScene>),
    Disc(DiscScene),
    Plate(Box<RotatingPlateScene>),
}

impl MovingScene {
    /// Parses and validates a moving-continuum scene (`model = "moving_string"`,
    /// `"disc_particle"` or `"rotating_plate"`); `source_name` labels errors.
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
            "rotating_plate" => {
                let f: RotatingPlateSceneFile =
                    table.try_into().map_err(|e| scene_error(source_name, e))?;
                Ok(MovingScene::Plate(Box::new(RotatingPlateScene::from_file(
                    f,
                )?)))
            }
            other => Err(InputError::new(
                "model",
                other,
                "\"moving_string\", \"disc_particle\" or \"rotating_plate\"",
            )
            .into()),
        }
    }
}
