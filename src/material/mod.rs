//! Constitutive laws of the Kelvin–Voigt body σ = A ε(u̇) + B ε(u) (Fernández & Sofonea 2004,
//! (2.1)), for plane problems (2D symmetric tensors).
//!
//! - `plane_law`: the trait (stress and tangent) and the linear isotropic form
//!   (A τ)_{αβ} = a1 (τ11 + τ22) δ_{αβ} + a2 τ_{αβ} of the paper's Test 2D, with plane-stress and
//!   plane-strain constructors.
//! - `nonlinear`: a saturating viscosity (Lipschitz, strongly monotone) and a softening elasticity
//!   (Lipschitz), the nonlinear A and B allowed by (2.10)–(2.11).
//! - `hyperelastic`: hyperelastic laws Π = ∂_F W(F) for plane strain and bars (linear,
//!   St Venant–Kirchhoff, neo-Hooke) with the Gonzalez energy-conserving discrete gradient
//!   (Barboteu–Danan–Sofonea (1.41)–(1.43)).
//! - `stress_state`: the strain, stress, out-of-plane stress and von Mises stress that result
//!   files report per element.

pub mod hyperelastic;
pub mod nonlinear;
pub mod plane_law;
pub mod stress_state;
