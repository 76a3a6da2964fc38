//! Finite elements: quadrature, P1 elements on intervals, Hermite cubic shapes, error norms.

pub mod hermite;
pub mod norms;
pub mod p1_interval;
pub mod quadrature;
pub mod sparse;
pub mod triangle_p1;
pub mod triangle_quadrature;
