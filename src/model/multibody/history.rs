//! The contact force as an output: the raw multiplier sum of each step, the step's impulse and
//! the two-step mean force (docs/multibody.md, "The recorded contact force").
//!
//! A step of the midpoint types (the midpoint rule, the energy–momentum scheme) reads
//! M (v_{n+1} − v_n) = k (f − ∇V − Σ λ_{n+1} ∇g): the multipliers λ_{n+1} recorded at t_{n+1} are
//! the mean contact force over [t_n, t_{n+1}], and the step's contact impulse is exactly
//! J_{n+1} = k Σ λ_{n+1}. Newmark's forces act at t_{n+1} with the trapezoidal rule,
//! J_{n+1} = k (Σ λ_n + Σ λ_{n+1})/2. At a persistent contact the constraint g(x_{n+1}) = 0 holds
//! at the step's end while the velocity v_{n+1} = 2d/k − v_n is not constrained; the velocity's
//! normal part alternates about its continuum value and so does the multiplier that brings it
//! back: the recorded force swings from step to step about the exact one (≈ 0.44 and 1.56 of it
//! on the head-on bars) by an amount that does not shrink with h. Two consecutive impulses do not
//! swing: the two-step mean
//!
//!   F̄_n = (J_n + J_{n+1}) / (2k)      (record n, centred at t_n),
//!
//! converges to the continuum force. At the ends of the record F̄_0 = J_1/(2k) (nothing before
//! t_0) and F̄_N = J_N/k (the last step alone).

use crate::model::multibody::scheme::MultibodyScheme;

/// The contact impulse J_n of each step from the raw forces F_n = Σ λ recorded at t_n
/// (`forces[0]` at t_0; J_0 = 0): k F_n for the midpoint types, k (F_{n−1} + F_n)/2 for
/// Newmark (module docs).
pub fn step_impulses(forces: &[f64], scheme: MultibodyScheme, k: f64) -> Vec<f64> {
    (0..forces.len())
        .map(|n| match (n, scheme) {
            (0, _) => 0.0,
            (_, MultibodyScheme::Newmark) => 0.5 * k * (forces[n - 1] + forces[n]),
            _ => k * forces[n],
        })
        .collect()
}

/// The two-step mean force F̄_n = (J_n + J_{n+1})/(2k) of each record (module docs; the last
/// record: J_N / k).
pub fn two_step_mean(forces: &[f64], scheme: MultibodyScheme, k: f64) -> Vec<f64> {
    let j = step_impulses(forces, scheme, k);
    let n = j.len();
    (0..n)
        .map(|i| {
            if i + 1 < n {
                (j[i] + j[i + 1]) / (2.0 * k)
            } else if n > 1 {
                j[i] / k
            } else {
                0.0
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    //! The impulses and means of a force that alternates about a constant: the mean recovers the
    //! constant inside the record, the impulses sum to the momentum the force transfers.
    use super::*;

    #[test]
    fn the_two_step_mean_of_an_alternating_force_is_its_centre() {
        let f: Vec<f64> = (0..9)
            .map(|n| {
                if n == 0 {
                    0.0
                } else if n % 2 == 1 {
                    0.44
                } else {
                    1.56
                }
            })
            .collect();
        let k = 0.1;
        let m = two_step_mean(&f, MultibodyScheme::EnergyMomentum, k);
        for (n, x) in m.iter().enumerate().take(8).skip(1) {
            assert!((x - 1.0).abs() < 1e-15, "n = {n}: {x}");
        }
        let j = step_impulses(&f, MultibodyScheme::EnergyMomentum, k);
        let total: f64 = j.iter().sum();
        assert!((total - k * f.iter().sum::<f64>()).abs() < 1e-15);
    }

    #[test]
    fn newmarks_impulse_is_the_trapezoidal_rule() {
        let f = [0.0, 2.0, 4.0];
        let j = step_impulses(&f, MultibodyScheme::Newmark, 0.5);
        assert_eq!(j, vec![0.0, 0.5, 1.5]);
        assert_eq!(
            two_step_mean(&f, MultibodyScheme::Newmark, 0.5),
            vec![0.5, 2.0, 3.0]
        );
    }
}
