//! Drawing mesh plots: the grid of cells, the filled triangles (sealed against anti-aliasing
//! seams), the wireframe, outlines, colour bar and legend.

use std::path::Path;

use plotters::coord::Shift;
use plotters::drawing::DrawingArea;
use plotters::element::Polygon;
use plotters::prelude::DrawingBackend;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{RGBAColor, RGBColor, ShapeStyle};

use crate::plot::colormap::{viridis, MISSING, PALETTE};
use crate::plot::draw::{
    draw_line, draw_major_grid, draw_major_ticks, draw_no_data, draw_polyline, draw_rect,
    draw_text_anchored, draw_title, draw_y_label, fill, stroke, text_size, text_style, DrawResult,
    LABEL_SIZE, LEGEND_SIZE, TEXT, TICK_SIZE,
};
use crate::plot::error::PlotError;
use crate::plot::geom::{clipped_polylines, ipx, Px, Rect};
use crate::plot::grid::render_cells;
use crate::plot::triangles::layout::{
    layout, legend_entry_width, legend_text, Bar, Layout, View, BAR_TICK, LEGEND_GAP,
    LEGEND_SAMPLE, LEGEND_SPACING, SUBDIVIDE_AREA,
};
use crate::plot::triangles::prepare::{validate, ColorScale, Mesh};
use crate::plot::triangles::{FieldValues, TriangleMeshPlot};

// Drawing

/// Renders `plots` in a grid of `columns` columns, each cell `cell` pixels, into an SVG string.
/// `path` only names the target in errors.
pub(crate) fn render(
    plots: &[TriangleMeshPlot],
    columns: usize,
    cell: (u32, u32),
    path: &Path,
) -> Result<String, PlotError> {
    for plot in plots {
        validate(plot, path)?;
    }
    let svg = render_cells(plots, columns, cell, path, |area, plot| {
        draw_plot(area, plot)
    })?;
    Ok(seal_polygons(&svg))
}

/// Gives every opaque filled polygon (the triangles: nothing else in these plots is a polygon)
/// a thin stroke of its own colour, and groups runs of them under one `<g>` setting the stroke
/// width. Without it, anti-aliasing leaves light seams along shared edges, the background
/// showing through where two triangles each cover half a pixel. Also makes line joins round
/// (on the root element, inherited), so that wireframe paths turning sharply at the boundary
/// do not end in miter spikes. Works on the lines plotters' SVG backend writes
/// (`<svg width=…>`, `<polygon opacity="1" fill="#RRGGBB" points="…"/>`); anything else is
/// copied unchanged.
pub(super) fn seal_polygons(svg: &str) -> String {
    const OPEN: &str = "<polygon opacity=\"1\" fill=\"";
    let mut out = String::with_capacity(svg.len() + svg.len() / 10);
    let mut grouped = false;
    for line in svg.split_inclusive('\n') {
        if let Some(rest) = line.strip_prefix("<svg ").filter(|_| out.is_empty()) {
            out.push_str("<svg stroke-linejoin=\"round\" ");
            out.push_str(rest);
            continue;
        }
        let sealed = line.strip_prefix(OPEN).and_then(|rest| {
            let color = rest.get(..7).filter(|c| c.starts_with('#'))?;
            Some((color, rest.get(7..)?))
        });
        match sealed {
            Some((color, rest)) => {
                if !grouped {
                    out.push_str("<g stroke-width=\"1\">\n");
                    grouped = true;
                }
                out.push_str("<polygon fill=\"");
                out.push_str(color);
                out.push_str("\" stroke=\"");
                out.push_str(color);
                out.push_str(rest);
            }
            None => {
                if grouped {
                    out.push_str("</g>\n");
                    grouped = false;
                }
                out.push_str(line);
            }
        }
    }
    if grouped {
        out.push_str("</g>\n");
    }
    out
}

/// Fills a triangle given in pixels, skipping those that round to zero area.
pub(super) fn fill_triangle<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    p: [Px; 3],
    color: RGBColor,
) -> DrawResult<DB> {
    let q = p.map(ipx);
    let cross = i64::from(q[1].0 - q[0].0) * i64::from(q[2].1 - q[0].1)
        - i64::from(q[2].0 - q[0].0) * i64::from(q[1].1 - q[0].1);
    if cross == 0 {
        return Ok(());
    }
    area.draw(&Polygon::new(q.to_vec(), fill(color.into())))
}

pub(super) fn midpoint(a: Px, b: Px) -> Px {
    (0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1))
}

/// Draws the filled triangles: coloured by the field, or light grey without field and wireframe.
pub(super) fn draw_fills<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    mesh: &Mesh,
    view: &View,
) -> DrawResult<DB> {
    let plot = mesh.plot;
    let corners = |i: usize| plot.triangles[i].map(|k| view.px(mesh.at(k)));
    match (&plot.field, mesh.scale) {
        (Some(field), Some(scale)) => match &field.values {
            FieldValues::PerTriangle(values) => {
                for &i in &mesh.drawable {
                    let v = values.get(i).copied().unwrap_or(f64::NAN);
                    fill_triangle(area, corners(i), scale.color(v))?;
                }
            }
            FieldValues::PerNode(values) => {
                for &i in &mesh.drawable {
                    let [a, b, c] =
                        plot.triangles[i].map(|k| values.get(k).copied().unwrap_or(f64::NAN));
                    let [p0, p1, p2] = corners(i);
                    let area2 =
                        ((p1.0 - p0.0) * (p2.1 - p0.1) - (p2.0 - p0.0) * (p1.1 - p0.1)).abs();
                    if 0.5 * area2 >= SUBDIVIDE_AREA {
                        let (m01, m12, m20) =
                            (midpoint(p0, p1), midpoint(p1, p2), midpoint(p2, p0));
                        let parts = [
                            ([p0, m01, m20], (4.0 * a + b + c) / 6.0),
                            ([p1, m12, m01], (4.0 * b + c + a) / 6.0),
                            ([p2, m20, m12], (4.0 * c + a + b) / 6.0),
                            ([m01, m12, m20], (a + b + c) / 3.0),
                        ];
                        for (p, v) in parts {
                            fill_triangle(area, p, scale.color(v))?;
                        }
                    } else {
                        fill_triangle(area, [p0, p1, p2], scale.color((a + b + c) / 3.0))?;
                    }
                }
            }
        },
        _ if !plot.wireframe => {
            for &i in &mesh.drawable {
                fill_triangle(area, corners(i), RGBColor(0xDD, 0xDD, 0xDD))?;
            }
        }
        _ => {}
    }
    Ok(())
}

/// The unique edges of `triangles`, chained into paths (node index sequences). Each walk goes
/// on along the unused edge that turns least, so structured meshes give long straight lines.
pub(super) fn edge_paths(
    triangles: &[[usize; 3]],
    positions: &dyn Fn(usize) -> (f64, f64),
) -> Vec<Vec<usize>> {
    let mut edges: Vec<(usize, usize)> = triangles
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .filter(|(a, b)| a != b)
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    // Adjacency lists (neighbour, edge) in a compressed layout, nodes renumbered densely.
    let mut ids: Vec<usize> = edges.iter().flat_map(|&(a, b)| [a, b]).collect();
    ids.sort_unstable();
    ids.dedup();
    let local = |k: usize| ids.binary_search(&k).unwrap_or(0);
    let mut start = vec![0usize; ids.len() + 1];
    for &(a, b) in &edges {
        start[local(a) + 1] += 1;
        start[local(b) + 1] += 1;
    }
    for i in 0..ids.len() {
        start[i + 1] += start[i];
    }
    let mut fill_at = start.clone();
    let mut adj = vec![(0usize, 0usize); 2 * edges.len()];
    for (e, &(a, b)) in edges.iter().enumerate() {
        let (la, lb) = (local(a), local(b));
        adj[fill_at[la]] = (lb, e);
        fill_at[la] += 1;
        adj[fill_at[lb]] = (la, e);
        fill_at[lb] += 1;
    }
    let mut used = vec![false; edges.len()];
    let mut remaining: Vec<usize> = (0..ids.len()).map(|i| start[i + 1] - start[i]).collect();
    // Odd-degree nodes first: every path must start or end at one of them.
    let mut order: Vec<usize> = (0..ids.len()).filter(|&i| remaining[i] % 2 == 1).collect();
    order.extend(0..ids.len());
    let mut paths = Vec::new();
    for &v0 in &order {
        while remaining[v0] > 0 {
            let mut path = vec![ids[v0]];
            let (mut prev, mut v) = (None::<usize>, v0);
            loop {
                let here = positions(ids[v]);
                let dir = prev.map(|u| {
                    let p = positions(ids[u]);
                    (here.0 - p.0, here.1 - p.1)
                });
                // The unused edge with the largest cosine to the incoming direction.
                let mut best: Option<(f64, usize, usize)> = None;
                for &(u, e) in &adj[start[v]..start[v + 1]] {
                    if used[e] {
                        continue;
                    }
                    let score = dir.map_or(0.0, |d| {
                        let q = positions(ids[u]);
                        let o = (q.0 - here.0, q.1 - here.1);
                        let n = (d.0.hypot(d.1) * o.0.hypot(o.1)).max(1e-300);
                        let c = (d.0 * o.0 + d.1 * o.1) / n;
                        if c.is_finite() {
                            c
                        } else {
                            0.0
                        }
                    });
                    if best.is_none_or(|(s, _, _)| score > s + 1e-12) {
                        best = Some((score, u, e));
                    }
                }
                let Some((_, u, e)) = best else { break };
                used[e] = true;
                remaining[v] -= 1;
                remaining[u] -= 1;
                path.push(ids[u]);
                prev = Some(v);
                v = u;
            }
            paths.push(path);
        }
    }
    paths
}

pub(super) fn draw_wireframe<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    mesh: &Mesh,
    view: &View,
) -> DrawResult<DB> {
    let tris: Vec<[usize; 3]> = mesh
        .drawable
        .iter()
        .map(|&i| mesh.plot.triangles[i])
        .collect();
    let style = if mesh.plot.field.is_some() {
        ShapeStyle {
            color: RGBAColor(0, 0, 0, 0.35),
            filled: false,
            stroke_width: 1,
        }
    } else {
        stroke(RGBColor(0x30, 0x30, 0x30), 1)
    };
    for path in edge_paths(&tris, &|k| mesh.at(k)) {
        let mut pts: Vec<Px> = Vec::with_capacity(path.len());
        for k in path {
            let p = view.px(mesh.at(k));
            let q = ipx(p);
            if pts.last().map(|&l| ipx(l)) != Some(q) {
                pts.push(p);
            }
        }
        draw_polyline(area, &pts, style)?;
    }
    Ok(())
}

pub(super) fn draw_plot<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    plot: &TriangleMeshPlot,
) -> DrawResult<DB> {
    let (w, h) = area.dim_in_pixel();
    let (w, h) = (f64::from(w), f64::from(h));
    let mesh = Mesh::new(plot);
    let lay = layout(&mesh, (w, h));
    let view = lay.view;
    let r = view.rect;
    let px_x = |t: f64| view.px((t, view.y.0)).0;
    let px_y = |t: f64| view.px((view.x.0, t)).1;

    // Grid, mesh, wireframe, outlines.
    draw_major_grid(
        area,
        &r,
        lay.x_axis.major.iter().map(|(t, _)| px_x(*t)),
        lay.y_axis.major.iter().map(|(t, _)| px_y(*t)),
    )?;
    draw_fills(area, &mesh, &view)?;
    if plot.wireframe {
        draw_wireframe(area, &mesh, &view)?;
    }
    let clip = Rect {
        left: r.left - 1.0,
        top: r.top - 1.0,
        right: r.right + 1.0,
        bottom: r.bottom + 1.0,
    };
    for o in &mesh.outlines {
        let pts: Vec<Option<Px>> = o.points.iter().map(|p| p.map(|p| view.px(p))).collect();
        let dash = o.outline.dashed.then_some((8.0, 5.0));
        for line in clipped_polylines(&pts, &clip) {
            draw_line(area, &line, stroke(PALETTE[o.color], 2), dash)?;
        }
    }

    // Frame, ticks and tick labels.
    draw_rect(area, &r, stroke(TEXT, 1))?;
    draw_major_ticks(
        area,
        &r,
        lay.x_axis.major.iter().map(|(t, l)| (px_x(*t), l.as_str())),
        lay.y_axis.major.iter().map(|(t, l)| (px_y(*t), l.as_str())),
    )?;

    if let (Some(bar), Some(scale)) = (&lay.bar, mesh.scale) {
        draw_bar(
            area,
            bar,
            &scale,
            plot.field.as_ref().map_or("", |f| f.name.as_str()),
        )?;
    }

    if !mesh.has_data() {
        draw_no_data(area, &r)?;
    }

    // Title, axis labels, legend.
    draw_title(area, &plot.title, lay.title_size, w)?;
    let tick_h = text_size("0", TICK_SIZE).1;
    let mut below = r.bottom + 9.0 + tick_h + 8.0;
    if !plot.x_label.is_empty() {
        draw_text_anchored(
            area,
            &plot.x_label,
            LABEL_SIZE,
            (HPos::Center, VPos::Top),
            ((r.left + r.right) / 2.0, below),
        )?;
        below += text_size("Ag", LABEL_SIZE).1 + 8.0;
    }
    if !plot.y_label.is_empty() {
        let label_h = text_size("Ag", LABEL_SIZE).1;
        let x = r.left - 9.0 - lay.y_tick_w - 10.0 - label_h;
        draw_y_label(area, &plot.y_label, x, &r)?;
    }
    draw_legend(area, &mesh, &lay, below, w)
}

/// Draws the colour bar: a gradient of one-pixel rows, its frame, labels, title and, when some
/// values are missing, a grey "NaN" swatch below it.
pub(super) fn draw_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    bar: &Bar,
    scale: &ColorScale,
    name: &str,
) -> DrawResult<DB> {
    let b = Rect {
        left: bar.rect.left.round(),
        top: bar.rect.top.round(),
        right: bar.rect.right.round(),
        bottom: bar.rect.bottom.round(),
    };
    let len = (b.bottom - b.top).max(1.0);
    if let Some((lo, hi)) = scale.range {
        // One rectangle per run of equal-colour pixel rows, each reaching down to the bottom
        // of the bar and painted over by the next: no seams where rows meet, even when scaled.
        let color_at = |y: f64| viridis((b.bottom - (y + 0.5)) / len);
        let mut y0 = b.top;
        while y0 < b.bottom {
            let c = color_at(y0);
            let mut y1 = y0 + 1.0;
            while y1 < b.bottom && color_at(y1) == c {
                y1 += 1.0;
            }
            let run = Rect {
                left: b.left,
                top: y0,
                right: b.right,
                bottom: b.bottom,
            };
            draw_rect(area, &run, fill(c.into()))?;
            y0 = y1;
        }
        for (v, label) in &bar.labels {
            let y = b.bottom - (v - lo) / (hi - lo) * len;
            draw_polyline(
                area,
                &[(b.right, y), (b.right + BAR_TICK, y)],
                stroke(TEXT, 1),
            )?;
            draw_text_anchored(
                area,
                label,
                TICK_SIZE,
                (HPos::Left, VPos::Center),
                (b.right + BAR_TICK + 4.0, y),
            )?;
        }
    }
    draw_rect(area, &b, stroke(TEXT, 1))?;
    if !name.is_empty() {
        let style = text_style(bar.title_size)
            .color(&TEXT)
            .pos(Pos::new(HPos::Left, VPos::Bottom));
        area.draw_text(name, &style, ipx((bar.title_x, b.top - 10.0)))?;
    }
    if scale.missing {
        let s = Rect {
            left: b.left,
            top: b.bottom + 10.0,
            right: b.right,
            bottom: b.bottom + 22.0,
        };
        draw_rect(area, &s, fill(MISSING.into()))?;
        draw_rect(area, &s, stroke(TEXT, 1))?;
        draw_text_anchored(
            area,
            "NaN",
            TICK_SIZE,
            (HPos::Left, VPos::Center),
            (s.right + BAR_TICK + 4.0, (s.top + s.bottom) / 2.0),
        )?;
    }
    Ok(())
}

/// Draws the outline legend in rows below the plot, each row centred under the box.
pub(super) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    mesh: &Mesh,
    lay: &Layout,
    top: f64,
    w: f64,
) -> DrawResult<DB> {
    let r = lay.view.rect;
    let row_h = text_size("Ag", LEGEND_SIZE).1 + 6.0;
    for (j, (row, rw)) in lay.legend.iter().enumerate() {
        let cy = top + row_h * j as f64 + row_h / 2.0;
        let mut x = (0.5 * (r.left + r.right) - 0.5 * rw)
            .min(w - 10.0 - rw)
            .max(10.0);
        for &i in row {
            let o = &mesh.outlines[i];
            let text = legend_text(o);
            let dash = o.outline.dashed.then_some((7.0, 4.0));
            draw_line(
                area,
                &[(x, cy), (x + LEGEND_SAMPLE, cy)],
                stroke(PALETTE[o.color], 2),
                dash,
            )?;
            draw_text_anchored(
                area,
                &text,
                LEGEND_SIZE,
                (HPos::Left, VPos::Center),
                (x + LEGEND_SAMPLE + LEGEND_GAP, cy),
            )?;
            x += legend_entry_width(&text) + LEGEND_SPACING;
        }
    }
    Ok(())
}
