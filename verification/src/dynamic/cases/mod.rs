//! The dynamic family's case kinds, one file (or folder) each: the case body's format (unknown
//! keys are errors), its checks, and its runner. [`bars`] holds what the two 1D kinds share.

pub mod bar_wall;
pub mod bars;
pub mod envelope;
pub mod extremes;
pub mod friction;
pub mod impact;
pub mod manufactured;
pub mod performance;
pub mod plan;
pub mod plan_self;
pub mod signorini_bar;
