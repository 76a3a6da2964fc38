//! One contact candidate — a slave node paired with a master segment or with the foundation — and
//! its contribution to a step's residual and Newton matrix (the energy–momentum paper, "EM",
//! (50)–(52) and (58)–(67); docs/multibody.md §3–§5).
//!
//! With Lagrange multipliers the candidate carries λ_N ≥ 0 (the normal force, EM (41)–(42)) and,
//! with friction, λ_T (the tangential force). The momentum equations receive −λ_N G_N − λ_T G_T,
//! G the scheme's force direction of the gap g and of the tangential coordinate τ
//! ([`super::invariants::direction`]). The constraint rows are the complementarity functions
//!
//!   C_N = λ_N − max(0, λ_N − c g₁),
//!   C_T = λ_T − proj_[−μλ_N, μλ_N](λ_T − c (τ₁ − τ₀)),
//!
//! whose semismooth Newton method is the return map of EM (50)–(52): the trial stick state
//! (τ₁ = τ₀, the stick constraint (52)), the slip criterion |λ_T^trial| − μ λ_N > 0 (50) and the
//! slip force λ_T = μ λ_N λ_T^trial/|λ_T^trial| (51), all evaluated at the end of the step. In slip
//! λ_T (τ₁ − τ₀) ≤ 0: friction only dissipates. With the penalty enforcement the normal force is
//! −∇̄P of the potential P = (ε/2) (g₋)² and the candidate has no normal multiplier (friction
//! needs the multiplier).

use nalgebra::SMatrix;

use crate::model::multibody::invariants::{
    direction, value_and_gradient, Evaluation, Gap, InvariantForms, InvariantFunction, Local6,
    PenaltyPotential, Tangential,
};

/// How a pair enforces the normal contact condition.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Enforcement {
    /// g ≥ 0, λ_N ≥ 0, λ_N g = 0 exactly (EM (19)–(21)).
    Lagrange,
    /// The penalty force of P = (ε/2) (g₋)² (for comparison). Its energy is conserved by the
    /// energy–momentum scheme (the secant force, [`PenaltyPotential::secant`]); it does not tend
    /// to the multipliers' solution as ε → ∞ at a fixed step (the penalty adds a contact mode of
    /// frequency √(ε/m), unresolved once ε k²/m ≫ 1; docs/multibody.md §3.1).
    Penalty { stiffness: f64 },
    /// The compliant multiplier (perturbed Lagrangian): λ_N ≥ 0, g₁ + λ_N/ε ≥ 0,
    /// λ_N (g₁ + λ_N/ε) = 0 — the penalty force ε (−g₁)₊ at the step's end carried by λ_N in the
    /// scheme's force direction, a regular O(1/ε) perturbation of the multipliers' step, which
    /// it tends to as ε → ∞.
    Compliant { stiffness: f64 },
}

impl Enforcement {
    /// 1/ε of the compliant multiplier, 0 for the exact multiplier (and the penalty).
    pub fn compliance(&self) -> f64 {
        match self {
            Enforcement::Compliant { stiffness } => 1.0 / stiffness,
            _ => 0.0,
        }
    }
}

/// The tangential state of a candidate in contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Tangent {
    /// Not in contact (no friction force).
    #[default]
    Free,
    /// τ₁ = τ₀ (EM (52)).
    Stick,
    /// Sliding with λ_T = μ λ_N · dir (EM (51)).
    Slip(f64),
}

/// A slave node paired with a master: its dofs, its state and its forces.
#[derive(Debug, Clone)]
pub struct Candidate {
    /// The pair it belongs to.
    pub pair: usize,
    /// The slave node (mesh node of the slave body) and its index among the slave surface's nodes.
    pub slave: usize,
    pub slave_index: usize,
    /// The master segment (None: the foundation).
    pub segment: Option<usize>,
    /// The global free dofs of x_s, x_1, x_2 (None: held, or a foundation point).
    pub dofs: [Option<usize>; 6],
    /// The reference positions (for the foundation: its two fixed points).
    pub reference: Local6,
    /// The positions at t_n.
    pub x0: Local6,
    /// ℓ of τ = ℓ ξ: the segment's length at t_n (1 for the foundation).
    pub ell: f64,
    /// g and τ at t_n (of this pairing).
    pub g0: f64,
    pub tau0: f64,
    /// g and τ at t_{n+1} (after the step).
    pub g1: f64,
    pub tau1: f64,
    /// The multipliers (λ_N: the normal force, ≥ 0; λ_T: the friction force).
    pub lambda_n: f64,
    pub lambda_t: f64,
    /// The unknown indices of λ_N and λ_T in the step system (set when the system is laid out).
    pub ln: Option<usize>,
    pub lt: Option<usize>,
    /// The normal constraint is active (C_N = c g₁).
    pub active: bool,
    /// Active at the start of the step (with the same master segment).
    pub was_active: bool,
    pub tangent: Tangent,
    /// The master segment changed during the step.
    pub switched: bool,
    /// The slave node was held (its constraint active) at the end of the previous step, on any
    /// segment: a held node that switches segment within the step measures g₀ anew against the
    /// next segment's line — at a concave kink of the master a small positive work, the
    /// vertex's non-smoothness — while any other set change with g₀ < 0 entered the master from
    /// inside.
    pub held: bool,
}

/// The pair law a candidate obeys.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairLaw {
    pub enforcement: Enforcement,
    /// μ (0: frictionless, no friction code runs).
    pub friction: f64,
}

impl PairLaw {
    /// Whether a candidate of this law carries λ_N.
    pub fn has_normal_multiplier(&self) -> bool {
        matches!(
            self.enforcement,
            Enforcement::Lagrange | Enforcement::Compliant { .. }
        )
    }

    /// Whether it carries λ_T.
    pub fn has_friction(&self) -> bool {
        self.friction > 0.0 && self.has_normal_multiplier()
    }
}

/// Local rows and columns: the six coordinates, λ_N (6) and λ_T (7).
pub type Local88 = SMatrix<f64, 8, 8>;

/// A candidate's contribution: residual rows and Newton matrix in local numbering.
#[derive(Debug, Clone, Copy)]
pub struct Contribution {
    /// Added to the momentum residual of the six coordinates.
    pub r_u: Local6,
    /// C_N and C_T.
    pub r_n: f64,
    pub r_t: f64,
    pub jac: Local88,
}

/// The scaling and regularization of the constraint rows.
#[derive(Debug, Clone, Copy)]
pub struct RowScale {
    /// c of C_N and C_T (a stiffness: the Newton matrix's largest diagonal).
    pub c: f64,
    /// −δ on an active row's diagonal in the Newton matrix (not in the residual): keeps the
    /// matrix regular when constraints are redundant (two-pass on a flat interface).
    pub regularization: f64,
    /// An inactive candidate activates only when λ_N − c g₁ exceeds the round-off of c g₁,
    /// 16 ε c |x|_∞ (false in a step's first Newton iteration: a touching node, g₁ = 0, then
    /// activates). Redundant constraints need it: two-pass on a flat interface writes the same
    /// gap twice where the meshes share a node; the split of their force is fixed only by
    /// c (g₁ − g₁′)/δ, round-off amplified by 1/δ, which can drive one multiplier negative — it
    /// is released, and without the band it would re-activate on the sign of a round-off gap in
    /// the next iteration and the active set would cycle with period 2.
    pub hysteresis: bool,
}

impl Candidate {
    /// The positions x₁ = reference + u of the local coordinates.
    pub fn positions(&self, u: &[f64]) -> Local6 {
        let mut x = self.reference;
        for (i, d) in self.dofs.iter().enumerate() {
            if let Some(d) = d {
                x[i] += u[*d];
            }
        }
        x
    }

    /// The residual and Newton matrix of the candidate at positions x₁, for the scheme's
    /// evaluation `at`; updates the active and tangential states from the complementarity
    /// functions (a slide that would reverse becomes stick: the solution then lies between the
    /// two slide states).
    pub fn contribute(
        &mut self,
        forms: &InvariantForms,
        law: &PairLaw,
        at: Evaluation,
        x1: &Local6,
        scale: RowScale,
    ) -> Contribution {
        let mut out = Contribution {
            r_u: Local6::zeros(),
            r_n: 0.0,
            r_t: 0.0,
            jac: Local88::zeros(),
        };
        let c = scale.c;
        match law.enforcement {
            Enforcement::Penalty { stiffness } => {
                let (g1, dg1) = value_and_gradient(forms, &Gap, x1);
                self.active = g1 < 0.0;
                if at == Evaluation::DiscreteGradient {
                    // P ∘ g: the secant of P(g) = (ε/2)(g₋)² times the gap's discrete gradient,
                    // s ∇̄g with s = (P(g₁) − P(g₀))/(g₁ − g₀) — exact work P(g₁) − P(g₀), no
                    // resultant and no torque (∇̄g has neither), and C¹ in x₁ (s is)
                    let g0 = Gap.value(&forms.invariants(&self.x0));
                    let (s, ds) = PenaltyPotential { stiffness }.secant(g0, g1);
                    let d = direction(forms, &Gap, at, &self.x0, x1);
                    out.r_u += s * d.g;
                    out.jac
                        .fixed_view_mut::<6, 6>(0, 0)
                        .add_assign(&(s * d.dg + ds * d.g * dg1.transpose()));
                } else {
                    let p = PenaltyPotential { stiffness };
                    let d = direction(forms, &p, at, &self.x0, x1);
                    out.r_u += d.g;
                    out.jac.fixed_view_mut::<6, 6>(0, 0).add_assign(&d.dg);
                }
                return out;
            }
            Enforcement::Lagrange | Enforcement::Compliant { .. } => {}
        }
        // the compliant row c (g₁ + λ_N/ε) (0 for the exact multiplier)
        let compliance = law.enforcement.compliance();
        let d = direction(forms, &Gap, at, &self.x0, x1);
        out.r_u -= self.lambda_n * d.g;
        out.jac
            .fixed_view_mut::<6, 6>(0, 0)
            .add_assign(&(-self.lambda_n * d.dg));
        out.jac.fixed_view_mut::<6, 1>(0, 6).copy_from(&(-d.g));
        let (g1, dg1) = value_and_gradient(forms, &Gap, x1);
        let band = if scale.hysteresis && !self.active {
            16.0 * f64::EPSILON * c * x1.amax()
        } else {
            0.0
        };
        self.active = self.lambda_n - c * (g1 + compliance * self.lambda_n) >= band;
        if self.active {
            out.r_n = c * (g1 + compliance * self.lambda_n);
            out.jac
                .fixed_view_mut::<1, 6>(6, 0)
                .copy_from(&(c * dg1.transpose()));
            // the compliance c/ε keeps the matrix regular by itself; −δ for the exact multiplier
            out.jac[(6, 6)] = if compliance > 0.0 {
                c * compliance
            } else {
                -scale.regularization
            };
        } else {
            out.r_n = self.lambda_n;
            out.jac[(6, 6)] = 1.0;
        }
        if !law.has_friction() {
            return out;
        }
        let tangential = Tangential { length: self.ell };
        let t = direction(forms, &tangential, at, &self.x0, x1);
        out.r_u -= self.lambda_t * t.g;
        out.jac
            .fixed_view_mut::<6, 6>(0, 0)
            .add_assign(&(-self.lambda_t * t.dg));
        out.jac.fixed_view_mut::<6, 1>(0, 7).copy_from(&(-t.g));
        if !self.active {
            self.tangent = Tangent::Free;
            out.r_t = self.lambda_t;
            out.jac[(7, 7)] = 1.0;
            return out;
        }
        let (tau1, dtau1) = value_and_gradient(forms, &tangential, x1);
        let slip = tau1 - self.tau0;
        let bound = law.friction * self.lambda_n.max(0.0);
        let trial = self.lambda_t - c * slip;
        let dir = if trial >= 0.0 { 1.0 } else { -1.0 };
        let reverses = matches!(self.tangent, Tangent::Slip(s) if s == -dir);
        if trial.abs() <= bound || reverses {
            self.tangent = Tangent::Stick;
            out.r_t = c * slip;
            out.jac
                .fixed_view_mut::<1, 6>(7, 0)
                .copy_from(&(c * dtau1.transpose()));
            out.jac[(7, 7)] = -scale.regularization;
        } else {
            self.tangent = Tangent::Slip(dir);
            out.r_t = self.lambda_t - bound * dir;
            out.jac[(7, 7)] = 1.0;
            if self.lambda_n > 0.0 {
                out.jac[(7, 6)] = -law.friction * dir;
            }
        }
        out
    }

    /// The penalty energy P(π(x₁)) (0 with multipliers).
    pub fn penalty_energy(&self, forms: &InvariantForms, law: &PairLaw, x1: &Local6) -> f64 {
        match law.enforcement {
            Enforcement::Penalty { stiffness } => {
                PenaltyPotential { stiffness }.value(&forms.invariants(x1))
            }
            Enforcement::Lagrange | Enforcement::Compliant { .. } => 0.0,
        }
    }

    /// g and τ at positions x (τ with this step's ℓ).
    pub fn gap_and_tangential(&self, forms: &InvariantForms, x: &Local6) -> (f64, f64) {
        let p = forms.invariants(x);
        (Gap.value(&p), Tangential { length: self.ell }.value(&p))
    }

    /// ξ of the projection at positions x.
    pub fn xi(&self, forms: &InvariantForms, x: &Local6) -> f64 {
        let p = forms.invariants(x);
        p[2] / p[0]
    }
}

use std::ops::AddAssign;

#[cfg(test)]
mod tests {
    //! A candidate's Newton matrix against central differences of its residual (multipliers,
    //! stick and slip, penalty), and the slip force's dissipation sign.
    use super::*;

    fn candidate() -> Candidate {
        let reference = Local6::from_column_slice(&[0.3, 0.0, 1.0, 0.0, 0.0, 0.0]);
        let x0 = Local6::from_column_slice(&[0.3, 0.01, 1.0, 0.0, 0.0, 0.0]);
        Candidate {
            pair: 0,
            slave: 0,
            slave_index: 0,
            segment: Some(0),
            dofs: [Some(0), Some(1), Some(2), Some(3), Some(4), Some(5)],
            reference,
            x0,
            ell: 1.0,
            g0: 0.01,
            tau0: 0.7,
            g1: 0.0,
            tau1: 0.0,
            lambda_n: 0.4,
            lambda_t: 0.05,
            ln: Some(6),
            lt: Some(7),
            active: false,
            was_active: false,
            tangent: Tangent::Free,
            switched: false,
            held: false,
        }
    }

    /// The full residual vector (8) at (x, λ).
    fn residual(cand: &Candidate, law: &PairLaw, at: Evaluation, z: &[f64; 8]) -> [f64; 8] {
        let forms = InvariantForms::new();
        let mut c = cand.clone();
        c.lambda_n = z[6];
        c.lambda_t = z[7];
        let x = Local6::from_column_slice(&z[..6]);
        let out = c.contribute(
            &forms,
            law,
            at,
            &x,
            RowScale {
                c: 3.0,
                regularization: 0.0,
                hysteresis: false,
            },
        );
        let mut r = [0.0; 8];
        r[..6].copy_from_slice(out.r_u.as_slice());
        r[6] = out.r_n;
        r[7] = out.r_t;
        r
    }

    fn check(law: PairLaw, z: [f64; 8], expect: Tangent) {
        check_from(&candidate(), law, z, expect);
    }

    /// The Newton matrix of `base` at z = (x₁, λ) against central differences of its residual.
    fn check_from(base: &Candidate, law: PairLaw, z: [f64; 8], expect: Tangent) {
        let forms = InvariantForms::new();
        for at in [
            Evaluation::End,
            Evaluation::Midpoint,
            Evaluation::DiscreteGradient,
        ] {
            let mut c = base.clone();
            c.lambda_n = z[6];
            c.lambda_t = z[7];
            let x = Local6::from_column_slice(&z[..6]);
            let out = c.contribute(
                &forms,
                &law,
                at,
                &x,
                RowScale {
                    c: 3.0,
                    regularization: 0.0,
                    hysteresis: false,
                },
            );
            if law.has_friction() {
                assert_eq!(c.tangent, expect, "{at:?}");
            }
            let h = 1e-7;
            for j in 0..8 {
                let (mut zp, mut zm) = (z, z);
                zp[j] += h;
                zm[j] -= h;
                let (rp, rm) = (residual(base, &law, at, &zp), residual(base, &law, at, &zm));
                for i in 0..8 {
                    let fd = (rp[i] - rm[i]) / (2.0 * h);
                    assert!(
                        (fd - out.jac[(i, j)]).abs() < 1e-5 * (1.0 + fd.abs()),
                        "{at:?} ({i}, {j}): {fd} vs {}",
                        out.jac[(i, j)]
                    );
                }
            }
        }
    }

    #[test]
    fn newton_matrix_matches_central_differences_in_stick_and_slip() {
        let law = PairLaw {
            enforcement: Enforcement::Lagrange,
            friction: 0.3,
        };
        // penetrated slightly (active), tangential displacement small: stick
        check(
            law,
            [0.3002, -0.001, 1.0, 0.0001, 0.0, 0.0, 0.4, 0.05],
            Tangent::Stick,
        );
        // large tangential displacement: slip
        check(
            law,
            [0.35, -0.001, 1.0, 0.0001, 0.0, 0.0, 0.4, 0.05],
            Tangent::Slip(1.0),
        );
        let frictionless = PairLaw {
            enforcement: Enforcement::Lagrange,
            friction: 0.0,
        };
        check(
            frictionless,
            [0.3, 0.02, 1.0, 0.0, 0.0, 0.0, 0.01, 0.0],
            Tangent::Free,
        );
        let penalty = PairLaw {
            enforcement: Enforcement::Penalty { stiffness: 40.0 },
            friction: 0.0,
        };
        // entering (g₀ = 0.01 > 0 > g₁)
        check(
            penalty,
            [0.31, -0.003, 1.0, 0.001, 0.0, 0.0, 0.0, 0.0],
            Tangent::Free,
        );
        // inside at both ends, and leaving (g₀ < 0 < g₁): the secant's other branches
        let mut inside = candidate();
        inside.x0[1] = -0.004;
        check_from(
            &inside,
            penalty,
            [0.31, -0.001, 1.0, 0.001, 0.0, 0.0, 0.0, 0.0],
            Tangent::Free,
        );
        check_from(
            &inside,
            penalty,
            [0.31, 0.002, 1.0, 0.001, 0.0, 0.0, 0.0, 0.0],
            Tangent::Free,
        );
        // the compliant multiplier, with friction in stick
        let compliant = PairLaw {
            enforcement: Enforcement::Compliant { stiffness: 50.0 },
            friction: 0.3,
        };
        check(
            compliant,
            [0.3002, -0.001, 1.0, 0.0001, 0.0, 0.0, 0.4, 0.05],
            Tangent::Stick,
        );
    }

    #[test]
    fn compliant_row_holds_the_penetration_lambda_over_stiffness() {
        // the row c (g₁ + λ/ε) vanishes at g₁ = −λ/ε: the penalty force ε (−g₁) carried by λ
        let forms = InvariantForms::new();
        let law = PairLaw {
            enforcement: Enforcement::Compliant { stiffness: 200.0 },
            friction: 0.0,
        };
        let mut c = candidate();
        c.lambda_n = 0.4;
        let x = Local6::from_column_slice(&[0.3, -0.4 / 200.0, 1.0, 0.0, 0.0, 0.0]);
        let scale = RowScale {
            c: 3.0,
            regularization: 1e-12,
            hysteresis: false,
        };
        let out = c.contribute(&forms, &law, Evaluation::End, &x, scale);
        assert!(c.active);
        assert!(out.r_n.abs() < 1e-15, "{}", out.r_n);
        assert_eq!(out.jac[(6, 6)], 3.0 / 200.0);
        // not compressed enough to hold λ: released
        c.lambda_n = 0.0;
        let open = Local6::from_column_slice(&[0.3, 1e-3, 1.0, 0.0, 0.0, 0.0]);
        let out = c.contribute(&forms, &law, Evaluation::End, &open, scale);
        assert!(!c.active);
        assert_eq!(out.r_n, 0.0);
    }

    #[test]
    fn released_constraint_reactivates_only_beyond_round_off_penetration() {
        // a frictionless candidate on the segment (1, 0) → (0, 0) (outward normal +y: the gap
        // is y_s), released (λ = 0, inactive), its slave node at the gap g
        let forms = InvariantForms::new();
        let law = PairLaw {
            enforcement: Enforcement::Lagrange,
            friction: 0.0,
        };
        let state = |g: f64, hysteresis: bool| {
            let mut c = candidate();
            c.lambda_n = 0.0;
            c.active = false;
            let x = Local6::from_column_slice(&[0.3, g, 1.0, 0.0, 0.0, 0.0]);
            let scale = RowScale {
                c: 3.0,
                regularization: 0.0,
                hysteresis,
            };
            c.contribute(&forms, &law, Evaluation::End, &x, scale);
            c.active
        };
        // a round-off penetration (below 16 ε c |x|): it stays released with the band, it
        // re-activates without (what made duplicated two-pass constraints cycle)
        assert!(!state(-1e-17, true));
        assert!(state(-1e-17, false));
        // touching with the band off (a step's first iteration): active
        assert!(state(0.0, false));
        // a real penetration re-activates it; a gap keeps it released
        assert!(state(-1e-9, true));
        assert!(!state(1e-9, true));
    }

    #[test]
    fn slip_force_opposes_the_slip() {
        let forms = InvariantForms::new();
        let law = PairLaw {
            enforcement: Enforcement::Lagrange,
            friction: 0.3,
        };
        let mut c = candidate();
        let x = Local6::from_column_slice(&[0.35, 0.0, 1.0, 0.0, 0.0, 0.0]);
        c.contribute(
            &forms,
            &law,
            Evaluation::DiscreteGradient,
            &x,
            RowScale {
                c: 3.0,
                regularization: 0.0,
                hysteresis: false,
            },
        );
        let Tangent::Slip(dir) = c.tangent else {
            panic!("expected slip")
        };
        let (_, tau1) = c.gap_and_tangential(&forms, &x);
        // the slip force's sign is dir; the slip τ₁ − τ₀ has the opposite sign
        assert!(dir * (tau1 - c.tau0) < 0.0);
    }
}
