//! What the scene formats share: reading a scene's TOML into its format, the check of its
//! `model`, and the errors for a missing key and for a key that the chosen variant (a shape, a
//! law) does not take.

use std::fmt::Display;

use serde::de::DeserializeOwned;

use crate::error::{Error, InputError};

/// The error of a scene that cannot be read (TOML syntax, an unknown key, a wrong type),
/// labelled with `source_name` (a file name).
pub(crate) fn scene_error(source_name: &str, e: impl Display) -> Error {
    Error::Scene {
        source_name: source_name.to_string(),
        message: crate::error::readable(&e.to_string()),
    }
}

/// The scene format `T` read from the TOML `text`; `source_name` labels errors.
pub(crate) fn parse_toml<T: DeserializeOwned>(text: &str, source_name: &str) -> Result<T, Error> {
    toml::from_str(text).map_err(|e| scene_error(source_name, e))
}

/// Checks that a scene file's `model` key names the `expected` model.
pub(crate) fn check_model(model: &str, expected: &str) -> Result<(), InputError> {
    if model == expected {
        Ok(())
    } else {
        Err(InputError::new("model", model, format!("\"{expected}\"")))
    }
}

/// The error for the missing key `field`, which should hold `what`.
pub(crate) fn missing(field: impl Into<String>, what: impl Into<String>) -> InputError {
    InputError::new(field, "(missing)", what)
}

/// Rejects the first key of `given` (name, whether present) that is present but not in
/// `allowed`: it is named `{prefix}.{key}` in an error saying that `choice` = (key, value), e.g.
/// (`shape`, `bar`), takes no such key.
pub(crate) fn reject_keys(
    prefix: &str,
    (key, value): (&str, &str),
    given: &[(&str, bool)],
    allowed: &[&str],
) -> Result<(), InputError> {
    match given
        .iter()
        .find(|(k, present)| *present && !allowed.contains(k))
    {
        Some((k, _)) => Err(InputError::new(
            format!("{prefix}.{k}"),
            "(given)",
            format!("no such key for {key} = \"{value}\""),
        )),
        None => Ok(()),
    }
}

/// A mesh generator's error with its field as the scene writes it: `mesh.width` → `body.size[0]`,
/// `mesh.height` → `body.size[1]`, `mesh.radius` → `body.radius` (`section` = `body` or
/// `geometry`).
pub(crate) fn mesh_field_as_written(
    section: &str,
) -> impl Fn(crate::error::InputError) -> crate::error::InputError + '_ {
    move |mut e| {
        if let Some(key) = e.field.strip_prefix("mesh.") {
            let key = match key {
                "width" => "size[0]",
                "height" => "size[1]",
                other => other,
            };
            e.field = format!("{section}.{key}");
        }
        e
    }
}
