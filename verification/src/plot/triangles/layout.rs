//! A mesh plot in pixel space: the equal-aspect mapping of its bounds, and the layout of one cell
//! (title, plot area, colour bar, legend).

use crate::plot::axis::{build_axis, Axis};
use crate::plot::draw::{text_size, LABEL_SIZE, LEGEND_SIZE, TICK_SIZE, TITLE_SIZE};
use crate::plot::figure::Scale;
use crate::plot::geom::{Px, Rect};
use crate::plot::triangles::prepare::{padded_bounds, Mesh, PreparedOutline};

// Equal-aspect mapping (pixel space)

/// The plot box and the data ranges it shows, with equal scales on both axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct View {
    pub(super) rect: Rect,
    pub(super) x: (f64, f64),
    pub(super) y: (f64, f64),
}

impl View {
    /// Pixels per data unit (the same along x and y).
    pub(super) fn scale(&self) -> f64 {
        (self.rect.right - self.rect.left) / (self.x.1 - self.x.0)
    }

    pub(super) fn px(&self, (x, y): (f64, f64)) -> Px {
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
pub(super) const MIN_FILL: f64 = 1.0 / 3.0;

/// The largest box inside `avail` (centred in it) showing the ranges `x` × `y` at equal scales
/// on both axes; if that box would be narrower (shorter) than [`MIN_FILL`] of `avail`, the
/// x (y) range is widened about its centre instead. Ranges must be finite with `hi > lo`.
pub(super) fn fit_equal_aspect(x: (f64, f64), y: (f64, f64), avail: Rect) -> View {
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

// Layout of one cell

pub(super) const BAR_GAP: f64 = 18.0;
pub(super) const BAR_WIDTH: f64 = 16.0;
pub(super) const BAR_TICK: f64 = 5.0;
pub(super) const PIXELS_PER_TICK: f64 = 70.0;
pub(super) const LEGEND_SAMPLE: f64 = 30.0;
pub(super) const LEGEND_GAP: f64 = 8.0;
pub(super) const LEGEND_SPACING: f64 = 20.0;
/// Per-node fields split triangles of at least this area (px²) into four.
pub(super) const SUBDIVIDE_AREA: f64 = 48.0;

/// Compact value label: four significant digits without trailing zeros (`6.562`, `49.22`,
/// `12346`), scientific outside 1e-3…1e5 (`1.235e-5`).
pub(super) fn compact(v: f64) -> String {
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
pub(super) struct Bar {
    pub(super) rect: Rect,
    pub(super) title_size: f64,
    /// Left end of the title: over the bar, moved left as far as needed to stay in the cell
    /// (the band above the plot box is free for it).
    pub(super) title_x: f64,
    /// (value, label) from bottom to top; empty when no value is finite.
    pub(super) labels: Vec<(f64, String)>,
}

/// Labels of a colour bar over `range` drawn `len` pixels long: the ends in compact form, and
/// round values between them that keep clear of the end labels.
pub(super) fn bar_labels(range: Option<(f64, f64)>, len: f64) -> Vec<(f64, String)> {
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
pub(super) struct Layout {
    pub(super) view: View,
    pub(super) x_axis: Axis,
    pub(super) y_axis: Axis,
    pub(super) title_size: f64,
    pub(super) y_tick_w: f64,
    pub(super) bar: Option<Bar>,
    /// Legend rows below the plot: entry indices into the outlines, and the row width.
    pub(super) legend: Vec<(Vec<usize>, f64)>,
}

pub(super) fn shrink_to_fit(text: &str, size: f64, width: f64) -> f64 {
    let mut size = size;
    while size > 10.0 && text_size(text, size).0 > width {
        size -= 1.0;
    }
    size
}

/// Legend entry width (sample line, gap, name).
pub(super) fn legend_entry_width(text: &str) -> f64 {
    LEGEND_SAMPLE + LEGEND_GAP + text_size(text, LEGEND_SIZE).0
}

pub(super) fn legend_text(o: &PreparedOutline) -> String {
    if o.drawable == 0 {
        format!("{} (no data)", o.outline.name)
    } else {
        o.outline.name.clone()
    }
}

pub(super) fn tick_width(axis: &Axis) -> f64 {
    axis.major
        .iter()
        .map(|(_, l)| text_size(l, TICK_SIZE).0)
        .fold(0.0, f64::max)
}

pub(super) fn axes_for(view: &View) -> (Axis, Axis) {
    let r = view.rect;
    let n = |len: f64| (len / PIXELS_PER_TICK).clamp(2.0, 10.0) as usize;
    (
        build_axis(Scale::Linear, view.x, n(r.right - r.left)),
        build_axis(Scale::Linear, view.y, n(r.bottom - r.top)),
    )
}

/// Lays out a cell of `(w, h)` pixels.
pub(super) fn layout(mesh: &Mesh, (w, h): (f64, f64)) -> Layout {
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
    // The box fitted between margins of `left_w` and `right_w` pixels.
    let fit = |left_w: f64, right_w: f64| {
        fit_equal_aspect(
            x_range,
            y_range,
            Rect {
                left: left_w,
                top: avail_top,
                right: (w - right_w).max(left_w + 20.0),
                bottom: avail_bottom,
            },
        )
    };
    let mut left_w = 10.0 + y_label_w + 30.0 + 9.0;
    let mut right_w = bar_w_for(avail_bottom - avail_top);
    let mut view = fit(left_w, right_w);
    for _ in 0..2 {
        let (_, y_axis) = axes_for(&view);
        left_w = 10.0 + y_label_w + tick_width(&y_axis) + 9.0;
        right_w = bar_w_for(view.rect.bottom - view.rect.top);
        view = fit(left_w, right_w);
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
