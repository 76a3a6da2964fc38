//! Moving continua with contacts and sliding friction: linearized models and their stability
//! (Hetzler 2009; restated in `docs/moving_continua.md`).
//!
//! In a spatial frame the equations linearized about a steady state read
//!
//! ```text
//!   M q̈ + (α D + v G) q̇ + (K(v) + K_c + p K_f + p N) q = 0      ((33), (86), (103), (108)),
//! ```
//!
//! and stability is read from the eigenvalues of (λ² M + λ C + K) x = 0
//! (`solve::quadratic_eigen`): divergence when a real eigenvalue crosses zero, flutter when a
//! complex pair crosses the imaginary axis.
//!
//! - [`basis`], [`finite_element_basis`]: Ritz bases of the string (sine; P1 and Hermite
//!   elements) and their Gram matrices.
//! - [`string_data`]: the dimensionless data (v̄, ᾱ, c̄, m̄, ā, k̄_p, μh̄) (79)–(82).
//! - [`string_model`]: the moving string with an oscillator in the bushing — ideal contact (85),
//!   penalty contact with the massless bushing (90)–(91), the thick string with Coulomb friction
//!   (102)–(103), (107)–(108); [`friction`]: the friction matrices R = K_f + N.
//! - [`disc`]: the particle pressed on a rotating disc, friction-induced damping μN/(Ω r0)
//!   (110)–(112).
//! - [`system`]: the linearized system stored by physical part; static condensation.
//! - [`properties`]: the matrix-property checks — skew-symmetry of G, symmetry of K_T, and the
//!   boundary terms R_P (58)–(60) and R_Q (61)–(64) that decide them.
//! - [`stability`]: verdicts (stable, marginal, divergence, flutter) with a justified round-off
//!   tolerance; [`branches`]: eigenvalue branches along a sweep; [`stability_map`]: verdicts on
//!   a parameter grid, parallel over points and deterministic; [`resolution`]: the eigenvalues
//!   that stand for the continuum (the rest is the basis's: a warning, never the verdict).

/// The dense matrix and complex types of this module's public API (faer 0.24), re-exported so
/// that users (and the verification crate) need no direct dependency on faer.
pub use faer::{c64, Mat, MatRef};

/// Serializes complex numbers as [Re, Im] pairs (serde's `serialize_with` for `Vec<Vec<c64>>`).
pub fn serialize_complex_rows<S: serde::Serializer>(
    rows: &[Vec<c64>],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeSeq;
    let mut seq = serializer.serialize_seq(Some(rows.len()))?;
    for row in rows {
        let pairs: Vec<[f64; 2]> = row.iter().map(|z| [z.re, z.im]).collect();
        seq.serialize_element(&pairs)?;
    }
    seq.end()
}

pub mod basis;
pub mod branches;
pub mod disc;
pub mod finite_element_basis;
pub mod friction;
pub mod linearized;
pub mod plate;
pub mod properties;
pub mod resolution;
pub mod stability;
pub mod stability_map;
pub mod string_data;
pub mod string_model;
pub mod sweep;
pub mod system;
