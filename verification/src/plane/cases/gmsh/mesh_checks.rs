//! Part 4 of `plane_gmsh`: the mesh checks as extremes. For each defect named in
//! `[mesh_checks] defects` the case writes a small crafted file into its report directory
//! (`meshes/<defect>.msh`; a 2.2 ASCII file of a few nodes, or a damaged copy of a committed 4.1
//! or 2.2 file), reads it with the reader a scene uses, and requires the typed error of that
//! defect with the element or node named by its tag in the file. A control file (the same
//! crafted square without a defect) must read. The gate counts the defects refused as expected:
//! all of them.

use std::path::Path;

use serde::Deserialize;

use contactlab::error::{MeshFileError, MeshProblem};
use contactlab::mesh::gmsh::{GmshMesh, Placement};

use crate::core::context::RunContext;
use crate::core::format::{invalid, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::plane::cases::gmsh::files::repository_root;

/// A defect of a crafted file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Defect {
    /// Three collinear nodes.
    DegenerateTriangle,
    /// Two nodes at one position.
    DuplicateNode,
    /// A node no triangle uses.
    UnusedNode,
    /// A line of a boundary group across the interior.
    GroupOffBoundary,
    /// An edge shared by three triangles.
    NonManifoldEdge,
    /// Two triangles touching at one node (four boundary edges meet there).
    NonManifoldNode,
    /// A 6-node triangle in a 2.2 file.
    UnsupportedElement,
    /// The 4.1 ASCII unit square with its triangle block declared as 3-node lines (type 8).
    UnsupportedElement41,
    /// The files of `truncate` cut at half their length: a syntax error at a byte offset, or a
    /// section count the bytes left cannot hold.
    TruncatedFile,
}

/// `[mesh_checks]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshChecksSpec {
    pub defects: Vec<Defect>,
    /// The committed files truncated by `truncated_file` (relative to the repository root); the
    /// first is also the base of `unsupported_element_41` (a 4.1 ASCII file with a block
    /// `2 1 2 <count>`: surface 1, 3-node triangles).
    pub truncate: Vec<String>,
}

impl MeshChecksSpec {
    /// At least one defect, no repeats, and files to truncate.
    pub fn check(&self, path: &Path) -> Result<(), CaseError> {
        if self.defects.is_empty() {
            return Err(invalid(path, "mesh_checks.defects", "[]", "one or more"));
        }
        for (i, d) in self.defects.iter().enumerate() {
            if self.defects[..i].contains(d) {
                return Err(invalid(
                    path,
                    &format!("mesh_checks.defects[{i}]"),
                    format!("{d:?}"),
                    "each defect once",
                ));
            }
        }
        if self.truncate.is_empty() {
            return Err(invalid(path, "mesh_checks.truncate", "[]", "one or more"));
        }
        Ok(())
    }
}

/// A 2.2 file of the given node and element lines, with the physical names "base" (dim 1, tag
/// 1) and "body" (dim 2, tag 2).
fn file22(nodes: &[&str], elements: &[&str]) -> Vec<u8> {
    format!(
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"base\"\n2 2 \"body\"\n\
         $EndPhysicalNames\n$Nodes\n{}\n{}\n$EndNodes\n$Elements\n{}\n{}\n$EndElements\n",
        nodes.len(),
        nodes.join("\n"),
        elements.len(),
        elements.join("\n")
    )
    .into_bytes()
}

/// The square (0, 1)² as nodes 1–4.
const SQUARE: [&str; 4] = ["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 0 1 0"];

/// Two triangles of the square and its bottom edge in the group "base".
const SQUARE_ELEMENTS: [&str; 3] = ["1 2 2 2 1 1 2 3", "2 2 2 2 1 1 3 4", "3 1 2 1 5 1 2"];

/// What a crafted file must give: the location and a test of the problem.
struct Expected {
    location: String,
    problem: fn(&MeshProblem) -> bool,
    describe: &'static str,
}

/// The crafted files of a defect: (name, bytes, expected error).
fn crafted(d: Defect, truncate: &[String]) -> Result<Vec<(String, Vec<u8>, Expected)>, String> {
    let one = |name: &str, bytes: Vec<u8>, location: &str, problem, describe| {
        Ok(vec![(
            name.to_string(),
            bytes,
            Expected {
                location: location.to_string(),
                problem,
                describe,
            },
        )])
    };
    let read = |file: &String| {
        std::fs::read(repository_root().join(file)).map_err(|e| format!("{file}: {e}"))
    };
    match d {
        Defect::DegenerateTriangle => one(
            "degenerate_triangle",
            file22(
                &["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 2 0 0"],
                &["1 2 2 2 1 1 2 3", "7 2 2 2 1 1 2 4"],
            ),
            "element 7 (surface 1)",
            |p| {
                matches!(
                    p,
                    MeshProblem::DegenerateTriangle {
                        nodes: [1, 2, 4],
                        ..
                    }
                )
            },
            "DegenerateTriangle, nodes [1, 2, 4]",
        ),
        Defect::DuplicateNode => one(
            "duplicate_node",
            file22(
                &["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 0 1 0", "5 1 1 0"],
                &["1 2 2 2 1 1 2 3", "2 2 2 2 1 1 5 4"],
            ),
            "node 5",
            |p| {
                matches!(
                    p,
                    MeshProblem::DuplicateNode {
                        node: 5,
                        other: 3,
                        ..
                    }
                )
            },
            "DuplicateNode 5 of 3",
        ),
        Defect::UnusedNode => one(
            "unused_node",
            file22(
                &["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 0 1 0", "6 5 5 0"],
                &["1 2 2 2 1 1 2 3", "2 2 2 2 1 1 3 4"],
            ),
            "node 6",
            |p| matches!(p, MeshProblem::UnusedNodes { count: 1, first } if first == &[6]),
            "UnusedNodes [6]",
        ),
        Defect::GroupOffBoundary => one(
            "group_off_boundary",
            file22(
                &SQUARE,
                &["1 2 2 2 1 1 2 3", "2 2 2 2 1 1 3 4", "3 1 2 1 5 1 3"],
            ),
            "element 3 (curve 5)",
            |p| matches!(p, MeshProblem::NotOnBoundary { group, nodes: [1, 3] } if group == "base"),
            "NotOnBoundary, group \"base\", nodes [1, 3]",
        ),
        Defect::NonManifoldEdge => one(
            "non_manifold_edge",
            file22(
                &["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 0 1 0", "5 2 0 0"],
                &["1 2 2 2 1 1 2 3", "2 2 2 2 1 1 3 4", "3 2 2 2 1 1 5 3"],
            ),
            "element 3 (surface 1)",
            |p| matches!(p, MeshProblem::NonManifoldEdge { triangles: 3, .. }),
            "NonManifoldEdge, 3 triangles",
        ),
        Defect::NonManifoldNode => one(
            "non_manifold_node",
            file22(
                &["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 2 1 0", "5 2 2 0"],
                &["1 2 2 2 1 1 2 3", "2 2 2 2 1 3 4 5"],
            ),
            "node 3",
            |p| matches!(p, MeshProblem::NonManifoldNode { edges: 4 }),
            "NonManifoldNode, 4 edges",
        ),
        Defect::UnsupportedElement => one(
            "unsupported_element",
            file22(&SQUARE, &["1 9 2 2 1 1 2 3 4 5 6", "2 2 2 2 1 1 3 4"]),
            "element 1 (surface 1)",
            |p| {
                matches!(p, MeshProblem::UnsupportedElement { code: 9, name }
                    if name == "6-node second order triangle")
            },
            "UnsupportedElement 9 (6-node second order triangle)",
        ),
        Defect::UnsupportedElement41 => {
            let text = String::from_utf8(read(&truncate[0])?)
                .map_err(|_| format!("{}: not text", truncate[0]))?;
            let Some(at) = text.find("\n2 1 2 ") else {
                return Err(format!("{}: no block `2 1 2 <count>`", truncate[0]));
            };
            let mut changed = text.clone();
            changed.replace_range(at..at + 7, "\n2 1 8 ");
            let first_tag = text[at + 1..]
                .lines()
                .nth(1)
                .and_then(|l| l.split_whitespace().next())
                .unwrap_or("?");
            one(
                "unsupported_element_41",
                changed.into_bytes(),
                &format!("element {first_tag} (surface 1)"),
                |p| {
                    matches!(p, MeshProblem::UnsupportedElement { code: 8, name }
                        if name == "3-node second order line")
                },
                "UnsupportedElement 8 (3-node second order line)",
            )
        }
        Defect::TruncatedFile => truncate
            .iter()
            .map(|file| {
                let mut bytes = read(file)?;
                bytes.truncate(bytes.len() / 2);
                let stem = Path::new(file)
                    .file_stem()
                    .map(|s| s.to_string_lossy().to_string())
                    .unwrap_or_default();
                Ok((
                    format!("truncated_{stem}"),
                    bytes,
                    Expected {
                        location: String::new(),
                        problem: |p| {
                            matches!(p, MeshProblem::Syntax(_) | MeshProblem::TooLarge { .. })
                        },
                        describe:
                            "Syntax at a byte offset, or a section count beyond the bytes left",
                    },
                ))
            })
            .collect(),
    }
}

/// Whether `e` is the expected error: the problem, and the location (an empty expected
/// location, a truncated file: a syntax error at a byte offset inside the file, or a section
/// whose count the bytes left cannot hold, found before anything is allocated for it).
fn as_expected(e: &MeshFileError, x: &Expected, len: usize) -> bool {
    let located = if x.location.is_empty() {
        match &e.problem {
            MeshProblem::TooLarge { what, .. } => what.starts_with('$'),
            _ => e
                .location
                .strip_prefix("byte ")
                .and_then(|b| b.parse::<usize>().ok())
                .is_some_and(|b| b <= len),
        }
    } else {
        e.location == x.location
    };
    located && (x.problem)(&e.problem) && e.to_string().contains(&e.location)
}

/// Runs part 4 and adds its gate.
pub fn run(spec: &MeshChecksSpec, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let dir = ctx.case_dir(&report.id)?.join("meshes");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.join(format!("{name}.msh"));
        std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        Ok::<_, String>(path)
    };
    let prefix = format!("{}/", dir.display());
    let mut checks = Vec::new();
    let mut rows = Vec::new();
    let control = write("control", &file22(&SQUARE, &SQUARE_ELEMENTS))?;
    let control_ok = GmshMesh::read(&control, Placement::default())
        .is_ok_and(|m| m.mesh.triangles().len() == 2 && m.boundary_groups["base"].len() == 1);
    checks.push(Check::holds(
        "control: the crafted square without a defect reads (2 triangles, group base)",
        control_ok,
        "a mesh",
    ));
    let (mut expected, mut total) = (0usize, 0usize);
    for &d in &spec.defects {
        for (name, bytes, x) in crafted(d, &spec.truncate)? {
            total += 1;
            let path = write(&name, &bytes)?;
            let (ok, message) = match GmshMesh::read(&path, Placement::default()) {
                Ok(m) => (
                    false,
                    format!(
                        "read without error ({} triangles)",
                        m.mesh.triangles().len()
                    ),
                ),
                Err(e) => (as_expected(&e, &x, bytes.len()), e.to_string()),
            };
            if ok {
                expected += 1;
            }
            let want = if x.location.is_empty() {
                format!("{} (byte ≤ {})", x.describe, bytes.len())
            } else {
                format!("{} at {}", x.describe, x.location)
            };
            checks.push(Check::holds(
                &format!("meshes/{name}.msh: {want}"),
                ok,
                "this error",
            ));
            rows.push(vec![
                format!("meshes/{name}.msh"),
                want,
                message.replace(&prefix, "meshes/"),
            ]);
        }
    }
    checks.push(Check::at_least(
        "crafted files refused with the expected error",
        expected as f64,
        total as f64,
    ));
    report.gates.push(GateVerdict::from_checks(
        format!("mesh checks: {total} crafted defective files, each a typed error"),
        "extreme",
        checks,
        "each defect must give its MeshFileError naming the element or node by its tag in the \
         file (a truncated file: a syntax error at a byte offset inside it, or a section count \
         beyond the bytes left, named with its section); none may read, none may panic",
    ));
    report.tables.push(Table {
        title: "Mesh checks: the crafted files and the errors read".into(),
        header: vec!["file".into(), "expected".into(), "message".into()],
        rows,
    });
    Ok(())
}
