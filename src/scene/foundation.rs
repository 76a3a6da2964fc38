//! The foundation laws of scenes: `law = "linear" | "lubricated" | "prescribed"` with their keys.

use crate::contact::normal_law::{FoundationLaw, NormalLaw};
use crate::error::InputError;
use crate::scene::common::{missing, reject_keys};
use crate::scene::field_spec::FieldSpec;

/// The law (2.7) `linear` (β), (2.8) `lubricated` (β, p0) or (2.9) `prescribed` (stress) of the
/// section `prefix`, with every key checked.
pub fn foundation_law(
    prefix: &str,
    law: &str,
    beta: Option<f64>,
    p0: Option<&FieldSpec>,
    stress: Option<&FieldSpec>,
) -> Result<FoundationLaw, InputError> {
    let key = |k: &str| format!("{prefix}.{k}");
    let required = |k: &str, present: bool| -> Result<(), InputError> {
        if present {
            Ok(())
        } else {
            Err(missing(key(k), format!("a value for law = \"{law}\"")))
        }
    };
    let reject = |k: &str, present: bool| reject_keys(prefix, ("law", law), &[(k, present)], &[]);
    let out = match law {
        "linear" => {
            required("beta", beta.is_some())?;
            reject("p0", p0.is_some())?;
            reject("stress", stress.is_some())?;
            FoundationLaw::Linear {
                beta: beta.unwrap_or_default(),
            }
        }
        "lubricated" => {
            required("beta", beta.is_some())?;
            required("p0", p0.is_some())?;
            reject("stress", stress.is_some())?;
            FoundationLaw::Lubricated {
                beta: beta.unwrap_or_default(),
                p0: p0
                    .map(|f| f.to_field(&key("p0")))
                    .transpose()?
                    .unwrap_or(crate::field::Field::Constant(0.0)),
            }
        }
        "prescribed" => {
            required("stress", stress.is_some())?;
            reject("beta", beta.is_some())?;
            reject("p0", p0.is_some())?;
            FoundationLaw::Prescribed {
                stress: stress
                    .map(|f| f.to_field(&key("stress")))
                    .transpose()?
                    .unwrap_or(crate::field::Field::Constant(0.0)),
            }
        }
        other => {
            return Err(InputError::new(
                key("law"),
                format!("\"{other}\""),
                "\"linear\" (2.7), \"lubricated\" (2.8) or \"prescribed\" (2.9)",
            ))
        }
    };
    out.validate().map_err(|e| InputError {
        field: e.field.replacen("foundation.", &format!("{prefix}."), 1),
        ..e
    })?;
    Ok(out)
}
