//! The grid of panels both renderers share: a white SVG canvas of `rows × cols` cells, each
//! drawn by the renderer of one picture (a figure or a triangle-mesh plot).

use std::path::Path;

use plotters::coord::Shift;
use plotters::drawing::{DrawingArea, IntoDrawingArea};
use plotters::prelude::SVGBackend;
use plotters::style::RGBColor;

use super::draw::{ensure_font, DrawResult};
use super::error::PlotError;

/// Renders `items` in a grid of `columns` columns (clamped to 1…`items.len()`), each cell `cell`
/// pixels, into an SVG string: fills the canvas white and draws item `i` with `draw_cell` into
/// cell `i`, row by row. `path` only names the target in errors.
pub(super) fn render_cells<T>(
    items: &[T],
    columns: usize,
    cell: (u32, u32),
    path: &Path,
    draw_cell: impl for<'b> Fn(&DrawingArea<SVGBackend<'b>, Shift>, &T) -> DrawResult<SVGBackend<'b>>,
) -> Result<String, PlotError> {
    ensure_font()?;
    let n = items.len().max(1);
    let cols = columns.clamp(1, n);
    let rows = n.div_ceil(cols);
    let size = (
        cell.0.saturating_mul(cols as u32),
        cell.1.saturating_mul(rows as u32),
    );
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, size).into_drawing_area();
        draw_cells(&root, items, (rows, cols), &draw_cell).map_err(|e| PlotError::Drawing {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    }
    Ok(buf)
}

/// Fills `root` white, splits it into `rows × cols` equal cells and draws item `i` into cell `i`.
fn draw_cells<'a, T>(
    root: &DrawingArea<SVGBackend<'a>, Shift>,
    items: &[T],
    (rows, cols): (usize, usize),
    draw_cell: &impl Fn(&DrawingArea<SVGBackend<'a>, Shift>, &T) -> DrawResult<SVGBackend<'a>>,
) -> DrawResult<SVGBackend<'a>> {
    root.fill(&RGBColor(255, 255, 255))?;
    let cells = root.split_evenly((rows, cols));
    for (item, area) in items.iter().zip(cells.iter()) {
        draw_cell(area, item)?;
    }
    root.present()
}
