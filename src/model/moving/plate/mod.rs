//! The rotating annular Kirchhoff plate of Hetzler (2009) §4.1, and a stationary friction pad on
//! it (disc-brake squeal, spinning saw blades); restated in `docs/moving_continua.md` (§4.1).
//!
//! - [`data`]: the plate (a, b, D, ρh, ν, h, outer edge), the pad and the parameters maps vary.
//! - [`radial`], [`angular`]: the Ritz bases (Hermite cubic elements in r; Fourier harmonics in
//!   φ, or a sector for the symmetry checks) and their Gram matrices.
//! - [`membrane`]: the in-plane stress of the spinning disc (optional stiffening).
//! - [`modes`]: the non-rotating plate harmonic by harmonic (ω_{n,m}, radial modes).
//! - [`model`]: M, G, K_b, K_T, K_σ and the pad; the system at a point; the modal reduction.

pub mod angular;
pub mod data;
pub mod membrane;
pub mod model;
pub mod modes;
pub mod radial;

pub use data::{OuterEdge, PadData, PlateData, PlateParameter, PlateProperties};
pub use model::{PlateDiscretization, RotatingPlateModel};
