//! Exact eigenvalues of the axially moving string (Hetzler 2009, §4.2.1;
//! docs/moving_continua.md), derived here.
//!
//! **String between guides.** w = W(ξ) e^{λτ} in ẅ + 2v̄ẇ' + ᾱẇ − (1 − v̄²) w'' = 0 (the strong
//! form of (83) without oscillator) with W = e^{sξ} gives
//! (1 − v̄²) s² − 2v̄λ s − (λ² + ᾱλ) = 0, so
//!
//! ```text
//!   s_{1,2} = (v̄ λ ± sqrt(λ² + (1 − v̄²) ᾱ λ)) / (1 − v̄²).
//! ```
//!
//! For ᾱ = 0: s₁ = λ/(1 − v̄), s₂ = −λ/(1 + v̄). W(0) = 0 gives W = e^{s₁ξ} − e^{s₂ξ}, and
//! W(1) = 0 needs e^{(s₁ − s₂)} = 1, s₁ − s₂ = 2λ/(1 − v̄²) = 2πin:
//!
//! ```text
//!   λ_n = i n π (1 − v̄²),   W_n(ξ) = 2i e^{i n π v̄ ξ} sin(nπξ).
//! ```
//!
//! Since W_n = 2i e^{inπv̄ξ} sin(nπξ), W_n''(0) = 2i·2·(inπv̄)(nπ) ≠ 0 for v̄ ≠ 0: the
//! eigenfunction is smooth but not odd-periodic, which sets the sine-basis rate (see the case
//! `moving_string_exact`). With damping, s₁ − s₂ = 2 sqrt(λ² + (1 − v̄²)ᾱλ)/(1 − v̄²) = 2πin
//! gives λ_n = (1 − v̄²)(−ᾱ/2 ± i sqrt(n²π² − ᾱ²/4)) ([`damped_string_eigenvalue`]).
//!
//! **With the oscillator at ā (ideal contact, thin string).** On [0, ā] W = A f_L, on [ā, 1]
//! W = B f_R with f_L = e^{s₁ξ} − e^{s₂ξ}, f_R = e^{s₁(ξ−1)} − e^{s₂(ξ−1)}. The point terms of
//! (83) — v̄² δw w'' and δw' w' integrated by parts across the kink at ā — give the jump
//! condition (1 − v̄²)[W']_ā = c̄ (W(ā) − U), and the mass m̄λ²U + c̄(U − W(ā)) = 0 gives
//! U = c̄ W(ā)/(m̄λ² + c̄). With continuity at ā the eigenvalues are the roots of
//!
//! ```text
//!   F(λ) = (m̄λ² + c̄)(1 − v̄²) (f_R'(ā) f_L(ā) − f_L'(ā) f_R(ā)) − c̄ m̄ λ² f_L(ā) f_R(ā),
//! ```
//!
//! found to round-off by the secant method from the discrete eigenvalues.

use nalgebra::Complex;

type C64 = Complex<f64>;

/// λ_n = i n π (1 − v̄²) of the undamped string (n ≥ 1): the frequency nπ(1 − v̄²).
pub fn string_eigenvalue(n: usize, speed: f64) -> f64 {
    n as f64 * std::f64::consts::PI * (1.0 - speed * speed)
}

/// The damped string's eigenvalue with Im ≥ 0 at v̄ = 0: W(1) = 0 needs
/// λ² + (1 − v̄²) ᾱ λ + (nπ(1 − v̄²))² = 0, so λ_n = (1 − v̄²) μ_n with
/// μ_n = −ᾱ/2 + i sqrt(n²π² − ᾱ²/4) (for ᾱ < 2nπ): the whole spectrum scales with 1 − v̄² and
/// passes through 0 at v̄ = 1 — every real part is −ᾱ(1 − v̄²)/2.
pub fn damped_string_eigenvalue(n: usize, speed: f64, damping: f64) -> C64 {
    let w = (n as f64 * std::f64::consts::PI).powi(2) - 0.25 * damping * damping;
    C64::new(-0.5 * damping, w.max(0.0).sqrt()) * (1.0 - speed * speed)
}

/// The string with an oscillator (ideal contact, no friction): the characteristic function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OscillatorCharacteristic {
    pub speed: f64,
    pub damping: f64,
    pub stiffness: f64,
    pub mass: f64,
    pub position: f64,
}

impl OscillatorCharacteristic {
    /// F(λ) (see the module docs).
    pub fn value(&self, lambda: C64) -> C64 {
        let v = self.speed;
        let b = 1.0 - v * v;
        let root = (lambda * lambda + lambda * (b * self.damping)).sqrt();
        let s1 = (lambda * v + root) / b;
        let s2 = (lambda * v - root) / b;
        let a = self.position;
        let (e1l, e2l) = ((s1 * a).exp(), (s2 * a).exp());
        let (e1r, e2r) = ((s1 * (a - 1.0)).exp(), (s2 * (a - 1.0)).exp());
        let fl = e1l - e2l;
        let dfl = s1 * e1l - s2 * e2l;
        let fr = e1r - e2r;
        let dfr = s1 * e1r - s2 * e2r;
        let l2 = lambda * lambda;
        (l2 * self.mass + self.stiffness) * b * (dfr * fl - dfl * fr)
            - l2 * (self.stiffness * self.mass) * fl * fr
    }

    /// The root of F near `guess`, by the secant method to |Δλ| ≤ 4ε|λ|.
    pub fn refine(&self, guess: C64) -> Result<C64, String> {
        let mut x0 = guess * (1.0 + 1e-7) + C64::new(1e-9, 0.0);
        let mut x1 = guess;
        let mut f0 = self.value(x0);
        let mut f1 = self.value(x1);
        for _ in 0..200 {
            let denom = f1 - f0;
            if denom.norm() == 0.0 {
                break;
            }
            let x2 = x1 - f1 * (x1 - x0) / denom;
            if !(x2.re.is_finite() && x2.im.is_finite()) {
                return Err(format!("secant diverged from {guess}"));
            }
            let step = (x2 - x1).norm();
            x0 = x1;
            f0 = f1;
            x1 = x2;
            f1 = self.value(x1);
            if step <= 4.0 * f64::EPSILON * x1.norm().max(1.0) {
                return Ok(x1);
            }
        }
        if f1.norm() == 0.0 {
            Ok(x1)
        } else {
            Err(format!(
                "secant did not converge from {guess} (last step at {x1}, |F| = {:e})",
                f1.norm()
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    //! Setting: the characteristic function in cases with known roots. Goal: the string's roots
    //! i n π (1 − v̄²) and the nodal modes at ā = 1/2 are roots for any oscillator.
    use super::*;

    #[test]
    fn nodal_modes_are_roots_for_any_oscillator() {
        let f = OscillatorCharacteristic {
            speed: 0.4,
            damping: 0.0,
            stiffness: 7.0,
            mass: 0.3,
            position: 0.5,
        };
        // the even modes vanish at ā = 1/2: W = e^{inπv̄ξ} sin(nπξ).
        let l = C64::new(0.0, string_eigenvalue(2, 0.4));
        let r = f.refine(l * (1.0 + 1e-3)).unwrap();
        assert!((r - l).norm() < 1e-12 * l.norm(), "{r} vs {l}");
    }
}
