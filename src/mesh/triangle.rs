//! Triangle meshes of plane bodies: nodes, counter-clockwise triangles and the boundary edges
//! (each oriented with the body on its left, so the outward normal is the edge tangent rotated
//! clockwise), with generators for rectangles.
//!
//! The structured rectangle cuts each of its n_x × n_y squares along the diagonal from (x_i, y_j)
//! to (x_{i+1}, y_{j+1}) — the convention of most codes, kept as the default so results compare.

use serde::{Deserialize, Serialize};

use crate::error::{require_positive, InputError};

/// A side of a rectangle (the generators tag boundary edges with it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RectangleSide {
    /// y = y_0.
    Bottom,
    /// x = x_1.
    Right,
    /// y = y_1.
    Top,
    /// x = x_0.
    Left,
}

impl RectangleSide {
    /// All sides.
    pub const ALL: [RectangleSide; 4] = [
        RectangleSide::Bottom,
        RectangleSide::Right,
        RectangleSide::Top,
        RectangleSide::Left,
    ];
}

/// Which diagonal cuts each square of a structured rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Diagonal {
    /// From (x_i, y_j) to (x_{i+1}, y_{j+1}) (the default).
    #[default]
    Up,
    /// From (x_{i+1}, y_j) to (x_i, y_{j+1}).
    Down,
}

/// A boundary edge: its two nodes (body on the left when walking from `nodes[0]` to `nodes[1]`)
/// and, for generated rectangles, the side it lies on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundaryEdge {
    pub nodes: [usize; 2],
    pub side: Option<RectangleSide>,
}

/// A triangle mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleMesh {
    nodes: Vec<[f64; 2]>,
    triangles: Vec<[usize; 3]>,
    boundary: Vec<BoundaryEdge>,
}

/// Grading of one direction of a structured rectangle: coordinates x_i = x_0 + L s(i/n) with
/// s(ξ) = ξ^q (towards the start), 1 − (1 − ξ)^q (towards the end), q ≥ 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Grading {
    pub exponent: f64,
    pub towards_start: bool,
}

impl Grading {
    /// No grading.
    pub const UNIFORM: Grading = Grading {
        exponent: 1.0,
        towards_start: true,
    };

    fn map(&self, xi: f64) -> f64 {
        if self.exponent == 1.0 {
            xi
        } else if self.towards_start {
            xi.powf(self.exponent)
        } else {
            1.0 - (1.0 - xi).powf(self.exponent)
        }
    }
}

/// A triangle whose area is at most this multiple of h_max² (the mesh's longest edge, squared) is
/// degenerate.
pub const DEGENERATE_AREA: f64 = 1e-12;

/// A rectangle's cells checked before any node is placed, so that an extreme `size` or
/// `divisions` is named as written (`mesh.size`, mapped to the scene's key) rather than as the
/// first degenerate triangle: the smallest cell's half area must exceed
/// [`DEGENERATE_AREA`] × the largest cell's diagonal², the test every triangle passes later.
fn check_cell_shape(
    size: [f64; 2],
    [nx, ny]: [usize; 2],
    coord: impl Fn(usize, usize, usize) -> f64,
) -> Result<(), InputError> {
    let gaps = |n: usize, k: usize| {
        let (first, last) = (
            coord(n, 1, k) - coord(n, 0, k),
            coord(n, n, k) - coord(n, n - 1, k),
        );
        (first.min(last), first.max(last))
    };
    let ((hx_min, hx_max), (hy_min, hy_max)) = (gaps(nx, 0), gaps(ny, 1));
    let area = 0.5 * hx_min * hy_min;
    let diagonal2 = hx_max * hx_max + hy_max * hy_max;
    if area.is_finite() && diagonal2.is_finite() && area > DEGENERATE_AREA * diagonal2 {
        return Ok(());
    }
    Err(InputError::new(
        "mesh.size",
        format!("[{}, {}] with divisions [{nx}, {ny}]", size[0], size[1]),
        format!(
            "cells of comparable sides: the smallest cell is {hx_min:.3e} × {hy_min:.3e} and the \
             longest diagonal {:.3e}, so its triangles' area falls below {DEGENERATE_AREA:e} × \
             diagonal² (change the size or the divisions so that the cells are less elongated)",
            diagonal2.sqrt()
        ),
    ))
}

impl TriangleMesh {
    /// The rectangle (x0, x0 + width) × (y0, y0 + height) cut into n_x × n_y squares, each split
    /// into two triangles along `diagonal`; boundary edges tagged with their side.
    pub fn rectangle(
        origin: [f64; 2],
        size: [f64; 2],
        divisions: [usize; 2],
        diagonal: Diagonal,
    ) -> Result<Self, InputError> {
        Self::graded_rectangle(origin, size, divisions, diagonal, [Grading::UNIFORM; 2])
    }

    /// [`TriangleMesh::rectangle`] with power-law grading in each direction.
    pub fn graded_rectangle(
        origin: [f64; 2],
        size: [f64; 2],
        divisions: [usize; 2],
        diagonal: Diagonal,
        grading: [Grading; 2],
    ) -> Result<Self, InputError> {
        for (i, name) in ["mesh.width", "mesh.height"].iter().enumerate() {
            require_positive(name, size[i])?;
            if !origin[i].is_finite() {
                return Err(InputError::new(
                    "mesh.origin",
                    origin[i],
                    "finite coordinates",
                ));
            }
            if !(grading[i].exponent.is_finite() && (1.0..=10.0).contains(&grading[i].exponent)) {
                return Err(InputError::new(
                    "mesh.grading",
                    grading[i].exponent,
                    "a number in [1, 10]",
                ));
            }
        }
        let [nx, ny] = divisions;
        if nx == 0 || ny == 0 {
            return Err(InputError::new(
                "mesh.divisions",
                format!("[{nx}, {ny}]"),
                "at least one square in each direction",
            ));
        }
        let coord = |n: usize, i: usize, k: usize| {
            if i == n {
                origin[k] + size[k]
            } else {
                origin[k] + size[k] * grading[k].map(i as f64 / n as f64)
            }
        };
        check_cell_shape(size, divisions, coord)?;
        let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1));
        for j in 0..=ny {
            for i in 0..=nx {
                nodes.push([coord(nx, i, 0), coord(ny, j, 1)]);
            }
        }
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut triangles = Vec::with_capacity(2 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                match diagonal {
                    Diagonal::Up => {
                        triangles.push([a, b, c]);
                        triangles.push([a, c, d]);
                    }
                    Diagonal::Down => {
                        triangles.push([a, b, d]);
                        triangles.push([b, c, d]);
                    }
                }
            }
        }
        let mut boundary = Vec::with_capacity(2 * (nx + ny));
        for i in 0..nx {
            boundary.push(BoundaryEdge {
                nodes: [id(i, 0), id(i + 1, 0)],
                side: Some(RectangleSide::Bottom),
            });
        }
        for j in 0..ny {
            boundary.push(BoundaryEdge {
                nodes: [id(nx, j), id(nx, j + 1)],
                side: Some(RectangleSide::Right),
            });
        }
        for i in (0..nx).rev() {
            boundary.push(BoundaryEdge {
                nodes: [id(i + 1, ny), id(i, ny)],
                side: Some(RectangleSide::Top),
            });
        }
        for j in (0..ny).rev() {
            boundary.push(BoundaryEdge {
                nodes: [id(0, j + 1), id(0, j)],
                side: Some(RectangleSide::Left),
            });
        }
        Self::checked(nodes, triangles, boundary)
    }

    /// A mesh from nodes and triangles: finite coordinates, valid indices, non-degenerate
    /// triangles (clockwise ones are reoriented); the boundary is the set of edges used by exactly
    /// one triangle, without side tags.
    pub fn from_parts(
        nodes: Vec<[f64; 2]>,
        mut triangles: Vec<[usize; 3]>,
    ) -> Result<Self, InputError> {
        for (i, p) in nodes.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(InputError::new(
                    format!("mesh.nodes[{i}]"),
                    format!("{p:?}"),
                    "finite coordinates",
                ));
            }
        }
        for (t, tri) in triangles.iter_mut().enumerate() {
            if let Some(&bad) = tri.iter().find(|&&v| v >= nodes.len()) {
                return Err(InputError::new(
                    format!("mesh.triangles[{t}]"),
                    bad,
                    format!("node indices below {}", nodes.len()),
                ));
            }
            if signed_area(&nodes, tri) < 0.0 {
                tri.swap(1, 2);
            }
        }
        let mut edges: std::collections::HashMap<(usize, usize), (usize, [usize; 2])> =
            std::collections::HashMap::new();
        for tri in &triangles {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let key = (a.min(b), a.max(b));
                edges.entry(key).or_insert((0, [a, b])).0 += 1;
            }
        }
        let mut boundary: Vec<BoundaryEdge> = edges
            .into_values()
            .filter(|(count, _)| *count == 1)
            .map(|(_, nodes)| BoundaryEdge { nodes, side: None })
            .collect();
        boundary.sort_by_key(|e| e.nodes);
        Self::checked(nodes, triangles, boundary)
    }

    /// The mesh of `nodes`, `triangles` and `boundary`, once every triangle has a positive area.
    fn checked(
        nodes: Vec<[f64; 2]>,
        triangles: Vec<[usize; 3]>,
        boundary: Vec<BoundaryEdge>,
    ) -> Result<Self, InputError> {
        let mesh = Self {
            nodes,
            triangles,
            boundary,
        };
        mesh.check_areas()?;
        Ok(mesh)
    }

    fn check_areas(&self) -> Result<(), InputError> {
        let scale = self.h_max().max(f64::MIN_POSITIVE);
        for (t, tri) in self.triangles.iter().enumerate() {
            let area = signed_area(&self.nodes, tri);
            if area.is_nan() || area <= DEGENERATE_AREA * scale * scale {
                return Err(InputError::new(
                    format!("mesh.triangles[{t}]"),
                    format!("{tri:?} (area {area:e})"),
                    "a non-degenerate triangle",
                ));
            }
        }
        Ok(())
    }

    /// Node coordinates.
    pub fn nodes(&self) -> &[[f64; 2]] {
        &self.nodes
    }

    /// Counter-clockwise triangles.
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// Boundary edges, body on the left.
    pub fn boundary(&self) -> &[BoundaryEdge] {
        &self.boundary
    }

    /// The outward unit normal and the length of a boundary edge.
    pub fn edge_normal(&self, edge: &BoundaryEdge) -> ([f64; 2], f64) {
        let a = self.nodes[edge.nodes[0]];
        let b = self.nodes[edge.nodes[1]];
        let (tx, ty) = (b[0] - a[0], b[1] - a[1]);
        let len = (tx * tx + ty * ty).sqrt();
        ([ty / len, -tx / len], len)
    }

    /// The longest edge of any triangle: the h of the error estimates.
    pub fn h_max(&self) -> f64 {
        let mut h = 0.0f64;
        for tri in &self.triangles {
            for k in 0..3 {
                let (a, b) = (self.nodes[tri[k]], self.nodes[tri[(k + 1) % 3]]);
                h = h.max(((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt());
            }
        }
        h
    }

    /// The area of triangle `t`.
    pub fn area(&self, t: usize) -> f64 {
        signed_area(&self.nodes, &self.triangles[t])
    }

    /// The nodes displaced by `u` (two values per node, interleaved), scaled by `scale`.
    pub fn displaced(&self, u: &[f64], scale: f64) -> Vec<[f64; 2]> {
        self.nodes
            .iter()
            .enumerate()
            .map(|(i, p)| [p[0] + scale * u[2 * i], p[1] + scale * u[2 * i + 1]])
            .collect()
    }
}

fn signed_area(nodes: &[[f64; 2]], tri: &[usize; 3]) -> f64 {
    let (a, b, c) = (nodes[tri[0]], nodes[tri[1]], nodes[tri[2]]);
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
}

#[cfg(test)]
mod tests {
    //! Triangle meshes: the rectangle's counts, orientation, diagonal convention, boundary normals
    //! and tags; validation of user meshes.
    use super::*;

    #[test]
    fn an_extreme_rectangle_names_its_size_not_a_triangle() {
        let err = TriangleMesh::rectangle([0.0, 0.0], [1.0, 1e12], [4, 4], Diagonal::Up)
            .err()
            .unwrap();
        assert_eq!(err.field, "mesh.size");
        assert!(err.value.contains("1000000000000"), "{err}");
        assert!(TriangleMesh::rectangle([0.0, 0.0], [1.0, 1e4], [4, 4], Diagonal::Up).is_ok());
    }

    #[test]
    fn rectangle_counts_and_total_area() {
        let m = TriangleMesh::rectangle([0.0, 0.0], [6.0, 6.0], [4, 3], Diagonal::Up).unwrap();
        assert_eq!(m.nodes().len(), 5 * 4);
        assert_eq!(m.triangles().len(), 24);
        assert_eq!(m.boundary().len(), 2 * (4 + 3));
        let total: f64 = (0..m.triangles().len()).map(|t| m.area(t)).sum();
        assert!((total - 36.0).abs() < 1e-12);
    }

    #[test]
    fn default_diagonal_runs_from_lower_left_to_upper_right() {
        let m = TriangleMesh::rectangle([0.0, 0.0], [1.0, 1.0], [1, 1], Diagonal::Up).unwrap();
        // both triangles contain nodes 0 = (0, 0) and 3 = (1, 1)
        for t in m.triangles() {
            assert!(t.contains(&0) && t.contains(&3));
        }
    }

    #[test]
    fn boundary_normals_point_outwards_on_each_side() {
        let m = TriangleMesh::rectangle([0.0, 0.0], [2.0, 1.0], [2, 2], Diagonal::Up).unwrap();
        for e in m.boundary() {
            let (n, len) = m.edge_normal(e);
            let expected = match e.side.unwrap() {
                RectangleSide::Bottom => [0.0, -1.0],
                RectangleSide::Right => [1.0, 0.0],
                RectangleSide::Top => [0.0, 1.0],
                RectangleSide::Left => [-1.0, 0.0],
            };
            assert!((n[0] - expected[0]).abs() < 1e-14 && (n[1] - expected[1]).abs() < 1e-14);
            assert!(len > 0.0);
        }
    }

    #[test]
    fn from_parts_finds_the_boundary_and_reorients() {
        let nodes = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let m = TriangleMesh::from_parts(nodes, vec![[0, 2, 1], [0, 2, 3]]).unwrap();
        assert_eq!(m.boundary().len(), 4);
        assert!((0..2).all(|t| m.area(t) > 0.0));
    }

    #[test]
    fn degenerate_triangle_and_bad_index_are_errors() {
        let nodes = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
        assert_eq!(
            TriangleMesh::from_parts(nodes.clone(), vec![[0, 1, 2]])
                .unwrap_err()
                .field,
            "mesh.triangles[0]"
        );
        assert!(TriangleMesh::from_parts(nodes, vec![[0, 1, 7]]).is_err());
        assert!(TriangleMesh::rectangle([0.0, 0.0], [1.0, 1.0], [0, 3], Diagonal::Up).is_err());
    }
}
