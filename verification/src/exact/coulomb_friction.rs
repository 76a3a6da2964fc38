//! The contact laws of the friction benchmarks, written here from their equations (never from
//! the solver's law objects), for the closed forms of [`super::sliding_block`] and
//! [`super::loaded_block`] and for the friction cases' check of the discrete equations
//! (`docs/dynamic.md` §1, §2, §6).
//!
//! **Coulomb friction with a penetration-dependent coefficient** (Barboteu–Danan–Sofonea, "BDS",
//! (1.12)–(1.13)): sliding, the friction force is −μ(η) N u̇_τ/|u̇_τ| with N the normal force and η
//! the penetration; at rest its size is at most μ(η) N. With μ0 = μ(g) and g the depth of the
//! asperity layer,
//!
//!   μ1(η) = (η/g) μ0 on (0, g),        μ2(η) = (2 − η/g) μ0 on (0, g),
//!
//! both μ0 for η ≥ g and 0 for η ≤ 0 (out of contact); a constant coefficient is μ0 for η > 0 and
//! 0 out of contact. μ1 rises from 0 to μ0 across the layer (the bound grows as the asperities
//! flatten), μ2 falls from 2μ0 to μ0 (it decreases); both are continuous at η = g.
//!
//! **Normal compliance per unit length of Γ3** at a contact point with penetrations p_{n−1} = q
//! and p_n = p of a step (BDS (1.8), (1.46)):
//!
//!   penalty:            N = r p_+                                  (the compliance at t_n),
//!   energy-consistent:  N = r (p_+² − q_+²) / (2 (p − q)),          r p_+ when p = q,
//!
//! the secant of the compliance energy (r/2) p_+², so that N (p − q) = (r/2)(p_+² − q_+²)
//! exactly. When p and q are both positive it is r (p + q)/2 (the formula divided out; this is
//! how it is evaluated there, to keep full precision when p ≈ q).

use serde::{Deserialize, Serialize};

/// Which coefficient of BDS (1.13).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FrictionLaw {
    /// μ0 in contact.
    Constant,
    /// μ1: (η/g) μ0 in the layer.
    Growing,
    /// μ2: (2 − η/g) μ0 in the layer.
    Decreasing,
}

impl FrictionLaw {
    /// The law's name in case files and scenes.
    pub fn name(self) -> &'static str {
        match self {
            Self::Constant => "constant",
            Self::Growing => "growing",
            Self::Decreasing => "decreasing",
        }
    }
}

/// A Coulomb coefficient μ(η) of BDS (1.13): the law, μ0 and the layer depth g (unused by the
/// constant law).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Coulomb {
    pub law: FrictionLaw,
    pub mu0: f64,
    pub depth: f64,
}

impl Coulomb {
    /// μ(η) (module docs).
    pub fn mu(&self, eta: f64) -> f64 {
        if eta <= 0.0 {
            return 0.0;
        }
        let ratio = (eta / self.depth).min(1.0);
        match self.law {
            FrictionLaw::Constant => self.mu0,
            FrictionLaw::Growing => ratio * self.mu0,
            FrictionLaw::Decreasing => (2.0 - ratio) * self.mu0,
        }
    }

    /// d(μ(η) r η)/dη · η / (μ(η) r η): the relative sensitivity of the friction bound of a
    /// compliance contact to the penetration (1 for a constant μ, 2 for μ1 in the layer,
    /// (2 − 2η/g)/(2 − η/g) for μ2 in the layer, 1 beyond it).
    pub fn bound_sensitivity(&self, eta: f64) -> f64 {
        let ratio = eta / self.depth;
        match self.law {
            _ if ratio >= 1.0 => 1.0,
            FrictionLaw::Constant => 1.0,
            FrictionLaw::Growing => 2.0,
            FrictionLaw::Decreasing => (2.0 - 2.0 * ratio) / (2.0 - ratio),
        }
    }
}

/// A normal compliance law of the foundation (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Compliance {
    /// N = r p_+ at t_n (BDS (1.8)).
    Penalty { stiffness: f64 },
    /// The secant (BDS (1.46)).
    EnergyConsistent { stiffness: f64 },
}

impl Compliance {
    /// The normal force per unit length of a step from q = p_{n−1} to p = p_n.
    pub fn force(&self, q: f64, p: f64) -> f64 {
        match *self {
            Self::Penalty { stiffness } => stiffness * p.max(0.0),
            Self::EnergyConsistent { stiffness } => {
                let (pp, qp) = (p.max(0.0), q.max(0.0));
                if p > 0.0 && q > 0.0 {
                    0.5 * stiffness * (pp + qp)
                } else if p == q {
                    stiffness * pp
                } else {
                    0.5 * stiffness * (pp * pp - qp * qp) / (p - q)
                }
            }
        }
    }

    /// r.
    pub fn stiffness(&self) -> f64 {
        match *self {
            Self::Penalty { stiffness } | Self::EnergyConsistent { stiffness } => stiffness,
        }
    }
}

#[cfg(test)]
mod tests {
    //! The laws against their definitions: the values of (1.13) at the ends of the layer and in
    //! it, continuity at η = g, zero out of contact; the secant's exact work and its limits.
    use super::*;

    fn coulomb(law: FrictionLaw) -> Coulomb {
        Coulomb {
            law,
            mu0: 0.4,
            depth: 0.02,
        }
    }

    #[test]
    fn coefficients_follow_bds_1_13() {
        let (m1, m2, c) = (
            coulomb(FrictionLaw::Growing),
            coulomb(FrictionLaw::Decreasing),
            coulomb(FrictionLaw::Constant),
        );
        for m in [m1, m2, c] {
            assert_eq!(m.mu(0.0), 0.0);
            assert_eq!(m.mu(-1.0), 0.0);
            assert_eq!(m.mu(0.02), 0.4);
            assert_eq!(m.mu(1.0), 0.4);
        }
        assert!((m1.mu(0.015) - 0.3).abs() < 1e-15);
        assert!((m2.mu(0.015) - 0.5).abs() < 1e-15);
        assert!((m2.mu(1e-12) - 0.8).abs() < 1e-9);
        assert_eq!(c.mu(1e-12), 0.4);
        // continuity at η = g
        for m in [m1, m2] {
            assert!((m.mu(0.02 * (1.0 - 1e-12)) - m.mu(0.02)).abs() < 1e-11);
        }
    }

    #[test]
    fn bound_sensitivity_is_the_log_derivative_of_mu_times_eta() {
        for law in [
            FrictionLaw::Constant,
            FrictionLaw::Growing,
            FrictionLaw::Decreasing,
        ] {
            let m = coulomb(law);
            for eta in [0.005, 0.015, 0.03] {
                let f = |e: f64| m.mu(e) * e;
                let h = 1e-7;
                let numeric = (f(eta + h) - f(eta - h)) / (2.0 * h) * eta / f(eta);
                assert!(
                    (numeric - m.bound_sensitivity(eta)).abs() < 1e-6,
                    "{law:?} {eta}: {numeric}"
                );
            }
        }
    }

    #[test]
    fn energy_consistent_force_has_exact_work_and_the_compliance_limit() {
        let c = Compliance::EnergyConsistent { stiffness: 50.0 };
        let energy = |p: f64| 25.0 * p.max(0.0).powi(2);
        for (q, p) in [(-0.01, 0.02), (0.01, 0.03), (0.02, -0.01), (0.005, 0.004)] {
            let work = c.force(q, p) * (p - q);
            assert!((work - (energy(p) - energy(q))).abs() < 1e-15, "{q} {p}");
        }
        assert_eq!(c.force(0.01, 0.01), 0.5);
        assert!((c.force(0.01, 0.01 + 1e-9) - 0.5).abs() < 1e-7);
        assert_eq!(c.force(-0.01, -0.02), 0.0);
        let p = Compliance::Penalty { stiffness: 50.0 };
        assert_eq!(p.force(0.5, 0.01), 0.5);
        assert_eq!(p.force(0.5, -0.01), 0.0);
    }
}
