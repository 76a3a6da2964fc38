//! Normal compliance forces of a step of a dynamic scheme, from the penetrations p_{n−1} (= q)
//! and p_n (= p) of a contact point (p > 0: the point is inside the foundation).
//!
//! - Plain penalty, the compliance evaluated at t_n (Barboteu–Danan–Sofonea, "BDS", (1.8)):
//!   N = r p_+.
//! - Energy-consistent compliance (BDS (1.46); Hauret–Le Tallec, "HLT", (3.68) against a plane
//!   wall):
//!
//!     N = r [p_+² − q_+²] / (2 (p − q)),
//!
//!   whose discrete work is exact: N (p − q) = (r/2)(p_+² − q_+²) (BDS Prop. 1.3, HLT Prop. 3.7).
//!   It needs no guard: when p and q have the same sign it reduces to r (p + q)/2 (both inside)
//!   or 0 (both outside), and when their signs differ p ≠ q.
//! - The HLT variant (3.69): the force λ_{n+1/2} ν plus a correction along the increment δφ that
//!   restores the exact work; against a plane wall it tilts the force when a contact point slides
//!   while entering or leaving (see [`tilted_correction`]).
//!
//! Derivatives: [`energy_consistent`] returns ∂N/∂p exactly (BDS's form, differentiated).

/// The force magnitude N and a generalized derivative ∂N/∂p.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalForce {
    pub value: f64,
    pub slope: f64,
}

/// Plain penalty N = r p_+ (BDS (1.8)), slope r H(p) (H(0) = 0).
#[inline]
pub fn penalty(r: f64, p: f64) -> NormalForce {
    if p > 0.0 {
        NormalForce {
            value: r * p,
            slope: r,
        }
    } else {
        NormalForce {
            value: 0.0,
            slope: 0.0,
        }
    }
}

/// The energy-consistent compliance N = r [p_+² − q_+²] / (2 (p − q)) (BDS (1.46), HLT (3.68))
/// with its exact derivative in p.
#[inline]
pub fn energy_consistent(r: f64, q: f64, p: f64) -> NormalForce {
    match (p > 0.0, q > 0.0) {
        (true, true) => NormalForce {
            value: 0.5 * r * (p + q),
            slope: 0.5 * r,
        },
        (false, false) => NormalForce {
            value: 0.0,
            slope: 0.0,
        },
        // entering: q ≤ 0 < p, so p − q > 0
        (true, false) => {
            let d = p - q;
            NormalForce {
                value: 0.5 * r * p * p / d,
                slope: 0.5 * r * p * (p - 2.0 * q) / (d * d),
            }
        }
        // leaving: p ≤ 0 < q, so q − p > 0
        (false, true) => {
            let d = q - p;
            NormalForce {
                value: 0.5 * r * q * q / d,
                slope: 0.5 * r * q * q / (d * d),
            }
        }
    }
}

/// The penalty energy (r/2) p_+² whose discrete gradient the energy-consistent force is.
#[inline]
pub fn penalty_energy(r: f64, p: f64) -> f64 {
    let pp = p.max(0.0);
    0.5 * r * pp * pp
}

/// The HLT variant (3.69) against a plane wall with unit normal ν (pointing out of the
/// foundation): the force on the body is
///
///   F = λ_{n+1/2} ν + c δφ / (δφ·δφ),   c = −(r/2)(p_+² − q_+²) − λ_{n+1/2} ν·δφ,
///
/// with λ_{n+1/2} = r (p_{n+1/2})_+ and δφ the increment of the contact point, so that
/// F·δφ = −(r/2)(p_+² − q_+²) exactly. Returns (λ_{n+1/2}, c / (δφ·δφ)); the correction is
/// dropped when δφ·δφ is below `tiny` (then c = O(|δφ|²) and the identity holds to round-off).
#[inline]
pub fn tilted_correction(r: f64, q: f64, p: f64, nu_dot_dphi: f64, dphi_sq: f64) -> (f64, f64) {
    let lambda_half = r * (0.5 * (p + q)).max(0.0);
    let c = -(penalty_energy(r, p) - penalty_energy(r, q)) - lambda_half * nu_dot_dphi;
    let tiny = f64::EPSILON * f64::EPSILON * (p * p + q * q).max(f64::MIN_POSITIVE);
    if dphi_sq <= tiny {
        (lambda_half, 0.0)
    } else {
        (lambda_half, c / dphi_sq)
    }
}

#[cfg(test)]
mod tests {
    //! The compliance forces: exact discrete work, continuity of the energy-consistent force
    //! across the contact onset, and its derivative against central differences.
    use super::*;

    #[test]
    fn energy_consistent_force_has_exact_discrete_work() {
        let r = 1e4;
        for &(q, p) in &[
            (-0.3, 0.2),
            (0.1, 0.4),
            (0.5, -0.2),
            (-0.1, -0.4),
            (0.2, 0.2),
        ] {
            let n = energy_consistent(r, q, p).value;
            let work = n * (p - q);
            let de = penalty_energy(r, p) - penalty_energy(r, q);
            assert!((work - de).abs() <= 1e-12 * de.abs().max(1.0), "{q} {p}");
        }
    }

    #[test]
    fn energy_consistent_slope_matches_central_differences() {
        let r = 3.0;
        for &(q, p) in &[
            (-0.3, 0.2),
            (0.1, 0.4),
            (0.5, -0.2),
            (0.5, -0.7),
            (-0.2, 0.05),
        ] {
            let h = 1e-6;
            let fd = (energy_consistent(r, q, p + h).value - energy_consistent(r, q, p - h).value)
                / (2.0 * h);
            let s = energy_consistent(r, q, p).slope;
            assert!((fd - s).abs() < 1e-7, "{q} {p}: {fd} vs {s}");
        }
    }

    #[test]
    fn energy_consistent_force_tends_to_the_penalty_force_as_steps_shrink() {
        let r = 2.0;
        for &p in &[0.3, 1e-3] {
            let n = energy_consistent(r, p - 1e-9, p).value;
            assert!((n - r * p).abs() < 1e-8);
        }
        // across the onset: continuous in p at p = 0
        let a = energy_consistent(r, -0.1, 1e-12).value;
        assert!(a.abs() < 1e-20);
    }

    #[test]
    fn tilted_force_has_exact_discrete_work() {
        let r = 50.0;
        // a point entering the wall (ν = (0, 1)) while sliding: δφ = (0.3, −0.2)
        let (q, p) = (-0.05, 0.15);
        let dphi = [0.3, -0.2];
        let nu = [0.0, 1.0];
        let nd = nu[0] * dphi[0] + nu[1] * dphi[1];
        let (lam, c) = tilted_correction(r, q, p, nd, dphi[0] * dphi[0] + dphi[1] * dphi[1]);
        let f = [lam * nu[0] + c * dphi[0], lam * nu[1] + c * dphi[1]];
        let work = f[0] * dphi[0] + f[1] * dphi[1];
        let de = penalty_energy(r, p) - penalty_energy(r, q);
        assert!((work + de).abs() < 1e-13 * de);
        // the force is tilted: a tangential component appears
        assert!(f[0].abs() > 1e-3);
    }

    #[test]
    fn tilted_correction_vanishes_when_the_point_stays_inside() {
        let r = 50.0;
        let (q, p) = (0.05, 0.15);
        let dphi = [0.3, -0.1];
        let (_, c) = tilted_correction(r, q, p, -0.1, 0.1);
        assert!(c.abs() < 1e-14, "{c} {dphi:?}");
    }
}
