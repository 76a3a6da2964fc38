//! A run of the suite: which cases a tier, a `--case` filter and a `--shard` select, running them
//! with one progress bar over the tier, the final summary table, and the catalogue `--list`.
//!
//! Imports run `bin → suite → registry → families → core`: the suite only calls the registry.

pub mod list;
pub mod run;
pub mod select;
