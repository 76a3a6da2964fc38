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
//! - [`model::dynamic`]: elastodynamic contact against a rigid foundation
//!   (Barboteu–Danan–Sofonea 2015, "BDS"; Hauret–Le Tallec 2006, "HLT"):
//!
//!   ρ ü − Div Π(F) = f0,  Π = ∂_F W(F),  normal compliance / limited penetration / Signorini and
//!   Coulomb friction with μ(u_ν) on Γ3   ((1.14)–(1.20)),
//!
//!   with P1 bars and plane-strain bodies, Newmark, the midpoint rule and Gonzalez's
//!   energy-conserving scheme (1.41)–(1.43), the energy-consistent contact force (1.46) = (3.68),
//!   the two-stage improved penalized method (1.44)–(1.45), one semismooth Newton method for all
//!   treatments (a linear body factors once and condenses onto its contact dofs), and an energy
//!   audit of every run: the residuals of BDS Propositions 1.1, 1.3 and HLT Proposition 3.7 per
//!   step.
//! - [`model::moving`]: moving continua with contacts and sliding friction — the axially moving
//!   string with an oscillator (ideal or penalty contact), the thick string with Coulomb friction,
//!   the particle on a rotating disc — linearized as M q̈ + C q̇ + K q = 0, with eigenvalue
//!   verdicts (stable, divergence, flutter), branch tracking and stability maps (Hetzler 2009).
//! - [`material`]: plane Kelvin–Voigt laws (linear isotropic, saturating viscosity, softening
//!   elasticity) with their tangents; hyperelastic laws (linear, St Venant–Kirchhoff, neo-Hooke;
//!   bars and plane strain) with the Gonzalez discrete gradient.
//! - [`contact`]: the laws p_ν (2.7)–(2.9) with generalized derivatives; the compliance forces of
//!   dynamic steps; Coulomb friction coefficients μ(u_ν) (BDS (1.13)).
//! - [`mesh`], [`time`], [`fem`]: interval and triangle meshes (rectangles, disks, annuli), time
//!   grids, quadrature, P1 elements, symmetric sparse assembly, norms.
//! - [`solve`]: the tridiagonal LDLᵀ, the sparse Cholesky (faer) with split passes, the
//!   safeguarded scalar semismooth Newton, quadratic eigenproblems (companion form, QZ for singular
//!   masses), a small dense eigenvalue kernel for stability maps, and an RK4 integrator.
//! - [`scene`]: TOML scenes validated into runnable models ([`scene::rod::RodScene`],
//!   [`scene::plane::PlaneScene`], [`scene::dynamic::DynamicScene`],
//!   [`scene::multibody::MultibodyScene`] (a dynamic scene of `[[body]]` sections),
//!   [`scene::moving`]).
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
pub mod run_control;
pub mod scene;
pub mod solve;
pub mod time;

/// The crate version (for reports).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
