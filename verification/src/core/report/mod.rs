//! Reports: one JSON file per case (the contract, documented in `reports/README.md`) and one
//! Markdown report with every case's tables and plots.

pub mod case_report;
pub mod compare;
pub mod markdown;
pub mod metadata;
