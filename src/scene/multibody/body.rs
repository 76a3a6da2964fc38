//! One `[[body]]` of a multibody scene: its name, its mesh (the shapes of the dynamic scene's
//! `[body]`, Gmsh files included), its plane-strain body (material, density, mass, supports,
//! tractions, body force) and its initial rigid velocity. Errors name the keys as written,
//! `body[1].material.poisson`.

use std::sync::Arc;

use crate::error::{require_finite, require_positive, Error, InputError};
use crate::mesh::gmsh::GmshMesh;
use crate::mesh::triangle::TriangleMesh;
use crate::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};
use crate::model::multibody::bodies::BodySet;
use crate::scene::boundary::{
    dirichlet_parts_at, require_parts_selected_at, traction_parts_at, vector,
};
use crate::scene::hyperelastic_law::hyperelastic;
use crate::scene::multibody::format::MultibodyBodySection;
use crate::scene::plane_shape::plane_mesh;

/// The shapes a `[[body]]` may have (a bar is one-dimensional: a one-body `[body]` scene).
const SHAPES: &str = "\"rectangle\", \"disk\", \"annulus\" or \"gmsh\" (a bar is a one-body \
                      scene: a [body] section with shape = \"bar\")";

/// The names of the bodies: each `name` as written, else `"body i"`; unique and not empty
/// (`body[i].name` named in the error).
pub(super) fn names(bodies: &[MultibodyBodySection]) -> Result<Vec<String>, InputError> {
    let mut out: Vec<String> = Vec::with_capacity(bodies.len());
    for (i, b) in bodies.iter().enumerate() {
        let name = b.name.clone().unwrap_or_else(|| format!("body {i}"));
        if name.trim().is_empty() {
            return Err(InputError::new(
                format!("body[{i}].name"),
                format!("\"{name}\""),
                "a name that is not blank",
            ));
        }
        if let Some(j) = out.iter().position(|n| *n == name) {
            return Err(InputError::new(
                format!("body[{i}].name"),
                format!("\"{name}\""),
                format!("a name no other body has (body[{j}] is \"{name}\" already)"),
            ));
        }
        out.push(name);
    }
    Ok(out)
}

/// The mesh of body `i` (and the Gmsh file it was read from, for its groups); a Gmsh `file` is
/// relative to `base_dir`.
pub(super) fn mesh(
    i: usize,
    b: &MultibodyBodySection,
    base_dir: Option<&std::path::Path>,
) -> Result<(TriangleMesh, Option<GmshMesh>), Error> {
    let shape = b.plane_shape();
    plane_mesh(
        &format!("body[{i}]"),
        &shape,
        &shape.given(),
        base_dir,
        SHAPES,
    )
}

/// The plane-strain body `i` on `mesh`, with the section's material, density, mass, supports,
/// tractions and body force.
pub(super) fn plane_body(
    i: usize,
    b: &MultibodyBodySection,
    (mesh, gmsh): (TriangleMesh, Option<&GmshMesh>),
) -> Result<Arc<PlaneBody>, Error> {
    let prefix = format!("body[{i}]");
    require_positive(&format!("{prefix}.density"), b.density)?;
    let m = &b.material;
    let law = hyperelastic(&format!("{prefix}.material"), &m.law, m.young, m.poisson)?;
    let dirichlet = dirichlet_parts_at(&format!("{prefix}."), &b.dirichlet, gmsh)?;
    let traction = traction_parts_at(&format!("{prefix}."), &b.traction, gmsh)?;
    require_parts_selected_at(&format!("{prefix}."), &mesh, &dirichlet, &traction)?;
    let body_force = vector(&format!("{prefix}.body_force"), &b.body_force)?;
    let body = PlaneBody::new(PlaneBodyData {
        mesh,
        density: b.density,
        law,
        dirichlet,
        traction,
        body_force,
        mass: b.mass,
        regions: Vec::new(),
    })
    .map_err(|mut e| {
        // the body's own checks name `body.…` (the one-body scene's section) or `mesh.…`
        if let Some(rest) = e.field.strip_prefix("body.") {
            e.field = format!("{prefix}.{rest}");
        } else if e.field.starts_with("mesh.") {
            e.field = format!("{prefix}.{}", e.field);
        }
        e
    })?;
    Ok(Arc::new(body))
}

/// The initial velocity of the system: each body's rigid motion v(X) = v + ω e_z × (X − c), c the
/// body's `spin_center` or its centre of mass (held components get none).
pub(super) fn initial_velocity(
    sections: &[MultibodyBodySection],
    bodies: &BodySet,
) -> Result<Vec<f64>, InputError> {
    let mut v = vec![0.0; bodies.dofs()];
    for (i, b) in sections.iter().enumerate() {
        for (c, x) in b.velocity.iter().enumerate() {
            require_finite(&format!("body[{i}].velocity[{c}]"), *x)?;
        }
        require_finite(&format!("body[{i}].angular_velocity"), b.angular_velocity)?;
        let center = match b.spin_center {
            Some(c) => {
                for (k, x) in c.iter().enumerate() {
                    require_finite(&format!("body[{i}].spin_center[{k}]"), *x)?;
                }
                c
            }
            None => bodies.centre_of_mass(i),
        };
        bodies.rigid_velocity(i, b.velocity, b.angular_velocity, center, &mut v);
    }
    Ok(v)
}
