//! Gmsh meshes in: a `.msh` file (format 4.1 ASCII or binary, or 2.2 ASCII) read into a
//! [`TriangleMesh`] with its named physical groups.
//!
//! - **Elements.** 3-node triangles make the mesh; 2-node lines carry the boundary groups; points
//!   are ignored. Any other type is an error naming Gmsh's name of the type and the element
//!   (`element 12 (surface 1): element type 9 (6-node second order triangle) is not supported`).
//! - **Physical groups.** Of dimension 1: named boundary parts (sets of boundary edges); of
//!   dimension 2: named regions (sets of triangles). A group without a `$PhysicalNames` entry is
//!   named by its number (`"7"`). Gmsh saves only the elements of physical groups when a file
//!   has any: the surface must be in a 2D group, or the file has no triangles.
//! - **Checks** (each a [`MeshFileError`] naming the file and the element or node by its tag in
//!   the file): nodes in the plane z = 0 (|z| ≤ 10⁻¹² × the bounding-box diagonal); no unused
//!   node (an error, not a silent drop: an unused node is most often a sign of an unmerged or
//!   half-saved geometry); no duplicate nodes (distance ≤ 10⁻¹² × the bounding-box diagonal); no
//!   degenerate triangle (|area| ≤ 10⁻¹² h², h the longest triangle edge of the mesh, the same
//!   criterion as [`TriangleMesh::from_parts`]); clockwise triangles, which Gmsh writes for
//!   surfaces whose normal points to −z, are reoriented silently (the orientation carries no
//!   information in 2D); no edge shared by more than two triangles and no boundary node where more
//!   than two boundary edges meet (a non-manifold boundary has no outward normal); every line of
//!   a boundary group is a boundary edge of the triangles.
//! - **Sizes.** Files longer than [`raw::MAX_FILE_BYTES`] are refused before they are read;
//!   every count in a section header is checked against [`raw::MAX_COUNT`] and against the bytes
//!   left before anything is allocated for it. A corrupted file gives an error, never a panic.

mod build;
pub mod raw;
mod v22;
mod v41;

use std::collections::BTreeMap;
use std::path::Path;

use crate::error::{InputError, MeshFileError, MeshProblem};
use crate::mesh::triangle::TriangleMesh;

/// A mesh read from a Gmsh file, with its physical groups.
#[derive(Debug, Clone, PartialEq)]
pub struct GmshMesh {
    /// The mesh: nodes in file order (all used), triangles in file order, counter-clockwise.
    pub mesh: TriangleMesh,
    /// The boundary parts: group name → sorted indices into `mesh.boundary()`.
    pub boundary_groups: BTreeMap<String, Vec<usize>>,
    /// The regions: group name → sorted triangle indices.
    pub regions: BTreeMap<String, Vec<usize>>,
    /// The Gmsh tag of each node.
    pub node_tags: Vec<u64>,
    /// The Gmsh tag of each triangle.
    pub triangle_tags: Vec<u64>,
}

/// A similarity applied to the file's coordinates: x ↦ scale x + offset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    pub scale: f64,
    pub offset: [f64; 2],
}

impl Default for Placement {
    fn default() -> Self {
        Self {
            scale: 1.0,
            offset: [0.0, 0.0],
        }
    }
}

impl GmshMesh {
    /// Reads the file at `path`.
    pub fn read(path: &Path, placement: Placement) -> Result<Self, MeshFileError> {
        let file = path.display().to_string();
        let fail = |problem| MeshFileError {
            file: file.clone(),
            location: "file".into(),
            problem,
        };
        let len = std::fs::metadata(path)
            .map_err(|e| fail(MeshProblem::Io(e.to_string())))?
            .len();
        if len > raw::MAX_FILE_BYTES {
            return Err(fail(MeshProblem::TooLarge {
                what: "file length (bytes)".into(),
                count: len,
                limit: format!("the hard maximum {}", raw::MAX_FILE_BYTES),
            }));
        }
        let bytes = std::fs::read(path).map_err(|e| fail(MeshProblem::Io(e.to_string())))?;
        Self::parse(&bytes, &file, placement)
    }

    /// Reads a file's bytes; `file` labels errors.
    pub fn parse(bytes: &[u8], file: &str, placement: Placement) -> Result<Self, MeshFileError> {
        let located = |(location, problem): (String, MeshProblem)| MeshFileError {
            file: file.to_string(),
            location,
            problem,
        };
        if bytes.len() as u64 > raw::MAX_FILE_BYTES {
            return Err(located((
                "file".into(),
                MeshProblem::TooLarge {
                    what: "file length (bytes)".into(),
                    count: bytes.len() as u64,
                    limit: format!("the hard maximum {}", raw::MAX_FILE_BYTES),
                },
            )));
        }
        let raw = read_raw(bytes).map_err(located)?;
        build::build(raw, placement).map_err(located)
    }

    /// The boundary edges of group `name`, or an error for `field` listing the file's groups.
    pub fn boundary_group(&self, field: &str, name: &str) -> Result<&[usize], InputError> {
        self.boundary_groups
            .get(name)
            .map(Vec::as_slice)
            .ok_or_else(|| unknown(field, name, "boundary", &self.boundary_groups))
    }

    /// The triangles of region `name`, or an error for `field` listing the file's regions.
    pub fn region(&self, field: &str, name: &str) -> Result<&[usize], InputError> {
        self.regions
            .get(name)
            .map(Vec::as_slice)
            .ok_or_else(|| unknown(field, name, "region (2D)", &self.regions))
    }
}

fn unknown(
    field: &str,
    name: &str,
    what: &str,
    groups: &BTreeMap<String, Vec<usize>>,
) -> InputError {
    let list: Vec<String> = groups.keys().map(|k| format!("\"{k}\"")).collect();
    InputError::new(
        field,
        format!("\"{name}\""),
        if list.is_empty() {
            format!("a {what} physical group of the mesh file (it has none)")
        } else {
            format!(
                "a {what} physical group of the mesh file: {}",
                list.join(", ")
            )
        },
    )
}

/// The raw content of a file of any supported format, after the `$MeshFormat` header check:
/// version 4.1 (ASCII or binary) or 2.2 (ASCII), data size 8.
fn read_raw(bytes: &[u8]) -> Result<raw::RawMesh, raw::Located> {
    let head = b"$MeshFormat";
    let start = raw::find(&bytes[..bytes.len().min(4096)], head)
        .ok_or_else(|| raw::syntax(0, "no $MeshFormat header at the start".into()))?;
    let after = &bytes[start + head.len()..];
    let ws = after.iter().take_while(|b| b.is_ascii_whitespace()).count();
    let len = after[ws..]
        .iter()
        .position(|&b| b == b'\n')
        .ok_or_else(|| raw::syntax(start, "truncated $MeshFormat header".into()))?;
    let line = std::str::from_utf8(&after[ws..ws + len])
        .map_err(|_| raw::syntax(start, "$MeshFormat header is not text".into()))?;
    let next = ws + len + 1;
    let words: Vec<&str> = line.split_ascii_whitespace().collect();
    let [version, file_type, data_size] = words[..] else {
        return Err(raw::syntax(
            start,
            format!("$MeshFormat: expected `version file-type data-size`, found `{line}`"),
        ));
    };
    if data_size != "8" {
        return Err(raw::syntax(
            start,
            format!("$MeshFormat: data size {data_size} (Gmsh writes 8)"),
        ));
    }
    match (version, file_type) {
        ("4.1", "0") => v41::read(bytes, None),
        ("4.1", "1") => {
            let one = after
                .get(next..next + 4)
                .and_then(|b| <[u8; 4]>::try_from(b).ok())
                .ok_or_else(|| raw::syntax(start, "truncated binary header".into()))?;
            let little = if i32::from_le_bytes(one) == 1 {
                true
            } else if i32::from_be_bytes(one) == 1 {
                false
            } else {
                return Err(raw::syntax(
                    start,
                    "binary header without the integer 1".into(),
                ));
            };
            v41::read(bytes, Some(little))
        }
        ("2.2", "0") => v22::read(bytes),
        (v, t) => Err((
            "file".into(),
            MeshProblem::UnsupportedFormat(format!(
                "{v} {}",
                if t == "1" { "binary" } else { "ASCII" }
            )),
        )),
    }
}

#[cfg(test)]
mod tests;
