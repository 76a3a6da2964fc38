//! Why a plot could not be written.

use std::path::PathBuf;

/// Errors of plotting.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The embedded font could not be registered with plotters.
    #[error("the embedded plot font could not be registered")]
    Font,
    /// Drawing the figure failed.
    #[error("drawing {path} failed: {message}")]
    Drawing {
        /// The SVG file being drawn.
        path: PathBuf,
        /// The backend's message.
        message: String,
    },
    /// Creating the folder or writing the file failed.
    #[error("writing {path} failed: {source}")]
    Io {
        /// The file or folder concerned.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A panel plot was given no figure.
    #[error("no figure given for the panel plot {path}")]
    NoFigures {
        /// The SVG file that was to be written.
        path: PathBuf,
    },
    /// A triangle of a `TriangleMeshPlot` names a node that does not exist.
    #[error("{path}: triangle {triangle} of the mesh plot \"{title}\" refers to node {node}, but the mesh has {nodes} nodes")]
    TriangleIndex {
        /// The SVG file that was to be written.
        path: PathBuf,
        /// Title of the offending plot.
        title: String,
        /// Index of the triangle.
        triangle: usize,
        /// The out-of-range node index.
        node: usize,
        /// Number of nodes of the mesh.
        nodes: usize,
    },
    /// A `TriangleField` does not have one value per triangle (or per node).
    #[error("{path}: field \"{field}\" of the mesh plot \"{title}\" has {found} values, expected one per {per} ({expected})")]
    FieldLength {
        /// The SVG file that was to be written.
        path: PathBuf,
        /// Title of the offending plot.
        title: String,
        /// Name of the field.
        field: String,
        /// "triangle" or "node".
        per: &'static str,
        /// Number of values expected.
        expected: usize,
        /// Number of values given.
        found: usize,
    },
}
