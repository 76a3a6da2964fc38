// Setting: small structured meshes rendered to strings (and a few files in the temp folder).
// Goal: pin colour-bar labels, NaN handling, typed errors, equal aspect, "no data",
// determinism and that a 96×96 mesh renders compactly.
use std::path::Path;
use std::time::Instant;

use super::draw::{edge_paths, render};
use super::layout::{compact, fit_equal_aspect, layout};
use super::prepare::{color_scale, Mesh};
use super::*;
use crate::plot::colormap::{viridis, MISSING};
use crate::plot::draw::ensure_font;
use crate::plot::error::PlotError;
use crate::plot::geom::Rect;
use crate::plot::svg::{write_triangle_panels_svg, write_triangle_svg};

/// An n×n square mesh on (0, size)², two triangles per cell, nodes moved by `u`.
fn square_mesh(
    n: usize,
    size: f64,
    u: impl Fn(f64, f64) -> (f64, f64),
) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let mut nodes = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (size * i as f64 / n as f64, size * j as f64 / n as f64);
            let (ux, uy) = u(x, y);
            nodes.push([x + ux, y + uy]);
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (nodes, tris)
}

fn no_move(_: f64, _: f64) -> (f64, f64) {
    (0.0, 0.0)
}

fn render_one(plot: &TriangleMeshPlot) -> String {
    render(
        std::slice::from_ref(plot),
        1,
        TRIANGLE_SIZE,
        Path::new("test.svg"),
    )
    .expect("render")
}

fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|rest| {
            let start = rest.find('>')? + 1;
            let end = rest.find("</text>")?;
            rest.get(start..end).map(|t| t.trim().to_string())
        })
        .collect()
}

fn assert_svg(svg: &str) {
    assert!(svg.trim_start().starts_with("<svg"));
    assert!(svg.trim_end().ends_with("</svg>"));
    assert!(
        !svg.contains("NaN\"") && !svg.contains("inf"),
        "non-finite coordinate in SVG"
    );
}

fn two_by_two(values: Vec<f64>) -> TriangleMeshPlot {
    let (nodes, tris) = square_mesh(2, 1.0, no_move);
    TriangleMeshPlot::new("2×2", nodes, tris).field(TriangleField::per_triangle("s", values))
}

#[test]
fn per_triangle_field_writes_colour_bar_with_min_and_max_labels() {
    let plot = two_by_two(vec![6.5623, 10.0, 20.0, 30.0, 40.0, 49.2222, 12.0, 13.0]);
    let path = std::env::temp_dir().join(format!("contactlab_tri_{}.svg", std::process::id()));
    write_triangle_svg(&plot, &path).expect("write");
    let svg = std::fs::read_to_string(&path).expect("read back");
    let _ = std::fs::remove_file(&path);
    assert_svg(&svg);
    let t = texts(&svg);
    for label in ["6.562", "49.22", "s", "2×2", "x", "y"] {
        assert!(t.iter().any(|x| x == label), "missing {label:?} in {t:?}");
    }
    assert_eq!(svg.matches("<polygon").count(), 8);
    // Triangles are sealed against anti-aliasing seams with a stroke of their own colour.
    assert_eq!(svg.matches("<g stroke-width=\"1\">").count(), 1);
    assert!(svg.contains("<polygon fill=\"#440154\" stroke=\"#440154\" points="));
}

#[test]
fn nan_values_are_grey_and_left_out_of_the_colour_range() {
    let scale = color_scale([1.0, f64::NAN, 3.0, f64::INFINITY], None);
    assert_eq!(scale.range, Some((1.0, 3.0)));
    assert!(scale.missing);
    assert_eq!(scale.color(f64::NAN), MISSING);
    assert_eq!(scale.color(3.0), viridis(1.0));
    let nan = f64::NAN;
    let svg = render_one(&two_by_two(vec![1.0, nan, 2.0, nan, 3.0, 4.0, nan, 5.0]));
    assert_svg(&svg);
    let t = texts(&svg);
    assert!(
        t.iter().any(|x| x == "1") && t.iter().any(|x| x == "5"),
        "{t:?}"
    );
    assert!(t.iter().any(|x| x == "NaN"), "NaN swatch missing: {t:?}");
    let grey = "fill=\"#B4B4B4\"";
    assert!(svg.matches(grey).count() >= 3);
    // All values missing: grey triangles, no range, still a valid picture.
    let svg = render_one(&two_by_two(vec![nan; 8]));
    assert_svg(&svg);
}

#[test]
fn constant_field_gets_a_padded_range() {
    assert_eq!(color_scale([2.0, 2.0], None).range, Some((1.8, 2.2)));
    assert_eq!(color_scale([0.0], None).range, Some((-1.0, 1.0)));
    assert_eq!(
        color_scale([1.0, 2.0], Some((0.0, 10.0))).range,
        Some((0.0, 10.0))
    );
    assert_eq!(
        color_scale([1.0, 2.0], Some((3.0, 3.0))).range,
        Some((1.0, 2.0))
    );
    assert_eq!(color_scale([f64::NAN], None).range, None);
}

#[test]
fn out_of_range_triangle_index_is_a_typed_error_naming_the_triangle() {
    let (nodes, mut tris) = square_mesh(2, 1.0, no_move);
    tris[5] = [0, 1, 99];
    let plot = TriangleMeshPlot::new("bad", nodes, tris);
    let path = std::env::temp_dir().join("contactlab_tri_never_written.svg");
    let err = write_triangle_svg(&plot, &path).unwrap_err();
    assert!(
        matches!(
            err,
            PlotError::TriangleIndex {
                triangle: 5,
                node: 99,
                nodes: 9,
                ..
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("triangle 5"), "{err}");
    assert!(!path.exists());
}

#[test]
fn field_of_the_wrong_length_is_a_typed_error() {
    let err = render(
        &[two_by_two(vec![1.0; 7])],
        1,
        TRIANGLE_SIZE,
        Path::new("t.svg"),
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            PlotError::FieldLength {
                expected: 8,
                found: 7,
                per: "triangle",
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn two_to_one_rectangle_keeps_its_aspect_on_screen() {
    ensure_font().unwrap();
    let (nodes, tris) = square_mesh(4, 1.0, |x, _| (x, 0.0)); // (0, 2) × (0, 1)
    let plot = TriangleMeshPlot::new("2:1", nodes, tris)
        .field(TriangleField::per_triangle("s", (0..32).map(f64::from)));
    let mesh = Mesh::new(&plot);
    for cell in [
        (720.0, 640.0),
        (560.0, 500.0),
        (300.0, 900.0),
        (1400.0, 300.0),
    ] {
        let view = layout(&mesh, cell).view;
        let (a, b) = (view.px((0.0, 0.0)), view.px((2.0, 1.0)));
        let ratio = (b.0 - a.0) / (a.1 - b.1);
        assert!((ratio - 2.0).abs() < 1e-9, "{cell:?}: {ratio}");
        let r = view.rect;
        assert!(r.left >= 0.0 && r.right <= cell.0 && r.top >= 0.0 && r.bottom <= cell.1);
    }
    // The pure fit, and its widening of a very elongated range.
    let v = fit_equal_aspect(
        (0.0, 100.0),
        (0.0, 1.0),
        Rect {
            left: 0.0,
            top: 0.0,
            right: 500.0,
            bottom: 400.0,
        },
    );
    assert!((v.rect.bottom - v.rect.top - 400.0 / 3.0).abs() < 1e-9);
    assert!((v.scale() - 5.0).abs() < 1e-12);
    assert!((v.y.1 - v.y.0 - (400.0 / 3.0) / 5.0).abs() < 1e-9);
}

#[test]
fn empty_mesh_writes_a_valid_svg_saying_no_data() {
    let plot = TriangleMeshPlot::new("empty", vec![], vec![])
        .field(TriangleField::per_triangle("s", vec![]))
        .wireframe(true);
    let svg = render_one(&plot);
    assert_svg(&svg);
    assert!(texts(&svg).iter().any(|t| t == "no data"));
    // Nodes that cannot be drawn make an empty mesh too.
    let plot = TriangleMeshPlot::new(
        "nan",
        vec![[f64::NAN, 0.0], [1.0, 0.0], [0.0, 1.0]],
        vec![[0, 1, 2]],
    );
    let svg = render_one(&plot);
    assert_svg(&svg);
    assert!(texts(&svg).iter().any(|t| t == "no data"));
}

#[test]
fn hostile_coordinates_and_outlines_do_not_break_the_picture() {
    let nodes = vec![
        [0.0, 0.0],
        [1e300, 0.0],
        [0.0, f64::INFINITY],
        [1.0, 1.0],
        [2.0, 2.0],
    ];
    let plot = TriangleMeshPlot::new(
        "hostile",
        nodes,
        vec![[0, 1, 3], [0, 3, 4], [2, 3, 4], [4, 4, 4]],
    )
    .field(TriangleField::per_node(
        "p",
        vec![1.0, -1.0, f64::NAN, 3.0, 1e308],
    ))
    .wireframe(true)
    .outline(
        Outline::new(
            "o",
            vec![[0.0, 0.0], [f64::NAN, 1.0], [2.0, 0.0], [0.0, 2.0]],
        )
        .closed()
        .dashed(),
    )
    .outline(Outline::new("nothing", vec![[f64::NAN, 1.0]]));
    let svg = render_one(&plot);
    assert_svg(&svg);
    assert!(texts(&svg).iter().any(|t| t == "nothing (no data)"));
}

#[test]
fn tiny_and_huge_meshes_stay_finite() {
    for scale in [1e-250, 1e-320, 1e-9, 1e299] {
        let (nodes, tris) = square_mesh(2, 1.0, no_move);
        let nodes = nodes.iter().map(|p| [p[0] * scale, p[1] * scale]).collect();
        let plot = TriangleMeshPlot::new("s", nodes, tris)
            .field(TriangleField::per_triangle(
                "v",
                (0..8).map(|k| f64::from(k) * scale),
            ))
            .wireframe(true);
        assert_svg(&render_one(&plot));
    }
}

#[test]
fn same_plot_gives_same_bytes() {
    let (nodes, tris) = square_mesh(6, 2.0, |x, y| (0.1 * y, -0.05 * x * y));
    let n = nodes.len();
    let plot = TriangleMeshPlot::new("d", nodes.clone(), tris)
        .field(TriangleField::per_node(
            "u",
            (0..n).map(|k| (k as f64).sin()),
        ))
        .wireframe(true)
        .outline(Outline::new("a", nodes[..3].to_vec()).dashed())
        .outline(Outline::new("b", nodes[3..6].to_vec()).color(2));
    assert_eq!(render_one(&plot), render_one(&plot.clone()));
}

#[test]
fn per_node_field_splits_large_triangles_into_four() {
    let (nodes, tris) = square_mesh(2, 1.0, no_move);
    let plot = TriangleMeshPlot::new("n", nodes, tris)
        .field(TriangleField::per_node("u", (0..9).map(f64::from)));
    assert_eq!(render_one(&plot).matches("<polygon").count(), 32);
}

#[test]
fn wireframe_edges_are_each_drawn_once_in_long_paths() {
    let (nodes, tris) = square_mesh(4, 1.0, no_move);
    let paths = edge_paths(&tris, &|k| (nodes[k][0], nodes[k][1]));
    let mut edges: Vec<(usize, usize)> = paths
        .iter()
        .flat_map(|p| p.windows(2).map(|w| (w[0].min(w[1]), w[0].max(w[1]))))
        .collect();
    let total = edges.len();
    edges.sort_unstable();
    edges.dedup();
    assert_eq!(edges.len(), total, "an edge was drawn twice");
    assert_eq!(total, 2 * 4 * 5 + 16); // grid lines plus one diagonal per cell
    assert!(paths.len() <= 20, "{} paths", paths.len());
}

#[test]
fn compact_labels_keep_four_significant_digits() {
    assert_eq!(compact(6.56234), "6.562");
    assert_eq!(compact(49.2222), "49.22");
    assert_eq!(compact(2.5), "2.5");
    assert_eq!(compact(-0.0), "0");
    assert_eq!(compact(12345.6), "12346");
    assert_eq!(compact(1.23456e-5), "1.235e-5");
    assert_eq!(compact(2e7), "2e7");
}

#[test]
fn panels_put_several_meshes_in_one_picture() {
    let plots = vec![
        two_by_two(vec![1.0; 8]),
        two_by_two(vec![2.0; 8]).wireframe(true),
    ];
    let svg = render(&plots, 2, TRIANGLE_PANEL_SIZE, Path::new("p.svg")).unwrap();
    assert_svg(&svg);
    assert!(svg.contains("width=\"1120\""));
    assert!(matches!(
        write_triangle_panels_svg(&[], 2, Path::new("p.svg")),
        Err(PlotError::NoFigures { .. })
    ));
}

#[test]
fn mesh_of_96_by_96_renders_compactly() {
    let (nodes, tris) = square_mesh(96, 6.0, |x, y| (0.02 * x * y, -0.01 * x));
    let values: Vec<f64> = tris
        .iter()
        .enumerate()
        .map(|(i, _)| (i as f64 * 0.001).sin())
        .collect();
    let plot =
        TriangleMeshPlot::new("96×96", nodes, tris).field(TriangleField::per_triangle("s", values));
    let start = Instant::now();
    let svg = render_one(&plot);
    let filled = start.elapsed();
    let wire = render_one(&plot.clone().wireframe(true));
    eprintln!(
        "96×96: field {:?}, {} bytes; with wireframe {:?} total, {} bytes",
        filled,
        svg.len(),
        start.elapsed(),
        wire.len()
    );
    assert_svg(&svg);
    assert!(svg.len() < 3_000_000 && wire.len() < 3_000_000);
    assert!(!svg.contains("<polyline fill=\"none\" opacity=\"0.35\""));
}

/// The demo figures of the brief: `cargo test … plot::triangles -- --ignored`.
#[test]
#[ignore = "writes demo figures to /tmp"]
fn demo_figures() {
    use std::f64::consts::PI;
    let u = |x: f64, y: f64| (0.1 * (PI * y / 6.0).sin() * x / 6.0, -0.3 * x * y / 36.0);
    let (nodes, tris) = square_mesh(20, 6.0, u);
    let (reference, _) = square_mesh(20, 6.0, no_move);
    // |ε| at each triangle's centroid (reference position), in percent.
    let strain = |x: f64, y: f64| {
        let e11 = 0.1 * (PI * y / 6.0).sin() / 6.0;
        let e22 = -0.3 * x / 36.0;
        let e12 = 0.5 * (0.1 * PI / 6.0 * (PI * y / 6.0).cos() * x / 6.0 - 0.3 * y / 36.0);
        100.0 * (e11 * e11 + e22 * e22 + 2.0 * e12 * e12).sqrt()
    };
    let values: Vec<f64> = tris
        .iter()
        .map(|t| {
            let c = t.iter().fold((0.0, 0.0), |c, &k| {
                (c.0 + reference[k][0] / 3.0, c.1 + reference[k][1] / 3.0)
            });
            strain(c.0, c.1)
        })
        .collect();
    let boundary = Outline::new(
        "initial boundary",
        vec![[0.0, 0.0], [6.0, 0.0], [6.0, 6.0], [0.0, 6.0]],
    )
    .closed()
    .dashed();
    let plot = TriangleMeshPlot::new(
        "Deformed mesh, strain magnitude",
        nodes.clone(),
        tris.clone(),
    )
    .field(TriangleField::per_triangle("|ε| (%)", values))
    .outline(boundary.clone());
    write_triangle_svg(&plot, Path::new("/tmp/tri_demo.svg")).unwrap();
    let wire = TriangleMeshPlot::new("Initial boundary and deformed mesh", nodes, tris)
        .wireframe(true)
        .outline(boundary);
    write_triangle_svg(&wire, Path::new("/tmp/tri_demo_wire.svg")).unwrap();
    let n = reference.len();
    let nodal = TriangleMeshPlot::new(
        "per-node field",
        reference.clone(),
        square_mesh(20, 6.0, no_move).1,
    )
    .field(TriangleField::per_node(
        "x·y",
        (0..n).map(|k| reference[k][0] * reference[k][1]),
    ));
    write_triangle_panels_svg(
        &[
            plot.clone(),
            wire.clone(),
            nodal,
            plot.clone().wireframe(true),
        ],
        2,
        Path::new("/tmp/tri_demo_panels.svg"),
    )
    .unwrap();
    // Edge cases for the eye: empty, NaN values, a 10:1 strip, a constant field.
    let (strip, strip_tris) = square_mesh(10, 1.0, |x, _| (9.0 * x, 0.0));
    let m = strip.len();
    let edge = [
        TriangleMeshPlot::new("empty", vec![], vec![])
            .field(TriangleField::per_triangle("s", vec![])),
        two_by_two(vec![1.0, f64::NAN, 2.0, 3.0, f64::NAN, 4.0, 5.0, 6.0]).wireframe(true),
        TriangleMeshPlot::new("10:1 strip", strip, strip_tris)
            .field(TriangleField::per_node(
                "a long field name, in units",
                (0..m).map(|k| (k as f64 * 0.3).sin()),
            ))
            .outline(Outline::new("centre line", vec![[0.0, 0.5], [10.0, 0.5]]))
            .outline(
                Outline::new(
                    "another outline with a long name",
                    vec![[0.0, 0.2], [10.0, 0.8]],
                )
                .dashed(),
            ),
        two_by_two(vec![2.0; 8]).field(TriangleField::per_triangle("const", vec![2.0; 8])),
    ];
    write_triangle_panels_svg(&edge, 2, Path::new("/tmp/tri_edge_panels.svg")).unwrap();
}
