//! A bar in a dynamic scene: the 1D body, its wall contact and its initial state.

use std::sync::Arc;

use crate::error::{Error, InputError};
use crate::field::Field;
use crate::material::hyperelastic::{Hyperelastic1d, LinearElastic1d, StVenantKirchhoff1d};
use crate::mesh::interval::IntervalMesh;
use crate::model::dynamic::bar::{BarBody, BarData, BarSupports};
use crate::model::dynamic::contact_model::{BarEnd, ContactModel};
use crate::scene::common::missing;
use crate::scene::dynamic::body::{BodyParts, SceneBody};
use crate::scene::dynamic::contact::treatment;
use crate::scene::dynamic::format::{scalar, DynamicSceneFile};

/// The bar of the scene `file`: its mesh, material, supports, body force, wall contact and
/// initial state.
pub(super) fn bar(file: &DynamicSceneFile) -> Result<BodyParts, Error> {
    let b = &file.body;
    let m = &file.material;
    if m.poisson.is_some() {
        return Err(InputError::new(
            "material.poisson",
            "(given)",
            "no Poisson ratio for a bar (young only)",
        )
        .into());
    }
    let law: Arc<dyn Hyperelastic1d> = match m.law.as_str() {
        "linear" => Arc::new(LinearElastic1d { young: m.young }),
        "st_venant_kirchhoff" => Arc::new(StVenantKirchhoff1d { young: m.young }),
        other => {
            return Err(InputError::new(
                "material.law",
                format!("\"{other}\""),
                "\"linear\" or \"st_venant_kirchhoff\" for a bar",
            )
            .into())
        }
    };
    let supports = b.supports.clone().unwrap_or_default();
    let mesh = IntervalMesh::uniform(
        b.length
            .ok_or_else(|| missing("body.length", "a length > 0"))?,
        b.elements
            .ok_or_else(|| missing("body.elements", "a number of elements ≥ 1"))?,
    )?;
    let nodes = mesh.nodes().to_vec();
    let body_force = match &file.body_force {
        Some(s) => scalar("body_force.value", &Some(s.value.clone()))?,
        None => Field::Constant(0.0),
    };
    let body = Arc::new(BarBody::new(BarData {
        mesh,
        density: b.density,
        area: b.area.unwrap_or(1.0),
        law,
        supports: BarSupports {
            left: supports.contains(&BarEnd::Left),
            right: supports.contains(&BarEnd::Right),
        },
        mass: b.mass,
        body_force,
    })?);
    if !file.dirichlet.is_empty() || !file.traction.is_empty() {
        return Err(InputError::new(
            "dirichlet",
            "(given)",
            "body.supports for a bar (no [[dirichlet]] or [[traction]])",
        )
        .into());
    }
    let contact = match &file.contact {
        None => None,
        Some(c) => {
            if c.level.is_some() || !c.sides.is_empty() || c.where_.is_some() {
                return Err(InputError::new(
                    "contact.level",
                    "(given)",
                    "end and wall for a bar (level, sides, where are for plane bodies)",
                )
                .into());
            }
            if c.friction.is_some() {
                return Err(InputError::new(
                    "contact.friction",
                    "(given)",
                    "no friction for a bar (no tangential direction)",
                )
                .into());
            }
            Some(ContactModel::bar_wall(
                &body,
                c.end
                    .ok_or_else(|| missing("contact.end", "\"left\" or \"right\""))?,
                c.wall
                    .ok_or_else(|| missing("contact.wall", "the wall position x"))?,
                treatment(c)?,
            )?)
        }
    };
    let u0f = scalar("initial.displacement", &file.initial.displacement)?;
    let v0f = scalar("initial.velocity", &file.initial.velocity)?;
    let u0: Vec<f64> = nodes.iter().map(|&x| u0f.eval(x, 0.0, 0.0)).collect();
    let v0: Vec<f64> = nodes.iter().map(|&x| v0f.eval(x, 0.0, 0.0)).collect();
    let (u0, v0) = (body.from_nodal(&u0), body.from_nodal(&v0));
    Ok((SceneBody::Bar(body), contact, u0, v0))
}
