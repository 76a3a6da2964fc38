//! The node-to-segment constraint written in invariants, and the discrete gradient that makes its
//! work exact (the energy–momentum paper, "EM", (43)–(49) and (61)–(67); docs/multibody.md §2–§3).
//!
//! A slave node x_s and a master segment x_1 → x_2 (the master body on the left when walking from
//! x_1 to x_2) form the local coordinates x = (x_s, x_1, x_2) ∈ ℝ⁶. With a = x_2 − x_1 and
//! b = x_s − x_1, three quadratic invariants of x under translations and rotations,
//!
//!   π₁ = a·a,   π₂ = b × a = b_x a_y − b_y a_x,   π₃ = a·b,
//!
//! give the normal gap (EM (16), the closest-point projection onto the segment's line) and the
//! convective coordinate of the projection (EM (14)):
//!
//!   g(π) = π₂ / √π₁,   ξ(π) = π₃ / π₁.
//!
//! Each π_k is a homogeneous quadratic form, π_k(x) = ½ xᵀ H_k x with a constant 6 × 6 matrix H_k,
//! so ∇π_k(x) = H_k x and π_k(x₁) − π_k(x₀) = ((x₀ + x₁)/2)ᵀ H_k (x₁ − x₀) exactly. A function
//! f(π) of the invariants then has the discrete gradient (Gonzalez, EM (67))
//!
//!   ∇̄f(π₀, π₁) = ∇f(π_m) + [f(π₁) − f(π₀) − ∇f(π_m)·Δπ] Δπ / |Δπ|²,   π_m = (π₀ + π₁)/2,
//!
//! and the force direction G(x₀, x₁) = Σ_k ∇̄f_k H_k x_{1/2} satisfies G·(x₁ − x₀) = f(π₁) − f(π₀)
//! to round-off (the constraint's discrete work is exact), Σ G = 0 over the x- and y-components
//! (no resultant: linear momentum) and Σ x_{1/2} × G = 0 (no torque: angular momentum), because
//! every π_k is invariant under translations and rotations.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

/// 6-vectors of local coordinates (x_s, x_1, x_2).
pub type Local6 = SVector<f64, 6>;
/// 6 × 6 local matrices.
pub type Local66 = SMatrix<f64, 6, 6>;

/// Below this relative size of Δπ the discrete gradient is the midpoint gradient: the bracket of
/// (67) is then a difference of nearly equal numbers divided by |Δπ|.
const DG_GUARD: f64 = 1e-7;

/// The constant matrices H_k with π_k(x) = ½ xᵀ H_k x.
#[derive(Debug, Clone, Copy)]
pub struct InvariantForms {
    pub h: [Local66; 3],
}

impl InvariantForms {
    /// H₁ (a·a), H₂ (b × a), H₃ (a·b) for the ordering x = (x_s, x_1, x_2).
    pub fn new() -> Self {
        // selection matrices: a = A x, b = B x
        let mut a = SMatrix::<f64, 2, 6>::zeros();
        let mut b = SMatrix::<f64, 2, 6>::zeros();
        for c in 0..2 {
            a[(c, 4 + c)] = 1.0;
            a[(c, 2 + c)] = -1.0;
            b[(c, c)] = 1.0;
            b[(c, 2 + c)] = -1.0;
        }
        // a bilinear form aᵀ Q b has the Hessian Aᵀ Q B + Bᵀ Qᵀ A
        let form =
            |q: nalgebra::Matrix2<f64>| a.transpose() * q * b + b.transpose() * q.transpose() * a;
        let h1 = 2.0 * a.transpose() * a;
        // aᵀ R b = a_y b_x − a_x b_y = b × a
        let h2 = form(nalgebra::Matrix2::new(0.0, -1.0, 1.0, 0.0));
        let h3 = form(nalgebra::Matrix2::identity());
        Self { h: [h1, h2, h3] }
    }

    /// π(x).
    pub fn invariants(&self, x: &Local6) -> Vector3<f64> {
        Vector3::from_fn(|k, _| 0.5 * x.dot(&(self.h[k] * x)))
    }

    /// The 6 × 3 matrix [H₁ x | H₂ x | H₃ x] = Dπ(x)ᵀ.
    pub fn gradients(&self, x: &Local6) -> SMatrix<f64, 6, 3> {
        let mut p = SMatrix::<f64, 6, 3>::zeros();
        for k in 0..3 {
            p.set_column(k, &(self.h[k] * x));
        }
        p
    }

    /// Σ_k w_k H_k.
    pub fn weighted(&self, w: &Vector3<f64>) -> Local66 {
        self.h[0] * w[0] + self.h[1] * w[1] + self.h[2] * w[2]
    }
}

impl Default for InvariantForms {
    fn default() -> Self {
        Self::new()
    }
}

/// A scalar function of the invariants, with its gradient and Hessian.
pub trait InvariantFunction {
    fn value(&self, p: &Vector3<f64>) -> f64;
    fn gradient(&self, p: &Vector3<f64>) -> Vector3<f64>;
    fn hessian(&self, p: &Vector3<f64>) -> Matrix3<f64>;
}

/// The normal gap g(π) = π₂ / √π₁ (positive outside the master body).
#[derive(Debug, Clone, Copy, Default)]
pub struct Gap;

impl InvariantFunction for Gap {
    fn value(&self, p: &Vector3<f64>) -> f64 {
        p[1] / p[0].sqrt()
    }

    fn gradient(&self, p: &Vector3<f64>) -> Vector3<f64> {
        let s = p[0].sqrt();
        Vector3::new(-0.5 * p[1] / (p[0] * s), 1.0 / s, 0.0)
    }

    fn hessian(&self, p: &Vector3<f64>) -> Matrix3<f64> {
        let s = p[0].sqrt();
        let mut h = Matrix3::zeros();
        h[(0, 0)] = 0.75 * p[1] / (p[0] * p[0] * s);
        h[(0, 1)] = -0.5 / (p[0] * s);
        h[(1, 0)] = h[(0, 1)];
        h
    }
}

/// The tangential coordinate τ(π) = ℓ ξ(π) = ℓ π₃ / π₁: the convective coordinate of the
/// projection scaled by a fixed length ℓ (the segment's length at the start of the step), so that
/// the friction multiplier is a force and τ₁ − τ₀ a slip length.
#[derive(Debug, Clone, Copy)]
pub struct Tangential {
    pub length: f64,
}

impl InvariantFunction for Tangential {
    fn value(&self, p: &Vector3<f64>) -> f64 {
        self.length * p[2] / p[0]
    }

    fn gradient(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.length * Vector3::new(-p[2] / (p[0] * p[0]), 0.0, 1.0 / p[0])
    }

    fn hessian(&self, p: &Vector3<f64>) -> Matrix3<f64> {
        let mut h = Matrix3::zeros();
        h[(0, 0)] = 2.0 * p[2] / (p[0] * p[0] * p[0]);
        h[(0, 2)] = -1.0 / (p[0] * p[0]);
        h[(2, 0)] = h[(0, 2)];
        self.length * h
    }
}

/// The penalty potential P(π) = (ε/2) (g(π)₋)², g₋ = min(g, 0): the stored energy of a
/// penetration in the penalty enforcement.
#[derive(Debug, Clone, Copy)]
pub struct PenaltyPotential {
    pub stiffness: f64,
}

impl InvariantFunction for PenaltyPotential {
    fn value(&self, p: &Vector3<f64>) -> f64 {
        let g = Gap.value(p).min(0.0);
        0.5 * self.stiffness * g * g
    }

    fn gradient(&self, p: &Vector3<f64>) -> Vector3<f64> {
        let g = Gap.value(p).min(0.0);
        self.stiffness * g * Gap.gradient(p)
    }

    fn hessian(&self, p: &Vector3<f64>) -> Matrix3<f64> {
        let g = Gap.value(p);
        if g >= 0.0 {
            return Matrix3::zeros();
        }
        let dg = Gap.gradient(p);
        self.stiffness * (dg * dg.transpose() + g * Gap.hessian(p))
    }
}

impl PenaltyPotential {
    /// The secant s = (P(g₁) − P(g₀))/(g₁ − g₀) of P(g) = (ε/2)(g₋)² as a function of the gap,
    /// and ∂s/∂g₁, written without the difference quotient (P is piecewise quadratic):
    /// both gaps ≥ 0: s = 0; both ≤ 0: s = ε (g₀ + g₁)/2; entering (g₀ > 0 > g₁):
    /// s = (ε/2) g₁²/(g₁ − g₀); leaving (g₀ < 0 < g₁): s = −(ε/2) g₀²/(g₁ − g₀). s is C¹ in g₁
    /// (the slopes agree at g₁ = 0 and g₁ = g₀), so the penalty's Newton residual is C¹.
    /// The energy–momentum penalty force is s ∇̄g (Armero & Petőcz's conserving penalty in
    /// terms of the gap's discrete gradient; docs/multibody.md §3).
    pub fn secant(&self, g0: f64, g1: f64) -> (f64, f64) {
        let e = self.stiffness;
        if g0 >= 0.0 && g1 >= 0.0 {
            (0.0, 0.0)
        } else if g0 <= 0.0 && g1 <= 0.0 {
            (0.5 * e * (g0 + g1), 0.5 * e)
        } else if g1 < 0.0 {
            let d = g1 - g0;
            (
                0.5 * e * g1 * g1 / d,
                0.5 * e * g1 * (g1 - 2.0 * g0) / (d * d),
            )
        } else {
            let d = g1 - g0;
            (-0.5 * e * g0 * g0 / d, 0.5 * e * g0 * g0 / (d * d))
        }
    }
}

/// The discrete gradient ∇̄f(π₀, π₁) of EM (67) and its derivative with respect to π₁.
pub fn discrete_gradient(
    f: &impl InvariantFunction,
    p0: &Vector3<f64>,
    p1: &Vector3<f64>,
) -> (Vector3<f64>, Matrix3<f64>) {
    let m = 0.5 * (p0 + p1);
    let d = p1 - p0;
    let dd = d.dot(&d);
    let gm = f.gradient(&m);
    let hm = f.hessian(&m);
    if dd <= DG_GUARD * DG_GUARD * (p0.dot(p0) + p1.dot(p1)) {
        return (gm, 0.5 * hm);
    }
    let e = f.value(p1) - f.value(p0) - gm.dot(&d);
    let de = f.gradient(p1) - gm - 0.5 * hm * d;
    let dg = gm + d * (e / dd);
    let jac = 0.5 * hm
        + d * de.transpose() / dd
        + (e / dd) * (Matrix3::identity() - 2.0 * d * d.transpose() / dd);
    (dg, jac)
}

/// Where a force direction and its Newton derivative are evaluated: the scheme's choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Evaluation {
    /// ∇f(π(x₁)) (Newmark: forces at t_{n+1}).
    End,
    /// ∇f(π(x_{1/2})) (the midpoint rule, EM (59)).
    Midpoint,
    /// The discrete gradient Σ ∇̄f_k H_k x_{1/2} (the energy–momentum scheme, EM (63)–(67)).
    DiscreteGradient,
}

/// A force direction G(x₀, x₁) of a function of the invariants and its derivative ∂G/∂x₁.
#[derive(Debug, Clone, Copy)]
pub struct Direction {
    pub g: Local6,
    pub dg: Local66,
}

/// G and ∂G/∂x₁ of f for the evaluation `at`.
pub fn direction(
    forms: &InvariantForms,
    f: &impl InvariantFunction,
    at: Evaluation,
    x0: &Local6,
    x1: &Local6,
) -> Direction {
    match at {
        Evaluation::End => {
            let p = forms.invariants(x1);
            let pg = forms.gradients(x1);
            let gr = f.gradient(&p);
            Direction {
                g: pg * gr,
                dg: forms.weighted(&gr) + pg * f.hessian(&p) * pg.transpose(),
            }
        }
        Evaluation::Midpoint => {
            let xm = 0.5 * (x0 + x1);
            let p = forms.invariants(&xm);
            let pg = forms.gradients(&xm);
            let gr = f.gradient(&p);
            Direction {
                g: pg * gr,
                dg: 0.5 * (forms.weighted(&gr) + pg * f.hessian(&p) * pg.transpose()),
            }
        }
        Evaluation::DiscreteGradient => {
            let xm = 0.5 * (x0 + x1);
            let pm = forms.gradients(&xm);
            let p0 = forms.invariants(x0);
            let p1 = forms.invariants(x1);
            let (dg, jac) = discrete_gradient(f, &p0, &p1);
            Direction {
                g: pm * dg,
                dg: 0.5 * forms.weighted(&dg) + pm * jac * forms.gradients(x1).transpose(),
            }
        }
    }
}

/// f(π(x)) and its gradient in x (the constraint row of Newton's matrix).
pub fn value_and_gradient(
    forms: &InvariantForms,
    f: &impl InvariantFunction,
    x: &Local6,
) -> (f64, Local6) {
    let p = forms.invariants(x);
    (f.value(&p), forms.gradients(x) * f.gradient(&p))
}

#[cfg(test)]
mod tests {
    //! The invariants' forms against their definitions; gradients and Hessians against central
    //! differences; the discrete gradient's exact work, zero resultant and zero torque; and the
    //! derivative of every force direction against central differences in x₁.
    use super::*;

    fn local(v: [f64; 6]) -> Local6 {
        Local6::from_column_slice(&v)
    }

    fn x0() -> Local6 {
        local([0.31, 0.05, -0.2, 0.0, 0.8, 0.1])
    }

    fn x1() -> Local6 {
        local([0.36, -0.02, -0.17, 0.03, 0.83, 0.09])
    }

    #[test]
    fn invariants_are_the_dot_and_cross_products() {
        let f = InvariantForms::new();
        let x = x0();
        let a = [x[4] - x[2], x[5] - x[3]];
        let b = [x[0] - x[2], x[1] - x[3]];
        let p = f.invariants(&x);
        assert!((p[0] - (a[0] * a[0] + a[1] * a[1])).abs() < 1e-15);
        assert!((p[1] - (b[0] * a[1] - b[1] * a[0])).abs() < 1e-15);
        assert!((p[2] - (a[0] * b[0] + a[1] * b[1])).abs() < 1e-15);
        // g is the signed distance to the line along the outward normal: a segment walked left to
        // right has its body above, and x_s lies just below the line (outside)
        let g = Gap.value(&p);
        let len = p[0].sqrt();
        let normal = [a[1] / len, -a[0] / len];
        assert!((g - (normal[0] * b[0] + normal[1] * b[1])).abs() < 1e-15);
        assert!(g > 0.0);
    }

    #[test]
    fn penalty_secant_is_exact_work_and_continuously_differentiable() {
        let p = PenaltyPotential { stiffness: 300.0 };
        let energy = |g: f64| 0.5 * 300.0 * g.min(0.0).powi(2);
        let cases = [
            (0.02, -0.01),
            (-0.01, 0.02),
            (-0.03, -0.01),
            (0.01, 0.03),
            (0.0, -0.02),
        ];
        for (g0, g1) in cases {
            let (s, ds) = p.secant(g0, g1);
            let work = s * (g1 - g0);
            let exact = energy(g1) - energy(g0);
            assert!(
                (work - exact).abs() < 1e-15 * (1.0 + exact.abs()),
                "{g0} {g1}"
            );
            let h = 1e-7;
            let fd = (p.secant(g0, g1 + h).0 - p.secant(g0, g1 - h).0) / (2.0 * h);
            assert!(
                (fd - ds).abs() < 1e-6 * (1.0 + ds.abs()),
                "{g0} {g1}: {fd} vs {ds}"
            );
        }
        // C¹ across g₁ = 0 from either side of g₀
        for g0 in [0.02, -0.02] {
            let (l, dl) = p.secant(g0, -1e-12);
            let (r, dr) = p.secant(g0, 1e-12);
            assert!((l - r).abs() < 1e-8, "{g0}: {l} vs {r}");
            assert!(
                (dl - dr).abs() < 1e-6 * (1.0 + dl.abs()),
                "{g0}: {dl} vs {dr}"
            );
        }
    }

    fn check_derivatives(f: &impl InvariantFunction, p: Vector3<f64>) {
        let h = 1e-6;
        let gr = f.gradient(&p);
        let he = f.hessian(&p);
        for j in 0..3 {
            let mut pp = p;
            let mut pm = p;
            pp[j] += h;
            pm[j] -= h;
            let fd = (f.value(&pp) - f.value(&pm)) / (2.0 * h);
            assert!(
                (fd - gr[j]).abs() < 1e-7 * (1.0 + gr[j].abs()),
                "gradient {j}"
            );
            let gd = (f.gradient(&pp) - f.gradient(&pm)) / (2.0 * h);
            for i in 0..3 {
                assert!(
                    (gd[i] - he[(i, j)]).abs() < 1e-6 * (1.0 + he[(i, j)].abs()),
                    "hessian {i}{j}"
                );
            }
        }
    }

    #[test]
    fn gap_tangential_and_penalty_derivatives_match_central_differences() {
        let p = InvariantForms::new().invariants(&x0());
        check_derivatives(&Gap, p);
        check_derivatives(&Tangential { length: 1.3 }, p);
        check_derivatives(&PenaltyPotential { stiffness: 50.0 }, p);
    }

    #[test]
    fn discrete_gradient_work_is_exact_and_force_has_no_resultant_or_torque() {
        let forms = InvariantForms::new();
        let (a, b) = (x0(), x1());
        let d = direction(&forms, &Gap, Evaluation::DiscreteGradient, &a, &b);
        let work = d.g.dot(&(b - a));
        let pa = forms.invariants(&a);
        let pb = forms.invariants(&b);
        assert!((work - (Gap.value(&pb) - Gap.value(&pa))).abs() < 1e-16);
        let xm = 0.5 * (a + b);
        for dir in [
            direction(&forms, &Gap, Evaluation::DiscreteGradient, &a, &b),
            direction(&forms, &Gap, Evaluation::Midpoint, &a, &b),
            direction(
                &forms,
                &Tangential { length: 0.9 },
                Evaluation::DiscreteGradient,
                &a,
                &b,
            ),
        ] {
            let fx = dir.g[0] + dir.g[2] + dir.g[4];
            let fy = dir.g[1] + dir.g[3] + dir.g[5];
            assert!(fx.abs() < 1e-15 && fy.abs() < 1e-15);
            let torque: f64 = (0..3)
                .map(|i| xm[2 * i] * dir.g[2 * i + 1] - xm[2 * i + 1] * dir.g[2 * i])
                .sum();
            assert!(torque.abs() < 1e-15, "torque {torque}");
        }
    }

    #[test]
    fn direction_derivatives_match_central_differences() {
        let forms = InvariantForms::new();
        let (a, b) = (x0(), x1());
        let pen = PenaltyPotential { stiffness: 7.0 };
        for at in [
            Evaluation::End,
            Evaluation::Midpoint,
            Evaluation::DiscreteGradient,
        ] {
            type DirectionOf<'a> = &'a dyn Fn(&Local6) -> Direction;
            let cases: [(DirectionOf, &str); 3] = [
                (&|x| direction(&forms, &Gap, at, &a, x), "gap"),
                (
                    &|x| direction(&forms, &Tangential { length: 1.1 }, at, &a, x),
                    "tangential",
                ),
                (&|x| direction(&forms, &pen, at, &a, x), "penalty"),
            ];
            for (dir, name) in cases {
                let d = dir(&b);
                let h = 1e-6;
                for j in 0..6 {
                    let mut bp = b;
                    let mut bm = b;
                    bp[j] += h;
                    bm[j] -= h;
                    let fd = (dir(&bp).g - dir(&bm).g) / (2.0 * h);
                    for i in 0..6 {
                        assert!(
                            (fd[i] - d.dg[(i, j)]).abs() < 2e-6 * (1.0 + d.dg[(i, j)].abs()),
                            "{name} {at:?} ({i}, {j}): fd {} vs {}",
                            fd[i],
                            d.dg[(i, j)]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn discrete_gradient_tends_to_the_midpoint_gradient() {
        let forms = InvariantForms::new();
        let a = x0();
        let b = a + Local6::repeat(1e-9);
        let dg = direction(&forms, &Gap, Evaluation::DiscreteGradient, &a, &b);
        let mp = direction(&forms, &Gap, Evaluation::Midpoint, &a, &b);
        assert!((dg.g - mp.g).norm() < 1e-12);
    }
}
