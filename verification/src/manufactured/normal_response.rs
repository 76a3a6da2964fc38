//! The normal damped response laws p_ν of Fernández & Sofonea (2004), (2.7)–(2.9), written a
//! second time from the formulas, independently of the solver's `FoundationLaw`, and generic over
//! dual numbers (docs/quasistatic.md, "Problem P"):
//!
//! - (2.7) p_ν(r) = β r;
//! - (2.8) p_ν(r) = β r_+ + p0, r_+ = max(r, 0);
//! - (2.9) p_ν(r) = S.
//!
//! The manufactured boundary sources use only these; the tests compare them with the solver's
//! law (values, and the derivative away from the kink r = 0).

use contactlab::contact::normal_law::FoundationLaw;
use contactlab::field::Field;
use num_dual::DualNum;

/// One of the laws (2.7)–(2.9) with constant data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NormalResponse {
    /// (2.7) p_ν(r) = β r.
    Linear { beta: f64 },
    /// (2.8) p_ν(r) = β r_+ + p0.
    Lubricated { beta: f64, p0: f64 },
    /// (2.9) p_ν(r) = S.
    Prescribed { stress: f64 },
}

impl NormalResponse {
    /// p_ν(r) on any (dual) number type (at r = 0 the branch r_+ = 0 is taken: the value is
    /// continuous there, only the derivative is not).
    pub fn value<D: DualNum<Primitive = f64> + Copy>(&self, r: D) -> D {
        match *self {
            NormalResponse::Linear { beta } => r * beta,
            NormalResponse::Lubricated { beta, p0 } => {
                let positive_part = if r.re() > 0.0 { r } else { D::zero() };
                positive_part * beta + p0
            }
            NormalResponse::Prescribed { stress } => D::from(stress),
        }
    }

    /// The solver's law with the same constants (handed to the solver; never used for data).
    pub fn solver_law(&self) -> FoundationLaw {
        match *self {
            NormalResponse::Linear { beta } => FoundationLaw::Linear { beta },
            NormalResponse::Lubricated { beta, p0 } => FoundationLaw::Lubricated {
                beta,
                p0: Field::Constant(p0),
            },
            NormalResponse::Prescribed { stress } => FoundationLaw::Prescribed {
                stress: Field::Constant(stress),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    //! The cross-check of (2.7)–(2.9) with the solver's `FoundationLaw`: values at pseudo-random
    //! normal velocities of both signs, and the automatic derivative against the solver's
    //! generalized derivative away from r = 0.
    use super::*;
    use contactlab::contact::normal_law::{NormalLaw, SpaceTime};
    use num_dual::Dual64;

    #[test]
    fn independent_contact_laws_agree_with_the_solver_values_and_slopes() {
        let laws = [
            NormalResponse::Linear { beta: 5.0 },
            NormalResponse::Lubricated { beta: 5.0, p0: 1.0 },
            NormalResponse::Lubricated {
                beta: 1000.0,
                p0: 2.0,
            },
            NormalResponse::Lubricated { beta: 0.0, p0: 2.0 },
            NormalResponse::Prescribed { stress: 2.0 },
        ];
        let at = SpaceTime {
            x: 0.3,
            y: 0.0,
            t: 0.7,
        };
        let mut state = 99u64;
        for law in laws {
            let solver = law.solver_law();
            for _ in 0..200 {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let r = 4.0 * ((state >> 11) as f64 / (1u64 << 53) as f64) - 2.0;
                let ours = law.value(Dual64::new(r, 1.0));
                let theirs = solver.value(r, at);
                assert!(
                    (ours.re - theirs).abs() <= 1e-15 * (1.0 + theirs.abs()),
                    "{law:?} at r = {r}: {} vs {theirs}",
                    ours.re
                );
                assert_eq!(ours.eps, solver.derivative(r, at), "{law:?} at r = {r}");
            }
            // the kink: continuous value at r = 0
            assert_eq!(law.value(0.0), solver.value(0.0, at));
        }
    }
}
