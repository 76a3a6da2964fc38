//! The drawing primitives both renderers use (figures and triangle-mesh plots): the embedded
//! font, text sizes and colours, text placement, strokes, fills, lines, polylines, rectangles
//! and markers, in pixel space.

use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::drawing::{DrawingArea, DrawingAreaErrorKind};
use plotters::element::{Circle, PathElement, Polygon, Rectangle};
use plotters::prelude::DrawingBackend;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{
    register_font, FontStyle, FontTransform, IntoFont, RGBAColor, RGBColor, ShapeStyle, TextStyle,
};

use super::colormap::PALETTE;
use super::error::PlotError;
use super::geom::{dashes, ipx, Px, Rect};

pub(super) const FONT_FAMILY: &str = "sans-serif";
pub(super) const FONT_BYTES: &[u8] = include_bytes!(concat!(
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
pub(super) const GRID_MINOR: RGBColor = RGBColor(0xEE, 0xEE, 0xEE);
pub(super) const GUIDE: RGBColor = RGBColor(0x44, 0x44, 0x44);
pub(super) const NOTE: RGBColor = RGBColor(0x80, 0x80, 0x80);

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
pub(super) fn draw_text_at<DB: DrawingBackend>(
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
pub(super) fn draw_marker<DB: DrawingBackend>(
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
// Pieces of a plot frame

/// Draws the major grid lines inside `r`: a vertical line at each pixel x of `xs`, then a
/// horizontal line at each pixel y of `ys`.
pub(super) fn draw_major_grid<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    r: &Rect,
    xs: impl IntoIterator<Item = f64>,
    ys: impl IntoIterator<Item = f64>,
) -> DrawResult<DB> {
    for x in xs {
        draw_polyline(area, &[(x, r.top), (x, r.bottom)], stroke(GRID_MAJOR, 1))?;
    }
    for y in ys {
        draw_polyline(area, &[(r.left, y), (r.right, y)], stroke(GRID_MAJOR, 1))?;
    }
    Ok(())
}

/// Draws the labelled major ticks of both axes outside `r`: `x_ticks` (pixel x, label) below
/// its bottom edge, then `y_ticks` (pixel y, label) left of its left edge.
pub(super) fn draw_major_ticks<'l, DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    r: &Rect,
    x_ticks: impl IntoIterator<Item = (f64, &'l str)>,
    y_ticks: impl IntoIterator<Item = (f64, &'l str)>,
) -> DrawResult<DB> {
    for (x, label) in x_ticks {
        draw_polyline(area, &[(x, r.bottom), (x, r.bottom + 6.0)], stroke(TEXT, 1))?;
        draw_text_anchored(
            area,
            label,
            TICK_SIZE,
            (HPos::Center, VPos::Top),
            (x, r.bottom + 9.0),
        )?;
    }
    for (y, label) in y_ticks {
        draw_polyline(area, &[(r.left - 6.0, y), (r.left, y)], stroke(TEXT, 1))?;
        draw_text_anchored(
            area,
            label,
            TICK_SIZE,
            (HPos::Right, VPos::Center),
            (r.left - 9.0, y),
        )?;
    }
    Ok(())
}

/// Writes "no data" in grey at the centre of `r`.
pub(super) fn draw_no_data<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    r: &Rect,
) -> DrawResult<DB> {
    let style = text_style(NOTE_SIZE + 4.0)
        .color(&NOTE)
        .pos(Pos::new(HPos::Center, VPos::Center));
    area.draw_text(
        "no data",
        &style,
        ipx(((r.left + r.right) / 2.0, (r.top + r.bottom) / 2.0)),
    )
}

/// Writes a non-empty `title` of font `size` centred at the top of an area `width` pixels wide.
pub(super) fn draw_title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    size: f64,
    width: f64,
) -> DrawResult<DB> {
    if title.is_empty() {
        return Ok(());
    }
    draw_text_anchored(
        area,
        title,
        size,
        (HPos::Center, VPos::Top),
        (width / 2.0, 10.0),
    )
}

/// Writes the y-axis `label` turned 270°, its top at pixel `x`, centred on `r` vertically.
pub(super) fn draw_y_label<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    label: &str,
    x: f64,
    r: &Rect,
) -> DrawResult<DB> {
    let style = text_style(LABEL_SIZE)
        .color(&TEXT)
        .transform(FontTransform::Rotate270)
        .pos(Pos::new(HPos::Center, VPos::Top));
    area.draw_text(label, &style, ipx((x, (r.top + r.bottom) / 2.0)))
}
