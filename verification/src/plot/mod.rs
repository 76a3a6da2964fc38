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

/// The most snapshots a `snapshots.svg` draws: a figure of 20 000 panels is a gigabyte of SVG
/// that nobody reads (every snapshot stays in solution.json and the VTK files).
pub const MAX_PLOTTED_SNAPSHOTS: usize = 12;

/// The indices of the snapshots drawn among `count`: all of them up to
/// [`MAX_PLOTTED_SNAPSHOTS`], else that many evenly spaced, i = round(j (count − 1)/(max − 1)),
/// the first and the last included.
pub fn plotted_snapshots(count: usize) -> Vec<usize> {
    if count <= MAX_PLOTTED_SNAPSHOTS {
        return (0..count).collect();
    }
    let last = (count - 1) as f64;
    let mut v: Vec<usize> = (0..MAX_PLOTTED_SNAPSHOTS)
        .map(|j| (j as f64 * last / (MAX_PLOTTED_SNAPSHOTS - 1) as f64).round() as usize)
        .collect();
    v.dedup();
    v
}

#[cfg(test)]
mod plotted_snapshot_tests {
    use super::*;

    #[test]
    fn at_most_twelve_snapshots_are_drawn_first_and_last_included() {
        assert_eq!(plotted_snapshots(3), vec![0, 1, 2]);
        let v = plotted_snapshots(20_000);
        assert_eq!(v.len(), MAX_PLOTTED_SNAPSHOTS);
        assert_eq!((v[0], v[v.len() - 1]), (0, 19_999));
        assert!(v.windows(2).all(|w| w[0] < w[1]));
    }
}
