//! A plane body in a dynamic scene: the mesh of its shape, the body with its boundary parts,
//! its half-space contact and its initial state.

use std::sync::Arc;

use crate::error::{Error, InputError};
use crate::field::Field;
use crate::material::hyperelastic::Hyperelastic2d;
use crate::mesh::gmsh::GmshMesh;
use crate::mesh::triangle::TriangleMesh;
use crate::model::dynamic::contact_model::{ContactModel, NormalTreatment};
use crate::model::dynamic::plane_body::{BodyRegion, PlaneBody, PlaneBodyData};
use crate::model::quasistatic::plane::BoundarySelector;
use crate::scene::boundary::{
    dirichlet_parts, require_parts_selected, selector, traction_parts, Selection,
};
use crate::scene::common::missing;
use crate::scene::dynamic::body::{BodyParts, SceneBody};
use crate::scene::dynamic::contact::{friction, treatment};
use crate::scene::dynamic::format::{pair, BodySection, DynamicContactSection, DynamicSceneFile};
use crate::scene::hyperelastic_law::hyperelastic;
use crate::scene::plane_shape::plane_mesh;

/// The mesh of the plane shape `b.shape` (`rectangle`, `disk`, `annulus` or `gmsh`) from its
/// keys, and the Gmsh file it was read from (for its groups); `given` lists which keys of
/// `[body]` are present (a key of another shape is an error).
pub(super) fn mesh(
    b: &BodySection,
    given: &[(&str, bool)],
    base_dir: Option<&std::path::Path>,
) -> Result<(TriangleMesh, Option<GmshMesh>), Error> {
    plane_mesh(
        "body",
        &b.plane_shape(),
        given,
        base_dir,
        "\"bar\", \"rectangle\", \"disk\", \"annulus\" or \"gmsh\"",
    )
}

/// The boundary part a dynamic `[contact]` section selects, if it selects one.
fn contact_selection(c: &DynamicContactSection) -> Option<Selection<'_>> {
    (!c.sides.is_empty() || c.where_.is_some() || c.group.is_some()).then_some(Selection {
        sides: &c.sides,
        where_: c.where_.as_ref(),
        group: c.group.as_ref(),
    })
}

/// The regions of `[[region]]` (section i named `region[i]`) of a body read from `gmsh`, each key
/// left out taken from the body (`body.density`, `[material]`, whose law is `body_law`).
fn regions(
    file: &DynamicSceneFile,
    gmsh: Option<&GmshMesh>,
    body_law: &Arc<dyn Hyperelastic2d>,
) -> Result<Vec<BodyRegion>, Error> {
    let mut out = Vec::with_capacity(file.region.len());
    for (i, r) in file.region.iter().enumerate() {
        let prefix = format!("region[{i}]");
        let Some(gmsh) = gmsh else {
            return Err(InputError::new(
                format!("{prefix}.group"),
                format!("\"{}\"", r.group),
                "a body read from a Gmsh file (body.shape = \"gmsh\") to name its regions",
            )
            .into());
        };
        let triangles = gmsh.region(&format!("{prefix}.group"), &r.group)?.to_vec();
        let body = &file.material;
        let law = match &r.material {
            None => body_law.clone(),
            Some(m) => {
                let poisson = m.poisson.or(body.poisson).ok_or_else(|| {
                    missing(
                        format!("{prefix}.material.poisson"),
                        "a Poisson ratio in (−1, 1/2)",
                    )
                })?;
                hyperelastic(
                    &format!("{prefix}.material"),
                    m.law.as_deref().unwrap_or(&body.law),
                    m.young.unwrap_or(body.young),
                    poisson,
                )?
            }
        };
        out.push(BodyRegion {
            name: r.group.clone(),
            triangles,
            density: r.density.unwrap_or(file.body.density),
            law,
        });
    }
    Ok(out)
}

/// The plane body on `mesh` with the material, boundary parts, body force, contact and initial
/// state of the scene `file`.
pub(super) fn plane(
    file: &DynamicSceneFile,
    (mesh, gmsh): (TriangleMesh, Option<GmshMesh>),
) -> Result<BodyParts, Error> {
    let gmsh = gmsh.as_ref();
    let m = &file.material;
    let poisson = m
        .poisson
        .ok_or_else(|| missing("material.poisson", "a Poisson ratio in (−1, 1/2)"))?;
    let law = hyperelastic("material", &m.law, m.young, poisson)?;
    let regions = regions(file, gmsh, &law)?;
    let dirichlet = dirichlet_parts(&file.dirichlet, gmsh)?;
    let traction = traction_parts(&file.traction, gmsh)?;
    let contact_part = match file.contact.as_ref().and_then(contact_selection) {
        Some(s) => Some(selector("contact", s, gmsh)?),
        None => None,
    };
    require_parts_selected(&mesh, &dirichlet, &traction, contact_part.as_ref())?;
    let body_force = match &file.body_force {
        Some(s) => pair("body_force.value", &Some(s.value.clone()))?,
        None => [Field::Constant(0.0), Field::Constant(0.0)],
    };
    let nodes = mesh.nodes().to_vec();
    let body = Arc::new(PlaneBody::new(PlaneBodyData {
        mesh,
        density: file.body.density,
        law,
        dirichlet,
        traction,
        body_force,
        mass: file.body.mass,
        regions,
    })?);
    let contact = match &file.contact {
        None => None,
        Some(c) => {
            if c.end.is_some() || c.wall.is_some() {
                return Err(InputError::new(
                    "contact.end",
                    "(given)",
                    "level (and sides or where) for a plane body (end and wall are for bars)",
                )
                .into());
            }
            let boundary = match contact_selection(c) {
                None => BoundarySelector::Predicate(Arc::new(|_| true)),
                Some(s) => selector("contact", s, gmsh)?,
            };
            Some(ContactModel::plane_half_space(
                &body,
                &boundary,
                c.level
                    .ok_or_else(|| missing("contact.level", "the foundation level y"))?,
                treatment(c)?,
                friction(c)?,
            )?)
        }
    };
    let u0f = pair("initial.displacement", &file.initial.displacement)?;
    let v0f = pair("initial.velocity", &file.initial.velocity)?;
    let interleave = |f: &[Field; 2]| -> Vec<f64> {
        nodes
            .iter()
            .flat_map(|p| [f[0].eval(p[0], p[1], 0.0), f[1].eval(p[0], p[1], 0.0)])
            .collect()
    };
    let (u0, v0) = (
        body.from_nodal(&interleave(&u0f)),
        body.from_nodal(&interleave(&v0f)),
    );
    if let Some(c) = &contact {
        starts_outside(c, &nodes, &u0, file.contact.as_ref().and_then(|c| c.level))?;
    }
    Ok((SceneBody::Plane(body), contact, u0, v0))
}

/// The body at t = 0 (nodes moved by `initial.displacement`) may not start inside the foundation
/// {y ≤ level} deeper than the treatment admits: for `signorini` the round-off of the gap,
/// 8 ε max(|level|, |y|) + 1e-12 × the body's height (the tolerance of the multibody overlap
/// check); for `limited_penetration` the layer depth g; for the penalties (a prestressed start)
/// the body's height. A deeper start is a careless level or initial state; the solver would meet
/// it as a singular Jacobian or a force beyond the range of doubles at the first step.
fn starts_outside(
    c: &ContactModel,
    nodes: &[[f64; 2]],
    u0: &[f64],
    level: Option<f64>,
) -> Result<(), InputError> {
    let level = level.unwrap_or(0.0);
    let (lo, hi) = nodes
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p[1]), hi.max(p[1]))
        });
    let scale = level.abs().max(lo.abs()).max(hi.abs());
    let round_off = 8.0 * f64::EPSILON * scale + 1e-12 * (hi - lo);
    let allowed = match c.treatment {
        NormalTreatment::LimitedPenetration { depth, .. } => depth + round_off,
        NormalTreatment::Signorini => round_off,
        // A penalty start inside the foundation is a prestressed start (dynamic_performance
        // presses a ball 2 mm in); deeper than the body is tall, the body is not beside the
        // foundation at all.
        _ => (hi - lo) + round_off,
    };
    let deepest = c
        .nodes
        .iter()
        .map(|n| {
            (
                n,
                n.offset + n.sign * u0.get(n.normal_dof).copied().unwrap_or(0.0),
            )
        })
        .max_by(|a, b| a.1.total_cmp(&b.1));
    match deepest {
        Some((n, p)) if p > allowed || p.is_nan() => Err(InputError::new(
            "contact.level",
            level,
            format!(
                "a foundation {{y ≤ level}} the body does not start inside: node {} at y = {} \
                 (with initial.displacement) starts {p:.3e} below the level, more than the {:.1e} \
                 the treatment admits (lower contact.level or move the body)",
                n.node, nodes[n.node][1], allowed
            ),
        )),
        _ => Ok(()),
    }
}
