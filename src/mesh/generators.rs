//! Triangle meshes of round bodies: a disk (the ball of BDS §1.7) and an annulus (the ring).
//!
//! The disk is the regular triangulation of a hexagon mapped onto concentric circles: ring i
//! (i = 1, …, n) carries 6i nodes at radius r i/n and angles 2πj/(6i), around a center node; the
//! band between rings i − 1 and i holds 6(2i − 1) triangles. Hence 1 + 3n(n + 1) nodes, 6n²
//! triangles, and a boundary of 6n edges inscribed in the circle; the area is that of the
//! inscribed regular 6n-gon, (6n/2) r² sin(2π/(6n)) = πr² (1 − O(1/n²)). The mesh has the
//! hexagon's symmetries (rotations by 60°, reflections about the corner lines).
//!
//! The annulus is a polar grid: `radial` × `around` cells, each split into two triangles with
//! diagonals alternating like a checkerboard, so that for an even `around` the mesh is symmetric
//! about the x-axis. Cells are closest to squares when around ≈ 2π r_mean radial/(r_o − r_i).
//!
//! Both come out of [`TriangleMesh::from_parts`], with counter-clockwise triangles and untagged
//! boundary edges.

use std::f64::consts::PI;

use crate::error::{require_positive, InputError};
use crate::mesh::triangle::TriangleMesh;

/// The largest number of nodes a generator builds (about 1 GiB of coordinates).
pub const MAX_NODES: usize = 1 << 26;

fn check_center(center: [f64; 2]) -> Result<(), InputError> {
    if center.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(InputError::new(
            "mesh.center",
            format!("{center:?}"),
            "finite coordinates",
        ))
    }
}

fn check_node_count(
    field: &str,
    value: impl std::fmt::Display,
    nodes: Option<usize>,
) -> Result<(), InputError> {
    match nodes {
        Some(n) if n <= MAX_NODES => Ok(()),
        _ => Err(InputError::new(
            field,
            value,
            format!("a value giving at most {MAX_NODES} nodes"),
        )),
    }
}

/// Nodes and counter-clockwise triangles of the disk (see the module documentation).
fn disk_parts(center: [f64; 2], radius: f64, rings: usize) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let ring_start = |i: usize| if i == 0 { 0 } else { 1 + 3 * i * (i - 1) };
    let mut nodes = Vec::with_capacity(ring_start(rings + 1));
    nodes.push(center);
    for i in 1..=rings {
        let r = if i == rings {
            radius
        } else {
            radius * i as f64 / rings as f64
        };
        for j in 0..6 * i {
            let theta = 2.0 * PI * j as f64 / (6 * i) as f64;
            nodes.push([center[0] + r * theta.cos(), center[1] + r * theta.sin()]);
        }
    }
    let mut triangles = Vec::with_capacity(6 * rings * rings);
    for i in 1..=rings {
        // In sector s the outer ring has nodes k = 0..=i, the inner ring k = 0..i (the center
        // for i = 1); consecutive sectors share their corner nodes.
        let outer = |s: usize, k: usize| ring_start(i) + (s * i + k) % (6 * i);
        let inner = |s: usize, k: usize| {
            if i == 1 {
                0
            } else {
                ring_start(i - 1) + (s * (i - 1) + k) % (6 * (i - 1))
            }
        };
        for s in 0..6 {
            for k in 0..i {
                triangles.push([outer(s, k), outer(s, k + 1), inner(s, k)]);
            }
            for k in 0..i - 1 {
                triangles.push([inner(s, k), outer(s, k + 1), inner(s, k + 1)]);
            }
        }
    }
    (nodes, triangles)
}

/// A disk of `radius` about `center`: `rings` concentric rings of nodes (ring i has 6i nodes) around
/// a center node; 1 + 3 rings (rings + 1) nodes, 6 rings² triangles, 6 rings boundary edges on
/// the circle. Minimum angle about 45° (47.6° at 2–3 rings, 44.0° at 40, 60° for one ring).
///
/// Errors name `mesh.center`, `mesh.radius` or `mesh.rings` (at least 1, at most
/// [`MAX_NODES`] nodes).
pub fn disk(center: [f64; 2], radius: f64, rings: usize) -> Result<TriangleMesh, InputError> {
    check_center(center)?;
    require_positive("mesh.radius", radius)?;
    if rings == 0 {
        return Err(InputError::new("mesh.rings", rings, "at least 1 ring"));
    }
    let nodes = rings
        .checked_add(1)
        .and_then(|r1| r1.checked_mul(rings))
        .and_then(|p| p.checked_mul(3))
        .and_then(|p| p.checked_add(1));
    check_node_count("mesh.rings", rings, nodes)?;
    let (nodes, triangles) = disk_parts(center, radius, rings);
    TriangleMesh::from_parts(nodes, triangles)
}

/// Nodes and counter-clockwise triangles of the annulus; node (j, k) — radius index j, angle
/// index k — is j·around + k.
fn annulus_parts(
    center: [f64; 2],
    inner: f64,
    outer: f64,
    radial: usize,
    around: usize,
) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let mut nodes = Vec::with_capacity((radial + 1) * around);
    for j in 0..=radial {
        let r = if j == radial {
            outer
        } else {
            inner + (outer - inner) * j as f64 / radial as f64
        };
        for k in 0..around {
            let theta = 2.0 * PI * k as f64 / around as f64;
            nodes.push([center[0] + r * theta.cos(), center[1] + r * theta.sin()]);
        }
    }
    let id = |j: usize, k: usize| j * around + k % around;
    let mut triangles = Vec::with_capacity(2 * radial * around);
    for j in 0..radial {
        for k in 0..around {
            // a, b on the inner circle of the cell (angles k, k + 1), d, c above them.
            let (a, b, c, d) = (id(j, k), id(j, k + 1), id(j + 1, k + 1), id(j + 1, k));
            if (j + k) % 2 == 0 {
                triangles.push([a, d, c]);
                triangles.push([a, c, b]);
            } else {
                triangles.push([a, d, b]);
                triangles.push([b, d, c]);
            }
        }
    }
    (nodes, triangles)
}

/// The annulus inner < |x − center| < outer: `radial` × `around` polar cells split into two
/// triangles each with alternating diagonals; (radial + 1) around nodes, 2 radial around
/// triangles, 2 around boundary edges (around on each circle).
///
/// Errors name `mesh.center`, `mesh.inner`, `mesh.outer` (0 < inner < outer), `mesh.radial`
/// (≥ 1) or `mesh.around` (≥ 3), and at most [`MAX_NODES`] nodes.
pub fn annulus(
    center: [f64; 2],
    inner: f64,
    outer: f64,
    radial: usize,
    around: usize,
) -> Result<TriangleMesh, InputError> {
    check_center(center)?;
    require_positive("mesh.inner", inner)?;
    require_positive("mesh.outer", outer)?;
    if outer <= inner {
        return Err(InputError::new(
            "mesh.outer",
            outer,
            format!("a radius > mesh.inner = {inner}"),
        ));
    }
    if radial == 0 {
        return Err(InputError::new("mesh.radial", radial, "at least 1 layer"));
    }
    if around < 3 {
        return Err(InputError::new(
            "mesh.around",
            around,
            "at least 3 divisions",
        ));
    }
    let nodes = radial.checked_add(1).and_then(|r1| r1.checked_mul(around));
    check_node_count(
        "mesh.around",
        format!("{around} (with radial = {radial})"),
        nodes,
    )?;
    let (nodes, triangles) = annulus_parts(center, inner, outer, radial, around);
    TriangleMesh::from_parts(nodes, triangles)
}

#[cfg(test)]
mod tests {
    //! Disk and annulus meshes: counts, area against the inscribed polygons and its O(h²) error,
    //! orientation, boundary on the circles with outward normals, symmetry, minimum angles, and
    //! typed errors for bad inputs.
    use std::collections::HashSet;

    use super::*;

    fn signed_area(nodes: &[[f64; 2]], t: &[usize; 3]) -> f64 {
        let (a, b, c) = (nodes[t[0]], nodes[t[1]], nodes[t[2]]);
        0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
    }

    fn total_area(m: &TriangleMesh) -> f64 {
        (0..m.triangles().len()).map(|t| m.area(t)).sum()
    }

    /// The smallest interior angle of any triangle, in degrees.
    fn min_angle(m: &TriangleMesh) -> f64 {
        let p = m.nodes();
        let mut worst = 180.0f64;
        for t in m.triangles() {
            for k in 0..3 {
                let (a, b, c) = (p[t[k]], p[t[(k + 1) % 3]], p[t[(k + 2) % 3]]);
                let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
                let cos = (u[0] * v[0] + u[1] * v[1]) / (u[0].hypot(u[1]) * v[0].hypot(v[1]));
                worst = worst.min(cos.clamp(-1.0, 1.0).acos().to_degrees());
            }
        }
        worst
    }

    fn polygon_area(sides: usize, r: f64) -> f64 {
        0.5 * sides as f64 * r * r * (2.0 * PI / sides as f64).sin()
    }

    fn triangle_set(triangles: &[[usize; 3]], map: impl Fn(usize) -> usize) -> HashSet<[usize; 3]> {
        triangles
            .iter()
            .map(|t| {
                let mut s = [map(t[0]), map(t[1]), map(t[2])];
                s.sort_unstable();
                s
            })
            .collect()
    }

    #[test]
    fn disk_counts_nodes_triangles_and_boundary_edges() {
        for n in 1..=6 {
            let m = disk([0.5, -1.0], 2.0, n).unwrap();
            assert_eq!(m.nodes().len(), 1 + 3 * n * (n + 1));
            assert_eq!(m.triangles().len(), 6 * n * n);
            assert_eq!(m.boundary().len(), 6 * n);
        }
    }

    #[test]
    fn disk_area_is_the_inscribed_polygon_and_converges_at_second_order() {
        let r = 1.5;
        let mut errors = Vec::new();
        for n in [2, 4, 8, 16] {
            let area = total_area(&disk([0.0, 0.0], r, n).unwrap());
            assert!((area - polygon_area(6 * n, r)).abs() < 1e-12);
            errors.push(PI * r * r - area);
        }
        for w in errors.windows(2) {
            let rate = (w[0] / w[1]).log2();
            assert!((rate - 2.0).abs() < 0.02, "rate {rate}");
        }
    }

    #[test]
    fn disk_triangles_are_built_counter_clockwise() {
        for n in 1..=8 {
            let (nodes, triangles) = disk_parts([3.0, 4.0], 0.7, n);
            assert!(triangles.iter().all(|t| signed_area(&nodes, t) > 0.0));
        }
    }

    #[test]
    fn disk_boundary_lies_on_the_circle_with_outward_normals() {
        let (c, r) = ([1.0, 2.0], 3.0);
        let m = disk(c, r, 5).unwrap();
        for e in m.boundary() {
            for &v in &e.nodes {
                let p = m.nodes()[v];
                assert!(((p[0] - c[0]).hypot(p[1] - c[1]) - r).abs() < 1e-13);
            }
            let (normal, _) = m.edge_normal(e);
            let p = m.nodes()[e.nodes[0]];
            assert!(normal[0] * (p[0] - c[0]) + normal[1] * (p[1] - c[1]) > 0.0);
        }
    }

    #[test]
    fn disk_has_the_hexagon_symmetries() {
        let n = 5;
        let (_, triangles) = disk_parts([0.0, 0.0], 1.0, n);
        let ring_of = |v: usize| (1..=n).find(|&i| v < 1 + 3 * i * (i + 1)).unwrap_or(0);
        let transform = |v: usize, f: &dyn Fn(usize, usize) -> usize| {
            if v == 0 {
                return 0;
            }
            let i = ring_of(v);
            let start = 1 + 3 * i * (i - 1);
            start + f(i, v - start) % (6 * i)
        };
        let original = triangle_set(&triangles, |v| v);
        let rotated = triangle_set(&triangles, |v| transform(v, &|i, j| j + i));
        let mirrored = triangle_set(&triangles, |v| transform(v, &|i, j| 6 * i - j));
        assert_eq!(original, rotated);
        assert_eq!(original, mirrored);
    }

    #[test]
    fn disk_minimum_angle_stays_above_40_degrees() {
        assert!((min_angle(&disk([0.0, 0.0], 1.0, 1).unwrap()) - 60.0).abs() < 1e-10);
        for n in [2, 3, 5, 10, 20, 40] {
            let a = min_angle(&disk([0.0, 0.0], 1.0, n).unwrap());
            assert!(a > 40.0, "rings {n}: minimum angle {a}");
        }
    }

    #[test]
    fn annulus_counts_area_and_second_order_convergence() {
        let (ri, ro) = (0.6, 1.0);
        let exact = PI * (ro * ro - ri * ri);
        let mut errors = Vec::new();
        for around in [16, 32, 64, 128] {
            let radial = around / 16;
            let m = annulus([0.0, 0.0], ri, ro, radial, around).unwrap();
            assert_eq!(m.nodes().len(), (radial + 1) * around);
            assert_eq!(m.triangles().len(), 2 * radial * around);
            assert_eq!(m.boundary().len(), 2 * around);
            let area = total_area(&m);
            assert!((area - (polygon_area(around, ro) - polygon_area(around, ri))).abs() < 1e-12);
            errors.push(exact - area);
        }
        for w in errors.windows(2) {
            let rate = (w[0] / w[1]).log2();
            assert!((rate - 2.0).abs() < 0.02, "rate {rate}");
        }
    }

    #[test]
    fn annulus_triangles_are_counter_clockwise_and_boundary_on_both_circles() {
        let (c, ri, ro) = ([-1.0, 0.5], 0.5, 2.0);
        let (nodes, triangles) = annulus_parts(c, ri, ro, 3, 17);
        assert!(triangles.iter().all(|t| signed_area(&nodes, t) > 0.0));
        let m = annulus(c, ri, ro, 3, 17).unwrap();
        let (mut on_inner, mut on_outer) = (0, 0);
        for e in m.boundary() {
            let radius = |v: usize| {
                let p = m.nodes()[v];
                (p[0] - c[0]).hypot(p[1] - c[1])
            };
            let (r0, r1) = (radius(e.nodes[0]), radius(e.nodes[1]));
            let p = m.nodes()[e.nodes[0]];
            let (normal, _) = m.edge_normal(e);
            let radial_component = normal[0] * (p[0] - c[0]) + normal[1] * (p[1] - c[1]);
            if (r0 - ri).abs() < 1e-13 && (r1 - ri).abs() < 1e-13 {
                on_inner += 1;
                assert!(radial_component < 0.0, "inner normal points into the hole");
            } else {
                assert!((r0 - ro).abs() < 1e-13 && (r1 - ro).abs() < 1e-13);
                on_outer += 1;
                assert!(radial_component > 0.0);
            }
        }
        assert_eq!((on_inner, on_outer), (17, 17));
    }

    #[test]
    fn annulus_with_even_around_is_symmetric_about_the_x_axis() {
        let (radial, around) = (3, 12);
        let (_, triangles) = annulus_parts([0.0, 0.0], 1.0, 2.0, radial, around);
        let mirror = |v: usize| {
            let (j, k) = (v / around, v % around);
            j * around + (around - k) % around
        };
        assert_eq!(
            triangle_set(&triangles, |v| v),
            triangle_set(&triangles, mirror)
        );
    }

    #[test]
    fn annulus_with_square_cells_has_minimum_angle_above_30_degrees() {
        // r_mean = 1.5, cell width 0.25: around ≈ 2π · 1.5/0.25 ≈ 38
        let a = min_angle(&annulus([0.0, 0.0], 1.0, 2.0, 4, 38).unwrap());
        assert!(a > 30.0, "minimum angle {a}");
    }

    #[test]
    fn bad_inputs_are_typed_errors_naming_the_field() {
        let field = |r: Result<TriangleMesh, InputError>| r.unwrap_err().field;
        assert_eq!(field(disk([0.0, 0.0], 0.0, 3)), "mesh.radius");
        assert_eq!(field(disk([0.0, 0.0], f64::NAN, 3)), "mesh.radius");
        assert_eq!(field(disk([0.0, 0.0], 1.0, 0)), "mesh.rings");
        assert_eq!(field(disk([f64::INFINITY, 0.0], 1.0, 2)), "mesh.center");
        assert_eq!(field(disk([0.0, 0.0], 1.0, usize::MAX)), "mesh.rings");
        assert_eq!(field(disk([0.0, 0.0], 1.0, 10_000)), "mesh.rings");
        assert_eq!(field(annulus([0.0, 0.0], 0.0, 1.0, 2, 8)), "mesh.inner");
        assert_eq!(field(annulus([0.0, 0.0], 1.0, 1.0, 2, 8)), "mesh.outer");
        assert_eq!(field(annulus([0.0, 0.0], 1.0, -2.0, 2, 8)), "mesh.outer");
        assert_eq!(field(annulus([0.0, 0.0], 0.5, 1.0, 0, 8)), "mesh.radial");
        assert_eq!(field(annulus([0.0, 0.0], 0.5, 1.0, 2, 2)), "mesh.around");
        assert_eq!(
            field(annulus([0.0, f64::NAN], 0.5, 1.0, 2, 8)),
            "mesh.center"
        );
        assert_eq!(
            field(annulus([0.0, 0.0], 0.5, 1.0, usize::MAX, 8)),
            "mesh.around"
        );
        let err = disk([0.0, 0.0], -2.0, 3).unwrap_err();
        assert_eq!(err.value, "-2");
    }
}
