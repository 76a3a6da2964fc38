//! From a file's raw content to a checked [`GmshMesh`]: the element types, the node map, the
//! checks of the module docs in the order a user fixes them (types, planarity, unused and
//! duplicate nodes, degenerate and clockwise triangles, manifoldness, boundary groups).

use std::collections::{BTreeMap, HashMap};

use super::raw::{element_name, Located, RawElement, RawMesh, LINE, POINT, TRIANGLE};
use super::{GmshMesh, Placement};
use crate::error::MeshProblem;
use crate::mesh::triangle::TriangleMesh;

/// The relative tolerance of the planarity and duplicate-node checks (× the bounding-box
/// diagonal) and of the degenerate-triangle check (× h²).
pub const RELATIVE_TOLERANCE: f64 = 1e-12;

/// How many unused node tags an error lists.
const LISTED: usize = 8;

/// Where element `e` is: `element 12 (surface 1)`.
fn at(e: &RawElement) -> String {
    let kind = match e.entity.0 {
        0 => "point",
        1 => "curve",
        2 => "surface",
        _ => "volume",
    };
    format!("element {} ({kind} {})", e.tag, e.entity.1)
}

/// Checks `raw` and builds the mesh (coordinates mapped by `placement`).
pub fn build(raw: RawMesh, placement: Placement) -> Result<GmshMesh, Located> {
    let mut index: HashMap<u64, usize> = HashMap::with_capacity(raw.nodes.len());
    for (i, n) in raw.nodes.iter().enumerate() {
        if index.insert(n.tag, i).is_some() {
            return Err((
                format!("node {}", n.tag),
                MeshProblem::Syntax("the node tag is defined twice".into()),
            ));
        }
    }
    let node_of = |e: &RawElement, tag: u64| {
        index
            .get(&tag)
            .copied()
            .ok_or_else(|| (at(e), MeshProblem::UnknownNode(tag)))
    };
    let mut triangles: Vec<[usize; 3]> = Vec::new();
    let mut triangle_elements: Vec<&RawElement> = Vec::new();
    let mut lines: Vec<(&RawElement, [usize; 2])> = Vec::new();
    for e in &raw.elements {
        match e.code {
            TRIANGLE if e.nodes.len() == 3 => {
                triangles.push([
                    node_of(e, e.nodes[0])?,
                    node_of(e, e.nodes[1])?,
                    node_of(e, e.nodes[2])?,
                ]);
                triangle_elements.push(e);
            }
            LINE if e.nodes.len() == 2 => {
                lines.push((e, [node_of(e, e.nodes[0])?, node_of(e, e.nodes[1])?]));
            }
            POINT => {}
            code => {
                return Err((
                    at(e),
                    MeshProblem::UnsupportedElement {
                        code,
                        name: element_name(code),
                    },
                ))
            }
        }
    }
    if triangles.is_empty() {
        return Err(("file".into(), MeshProblem::NoTriangles));
    }
    // Planarity, against the bounding box of the file's coordinates.
    let diagonal = bounding_diagonal(raw.nodes.iter().map(|n| n.xyz));
    let tol = RELATIVE_TOLERANCE * diagonal;
    for n in &raw.nodes {
        if !n.xyz.iter().all(|x| x.is_finite()) {
            return Err((
                format!("node {}", n.tag),
                MeshProblem::Syntax(format!("non-finite coordinates {:?}", n.xyz)),
            ));
        }
        if n.xyz[2].abs() > tol {
            return Err((
                format!("node {}", n.tag),
                MeshProblem::NotPlanar {
                    z: n.xyz[2],
                    tolerance: tol,
                },
            ));
        }
    }
    // Unused nodes.
    let mut used = vec![false; raw.nodes.len()];
    for t in &triangles {
        for &v in t {
            used[v] = true;
        }
    }
    let unused: Vec<u64> = (0..raw.nodes.len())
        .filter(|&i| !used[i])
        .map(|i| raw.nodes[i].tag)
        .collect();
    if !unused.is_empty() {
        return Err((
            format!("node {}", unused[0]),
            MeshProblem::UnusedNodes {
                count: unused.len(),
                first: unused.iter().take(LISTED).copied().collect(),
            },
        ));
    }
    let nodes: Vec<[f64; 2]> = raw
        .nodes
        .iter()
        .map(|n| {
            [
                placement.scale * n.xyz[0] + placement.offset[0],
                placement.scale * n.xyz[1] + placement.offset[1],
            ]
        })
        .collect();
    let tags: Vec<u64> = raw.nodes.iter().map(|n| n.tag).collect();
    duplicates(&nodes, &tags)?;
    orient(&nodes, &mut triangles, &triangle_elements, &tags)?;
    manifold_edges(&triangles, &triangle_elements, &tags)?;
    let mesh = TriangleMesh::from_parts(nodes, triangles).map_err(|e| {
        (
            "file".to_string(),
            MeshProblem::Syntax(format!("mesh rejected: {e}")),
        )
    })?;
    manifold_nodes(&mesh, &tags)?;
    let names: HashMap<(i32, i32), &str> = raw
        .physical_names
        .iter()
        .map(|(d, t, n)| ((*d, *t), n.as_str()))
        .collect();
    let name = |dim: i32, tag: i32| {
        names
            .get(&(dim, tag))
            .map_or_else(|| tag.to_string(), |n| n.to_string())
    };
    let mut edge_index: HashMap<(usize, usize), usize> = HashMap::new();
    for (i, e) in mesh.boundary().iter().enumerate() {
        let [a, b] = e.nodes;
        edge_index.insert((a.min(b), a.max(b)), i);
    }
    let mut boundary_groups: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (e, [a, b]) in &lines {
        if e.physical.is_empty() {
            continue;
        }
        let edge = edge_index.get(&(*a.min(b), *a.max(b))).copied();
        for &p in &e.physical {
            let group = name(1, p);
            let Some(edge) = edge else {
                return Err((
                    at(e),
                    MeshProblem::NotOnBoundary {
                        group,
                        nodes: [tags[*a], tags[*b]],
                    },
                ));
            };
            boundary_groups.entry(group).or_default().push(edge);
        }
    }
    let mut regions: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (t, e) in triangle_elements.iter().enumerate() {
        for &p in &e.physical {
            regions.entry(name(2, p)).or_default().push(t);
        }
    }
    for list in boundary_groups.values_mut().chain(regions.values_mut()) {
        list.sort_unstable();
        list.dedup();
    }
    Ok(GmshMesh {
        mesh,
        boundary_groups,
        regions,
        node_tags: tags,
        triangle_tags: triangle_elements.iter().map(|e| e.tag).collect(),
    })
}

fn bounding_diagonal(points: impl Iterator<Item = [f64; 3]>) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let d2: f64 = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum();
    if d2.is_finite() {
        d2.sqrt()
    } else {
        0.0
    }
}

/// No two nodes within 10⁻¹² × the bounding-box diagonal (cells of that size hashed, each node
/// compared with the nodes of its 3 × 3 cells).
fn duplicates(nodes: &[[f64; 2]], tags: &[u64]) -> Result<(), Located> {
    let diagonal = bounding_diagonal(nodes.iter().map(|p| [p[0], p[1], 0.0]));
    let tol = RELATIVE_TOLERANCE * diagonal;
    let cell = tol.max(f64::MIN_POSITIVE);
    let key = |p: &[f64; 2]| ((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64);
    let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::with_capacity(nodes.len());
    for (i, p) in nodes.iter().enumerate() {
        let (cx, cy) = key(p);
        for dx in -1..=1i64 {
            for dy in -1..=1i64 {
                let Some(others) = cells.get(&(cx.saturating_add(dx), cy.saturating_add(dy)))
                else {
                    continue;
                };
                for &j in others {
                    let q = nodes[j];
                    let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
                    if d <= tol {
                        return Err((
                            format!("node {}", tags[i]),
                            MeshProblem::DuplicateNode {
                                node: tags[i],
                                other: tags[j],
                                distance: d,
                                tolerance: tol,
                            },
                        ));
                    }
                }
            }
        }
        cells.entry((cx, cy)).or_default().push(i);
    }
    Ok(())
}

/// Degenerate triangles are errors; clockwise ones are reoriented.
fn orient(
    nodes: &[[f64; 2]],
    triangles: &mut [[usize; 3]],
    elements: &[&RawElement],
    tags: &[u64],
) -> Result<(), Located> {
    let mut h = 0.0f64;
    for t in triangles.iter() {
        for k in 0..3 {
            let (a, b) = (nodes[t[k]], nodes[t[(k + 1) % 3]]);
            h = h.max(((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt());
        }
    }
    let tol = RELATIVE_TOLERANCE * h * h;
    for (t, e) in triangles.iter_mut().zip(elements) {
        let (a, b, c) = (nodes[t[0]], nodes[t[1]], nodes[t[2]]);
        let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
        if area.is_nan() || area.abs() <= tol {
            return Err((
                at(e),
                MeshProblem::DegenerateTriangle {
                    nodes: t.map(|v| tags[v]),
                    area,
                    tolerance: tol,
                },
            ));
        }
        if area < 0.0 {
            t.swap(1, 2);
        }
    }
    Ok(())
}

/// No edge of more than two triangles.
fn manifold_edges(
    triangles: &[[usize; 3]],
    elements: &[&RawElement],
    tags: &[u64],
) -> Result<(), Located> {
    let mut count: HashMap<(usize, usize), usize> = HashMap::with_capacity(2 * triangles.len());
    for (t, e) in triangles.iter().zip(elements) {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let n = count.entry((a.min(b), a.max(b))).or_insert(0);
            *n += 1;
            if *n > 2 {
                return Err((
                    at(e),
                    MeshProblem::NonManifoldEdge {
                        nodes: [tags[a], tags[b]],
                        triangles: *n,
                    },
                ));
            }
        }
    }
    Ok(())
}

/// No boundary node with more than two boundary edges.
fn manifold_nodes(mesh: &TriangleMesh, tags: &[u64]) -> Result<(), Located> {
    let mut degree = vec![0usize; mesh.nodes().len()];
    for e in mesh.boundary() {
        for &v in &e.nodes {
            degree[v] += 1;
        }
    }
    // The lowest-numbered offending node, whatever the order of the boundary edges.
    match degree.iter().position(|&d| d > 2) {
        Some(v) => Err((
            format!("node {}", tags[v]),
            MeshProblem::NonManifoldNode { edges: degree[v] },
        )),
        None => Ok(()),
    }
}
