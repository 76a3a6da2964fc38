//! Hyperelastic laws Π = ∂_F W(F), F = I + ∇u (Barboteu–Danan–Sofonea, "BDS", (1.14)), for plane
//! strain (F a 2×2 matrix) and for bars (F = 1 + u_x a scalar), each with the energy-conserving
//! discrete gradient of Gonzalez (BDS (1.41)–(1.43)).
//!
//! A discrete gradient is a stress Π^algo(F0, F1) with
//!
//!   Π^algo : (F1 − F0) = W(F1) − W(F0)                                        (BDS (1.43))
//!
//! exactly; used as the internal force of the midpoint scheme it makes the discrete energy balance
//! (BDS Proposition 1.1, (1.47)–(1.48)) hold to round-off. For W = W̃(C), C = FᵀF, Gonzalez's
//! choice is (BDS (1.42))
//!
//!   Π^algo = F_{n−1/2} Σ^algo,  F_{n−1/2} = (F0 + F1)/2,
//!   Σ^algo = S(C_{n−1/2}) + 2 [W̃(C1) − W̃(C0) − ½ S(C_{n−1/2}) : ΔC] ΔC / (ΔC : ΔC),
//!   S = 2 ∂W̃/∂C,  C_{n−1/2} = (C0 + C1)/2,  ΔC = C1 − C0.
//!
//! The identity follows from sym(F_{n−1/2}ᵀ (F1 − F0)) = ΔC/2 (the skew part
//! (F0ᵀF1 − F1ᵀF0)/2 drops out against the symmetric Σ^algo): Π^algo : ΔF = ½ Σ^algo : ΔC =
//! ½ S : ΔC + [ΔW − ½ S : ΔC] = ΔW.
//!
//! Round-off. The laws compute W(F1) − W(F0) without cancellation
//! ([`Hyperelastic2d::energy_difference`]), so the bracket of Σ^algo has an absolute error of order
//! ε_mach |S| |ΔC| and the correction term an error of order ε_mach |S| however small ΔC is: the
//! stress never amplifies round-off. The correction is dropped (the limit ΔC → 0) only when
//! |ΔC| ≤ ε_mach |C_{n−1/2}|, where it is O(|ΔC|²) and the identity still holds to round-off.
//!
//! Inadmissible states. Neo-Hooke needs J = det F > 0. For J ≤ 0 (or a non-finite F) its
//! `energy` is +∞ and its stresses and tangents are NaN; a caller (a Newton iteration, a line
//! search) tests [`Hyperelastic2d::admissible`] on each element's F and rejects or cuts the step.
//! St Venant–Kirchhoff and the linear law are defined for every finite F.

use std::fmt::Debug;

use nalgebra::Matrix2;
use serde::{Deserialize, Serialize};

use crate::error::{require_positive, InputError};

/// A hyperelastic law of plane strain, W(F) per unit reference area (unit thickness).
pub trait Hyperelastic2d: Send + Sync + Debug {
    /// W(F), the stored energy per unit reference volume (+∞ for an inadmissible F).
    fn energy(&self, f: &Matrix2<f64>) -> f64;

    /// W(F1) − W(F0), computed without cancellation where the law allows it (the default subtracts).
    fn energy_difference(&self, f0: &Matrix2<f64>, f1: &Matrix2<f64>) -> f64 {
        self.energy(f1) - self.energy(f0)
    }

    /// The first Piola–Kirchhoff stress P = ∂W/∂F (BDS (1.14)).
    fn piola(&self, f: &Matrix2<f64>) -> Matrix2<f64>;

    /// dP = ∂P/∂F : dF, the tangent applied to dF.
    fn tangent(&self, f: &Matrix2<f64>, df: &Matrix2<f64>) -> Matrix2<f64>;

    /// A discrete gradient Π^algo(F0, F1): Π^algo : (F1 − F0) = W(F1) − W(F0) exactly
    /// (BDS (1.41)–(1.43)), with Π^algo(F, F) = P(F).
    fn discrete_gradient(&self, f0: &Matrix2<f64>, f1: &Matrix2<f64>) -> Matrix2<f64>;

    /// ∂Π^algo/∂F1 : dF1, the derivative of [`Hyperelastic2d::discrete_gradient`] with respect to
    /// its second argument (the Newton tangent of the energy-conserving step).
    fn discrete_gradient_tangent(
        &self,
        f0: &Matrix2<f64>,
        f1: &Matrix2<f64>,
        df1: &Matrix2<f64>,
    ) -> Matrix2<f64>;

    /// Whether F lies in the domain of W (finite entries; for neo-Hooke also det F > 0). Outside
    /// it the energy is +∞ and the stresses are NaN.
    fn admissible(&self, f: &Matrix2<f64>) -> bool {
        f.iter().all(|v| v.is_finite())
    }

    /// Whether the law is the small-strain (geometrically linear) one.
    fn is_small_strain(&self) -> bool;

    /// The out-of-plane stress σ_33 of plane strain (F_33 = 1), in the measure of
    /// [`crate::material::stress_state`]: the small-strain law's σ_33 = λ tr ε
    /// (= κ (σ_11 + σ_22)), the finite-strain laws' Cauchy σ_33 = S_33 / J (F_33 = 1), NaN
    /// outside the law's domain.
    fn out_of_plane_stress(&self, f: &Matrix2<f64>) -> f64;

    /// A short description for reports.
    fn describe(&self) -> String;

    /// Checks the constants; errors name `field.lambda` or `field.mu`.
    fn validate(&self, field: &str) -> Result<(), InputError>;

    /// The longitudinal wave speed √((λ + 2μ)/ρ) at F = I, for time-step guidance (NaN unless
    /// density > 0).
    fn wave_speed(&self, density: f64) -> f64;
}

/// A hyperelastic law of a bar, W(F) per unit reference volume with F = 1 + u_x.
pub trait Hyperelastic1d: Send + Sync + Debug {
    /// W(F).
    fn energy(&self, f: f64) -> f64;

    /// W(F1) − W(F0), computed without cancellation where the law allows it.
    fn energy_difference(&self, f0: f64, f1: f64) -> f64 {
        self.energy(f1) - self.energy(f0)
    }

    /// P = W′(F).
    fn piola(&self, f: f64) -> f64;

    /// dP/dF = W″(F) (the tangent stiffness; multiply by dF for the increment).
    fn tangent(&self, f: f64) -> f64;

    /// The discrete gradient Π^algo(F0, F1) = (W(F1) − W(F0))/(F1 − F0), extended by P(F) at
    /// F1 = F0 (Gonzalez's (BDS (1.42)) in one dimension).
    fn discrete_gradient(&self, f0: f64, f1: f64) -> f64;

    /// ∂Π^algo/∂F1 (exact).
    fn discrete_gradient_tangent(&self, f0: f64, f1: f64) -> f64;

    /// Whether F lies in the domain of W (finite).
    fn admissible(&self, f: f64) -> bool {
        f.is_finite()
    }

    /// Whether the law is the small-strain one.
    fn is_small_strain(&self) -> bool;

    /// A short description for reports.
    fn describe(&self) -> String;

    /// Checks the constants; errors name `field.young`.
    fn validate(&self, field: &str) -> Result<(), InputError>;

    /// The wave speed √(E/ρ) at F = 1.
    fn wave_speed(&self, density: f64) -> f64;
}

/// Plane-strain Lamé constants from Young's modulus and Poisson's ratio:
/// λ = Eκ/((1 + κ)(1 − 2κ)), μ = E/(2(1 + κ)). Errors name `young` or `poisson`.
pub fn lame_from_young_poisson(young: f64, poisson: f64) -> Result<(f64, f64), InputError> {
    require_positive("young", young)?;
    if !(poisson.is_finite() && poisson > -1.0 && poisson < 0.5) {
        return Err(InputError::new(
            "poisson",
            poisson,
            "a number in the open interval (-1, 1/2)",
        ));
    }
    let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    let mu = young / (2.0 * (1.0 + poisson));
    Ok((lambda, mu))
}

/// μ > 0 and 3λ + 2μ > 0 (a positive bulk modulus: exactly the range E > 0, −1 < κ < 1/2).
fn check_lame(prefix: &str, lambda: f64, mu: f64) -> Result<(), InputError> {
    let name = |n: &str| {
        if prefix.is_empty() {
            n.to_string()
        } else {
            format!("{prefix}.{n}")
        }
    };
    require_positive(&name("mu"), mu)?;
    if !(lambda.is_finite() && 3.0 * lambda + 2.0 * mu > 0.0) {
        return Err(InputError::new(
            name("lambda"),
            lambda,
            format!(
                "a finite number > -2μ/3 = {} (E > 0, -1 < κ < 1/2)",
                -2.0 * mu / 3.0
            ),
        ));
    }
    Ok(())
}

/// The constructors and constant checks shared by the plane laws with Lamé constants.
macro_rules! lame_law {
    ($law:ident) => {
        impl $law {
            /// From Young's modulus E and Poisson's ratio κ in plane strain; errors name `young`
            /// or `poisson`.
            pub fn from_young_poisson(young: f64, poisson: f64) -> Result<Self, InputError> {
                let (lambda, mu) = lame_from_young_poisson(young, poisson)?;
                Ok(Self { lambda, mu })
            }

            /// From the Lamé constants (λ, μ); errors name `lambda` or `mu`.
            pub fn from_lame(lambda: f64, mu: f64) -> Result<Self, InputError> {
                check_lame("", lambda, mu)?;
                Ok(Self { lambda, mu })
            }
        }
    };
}

/// The methods of [`Hyperelastic2d`] that every law with Lamé constants (λ, μ) shares, for a law
/// called `$name` in descriptions: whether it is small-strain, its description, the check of
/// (λ, μ), and the P-wave speed sqrt((λ + 2μ)/ρ). Invoked inside the law's `impl`.
macro_rules! lame_law_methods {
    ($name:literal, small_strain: $small:literal) => {
        fn is_small_strain(&self) -> bool {
            $small
        }

        fn describe(&self) -> String {
            format!(
                concat!($name, ", plane strain (λ = {}, μ = {})"),
                self.lambda, self.mu
            )
        }

        fn validate(&self, field: &str) -> Result<(), InputError> {
            check_lame(field, self.lambda, self.mu)
        }

        fn wave_speed(&self, density: f64) -> f64 {
            ((self.lambda + 2.0 * self.mu) / density).sqrt()
        }
    };
}

/// The methods of [`Hyperelastic1d`] that every bar law with Young's modulus E shares, for a law
/// called `$name` in descriptions: whether it is small-strain, its description, the check of E,
/// and the wave speed sqrt(E/ρ). Invoked inside the law's `impl`.
macro_rules! young_law_methods {
    ($name:literal, small_strain: $small:literal) => {
        fn is_small_strain(&self) -> bool {
            $small
        }

        fn describe(&self) -> String {
            format!(concat!($name, " (E = {})"), self.young)
        }

        fn validate(&self, field: &str) -> Result<(), InputError> {
            check_young(field, self.young)
        }

        fn wave_speed(&self, density: f64) -> f64 {
            (self.young / density).sqrt()
        }
    };
}

// ---------------------------------------------------------------------------------------------
// Small 2×2 tensor algebra.

/// A : B = Σ A_ij B_ij.
#[inline]
fn ddot(a: &Matrix2<f64>, b: &Matrix2<f64>) -> f64 {
    a.dot(b)
}

/// A + Aᵀ.
#[inline]
fn twice_sym(a: &Matrix2<f64>) -> Matrix2<f64> {
    a + a.transpose()
}

/// The cofactor matrix, ∂ det F/∂F: det(F + G) = det F + cof F : G + det G (exact in 2D).
#[inline]
fn cofactor(f: &Matrix2<f64>) -> Matrix2<f64> {
    Matrix2::new(f[(1, 1)], -f[(1, 0)], -f[(0, 1)], f[(0, 0)])
}

#[inline]
fn det(f: &Matrix2<f64>) -> f64 {
    f[(0, 0)] * f[(1, 1)] - f[(0, 1)] * f[(1, 0)]
}

/// ln det F for F = I + H, as ln(1 + tr H + det H) without cancellation near F = I.
#[inline]
fn ln_det(f: &Matrix2<f64>) -> f64 {
    let h = f - Matrix2::identity();
    (h.trace() + det(&h)).ln_1p()
}

/// The Green–Lagrange strain E = (C − I)/2 = (H + Hᵀ + HᵀH)/2, H = F − I.
#[inline]
fn green_lagrange(f: &Matrix2<f64>) -> Matrix2<f64> {
    let h = f - Matrix2::identity();
    0.5 * (twice_sym(&h) + h.transpose() * h)
}

fn nan_matrix() -> Matrix2<f64> {
    Matrix2::from_element(f64::NAN)
}

// ---------------------------------------------------------------------------------------------
// (a) Linear elasticity.

/// Small-strain linear elasticity (BDS §1.7, the ball test):
/// W = λ/2 (tr ε)² + μ ε : ε, ε = sym(F − I), P = σ(ε) = λ tr ε I + 2μ ε.
///
/// Its discrete gradient is the stress at the midpoint strain, σ((ε0 + ε1)/2), exact because W is
/// quadratic (the midpoint rule conserves energy, BDS §1.6.1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LinearElastic {
    pub lambda: f64,
    pub mu: f64,
}

lame_law!(LinearElastic);

impl LinearElastic {
    /// σ(ε) = λ tr ε I + 2μ ε.
    pub fn stress(&self, eps: &Matrix2<f64>) -> Matrix2<f64> {
        Matrix2::identity() * (self.lambda * eps.trace()) + eps * (2.0 * self.mu)
    }

    /// ε = sym(F − I).
    pub fn strain(f: &Matrix2<f64>) -> Matrix2<f64> {
        0.5 * twice_sym(&(f - Matrix2::identity()))
    }
}

impl Hyperelastic2d for LinearElastic {
    fn energy(&self, f: &Matrix2<f64>) -> f64 {
        let eps = Self::strain(f);
        0.5 * self.lambda * eps.trace().powi(2) + self.mu * ddot(&eps, &eps)
    }

    /// W(F1) − W(F0) = σ(ε_mid) : (ε1 − ε0), exact for the quadratic W.
    fn energy_difference(&self, f0: &Matrix2<f64>, f1: &Matrix2<f64>) -> f64 {
        let eps_mid = Self::strain(&(0.5 * (f0 + f1)));
        let d_eps = 0.5 * twice_sym(&(f1 - f0));
        ddot(&self.stress(&eps_mid), &d_eps)
    }

    fn piola(&self, f: &Matrix2<f64>) -> Matrix2<f64> {
        self.stress(&Self::strain(f))
    }

    /// σ_33 = λ tr ε (ε_33 = 0).
    fn out_of_plane_stress(&self, f: &Matrix2<f64>) -> f64 {
        self.lambda * Self::strain(f).trace()
    }

    fn tangent(&self, _f: &Matrix2<f64>, df: &Matrix2<f64>) -> Matrix2<f64> {
        self.stress(&(0.5 * twice_sym(df)))
    }

    /// σ(ε((F0 + F1)/2)).
    fn discrete_gradient(&self, f0: &Matrix2<f64>, f1: &Matrix2<f64>) -> Matrix2<f64> {
        self.piola(&(0.5 * (f0 + f1)))
    }

    /// ½ σ(sym dF1) (exact).
    fn discrete_gradient_tangent(
        &self,
        _f0: &Matrix2<f64>,
        _f1: &Matrix2<f64>,
        df1: &Matrix2<f64>,
    ) -> Matrix2<f64> {
        0.5 * self.tangent(&Matrix2::identity(), df1)
    }

    lame_law_methods!("linear elastic", small_strain: true);
}

// ---------------------------------------------------------------------------------------------
// (b) St Venant–Kirchhoff.

/// St Venant–Kirchhoff: W̃(C) = λ/8 (tr C − 2)² + μ/4 tr((C − I)²), i.e.
/// W = λ/2 (tr E)² + μ E : E with E = (C − I)/2, S = 2 ∂W̃/∂C = λ tr E I + 2μ E, P = F S.
///
/// W̃ is quadratic in C, so W̃(C1) − W̃(C0) = ½ S(C_{n−1/2}) : ΔC exactly and the correction term of
/// Gonzalez's Σ^algo (BDS (1.42)) vanishes identically: the discrete gradient is
/// Π^algo = F_{n−1/2} S(C_{n−1/2}), with an exact tangent and no guard needed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StVenantKirchhoff {
    pub lambda: f64,
    pub mu: f64,
}

lame_law!(StVenantKirchhoff);

impl StVenantKirchhoff {
    /// S(E) = λ tr E I + 2μ E (linear in E).
    pub fn second_piola(&self, e: &Matrix2<f64>) -> Matrix2<f64> {
        Matrix2::identity() * (self.lambda * e.trace()) + e * (2.0 * self.mu)
    }
}

impl Hyperelastic2d for StVenantKirchhoff {
    fn energy(&self, f: &Matrix2<f64>) -> f64 {
        let e = green_lagrange(f);
        0.5 * self.lambda * e.trace().powi(2) + self.mu * ddot(&e, &e)
    }

    /// ½ S(E_mid) : ΔC with ΔC = 2 sym(F_midᵀ ΔF): exact, no cancellation.
    fn energy_difference(&self, f0: &Matrix2<f64>, f1: &Matrix2<f64>) -> f64 {
        let e_mid = 0.5 * (green_lagrange(f0) + green_lagrange(f1));
        let f_mid = 0.5 * (f0 + f1);
        let half_dc = 0.5 * twice_sym(&(f_mid.transpose() * (f1 - f0)));
        ddot(&self.second_piola(&e_mid), &half_dc)
    }

    fn piola(&self, f: &Matrix2<f64>) -> Matrix2<f64> {
        f * self.second_piola(&green_lagrange(f))
    }

    /// S_33 = λ tr E (E_33 = 0), σ_33 = S_33 / J.
    fn out_of_plane_stress(&self, f: &Matrix2<f64>) -> f64 {
        self.lambda * green_lagrange(f).trace() / det(f)
    }

    /// dP = dF S + F S(dE), dE = sym(Fᵀ dF).
    fn tangent(&self, f: &Matrix2<f64>, df: &Matrix2<f64>) -> Matrix2<f64> {
        let s = self.second_piola(&green_lagrange(f));
        let de = 0.5 * twice_sym(&(f.transpose() * df));
        df * s + f * self.second_piola(&de)
    }

    /// Π^algo = F_{n−1/2} S(C_{n−1/2}) (BDS (1.42) with its vanishing correction).
    fn discrete_gradient(&self, f0: &Matrix2<f64>, f1: &Matrix2<f64>) -> Matrix2<f64> {
        let e_mid = 0.5 * (green_lagrange(f0) + green_lagrange(f1));
        0.5 * (f0 + f1) * self.second_piola(&e_mid)
    }

    /// ½ dF1 S(E_mid) + F_mid S(½ sym(F1ᵀ dF1)) (exact).
    fn discrete_gradient_tangent(
        &self,
        f0: &Matrix2<f64>,
        f1: &Matrix2<f64>,
        df1: &Matrix2<f64>,
    ) -> Matrix2<f64> {
        let e_mid = 0.5 * (green_lagrange(f0) + green_lagrange(f1));
        let d_e_mid = 0.25 * twice_sym(&(f1.transpose() * df1));
        0.5 * df1 * self.second_piola(&e_mid) + 0.5 * (f0 + f1) * self.second_piola(&d_e_mid)
    }

    lame_law_methods!("St Venant-Kirchhoff", small_strain: false);
}

// ---------------------------------------------------------------------------------------------
// (c) Neo-Hooke.

/// Compressible neo-Hooke in plane strain: W = μ/2 (tr C − 2 − 2 ln J) + λ/2 (ln J)², J = det F > 0;
/// in C: W̃(C) = μ/2 (tr C − 2 − ln det C) + λ/8 (ln det C)²,
/// S = 2 ∂W̃/∂C = μ (I − C⁻¹) + λ ln J C⁻¹, P = F S = μ (F − F⁻ᵀ) + λ ln J F⁻ᵀ.
///
/// The discrete gradient is Gonzalez's (BDS (1.42)) with the correction term. Its tangent is the
/// exact derivative when |ΔC| > √ε_mach |C_{n−1/2}|; below, where the exact formula would divide
/// round-off by |ΔC|, the derivative of the O(|ΔC|²) correction is dropped, a consistent
/// approximation with relative error O(√ε_mach) ≈ 1e−8 (Newton still converges quadratically to
/// that level and linearly beyond, far below any useful tolerance).
///
/// For J ≤ 0 the energy is +∞ and stresses and tangents are NaN: test
/// [`Hyperelastic2d::admissible`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NeoHooke {
    pub lambda: f64,
    pub mu: f64,
}

lame_law!(NeoHooke);

/// The quantities of Gonzalez's formula for one pair (F0, F1).
struct GonzalezMidpoint {
    f_mid: Matrix2<f64>,
    c_mid: Matrix2<f64>,
    delta_c: Matrix2<f64>,
    s_mid: Matrix2<f64>,
    /// q = W̃(C1) − W̃(C0) − ½ S(C_mid) : ΔC.
    q: f64,
    /// n = ΔC : ΔC.
    n: f64,
    /// |C_mid|², the scale of the guards.
    c_scale2: f64,
}

impl GonzalezMidpoint {
    /// Σ^algo = S(C_mid) + 2 q ΔC/n, or S(C_mid) when |ΔC| ≤ ε_mach |C_mid|.
    fn sigma(&self) -> Matrix2<f64> {
        let eps = f64::EPSILON;
        if self.n > eps * eps * self.c_scale2 {
            self.s_mid + self.delta_c * (2.0 * self.q / self.n)
        } else {
            self.s_mid
        }
    }
}

impl NeoHooke {
    /// S(C) = μ (I − C⁻¹) + λ ln J C⁻¹, ln J = ½ ln det C (C symmetric positive definite).
    fn s_of_c(&self, c: &Matrix2<f64>) -> Matrix2<f64> {
        let det_c = det(c);
        let c_inv = cofactor(c) / det_c;
        let ln_j = 0.5 * det_c.ln();
        (Matrix2::identity() - c_inv) * self.mu + c_inv * (self.lambda * ln_j)
    }

    /// dS = (μ − λ ln J) C⁻¹ dC C⁻¹ + λ/2 (C⁻¹ : dC) C⁻¹.
    fn ds_of_c(&self, c: &Matrix2<f64>, dc: &Matrix2<f64>) -> Matrix2<f64> {
        let det_c = det(c);
        let c_inv = cofactor(c) / det_c;
        let ln_j = 0.5 * det_c.ln();
        c_inv * dc * c_inv * (self.mu - self.lambda * ln_j)
            + c_inv * (0.5 * self.lambda * ddot(&c_inv, dc))
    }

    fn midpoint(&self, f0: &Matrix2<f64>, f1: &Matrix2<f64>) -> Option<GonzalezMidpoint> {
        if !(self.admissible(f0) && self.admissible(f1)) {
            return None;
        }
        let f_mid = 0.5 * (f0 + f1);
        let delta_c = twice_sym(&(f_mid.transpose() * (f1 - f0)));
        let c_mid = 0.5 * (f0.transpose() * f0 + f1.transpose() * f1);
        let s_mid = self.s_of_c(&c_mid);
        let q = self.energy_difference(f0, f1) - 0.5 * ddot(&s_mid, &delta_c);
        Some(GonzalezMidpoint {
            f_mid,
            c_mid,
            delta_c,
            s_mid,
            q,
            n: ddot(&delta_c, &delta_c),
            c_scale2: ddot(&c_mid, &c_mid),
        })
    }
}

impl Hyperelastic2d for NeoHooke {
    fn energy(&self, f: &Matrix2<f64>) -> f64 {
        if !self.admissible(f) {
            return f64::INFINITY;
        }
        let h = f - Matrix2::identity();
        // tr C − 2 = 2 tr H + H : H
        let tr_c_minus_2 = 2.0 * h.trace() + ddot(&h, &h);
        let ln_j = ln_det(f);
        0.5 * self.mu * (tr_c_minus_2 - 2.0 * ln_j) + 0.5 * self.lambda * ln_j * ln_j
    }

    /// μ/2 (tr ΔC − 2 Δln J) + λ/2 Δln J (ln J0 + ln J1), with tr ΔC = 2 F_mid : ΔF and
    /// Δln J = ln(1 + (cof F0 : ΔF + det ΔF)/J0): no cancellation however close F0 and F1 are.
    fn energy_difference(&self, f0: &Matrix2<f64>, f1: &Matrix2<f64>) -> f64 {
        if !(self.admissible(f0) && self.admissible(f1)) {
            return self.energy(f1) - self.energy(f0);
        }
        let df = f1 - f0;
        let f_mid = 0.5 * (f0 + f1);
        let tr_dc = 2.0 * ddot(&f_mid, &df);
        let d_ln_j = ((ddot(&cofactor(f0), &df) + det(&df)) / det(f0)).ln_1p();
        0.5 * self.mu * (tr_dc - 2.0 * d_ln_j)
            + 0.5 * self.lambda * d_ln_j * (ln_det(f0) + ln_det(f1))
    }

    fn piola(&self, f: &Matrix2<f64>) -> Matrix2<f64> {
        if !self.admissible(f) {
            return nan_matrix();
        }
        let f_inv_t = cofactor(f) / det(f);
        (f - f_inv_t) * self.mu + f_inv_t * (self.lambda * ln_det(f))
    }

    /// S_33 = μ (1 − C_33⁻¹) + λ ln J C_33⁻¹ = λ ln J (C_33 = 1), σ_33 = λ ln J / J.
    fn out_of_plane_stress(&self, f: &Matrix2<f64>) -> f64 {
        if !self.admissible(f) {
            return f64::NAN;
        }
        self.lambda * ln_det(f) / det(f)
    }

    /// dP = μ dF + (μ − λ ln J) F⁻ᵀ dFᵀ F⁻ᵀ + λ (F⁻ᵀ : dF) F⁻ᵀ.
    fn tangent(&self, f: &Matrix2<f64>, df: &Matrix2<f64>) -> Matrix2<f64> {
        if !self.admissible(f) {
            return nan_matrix();
        }
        let f_inv_t = cofactor(f) / det(f);
        df * self.mu
            + f_inv_t * df.transpose() * f_inv_t * (self.mu - self.lambda * ln_det(f))
            + f_inv_t * (self.lambda * ddot(&f_inv_t, df))
    }

    /// Gonzalez: Π^algo = F_{n−1/2} Σ^algo (BDS (1.42)); NaN if F0 or F1 is inadmissible.
    fn discrete_gradient(&self, f0: &Matrix2<f64>, f1: &Matrix2<f64>) -> Matrix2<f64> {
        match self.midpoint(f0, f1) {
            Some(g) => g.f_mid * g.sigma(),
            None => nan_matrix(),
        }
    }

    /// dΠ = ½ dF1 Σ + F_mid dΣ with dC = dF1ᵀF1 + F1ᵀdF1, dΣ = dS(C_mid)[dC/2] +
    /// 2 [dq ΔC/n + q dC/n − q ΔC (2 ΔC : dC)/n²], dq = ½ S(C1) : dC − ½ dS_mid : ΔC − ½ S_mid : dC;
    /// the bracket is dropped when |ΔC| ≤ √ε_mach |C_mid| (see the type's documentation).
    fn discrete_gradient_tangent(
        &self,
        f0: &Matrix2<f64>,
        f1: &Matrix2<f64>,
        df1: &Matrix2<f64>,
    ) -> Matrix2<f64> {
        let Some(g) = self.midpoint(f0, f1) else {
            return nan_matrix();
        };
        let dc = twice_sym(&(f1.transpose() * df1));
        let ds_mid = self.ds_of_c(&g.c_mid, &(0.5 * dc));
        let mut d_sigma = ds_mid;
        if g.n > f64::EPSILON * g.c_scale2 {
            let s1 = self.s_of_c(&(f1.transpose() * f1));
            let dq = 0.5 * (ddot(&s1, &dc) - ddot(&ds_mid, &g.delta_c) - ddot(&g.s_mid, &dc));
            let dn = 2.0 * ddot(&g.delta_c, &dc);
            d_sigma += (g.delta_c * (dq / g.n) + dc * (g.q / g.n)
                - g.delta_c * (g.q * dn / (g.n * g.n)))
                * 2.0;
        }
        0.5 * df1 * g.sigma() + g.f_mid * d_sigma
    }

    /// Finite entries and J = det F > 0.
    fn admissible(&self, f: &Matrix2<f64>) -> bool {
        f.iter().all(|v| v.is_finite()) && det(f) > 0.0
    }

    lame_law_methods!("neo-Hooke", small_strain: false);
}

// ---------------------------------------------------------------------------------------------
// Bars.

fn check_young(field: &str, young: f64) -> Result<(), InputError> {
    let name = if field.is_empty() {
        "young".to_string()
    } else {
        format!("{field}.young")
    };
    require_positive(&name, young).map(|_| ())
}

/// A linear elastic bar: W = E/2 (F − 1)², P = E (F − 1); discrete gradient E((F0 + F1)/2 − 1)
/// (exact for the quadratic W).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LinearElastic1d {
    pub young: f64,
}

impl Hyperelastic1d for LinearElastic1d {
    fn energy(&self, f: f64) -> f64 {
        0.5 * self.young * (f - 1.0).powi(2)
    }

    fn energy_difference(&self, f0: f64, f1: f64) -> f64 {
        self.discrete_gradient(f0, f1) * (f1 - f0)
    }

    fn piola(&self, f: f64) -> f64 {
        self.young * (f - 1.0)
    }

    fn tangent(&self, _f: f64) -> f64 {
        self.young
    }

    fn discrete_gradient(&self, f0: f64, f1: f64) -> f64 {
        self.young * (0.5 * ((f0 - 1.0) + (f1 - 1.0)))
    }

    fn discrete_gradient_tangent(&self, _f0: f64, _f1: f64) -> f64 {
        0.5 * self.young
    }

    young_law_methods!("linear elastic bar", small_strain: true);
}

/// A St Venant–Kirchhoff bar: W = E/8 (F² − 1)², P = E/2 (F² − 1) F.
///
/// The discrete gradient (W(F1) − W(F0))/(F1 − F0) = E/8 (F0 + F1)(F0² + F1² − 2) is a polynomial
/// (it is Gonzalez's F_mid S(C_mid), the correction vanishing since W̃ is quadratic in C = F²):
/// no division, no guard, exact at F1 = F0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StVenantKirchhoff1d {
    pub young: f64,
}

impl Hyperelastic1d for StVenantKirchhoff1d {
    fn energy(&self, f: f64) -> f64 {
        0.125 * self.young * ((f - 1.0) * (f + 1.0)).powi(2)
    }

    fn energy_difference(&self, f0: f64, f1: f64) -> f64 {
        self.discrete_gradient(f0, f1) * (f1 - f0)
    }

    fn piola(&self, f: f64) -> f64 {
        0.5 * self.young * (f - 1.0) * (f + 1.0) * f
    }

    /// E/2 (3F² − 1).
    fn tangent(&self, f: f64) -> f64 {
        0.5 * self.young * (3.0 * f * f - 1.0)
    }

    fn discrete_gradient(&self, f0: f64, f1: f64) -> f64 {
        let s = (f0 - 1.0) * (f0 + 1.0) + (f1 - 1.0) * (f1 + 1.0);
        0.125 * self.young * (f0 + f1) * s
    }

    /// E/8 [(F0² + F1² − 2) + 2 F1 (F0 + F1)].
    fn discrete_gradient_tangent(&self, f0: f64, f1: f64) -> f64 {
        let s = (f0 - 1.0) * (f0 + 1.0) + (f1 - 1.0) * (f1 + 1.0);
        0.125 * self.young * (s + 2.0 * f1 * (f0 + f1))
    }

    young_law_methods!("St Venant-Kirchhoff bar", small_strain: false);
}

#[cfg(test)]
mod tests {
    //! Plane-strain and bar hyperelastic laws, checked against their own definitions: P and every
    //! tangent against central finite differences, the discrete-gradient identity (BDS (1.43)) to
    //! round-off (random, nearly equal and equal pairs), objectivity, the small-strain limit, and
    //! typed errors for bad constants and inverted elements.
    use super::*;
    use crate::material::plane_law::IsotropicLinear;

    const YOUNG: f64 = 210.0;
    const POISSON: f64 = 0.3;

    fn linear() -> LinearElastic {
        LinearElastic::from_young_poisson(YOUNG, POISSON).unwrap()
    }
    fn svk() -> StVenantKirchhoff {
        StVenantKirchhoff::from_young_poisson(YOUNG, POISSON).unwrap()
    }
    fn neo_hooke() -> NeoHooke {
        NeoHooke::from_young_poisson(YOUNG, POISSON).unwrap()
    }
    fn laws() -> Vec<Box<dyn Hyperelastic2d>> {
        vec![Box::new(linear()), Box::new(svk()), Box::new(neo_hooke())]
    }
    fn finite_strain_laws() -> Vec<Box<dyn Hyperelastic2d>> {
        vec![Box::new(svk()), Box::new(neo_hooke())]
    }

    /// SplitMix64: a deterministic pseudo-random stream, uniform numbers in (−a, a).
    struct Rng(u64);
    impl Rng {
        fn uniform(&mut self, a: f64) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            let u = (z >> 11) as f64 / (1u64 << 53) as f64;
            a * (2.0 * u - 1.0)
        }
        fn matrix(&mut self, a: f64) -> Matrix2<f64> {
            Matrix2::new(
                self.uniform(a),
                self.uniform(a),
                self.uniform(a),
                self.uniform(a),
            )
        }
        /// F = I + G with |G_ij| < a and det F ≥ 0.1.
        fn deformation(&mut self, a: f64) -> Matrix2<f64> {
            loop {
                let f = Matrix2::identity() + self.matrix(a);
                if f.determinant() >= 0.1 {
                    return f;
                }
            }
        }
    }

    fn rotation(theta: f64) -> Matrix2<f64> {
        Matrix2::new(theta.cos(), -theta.sin(), theta.sin(), theta.cos())
    }

    /// Identity, moderate, large stretch, large shear, rotated stretch, compression.
    fn sample_deformations() -> Vec<Matrix2<f64>> {
        vec![
            Matrix2::identity(),
            Matrix2::new(1.1, 0.2, -0.1, 0.95),
            Matrix2::new(2.5, 0.0, 0.0, 0.6),
            Matrix2::new(1.0, 1.5, 0.0, 1.0),
            rotation(0.7) * Matrix2::new(1.8, 0.4, 0.3, 0.7),
            Matrix2::new(0.5, -0.3, 0.2, 0.4),
        ]
    }

    fn directions() -> [Matrix2<f64>; 2] {
        [
            Matrix2::new(0.3, -0.7, 0.5, 0.2),
            Matrix2::new(-0.4, 0.1, 0.9, -0.6),
        ]
    }

    /// |a − b| / max(|a|, |b|, floor).
    fn rel(a: &Matrix2<f64>, b: &Matrix2<f64>, floor: f64) -> f64 {
        (a - b).norm() / a.norm().max(b.norm()).max(floor)
    }

    fn unit(i: usize, j: usize) -> Matrix2<f64> {
        let mut e = Matrix2::zeros();
        e[(i, j)] = 1.0;
        e
    }

    #[test]
    fn lame_constants_from_young_and_poisson() {
        let (lambda, mu) = lame_from_young_poisson(210.0, 0.25).unwrap();
        assert!((lambda - 84.0).abs() < 1e-12 && (mu - 84.0).abs() < 1e-12);
        let law = NeoHooke::from_lame(84.0, 84.0).unwrap();
        assert!((law.wave_speed(7.0) - 6.0).abs() < 1e-14); // √((84 + 168)/7)
        assert!((LinearElastic1d { young: 9.0 }.wave_speed(4.0) - 1.5).abs() < 1e-15);
    }

    #[test]
    fn energies_match_the_paper_forms_in_c() {
        let (svk, nh) = (svk(), neo_hooke());
        for f in sample_deformations() {
            let c = f.transpose() * f;
            let cm = c - Matrix2::identity();
            let w_svk =
                svk.lambda / 8.0 * (c.trace() - 2.0).powi(2) + svk.mu / 4.0 * (cm * cm).trace();
            assert!((svk.energy(&f) - w_svk).abs() <= 1e-13 * w_svk.max(1.0));
            let ln_j = f.determinant().ln();
            let w_nh = nh.mu / 2.0 * (c.trace() - 2.0 - 2.0 * ln_j) + nh.lambda / 2.0 * ln_j * ln_j;
            assert!((nh.energy(&f) - w_nh).abs() <= 1e-13 * w_nh.max(1.0));
        }
    }

    #[test]
    fn piola_matches_central_differences_of_energy() {
        let h = 1e-6;
        for law in laws() {
            for f in sample_deformations() {
                let p = law.piola(&f);
                let mut fd = Matrix2::zeros();
                for i in 0..2 {
                    for j in 0..2 {
                        let e = unit(i, j);
                        fd[(i, j)] =
                            (law.energy(&(f + h * e)) - law.energy(&(f - h * e))) / (2.0 * h);
                    }
                }
                let err = rel(&p, &fd, YOUNG);
                assert!(err < 1e-7, "{}: F = {f}, error {err:e}", law.describe());
            }
        }
    }

    #[test]
    fn tangent_matches_central_differences_of_piola() {
        let h = 1e-6;
        for law in laws() {
            for f in sample_deformations() {
                for d in directions() {
                    let fd = (law.piola(&(f + h * d)) - law.piola(&(f - h * d))) / (2.0 * h);
                    let err = rel(&law.tangent(&f, &d), &fd, YOUNG);
                    assert!(err < 1e-7, "{}: F = {f}, error {err:e}", law.describe());
                }
            }
        }
    }

    #[test]
    fn linear_stress_is_plane_strain_hooke() {
        let law = linear();
        let hooke = IsotropicLinear::plane_strain(YOUNG, POISSON);
        let f = Matrix2::new(1.01, 0.003, -0.007, 0.98);
        let eps = LinearElastic::strain(&f);
        let s = hooke.apply(&[eps[(0, 0)], eps[(1, 1)], eps[(0, 1)]]);
        let p = law.piola(&f);
        let expected = Matrix2::new(s[0], s[2], s[2], s[1]);
        assert!(rel(&p, &expected, 1.0) < 1e-14);
        // W = ½ σ : ε
        assert!((law.energy(&f) - 0.5 * ddot(&p, &eps)).abs() < 1e-14 * law.energy(&f));
    }

    #[test]
    fn finite_strain_tangents_at_identity_are_plane_strain_hooke() {
        let lin = linear();
        for law in finite_strain_laws() {
            for d in directions() {
                let err = rel(
                    &law.tangent(&Matrix2::identity(), &d),
                    &lin.tangent(&Matrix2::identity(), &d),
                    1.0,
                );
                assert!(err < 1e-14, "{}: error {err:e}", law.describe());
            }
            assert!(law.piola(&Matrix2::identity()).norm() < 1e-12);
            assert!((law.wave_speed(2.0) - lin.wave_speed(2.0)).abs() < 1e-14);
        }
    }

    #[test]
    fn gonzalez_stress_is_exact_discrete_gradient_for_random_pairs() {
        let mut rng = Rng(7);
        for law in laws() {
            let mut worst: f64 = 0.0;
            for _ in 0..2000 {
                let f0 = rng.deformation(0.6);
                let f1 = loop {
                    let f1 = f0 + rng.matrix(0.4);
                    if f1.determinant() >= 0.1 {
                        break f1;
                    }
                };
                let pi = law.discrete_gradient(&f0, &f1);
                let df = f1 - f0;
                let dw = law.energy_difference(&f0, &f1);
                let scale = pi.norm() * df.norm();
                worst = worst.max((ddot(&pi, &df) - dw).abs() / scale);
                // the cancellation-free difference agrees with the subtracted energies
                let (w0, w1) = (law.energy(&f0), law.energy(&f1));
                assert!((dw - (w1 - w0)).abs() <= 4.0 * f64::EPSILON * (w0 + w1 + scale));
            }
            assert!(
                worst < 1e-14,
                "{}: worst relative defect {worst:e}",
                law.describe()
            );
        }
    }

    #[test]
    fn discrete_gradient_identity_holds_for_nearly_equal_and_equal_pairs() {
        let [d, _] = directions();
        for law in laws() {
            for f0 in sample_deformations() {
                for k in 1..=16 {
                    let h = 10f64.powi(-k);
                    let f1 = f0 + h * d;
                    let pi = law.discrete_gradient(&f0, &f1);
                    assert!(pi.iter().all(|v| v.is_finite()));
                    let df = f1 - f0;
                    let dw = law.energy_difference(&f0, &f1);
                    let scale = pi.norm().max(1.0) * df.norm();
                    let defect = (ddot(&pi, &df) - dw).abs() / scale;
                    assert!(
                        defect < 1e-14,
                        "{}: F0 = {f0}, h = {h:e}, defect {defect:e}",
                        law.describe()
                    );
                    // against the midpoint rule W(F1) − W(F0) = P(F_mid) : ΔF + O(|ΔF|³): no
                    // cancellation in energy_difference however small ΔF is
                    let mid = ddot(&law.piola(&(0.5 * (f0 + f1))), &df);
                    // (P(F_mid) itself carries the rounding of F_mid, ε |F| |∂P/∂F|; a subtraction
                    // W(F1) − W(F0) would be off by ε W ~ ε YOUNG |F|⁴, far above this bound)
                    let rounding = 100.0 * f64::EPSILON * YOUNG * (1.0 + f0.norm_squared());
                    let bound =
                        (10.0 * YOUNG * df.norm_squared() + rounding) * df.norm() + 1e-14 * scale;
                    assert!((dw - mid).abs() <= bound, "{}: h = {h:e}", law.describe());
                }
                let pi = law.discrete_gradient(&f0, &f0);
                assert!(
                    rel(&pi, &law.piola(&f0), YOUNG) < 1e-14,
                    "{}: F = {f0}",
                    law.describe()
                );
                assert_eq!(law.energy_difference(&f0, &f0), 0.0);
            }
        }
    }

    #[test]
    fn discrete_gradient_tends_to_piola_as_f1_tends_to_f0() {
        let [d, _] = directions();
        for law in laws() {
            for f in sample_deformations() {
                let err = |h: f64| (law.discrete_gradient(&f, &(f + h * d)) - law.piola(&f)).norm();
                let err_mid = |h: f64| {
                    let f1 = f + h * d;
                    (law.discrete_gradient(&f, &f1) - law.piola(&(0.5 * (f + f1)))).norm()
                };
                let floor = 1e-12 * YOUNG;
                // first order towards P(F0), second order towards P(F_mid)
                assert!(
                    err(1e-4) <= 0.011 * err(1e-2) + floor,
                    "{}: F = {f}",
                    law.describe()
                );
                assert!(
                    err_mid(1e-3) <= 0.011 * err_mid(1e-2) + floor,
                    "{}: F = {f}",
                    law.describe()
                );
                assert!(err(1e-10) <= 1e-7 * YOUNG);
            }
        }
    }

    #[test]
    fn discrete_gradient_tangent_matches_central_differences() {
        let mut rng = Rng(11);
        let h = 1e-6;
        for law in laws() {
            for _ in 0..200 {
                let f0 = rng.deformation(0.6);
                let f1 = f0 + rng.matrix(0.3);
                let d = rng.matrix(1.0);
                if (f1 - h * d).determinant() < 0.1 || (f1 + h * d).determinant() < 0.1 {
                    continue;
                }
                let fd = (law.discrete_gradient(&f0, &(f1 + h * d))
                    - law.discrete_gradient(&f0, &(f1 - h * d)))
                    / (2.0 * h);
                let err = rel(&law.discrete_gradient_tangent(&f0, &f1, &d), &fd, YOUNG);
                assert!(
                    err < 1e-7,
                    "{}: F0 = {f0}, F1 = {f1}, error {err:e}",
                    law.describe()
                );
            }
            for f0 in sample_deformations() {
                for d in directions() {
                    for gap in [0.3, 1e-2, 1e-4] {
                        let f1 = f0 + gap * directions()[1];
                        let fd = (law.discrete_gradient(&f0, &(f1 + h * d))
                            - law.discrete_gradient(&f0, &(f1 - h * d)))
                            / (2.0 * h);
                        let err = rel(&law.discrete_gradient_tangent(&f0, &f1, &d), &fd, YOUNG);
                        assert!(
                            err < 1e-6,
                            "{}: F0 = {f0}, gap {gap}, error {err:e}",
                            law.describe()
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn discrete_gradient_tangent_of_close_pairs_is_half_the_midpoint_tangent() {
        // ∂Π/∂F1 → ½ ∂P/∂F as F1 → F0 (Π is symmetric in F0, F1), across the √ε guard of
        // neo-Hooke, without amplified round-off.
        let [g, d] = directions();
        for law in laws() {
            for f0 in sample_deformations() {
                for k in [4, 6, 7, 8, 9, 10, 12, 14, 16] {
                    let h = 10f64.powi(-k);
                    let f1 = f0 + h * g;
                    let half = 0.5 * law.tangent(&(0.5 * (f0 + f1)), &d);
                    let err = rel(&law.discrete_gradient_tangent(&f0, &f1, &d), &half, YOUNG);
                    assert!(
                        err < 5.0 * h + 1e-7,
                        "{}: F0 = {f0}, k = {k}, error {err:e}",
                        law.describe()
                    );
                }
                let exact = law.discrete_gradient_tangent(&f0, &f0, &d);
                assert!(rel(&exact, &(0.5 * law.tangent(&f0, &d)), YOUNG) < 1e-14);
            }
        }
    }

    #[test]
    fn finite_strain_laws_are_frame_indifferent() {
        let mut rng = Rng(3);
        for law in finite_strain_laws() {
            for _ in 0..100 {
                let q = rotation(rng.uniform(3.0));
                let (f0, f1) = (rng.deformation(0.6), rng.deformation(0.6));
                let w = law.energy(&f0);
                assert!((law.energy(&(q * f0)) - w).abs() <= 1e-13 * w.max(1.0));
                assert!(rel(&law.piola(&(q * f0)), &(q * law.piola(&f0)), YOUNG) < 1e-13);
                let pi = law.discrete_gradient(&(q * f0), &(q * f1));
                assert!(rel(&pi, &(q * law.discrete_gradient(&f0, &f1)), YOUNG) < 1e-12);
            }
        }
        // the small-strain law is not: a rigid rotation stores energy
        let lin = linear();
        assert!(lin.is_small_strain() && lin.energy(&rotation(0.5)) > 1.0);
        assert!(finite_strain_laws().iter().all(|l| !l.is_small_strain()));
    }

    #[test]
    fn invalid_constants_are_typed_errors_naming_the_field() {
        for (young, poisson, field) in [
            (0.0, 0.3, "young"),
            (-1.0, 0.3, "young"),
            (f64::NAN, 0.3, "young"),
            (f64::INFINITY, 0.3, "young"),
            (210.0, 0.5, "poisson"),
            (210.0, -1.0, "poisson"),
            (210.0, 0.7, "poisson"),
            (210.0, f64::NAN, "poisson"),
        ] {
            assert_eq!(
                NeoHooke::from_young_poisson(young, poisson)
                    .unwrap_err()
                    .field,
                field
            );
            assert_eq!(
                StVenantKirchhoff::from_young_poisson(young, poisson)
                    .unwrap_err()
                    .field,
                field
            );
            assert_eq!(
                LinearElastic::from_young_poisson(young, poisson)
                    .unwrap_err()
                    .field,
                field
            );
        }
        assert_eq!(NeoHooke::from_lame(1.0, 0.0).unwrap_err().field, "mu");
        assert_eq!(NeoHooke::from_lame(-1.0, 1.0).unwrap_err().field, "lambda");
        assert!(NeoHooke::from_lame(-0.5, 1.0).is_ok()); // κ < 0
        let bad = NeoHooke {
            lambda: 1.0,
            mu: -2.0,
        };
        assert_eq!(
            bad.validate("body.material").unwrap_err().field,
            "body.material.mu"
        );
        let bad = StVenantKirchhoff {
            lambda: f64::NAN,
            mu: 2.0,
        };
        assert_eq!(
            bad.validate("body.material").unwrap_err().field,
            "body.material.lambda"
        );
        assert!(neo_hooke().validate("body.material").is_ok());
        let err = LinearElastic1d { young: 0.0 }.validate("bar").unwrap_err();
        assert_eq!((err.field.as_str(), err.value.as_str()), ("bar.young", "0"));
        assert!(StVenantKirchhoff1d { young: -3.0 }.validate("bar").is_err());
    }

    #[test]
    fn neo_hooke_with_nonpositive_jacobian_is_flagged_without_panic() {
        let law = neo_hooke();
        let good = Matrix2::new(1.1, 0.1, 0.0, 0.9);
        for f in [
            Matrix2::new(1.0, 0.0, 0.0, -1.0),
            Matrix2::new(1.0, 1.0, 1.0, 1.0),
            Matrix2::zeros(),
            Matrix2::new(f64::NAN, 0.0, 0.0, 1.0),
        ] {
            assert!(!law.admissible(&f));
            assert_eq!(law.energy(&f), f64::INFINITY);
            let d = directions()[0];
            for s in [
                law.piola(&f),
                law.tangent(&f, &d),
                law.discrete_gradient(&good, &f),
                law.discrete_gradient(&f, &good),
                law.discrete_gradient_tangent(&good, &f, &d),
            ] {
                assert!(s.iter().all(|v| v.is_nan()));
            }
            assert!(!law.energy_difference(&good, &f).is_finite());
        }
        assert!(law.admissible(&good) && svk().admissible(&Matrix2::new(1.0, 0.0, 0.0, -1.0)));
        // the energy barrier grows without bound as J → 0+ (like λ/2 (ln J)²)
        let barrier = |j: f64| law.energy(&Matrix2::new(1.0, 0.0, 0.0, j));
        assert!(barrier(1e-8) > 10.0 * barrier(0.1) && barrier(1e-300) > 1e5);
    }

    #[test]
    fn bar_laws_match_their_energies_and_discrete_gradients() {
        let h = 1e-6;
        let bars: [Box<dyn Hyperelastic1d>; 2] = [
            Box::new(LinearElastic1d { young: YOUNG }),
            Box::new(StVenantKirchhoff1d { young: YOUNG }),
        ];
        let mut rng = Rng(5);
        for bar in &bars {
            for f in [1.0, 0.3, 0.9, 1.2, 2.5] {
                let fd_p = (bar.energy(f + h) - bar.energy(f - h)) / (2.0 * h);
                assert!((bar.piola(f) - fd_p).abs() <= 1e-7 * YOUNG.max(bar.piola(f).abs()));
                let fd_t = (bar.piola(f + h) - bar.piola(f - h)) / (2.0 * h);
                assert!((bar.tangent(f) - fd_t).abs() <= 1e-7 * YOUNG.max(bar.tangent(f).abs()));
                assert!((bar.discrete_gradient(f, f) - bar.piola(f)).abs() <= 1e-14 * YOUNG);
                assert!(
                    (bar.discrete_gradient_tangent(f, f) - 0.5 * bar.tangent(f)).abs()
                        <= 1e-13 * YOUNG
                );
            }
            for _ in 0..1000 {
                let f0 = 1.0 + rng.uniform(0.8);
                let f1 = f0 + rng.uniform(0.5) * 10f64.powi(-(rng.uniform(8.0).abs() as i32));
                let pi = bar.discrete_gradient(f0, f1);
                let dw = bar.energy_difference(f0, f1);
                let scale = pi.abs().max(1.0) * (f1 - f0).abs();
                assert!((pi * (f1 - f0) - dw).abs() <= 1e-14 * scale);
                let (w0, w1) = (bar.energy(f0), bar.energy(f1));
                assert!((dw - (w1 - w0)).abs() <= 4.0 * f64::EPSILON * (w0 + w1 + scale));
                let fd = (bar.discrete_gradient(f0, f1 + h) - bar.discrete_gradient(f0, f1 - h))
                    / (2.0 * h);
                assert!((bar.discrete_gradient_tangent(f0, f1) - fd).abs() <= 1e-7 * YOUNG);
            }
            assert!(bar.admissible(0.5) && !bar.admissible(f64::NAN));
            assert!(!bar.describe().is_empty());
        }
        assert!(bars[0].is_small_strain() && !bars[1].is_small_strain());
    }
}
