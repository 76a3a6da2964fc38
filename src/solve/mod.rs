//! Solvers: factorizations and nonsmooth (semismooth Newton) equations.
//!
//! - `tridiagonal`: LDLᵀ of a symmetric tridiagonal matrix (the 1D P1 stiffness), factored once.
//! - `scalar_semismooth`: semismooth Newton for a strictly increasing scalar equation (the contact
//!   equation condensed onto one node), safeguarded by bracketing.
//! - `quadratic_eigen`: the quadratic eigenproblem (λ²M + λC + K)x = 0 through the companion form
//!   (faer's dense eigensolver, `Par::Seq`), and the QZ path for singular mass matrices.
//! - `small_eigenvalues`: eigenvalue-only Householder + Francis QR for small dense matrices and
//!   rank-one lines (the stability maps' kernel).
//! - `balance`: the diagonal power-of-2 similarity both eigensolvers apply first.
//! - `dense_cholesky`: the Cholesky factor of a small dense SPD matrix (a mass matrix).
//! - `linear_ode`: RK4 for M q̈ + C q̇ + K q = 0 (the time-integration check of verdicts).

pub mod balance;
pub mod dense_cholesky;
pub mod linear_ode;
pub mod quadratic_eigen;
pub mod scalar_semismooth;
pub mod small_eigenvalues;
pub mod sparse_cholesky;
pub mod sparse_lu;
pub mod tridiagonal;
