//! # contactlab — verified contact mechanics
//!
//! Solvers for bodies that touch, rub and bounce, each shipped with its evidence (the crate
//! `contactlab-verify` runs the exact and manufactured solutions, rate fits and gates).
//!
//! ## A tour
//!
//! - [`model::quasistatic`]: the quasistatic Kelvin–Voigt body with normal damped response
//!   (Fernández & Sofonea 2004):
//!
//!   σ = A ε(u̇) + B ε(u),  Div σ + f0 = 0,  −σ_ν = p_ν(u̇_ν) on Γ3   ((2.1)–(2.6)),
//!
//!   discretized by P1 elements and the scheme
//!   (A ε(w_n), ε(v)) + (B ε(u_{n−1} + θ k_n w_n), ε(v)) + j(w_n, v) = (f(τ_n), v),
//!   u_n = u_{n−1} + k_n w_n, with θ = 0 (the paper's explicit scheme), 1 (implicit) or 1/2
//!   (midpoint). The 1D rod ([`model::quasistatic::rod_solver`]) factors its stiffness once and
//!   condenses the contact onto the end node: a step is one scalar semismooth Newton solve and one
//!   pass over the nodal values. Plane bodies ([`model::quasistatic::plane_solver`]) factor
//!   A + θkB once with the Γ3 dofs last and condense the contact onto them (linear A, B), or run a
//!   full semismooth Newton method (nonlinear A or B); a body whose only vertical support is the
//!   contact is handled with its free rigid motion, and a step without equilibrium is a typed
//!   error.
//! - [`material`]: plane Kelvin–Voigt laws (linear isotropic, saturating viscosity, softening
//!   elasticity) with their tangents.
//! - [`contact::normal_law`]: the laws p_ν (2.7)–(2.9) with generalized derivatives.
//! - [`mesh`], [`time`], [`fem`]: interval and triangle meshes, time grids, quadrature, P1
//!   elements, symmetric sparse assembly, norms.
//! - [`solve`]: the tridiagonal LDLᵀ, the sparse Cholesky (faer) with split passes, the
//!   safeguarded scalar semismooth Newton.
//! - [`scene`]: TOML scenes validated into runnable models ([`scene::rod::RodScene`],
//!   [`scene::plane::PlaneScene`]).
//! - [`error`]: typed errors naming fields, values, steps, times and residuals.
//!
//! ## Example
//!
//! ```
//! use contactlab::mesh::interval::IntervalMesh;
//! use contactlab::model::quasistatic::rod::RodProblem;
//! use contactlab::model::quasistatic::rod_output::RodOutputRequest;
//! use contactlab::model::quasistatic::rod_solver::{RodParams, RodSolver};
//! use contactlab::model::quasistatic::scheme::TimeScheme;
//! use contactlab::time::grid::TimeGrid;
//!
//! let problem = RodProblem::fernandez_sofonea(6.0);
//! let solver = RodSolver::new(
//!     &problem,
//!     IntervalMesh::uniform(1.0, 100)?,
//!     TimeGrid::uniform(0.5, 50)?,
//!     TimeScheme::Explicit,
//!     RodParams::default(),
//! )?;
//! let solution = solver.solve(&RodOutputRequest::default())?;
//! assert!((solution.end_displacement[50] - (-0.394993932862)).abs() < 1e-11);
//! # Ok::<(), contactlab::error::Error>(())
//! ```

// Numerical kernels index several arrays in lockstep (u_i, w_i, g_i, z_i; rows and columns):
// index loops read as the formulas they implement.
#![allow(clippy::needless_range_loop)]

pub mod contact;
pub mod error;
pub mod fem;
pub mod field;
pub mod material;
pub mod mesh;
pub mod model;
pub mod scene;
pub mod solve;
pub mod time;

/// The crate version (for reports).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
