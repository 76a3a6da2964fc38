//! ParaView output of `verify scene` (`[output] vtk = true` or `--vtk`): one VTK XML
//! UnstructuredGrid file (`.vtu`) per output time and a `.pvd` collection that lists them with
//! their time values, so that ParaView opens the whole run as one time series.
//!
//! - [`frame`]: the data of one file — points (z = 0), cells (P1 triangles or line segments),
//!   point and cell arrays — and its checks (sizes; every value finite, else an error naming the
//!   array and the time);
//! - [`vtu`]: one frame as a `.vtu` through vtkio's model and writer;
//! - [`pvd`]: the collection file (quick-xml);
//! - [`series`]: a whole series — every frame checked before any file is written.
//!
//! The families build the frames from their solutions (`plane/vtk.rs`, `rod/vtk.rs`,
//! `dynamic/vtk.rs`); this module knows no family.

pub mod frame;
pub mod pvd;
pub mod series;
pub mod vtu;

pub use frame::{Array, Cells, Frame, Values};
pub use series::write_series;
