//! Time grids 0 = t_0 < t_1 < … < t_N = T.

pub mod grid;
