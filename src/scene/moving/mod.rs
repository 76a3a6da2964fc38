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
//! Unknown keys are errors; every value is validated with an error naming its field.
//!
//! `string` holds the `moving_string` scene, `disc` the `disc_particle` scene, `sections` the
//! sections both share.

mod disc;
mod sections;
mod string;

use crate::error::{Error, InputError};
use crate::scene::common::scene_error;

pub use disc::{
    DiscParameter, DiscPoint, DiscScene, DiscSceneFile, DiscSceneResult, DiscSweep, ParticleSection,
};
pub use sections::{axis_values, AxisSection, StabilitySection};
pub use string::{
    DiscretizationSection, MapSection, MovingStringScene, MovingStringSceneFile, OscillatorSection,
    StringSceneResult, StringSection,
};

/// Either scene.
#[derive(Debug)]
pub enum MovingScene {
    String(Box<MovingStringScene>),
    Disc(DiscScene),
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
