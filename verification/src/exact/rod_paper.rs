//! The paper's two exact solutions of T1D, written out as printed (Fernández & Sofonea 2004, §4.1;
//! data L = 1, T = 0.5, a = b = 1, f0 = 10, β = 1).
//!
//! (4.6) p0 = 6: u(x, t) = (1 − e^{−t})(4x − 5x²),                       σ = 4 − 10x
//! (4.7) p0 = 2: u(x, t) = 5x(x − 1)e^{−t} − 3x e^{−t/2} + 8x − 5x²,    σ = −(3/2)e^{−t/2} + 8 − 10x

use crate::exact::{RodExactSolution, RodJet};

/// (4.6): p0 = 6, the end recedes (u_t(1, t) = −e^{−t} < 0) and the damper is inactive.
#[derive(Debug, Clone, Copy, Default)]
pub struct PaperP0Equals6;

/// (4.7): p0 = 2, the end presses into the foundation (u_t(1, t) = (3/2)e^{−t/2} > 0).
#[derive(Debug, Clone, Copy, Default)]
pub struct PaperP0Equals2;

impl RodExactSolution for PaperP0Equals6 {
    fn name(&self) -> &str {
        "paper (4.6), p0 = 6"
    }
    fn source(&self) -> &str {
        "Fernández & Sofonea 2004, (4.6)"
    }
    fn jet(&self, x: f64, t: f64) -> RodJet {
        let e = (-t).exp();
        let q = 4.0 * x - 5.0 * x * x;
        RodJet {
            u: (1.0 - e) * q,
            u_x: (1.0 - e) * (4.0 - 10.0 * x),
            u_t: e * q,
            u_xt: e * (4.0 - 10.0 * x),
            u_xx: -10.0 * (1.0 - e),
            u_xxt: -10.0 * e,
        }
    }
}

impl RodExactSolution for PaperP0Equals2 {
    fn name(&self) -> &str {
        "paper (4.7), p0 = 2"
    }
    fn source(&self) -> &str {
        "Fernández & Sofonea 2004, (4.7)"
    }
    fn jet(&self, x: f64, t: f64) -> RodJet {
        let e = (-t).exp();
        let h = (-0.5 * t).exp();
        RodJet {
            u: 5.0 * x * (x - 1.0) * e - 3.0 * x * h + 8.0 * x - 5.0 * x * x,
            u_x: 5.0 * (2.0 * x - 1.0) * e - 3.0 * h + 8.0 - 10.0 * x,
            u_t: -5.0 * x * (x - 1.0) * e + 1.5 * x * h,
            u_xt: -5.0 * (2.0 * x - 1.0) * e + 1.5 * h,
            u_xx: 10.0 * e - 10.0,
            u_xxt: -10.0 * e,
        }
    }
}
