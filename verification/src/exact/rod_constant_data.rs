//! The exact solutions of problem T1D (Fernández & Sofonea 2004, §4.1) for constant data.
//!
//! Data: L, a, b > 0, f0 constant, u0 = 0, and a law p_ν among (2.7) β r, (2.8) β r_+ + p0,
//! (2.9) S, all constant. Derivation: σ_x = −f0 gives σ(x, t) = f0 (L − x) − s(t) with
//! s(t) = −σ(L, t) = p_ν(U'(t)), U(t) = u(L, t). Integrating a ε_t + b ε = σ (ε = u_x) over (0, L):
//!
//!   a U' + b U = f0 L²/2 − L s(t).
//!
//! Write s = p0 + β_act U' (β_act = β when the damper acts, 0 otherwise; p0 = S for (2.9), 0 for
//! (2.7)). Then with c = f0 L²/2 − L p0 and λ = b / (a + L β_act):
//!
//!   U(t) = (c/b)(1 − e^{−λt}),   U'(t) = c/(a + L β_act) e^{−λt},   sign U' = sign c.
//!
//! For (2.8) the regime is consistent exactly when β_act = β for c > 0 (the end presses into the
//! foundation) and β_act = 0 for c ≤ 0 (it recedes): the threshold is p0 = f0 L/2. For (2.7) and
//! (2.9) there is no switch. With s(t) = p0 + D e^{−λt}, D = β_act c/(a + L β_act), λ1 = b/a:
//!
//!   ε(x, t) = f0 (L − x)/b (1 − e^{−λ1 t}) − I(t)/a,
//!   I(t) = ∫_0^t e^{−λ1 (t−τ)} s(τ) dτ = p0 (1 − e^{−λ1 t})/λ1 + D e^{−λ1 t} expm1((λ1 − λ) t)/(λ1 − λ),
//!   u(x, t) = f0 (L x − x²/2)/b (1 − e^{−λ1 t}) − x I(t)/a,
//!
//! (the last fraction tends to t e^{−λ1 t} as λ → λ1 and is evaluated without cancellation).
//! The paper's p0 = 6 and p0 = 2 solutions, (4.6) and (4.7), are the members with L = a = b = β = 1,
//! f0 = 10.

use contactlab::contact::normal_law::FoundationLaw;
use contactlab::model::quasistatic::rod::RodProblem;

use crate::exact::{RodExactSolution, RodJet};

/// The law's constants as the derivation needs them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ConstantLaw {
    /// (2.7) p_ν(r) = β r.
    Linear { beta: f64 },
    /// (2.8) p_ν(r) = β r_+ + p0.
    Lubricated { beta: f64, p0: f64 },
    /// (2.9) p_ν(r) = S.
    Prescribed { stress: f64 },
}

/// Why a problem is not in the constant-data family.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("the constant-data exact solution needs {what}")]
pub struct NotConstantData {
    pub what: String,
}

/// The exact solution of T1D for constant data.
#[derive(Debug, Clone, PartialEq)]
pub struct RodConstantData {
    pub length: f64,
    pub viscosity: f64,
    pub elasticity: f64,
    pub load: f64,
    pub law: ConstantLaw,
    /// p0 of s(t) = p0 + D e^{−λt}.
    p0: f64,
    /// D.
    d: f64,
    /// λ = b / (a + L β_act).
    lambda: f64,
    /// λ1 = b / a.
    lambda1: f64,
    /// c = f0 L²/2 − L p0.
    c: f64,
    /// Whether the damper acts (β_act = β > 0).
    active: bool,
    name: String,
}

impl RodConstantData {
    /// The solution for data (L, a, b, f0, law).
    pub fn new(length: f64, viscosity: f64, elasticity: f64, load: f64, law: ConstantLaw) -> Self {
        let (p0, beta) = match law {
            ConstantLaw::Linear { beta } => (0.0, beta),
            ConstantLaw::Lubricated { beta, p0 } => (p0, beta),
            ConstantLaw::Prescribed { stress } => (stress, 0.0),
        };
        let c = load * length * length / 2.0 - length * p0;
        let active = match law {
            ConstantLaw::Linear { .. } => true,
            ConstantLaw::Lubricated { .. } => c > 0.0,
            ConstantLaw::Prescribed { .. } => false,
        };
        let beta_act = if active { beta } else { 0.0 };
        let denom = viscosity + length * beta_act;
        let lambda = elasticity / denom;
        let lambda1 = elasticity / viscosity;
        let d = beta_act * c / denom;
        let name = match law {
            ConstantLaw::Linear { beta } => format!("rod constant data, linear beta = {beta}"),
            ConstantLaw::Lubricated { beta, p0 } => {
                format!("rod constant data, lubricated beta = {beta}, p0 = {p0}")
            }
            ConstantLaw::Prescribed { stress } => {
                format!("rod constant data, prescribed S = {stress}")
            }
        };
        Self {
            length,
            viscosity,
            elasticity,
            load,
            law,
            p0,
            d,
            lambda,
            lambda1,
            c,
            active,
            name,
        }
    }

    /// The paper's data with oil pressure p0 ((4.6) for p0 = 6, (4.7) for p0 = 2).
    pub fn fernandez_sofonea(p0: f64) -> Self {
        Self::new(
            1.0,
            1.0,
            1.0,
            10.0,
            ConstantLaw::Lubricated { beta: 1.0, p0 },
        )
    }

    /// The member of the family for a rod problem, if its data are constant and u0 = 0.
    pub fn for_problem(problem: &RodProblem) -> Result<Self, NotConstantData> {
        let load = problem.load.as_constant().ok_or_else(|| NotConstantData {
            what: format!("a constant load (got {})", problem.load),
        })?;
        if problem.initial_displacement.as_constant() != Some(0.0) {
            return Err(NotConstantData {
                what: format!("u0 = 0 (got {})", problem.initial_displacement),
            });
        }
        let law = problem
            .foundation
            .as_ref()
            .as_foundation_law()
            .ok_or_else(|| NotConstantData {
                what: "one of the laws (2.7)-(2.9)".to_string(),
            })?;
        let law = match law {
            FoundationLaw::Linear { beta } => ConstantLaw::Linear { beta: *beta },
            FoundationLaw::Lubricated { beta, p0 } => ConstantLaw::Lubricated {
                beta: *beta,
                p0: p0.as_constant().ok_or_else(|| NotConstantData {
                    what: format!("a constant p0 (got {p0})"),
                })?,
            },
            FoundationLaw::Prescribed { stress } => ConstantLaw::Prescribed {
                stress: stress.as_constant().ok_or_else(|| NotConstantData {
                    what: format!("a constant S (got {stress})"),
                })?,
            },
        };
        Ok(Self::new(
            problem.length,
            problem.viscosity,
            problem.elasticity,
            load,
            law,
        ))
    }

    /// The regime threshold of law (2.8): p0 = f0 L / 2.
    pub fn threshold_p0(&self) -> f64 {
        self.load * self.length / 2.0
    }

    /// Whether the damper acts (the end presses into the foundation).
    pub fn damper_active(&self) -> bool {
        self.active && self.d != 0.0
    }

    /// s(t) = −σ(L, t) = p0 + D e^{−λt}.
    pub fn contact_pressure(&self, t: f64) -> f64 {
        self.p0 + self.d * (-self.lambda * t).exp()
    }

    /// U(t) = u(L, t) = (c/b)(1 − e^{−λt}).
    pub fn end_displacement(&self, t: f64) -> f64 {
        -self.c / self.elasticity * (-self.lambda * t).exp_m1()
    }

    /// (I(t), I'(t)).
    fn memory(&self, t: f64) -> (f64, f64) {
        let l1 = self.lambda1;
        let e1 = (-l1 * t).exp();
        let delta = l1 - self.lambda;
        let ratio = if delta.abs() * t < 1e-300 {
            t
        } else {
            (delta * t).exp_m1() / delta
        };
        let i = self.p0 * (-(-l1 * t).exp_m1()) / l1 + self.d * e1 * ratio;
        let di = self.contact_pressure(t) - l1 * i;
        (i, di)
    }
}

impl RodExactSolution for RodConstantData {
    fn name(&self) -> &str {
        &self.name
    }

    fn source(&self) -> &str {
        "derived in verification/src/exact/rod_constant_data.rs (Fernández & Sofonea 2004, §4.1: (4.6), (4.7) are members)"
    }

    fn jet(&self, x: f64, t: f64) -> RodJet {
        self.time_factors(t).jet(x)
    }

    fn jets_at_time(&self, xs: &[f64], t: f64, out: &mut [RodJet]) {
        let tf = self.time_factors(t);
        for (o, &x) in out.iter_mut().zip(xs) {
            *o = tf.jet(x);
        }
    }
}

/// The time-dependent factors of the constant-data solution at one t: u is a polynomial in x
/// whose coefficients these are.
struct TimeFactors {
    f0_over_b: f64,
    length: f64,
    inv_a: f64,
    one_minus: f64,
    l1_e1: f64,
    i: f64,
    di: f64,
}

impl TimeFactors {
    #[inline]
    fn jet(&self, x: f64) -> RodJet {
        let (c, l) = (self.f0_over_b, self.length);
        let q = l * x - 0.5 * x * x;
        RodJet {
            u: c * q * self.one_minus - x * self.i * self.inv_a,
            u_x: c * (l - x) * self.one_minus - self.i * self.inv_a,
            u_t: c * q * self.l1_e1 - x * self.di * self.inv_a,
            u_xt: c * (l - x) * self.l1_e1 - self.di * self.inv_a,
            u_xx: -c * self.one_minus,
            u_xxt: -c * self.l1_e1,
        }
    }
}

impl RodConstantData {
    fn time_factors(&self, t: f64) -> TimeFactors {
        let l1 = self.lambda1;
        let (i, di) = self.memory(t);
        TimeFactors {
            f0_over_b: self.load / self.elasticity,
            length: self.length,
            inv_a: 1.0 / self.viscosity,
            one_minus: -(-l1 * t).exp_m1(),
            l1_e1: l1 * (-l1 * t).exp(),
            i,
            di,
        }
    }
}

#[cfg(test)]
mod tests {
    //! The constant-data family against the equations it claims to solve: the PDE
    //! a u_xxt + b u_xx + f0 = 0 (derivatives checked by finite differences), u(0, t) = 0,
    //! −σ(L, t) = p_ν(u_t(L, t)) with the library's own law, u(x, 0) = 0; and the paper's two
    //! solutions as members.
    use super::*;
    use crate::exact::rod_paper::{PaperP0Equals2, PaperP0Equals6};
    use contactlab::contact::normal_law::{NormalLaw, SpaceTime};
    use contactlab::field::Field;

    fn members() -> Vec<(RodConstantData, FoundationLaw)> {
        let mut v = Vec::new();
        for &(f0, p0, beta) in &[
            (10.0, 6.0, 1.0),
            (10.0, 2.0, 1.0),
            (3.0, 0.5, 4.0),
            (3.0, 2.0, 0.0),
            (-2.0, 0.0, 2.0),
            (10.0, 5.0 + 1e-9, 1.0),
            (10.0, 5.0 - 1e-9, 1.0),
            (10.0, 2.0, 1e12),
        ] {
            v.push((
                RodConstantData::new(1.3, 0.7, 2.1, f0, ConstantLaw::Lubricated { beta, p0 }),
                FoundationLaw::Lubricated {
                    beta,
                    p0: Field::Constant(p0),
                },
            ));
        }
        v.push((
            RodConstantData::new(1.3, 0.7, 2.1, 4.0, ConstantLaw::Linear { beta: 0.8 }),
            FoundationLaw::Linear { beta: 0.8 },
        ));
        v.push((
            RodConstantData::new(1.3, 0.7, 2.1, 4.0, ConstantLaw::Prescribed { stress: 5.0 }),
            FoundationLaw::Prescribed {
                stress: Field::Constant(5.0),
            },
        ));
        v
    }

    #[test]
    fn closed_form_derivatives_match_finite_differences() {
        let eps = 1e-5;
        for (s, _) in members() {
            for &(x, t) in &[(0.3, 0.2), (0.9, 1.1), (1.2, 0.05)] {
                let j = s.jet(x, t);
                let fd_x = (s.jet(x + eps, t).u - s.jet(x - eps, t).u) / (2.0 * eps);
                let fd_t = (s.jet(x, t + eps).u - s.jet(x, t - eps).u) / (2.0 * eps);
                let fd_xt = (s.jet(x, t + eps).u_x - s.jet(x, t - eps).u_x) / (2.0 * eps);
                let fd_xx = (s.jet(x + eps, t).u_x - s.jet(x - eps, t).u_x) / (2.0 * eps);
                let fd_xxt = (s.jet(x, t + eps).u_xx - s.jet(x, t - eps).u_xx) / (2.0 * eps);
                let scale = 1.0 + j.u.abs() + j.u_x.abs() + j.u_t.abs();
                for (got, fd) in [
                    (j.u_x, fd_x),
                    (j.u_t, fd_t),
                    (j.u_xt, fd_xt),
                    (j.u_xx, fd_xx),
                    (j.u_xxt, fd_xxt),
                ] {
                    assert!(
                        (got - fd).abs() < 1e-7 * scale,
                        "{}: {got} vs {fd}",
                        s.name()
                    );
                }
            }
        }
    }

    #[test]
    fn family_solves_pde_boundary_contact_and_initial_conditions() {
        for (s, law) in members() {
            let (a, b, l, f0) = (s.viscosity, s.elasticity, s.length, s.load);
            for &t in &[0.0, 0.01, 0.25, 0.5, 2.0] {
                // PDE σ_x + f0 = a u_xxt + b u_xx + f0 = 0
                for &x in &[0.0, 0.4, l] {
                    let j = s.jet(x, t);
                    let res = a * j.u_xxt + b * j.u_xx + f0;
                    assert!(
                        res.abs() < 1e-12 * (1.0 + f0.abs()),
                        "{}: PDE residual {res}",
                        s.name()
                    );
                }
                // clamped end
                assert!(s.jet(0.0, t).u.abs() < 1e-15);
                // contact: −σ(L) = p_ν(u_t(L))
                let j = s.jet(l, t);
                let sigma = a * j.u_xt + b * j.u_x;
                let at = SpaceTime { x: l, y: 0.0, t };
                let p = law.value(j.u_t, at);
                // p_ν amplifies the absolute round-off of u_t(L) (a difference of O(f0 L²/b)
                // terms) by β: the tolerance says so.
                let beta = law.lipschitz_constant();
                let ut_roundoff = 1e-14 * (1.0 + f0.abs() * l * l / b + sigma.abs() * l / a);
                assert!(
                    (-sigma - p).abs() < 1e-10 * (1.0 + p.abs()) + beta * ut_roundoff,
                    "{} t = {t}: −σ(L) = {} vs p = {p}",
                    s.name(),
                    -sigma
                );
                assert!((j.u - s.end_displacement(t)).abs() < 1e-12 * (1.0 + j.u.abs()));
            }
            // initial condition
            for &x in &[0.2, 0.7, l] {
                assert!(s.jet(x, 0.0).u.abs() < 1e-15);
            }
        }
    }

    #[test]
    fn regime_switches_at_threshold_p0_equals_f0_l_over_2() {
        let s = RodConstantData::fernandez_sofonea(6.0);
        assert_eq!(s.threshold_p0(), 5.0);
        assert!(!s.damper_active());
        assert!(s.jet(1.0, 0.3).u_t < 0.0);
        let s = RodConstantData::fernandez_sofonea(2.0);
        assert!(s.damper_active());
        assert!(s.jet(1.0, 0.3).u_t > 0.0);
    }

    #[test]
    fn paper_solutions_4_6_and_4_7_are_members() {
        let fam6 = RodConstantData::fernandez_sofonea(6.0);
        let fam2 = RodConstantData::fernandez_sofonea(2.0);
        for &(x, t) in &[(0.1, 0.1), (0.5, 0.25), (1.0, 0.5), (0.77, 0.013)] {
            let (a, b) = (fam6.jet(x, t), PaperP0Equals6.jet(x, t));
            let (c, d) = (fam2.jet(x, t), PaperP0Equals2.jet(x, t));
            for (p, q) in [(a, b), (c, d)] {
                assert!((p.u - q.u).abs() < 1e-14);
                assert!((p.u_x - q.u_x).abs() < 1e-13);
                assert!((p.u_t - q.u_t).abs() < 1e-13);
                assert!((p.u_xt - q.u_xt).abs() < 1e-13);
            }
        }
    }
}
