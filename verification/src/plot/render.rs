//! Drawing a [`Figure`] onto a plotters drawing area, in pixel space.
//!
//! Everything is laid out and clipped here (axes, grid, ticks, series, reference lines, legend),
//! so that the output does not depend on plotters' own chart heuristics and never sees a
//! non-finite coordinate.

use std::path::Path;

use plotters::coord::Shift;
use plotters::drawing::DrawingArea;
use plotters::prelude::DrawingBackend;
use plotters::style::text_anchor::{HPos, VPos};
use plotters::style::{RGBAColor, RGBColor};

use super::axis::{auto_range, build_axis, to_axis, user_range, Axis};
use super::colormap::PALETTE;
use super::draw::{
    draw_line, draw_major_grid, draw_major_ticks, draw_marker, draw_no_data, draw_polyline,
    draw_rect, draw_text_anchored, draw_text_at, draw_title, draw_y_label, fill, stroke, text_size,
    DrawResult, GRID_MINOR, GUIDE, LABEL_SIZE, LEGEND_SIZE, NOTE_SIZE, TEXT, TICK_SIZE, TITLE_SIZE,
};
use super::error::PlotError;
use super::figure::Figure;
use super::geom::{clip_segment, clipped_polylines, samples, Px, Rect};
use super::grid::render_cells;
use super::render_data::{prepare, reference_lines, Prepared};

/// Pixel coordinates are clamped to this magnitude before clipping.
const PIXEL_LIMIT: f64 = 1e12;

/// Renders `figures` in a grid of `columns` columns, each cell `cell` pixels, into an SVG string.
/// `path` only names the target in errors.
pub(super) fn render(
    figures: &[Figure],
    columns: usize,
    cell: (u32, u32),
    path: &Path,
) -> Result<String, PlotError> {
    render_cells(figures, columns, cell, path, |area, figure| {
        draw_figure(area, figure)
    })
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
    draw_major_grid(
        area,
        &r,
        frame.x.major.iter().map(|(t, _)| frame.px_x(*t)),
        frame.y.major.iter().map(|(t, _)| frame.px_y(*t)),
    )?;

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
    draw_major_ticks(
        area,
        &r,
        frame
            .x
            .major
            .iter()
            .map(|(t, l)| (frame.px_x(*t), l.as_str())),
        frame
            .y
            .major
            .iter()
            .map(|(t, l)| (frame.px_y(*t), l.as_str())),
    )?;

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
        draw_no_data(area, &r)?;
    }

    // Title and axis labels.
    draw_title(area, &figure.title, title_size, w)?;
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
        draw_y_label(area, &figure.y_label, 10.0, &r)?;
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
