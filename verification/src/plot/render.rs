//! Drawing a [`Figure`] onto a plotters drawing area, in pixel space.
//!
//! Everything is laid out and clipped here (axes, grid, ticks, series, reference lines, legend),
//! so that the output does not depend on plotters' own chart heuristics and never sees a
//! non-finite coordinate.

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::drawing::{DrawingArea, DrawingAreaErrorKind, IntoDrawingArea};
use plotters::element::{Circle, PathElement, Polygon, Rectangle};
use plotters::prelude::{DrawingBackend, SVGBackend};
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{
    register_font, FontStyle, FontTransform, IntoFont, RGBAColor, RGBColor, ShapeStyle, TextStyle,
};

use super::axis::{auto_range, build_axis, to_axis, user_range, Axis};
use super::geom::{clip_segment, clipped_polylines, dashes, ipx, samples, Px, Rect};
use super::{Figure, PlotError, Scale, Series};

/// Okabe–Ito colour-blind-friendly palette, most distinguishable first.
pub(crate) const PALETTE: [RGBColor; 8] = [
    RGBColor(0x00, 0x72, 0xB2), // blue
    RGBColor(0xD5, 0x5E, 0x00), // vermillion
    RGBColor(0x00, 0x9E, 0x73), // bluish green
    RGBColor(0xCC, 0x79, 0xA7), // reddish purple
    RGBColor(0xE6, 0x9F, 0x00), // orange
    RGBColor(0x56, 0xB4, 0xE9), // sky blue
    RGBColor(0x00, 0x00, 0x00), // black
    RGBColor(0xF0, 0xE4, 0x42), // yellow
];

const FONT_FAMILY: &str = "sans-serif";
const FONT_BYTES: &[u8] = include_bytes!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/assets/DejaVuSans.ttf"
));

// Font sizes in plotters units (the SVG font-size is this / 1.24).
pub(super) const TITLE_SIZE: f64 = 21.0;
pub(super) const LABEL_SIZE: f64 = 18.0;
pub(super) const TICK_SIZE: f64 = 16.0;
pub(super) const LEGEND_SIZE: f64 = 16.0;
pub(super) const NOTE_SIZE: f64 = 16.0;

pub(super) const TEXT: RGBColor = RGBColor(0x20, 0x20, 0x20);
pub(super) const GRID_MAJOR: RGBColor = RGBColor(0xD9, 0xD9, 0xD9);
const GRID_MINOR: RGBColor = RGBColor(0xEE, 0xEE, 0xEE);
const GUIDE: RGBColor = RGBColor(0x44, 0x44, 0x44);
pub(super) const NOTE: RGBColor = RGBColor(0x80, 0x80, 0x80);

/// log10(2): the reference slopes sit a factor 2 below their anchor point.
const LOG10_2: f64 = std::f64::consts::LOG10_2;
/// Pixel coordinates are clamped to this magnitude before clipping.
const PIXEL_LIMIT: f64 = 1e12;

pub(super) type DrawResult<DB> =
    Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// Registers the embedded font once; every later call returns the first outcome.
pub(super) fn ensure_font() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED
        .get_or_init(|| register_font(FONT_FAMILY, FontStyle::Normal, FONT_BYTES).is_ok());
    if ok {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}

/// Renders `figures` in a grid of `columns` columns, each cell `cell` pixels, into an SVG string.
/// `path` only names the target in errors.
pub(crate) fn render(
    figures: &[Figure],
    columns: usize,
    cell: (u32, u32),
    path: &Path,
) -> Result<String, PlotError> {
    ensure_font()?;
    let n = figures.len().max(1);
    let cols = columns.clamp(1, n);
    let rows = n.div_ceil(cols);
    let size = (
        cell.0.saturating_mul(cols as u32),
        cell.1.saturating_mul(rows as u32),
    );
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, size).into_drawing_area();
        draw_grid(&root, figures, rows, cols).map_err(|e| PlotError::Drawing {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    }
    Ok(buf)
}

fn draw_grid<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    figures: &[Figure],
    rows: usize,
    cols: usize,
) -> DrawResult<DB> {
    root.fill(&RGBColor(255, 255, 255))?;
    let cells = root.split_evenly((rows, cols));
    for (figure, cell) in figures.iter().zip(cells.iter()) {
        draw_figure(cell, figure)?;
    }
    root.present()
}

// ---------------------------------------------------------------------------------------------
// Text helpers

pub(super) fn text_style(size: f64) -> TextStyle<'static> {
    TextStyle::from((FONT_FAMILY, size).into_font())
}

/// Estimated (width, height) of `text` in pixels.
pub(super) fn text_size(text: &str, size: f64) -> (f64, f64) {
    match (FONT_FAMILY, size).into_font().box_size(text) {
        Ok((w, h)) => (f64::from(w), f64::from(h)),
        Err(_) => (0.6 * size * text.chars().count() as f64, size / 1.24),
    }
}

/// Draws `text` with its top-left corner at `p`.
fn draw_text_at<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    size: f64,
    color: &RGBColor,
    p: Px,
) -> DrawResult<DB> {
    let style = text_style(size)
        .color(color)
        .pos(Pos::new(HPos::Left, VPos::Top));
    area.draw_text(text, &style, ipx(p))
}

pub(super) fn draw_text_anchored<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    size: f64,
    anchor: (HPos, VPos),
    p: Px,
) -> DrawResult<DB> {
    let style = text_style(size)
        .color(&TEXT)
        .pos(Pos::new(anchor.0, anchor.1));
    area.draw_text(text, &style, ipx(p))
}

// ---------------------------------------------------------------------------------------------
// Shapes

pub(super) fn stroke(color: RGBColor, width: u32) -> ShapeStyle {
    ShapeStyle {
        color: color.into(),
        filled: false,
        stroke_width: width,
    }
}

pub(super) fn fill(color: RGBAColor) -> ShapeStyle {
    ShapeStyle {
        color,
        filled: true,
        stroke_width: 1,
    }
}

pub(super) fn draw_polyline<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    line: &[Px],
    style: ShapeStyle,
) -> DrawResult<DB> {
    if line.len() < 2 {
        return Ok(());
    }
    let pts: Vec<(i32, i32)> = line.iter().map(|&p| ipx(p)).collect();
    area.draw(&PathElement::new(pts, style))
}

/// Draws a polyline solid, or dashed with (on, off) pixel lengths.
pub(super) fn draw_line<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    line: &[Px],
    style: ShapeStyle,
    dash: Option<(f64, f64)>,
) -> DrawResult<DB> {
    match dash {
        None => draw_polyline(area, line, style),
        Some((on, off)) => {
            for d in dashes(line, on, off) {
                draw_polyline(area, &d, style)?;
            }
            Ok(())
        }
    }
}

pub(super) fn draw_rect<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    r: &Rect,
    style: ShapeStyle,
) -> DrawResult<DB> {
    area.draw(&Rectangle::new(
        [ipx((r.left, r.top)), ipx((r.right, r.bottom))],
        style,
    ))
}

/// Marker shapes, cycled with the colour index so that series differ without colour too.
fn draw_marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    p: Px,
    color_index: usize,
) -> DrawResult<DB> {
    const R: i32 = 4;
    let color = PALETTE[color_index % PALETTE.len()];
    let style = fill(color.into());
    let (x, y) = ipx(p);
    match color_index % 6 {
        0 => area.draw(&Circle::new((x, y), R, style)),
        1 => area.draw(&Rectangle::new(
            [(x - R + 1, y - R + 1), (x + R - 1, y + R - 1)],
            style,
        )),
        2 => area.draw(&Polygon::new(
            vec![(x, y - R - 1), (x + R, y + R - 1), (x - R, y + R - 1)],
            style,
        )),
        3 => area.draw(&Polygon::new(
            vec![(x, y - R - 1), (x + R, y), (x, y + R + 1), (x - R, y)],
            style,
        )),
        4 => area.draw(&Polygon::new(
            vec![(x, y + R + 1), (x + R, y - R + 1), (x - R, y - R + 1)],
            style,
        )),
        _ => {
            let s = stroke(color, 2);
            area.draw(&PathElement::new(vec![(x - R, y - R), (x + R, y + R)], s))?;
            area.draw(&PathElement::new(vec![(x - R, y + R), (x + R, y - R)], s))
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Data preparation (axis space)

/// A series mapped to axis space.
struct Prepared<'a> {
    series: &'a Series,
    color: usize,
    /// Points in axis space; `None` for points that cannot be drawn on these scales.
    points: Vec<Option<(f64, f64)>>,
    drawable: usize,
}

/// Maps every series of the figure to axis space and gives it its colour.
fn prepare(figure: &Figure) -> Vec<Prepared<'_>> {
    let colors = assign_colors(&figure.series);
    figure
        .series
        .iter()
        .zip(colors)
        .map(|(s, color)| {
            let points: Vec<Option<(f64, f64)>> = s
                .points
                .iter()
                .map(|&(x, y)| Some((to_axis(figure.x_scale, x)?, to_axis(figure.y_scale, y)?)))
                .collect();
            let drawable = points.iter().flatten().count();
            Prepared {
                series: s,
                color,
                points,
                drawable,
            }
        })
        .collect()
}

/// Colour of each series: explicit indices as given, automatic ones in palette order,
/// skipping colours chosen explicitly elsewhere while any remain.
fn assign_colors(series: &[Series]) -> Vec<usize> {
    let n = PALETTE.len();
    let explicit: Vec<usize> = series
        .iter()
        .filter_map(|s| s.style.color.map(|c| c % n))
        .collect();
    let mut next = 0usize;
    series
        .iter()
        .map(|s| match s.style.color {
            Some(c) => c % n,
            None => {
                let free = (0..n)
                    .map(|k| (next + k) % n)
                    .find(|c| !explicit.contains(c));
                let c = free.unwrap_or(next % n);
                next = c + 1;
                c
            }
        })
        .collect()
}

/// A reference slope line in axis space.
struct RefLine<'a> {
    label: &'a str,
    from: (f64, f64),
    to: (f64, f64),
}

/// What a series offers as an anchor for reference slopes (log–log axis space).
struct Anchor {
    /// The smallest-x drawable point (the first of them on ties).
    finest: (f64, f64),
    /// Largest drawable x.
    x_max: f64,
    /// Least-squares slope of the drawable points, if they have distinct x.
    slope: Option<f64>,
}

fn anchor_of(points: &[Option<(f64, f64)>]) -> Option<Anchor> {
    let pts: Vec<(f64, f64)> = points.iter().flatten().copied().collect();
    let &finest = pts.iter().reduce(|a, b| if b.0 < a.0 { b } else { a })?;
    let x_max = pts.iter().map(|p| p.0).fold(finest.0, f64::max);
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let slope = (sxx > 1e-18).then(|| sxy / sxx).filter(|s| s.is_finite());
    Some(Anchor {
        finest,
        x_max,
        slope,
    })
}

/// Reference lines, each a factor 2 below the finest (smallest-x) point of an anchor series and
/// spanning that series' x range (one decade if it has a single x). The anchor is, among the
/// series whose fitted log–log slope is within 0.3 of the fitted slope nearest the reference
/// slope, the one giving the lowest line (so the line runs under all of them); failing any
/// fitted slope, the first series with a drawable point.
fn reference_lines<'a>(figure: &'a Figure, prepared: &[Prepared]) -> Vec<RefLine<'a>> {
    if figure.x_scale != Scale::Log || figure.y_scale != Scale::Log {
        return Vec::new();
    }
    let anchors: Vec<Anchor> = prepared
        .iter()
        .filter_map(|s| anchor_of(&s.points))
        .collect();
    let Some(first) = anchors.first() else {
        return Vec::new();
    };
    figure
        .reference_slopes
        .iter()
        .filter(|r| r.slope.is_finite())
        .filter_map(|r| {
            let p = r.slope;
            let intercept = |a: &&Anchor| a.finest.1 - p * a.finest.0;
            let misfit = |a: &&Anchor| a.slope.map_or(f64::INFINITY, |s| (s - p).abs());
            let best = anchors
                .iter()
                .map(|a| misfit(&a))
                .fold(f64::INFINITY, f64::min);
            let anchor = anchors
                .iter()
                .filter(|a| best.is_finite() && misfit(a) <= best + 0.3)
                .min_by(|a, b| intercept(a).total_cmp(&intercept(b)))
                .unwrap_or(first);
            let (x0, y0) = anchor.finest;
            let x1 = if anchor.x_max - x0 < 1e-9 {
                x0 + 1.0
            } else {
                anchor.x_max
            };
            let ya = y0 - LOG10_2;
            let yb = ya + p * (x1 - x0);
            (yb.is_finite() && (-330.0..=310.0).contains(&yb)).then_some(RefLine {
                label: &r.label,
                from: (x0, ya),
                to: (x1, yb),
            })
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// The figure

/// Pixel mapping of the plot area.
struct Frame {
    rect: Rect,
    x: Axis,
    y: Axis,
}

impl Frame {
    fn px(&self, (tx, ty): (f64, f64)) -> Px {
        let w = self.rect.right - self.rect.left;
        let h = self.rect.bottom - self.rect.top;
        let x = self.rect.left + self.x.fraction(tx) * w;
        let y = self.rect.bottom - self.y.fraction(ty) * h;
        (
            x.clamp(-PIXEL_LIMIT, PIXEL_LIMIT),
            y.clamp(-PIXEL_LIMIT, PIXEL_LIMIT),
        )
    }
    fn px_x(&self, tx: f64) -> f64 {
        self.px((tx, self.y.lo)).0
    }
    fn px_y(&self, ty: f64) -> f64 {
        self.px((self.x.lo, ty)).1
    }
}

/// A text label placed in the plot: top-left corner and size.
struct Label<'a> {
    text: &'a str,
    at: Px,
    size: (f64, f64),
}

impl Label<'_> {
    fn rect(&self) -> Rect {
        Rect {
            left: self.at.0,
            top: self.at.1,
            right: self.at.0 + self.size.0,
            bottom: self.at.1 + self.size.1,
        }
    }
}

/// The label at the first of `candidates` (top-left corners, moved inside `r`) whose box
/// covers the fewest `obstacles`.
fn place_label<'t>(
    text: &'t str,
    size: (f64, f64),
    candidates: &[Px],
    r: &Rect,
    obstacles: &[Px],
) -> Label<'t> {
    let mut best: Option<(usize, Px)> = None;
    for &c in candidates {
        let at = keep_inside(c, size, r);
        let rect = Label { text, at, size }.rect();
        let covered = obstacles.iter().filter(|p| rect.contains(**p, 2.0)).count();
        if best.is_none_or(|(n, _)| covered < n) {
            best = Some((covered, at));
        }
    }
    let at = best.map_or_else(|| keep_inside((r.left, r.top), size, r), |(_, at)| at);
    Label { text, at, size }
}

/// Points covering a rectangle about every `step` pixels.
fn box_samples(b: &Rect, step: f64) -> Vec<Px> {
    let nx = ((b.right - b.left) / step).ceil().clamp(1.0, 1000.0) as usize;
    let ny = ((b.bottom - b.top) / step).ceil().clamp(1.0, 1000.0) as usize;
    (0..=ny)
        .flat_map(|j| {
            (0..=nx).map(move |i| {
                (
                    b.left + (b.right - b.left) * i as f64 / nx as f64,
                    b.top + (b.bottom - b.top) * j as f64 / ny as f64,
                )
            })
        })
        .collect()
}

/// Moves a `size` box with top-left `at` inside `r` (2 px inset) where possible.
fn keep_inside(at: Px, size: (f64, f64), r: &Rect) -> Px {
    let x = at.0.min(r.right - 2.0 - size.0).max(r.left + 2.0);
    let y = at.1.min(r.bottom - 2.0 - size.1).max(r.top + 2.0);
    (x, y)
}

fn draw_figure<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    figure: &Figure,
) -> DrawResult<DB> {
    let (w, h) = area.dim_in_pixel();
    let (w, h) = (f64::from(w), f64::from(h));

    // Data in axis space.
    let prepared = prepare(figure);
    let has_data = prepared.iter().any(|s| s.drawable > 0);
    let refs = reference_lines(figure, &prepared);
    let vlines: Vec<(f64, &str)> = figure
        .vertical_lines
        .iter()
        .filter_map(|v| Some((to_axis(figure.x_scale, v.x)?, v.label.as_str())))
        .collect();
    let hlines: Vec<(f64, &str)> = figure
        .horizontal_lines
        .iter()
        .filter_map(|l| Some((to_axis(figure.y_scale, l.y)?, l.label.as_str())))
        .collect();

    // Ranges.
    let x_range = user_range(figure.x_scale, figure.x_range).unwrap_or_else(|| {
        let xs: Vec<f64> = prepared
            .iter()
            .flat_map(|s| s.points.iter().flatten().map(|p| p.0))
            .chain(refs.iter().flat_map(|r| [r.from.0, r.to.0]))
            .chain(vlines.iter().map(|v| v.0))
            .collect();
        auto_range(figure.x_scale, &xs)
    });
    let y_range = user_range(figure.y_scale, figure.y_range).unwrap_or_else(|| {
        let in_x = |x: f64| x >= x_range.0 && x <= x_range.1;
        let ys: Vec<f64> = prepared
            .iter()
            .flat_map(|s| s.points.iter().flatten().filter(|p| in_x(p.0)).map(|p| p.1))
            .chain(refs.iter().flat_map(|r| [r.from.1, r.to.1]))
            .chain(hlines.iter().map(|l| l.0))
            .collect();
        auto_range(figure.y_scale, &ys)
    });

    // Layout.
    let mut title_size = TITLE_SIZE;
    while title_size > 10.0 && text_size(&figure.title, title_size).0 > w - 20.0 {
        title_size -= 1.0;
    }
    let title_h = if figure.title.is_empty() {
        0.0
    } else {
        text_size("Ag", title_size).1
    };
    let tick_h = text_size("0", TICK_SIZE).1;
    let label_h = text_size("Ag", LABEL_SIZE).1;
    let top = 10.0 + title_h + 14.0;
    let mut bottom_margin = 6.0 + 6.0 + tick_h + 10.0;
    if !figure.x_label.is_empty() {
        bottom_margin += label_h + 6.0;
    }
    let bottom = (h - bottom_margin).max(top + 10.0);
    let y_axis = build_axis(
        figure.y_scale,
        y_range,
        ((bottom - top) / 45.0).clamp(2.0, 10.0) as usize,
    );
    let y_tick_w = y_axis
        .major
        .iter()
        .map(|(_, l)| text_size(l, TICK_SIZE).0)
        .fold(0.0, f64::max);
    let mut left = 10.0 + y_tick_w + 6.0 + 6.0;
    if !figure.y_label.is_empty() {
        left += label_h + 10.0;
    }
    let right = (w - 28.0).max(left + 10.0);
    let x_axis = build_axis(
        figure.x_scale,
        x_range,
        ((right - left) / 90.0).clamp(2.0, 10.0) as usize,
    );
    let frame = Frame {
        rect: Rect {
            left,
            top,
            right,
            bottom,
        },
        x: x_axis,
        y: y_axis,
    };
    let r = frame.rect;

    // Grid: light lines at unlabelled decades always, at the other minor ticks only when the
    // axis spans few decades (otherwise they would hatch the plot).
    let minor_grid = |axis: &Axis, t: f64| axis.hi - axis.lo <= 3.5 || t.fract() == 0.0;
    for &t in frame.x.minor.iter().filter(|&&t| minor_grid(&frame.x, t)) {
        let x = frame.px_x(t);
        draw_polyline(area, &[(x, r.top), (x, r.bottom)], stroke(GRID_MINOR, 1))?;
    }
    for &t in frame.y.minor.iter().filter(|&&t| minor_grid(&frame.y, t)) {
        let y = frame.px_y(t);
        draw_polyline(area, &[(r.left, y), (r.right, y)], stroke(GRID_MINOR, 1))?;
    }
    for (t, _) in &frame.x.major {
        let x = frame.px_x(*t);
        draw_polyline(area, &[(x, r.top), (x, r.bottom)], stroke(GRID_MAJOR, 1))?;
    }
    for (t, _) in &frame.y.major {
        let y = frame.px_y(*t);
        draw_polyline(area, &[(r.left, y), (r.right, y)], stroke(GRID_MAJOR, 1))?;
    }

    // Geometry in pixels. Everything drawn inside the plot is also sampled into `obstacles`,
    // which the labels and then the legend try not to cover.
    let mut obstacles: Vec<Px> = Vec::new();
    let vertical: Vec<([Px; 2], &str)> = vlines
        .iter()
        .map(|&(t, label)| (frame.px_x(t), label))
        .filter(|&(x, _)| x >= r.left - 0.5 && x <= r.right + 0.5)
        .map(|(x, label)| ([(x, r.top), (x, r.bottom)], label))
        .collect();
    let horizontal: Vec<([Px; 2], &str)> = hlines
        .iter()
        .map(|&(t, label)| (frame.px_y(t), label))
        .filter(|&(y, _)| y >= r.top - 0.5 && y <= r.bottom + 0.5)
        .map(|(y, label)| ([(r.left, y), (r.right, y)], label))
        .collect();
    let slopes: Vec<([Px; 2], &str)> = refs
        .iter()
        .filter_map(|rl| {
            let (a, b) = clip_segment(frame.px(rl.from), frame.px(rl.to), &r)?;
            Some(([a, b], rl.label))
        })
        .collect();
    for (line, _) in vertical.iter().chain(&horizontal).chain(&slopes) {
        obstacles.extend(samples(line, 3.0));
    }
    // Per series: visible polylines (if drawn as lines) and visible marker positions.
    let drawn: Vec<(Vec<Vec<Px>>, Vec<Px>)> = prepared
        .iter()
        .map(|s| {
            let pts: Vec<Option<Px>> = s.points.iter().map(|p| p.map(|p| frame.px(p))).collect();
            let style = s.series.style;
            let lines = if style.line || !style.markers {
                clipped_polylines(&pts, &r)
            } else {
                Vec::new()
            };
            let marks: Vec<Px> = if style.markers {
                pts.iter()
                    .flatten()
                    .copied()
                    .filter(|p| r.contains(*p, 0.5))
                    .collect()
            } else {
                Vec::new()
            };
            (lines, marks)
        })
        .collect();
    for (lines, marks) in &drawn {
        for line in lines {
            obstacles.extend(samples(line, 3.0));
        }
        obstacles.extend(marks);
    }

    // Marker lines and reference slopes, behind the data.
    for (line, _) in vertical.iter().chain(&horizontal) {
        draw_line(area, line, stroke(GUIDE, 2), Some((6.0, 4.0)))?;
    }
    for (line, _) in &slopes {
        draw_line(area, line, stroke(GUIDE, 2), Some((8.0, 5.0)))?;
    }

    // Series.
    for (s, (lines, marks)) in prepared.iter().zip(&drawn) {
        let dash = s.series.style.dashed.then_some((8.0, 5.0));
        for line in lines {
            draw_line(area, line, stroke(PALETTE[s.color], 2), dash)?;
        }
        for p in marks {
            draw_marker(area, *p, s.color)?;
        }
    }

    // Labels of marker lines and slopes, each where it covers the fewest obstacles.
    let mut labels: Vec<Label> = Vec::new();
    fn place<'t>(
        text: &'t str,
        candidates: &[Px],
        r: &Rect,
        obstacles: &mut Vec<Px>,
    ) -> Option<Label<'t>> {
        if text.is_empty() {
            return None;
        }
        let size = text_size(text, NOTE_SIZE);
        let label = place_label(text, size, candidates, r, obstacles);
        obstacles.extend(box_samples(&label.rect(), 4.0));
        Some(label)
    }
    for ([p, _], text) in &vertical {
        let size = text_size(text, NOTE_SIZE);
        let (x, top, bottom) = (p.0, r.top + 5.0, r.bottom - 5.0 - size.1);
        let candidates = [
            (x + 5.0, top),
            (x - 5.0 - size.0, top),
            (x + 5.0, bottom),
            (x - 5.0 - size.0, bottom),
        ];
        labels.extend(place(text, &candidates, &r, &mut obstacles));
    }
    for ([p, _], text) in &horizontal {
        let size = text_size(text, NOTE_SIZE);
        let (y, right, left) = (p.1, r.right - 5.0 - size.0, r.left + 5.0);
        let candidates = [
            (right, y - 4.0 - size.1),
            (right, y + 4.0),
            (left, y - 4.0 - size.1),
            (left, y + 4.0),
        ];
        labels.extend(place(text, &candidates, &r, &mut obstacles));
    }
    for ([a, b], text) in &slopes {
        // Beside the line with the box corner nearest the line just off it, so that the text
        // never crosses it; preferably under it (away from the data it was offset from).
        let size = text_size(text, NOTE_SIZE);
        let rising = b.1 <= a.1;
        let mut candidates = Vec::new();
        for below in [true, false] {
            for f in [0.6, 0.4, 0.75, 0.25, 0.5, 0.9, 0.1] {
                let p = (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1));
                candidates.push(match (rising, below) {
                    (true, true) => (p.0 + 5.0, p.1 + 5.0),
                    (false, true) => (p.0 - 5.0 - size.0, p.1 + 5.0),
                    (true, false) => (p.0 - 5.0 - size.0, p.1 - 5.0 - size.1),
                    (false, false) => (p.0 + 5.0, p.1 - 5.0 - size.1),
                });
            }
        }
        labels.extend(place(text, &candidates, &r, &mut obstacles));
    }

    // Frame, ticks and tick labels.
    draw_rect(area, &r, stroke(TEXT, 1))?;
    for &t in &frame.x.minor {
        let x = frame.px_x(t);
        draw_polyline(area, &[(x, r.bottom), (x, r.bottom + 3.0)], stroke(TEXT, 1))?;
    }
    for &t in &frame.y.minor {
        let y = frame.px_y(t);
        draw_polyline(area, &[(r.left - 3.0, y), (r.left, y)], stroke(TEXT, 1))?;
    }
    for (t, label) in &frame.x.major {
        let x = frame.px_x(*t);
        draw_polyline(area, &[(x, r.bottom), (x, r.bottom + 6.0)], stroke(TEXT, 1))?;
        draw_text_anchored(
            area,
            label,
            TICK_SIZE,
            (HPos::Center, VPos::Top),
            (x, r.bottom + 9.0),
        )?;
    }
    for (t, label) in &frame.y.major {
        let y = frame.px_y(*t);
        draw_polyline(area, &[(r.left - 6.0, y), (r.left, y)], stroke(TEXT, 1))?;
        draw_text_anchored(
            area,
            label,
            TICK_SIZE,
            (HPos::Right, VPos::Center),
            (r.left - 9.0, y),
        )?;
    }

    // Annotation labels, on a light halo.
    for l in &labels {
        let b = l.rect();
        let halo = Rect {
            left: b.left - 2.0,
            top: b.top - 1.0,
            right: b.right + 2.0,
            bottom: b.bottom + 2.0,
        };
        draw_rect(area, &halo, fill(RGBAColor(255, 255, 255, 0.75)))?;
        draw_text_at(area, l.text, NOTE_SIZE, &GUIDE, l.at)?;
    }

    // Legend.
    if has_data {
        draw_legend(area, &prepared, &r, &obstacles)?;
    } else {
        let cx = (r.left + r.right) / 2.0;
        let cy = (r.top + r.bottom) / 2.0;
        let style = text_style(NOTE_SIZE + 4.0)
            .color(&NOTE)
            .pos(Pos::new(HPos::Center, VPos::Center));
        area.draw_text("no data", &style, ipx((cx, cy)))?;
    }

    // Title and axis labels.
    if !figure.title.is_empty() {
        draw_text_anchored(
            area,
            &figure.title,
            title_size,
            (HPos::Center, VPos::Top),
            (w / 2.0, 10.0),
        )?;
    }
    if !figure.x_label.is_empty() {
        draw_text_anchored(
            area,
            &figure.x_label,
            LABEL_SIZE,
            (HPos::Center, VPos::Bottom),
            ((r.left + r.right) / 2.0, h - 8.0),
        )?;
    }
    if !figure.y_label.is_empty() {
        let style = text_style(LABEL_SIZE)
            .color(&TEXT)
            .transform(FontTransform::Rotate270)
            .pos(Pos::new(HPos::Center, VPos::Top));
        area.draw_text(
            &figure.y_label,
            &style,
            ipx((10.0, (r.top + r.bottom) / 2.0)),
        )?;
    }
    Ok(())
}

/// Draws the legend in the corner of the plot area that hides the fewest obstacle points
/// (ties: upper right, upper left, lower right, lower left).
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    prepared: &[Prepared],
    r: &Rect,
    obstacles: &[Px],
) -> DrawResult<DB> {
    let entries: Vec<(String, &Prepared)> = prepared
        .iter()
        .filter(|s| !s.series.name.is_empty())
        .map(|s| {
            let text = if s.drawable == 0 {
                format!("{} (no data)", s.series.name)
            } else {
                s.series.name.clone()
            };
            (text, s)
        })
        .collect();
    if entries.is_empty() {
        return Ok(());
    }
    const PAD: f64 = 8.0;
    const SAMPLE: f64 = 30.0;
    const GAP: f64 = 8.0;
    let text_h = text_size("Ag", LEGEND_SIZE).1;
    let row_h = text_h.max(10.0) + 7.0;
    let text_w = entries
        .iter()
        .map(|(t, _)| text_size(t, LEGEND_SIZE).0)
        .fold(0.0, f64::max);
    let (bw, bh) = (
        PAD + SAMPLE + GAP + text_w + PAD,
        PAD + row_h * entries.len() as f64 + PAD - 7.0,
    );
    const INSET: f64 = 8.0;
    let corners = [
        (r.right - INSET - bw, r.top + INSET),
        (r.left + INSET, r.top + INSET),
        (r.right - INSET - bw, r.bottom - INSET - bh),
        (r.left + INSET, r.bottom - INSET - bh),
    ];
    let boxes = corners.map(|(x, y)| Rect {
        left: x,
        top: y,
        right: x + bw,
        bottom: y + bh,
    });
    let hidden = |b: &Rect| obstacles.iter().filter(|p| b.contains(**p, 4.0)).count();
    let best = boxes
        .iter()
        .enumerate()
        .min_by_key(|(i, b)| (hidden(b), *i))
        .map(|(_, b)| *b)
        .unwrap_or(boxes[0]);

    draw_rect(area, &best, fill(RGBAColor(255, 255, 255, 0.85)))?;
    draw_rect(area, &best, stroke(RGBColor(0xA0, 0xA0, 0xA0), 1))?;
    for (i, (text, s)) in entries.iter().enumerate() {
        let cy = best.top + PAD + row_h * i as f64 + text_h / 2.0;
        let x0 = best.left + PAD;
        let style = s.series.style;
        if style.line || !style.markers {
            let dash = style.dashed.then_some((7.0, 4.0));
            draw_line(
                area,
                &[(x0, cy), (x0 + SAMPLE, cy)],
                stroke(PALETTE[s.color], 2),
                dash,
            )?;
        }
        if style.markers {
            draw_marker(area, (x0 + SAMPLE / 2.0, cy), s.color)?;
        }
        draw_text_anchored(
            area,
            text,
            LEGEND_SIZE,
            (HPos::Left, VPos::Center),
            (x0 + SAMPLE + GAP, cy),
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    // Setting: colour assignment and reference-line geometry, without drawing.
    // Goal: pin the automatic colour order and the anchor of reference slopes.
    use super::*;

    #[test]
    fn automatic_colors_skip_explicitly_chosen_ones() {
        let s = |c: Option<usize>| {
            let mut s = Series::line("s", vec![(1.0, 1.0)]);
            s.style.color = c;
            s
        };
        let colors = assign_colors(&[s(None), s(Some(1)), s(None), s(Some(9))]);
        assert_eq!(colors, vec![0, 1, 2, 1]);
    }

    #[test]
    fn reference_line_sits_a_factor_two_below_the_finest_point() {
        let fig = Figure::new("t")
            .log_log()
            .series(Series::line(
                "a",
                vec![(0.1, 1e-2), (0.01, 1e-4), (f64::NAN, 1.0)],
            ))
            .reference_slope(2.0, "slope 2");
        let prepared = prepare(&fig);
        let refs = reference_lines(&fig, &prepared);
        assert_eq!(refs.len(), 1);
        assert!((refs[0].from.0 + 2.0).abs() < 1e-12);
        assert!((refs[0].from.1 - (-4.0 - LOG10_2)).abs() < 1e-12);
        assert!((refs[0].to.0 + 1.0).abs() < 1e-12);
        assert!((refs[0].to.1 - (-2.0 - LOG10_2)).abs() < 1e-12);
    }

    #[test]
    fn each_reference_slope_runs_under_the_lowest_series_of_matching_order() {
        let hs = [0.1, 0.05, 0.025];
        let fig = Figure::new("t")
            .log_log()
            .series(Series::line("first order", hs.map(|h| (h, h))))
            .series(Series::line("second order", hs.map(|h| (h, h * h))))
            .series(Series::line(
                "second order, lower",
                hs.map(|h| (h, 0.1 * h * h)),
            ))
            .reference_slope(1.0, "slope 1")
            .reference_slope(2.0, "slope 2")
            .reference_slope(4.0, "slope 4")
            .reference_slope(f64::INFINITY, "dropped");
        let refs = reference_lines(&fig, &prepare(&fig));
        assert_eq!(refs.len(), 3);
        let finest = 0.025f64.log10();
        let below = |y: f64| y.log10() - LOG10_2;
        assert!((refs[0].from.1 - below(0.025)).abs() < 1e-12);
        assert!((refs[1].from.1 - below(0.1 * 0.025 * 0.025)).abs() < 1e-12);
        // No series near slope 4: the group nearest in slope (2) is used, its lowest member.
        assert!((refs[2].from.1 - below(0.1 * 0.025 * 0.025)).abs() < 1e-12);
        assert!(refs.iter().all(|r| (r.from.0 - finest).abs() < 1e-12));
    }
}
