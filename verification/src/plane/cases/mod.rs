//! The plane body's case kinds, one file each: the case body's format (unknown keys are errors),
//! its checks, and its runner.

pub mod convergence;
pub mod envelope;
pub mod gmsh;
pub mod paper_test_2d;
pub mod paths;
pub mod performance;
pub mod plan;
pub mod plan_self;
pub mod stability;
