//! A mesh plot in data space: the checks of its indices and field, the colour scale of the
//! field, the drawable triangles and outlines, and the padded bounds.

use std::path::Path;

use plotters::style::RGBColor;

use crate::plot::axis::to_axis;
use crate::plot::colormap::{viridis, MISSING, PALETTE};
use crate::plot::error::PlotError;
use crate::plot::figure::Scale;
use crate::plot::triangles::{FieldValues, Outline, TriangleMeshPlot};

// Validation and data preparation (data space)

/// Checks the triangle indices and the field length.
pub(super) fn validate(plot: &TriangleMeshPlot, path: &Path) -> Result<(), PlotError> {
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
pub(super) fn point(p: [f64; 2]) -> Option<(f64, f64)> {
    Some((to_axis(Scale::Linear, p[0])?, to_axis(Scale::Linear, p[1])?))
}

/// Colour range of a field and whether grey (missing) values occur.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct ColorScale {
    /// `None` when no value is finite.
    pub(super) range: Option<(f64, f64)>,
    pub(super) missing: bool,
}

impl ColorScale {
    pub(super) fn color(&self, v: f64) -> RGBColor {
        match self.range {
            Some((lo, hi)) if v.is_finite() => viridis((v - lo) / (hi - lo)),
            _ => MISSING,
        }
    }
}

/// The colour range: the user's if usable, else the range of the finite `values`, padded by
/// 10 % of their magnitude (or 1) when they are all equal.
pub(super) fn color_scale(
    values: impl IntoIterator<Item = f64>,
    user: Option<(f64, f64)>,
) -> ColorScale {
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

pub(super) struct PreparedOutline<'a> {
    pub(super) outline: &'a Outline,
    pub(super) points: Vec<Option<(f64, f64)>>,
    pub(super) color: usize,
    pub(super) drawable: usize,
}

/// A plot reduced to what can be drawn.
pub(super) struct Mesh<'a> {
    pub(super) plot: &'a TriangleMeshPlot,
    pub(super) nodes: Vec<Option<(f64, f64)>>,
    /// Indices (into `plot.triangles`) of the triangles whose three nodes can be drawn.
    pub(super) drawable: Vec<usize>,
    pub(super) outlines: Vec<PreparedOutline<'a>>,
    pub(super) scale: Option<ColorScale>,
}

impl<'a> Mesh<'a> {
    /// Prepares a validated plot.
    pub(super) fn new(plot: &'a TriangleMeshPlot) -> Self {
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

    pub(super) fn has_data(&self) -> bool {
        !self.drawable.is_empty() || self.outlines.iter().any(|o| o.drawable > 0)
    }

    /// Node position of a drawable triangle's corner.
    pub(super) fn at(&self, k: usize) -> (f64, f64) {
        self.nodes[k].unwrap_or((0.0, 0.0))
    }

    /// Bounding box ((x_lo, x_hi), (y_lo, y_hi)) of the drawable nodes and outline points.
    pub(super) fn bounds(&self) -> Option<((f64, f64), (f64, f64))> {
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
pub(super) fn outline_colors(outlines: &[Outline], over_field: bool) -> Vec<usize> {
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
pub(super) fn padded_bounds(bounds: Option<((f64, f64), (f64, f64))>) -> ((f64, f64), (f64, f64)) {
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
