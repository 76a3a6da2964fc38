//! The description of a plot: a [`Figure`] of [`Series`] on linear or logarithmic axes, with
//! reference slopes and marker lines, and the sizes and palette every figure uses.

use serde::{Deserialize, Serialize};

use super::colormap::PALETTE;

/// Default size of a single figure, in pixels (width, height).
pub const DEFAULT_SIZE: (u32, u32) = (720, 480);

/// Size of one cell of a panel grid, in pixels (width, height).
pub const PANEL_SIZE: (u32, u32) = (600, 420);

/// Number of colours in the palette; colour indices are taken modulo this.
pub const PALETTE_LEN: usize = PALETTE.len();

/// Scale of an axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Scale {
    /// Linear axis.
    #[default]
    Linear,
    /// Base-10 logarithmic axis; values ≤ 0 cannot be drawn and are skipped.
    Log,
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Style {
    /// Join consecutive points with a line (a skipped point breaks the line).
    pub line: bool,
    /// Draw a marker at each point; the marker shape follows the colour index.
    pub markers: bool,
    /// Dash the line.
    pub dashed: bool,
    /// Index into the colour-blind-friendly (Okabe–Ito) palette, modulo [`PALETTE_LEN`];
    /// `None` takes the next colour not chosen explicitly by another series.
    pub color: Option<usize>,
}

impl Default for Style {
    /// A solid line without markers, automatic colour.
    fn default() -> Self {
        Style {
            line: true,
            markers: false,
            dashed: false,
            color: None,
        }
    }
}

/// A named sequence of (x, y) points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Series {
    /// Legend entry; an empty name keeps the series out of the legend.
    pub name: String,
    /// Points in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: Style,
}

impl Series {
    fn with_style(
        name: impl Into<String>,
        points: impl IntoIterator<Item = (f64, f64)>,
        line: bool,
        markers: bool,
    ) -> Self {
        Series {
            name: name.into(),
            points: points.into_iter().collect(),
            style: Style {
                line,
                markers,
                ..Style::default()
            },
        }
    }

    /// A series drawn as a solid line.
    pub fn line(name: impl Into<String>, points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Self::with_style(name, points, true, false)
    }

    /// A series drawn as markers only.
    pub fn markers(name: impl Into<String>, points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Self::with_style(name, points, false, true)
    }

    /// A series drawn as a line with a marker at each point.
    pub fn line_markers(
        name: impl Into<String>,
        points: impl IntoIterator<Item = (f64, f64)>,
    ) -> Self {
        Self::with_style(name, points, true, true)
    }

    /// A series from separate x and y slices (extra values of the longer one are ignored).
    pub fn from_xy(name: impl Into<String>, xs: &[f64], ys: &[f64]) -> Self {
        Self::line(name, xs.iter().copied().zip(ys.iter().copied()))
    }

    /// Dashes the line.
    pub fn dashed(mut self) -> Self {
        self.style.dashed = true;
        self
    }

    /// Chooses the palette colour (index modulo [`PALETTE_LEN`]).
    pub fn color(mut self, index: usize) -> Self {
        self.style.color = Some(index);
        self
    }

    /// Adds markers to the series.
    pub fn with_markers(mut self) -> Self {
        self.style.markers = true;
        self
    }
}

/// A reference line of given slope on a log–log plot (a power law `y ∝ x^slope`), drawn dashed
/// a factor 2 below the finest (smallest-x) point of an anchor series, over that series' x range,
/// and labelled beneath. The anchor is the lowest of the series whose fitted log–log slope is
/// within 0.3 of the fitted slope nearest `slope` (so the line runs under the series it
/// describes), or the first drawable series when no slope can be fitted. Ignored unless both
/// axes are logarithmic, and when `slope` is not finite.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReferenceSlope {
    /// Slope in log–log space (the expected order of convergence).
    pub slope: f64,
    /// Label written next to the line, e.g. "slope 2".
    pub label: String,
}

impl ReferenceSlope {
    /// A reference slope with its label.
    pub fn new(slope: f64, label: impl Into<String>) -> Self {
        ReferenceSlope {
            slope,
            label: label.into(),
        }
    }
}

/// A labelled vertical line at `x` across the whole plot (e.g. a predicted stability bound).
/// Included in the automatic x range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VerticalLine {
    /// Position on the x axis (data units).
    pub x: f64,
    /// Label written next to the top of the line (may be empty).
    pub label: String,
}

impl VerticalLine {
    /// A vertical line with its label.
    pub fn new(x: f64, label: impl Into<String>) -> Self {
        VerticalLine {
            x,
            label: label.into(),
        }
    }
}

/// A labelled horizontal line at `y` across the whole plot (e.g. a tolerance).
/// Included in the automatic y range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HorizontalLine {
    /// Position on the y axis (data units).
    pub y: f64,
    /// Label written above the right end of the line (may be empty).
    pub label: String,
}

impl HorizontalLine {
    /// A horizontal line with its label.
    pub fn new(y: f64, label: impl Into<String>) -> Self {
        HorizontalLine {
            y,
            label: label.into(),
        }
    }
}

/// A complete plot description. Build it with [`Figure::new`] and the builder methods.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Figure {
    /// Title above the plot.
    pub title: String,
    /// Label of the x axis.
    pub x_label: String,
    /// Label of the y axis.
    pub y_label: String,
    /// Scale of the x axis.
    pub x_scale: Scale,
    /// Scale of the y axis.
    pub y_scale: Scale,
    /// Data series, drawn in order (later on top).
    pub series: Vec<Series>,
    /// Reference power laws (log–log plots only).
    pub reference_slopes: Vec<ReferenceSlope>,
    /// Labelled vertical lines.
    pub vertical_lines: Vec<VerticalLine>,
    /// Labelled horizontal lines.
    pub horizontal_lines: Vec<HorizontalLine>,
    /// Fixed x range in data units; `None`, or an unusable range (empty, non-finite, ≤ 0 on a
    /// log axis), means automatic.
    pub x_range: Option<(f64, f64)>,
    /// Fixed y range in data units; as for `x_range`.
    pub y_range: Option<(f64, f64)>,
}

impl Figure {
    /// An empty figure with linear axes and no labels.
    pub fn new(title: impl Into<String>) -> Self {
        Figure {
            title: title.into(),
            x_label: String::new(),
            y_label: String::new(),
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
            series: Vec::new(),
            reference_slopes: Vec::new(),
            vertical_lines: Vec::new(),
            horizontal_lines: Vec::new(),
            x_range: None,
            y_range: None,
        }
    }

    /// Sets the x-axis label.
    pub fn x_label(mut self, label: impl Into<String>) -> Self {
        self.x_label = label.into();
        self
    }

    /// Sets the y-axis label.
    pub fn y_label(mut self, label: impl Into<String>) -> Self {
        self.y_label = label.into();
        self
    }

    /// Sets the x-axis scale.
    pub fn x_scale(mut self, scale: Scale) -> Self {
        self.x_scale = scale;
        self
    }

    /// Sets the y-axis scale.
    pub fn y_scale(mut self, scale: Scale) -> Self {
        self.y_scale = scale;
        self
    }

    /// Both axes logarithmic.
    pub fn log_log(self) -> Self {
        self.x_scale(Scale::Log).y_scale(Scale::Log)
    }

    /// Linear x axis, logarithmic y axis.
    pub fn semilog_y(self) -> Self {
        self.x_scale(Scale::Linear).y_scale(Scale::Log)
    }

    /// Logarithmic x axis, linear y axis.
    pub fn semilog_x(self) -> Self {
        self.x_scale(Scale::Log).y_scale(Scale::Linear)
    }

    /// Adds a series.
    pub fn series(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// Adds several series.
    pub fn extend_series(mut self, series: impl IntoIterator<Item = Series>) -> Self {
        self.series.extend(series);
        self
    }

    /// Adds a reference slope (log–log plots only).
    pub fn reference_slope(mut self, slope: f64, label: impl Into<String>) -> Self {
        self.reference_slopes
            .push(ReferenceSlope::new(slope, label));
        self
    }

    /// Adds a labelled vertical line.
    pub fn vertical_line(mut self, x: f64, label: impl Into<String>) -> Self {
        self.vertical_lines.push(VerticalLine::new(x, label));
        self
    }

    /// Adds a labelled horizontal line.
    pub fn horizontal_line(mut self, y: f64, label: impl Into<String>) -> Self {
        self.horizontal_lines.push(HorizontalLine::new(y, label));
        self
    }

    /// Fixes the x range (data units).
    pub fn x_range(mut self, lo: f64, hi: f64) -> Self {
        self.x_range = Some((lo, hi));
        self
    }

    /// Fixes the y range (data units).
    pub fn y_range(mut self, lo: f64, hi: f64) -> Self {
        self.y_range = Some((lo, hi));
        self
    }
}
