//! Ritz bases of the string between fixed guides, w(0) = w(1) = 0, and the string operators they
//! induce.
//!
//! With w ≈ Φ(ξ) q the weak form (Hetzler 2009, (83)) needs four Gram matrices
//! (⟨A, B⟩ = ∫₀¹ A B dξ, row index = test function, column index = trial function):
//!
//! ```text
//!   mass       ⟨Φᵀ, Φ⟩        (M and, for mass-proportional damping, D)
//!   transport  ⟨Φᵀ, Φ'⟩       (G = 2 ⟨Φᵀ, Φ'⟩, skew for w(0) = w(1) = 0: R_P = 0, (58)–(60))
//!   stiffness  ⟨Φ'ᵀ, Φ'⟩      (the prestress P, w' δw')
//!   curvature  ⟨Φᵀ, Φ''⟩      (the transport stiffness v̄² ⟨Φᵀ, Φ''⟩; for C⁰ or C¹ elements
//!                              through ⟨Φᵀ, Φ''⟩ = [Φᵀ Φ']₀¹ − ⟨Φ'ᵀ, Φ'⟩, (61)–(64))
//! ```
//!
//! and the point values Φ(ā), Φ'(ā) of the bushing (84)–(85), (101)–(102).

use faer::Mat;

/// The Gram matrices of a Ritz basis (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct StringOperators {
    /// ⟨Φᵀ, Φ⟩.
    pub mass: Mat<f64>,
    /// ⟨Φᵀ, Φ'⟩.
    pub transport: Mat<f64>,
    /// ⟨Φ'ᵀ, Φ'⟩.
    pub stiffness: Mat<f64>,
    /// ⟨Φᵀ, Φ''⟩.
    pub curvature: Mat<f64>,
}

/// A Ritz basis of functions with Φ(0) = Φ(1) = 0.
pub trait RitzBasis: Send + Sync {
    /// The number of basis functions (generalized coordinates q).
    fn len(&self) -> usize;

    /// True for an empty basis.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The Gram matrices.
    fn operators(&self) -> StringOperators;

    /// Φ_k(ξ) into `values` and Φ'_k(ξ) into `slopes` (both of length [`RitzBasis::len`]). Where
    /// Φ' jumps (a node of C⁰ elements) the slope is the mean of the one-sided slopes.
    fn point_values_into(&self, xi: f64, values: &mut [f64], slopes: &mut [f64]);

    /// The patch means over [a, b] (0 < a < b < 1): (1/(b − a)) ∫_a^b Φ_k into `means`, and the
    /// mean slopes (Φ_k(b) − Φ_k(a))/(b − a) into `mean_slopes` — the contact patch of width
    /// b − a (docs/moving_continua.md), exact for every basis.
    fn patch_means_into(&self, a: f64, b: f64, means: &mut [f64], mean_slopes: &mut [f64]);

    /// A short description (`sine, N = 20`).
    fn label(&self) -> String;
}

/// The sine basis Φ_k(ξ) = √2 sin(kπξ), k = 1..N, orthonormal in L²(0, 1).
///
/// Closed-form operators: ⟨Φ_j, Φ_k⟩ = δ_jk, ⟨Φ'_j, Φ'_k⟩ = (kπ)² δ_jk,
/// ⟨Φ_j, Φ''_k⟩ = −(kπ)² δ_jk, and, from ∫₀¹ sin(jπξ) cos(kπξ) dξ = 2j / (π (j² − k²)) for j + k
/// odd (0 otherwise), ⟨Φ_j, Φ'_k⟩ = 4 j k / (j² − k²) for j + k odd, 0 otherwise — skew-symmetric.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SineBasis {
    modes: usize,
}

impl SineBasis {
    /// N sine modes, N ≥ 1.
    pub fn new(modes: usize) -> Result<Self, crate::error::InputError> {
        if modes == 0 {
            return Err(crate::error::InputError::new(
                "discretization.modes",
                modes,
                "at least 1 basis function",
            ));
        }
        Ok(Self { modes })
    }
}

impl RitzBasis for SineBasis {
    fn len(&self) -> usize {
        self.modes
    }

    fn operators(&self) -> StringOperators {
        let n = self.modes;
        let pi = std::f64::consts::PI;
        let kk = |k: usize| ((k + 1) as f64 * pi).powi(2);
        StringOperators {
            mass: Mat::from_fn(n, n, |i, j| if i == j { 1.0 } else { 0.0 }),
            transport: Mat::from_fn(n, n, |i, j| {
                let (a, b) = ((i + 1) as f64, (j + 1) as f64);
                if (i + j) % 2 == 1 {
                    4.0 * a * b / (a * a - b * b)
                } else {
                    0.0
                }
            }),
            stiffness: Mat::from_fn(n, n, |i, j| if i == j { kk(i) } else { 0.0 }),
            curvature: Mat::from_fn(n, n, |i, j| if i == j { -kk(i) } else { 0.0 }),
        }
    }

    fn point_values_into(&self, xi: f64, values: &mut [f64], slopes: &mut [f64]) {
        let pi = std::f64::consts::PI;
        let s2 = std::f64::consts::SQRT_2;
        for k in 0..self.modes {
            let kp = (k + 1) as f64 * pi;
            values[k] = s2 * (kp * xi).sin();
            slopes[k] = s2 * kp * (kp * xi).cos();
        }
    }

    /// Closed form, in the product form that keeps its digits for a narrow patch:
    /// mean = √2 · 2 sin(kπ(a + b)/2) sin(kπ(b − a)/2) / (kπ(b − a)),
    /// mean slope = √2 · 2 cos(kπ(a + b)/2) sin(kπ(b − a)/2) / (b − a).
    fn patch_means_into(&self, a: f64, b: f64, means: &mut [f64], mean_slopes: &mut [f64]) {
        let pi = std::f64::consts::PI;
        let s2 = std::f64::consts::SQRT_2;
        let (mid, width) = (0.5 * (a + b), b - a);
        for k in 0..self.modes {
            let kp = (k + 1) as f64 * pi;
            let half = (0.5 * kp * width).sin();
            means[k] = s2 * 2.0 * (kp * mid).sin() * half / (kp * width);
            mean_slopes[k] = s2 * 2.0 * (kp * mid).cos() * half / width;
        }
    }

    fn label(&self) -> String {
        format!("sine, N = {}", self.modes)
    }
}

#[cfg(test)]
mod tests {
    //! Setting: the closed-form sine operators. Goal: they equal Gauss quadrature of their
    //! definitions, and the transport operator is exactly skew.
    use super::*;
    use crate::fem::quadrature::GaussLegendre;

    #[test]
    fn sine_patch_means_equal_their_quadrature() {
        // the product form of the closed form against 40-point Gauss of the definition; a narrow
        // patch keeps its digits (the plain form cos − cos would lose them)
        let b = SineBasis::new(30).unwrap();
        let g = GaussLegendre::new(40).unwrap();
        let pi = std::f64::consts::PI;
        let (mut m, mut s) = (vec![0.0; 30], vec![0.0; 30]);
        for (lo, hi) in [(0.275, 0.325), (0.1, 0.6), (0.41 - 1e-6, 0.41 + 1e-6)] {
            b.patch_means_into(lo, hi, &mut m, &mut s);
            for k in 0..30 {
                let kp = (k + 1) as f64 * pi;
                let f = |x: f64| std::f64::consts::SQRT_2 * (kp * x).sin();
                let quad: f64 = g
                    .points()
                    .iter()
                    .zip(g.weights())
                    .map(|(t, w)| 0.5 * w * f(0.5 * (lo + hi) + 0.5 * (hi - lo) * t))
                    .sum();
                assert!((m[k] - quad).abs() < 1e-13, "k = {k}, [{lo}, {hi}]");
                let slope = (f(hi) - f(lo)) / (hi - lo);
                assert!((s[k] - slope).abs() < 1e-8 * kp, "k = {k}, [{lo}, {hi}]");
            }
        }
    }

    #[test]
    fn sine_operators_equal_their_quadrature() {
        let b = SineBasis::new(7).unwrap();
        let ops = b.operators();
        let g = GaussLegendre::new(40).unwrap();
        let pi = std::f64::consts::PI;
        let f = |k: usize, x: f64| {
            let kp = (k + 1) as f64 * pi;
            let s2 = std::f64::consts::SQRT_2;
            [
                s2 * (kp * x).sin(),
                s2 * kp * (kp * x).cos(),
                -s2 * kp * kp * (kp * x).sin(),
            ]
        };
        for i in 0..7 {
            for j in 0..7 {
                let m = g.integrate(0.0, 1.0, |x| f(i, x)[0] * f(j, x)[0]);
                let t = g.integrate(0.0, 1.0, |x| f(i, x)[0] * f(j, x)[1]);
                let s = g.integrate(0.0, 1.0, |x| f(i, x)[1] * f(j, x)[1]);
                let c = g.integrate(0.0, 1.0, |x| f(i, x)[0] * f(j, x)[2]);
                assert!((m - ops.mass[(i, j)]).abs() < 1e-13);
                assert!((t - ops.transport[(i, j)]).abs() < 1e-12, "{i} {j} {t}");
                assert!((s - ops.stiffness[(i, j)]).abs() < 1e-10);
                assert!((c - ops.curvature[(i, j)]).abs() < 1e-10);
                assert_eq!(ops.transport[(i, j)], -ops.transport[(j, i)]);
            }
        }
    }

    #[test]
    fn zero_modes_is_an_input_error() {
        assert_eq!(SineBasis::new(0).unwrap_err().field, "discretization.modes");
    }
}
