//! The core of the suite. It knows no model family: a case's header and the format helpers, the
//! one scene-override mechanism, the run context, the sweep driver and convergence studies, gates,
//! and reports.

pub mod audit_floor;
pub mod case;
pub mod context;
pub mod convergence;
pub mod cpu_clock;
pub mod format;
pub mod gate;
pub mod json_out;
pub mod likely_inputs;
pub mod overrides;
pub mod plan;
pub mod report;
pub mod shard;
pub mod study;
pub mod sweep;
