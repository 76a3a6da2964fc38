//! Finite elements: quadrature, P1 elements on intervals, error norms.

pub mod norms;
pub mod p1_interval;
pub mod quadrature;
