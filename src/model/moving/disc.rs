//! A particle pressed on a rotating disc (Hetzler 2009, §4.2.3, Fig. 16).
//!
//! A particle of mass m, guided radially, is pressed by the normal force N onto a disc spinning at
//! Ω; a radial spring c is relaxed at r0; Coulomb friction μ. Relative to the disc the particle
//! moves with v_rel = ṙ e_r − Ω r e_t, so the friction force −μN v_rel/|v_rel| has the radial
//! component
//!
//! ```text
//!   F_r(r, ṙ) = −μ N ṙ / sqrt(ṙ² + (Ω r)²),
//! ```
//!
//! and the radial equation is m r̈ + c (r − r0) = F_r(r, ṙ). About the steady state r = r0,
//! ṙ = 0, ∂F_r/∂ṙ = −μN/(|Ω| r0) and ∂F_r/∂r = 0: the change of the friction direction (the
//! operator R1, (45), (67): symmetric, positive definite) acts as a viscous damping inversely
//! proportional to the sliding speed,
//!
//! ```text
//!   m Δr̈ + (μ N / (Ω r0)) Δṙ + c Δr = 0                                  (112).
//! ```

use crate::error::{require_nonnegative, require_positive, InputError};
use crate::model::moving::system::MovingSystem;

/// The particle on the rotating disc.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscParticle {
    /// m > 0.
    pub mass: f64,
    /// c > 0 (radial spring).
    pub stiffness: f64,
    /// N ≥ 0 (normal force).
    pub normal_force: f64,
    /// μ ≥ 0.
    pub friction_coefficient: f64,
    /// r0 > 0 (the spring's relaxed radius, the steady state).
    pub radius: f64,
    /// Ω ≠ 0 (rad per unit time).
    pub angular_speed: f64,
}

impl DiscParticle {
    /// Checks every value, naming the field of an invalid one.
    pub fn validate(&self) -> Result<(), InputError> {
        require_positive("particle.mass", self.mass)?;
        require_positive("particle.stiffness", self.stiffness)?;
        require_nonnegative("particle.normal_force", self.normal_force)?;
        require_nonnegative("particle.friction_coefficient", self.friction_coefficient)?;
        require_positive("particle.radius", self.radius)?;
        if !(self.angular_speed.is_finite() && self.angular_speed != 0.0) {
            return Err(InputError::new(
                "particle.angular_speed",
                self.angular_speed,
                "a finite non-zero number (the linearization needs sliding, Ω r0 > 0)",
            ));
        }
        Ok(())
    }

    /// The nonlinear radial friction force F_r(r, ṙ) = −μN ṙ / sqrt(ṙ² + (Ω r)²).
    pub fn friction_force(&self, r: f64, rdot: f64) -> f64 {
        let speed = (rdot * rdot + (self.angular_speed * r).powi(2)).sqrt();
        if speed == 0.0 {
            0.0
        } else {
            -self.friction_coefficient * self.normal_force * rdot / speed
        }
    }

    /// The friction-induced damping μN/(|Ω| r0) of (112).
    pub fn friction_damping(&self) -> f64 {
        self.friction_coefficient * self.normal_force / (self.angular_speed.abs() * self.radius)
    }

    /// The linearized 1-dof system m Δr̈ + (μN/(|Ω| r0)) Δṙ + c Δr = 0: the damping term is the
    /// symmetric friction operator R1 (stored as `damping`).
    pub fn system(&self) -> Result<MovingSystem, InputError> {
        self.validate()?;
        let mut s = MovingSystem::zeros(vec!["Δr".into()]);
        s.mass[(0, 0)] = self.mass;
        s.damping[(0, 0)] = self.friction_damping();
        s.stiffness[(0, 0)] = self.stiffness;
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    //! Setting: the particle of Fig. 16. Goal: the linearized damping equals the slope of the
    //! nonlinear friction force, and bad data are named.
    use super::*;

    fn particle(omega: f64) -> DiscParticle {
        DiscParticle {
            mass: 2.0,
            stiffness: 50.0,
            normal_force: 10.0,
            friction_coefficient: 0.3,
            radius: 0.1,
            angular_speed: omega,
        }
    }

    #[test]
    fn damping_is_the_slope_of_the_friction_force() {
        let p = particle(40.0);
        let h = 1e-6;
        let slope = (p.friction_force(0.1, h) - p.friction_force(0.1, -h)) / (2.0 * h);
        assert!((slope + p.friction_damping()).abs() < 1e-6 * p.friction_damping());
        assert!((p.friction_damping() - 0.3 * 10.0 / 4.0).abs() < 1e-15);
        assert_eq!(p.friction_force(0.1, 0.0), 0.0);
    }

    #[test]
    fn zero_speed_is_an_input_error() {
        assert_eq!(
            particle(0.0).system().unwrap_err().field,
            "particle.angular_speed"
        );
    }
}
