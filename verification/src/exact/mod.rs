//! Closed-form solutions, each citing its source and equation.
//!
//! - `bimaterial_strip`: a strip of two Kelvin–Voigt materials in series under an end traction,
//!   static and after n implicit steps (derived there; docs/quasistatic.md).
//! - `rod_constant_data`: the family of exact solutions of problem T1D with constant data
//!   (derived here; the paper's two, (4.6) and (4.7), are members).
//! - `rod_paper`: the paper's (4.6) and (4.7) written out literally, to check the family against.
//! - `bar_impact`: two free bars meeting (head-on at ±v; a striker hitting a longer target at rest):
//!   d'Alembert's solution with the images at the free ends (derived there; docs/multibody.md).
//! - `signorini_bar`: the exact 1D benchmarks of dynamic contact (periodic Signorini bar, free bar
//!   hitting a rigid wall; docs/dynamic.md §5).
//! - `coulomb_friction`, `sliding_block`, `loaded_block`: the friction benchmarks (BDS (1.8),
//!   (1.12)–(1.13), (1.46); docs/dynamic.md §6): the laws written out, the block that slides to a
//!   stop as a rigid body, and the momentum invariant of a loaded block.
//! - `moving_string`: eigenvalues of the axially moving string, alone and with an oscillator
//!   (Hetzler 2009, §4.2.1; docs/moving_continua.md).
//! - `thick_string_galerkin`, `thick_string_continuum`: the thick string with friction (Hetzler
//!   2009, §4.2.2): an independent sine-Galerkin model (closed-form integrals, its own
//!   eigensolver) and the continuum characteristic function with the jump conditions at ā.
//! - `plate_annulus` (with `bessel`): the natural frequencies of the annular Kirchhoff plate clamped
//!   at the inner edge or at the centre (Hetzler 2009, §4.1; Leissa, Vibration of Plates, ch. 2):
//!   the Bessel-function characteristic determinants, derived there.

pub mod bar_impact;
pub mod bessel;
pub mod bimaterial_strip;
pub mod contact_patch;
pub mod coulomb_friction;
pub mod loaded_block;
pub mod moving_string;
pub mod plate_annulus;
pub mod rod_constant_data;
pub mod rod_paper;
pub mod signorini_bar;
pub mod sliding_block;
pub mod thick_string_continuum;
pub mod thick_string_galerkin;
pub mod thick_string_patch;
pub mod two_block_slide;

/// u and the derivatives the rod's equations and error norms need, at one (x, t).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodJet {
    pub u: f64,
    pub u_x: f64,
    pub u_t: f64,
    pub u_xt: f64,
    pub u_xx: f64,
    pub u_xxt: f64,
}

/// A solution of the rod problem, known in closed form (or manufactured).
pub trait RodExactSolution: Send + Sync {
    /// A short name.
    fn name(&self) -> &str;
    /// Where it comes from (paper and equation, or "manufactured").
    fn source(&self) -> &str;
    /// u and its derivatives at (x, t).
    fn jet(&self, x: f64, t: f64) -> RodJet;

    /// The jets at many points at one time, into `out` (solutions whose time dependence is
    /// separable override this to evaluate the time factors once).
    fn jets_at_time(&self, xs: &[f64], t: f64, out: &mut [RodJet]) {
        for (o, &x) in out.iter_mut().zip(xs) {
            *o = self.jet(x, t);
        }
    }
}
