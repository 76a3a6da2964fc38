//! The continuum characteristic function of the thick string whose bushing touches it on a patch
//! of width ε instead of a point (the regularization of issue 16; docs/moving_continua.md): the
//! reference of the patch model's eigenvalues and flutter onsets.
//!
//! **The model.** On the patch P = [a₋, a₊], a± = ā ± ε/2, the bushing reads the patch mean
//! W̄ = (1/ε) ∫_P W in place of the point value W(ā), and the friction moment acts on the mean
//! slope (δw(a₊) − δw(a₋))/ε in place of δw'(ā). Both are bounded on H¹, so no jump opens and the
//! high modes see a friction coupling bounded in their wavenumber. In the weak form (left-hand
//! side, the friction's virtual work moved over as in `thick_string_galerkin`):
//!
//! ```text
//!   ∫₀¹ [δw (λ²W + ᾱλW + 2v̄λW') + b W'δw'] dξ + c̄ (W̄ − U) δw̄ − (p/2)(W̄ − U)(δw(a₊) − δw(a₋))/ε = 0,
//! ```
//!
//! b = 1 − v̄², δw̄ the patch mean of δw, and the oscillator gives W̄ − U = g W̄,
//! g = m̄λ²/(m̄λ² + c̄) as in `thick_string_continuum`.
//!
//! **Strong form.** With κ = λ² + ᾱλ: b W'' − 2v̄λ W' − κ W = (c̄ g W̄/ε) χ_P (a uniform load on the
//! patch), W continuous, and slope jumps at the patch ends (coefficients of δw(a±)):
//!
//! ```text
//!   b [W'](a₋) = + (p/2ε) g W̄,     b [W'](a₊) = − (p/2ε) g W̄.
//! ```
//!
//! As ε → 0 the slope inside the patch carries the difference: [W] → (p/2b) g W̄, the point model's
//! jump. **Solution.** W = A f_L on [0, a₋], W = B f_R on [a₊, 1] (f_L, f_R as in
//! `thick_string_continuum`), W = C₁ e^{s₁(ξ−ā)} + C₂ e^{s₂(ξ−ā)} + w_p W̄ on P with the particular
//! solution w_p = −c̄ g/(ε κ); unknowns (A, B, C₁, C₂, W̄) and five conditions: W continuous at a₋
//! and a₊, the two slope jumps, and ε W̄ = ∫_P W. The column of W̄ carries every pole (of g at
//! D = m̄λ² + c̄ = 0, of w_p at κ = 0); multiplied by D κ ε it reads
//! (−c̄G, c̄G, −(p/2)Gκ, (p/2)Gκ, ε(εDκ + c̄G)), G = m̄λ², and the 5 × 5 determinant is F(λ).
//! Swapping s₁ and s₂ changes its sign only.

use nalgebra::{Complex, Matrix5};

use super::thick_string_continuum::secant_root;
use super::thick_string_galerkin::ThickString;

type C64 = Complex<f64>;

/// The characteristic function F(λ) of the patch model of width `width` (module docs).
pub fn patch_characteristic(d: &ThickString, width: f64, lambda: C64) -> C64 {
    let v = d.speed;
    let b = 1.0 - v * v;
    let root = (lambda * lambda + lambda * (b * d.damping)).sqrt();
    let s1 = (lambda * v + root) / b;
    let s2 = (lambda * v - root) / b;
    let eps = width;
    let (am, ap) = (d.position - 0.5 * eps, d.position + 0.5 * eps);
    // f_L at a₋ and f_R at a₊ with their slopes
    let (l1, l2) = ((s1 * am).exp(), (s2 * am).exp());
    let (r1, r2) = ((s1 * (ap - 1.0)).exp(), (s2 * (ap - 1.0)).exp());
    let (l, dl) = (l1 - l2, s1 * l1 - s2 * l2);
    let (r, dr) = (r1 - r2, s1 * r1 - s2 * r2);
    // the patch's exponentials about ā, and their integrals over P
    let (e1m, e2m) = ((-s1 * (0.5 * eps)).exp(), (-s2 * (0.5 * eps)).exp());
    let (e1p, e2p) = ((s1 * (0.5 * eps)).exp(), (s2 * (0.5 * eps)).exp());
    let integral = |s: C64, ep: C64, em: C64| {
        if (s * eps).norm() < 1e-6 {
            // (e^{sε/2} − e^{−sε/2})/s = ε (1 + (sε)²/24 + …)
            C64::new(eps, 0.0) * (C64::new(1.0, 0.0) + s * s * (eps * eps / 24.0))
        } else {
            (ep - em) / s
        }
    };
    let (i1, i2) = (integral(s1, e1p, e1m), integral(s2, e2p, e2m));
    let kappa = lambda * lambda + lambda * d.damping;
    let gg = lambda * lambda * d.mass;
    let dd = gg + d.stiffness;
    let c = d.stiffness;
    let p = d.control;
    let z = C64::new(0.0, 0.0);
    let half_p_g_kappa = gg * kappa * (0.5 * p);
    #[rustfmt::skip]
    let m = Matrix5::new(
        // A        B        C1              C2              W̄ (× D κ ε)
        -l,         z,       e1m,            e2m,            -(gg * c),
        z,          r,       -e1p,           -e2p,           gg * c,
        -(dl * b),  z,       s1 * e1m * b,   s2 * e2m * b,   -half_p_g_kappa,
        z,          dr * b,  -(s1 * e1p * b), -(s2 * e2p * b), half_p_g_kappa,
        z,          z,       -i1,            -i2,            (dd * kappa * eps + gg * c) * eps,
    );
    m.determinant()
}

/// The root of the patch model's F near `guess`.
pub fn patch_root(d: &ThickString, width: f64, guess: C64) -> Result<C64, String> {
    secant_root(|l| patch_characteristic(d, width, l), guess)
}

#[cfg(test)]
mod tests {
    //! Setting: the map's data and a bushing at mid-span. Goal: the patch model tends to the point
    //! model (`thick_string_continuum`) as ε → 0, at first order in ε; at ā = 1/2 the string modes
    //! that are odd about mid-span (sin 2kπξ) have W̄ = 0 and zero mean slope over a centred
    //! patch: they stay roots for any friction and any ε.
    use super::*;
    use crate::exact::thick_string_continuum::continuum_root;

    fn data(position: f64, control: f64) -> ThickString {
        ThickString {
            speed: 0.5,
            damping: 0.05,
            stiffness: 2.0,
            mass: 0.5,
            position,
            control,
            patch: 0.0,
        }
    }

    #[test]
    fn the_patch_tends_to_the_point_at_first_order() {
        let d = data(0.3, 0.04);
        for guess in [
            C64::new(-0.01, 1.45),
            C64::new(-0.02, 2.6),
            C64::new(-0.02, 4.3),
        ] {
            let point = continuum_root(&d, guess).unwrap();
            let errs: Vec<f64> = [0.02, 0.01, 0.005, 0.0025, 0.00125]
                .iter()
                .map(|&eps| (patch_root(&d, eps, point).unwrap() - point).norm())
                .collect();
            // pre-asymptotic at ε = 0.02 (rate 0.65 there for the lowest root), then first order
            for w in errs[2..].windows(2) {
                let rate = (w[0] / w[1]).log2();
                assert!((0.9..1.1).contains(&rate), "{errs:?}");
            }
            assert!(errs[4] < 1e-3 * point.norm(), "{errs:?}");
        }
    }

    #[test]
    fn odd_modes_about_a_centred_patch_stay_roots() {
        // the odd mode k = 2 of the string (sin 2πξ) without oscillator coupling: λ = i 2π b
        for p in [0.0, 0.3, 2.0] {
            let mut d = data(0.5, p);
            d.speed = 0.0;
            d.damping = 0.0;
            let exact = C64::new(0.0, 2.0 * std::f64::consts::PI);
            let r = patch_root(&d, 0.1, exact * (1.0 + 1e-3)).unwrap();
            assert!((r - exact).norm() < 1e-10, "p = {p}: {r}");
        }
    }
}
