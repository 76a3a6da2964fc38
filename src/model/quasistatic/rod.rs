//! Problem T1D: the Kelvin–Voigt rod on a damped foundation (Fernández & Sofonea 2004, §4.1).
//!
//! Ω = (0, L):  σ = a u_xt + b u_x,  σ_x + f0 = 0,  u(0, t) = 0,  −σ(L, t) = p_ν(u_t(L, t)),
//! u(x, 0) = u0(x)   ((4.1)–(4.5)). Variational form: for all v with v(0) = 0,
//!
//!   ∫ (a u_xt + b u_x) v_x dx + p_ν(u_t(L)) v(L) = ∫ f0 v dx.

use std::sync::Arc;

use crate::contact::normal_law::{FoundationLaw, NormalLaw};
use crate::error::{require_positive, InputError};
use crate::field::Field;

/// The data of the rod problem.
#[derive(Debug, Clone)]
pub struct RodProblem {
    /// L > 0 (m).
    pub length: f64,
    /// T > 0 (s).
    pub final_time: f64,
    /// a > 0, the viscosity (N·s/m).
    pub viscosity: f64,
    /// b > 0, the elasticity (N/m).
    pub elasticity: f64,
    /// f0(x, t), the body force (N/m).
    pub load: Field,
    /// u0(x), the initial displacement; must vanish at x = 0.
    pub initial_displacement: Field,
    /// p_ν, the foundation's normal damped response at x = L.
    pub foundation: Arc<dyn NormalLaw>,
}

impl RodProblem {
    /// The paper's data (§4.1): L = 1, T = 0.5, a = b = 1, f0 = 10, β = 1, u0 = 0, law (2.8) with
    /// oil pressure `p0` (the paper runs p0 = 6 and p0 = 2).
    pub fn fernandez_sofonea(p0: f64) -> Self {
        Self {
            length: 1.0,
            final_time: 0.5,
            viscosity: 1.0,
            elasticity: 1.0,
            load: Field::Constant(10.0),
            initial_displacement: Field::Constant(0.0),
            foundation: Arc::new(FoundationLaw::Lubricated {
                beta: 1.0,
                p0: Field::Constant(p0),
            }),
        }
    }

    /// Checks every datum; the error names the field and the value.
    pub fn validate(&self) -> Result<(), InputError> {
        require_positive("rod.length", self.length)?;
        require_positive("rod.final_time", self.final_time)?;
        require_positive("rod.viscosity", self.viscosity)?;
        require_positive("rod.elasticity", self.elasticity)?;
        self.load.validate("rod.load")?;
        self.initial_displacement
            .validate("rod.initial_displacement")?;
        let u00 = self.initial_displacement.eval(0.0, 0.0, 0.0);
        if u00 != 0.0 {
            return Err(InputError::new(
                "rod.initial_displacement",
                format!("{} (u0(0) = {u00})", self.initial_displacement),
                "u0(0) = 0 (the rod is clamped at x = 0)",
            ));
        }
        self.foundation.validate()?;
        Ok(())
    }

    /// The explicit scheme's step bound k < 2a/b (the amplification factor of every mode away from
    /// the contact node is 1 − k b/a).
    pub fn explicit_stability_bound(&self) -> f64 {
        2.0 * self.viscosity / self.elasticity
    }
}

#[cfg(test)]
mod tests {
    //! Rod data: the paper's data validate; each bad datum is named in its error.
    use super::*;

    #[test]
    fn paper_data_are_valid() {
        assert!(RodProblem::fernandez_sofonea(6.0).validate().is_ok());
    }

    #[test]
    fn bad_data_name_their_field() {
        let mut p = RodProblem::fernandez_sofonea(6.0);
        p.viscosity = -1.0;
        assert_eq!(p.validate().unwrap_err().field, "rod.viscosity");
        let mut p = RodProblem::fernandez_sofonea(6.0);
        p.final_time = 0.0;
        assert_eq!(p.validate().unwrap_err().field, "rod.final_time");
        let mut p = RodProblem::fernandez_sofonea(6.0);
        p.elasticity = f64::INFINITY;
        assert_eq!(p.validate().unwrap_err().field, "rod.elasticity");
        let mut p = RodProblem::fernandez_sofonea(6.0);
        p.initial_displacement = Field::Constant(1.0);
        assert_eq!(p.validate().unwrap_err().field, "rod.initial_displacement");
        let mut p = RodProblem::fernandez_sofonea(6.0);
        p.load = Field::Constant(f64::NAN);
        assert_eq!(p.validate().unwrap_err().field, "rod.load");
    }
}
