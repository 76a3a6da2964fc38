//! Reports: per case a JSON file of its deterministic numbers and one of what varies from run to
//! run (the contract, documented in `reports/README.md`), and one Markdown report with every
//! case's tables and plots.

pub mod benchmarks;
pub mod case_report;
pub mod compare;
pub mod manifest;
pub mod markdown;
pub mod metadata;
pub mod readme;
pub mod split;
