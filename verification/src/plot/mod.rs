//! SVG plots for the verification reports.
//!
//! A small declarative layer over `plotters`' SVG backend: describe a [`Figure`] (series,
//! scales, reference slopes, marker lines) and write it with [`write_svg`], or several figures
//! in a grid with [`write_panels_svg`]. Drawing never panics on data: non-finite points (and
//! points ≤ 0 on log axes) are skipped, degenerate ranges are padded, and a figure with nothing
//! drawable still produces a valid SVG saying "no data". The same figure always gives the same
//! bytes.
//!
//! ```no_run
//! use contactlab_verify::plot::{write_svg, Figure, Series};
//! let fig = Figure::new("Convergence in h")
//!     .x_label("h")
//!     .y_label("L2 error")
//!     .log_log()
//!     .series(Series::line_markers("scheme A", vec![(0.1, 1e-2), (0.05, 2.6e-3)]))
//!     .reference_slope(2.0, "slope 2");
//! write_svg(&fig, std::path::Path::new("reports/convergence_h.svg")).unwrap();
//! ```
//!
//! Module map: `figure` describes a plot; `render` draws figures and
//! `triangles` draws triangle-mesh plots, both with the primitives of `draw` (fonts, colours,
//! text, shapes) on the axes of `axis` and the clipped geometry of `geom`; `svg` is the one path
//! that writes either kind, alone or as a grid of panels (laid out by `grid`).

mod axis;
mod colormap;
mod draw;
mod error;
mod figure;
mod geom;
mod grid;
mod render;
mod render_data;
mod svg;
#[cfg(test)]
mod tests;
mod triangles;

pub use error::PlotError;
pub use figure::{
    Figure, HorizontalLine, ReferenceSlope, Scale, Series, Style, VerticalLine, DEFAULT_SIZE,
    PALETTE_LEN, PANEL_SIZE,
};
pub use svg::{
    write_grid, write_panels_svg, write_sized, write_svg, write_svg_sized,
    write_triangle_panels_svg, write_triangle_svg, write_triangle_svg_sized, Panel,
};
pub use triangles::{
    FieldValues, Outline, TriangleField, TriangleMeshPlot, TRIANGLE_PANEL_SIZE, TRIANGLE_SIZE,
};
