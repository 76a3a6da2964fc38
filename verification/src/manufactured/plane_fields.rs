//! The displacement fields u(x, y, t) of the plane manufactured solutions on Ω = (0, 1)², T = 1,
//! each one closure generic over dual numbers. Every field vanishes on Γ1 = {x = 0} (the factor
//! x); on Γ3 = {y = 0} (ν = (0, −1)) the normal velocity is u̇_ν = −u̇2.
//!
//! - `Switching`: u1 = x (0.1 sin πy + 0.2 t),
//!   u2 = x (−0.3 t + 0.1 sin 2πt cos(πx/2)) − 0.05 x y t;
//!   u̇_ν = x (0.3 − 0.2π cos 2πt cos(πx/2)) changes sign in x and t: each point of Γ3 switches
//!   the damper at its own times t*(x). Smooth in space but not in V^h: the P1 solution carries a
//!   space error.
//! - `Affine { switch_time: t* }`: u1 = x a(t), u2 = x b(t) with a(t) = 0.2 t + 0.05 sin 2πt and
//!   b(t) = 0.2 ((t − t* − 1) eᵗ + t* + 1), so that ḃ = 0.2 (t − t*) eᵗ and
//!   u̇_ν = 0.2 x (t* − t) eᵗ: every point of Γ3 moves into the foundation (damper on) before t*
//!   and recedes after it — one switching time for the whole boundary. Affine in space, the field
//!   lies in V^h of every mesh, and so does everything the semi-discrete problem needs: its
//!   strain and stress are constant in space (f0 = 0), the tractions on Γ2 are constant, and on Γ3
//!   p_ν(u̇_ν) is affine in x at each t (u̇_ν has one sign along Γ3), which the 2-point Gauss rule
//!   of the contact term and the 3-point rule of the source integrate exactly against P1 test
//!   functions. The semi-discrete Galerkin solution is therefore u itself: the error of a run
//!   against u is its time error alone (docs/quasistatic.md, "Manufactured solutions").

use num_dual::DualNum;

/// A displacement field of the manufactured solutions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlaneField {
    /// Smooth, spatially rich; the damper switches at x-dependent times.
    Switching,
    /// In V^h of every mesh; the damper switches at `switch_time` on all of Γ3.
    Affine { switch_time: f64 },
}

impl PlaneField {
    /// u(x, y, t) on any (dual) number type.
    pub fn eval<D: DualNum<Primitive = f64> + Copy>(&self, x: D, y: D, t: D) -> [D; 2] {
        let pi = std::f64::consts::PI;
        match *self {
            PlaneField::Switching => {
                let u1 = x * ((y * pi).sin() * 0.1 + t * 0.2);
                let u2 = x * (t * (-0.3) + (t * (2.0 * pi)).sin() * (x * (pi / 2.0)).cos() * 0.1)
                    - x * y * t * 0.05;
                [u1, u2]
            }
            PlaneField::Affine { switch_time } => {
                let a = t * 0.2 + (t * (2.0 * pi)).sin() * 0.05;
                let b = ((t - switch_time - 1.0) * t.exp() + switch_time + 1.0) * 0.2;
                [x * a, x * b]
            }
        }
    }

    /// The switching time of an affine field (None for the spatially rich one).
    pub fn switch_time(&self) -> Option<f64> {
        match *self {
            PlaneField::Switching => None,
            PlaneField::Affine { switch_time } => Some(switch_time),
        }
    }

    /// A short description for names and reports.
    pub fn describe(&self) -> String {
        match *self {
            PlaneField::Switching => "switching in x and t".to_string(),
            PlaneField::Affine { switch_time } => {
                format!("affine in space, switching at t* = {switch_time}")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    //! The fields: zero on Γ1 (the affine one also at t = 0); the affine field's normal velocity on Γ3 has the
    //! closed form 0.2 x (t* − t) eᵗ (one sign change, at t*, for every x > 0); the switching
    //! field's changes sign in x and t.
    use super::*;
    use num_dual::Dual64;

    #[test]
    fn fields_vanish_on_the_clamped_side_and_the_affine_one_initially() {
        let affine = PlaneField::Affine { switch_time: 0.5 };
        for f in [PlaneField::Switching, affine] {
            for &(y, t) in &[(0.0, 0.4), (0.3, 0.9), (1.0, 0.1)] {
                assert_eq!(f.eval::<f64>(0.0, y, t), [0.0, 0.0]);
            }
        }
        {
            let f = affine;
            for &(x, y) in &[(0.3, 0.2), (1.0, 1.0)] {
                let u: [f64; 2] = f.eval(x, y, 0.0);
                assert!(u[0].abs() < 1e-16 && u[1].abs() < 1e-16, "{f:?}: {u:?}");
            }
        }
    }

    #[test]
    fn affine_normal_velocity_has_its_closed_form_and_one_switch() {
        let ts = 0.6180339887498949;
        let f = PlaneField::Affine { switch_time: ts };
        for &x in &[0.25, 1.0] {
            for &t in &[0.1, 0.5, ts, 0.7, 1.0] {
                let u = f.eval(Dual64::from(x), Dual64::from(0.0), Dual64::new(t, 1.0));
                let un = -u[1].eps;
                let closed = 0.2 * x * (ts - t) * t.exp();
                assert!((un - closed).abs() < 1e-15, "{un} vs {closed}");
            }
        }
    }

    #[test]
    fn switching_normal_velocity_changes_sign_in_x_and_t() {
        let f = PlaneField::Switching;
        let un = |x: f64, t: f64| {
            -f.eval(Dual64::from(x), Dual64::from(0.0), Dual64::new(t, 1.0))[1].eps
        };
        // in t at x = 0.2, in x at t = 0
        assert!(un(0.2, 0.0) < 0.0 && un(0.2, 0.25) > 0.0 && un(0.9, 0.0) > 0.0);
    }
}
