//! The boundary parts of a plane body's scene, shared by the plane and the dynamic scenes:
//! `[[dirichlet]]` and `[[traction]]` sections, each selecting its edges by side, by a `where`
//! expression or by a boundary `group` of the body's Gmsh file (exactly one of the three), and
//! vectors of two numbers or expressions.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::error::InputError;
use crate::field::{Expression, Field};
use crate::mesh::gmsh::GmshMesh;
use crate::mesh::triangle::{RectangleSide, TriangleMesh};
use crate::model::quasistatic::plane::{BoundarySelector, DirichletPart, Support, TractionPart};
use crate::scene::common::missing;
use crate::scene::field_spec::FieldSpec;

/// `[[dirichlet]]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DirichletSection {
    /// The sides of the rectangle this part holds; either this or `where`.
    #[serde(default)]
    pub sides: Vec<RectangleSide>,
    /// Instead of `sides`: an expression of x, y selecting the boundary edges whose midpoint makes
    /// it positive (e.g. `"1e-9 - x"` for the edges on x = 0).
    #[serde(rename = "where")]
    pub where_: Option<String>,
    /// Instead of `sides` or `where`: a boundary physical group (dimension 1) of the body's Gmsh
    /// file (`shape = "gmsh"`), by name.
    pub group: Option<String>,
    /// Which displacement components the part holds at zero (u = 0 on Γ1: (2.3) quasistatic,
    /// (1.16) dynamic).
    pub support: Support,
}

/// `[[traction]]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionSection {
    /// The sides of the rectangle this part loads; either this or `where`.
    #[serde(default)]
    pub sides: Vec<RectangleSide>,
    /// Instead of `sides`: an expression of x, y that is positive at the midpoints of the part's
    /// edges.
    #[serde(rename = "where")]
    pub where_: Option<String>,
    /// A boundary group of the body's Gmsh file (as in `[[dirichlet]]`).
    pub group: Option<String>,
    /// The traction f2 on the part, [x, y]: numbers or expressions of x, y, t (σν = f2, (2.4)
    /// quasistatic; Πν = f2, (1.17) dynamic).
    #[serde(deserialize_with = "super::fixed_array::exact")]
    pub value: [FieldSpec; 2],
}

/// How a section selects its boundary part: exactly one of `sides`, `where`, `group`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Selection<'a> {
    pub sides: &'a [RectangleSide],
    pub where_: Option<&'a String>,
    pub group: Option<&'a String>,
}

/// The boundary part of a section: its sides, the edges whose midpoint makes `where` positive,
/// or the edges of a boundary group of `gmsh` (the body's mesh file, if it has one).
pub(crate) fn selector(
    prefix: &str,
    s: Selection,
    gmsh: Option<&GmshMesh>,
) -> Result<BoundarySelector, InputError> {
    if let Some(name) = s.group {
        if !s.sides.is_empty() || s.where_.is_some() {
            return Err(InputError::new(
                format!("{prefix}.group"),
                "(given with sides or where)",
                "exactly one of sides, where and group",
            ));
        }
        let Some(gmsh) = gmsh else {
            return Err(InputError::new(
                format!("{prefix}.group"),
                format!("\"{name}\""),
                "a body read from a Gmsh file (shape = \"gmsh\") to name its groups",
            ));
        };
        let edges = gmsh.boundary_group(&format!("{prefix}.group"), name)?;
        return Ok(BoundarySelector::Edges {
            group: name.clone(),
            edges: Arc::new(edges.to_vec()),
        });
    }
    let (sides, where_) = (s.sides, s.where_);
    match (sides.is_empty(), where_) {
        (false, None) => Ok(BoundarySelector::Sides(sides.to_vec())),
        (true, Some(text)) => {
            let e = Expression::parse(&format!("{prefix}.where"), text)?;
            Ok(BoundarySelector::Predicate(Arc::new(move |p: [f64; 2]| {
                e.eval(p[0], p[1], 0.0) > 0.0
            })))
        }
        (false, Some(_)) => Err(InputError::new(
            format!("{prefix}.where"),
            "(given with sides)",
            "either sides or where",
        )),
        (true, None) => Err(missing(
            format!("{prefix}.sides"),
            "sides = [...], where = \"expression of x, y\" or group = \"name\"",
        )),
    }
}

/// The two fields of the vector `v`, its components named `{prefix}[0]` and `{prefix}[1]`.
pub(crate) fn vector(prefix: &str, v: &[FieldSpec; 2]) -> Result<[Field; 2], InputError> {
    Ok([
        v[0].to_field(&format!("{prefix}[0]"))?,
        v[1].to_field(&format!("{prefix}[1]"))?,
    ])
}

/// The Dirichlet parts of the `[[dirichlet]]` sections, section i named `dirichlet[i]`.
pub(crate) fn dirichlet_parts(
    sections: &[DirichletSection],
    gmsh: Option<&GmshMesh>,
) -> Result<Vec<DirichletPart>, InputError> {
    dirichlet_parts_at("", sections, gmsh)
}

/// [`dirichlet_parts`] of sections nested in another (`[[body.dirichlet]]`): section i named
/// `{prefix}dirichlet[i]` (`prefix` = `body[1].`).
pub(crate) fn dirichlet_parts_at(
    prefix: &str,
    sections: &[DirichletSection],
    gmsh: Option<&GmshMesh>,
) -> Result<Vec<DirichletPart>, InputError> {
    sections
        .iter()
        .enumerate()
        .map(|(i, d)| {
            Ok(DirichletPart {
                boundary: selector(
                    &format!("{prefix}dirichlet[{i}]"),
                    Selection {
                        sides: &d.sides,
                        where_: d.where_.as_ref(),
                        group: d.group.as_ref(),
                    },
                    gmsh,
                )?,
                support: d.support,
            })
        })
        .collect()
}

/// Every part selects at least one boundary edge of `mesh`: a selector that selects nothing (the
/// sides of a rectangle on a disk, a `where` negative everywhere) would clamp, load or support
/// nothing, silently. `parts` are (the section's name, its selector).
fn require_selected<'a>(
    mesh: &TriangleMesh,
    parts: impl IntoIterator<Item = (String, &'a BoundarySelector)>,
) -> Result<(), InputError> {
    for (name, sel) in parts {
        if !(0..mesh.boundary().len()).any(|e| sel.contains(mesh, e)) {
            let (key, written) = match sel {
                BoundarySelector::Sides(s) => (
                    "sides",
                    format!(
                        "[{}]",
                        s.iter()
                            .map(|x| format!("\"{}\"", format!("{x:?}").to_lowercase()))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ),
                BoundarySelector::Predicate(_) => ("where", "(the expression)".to_string()),
                BoundarySelector::Edges { group, .. } => ("group", format!("\"{group}\"")),
            };
            return Err(InputError::new(
                format!("{name}.{key}"),
                written,
                format!(
                    "a selection of at least one of the body's {} boundary edges (it selects none)",
                    mesh.boundary().len()
                ),
            ));
        }
    }
    Ok(())
}

/// [`require_selected`] for the Dirichlet and traction parts (named `dirichlet[i]`,
/// `traction[i]`) and a contact part.
pub(crate) fn require_parts_selected(
    mesh: &TriangleMesh,
    dirichlet: &[DirichletPart],
    traction: &[TractionPart],
    contact: Option<&BoundarySelector>,
) -> Result<(), InputError> {
    require_parts_selected_at("", mesh, dirichlet, traction)?;
    require_selected(mesh, contact.map(|c| ("contact".to_string(), c)))
}

/// [`require_selected`] for the Dirichlet and traction parts of a nested section (named
/// `{prefix}dirichlet[i]`, `{prefix}traction[i]`).
pub(crate) fn require_parts_selected_at(
    prefix: &str,
    mesh: &TriangleMesh,
    dirichlet: &[DirichletPart],
    traction: &[TractionPart],
) -> Result<(), InputError> {
    require_selected(
        mesh,
        dirichlet
            .iter()
            .enumerate()
            .map(|(i, d)| (format!("{prefix}dirichlet[{i}]"), &d.boundary))
            .chain(
                traction
                    .iter()
                    .enumerate()
                    .map(|(i, t)| (format!("{prefix}traction[{i}]"), &t.boundary)),
            ),
    )
}

/// [`require_selected`] for one part, named `name` (`contact_pair[0].slave`).
pub(crate) fn require_part_selected(
    mesh: &TriangleMesh,
    name: &str,
    part: &BoundarySelector,
) -> Result<(), InputError> {
    require_selected(mesh, [(name.to_string(), part)])
}

/// The traction parts of the `[[traction]]` sections, section i named `traction[i]`.
pub(crate) fn traction_parts(
    sections: &[TractionSection],
    gmsh: Option<&GmshMesh>,
) -> Result<Vec<TractionPart>, InputError> {
    traction_parts_at("", sections, gmsh)
}

/// [`traction_parts`] of sections nested in another (`[[body.traction]]`): section i named
/// `{prefix}traction[i]` (`prefix` = `body[1].`).
pub(crate) fn traction_parts_at(
    prefix: &str,
    sections: &[TractionSection],
    gmsh: Option<&GmshMesh>,
) -> Result<Vec<TractionPart>, InputError> {
    sections
        .iter()
        .enumerate()
        .map(|(i, t)| {
            Ok(TractionPart {
                boundary: selector(
                    &format!("{prefix}traction[{i}]"),
                    Selection {
                        sides: &t.sides,
                        where_: t.where_.as_ref(),
                        group: t.group.as_ref(),
                    },
                    gmsh,
                )?,
                traction: vector(&format!("{prefix}traction[{i}].value"), &t.value)?,
            })
        })
        .collect()
}
