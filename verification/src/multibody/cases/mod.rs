//! The case kinds of the multibody family, one file (or folder) each.

pub mod bars;
pub mod envelope;
pub mod extremes;
pub mod friction;
pub mod impact;
pub mod patch;
pub mod sliding;
