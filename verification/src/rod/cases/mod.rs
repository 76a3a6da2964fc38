//! The rod's case kinds, one file each: the case body's format (unknown keys are errors), its
//! checks, and its runner.

pub mod convergence;
pub mod discrete_reference;
pub mod envelope;
pub mod extreme_checks;
pub mod extremes;
pub mod paper_figures;
pub mod performance;
pub mod plan;
pub mod plan_self;
pub mod stability;
pub mod work_precision;
