//! The one path by which a plot becomes an SVG file: a [`Panel`] (a [`Figure`] or a
//! [`TriangleMeshPlot`]) renders a grid of itself into an SVG string, and [`write_sized`] and
//! [`write_grid`] write one picture or a grid to a file, creating missing folders.

use std::path::Path;

use super::error::PlotError;
use super::figure::{Figure, DEFAULT_SIZE, PANEL_SIZE};
use super::triangles::{TriangleMeshPlot, TRIANGLE_PANEL_SIZE, TRIANGLE_SIZE};

/// Something drawn alone or as the cells of a grid.
pub trait Panel: Sized {
    /// The size of one cell of a grid, in pixels (width, height).
    const CELL: (u32, u32);

    /// Renders `items` in a grid of `columns` columns, each cell `cell` pixels, into an SVG
    /// string; `path` only names the target in errors.
    fn render_grid(
        items: &[Self],
        columns: usize,
        cell: (u32, u32),
        path: &Path,
    ) -> Result<String, PlotError>;
}

impl Panel for Figure {
    const CELL: (u32, u32) = PANEL_SIZE;

    fn render_grid(
        items: &[Self],
        columns: usize,
        cell: (u32, u32),
        path: &Path,
    ) -> Result<String, PlotError> {
        super::render::render(items, columns, cell, path)
    }
}

impl Panel for TriangleMeshPlot {
    const CELL: (u32, u32) = TRIANGLE_PANEL_SIZE;

    fn render_grid(
        items: &[Self],
        columns: usize,
        cell: (u32, u32),
        path: &Path,
    ) -> Result<String, PlotError> {
        super::triangles::draw::render(items, columns, cell, path)
    }
}

/// Writes one picture of `size` = (width, height) pixels to `path`. Sizes are clamped to
/// 100…10 000 pixels.
pub fn write_sized<P: Panel>(item: &P, size: (u32, u32), path: &Path) -> Result<(), PlotError> {
    let svg = P::render_grid(std::slice::from_ref(item), 1, clamp_size(size), path)?;
    write_file(path, &svg)
}

/// Writes several pictures in a grid (`columns` per row, filled row by row) into one SVG at
/// `path`; each cell is [`Panel::CELL`], so the picture grows with the grid. `columns` is clamped
/// to 1…`items.len()`.
pub fn write_grid<P: Panel>(items: &[P], columns: usize, path: &Path) -> Result<(), PlotError> {
    if items.is_empty() {
        return Err(PlotError::NoFigures {
            path: path.to_path_buf(),
        });
    }
    let svg = P::render_grid(items, columns, P::CELL, path)?;
    write_file(path, &svg)
}

/// Writes `figure` as an SVG of [`DEFAULT_SIZE`] to `path`.
pub fn write_svg(figure: &Figure, path: &Path) -> Result<(), PlotError> {
    write_sized(figure, DEFAULT_SIZE, path)
}

/// Writes `figure` as an SVG of `size` pixels to `path`.
pub fn write_svg_sized(figure: &Figure, size: (u32, u32), path: &Path) -> Result<(), PlotError> {
    write_sized(figure, size, path)
}

/// Writes several figures in a grid into one SVG at `path` (cells of [`PANEL_SIZE`]).
pub fn write_panels_svg(figures: &[Figure], columns: usize, path: &Path) -> Result<(), PlotError> {
    write_grid(figures, columns, path)
}

/// Writes a mesh plot as an SVG of [`TRIANGLE_SIZE`] to `path`.
pub fn write_triangle_svg(plot: &TriangleMeshPlot, path: &Path) -> Result<(), PlotError> {
    write_sized(plot, TRIANGLE_SIZE, path)
}

/// Writes a mesh plot as an SVG of `size` pixels to `path`.
pub fn write_triangle_svg_sized(
    plot: &TriangleMeshPlot,
    size: (u32, u32),
    path: &Path,
) -> Result<(), PlotError> {
    write_sized(plot, size, path)
}

/// Writes several mesh plots in a grid into one SVG at `path` (cells of [`TRIANGLE_PANEL_SIZE`]).
pub fn write_triangle_panels_svg(
    plots: &[TriangleMeshPlot],
    columns: usize,
    path: &Path,
) -> Result<(), PlotError> {
    write_grid(plots, columns, path)
}

fn clamp_size((w, h): (u32, u32)) -> (u32, u32) {
    (w.clamp(100, 10_000), h.clamp(100, 10_000))
}

fn write_file(path: &Path, contents: &str) -> Result<(), PlotError> {
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent).map_err(|source| PlotError::Io {
            path: parent.to_path_buf(),
            source,
        })?;
    }
    std::fs::write(path, contents).map_err(|source| PlotError::Io {
        path: path.to_path_buf(),
        source,
    })
}
