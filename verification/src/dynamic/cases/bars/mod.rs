//! What the two 1D kinds (`dynamic_signorini_bar`, `dynamic_bar_wall`) share: the run families
//! ([`family`]), the sweeps and their outcomes ([`sweep`]), the gates ([`gates`]), the figures
//! and tables ([`report`]), and the run logic ([`runs`]).

pub mod family;
pub mod gates;
pub mod report;
pub mod runs;
pub mod sweep;
