//! Triangle-mesh plots for 2D finite-element results.
//!
//! Describe a [`TriangleMeshPlot`] (nodes, triangles, optionally a scalar [`TriangleField`],
//! a wireframe and [`Outline`]s such as the undeformed boundary) and write it with
//! `write_triangle_svg`, or several in a grid with `write_triangle_panels_svg`. The plot
//! keeps an equal aspect ratio (one unit in x is as long on screen as one unit in y), colours a
//! field with the perceptually uniform viridis map and explains it with a colour bar on the
//! right. As for the other figures, drawing never panics on data: triangles touching a node
//! with a non-finite coordinate are skipped, non-finite field values are drawn grey and left out
//! of the colour range, a mesh with nothing drawable gives a valid SVG saying "no data", and the
//! same plot always gives the same bytes. Only malformed input is an error: a triangle naming a
//! node that does not exist, or a field with the wrong number of values.
//!
//! ```no_run
//! use contactlab_verify::plot::{write_triangle_svg, Outline, TriangleField, TriangleMeshPlot};
//! let nodes = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
//! let plot = TriangleMeshPlot::new("Deformed mesh", nodes.clone(), vec![[0, 1, 2], [0, 2, 3]])
//!     .field(TriangleField::per_triangle("|ε|", vec![0.1, 0.3]))
//!     .wireframe(true)
//!     .outline(Outline::new("undeformed", nodes).closed().dashed());
//! write_triangle_svg(&plot, std::path::Path::new("reports/mesh.svg")).unwrap();
//! ```

pub(super) mod draw;
mod layout;
mod prepare;
#[cfg(test)]
mod tests;

use serde::{Deserialize, Serialize};

/// Default size of a single triangle-mesh plot, in pixels (width, height).
pub const TRIANGLE_SIZE: (u32, u32) = (720, 640);

/// Size of one cell of a grid of triangle-mesh plots, in pixels (width, height).
pub const TRIANGLE_PANEL_SIZE: (u32, u32) = (560, 500);

/// Where the values of a [`TriangleField`] live.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum FieldValues {
    /// One value per triangle, in the order of [`TriangleMeshPlot::triangles`]; each triangle
    /// is drawn in one flat colour.
    PerTriangle(Vec<f64>),
    /// One value per node, in the order of [`TriangleMeshPlot::nodes`]. A triangle covering at
    /// least 48 px² on screen is split into four at its edge midpoints and each part coloured
    /// by the linearly interpolated value at its centroid; a smaller one is coloured by the
    /// value at its own centroid (the mean of its three nodal values).
    PerNode(Vec<f64>),
}

/// A scalar field on the mesh, coloured with viridis and explained by a colour bar titled
/// `name`. Non-finite values are drawn grey and excluded from the automatic range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TriangleField {
    /// Title of the colour bar.
    pub name: String,
    /// The values.
    pub values: FieldValues,
    /// Fixed colour range (values outside take the end colours); `None`, or an unusable range
    /// (non-finite, empty or reversed), means the range of the drawn values, padded when they
    /// are all equal.
    pub range: Option<(f64, f64)>,
}

impl TriangleField {
    /// A field with one value per triangle (flat colour per triangle).
    pub fn per_triangle(name: impl Into<String>, values: impl IntoIterator<Item = f64>) -> Self {
        TriangleField {
            name: name.into(),
            values: FieldValues::PerTriangle(values.into_iter().collect()),
            range: None,
        }
    }

    /// A field with one value per node (see [`FieldValues::PerNode`] for how it is coloured).
    pub fn per_node(name: impl Into<String>, values: impl IntoIterator<Item = f64>) -> Self {
        TriangleField {
            name: name.into(),
            values: FieldValues::PerNode(values.into_iter().collect()),
            range: None,
        }
    }

    /// Fixes the colour range.
    pub fn range(mut self, lo: f64, hi: f64) -> Self {
        self.range = Some((lo, hi));
        self
    }
}

/// A polyline drawn over the mesh (e.g. the undeformed boundary), listed in the legend under
/// its name unless the name is empty. A non-finite point breaks the line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outline {
    /// Legend entry; an empty name keeps the outline out of the legend.
    pub name: String,
    /// Points in drawing order.
    pub points: Vec<[f64; 2]>,
    /// Join the last point back to the first.
    pub closed: bool,
    /// Dash the line.
    pub dashed: bool,
    /// Index into the Okabe–Ito palette, modulo [`super::PALETTE_LEN`]; `None` takes the next
    /// colour not chosen explicitly by another outline (over a field the order starts with the
    /// colours that stand out against viridis: vermillion, black, reddish purple, orange).
    pub color: Option<usize>,
}

impl Outline {
    /// An open, solid outline with automatic colour.
    pub fn new(name: impl Into<String>, points: impl IntoIterator<Item = [f64; 2]>) -> Self {
        Outline {
            name: name.into(),
            points: points.into_iter().collect(),
            closed: false,
            dashed: false,
            color: None,
        }
    }

    /// Dashes the line.
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }

    /// Joins the last point back to the first.
    pub fn closed(mut self) -> Self {
        self.closed = true;
        self
    }

    /// Chooses the palette colour (index modulo [`super::PALETTE_LEN`]).
    pub fn color(mut self, index: usize) -> Self {
        self.color = Some(index);
        self
    }
}

/// A plot of a 2D triangle mesh. Build it with [`TriangleMeshPlot::new`] and the builder
/// methods. Without a field the triangles are filled light grey unless the wireframe is on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TriangleMeshPlot {
    /// Title above the plot.
    pub title: String,
    /// Node coordinates (x, y).
    pub nodes: Vec<[f64; 2]>,
    /// Triangles as indices into `nodes`.
    pub triangles: Vec<[usize; 3]>,
    /// Scalar field to colour the triangles with.
    pub field: Option<TriangleField>,
    /// Draw the triangle edges.
    pub wireframe: bool,
    /// Polylines drawn over the mesh.
    pub outlines: Vec<Outline>,
    /// Label of the x axis.
    pub x_label: String,
    /// Label of the y axis.
    pub y_label: String,
}

impl TriangleMeshPlot {
    /// A mesh plot without field, wireframe or outlines, with axes labelled "x" and "y".
    pub fn new(title: impl Into<String>, nodes: Vec<[f64; 2]>, triangles: Vec<[usize; 3]>) -> Self {
        TriangleMeshPlot {
            title: title.into(),
            nodes,
            triangles,
            field: None,
            wireframe: false,
            outlines: Vec::new(),
            x_label: "x".to_string(),
            y_label: "y".to_string(),
        }
    }

    /// Sets the field.
    pub fn field(mut self, field: TriangleField) -> Self {
        self.field = Some(field);
        self
    }

    /// Switches the wireframe on or off.
    pub fn wireframe(mut self, on: bool) -> Self {
        self.wireframe = on;
        self
    }

    /// Adds an outline.
    pub fn outline(mut self, outline: Outline) -> Self {
        self.outlines.push(outline);
        self
    }

    /// Sets the axis labels (empty strings leave an axis unlabelled).
    pub fn labels(mut self, x: impl Into<String>, y: impl Into<String>) -> Self {
        self.x_label = x.into();
        self.y_label = y.into();
        self
    }
}
