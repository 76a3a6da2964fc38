//! Solvers: factorizations and nonsmooth (semismooth Newton) equations.
//!
//! - `tridiagonal`: LDLᵀ of a symmetric tridiagonal matrix (the 1D P1 stiffness), factored once.
//! - `scalar_semismooth`: semismooth Newton for a strictly increasing scalar equation (the contact
//!   equation condensed onto one node), safeguarded by bracketing.

pub mod scalar_semismooth;
pub mod sparse_cholesky;
pub mod tridiagonal;
