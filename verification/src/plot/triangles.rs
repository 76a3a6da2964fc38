//! Triangle-mesh plots for 2D finite-element results.
//!
//! Describe a [`TriangleMeshPlot`] (nodes, triangles, optionally a scalar [`TriangleField`],
//! a wireframe and [`Outline`]s such as the undeformed boundary) and write it with
//! [`write_triangle_svg`], or several in a grid with [`write_triangle_panels_svg`]. The plot
//! keeps an equal aspect ratio (one unit in x is as long on screen as one unit in y), colours a
//! field with the perceptually uniform viridis map and explains it with a colour bar on the
//! right. As for the other figures, drawing never panics on data: triangles touching a node
//! with a non-finite coordinate are skipped, non-finite field values are drawn grey and left out
//! of the colour range, a mesh with nothing drawable gives a valid SVG saying "no data", and the
//! same plot always gives the same bytes. Only malformed input is an error: a triangle naming a
//! node that does not exist, or a field with the wrong number of values.
//!
//! ```no_run
//! use contactlab_verify::plot::{write_triangle_svg, Outline, TriangleField, TriangleMeshPlot};
//! let nodes = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
//! let plot = TriangleMeshPlot::new("Deformed mesh", nodes.clone(), vec![[0, 1, 2], [0, 2, 3]])
//!     .field(TriangleField::per_triangle("|ε|", vec![0.1, 0.3]))
//!     .wireframe(true)
//!     .outline(Outline::new("undeformed", nodes).closed().dashed());
//! write_triangle_svg(&plot, std::path::Path::new("reports/mesh.svg")).unwrap();
//! ```

use std::path::Path;

use plotters::coord::Shift;
use plotters::drawing::{DrawingArea, IntoDrawingArea};
use plotters::element::Polygon;
use plotters::prelude::{DrawingBackend, SVGBackend};
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{FontTransform, RGBAColor, RGBColor, ShapeStyle};
use serde::{Deserialize, Serialize};

use super::axis::{build_axis, to_axis, Axis};
use super::colormap::{viridis, MISSING};
use super::geom::{clipped_polylines, ipx, Px, Rect};
use super::render::{
    draw_line, draw_polyline, draw_rect, draw_text_anchored, ensure_font, fill, stroke, text_size,
    text_style, DrawResult, GRID_MAJOR, LABEL_SIZE, LEGEND_SIZE, NOTE, NOTE_SIZE, PALETTE, TEXT,
    TICK_SIZE, TITLE_SIZE,
};
use super::{clamp_size, write_file, PlotError, Scale};

/// Default size of a single triangle-mesh plot, in pixels (width, height).
pub const TRIANGLE_SIZE: (u32, u32) = (720, 640);

/// Size of one cell of a grid of triangle-mesh plots, in pixels (width, height).
pub const TRIANGLE_PANEL_SIZE: (u32, u32) = (560, 500);

/// Where the values of a [`TriangleField`] live.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum FieldValues {
    /// One value per triangle, in the order of [`TriangleMeshPlot::triangles`]; each triangle
    /// is drawn in one flat colour.
    PerTriangle(Vec<f64>),
    /// One value per node, in the order of [`TriangleMeshPlot::nodes`]. A triangle covering at
    /// least 48 px² on screen is split into four at its edge midpoints and each part coloured
    /// by the linearly interpolated value at its centroid; a smaller one is coloured by the
    /// value at its own centroid (the mean of its three nodal values).
    PerNode(Vec<f64>),
}

/// A scalar field on the mesh, coloured with viridis and explained by a colour bar titled
/// `name`. Non-finite values are drawn grey and excluded from the automatic range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TriangleField {
    /// Title of the colour bar.
    pub name: String,
    /// The values.
    pub values: FieldValues,
    /// Fixed colour range (values outside take the end colours); `None`, or an unusable range
    /// (non-finite, empty or reversed), means the range of the drawn values, padded when they
    /// are all equal.
    pub range: Option<(f64, f64)>,
}

impl TriangleField {
    /// A field with one value per triangle (flat colour per triangle).
    pub fn per_triangle(name: impl Into<String>, values: impl IntoIterator<Item = f64>) -> Self {
        TriangleField {
            name: name.into(),
            values: FieldValues::PerTriangle(values.into_iter().collect()),
            range: None,
        }
    }

    /// A field with one value per node (see [`FieldValues::PerNode`] for how it is coloured).
    pub fn per_node(name: impl Into<String>, values: impl IntoIterator<Item = f64>) -> Self {
        TriangleField {
            name: name.into(),
            values: FieldValues::PerNode(values.into_iter().collect()),
            range: None,
        }
    }

    /// Fixes the colour range.
    pub fn range(mut self, lo: f64, hi: f64) -> Self {
        self.range = Some((lo, hi));
        self
    }
}

/// A polyline drawn over the mesh (e.g. the undeformed boundary), listed in the legend under
/// its name unless the name is empty. A non-finite point breaks the line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outline {
    /// Legend entry; an empty name keeps the outline out of the legend.
    pub name: String,
    /// Points in drawing order.
    pub points: Vec<[f64; 2]>,
    /// Join the last point back to the first.
    pub closed: bool,
    /// Dash the line.
    pub dashed: bool,
    /// Index into the Okabe–Ito palette, modulo [`super::PALETTE_LEN`]; `None` takes the next
    /// colour not chosen explicitly by another outline (over a field the order starts with the
    /// colours that stand out against viridis: vermillion, black, reddish purple, orange).
    pub color: Option<usize>,
}

impl Outline {
    /// An open, solid outline with automatic colour.
    pub fn new(name: impl Into<String>, points: impl IntoIterator<Item = [f64; 2]>) -> Self {
        Outline {
            name: name.into(),
            points: points.into_iter().collect(),
            closed: false,
            dashed: false,
            color: None,
        }
    }

    /// Dashes the line.
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }

    /// Joins the last point back to the first.
    pub fn closed(mut self) -> Self {
        self.closed = true;
        self
    }

    /// Chooses the palette colour (index modulo [`super::PALETTE_LEN`]).
    pub fn color(mut self, index: usize) -> Self {
        self.color = Some(index);
        self
    }
}

/// A plot of a 2D triangle mesh. Build it with [`TriangleMeshPlot::new`] and the builder
/// methods. Without a field the triangles are filled light grey unless the wireframe is on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TriangleMeshPlot {
    /// Title above the plot.
    pub title: String,
    /// Node coordinates (x, y).
    pub nodes: Vec<[f64; 2]>,
    /// Triangles as indices into `nodes`.
    pub triangles: Vec<[usize; 3]>,
    /// Scalar field to colour the triangles with.
    pub field: Option<TriangleField>,
    /// Draw the triangle edges.
    pub wireframe: bool,
    /// Polylines drawn over the mesh.
    pub outlines: Vec<Outline>,
    /// Label of the x axis.
    pub x_label: String,
    /// Label of the y axis.
    pub y_label: String,
}

impl TriangleMeshPlot {
    /// A mesh plot without field, wireframe or outlines, with axes labelled "x" and "y".
    pub fn new(title: impl Into<String>, nodes: Vec<[f64; 2]>, triangles: Vec<[usize; 3]>) -> Self {
        TriangleMeshPlot {
            title: title.into(),
            nodes,
            triangles,
            field: None,
            wireframe: false,
            outlines: Vec::new(),
            x_label: "x".to_string(),
            y_label: "y".to_string(),
        }
    }

    /// Sets the field.
    pub fn field(mut self, field: TriangleField) -> Self {
        self.field = Some(field);
        self
    }

    /// Switches the wireframe on or off.
    pub fn wireframe(mut self, on: bool) -> Self {
        self.wireframe = on;
        self
    }

    /// Adds an outline.
    pub fn outline(mut self, outline: Outline) -> Self {
        self.outlines.push(outline);
        self
    }

    /// Sets the axis labels (empty strings leave an axis unlabelled).
    pub fn labels(mut self, x: impl Into<String>, y: impl Into<String>) -> Self {
        self.x_label = x.into();
        self.y_label = y.into();
        self
    }
}

/// Writes `plot` as an SVG of [`TRIANGLE_SIZE`] to `path`, creating missing parent folders.
pub fn write_triangle_svg(plot: &TriangleMeshPlot, path: &Path) -> Result<(), PlotError> {
    write_triangle_svg_sized(plot, TRIANGLE_SIZE, path)
}

/// Writes `plot` as an SVG of `size` = (width, height) pixels to `path`, creating missing parent
/// folders. Sizes are clamped to 100…10 000 pixels.
pub fn write_triangle_svg_sized(
    plot: &TriangleMeshPlot,
    size: (u32, u32),
    path: &Path,
) -> Result<(), PlotError> {
    let svg = render(std::slice::from_ref(plot), 1, clamp_size(size), path)?;
    write_file(path, &svg)
}

/// Writes several mesh plots in a grid (`columns` per row, filled row by row) into one SVG at
/// `path`; each cell is [`TRIANGLE_PANEL_SIZE`]. `columns` is clamped to 1…`plots.len()`.
pub fn write_triangle_panels_svg(
    plots: &[TriangleMeshPlot],
    columns: usize,
    path: &Path,
) -> Result<(), PlotError> {
    if plots.is_empty() {
        return Err(PlotError::NoFigures {
            path: path.to_path_buf(),
        });
    }
    let svg = render(plots, columns, TRIANGLE_PANEL_SIZE, path)?;
    write_file(path, &svg)
}

// ---------------------------------------------------------------------------------------------
// Validation and data preparation (data space)

/// Checks the triangle indices and the field length.
fn validate(plot: &TriangleMeshPlot, path: &Path) -> Result<(), PlotError> {
    let nodes = plot.nodes.len();
    for (triangle, t) in plot.triangles.iter().enumerate() {
        if let Some(&node) = t.iter().find(|&&k| k >= nodes) {
            return Err(PlotError::TriangleIndex {
                path: path.to_path_buf(),
                title: plot.title.clone(),
                triangle,
                node,
                nodes,
            });
        }
    }
    if let Some(field) = &plot.field {
        let (expected, found, per) = match &field.values {
            FieldValues::PerTriangle(v) => (plot.triangles.len(), v.len(), "triangle"),
            FieldValues::PerNode(v) => (nodes, v.len(), "node"),
        };
        if expected != found {
            return Err(PlotError::FieldLength {
                path: path.to_path_buf(),
                title: plot.title.clone(),
                field: field.name.clone(),
                per,
                expected,
                found,
            });
        }
    }
    Ok(())
}

/// A point that can be drawn: both coordinates finite and of sane magnitude.
fn point(p: [f64; 2]) -> Option<(f64, f64)> {
    Some((to_axis(Scale::Linear, p[0])?, to_axis(Scale::Linear, p[1])?))
}

/// Colour range of a field and whether grey (missing) values occur.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ColorScale {
    /// `None` when no value is finite.
    range: Option<(f64, f64)>,
    missing: bool,
}

impl ColorScale {
    fn color(&self, v: f64) -> RGBColor {
        match self.range {
            Some((lo, hi)) if v.is_finite() => viridis((v - lo) / (hi - lo)),
            _ => MISSING,
        }
    }
}

/// The colour range: the user's if usable, else the range of the finite `values`, padded by
/// 10 % of their magnitude (or 1) when they are all equal.
fn color_scale(values: impl IntoIterator<Item = f64>, user: Option<(f64, f64)>) -> ColorScale {
    let mut missing = false;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values {
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        } else {
            missing = true;
        }
    }
    let usable =
        |(a, b): (f64, f64)| a.is_finite() && b.is_finite() && b > a && (b - a).is_finite();
    let range = if let Some(r) = user.filter(|&r| usable(r)) {
        Some(r)
    } else if lo > hi {
        None
    } else {
        let mag = lo.abs().max(hi.abs());
        if usable((lo, hi)) && hi - lo > 1e-12 * mag {
            Some((lo, hi))
        } else {
            let pad = if mag > 1e-300 { 0.1 * mag } else { 1.0 };
            Some((lo - pad, hi + pad)).filter(|&r| usable(r))
        }
    };
    ColorScale { range, missing }
}

struct PreparedOutline<'a> {
    outline: &'a Outline,
    points: Vec<Option<(f64, f64)>>,
    color: usize,
    drawable: usize,
}

/// A plot reduced to what can be drawn.
struct Mesh<'a> {
    plot: &'a TriangleMeshPlot,
    nodes: Vec<Option<(f64, f64)>>,
    /// Indices (into `plot.triangles`) of the triangles whose three nodes can be drawn.
    drawable: Vec<usize>,
    outlines: Vec<PreparedOutline<'a>>,
    scale: Option<ColorScale>,
}

impl<'a> Mesh<'a> {
    /// Prepares a validated plot.
    fn new(plot: &'a TriangleMeshPlot) -> Self {
        let nodes: Vec<Option<(f64, f64)>> = plot.nodes.iter().map(|&p| point(p)).collect();
        let drawable: Vec<usize> = plot
            .triangles
            .iter()
            .enumerate()
            .filter(|(_, t)| t.iter().all(|&k| nodes.get(k).is_some_and(|p| p.is_some())))
            .map(|(i, _)| i)
            .collect();
        let scale = plot.field.as_ref().map(|f| match &f.values {
            FieldValues::PerTriangle(v) => {
                color_scale(drawable.iter().filter_map(|&i| v.get(i).copied()), f.range)
            }
            FieldValues::PerNode(v) => {
                let mut used = vec![false; nodes.len()];
                for &i in &drawable {
                    for &k in &plot.triangles[i] {
                        used[k] = true;
                    }
                }
                let values = v.iter().zip(&used).filter(|(_, &u)| u).map(|(&x, _)| x);
                color_scale(values, f.range)
            }
        });
        let colors = outline_colors(&plot.outlines, plot.field.is_some());
        let outlines = plot
            .outlines
            .iter()
            .zip(colors)
            .map(|(o, color)| {
                let mut points: Vec<Option<(f64, f64)>> =
                    o.points.iter().map(|&p| point(p)).collect();
                if o.closed && points.len() > 2 {
                    points.push(points[0]);
                }
                let drawable = points.iter().flatten().count();
                PreparedOutline {
                    outline: o,
                    points,
                    color,
                    drawable,
                }
            })
            .collect();
        Mesh {
            plot,
            nodes,
            drawable,
            outlines,
            scale,
        }
    }

    fn has_data(&self) -> bool {
        !self.drawable.is_empty() || self.outlines.iter().any(|o| o.drawable > 0)
    }

    /// Node position of a drawable triangle's corner.
    fn at(&self, k: usize) -> (f64, f64) {
        self.nodes[k].unwrap_or((0.0, 0.0))
    }

    /// Bounding box ((x_lo, x_hi), (y_lo, y_hi)) of the drawable nodes and outline points.
    fn bounds(&self) -> Option<((f64, f64), (f64, f64))> {
        let tri_points = self
            .drawable
            .iter()
            .flat_map(|&i| self.plot.triangles[i].iter().map(|&k| self.at(k)));
        let outline_points = self
            .outlines
            .iter()
            .flat_map(|o| o.points.iter().flatten().copied());
        let mut b: Option<((f64, f64), (f64, f64))> = None;
        for (x, y) in tri_points.chain(outline_points) {
            b = Some(match b {
                None => ((x, x), (y, y)),
                Some(((x0, x1), (y0, y1))) => ((x0.min(x), x1.max(x)), (y0.min(y), y1.max(y))),
            });
        }
        b
    }
}

/// Automatic outline colours: explicit indices as given, automatic ones in `order`, skipping
/// colours chosen explicitly elsewhere while any remain.
fn outline_colors(outlines: &[Outline], over_field: bool) -> Vec<usize> {
    let n = PALETTE.len();
    let order: Vec<usize> = if over_field {
        vec![1, 6, 3, 4, 0, 2, 5, 7]
    } else {
        (0..n).collect()
    };
    let explicit: Vec<usize> = outlines
        .iter()
        .filter_map(|o| o.color.map(|c| c % n))
        .collect();
    let mut next = 0usize;
    outlines
        .iter()
        .map(|o| match o.color {
            Some(c) => c % n,
            None => {
                let free = (0..n)
                    .map(|k| (next + k) % n)
                    .find(|&k| !explicit.contains(&order[k]));
                let k = free.unwrap_or(next % n);
                next = k + 1;
                order[k]
            }
        })
        .collect()
}

/// The axis ranges around a bounding box: padded on every side by 4 % of the larger span
/// (so that thin meshes get visible room too); a single point is padded by 10 % of its
/// magnitude (or 1). No bounds give the unit square.
fn padded_bounds(bounds: Option<((f64, f64), (f64, f64))>) -> ((f64, f64), (f64, f64)) {
    let Some(((x0, x1), (y0, y1))) = bounds else {
        return ((0.0, 1.0), (0.0, 1.0));
    };
    let span = (x1 - x0).max(y1 - y0);
    let mag = [x0, x1, y0, y1].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    // Spans below 1e-200 are treated as a point, so that pixels per unit stay finite.
    let pad = if span > 1e-12 * mag && span > 1e-200 && span.is_finite() {
        0.04 * span
    } else if mag > 1e-200 {
        0.1 * mag
    } else {
        1.0
    };
    ((x0 - pad, x1 + pad), (y0 - pad, y1 + pad))
}

// ---------------------------------------------------------------------------------------------
// Equal-aspect mapping (pixel space)

/// The plot box and the data ranges it shows, with equal scales on both axes.
#[derive(Debug, Clone, Copy, PartialEq)]
struct View {
    rect: Rect,
    x: (f64, f64),
    y: (f64, f64),
}

impl View {
    /// Pixels per data unit (the same along x and y).
    fn scale(&self) -> f64 {
        (self.rect.right - self.rect.left) / (self.x.1 - self.x.0)
    }

    fn px(&self, (x, y): (f64, f64)) -> Px {
        let s = self.scale();
        const LIMIT: f64 = 1e12;
        (
            (self.rect.left + (x - self.x.0) * s).clamp(-LIMIT, LIMIT),
            (self.rect.bottom - (y - self.y.0) * s).clamp(-LIMIT, LIMIT),
        )
    }
}

/// The box always gets at least this fraction of the available width and height: a very
/// elongated mesh widens the shorter range instead of shrinking the box to a sliver.
const MIN_FILL: f64 = 1.0 / 3.0;

/// The largest box inside `avail` (centred in it) showing the ranges `x` × `y` at equal scales
/// on both axes; if that box would be narrower (shorter) than [`MIN_FILL`] of `avail`, the
/// x (y) range is widened about its centre instead. Ranges must be finite with `hi > lo`.
fn fit_equal_aspect(x: (f64, f64), y: (f64, f64), avail: Rect) -> View {
    let aw = (avail.right - avail.left).max(1.0);
    let ah = (avail.bottom - avail.top).max(1.0);
    let (xs, ys) = (x.1 - x.0, y.1 - y.0);
    let s = (aw / xs).min(ah / ys);
    let widen = |(lo, hi): (f64, f64), span: f64, room: f64| -> ((f64, f64), f64) {
        let len = span * s;
        if len >= MIN_FILL * room {
            ((lo, hi), len)
        } else {
            let len = MIN_FILL * room;
            let half = 0.5 * len / s;
            let c = 0.5 * (lo + hi);
            ((c - half, c + half), len)
        }
    };
    let (x, w) = widen(x, xs, aw);
    let (y, h) = widen(y, ys, ah);
    let left = avail.left + 0.5 * (aw - w);
    let top = avail.top + 0.5 * (ah - h);
    View {
        rect: Rect {
            left,
            top,
            right: left + w,
            bottom: top + h,
        },
        x,
        y,
    }
}

// ---------------------------------------------------------------------------------------------
// Layout of one cell

const BAR_GAP: f64 = 18.0;
const BAR_WIDTH: f64 = 16.0;
const BAR_TICK: f64 = 5.0;
const PIXELS_PER_TICK: f64 = 70.0;
const LEGEND_SAMPLE: f64 = 30.0;
const LEGEND_GAP: f64 = 8.0;
const LEGEND_SPACING: f64 = 20.0;
/// Per-node fields split triangles of at least this area (px²) into four.
const SUBDIVIDE_AREA: f64 = 48.0;

/// Compact value label: four significant digits without trailing zeros (`6.562`, `49.22`,
/// `12346`), scientific outside 1e-3…1e5 (`1.235e-5`).
fn compact(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v.is_nan() {
            "NaN".into()
        } else if v == 0.0 {
            "0".into()
        } else {
            format!("{v}")
        };
    }
    let a = v.abs();
    let trim = |s: String| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if (1e-3..1e5).contains(&a) {
        let d = (3 - a.log10().floor() as i32).max(0) as usize;
        let s = trim(format!("{v:.d$}"));
        if s == "-0" {
            "0".into()
        } else {
            s
        }
    } else {
        let s = format!("{v:.3e}");
        match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", trim(m.to_string())),
            None => s,
        }
    }
}

/// The colour bar of a field: its box and labelled values.
struct Bar {
    rect: Rect,
    title_size: f64,
    /// Left end of the title: over the bar, moved left as far as needed to stay in the cell
    /// (the band above the plot box is free for it).
    title_x: f64,
    /// (value, label) from bottom to top; empty when no value is finite.
    labels: Vec<(f64, String)>,
}

/// Labels of a colour bar over `range` drawn `len` pixels long: the ends in compact form, and
/// round values between them that keep clear of the end labels.
fn bar_labels(range: Option<(f64, f64)>, len: f64) -> Vec<(f64, String)> {
    let Some((lo, hi)) = range else {
        return Vec::new();
    };
    let label_h = text_size("0", TICK_SIZE).1;
    let clear = (label_h + 4.0) / len.max(1.0) * (hi - lo);
    let axis = build_axis(
        Scale::Linear,
        (lo, hi),
        (len / PIXELS_PER_TICK).clamp(2.0, 5.0) as usize,
    );
    let mut labels = vec![(lo, compact(lo))];
    labels.extend(
        axis.major
            .into_iter()
            .filter(|(t, _)| *t - lo > clear && hi - *t > clear),
    );
    labels.push((hi, compact(hi)));
    labels
}

/// Everything about a cell that depends only on the plot and the cell size.
struct Layout {
    view: View,
    x_axis: Axis,
    y_axis: Axis,
    title_size: f64,
    y_tick_w: f64,
    bar: Option<Bar>,
    /// Legend rows below the plot: entry indices into the outlines, and the row width.
    legend: Vec<(Vec<usize>, f64)>,
}

fn shrink_to_fit(text: &str, size: f64, width: f64) -> f64 {
    let mut size = size;
    while size > 10.0 && text_size(text, size).0 > width {
        size -= 1.0;
    }
    size
}

/// Legend entry width (sample line, gap, name).
fn legend_entry_width(text: &str) -> f64 {
    LEGEND_SAMPLE + LEGEND_GAP + text_size(text, LEGEND_SIZE).0
}

fn legend_text(o: &PreparedOutline) -> String {
    if o.drawable == 0 {
        format!("{} (no data)", o.outline.name)
    } else {
        o.outline.name.clone()
    }
}

fn tick_width(axis: &Axis) -> f64 {
    axis.major
        .iter()
        .map(|(_, l)| text_size(l, TICK_SIZE).0)
        .fold(0.0, f64::max)
}

fn axes_for(view: &View) -> (Axis, Axis) {
    let r = view.rect;
    let n = |len: f64| (len / PIXELS_PER_TICK).clamp(2.0, 10.0) as usize;
    (
        build_axis(Scale::Linear, view.x, n(r.right - r.left)),
        build_axis(Scale::Linear, view.y, n(r.bottom - r.top)),
    )
}

/// Lays out a cell of `(w, h)` pixels.
fn layout(mesh: &Mesh, (w, h): (f64, f64)) -> Layout {
    let plot = mesh.plot;
    let (x_range, y_range) = padded_bounds(mesh.bounds());
    let title_size = shrink_to_fit(&plot.title, TITLE_SIZE, w - 20.0);
    let title_h = if plot.title.is_empty() {
        0.0
    } else {
        text_size("Ag", title_size).1
    };
    let tick_h = text_size("0", TICK_SIZE).1;
    let label_h = text_size("Ag", LABEL_SIZE).1;

    // Legend rows (below the axis label), wrapped to the cell width.
    let mut legend: Vec<(Vec<usize>, f64)> = Vec::new();
    for (i, o) in mesh.outlines.iter().enumerate() {
        if o.outline.name.is_empty() {
            continue;
        }
        let ew = legend_entry_width(&legend_text(o));
        match legend.last_mut() {
            Some((row, rw)) if *rw + LEGEND_SPACING + ew <= w - 20.0 => {
                row.push(i);
                *rw += LEGEND_SPACING + ew;
            }
            _ => legend.push((vec![i], ew)),
        }
    }
    let legend_row_h = text_size("Ag", LEGEND_SIZE).1 + 6.0;

    // Colour bar: title above it, labels to its right.
    let bar_parts = mesh
        .scale
        .filter(|_| !mesh.drawable.is_empty())
        .map(|scale| {
            let name = plot.field.as_ref().map_or("", |f| f.name.as_str());
            let size = shrink_to_fit(name, LEGEND_SIZE, w - 20.0);
            let title_h = if name.is_empty() {
                0.0
            } else {
                text_size("Ag", size).1
            };
            let title_w = text_size(name, size).0;
            (scale, size, title_h, title_w)
        });

    let top = 10.0 + if title_h > 0.0 { title_h + 12.0 } else { 0.0 };
    let band = bar_parts.map_or(0.0, |(_, _, th, _)| if th > 0.0 { th + 10.0 } else { 0.0 });
    let mut bottom_margin = 6.0 + 3.0 + tick_h + 10.0;
    if !plot.x_label.is_empty() {
        bottom_margin += label_h + 8.0;
    }
    if !legend.is_empty() {
        bottom_margin += legend_row_h * legend.len() as f64 + 4.0;
    }
    let y_label_w = if plot.y_label.is_empty() {
        0.0
    } else {
        label_h + 10.0
    };
    let avail_top = top + band;
    let avail_bottom = (h - bottom_margin).max(avail_top + 20.0);

    // The bar's labels depend on its length (= the box height), which depends on the width
    // left for the box; the widest label of the available height bounds them.
    let bar_w_for = |len: f64| {
        bar_parts.map_or(20.0, |(scale, _, _, _)| {
            let labels_w = bar_labels(scale.range, len)
                .iter()
                .map(|(_, l)| text_size(l, TICK_SIZE).0)
                .chain(std::iter::once(if scale.missing {
                    text_size("NaN", TICK_SIZE).0 + 6.0
                } else {
                    0.0
                }))
                .fold(0.0, f64::max);
            BAR_GAP + BAR_WIDTH + BAR_TICK + 4.0 + labels_w + 12.0
        })
    };

    // Two passes: margins from estimated ticks, then from the ticks of the fitted box.
    let mut left_w = 10.0 + y_label_w + 30.0 + 9.0;
    let mut right_w = bar_w_for(avail_bottom - avail_top);
    let mut view = fit_equal_aspect(
        x_range,
        y_range,
        Rect {
            left: left_w,
            top: avail_top,
            right: (w - right_w).max(left_w + 20.0),
            bottom: avail_bottom,
        },
    );
    for _ in 0..2 {
        let (_, y_axis) = axes_for(&view);
        left_w = 10.0 + y_label_w + tick_width(&y_axis) + 9.0;
        right_w = bar_w_for(view.rect.bottom - view.rect.top);
        view = fit_equal_aspect(
            x_range,
            y_range,
            Rect {
                left: left_w,
                top: avail_top,
                right: (w - right_w).max(left_w + 20.0),
                bottom: avail_bottom,
            },
        );
    }
    // Centre the group (y labels, box, colour bar) horizontally in the cell.
    let group_w = left_w + (view.rect.right - view.rect.left) + right_w;
    let shift = 0.5 * (w - group_w) + left_w - view.rect.left;
    if shift.is_finite() {
        view.rect.left += shift;
        view.rect.right += shift;
    }
    let (x_axis, y_axis) = axes_for(&view);
    let y_tick_w = tick_width(&y_axis);
    let bar = bar_parts.map(|(scale, title_size, _, title_w)| {
        let rect = Rect {
            left: view.rect.right + BAR_GAP,
            top: view.rect.top,
            right: view.rect.right + BAR_GAP + BAR_WIDTH,
            bottom: view.rect.bottom,
        };
        Bar {
            rect,
            title_size,
            title_x: rect.left.min(w - 10.0 - title_w).max(10.0),
            labels: bar_labels(scale.range, rect.bottom - rect.top),
        }
    });
    Layout {
        view,
        x_axis,
        y_axis,
        title_size,
        y_tick_w,
        bar,
        legend,
    }
}

// ---------------------------------------------------------------------------------------------
// Drawing

/// Renders `plots` in a grid of `columns` columns, each cell `cell` pixels, into an SVG string.
/// `path` only names the target in errors.
fn render(
    plots: &[TriangleMeshPlot],
    columns: usize,
    cell: (u32, u32),
    path: &Path,
) -> Result<String, PlotError> {
    for plot in plots {
        validate(plot, path)?;
    }
    ensure_font()?;
    let n = plots.len().max(1);
    let cols = columns.clamp(1, n);
    let rows = n.div_ceil(cols);
    let size = (
        cell.0.saturating_mul(cols as u32),
        cell.1.saturating_mul(rows as u32),
    );
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, size).into_drawing_area();
        draw_grid(&root, plots, rows, cols).map_err(|e| PlotError::Drawing {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    }
    Ok(seal_polygons(&buf))
}

/// Gives every opaque filled polygon (the triangles: nothing else in these plots is a polygon)
/// a thin stroke of its own colour, and groups runs of them under one `<g>` setting the stroke
/// width. Without it, anti-aliasing leaves light seams along shared edges, the background
/// showing through where two triangles each cover half a pixel. Also makes line joins round
/// (on the root element, inherited), so that wireframe paths turning sharply at the boundary
/// do not end in miter spikes. Works on the lines plotters' SVG backend writes
/// (`<svg width=…>`, `<polygon opacity="1" fill="#RRGGBB" points="…"/>`); anything else is
/// copied unchanged.
fn seal_polygons(svg: &str) -> String {
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

fn draw_grid<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    plots: &[TriangleMeshPlot],
    rows: usize,
    cols: usize,
) -> DrawResult<DB> {
    root.fill(&RGBColor(255, 255, 255))?;
    let cells = root.split_evenly((rows, cols));
    for (plot, cell) in plots.iter().zip(cells.iter()) {
        draw_plot(cell, plot)?;
    }
    root.present()
}

/// Fills a triangle given in pixels, skipping those that round to zero area.
fn fill_triangle<DB: DrawingBackend>(
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

fn midpoint(a: Px, b: Px) -> Px {
    (0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1))
}

/// Draws the filled triangles: coloured by the field, or light grey without field and wireframe.
fn draw_fills<DB: DrawingBackend>(
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
fn edge_paths(
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

fn draw_wireframe<DB: DrawingBackend>(
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

fn draw_plot<DB: DrawingBackend>(
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
    for (t, _) in &lay.x_axis.major {
        let x = px_x(*t);
        draw_polyline(area, &[(x, r.top), (x, r.bottom)], stroke(GRID_MAJOR, 1))?;
    }
    for (t, _) in &lay.y_axis.major {
        let y = px_y(*t);
        draw_polyline(area, &[(r.left, y), (r.right, y)], stroke(GRID_MAJOR, 1))?;
    }
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
    for (t, label) in &lay.x_axis.major {
        let x = px_x(*t);
        draw_polyline(area, &[(x, r.bottom), (x, r.bottom + 6.0)], stroke(TEXT, 1))?;
        draw_text_anchored(
            area,
            label,
            TICK_SIZE,
            (HPos::Center, VPos::Top),
            (x, r.bottom + 9.0),
        )?;
    }
    for (t, label) in &lay.y_axis.major {
        let y = px_y(*t);
        draw_polyline(area, &[(r.left - 6.0, y), (r.left, y)], stroke(TEXT, 1))?;
        draw_text_anchored(
            area,
            label,
            TICK_SIZE,
            (HPos::Right, VPos::Center),
            (r.left - 9.0, y),
        )?;
    }

    if let (Some(bar), Some(scale)) = (&lay.bar, mesh.scale) {
        draw_bar(
            area,
            bar,
            &scale,
            plot.field.as_ref().map_or("", |f| f.name.as_str()),
        )?;
    }

    if !mesh.has_data() {
        let style = text_style(NOTE_SIZE + 4.0)
            .color(&NOTE)
            .pos(Pos::new(HPos::Center, VPos::Center));
        area.draw_text(
            "no data",
            &style,
            ipx(((r.left + r.right) / 2.0, (r.top + r.bottom) / 2.0)),
        )?;
    }

    // Title, axis labels, legend.
    if !plot.title.is_empty() {
        draw_text_anchored(
            area,
            &plot.title,
            lay.title_size,
            (HPos::Center, VPos::Top),
            (w / 2.0, 10.0),
        )?;
    }
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
        let style = text_style(LABEL_SIZE)
            .color(&TEXT)
            .transform(FontTransform::Rotate270)
            .pos(Pos::new(HPos::Center, VPos::Top));
        let x = r.left - 9.0 - lay.y_tick_w - 10.0 - label_h;
        area.draw_text(&plot.y_label, &style, ipx((x, (r.top + r.bottom) / 2.0)))?;
    }
    draw_legend(area, &mesh, &lay, below, w)
}

/// Draws the colour bar: a gradient of one-pixel rows, its frame, labels, title and, when some
/// values are missing, a grey "NaN" swatch below it.
fn draw_bar<DB: DrawingBackend>(
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
fn draw_legend<DB: DrawingBackend>(
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

#[cfg(test)]
mod tests {
    // Setting: small structured meshes rendered to strings (and a few files in the temp folder).
    // Goal: pin colour-bar labels, NaN handling, typed errors, equal aspect, "no data",
    // determinism and that a 96×96 mesh renders compactly.
    use super::*;
    use std::time::Instant;

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
        let plot = TriangleMeshPlot::new("96×96", nodes, tris)
            .field(TriangleField::per_triangle("s", values));
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
}
