//! The shape of a plane body as a scene writes it — `shape = "rectangle" | "disk" | "annulus" |
//! "gmsh"` with that shape's keys — turned into its mesh, and its node count estimated from the
//! keys alone (before anything is allocated). Shared by the dynamic scene's `[body]` and the
//! multibody scene's `[[body]]` sections; errors name the keys under the section's prefix as
//! written (`body.radius`, `body[1].divisions`).

use crate::error::{Error, InputError};
use crate::mesh::generators::{annulus, disk};
use crate::mesh::gmsh::GmshMesh;
use crate::mesh::triangle::{Diagonal, Grading, TriangleMesh};
use crate::scene::common::{mesh_field_as_written, missing, reject_keys};
use crate::scene::plane::read_gmsh;

/// The shape keys of a plane body section (borrowed from the section that holds them).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlaneShape<'a> {
    pub shape: &'a str,
    pub origin: Option<[f64; 2]>,
    pub size: Option<[f64; 2]>,
    pub divisions: Option<[usize; 2]>,
    pub diagonal: Option<Diagonal>,
    pub center: Option<[f64; 2]>,
    pub radius: Option<f64>,
    pub rings: Option<usize>,
    pub inner: Option<f64>,
    pub outer: Option<f64>,
    pub radial: Option<usize>,
    pub around: Option<usize>,
    pub file: Option<&'a String>,
    pub scale: Option<f64>,
    pub offset: Option<[f64; 2]>,
}

impl PlaneShape<'_> {
    /// Which shape keys are present (name, present), for [`reject_keys`].
    pub fn given(&self) -> Vec<(&'static str, bool)> {
        vec![
            ("origin", self.origin.is_some()),
            ("size", self.size.is_some()),
            ("divisions", self.divisions.is_some()),
            ("diagonal", self.diagonal.is_some()),
            ("center", self.center.is_some()),
            ("radius", self.radius.is_some()),
            ("rings", self.rings.is_some()),
            ("inner", self.inner.is_some()),
            ("outer", self.outer.is_some()),
            ("radial", self.radial.is_some()),
            ("around", self.around.is_some()),
            ("file", self.file.is_some()),
            ("scale", self.scale.is_some()),
            ("offset", self.offset.is_some()),
        ]
    }

    /// The node count of the generated shapes from their keys alone, with the key that sets it
    /// (`{prefix}.divisions`) and its value as written: rectangle (n_x + 1)(n_y + 1), disk at most
    /// 4 (rings + 1)², annulus (radial + 1) × around. `None` for a Gmsh body (its count is known
    /// once the file is read) and an unknown shape.
    pub fn node_estimate(&self, prefix: &str) -> Option<(String, String, f64)> {
        let f = |v: Option<usize>| v.map_or(0.0, |n| n as f64);
        let s = |v: Option<usize>| v.unwrap_or_default().to_string();
        Some(match self.shape {
            "rectangle" => {
                let d = self.divisions.unwrap_or_default();
                let [nx, ny] = d.map(|v| v as f64);
                (
                    format!("{prefix}.divisions"),
                    format!("[{}, {}]", d[0], d[1]),
                    (nx + 1.0) * (ny + 1.0),
                )
            }
            "disk" => (
                format!("{prefix}.rings"),
                s(self.rings),
                4.0 * (f(self.rings) + 1.0).powi(2),
            ),
            "annulus" => (
                format!("{prefix}.radial"),
                format!("{} (around = {})", s(self.radial), s(self.around)),
                (f(self.radial) + 1.0) * f(self.around),
            ),
            _ => return None,
        })
    }
}

/// The mesh of the plane shape `s.shape` (`rectangle`, `disk`, `annulus` or `gmsh`) from its
/// keys, and the Gmsh file it was read from (for its groups). `given` lists which keys of the
/// section are present (a key of another shape is an error named `{prefix}.{key}`); a Gmsh
/// `file` is relative to `base_dir`; `shapes` is what an unknown shape's error expects.
pub(crate) fn plane_mesh(
    prefix: &str,
    s: &PlaneShape,
    given: &[(&str, bool)],
    base_dir: Option<&std::path::Path>,
    shapes: &str,
) -> Result<(TriangleMesh, Option<GmshMesh>), Error> {
    let need = |key: &str| format!("{prefix}.{key}");
    if s.shape == "gmsh" {
        reject_keys(
            prefix,
            ("shape", "gmsh"),
            given,
            &["file", "scale", "offset"],
        )?;
        let gmsh = read_gmsh(prefix, s.file, s.scale, s.offset, base_dir)?;
        return Ok((gmsh.mesh.clone(), Some(gmsh)));
    }
    let mesh = match s.shape {
        "rectangle" => {
            reject_keys(
                prefix,
                ("shape", "rectangle"),
                given,
                &["origin", "size", "divisions", "diagonal"],
            )?;
            TriangleMesh::graded_rectangle(
                s.origin.unwrap_or([0.0, 0.0]),
                s.size
                    .ok_or_else(|| missing(need("size"), "[width, height]"))?,
                s.divisions
                    .ok_or_else(|| missing(need("divisions"), "[n_x, n_y]"))?,
                s.diagonal.unwrap_or_default(),
                [Grading::UNIFORM; 2],
            )
            .map_err(mesh_field_as_written(prefix))?
        }
        "disk" => {
            reject_keys(
                prefix,
                ("shape", "disk"),
                given,
                &["center", "radius", "rings"],
            )?;
            disk(
                s.center.ok_or_else(|| missing(need("center"), "[x, y]"))?,
                s.radius
                    .ok_or_else(|| missing(need("radius"), "a radius > 0"))?,
                s.rings
                    .ok_or_else(|| missing(need("rings"), "a number of rings ≥ 1"))?,
            )
            .map_err(mesh_field_as_written(prefix))?
        }
        "annulus" => {
            reject_keys(
                prefix,
                ("shape", "annulus"),
                given,
                &["center", "inner", "outer", "radial", "around"],
            )?;
            annulus(
                s.center.ok_or_else(|| missing(need("center"), "[x, y]"))?,
                s.inner
                    .ok_or_else(|| missing(need("inner"), "a radius > 0"))?,
                s.outer
                    .ok_or_else(|| missing(need("outer"), "a radius > inner"))?,
                s.radial
                    .ok_or_else(|| missing(need("radial"), "layers ≥ 1"))?,
                s.around
                    .ok_or_else(|| missing(need("around"), "cells around ≥ 3"))?,
            )
            .map_err(mesh_field_as_written(prefix))?
        }
        other => return Err(InputError::new(need("shape"), format!("\"{other}\""), shapes).into()),
    };
    Ok((mesh, None))
}
