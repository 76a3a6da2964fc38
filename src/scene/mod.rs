//! Scenes: a TOML description of one physical setup, validated into a runnable model that contains
//! only what the scene asks for.
//!
//! Every scene names its `model` (`"rod"`: the quasistatic Kelvin–Voigt rod; `"plane"`: the
//! quasistatic plane body; `"dynamic"`: an elastic body against a rigid foundation). Unknown keys are
//! errors (a misspelt key must not silently fall back to a default), and every value is checked
//! with an error that names its field.

pub mod dynamic;
pub mod field_spec;
pub mod foundation;
pub mod moving;
pub mod plane;
pub mod rod;

use crate::error::Error;

/// Reads the `model` key of a scene (which model the rest of the file describes).
pub fn model_of(text: &str, source_name: &str) -> Result<String, Error> {
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| Error::Scene {
        source_name: source_name.to_string(),
        message: e.to_string(),
    })?;
    match table.get("model") {
        Some(toml::Value::String(s)) => Ok(s.clone()),
        Some(other) => Err(crate::error::InputError::new(
            "model",
            other,
            "a string naming the model, e.g. \"rod\"",
        )
        .into()),
        None => Err(crate::error::InputError::new(
            "model",
            "(missing)",
            "a string naming the model, e.g. model = \"rod\"",
        )
        .into()),
    }
}
