//! What the two 1D kinds (`dynamic_signorini_bar`, `dynamic_bar_wall`) share: run families,
//! sweeps, gates and plots ([`common`]), and the run logic ([`runs`]).

pub mod common;
pub mod runs;
