//! Manufactured solutions of the rod problem T1D.
//!
//! Given a smooth u(x, t) with u(0, t) = 0, the data that make it the exact solution are
//!
//!   f0(x, t) = −σ_x = −(a u_xxt + b u_xx),     u0(x) = u(x, 0),
//!   p0(t)    = −σ(L, t) − β (u_t(L, t))_+       (law (2.8) with a time-dependent oil pressure),
//!
//! so that −σ(L, t) = β (u_t(L, t))_+ + p0(t) holds exactly. All derivatives come from one
//! evaluation of u on hyper-hyper-dual numbers (x carries ε1 and ε2, t carries ε3):
//! u_x = ε1, u_xx = ε1ε2, u_t = ε3, u_xt = ε1ε3, u_xxt = ε1ε2ε3.

use std::sync::Arc;

use num_dual::{DualNum, HyperHyperDual64};

use contactlab::contact::normal_law::FoundationLaw;
use contactlab::field::{Dependence, Field};
use contactlab::model::quasistatic::rod::RodProblem;

use crate::exact::{RodExactSolution, RodJet};

/// The dual number type manufactured rod solutions are written in.
pub type Hhd = HyperHyperDual64;

/// u(x, t) on hyper-hyper-dual numbers.
pub type RodClosure = fn(Hhd, Hhd) -> Hhd;

/// A manufactured solution with the rod's material and foundation constants.
#[derive(Clone)]
pub struct RodManufactured {
    name: String,
    pub length: f64,
    pub final_time: f64,
    pub viscosity: f64,
    pub elasticity: f64,
    pub beta: f64,
    u: RodClosure,
}

impl std::fmt::Debug for RodManufactured {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "RodManufactured({})", self.name)
    }
}

/// The jet of u at (x, t) by one hyper-hyper-dual evaluation.
pub fn jet_of(u: RodClosure, x: f64, t: f64) -> RodJet {
    let xd = Hhd::new(x, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let td = Hhd::from_re(t).derivative3();
    let r = u(xd, td);
    RodJet {
        u: r.re,
        u_x: r.eps1,
        u_t: r.eps3,
        u_xt: r.eps1eps3,
        u_xx: r.eps1eps2,
        u_xxt: r.eps1eps2eps3,
    }
}

impl RodManufactured {
    /// A manufactured solution `u` for the rod (L, T, a, b) on a lubricated foundation with
    /// damping β.
    pub fn new(
        name: &str,
        (length, final_time): (f64, f64),
        (viscosity, elasticity, beta): (f64, f64, f64),
        u: RodClosure,
    ) -> Self {
        Self {
            name: name.to_string(),
            length,
            final_time,
            viscosity,
            elasticity,
            beta,
            u,
        }
    }

    /// u(x, t) = sin(πx/2) (0.1 + t + 0.3 sin(2πt)) on L = 1, T = 1, a = 1, b = 2, β = 3:
    /// u_t(L, t) = 1 + 0.6π cos(2πt) changes sign twice (t ≈ 0.34 and 0.66), so both branches of
    /// r_+ are exercised and the damper switches on and off; u0 ≠ 0 and f0 depends on x and t.
    pub fn switching() -> Self {
        Self::new(
            "rod manufactured, switching damper",
            (1.0, 1.0),
            (1.0, 2.0, 3.0),
            |x, t| {
                let pi = std::f64::consts::PI;
                (x * (pi / 2.0)).sin() * (t + 0.1 + (t * (2.0 * pi)).sin() * 0.3)
            },
        )
    }

    /// u(x, t) = x (1 − x/2) e^{−t} cos(x t) on L = 1, T = 0.5, a = 0.5, b = 1.5, β = 2: a smooth
    /// solution whose end keeps receding (the damper is never active), with a non-polynomial profile
    /// so that P1 is not nodally exact.
    pub fn receding_smooth() -> Self {
        Self::new(
            "rod manufactured, receding",
            (1.0, 0.5),
            (0.5, 1.5, 2.0),
            |x, t| x * (-(x * 0.5) + 1.0) * (-t).exp() * (x * t).cos(),
        )
    }

    /// The name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The rod problem whose exact solution this is.
    pub fn problem(&self) -> RodProblem {
        let (a, b, beta, l) = (self.viscosity, self.elasticity, self.beta, self.length);
        let u = self.u;
        let load = Field::function(
            Dependence {
                x: true,
                y: false,
                t: true,
            },
            move |x, _, t| {
                let j = jet_of(u, x, t);
                -(a * j.u_xxt + b * j.u_xx)
            },
        );
        let p0 = Field::function(
            Dependence {
                x: false,
                y: false,
                t: true,
            },
            move |_, _, t| {
                let j = jet_of(u, l, t);
                -(a * j.u_xt + b * j.u_x) - beta * j.u_t.max(0.0)
            },
        );
        let u0 = Field::function(
            Dependence {
                x: true,
                y: false,
                t: false,
            },
            move |x, _, _| jet_of(u, x, 0.0).u,
        );
        RodProblem {
            length: l,
            final_time: self.final_time,
            viscosity: a,
            elasticity: b,
            load,
            initial_displacement: u0,
            foundation: Arc::new(FoundationLaw::Lubricated { beta, p0 }),
        }
    }
}

impl RodExactSolution for RodManufactured {
    fn name(&self) -> &str {
        &self.name
    }
    fn source(&self) -> &str {
        "manufactured (data by automatic differentiation, verification/src/manufactured/rod.rs)"
    }
    fn jet(&self, x: f64, t: f64) -> RodJet {
        jet_of(self.u, x, t)
    }
}

#[cfg(test)]
mod tests {
    //! Manufactured rod solutions: automatic-differentiation derivatives agree with finite
    //! differences, and the derived data make u satisfy every equation of T1D.
    use super::*;
    use contactlab::contact::normal_law::SpaceTime;

    #[test]
    fn dual_derivatives_match_finite_differences() {
        for m in [
            RodManufactured::switching(),
            RodManufactured::receding_smooth(),
        ] {
            let eps = 1e-5;
            for &(x, t) in &[(0.3, 0.2), (0.8, 0.45)] {
                let j = m.jet(x, t);
                let u = |x, t| m.jet(x, t);
                assert!((j.u_x - (u(x + eps, t).u - u(x - eps, t).u) / (2.0 * eps)).abs() < 1e-8);
                assert!((j.u_t - (u(x, t + eps).u - u(x, t - eps).u) / (2.0 * eps)).abs() < 1e-8);
                assert!(
                    (j.u_xt - (u(x, t + eps).u_x - u(x, t - eps).u_x) / (2.0 * eps)).abs() < 1e-8
                );
                assert!(
                    (j.u_xx - (u(x + eps, t).u_x - u(x - eps, t).u_x) / (2.0 * eps)).abs() < 1e-8
                );
                assert!(
                    (j.u_xxt - (u(x, t + eps).u_xx - u(x, t - eps).u_xx) / (2.0 * eps)).abs()
                        < 1e-7
                );
            }
        }
    }

    #[test]
    fn derived_data_make_u_exact() {
        for m in [
            RodManufactured::switching(),
            RodManufactured::receding_smooth(),
        ] {
            let p = m.problem();
            p.validate().unwrap();
            let (a, b, l) = (p.viscosity, p.elasticity, p.length);
            for &t in &[0.0, 0.2, 0.5] {
                for &x in &[0.1, 0.6, 1.0] {
                    let j = m.jet(x, t);
                    let res = a * j.u_xxt + b * j.u_xx + p.load.eval(x, 0.0, t);
                    assert!(res.abs() < 1e-12, "PDE residual {res}");
                }
                assert!(m.jet(0.0, t).u.abs() < 1e-15);
                let j = m.jet(l, t);
                let at = SpaceTime { x: l, y: 0.0, t };
                let sigma = a * j.u_xt + b * j.u_x;
                assert!((-sigma - p.foundation.value(j.u_t, at)).abs() < 1e-12);
            }
            assert_eq!(
                p.initial_displacement.eval(0.5, 0.0, 0.0),
                m.jet(0.5, 0.0).u
            );
        }
    }

    #[test]
    fn switching_solution_changes_the_sign_of_the_end_velocity() {
        let m = RodManufactured::switching();
        assert!(m.jet(1.0, 0.1).u_t > 0.0);
        assert!(m.jet(1.0, 0.5).u_t < 0.0);
        assert!(m.jet(1.0, 0.9).u_t > 0.0);
    }
}
