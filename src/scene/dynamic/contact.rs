//! The contact of a dynamic scene: the normal treatment and the friction coefficient of
//! `[contact]`.

use crate::contact::friction::FrictionCoefficient;
use crate::error::InputError;
use crate::model::dynamic::contact_model::NormalTreatment;
use crate::scene::common::missing;
use crate::scene::dynamic::format::DynamicContactSection;

/// The normal treatment of `[contact]`, with the keys it needs.
pub(super) fn treatment(c: &DynamicContactSection) -> Result<NormalTreatment, InputError> {
    let r = || {
        c.stiffness
            .ok_or_else(|| missing("contact.stiffness", "the penalty stiffness r > 0"))
    };
    let t = match c.treatment.as_str() {
        "penalty" => NormalTreatment::Penalty { stiffness: r()? },
        "energy_consistent" | "hauret_le_tallec" => {
            NormalTreatment::EnergyConsistent { stiffness: r()? }
        }
        "hauret_le_tallec_tilted" => NormalTreatment::HauretLeTallecTilted { stiffness: r()? },
        "limited_penetration" => NormalTreatment::LimitedPenetration {
            stiffness: r()?,
            depth: c
                .depth
                .ok_or_else(|| missing("contact.depth", "the depth g > 0 of the asperity layer"))?,
        },
        "signorini" => {
            if c.stiffness.is_some() {
                return Err(InputError::new(
                    "contact.stiffness",
                    "(given)",
                    "no stiffness for treatment = \"signorini\" (exact non-penetration)",
                ));
            }
            NormalTreatment::Signorini
        }
        other => {
            return Err(InputError::new(
                "contact.treatment",
                format!("\"{other}\""),
                "\"penalty\", \"energy_consistent\", \"hauret_le_tallec\", \
                 \"hauret_le_tallec_tilted\", \"limited_penetration\" or \"signorini\"",
            ))
        }
    };
    t.validate("contact")?;
    Ok(t)
}

/// The friction coefficient of `[contact.friction]` (none without that section).
pub(super) fn friction(
    c: &DynamicContactSection,
) -> Result<Option<FrictionCoefficient>, InputError> {
    let Some(f) = &c.friction else {
        return Ok(None);
    };
    let depth = || {
        f.depth.or(c.depth).ok_or_else(|| {
            missing(
                "contact.friction.depth",
                "the depth g of (1.13) (or contact.depth)",
            )
        })
    };
    let coef = match f.law.as_str() {
        "constant" => FrictionCoefficient::Constant { mu0: f.mu0 },
        "growing" | "mu1" => FrictionCoefficient::Growing {
            mu0: f.mu0,
            depth: depth()?,
        },
        "decreasing" | "mu2" => FrictionCoefficient::Decreasing {
            mu0: f.mu0,
            depth: depth()?,
        },
        other => {
            return Err(InputError::new(
                "contact.friction.law",
                format!("\"{other}\""),
                "\"constant\", \"growing\" (μ1) or \"decreasing\" (μ2)",
            ))
        }
    };
    coef.validate("contact.friction")?;
    Ok(Some(coef))
}
