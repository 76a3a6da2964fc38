//! Scenes: a TOML description of one physical setup, validated into a runnable model that contains
//! only what the scene asks for.
//!
//! Every scene names its `model` (`"rod"`: the quasistatic Kelvin–Voigt rod; `"plane"`: the
//! quasistatic plane body; `"dynamic"`: an elastic body against a rigid foundation — or, written
//! as `[[body]]` sections, several bodies in contact ([`multibody`]);
//! `"moving_string"`, `"disc_particle"`: moving continua). [`Scene`] reads any of them once and
//! runs it into a [`Solution`]; each model's module holds its format. Unknown keys are errors (a
//! misspelt key must not silently fall back to a default), and every value is checked with an
//! error that names its field.
//!
//! What several formats share has one home: `common` (reading the TOML, the `model` check, the
//! errors for missing and misplaced keys), `boundary` (the boundary parts of plane bodies),
//! `plane_shape` (a plane body's shape keys and its mesh), `hyperelastic_law` (a plane-strain
//! law from `law`, `young`, `poisson`), `field_spec` and `foundation`.

pub mod any;
mod boundary;
mod common;
pub mod dynamic;
pub mod field_spec;
mod fixed_array;
pub mod foundation;
mod hyperelastic_law;
pub mod memory;
pub mod moving;
pub mod multibody;
pub mod plane;
mod plane_shape;
pub mod rod;

pub use any::{Scene, Solution};
