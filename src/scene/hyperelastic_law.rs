//! The plane-strain hyperelastic law of a scene's material keys (`law`, `young`, `poisson`),
//! shared by the dynamic scene's `[material]` (and its regions) and the multibody scene's
//! `[[body]]` materials.

use std::sync::Arc;

use crate::error::InputError;
use crate::material::hyperelastic::{Hyperelastic2d, LinearElastic, NeoHooke, StVenantKirchhoff};

/// The plane-strain law `law` with Young's modulus `young` and Poisson's ratio `poisson`; errors
/// name `{prefix}.law`, `{prefix}.young`, `{prefix}.poisson`.
pub(crate) fn hyperelastic(
    prefix: &str,
    law: &str,
    young: f64,
    poisson: f64,
) -> Result<Arc<dyn Hyperelastic2d>, InputError> {
    Ok(match law {
        "linear" => Arc::new(
            LinearElastic::from_young_poisson(young, poisson).map_err(|e| e.within(prefix))?,
        ),
        "st_venant_kirchhoff" => Arc::new(
            StVenantKirchhoff::from_young_poisson(young, poisson).map_err(|e| e.within(prefix))?,
        ),
        "neo_hooke" => {
            Arc::new(NeoHooke::from_young_poisson(young, poisson).map_err(|e| e.within(prefix))?)
        }
        other => {
            return Err(InputError::new(
                format!("{prefix}.law"),
                format!("\"{other}\""),
                "\"linear\", \"st_venant_kirchhoff\" or \"neo_hooke\"",
            ))
        }
    })
}
