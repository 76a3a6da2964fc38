//! The sliding block: the friction benchmark that reduces to one dimension (`docs/dynamic.md` §6).
//!
//! **Setting.** A plane-strain rectangle (0, L) × (0, H) of a linear elastic material (Young's
//! modulus E, Poisson's ratio ν, density ρ). Its bottom y = 0 is the contact boundary Γ3 against
//! the foundation {y ≤ δ} (it starts inside the asperity layer by δ, the *squeeze*); its top is
//! held at u_y = 0 by frictionless rollers and is free along x; its sides are free. At t = 0 it
//! rests in normal equilibrium and is launched along x with the velocity v0 everywhere.
//!
//! **Normal equilibrium.** A uniform compression lifts the bottom by e: u_y = e (1 − y/H),
//! ε_yy = −e/H; the free sides (σ_xx = 0) give, in plane strain, ε_xx = ν/(1 − ν) · e/H,
//! u_x = ε_xx (x − L/2), and σ_yy = −E′ e/H with E′ = E/(1 − ν²). The bottom penetrates the layer
//! by η = δ − e, and the compliance r η (BDS (1.8)) balances the stress, E′ e/H = r η:
//!
//!   η_c = δ E′/(E′ + r H),   N = r η_c L   (the total normal force per unit thickness).
//!
//! With the limited penetration of depth g_b (BDS (1.18), the improved penalized method, IPM)
//! and g_b ≤ η_c, the rigid base holds the bottom at η = g_b and carries the rest of the load:
//! N = E′ (δ − g_b) L/H, and the friction bound is μ0 N (stage (b), BDS §1.6.2). The case gives
//! η_c (its `penetration`) and the squeeze follows: δ = η_c (E′ + r H)/E′. The equilibrium
//! displacement is affine, so P1 elements represent it exactly, and the nodal contact forces of a
//! uniform pressure (weights w_i, Σ w_i = L) balance it node by node: the discrete block starts in
//! exact equilibrium.
//!
//! **Tangential motion.** Every contact point slides in +x at the same penetration η, so the
//! friction traction is uniform, of total F = μ(η) N (BDS (1.12); μ(η) of (1.13), μ0 in stage
//! (b)), and the block decelerates as a rigid body of mass m = ρ L H:
//!
//!   a = F/m,   v(t) = v0 − a t,   s(t) = v0 t − a t²/2   for t ≤ t* = v0/a,   s* = v0²/(2a),
//!
//! and then sticks: at rest no tangential force acts (the rollers are frictionless), and T = 0 is
//! within the bound.
//!
//! **What is exact.** The friction traction acts on the bottom, the inertia ρ a in the volume:
//! they do not balance point by point, so the block shears. Quasi-statically the shear stress
//! falls linearly from τ = F/L at the bottom to 0 at the top and the bottom lags the top by
//! δ_s = τ H/(2G), G = E/(2(1 + ν)); the free sides carry no shear, so near them the shear turns
//! into a small couple that changes the penetration. The rigid motion above is the E → ∞ limit,
//! and its error on the slip is O(δ_s): the cases choose E so that δ_s is far below every
//! discretization error they gate (the case files state the numbers). The normal equilibrium is
//! exact for every E.
//!
//! **The midpoint rule with the backward-difference slip rate** (BDS (1.36)–(1.38)) on the rigid
//! block: m (δu_n − δu_{n−1})/k = T_n, u_n − u_{n−1} = k (δu_n + δu_{n−1})/2 (BDS (1.31)),
//! T_n ∈ −F ∂|u_n − u_{n−1}|. While the block slides, δu_n = v(t_n) and u_n = s(t_n) exactly (a
//! constant force is integrated exactly). A step slides iff its mean velocity
//! (δu_n + δu_{n−1})/2 = v(t_{n−1/2}) is positive, i.e. t_{n−1/2} < t*; the first step with
//! t_{n−1/2} ≥ t* sticks — d = 0 needs |T| = 2m |δu_{n−1}|/k ≤ F, i.e. |v(t_{n−1})| ≤ a k/2,
//! which holds there, and neither slide is consistent — and so does every later step, with
//! δu alternating in sign at the same size. Hence the discrete stop time t_s = t_{n_s − 1}
//! (n_s that first sticking step) is within k/2 of t*, the slip stays at s(t_s) (the parabola,
//! past t* if t_s > t*), and the velocity after the stop alternates ±v(t_s). With
//! t*/k = N* + θ (0 < θ < 1, θ ≠ 1/2), t_s = t* − θ k for θ < 1/2 and t* + (1 − θ) k for
//! θ > 1/2: the errors are k φ (stop time), a k² φ²/2 (slip) and a k φ (velocity after the stop),
//! φ = min(θ, 1 − θ) — orders 1, 2 and 1 in k with a constant set by the phase. A sweep with
//! T = (3/2) t* and N steps not a multiple of 3 has t*/k = 2N/3, θ ∈ {1/3, 2/3} and φ = 1/3 on
//! every level: the errors are exactly k/3, a k²/18 and a k/3.

use serde::Serialize;

use crate::exact::coulomb_friction::Coulomb;

/// The foundation under the block.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum BlockFoundation {
    /// Normal compliance r (penalty or energy-consistent: the same equilibrium).
    Compliance { stiffness: f64 },
    /// Compliance r on a rigid base at depth g_b (BDS (1.18), the IPM).
    LimitedPenetration { stiffness: f64, depth: f64 },
}

impl BlockFoundation {
    /// r.
    pub fn stiffness(&self) -> f64 {
        match *self {
            Self::Compliance { stiffness } | Self::LimitedPenetration { stiffness, .. } => {
                stiffness
            }
        }
    }
}

/// The sliding block (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SlidingBlock {
    pub length: f64,
    pub height: f64,
    pub density: f64,
    pub young: f64,
    pub poisson: f64,
    pub foundation: BlockFoundation,
    /// η_c: the compliance's equilibrium penetration (the squeeze follows from it).
    pub penetration: f64,
    pub speed: f64,
    pub friction: Coulomb,
}

/// The discrete stop of the midpoint rule on the rigid block at step k (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DiscreteStop {
    /// n_s − 1: the last step that slides.
    pub last_sliding_step: usize,
    /// t_s = (n_s − 1) k.
    pub time: f64,
    /// s(t_s).
    pub slip: f64,
    /// v(t_s): the velocity that alternates in sign after the stop.
    pub velocity: f64,
    /// θ = frac(t*/k).
    pub phase: f64,
}

impl SlidingBlock {
    /// E′ = E/(1 − ν²).
    pub fn plane_strain_modulus(&self) -> f64 {
        self.young / (1.0 - self.poisson * self.poisson)
    }

    /// G = E/(2(1 + ν)).
    pub fn shear_modulus(&self) -> f64 {
        0.5 * self.young / (1.0 + self.poisson)
    }

    /// δ = η_c (E′ + r H)/E′ = η_c + e_c: the foundation level above the undeformed bottom.
    pub fn squeeze(&self) -> f64 {
        self.penetration + self.compliance_lift()
    }

    /// e_c = η_c r H/E′: the lift of the bottom that the compliance alone balances.
    fn compliance_lift(&self) -> f64 {
        self.penetration * self.foundation.stiffness() * self.height / self.plane_strain_modulus()
    }

    /// Whether the rigid base carries the block (limited penetration with g_b ≤ η_c).
    pub fn on_the_base(&self) -> bool {
        matches!(self.foundation, BlockFoundation::LimitedPenetration { depth, .. } if depth <= self.penetration)
    }

    /// η: η_c, or g_b on the base.
    pub fn equilibrium_penetration(&self) -> f64 {
        match self.foundation {
            BlockFoundation::LimitedPenetration { depth, .. } if self.on_the_base() => depth,
            _ => self.penetration,
        }
    }

    /// e = δ − η: the lift of the bottom (e_c off the base, computed without the cancellation).
    pub fn lift(&self) -> f64 {
        if self.on_the_base() {
            self.squeeze() - self.equilibrium_penetration()
        } else {
            self.compliance_lift()
        }
    }

    /// N = E′ e L/H (= r η_c L off the base).
    pub fn normal_force(&self) -> f64 {
        self.plane_strain_modulus() * self.lift() * self.length / self.height
    }

    /// The friction coefficient that acts: μ(η), or μ0 on the base.
    pub fn friction_coefficient(&self) -> f64 {
        if self.on_the_base() {
            self.friction.mu0
        } else {
            self.friction.mu(self.equilibrium_penetration())
        }
    }

    /// F = μ N.
    pub fn friction_force(&self) -> f64 {
        self.friction_coefficient() * self.normal_force()
    }

    /// m = ρ L H.
    pub fn mass(&self) -> f64 {
        self.density * self.length * self.height
    }

    /// a = F/m.
    pub fn deceleration(&self) -> f64 {
        self.friction_force() / self.mass()
    }

    /// t* = v0/a.
    pub fn stop_time(&self) -> f64 {
        self.speed / self.deceleration()
    }

    /// s* = v0²/(2a).
    pub fn stop_distance(&self) -> f64 {
        self.speed * self.speed / (2.0 * self.deceleration())
    }

    /// v(t): v0 − a t until t*, then 0.
    pub fn velocity(&self, t: f64) -> f64 {
        (self.speed - self.deceleration() * t).max(0.0)
    }

    /// s(t): the slip, v0 t − a t²/2 until t*, then s*.
    pub fn slip(&self, t: f64) -> f64 {
        let t = t.min(self.stop_time());
        self.speed * t - 0.5 * self.deceleration() * t * t
    }

    /// The equilibrium displacement at (x, y): (ε_xx (x − L/2), e (1 − y/H)).
    pub fn equilibrium_displacement(&self, x: f64, y: f64) -> [f64; 2] {
        let strain = self.lift() / self.height;
        let nu = self.poisson;
        [
            nu / (1.0 - nu) * strain * (x - 0.5 * self.length),
            self.lift() * (1.0 - y / self.height),
        ]
    }

    /// δ_s = τ H/(2G), τ = F/L: the quasi-static shear lag of the bottom behind the top, the
    /// scale of the block's departure from the rigid motion.
    pub fn shear_lag(&self) -> f64 {
        self.friction_force() / self.length * self.height / (2.0 * self.shear_modulus())
    }

    /// The stop of the midpoint rule on the rigid block with step k (module docs).
    pub fn discrete_stop(&self, k: f64) -> DiscreteStop {
        let t_star = self.stop_time();
        // the first step n with (n − 1/2) k ≥ t*
        let n_s = (t_star / k + 0.5).ceil().max(1.0) as usize;
        let time = (n_s - 1) as f64 * k;
        let a = self.deceleration();
        DiscreteStop {
            last_sliding_step: n_s - 1,
            time,
            slip: self.speed * time - 0.5 * a * time * time,
            velocity: self.speed - a * time,
            phase: (t_star / k).fract(),
        }
    }
}

#[cfg(test)]
mod tests {
    //! The sliding block against the problem it solves: the equilibrium (stress, compliance and
    //! squeeze consistent), the motion (ODE, stop, stick bound), and the discrete stop against a
    //! direct run of the midpoint rule with the friction inclusion on the rigid block, written
    //! here as a scalar loop.
    use super::*;
    use crate::exact::coulomb_friction::FrictionLaw;

    fn block(law: FrictionLaw, foundation: BlockFoundation) -> SlidingBlock {
        SlidingBlock {
            length: 1.0,
            height: 0.25,
            density: 1.0,
            young: 2e7,
            poisson: 0.3,
            foundation,
            penetration: 0.01,
            speed: 1.0,
            friction: Coulomb {
                law,
                mu0: 0.4,
                depth: 0.01 / 0.75,
            },
        }
    }

    const COMPLIANCE: BlockFoundation = BlockFoundation::Compliance { stiffness: 50.0 };

    #[test]
    fn equilibrium_balances_stress_compliance_and_squeeze() {
        let b = block(FrictionLaw::Constant, COMPLIANCE);
        let stress = b.plane_strain_modulus() * b.lift() / b.height;
        assert!((stress - 50.0 * b.penetration).abs() < 1e-12 * stress);
        assert!((b.lift() + b.equilibrium_penetration() - b.squeeze()).abs() < 1e-15);
        // σ_xx = (λ + 2μ) ε_xx + λ ε_yy = 0 with the strains of the displacement
        let (e, nu) = (b.young, b.poisson);
        let lam = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = b.shear_modulus();
        let h = 1e-3;
        let [ux1, uy1] = b.equilibrium_displacement(0.5 + h, 0.1);
        let [ux0, _] = b.equilibrium_displacement(0.5 - h, 0.1);
        let [_, uy2] = b.equilibrium_displacement(0.5, 0.1 + h);
        let [_, uy0] = b.equilibrium_displacement(0.5, 0.1 - h);
        let exx = (ux1 - ux0) / (2.0 * h);
        let eyy = (uy2 - uy0) / (2.0 * h);
        assert!(((lam + 2.0 * mu) * exx + lam * eyy).abs() < 1e-9 * stress);
        // σ_yy = −E′ e/H, and the bottom sits at the penetration η
        assert!((lam * exx + (lam + 2.0 * mu) * eyy + stress).abs() < 1e-9 * stress);
        assert_eq!(uy1, b.lift() * (1.0 - 0.1 / b.height));
        let [_, uy_bottom] = b.equilibrium_displacement(0.3, 0.0);
        assert!((b.squeeze() - uy_bottom - b.penetration).abs() < 1e-15);
        assert!((b.normal_force() - 50.0 * b.penetration * b.length).abs() < 1e-12);
    }

    #[test]
    fn the_base_carries_the_block_beyond_its_depth_with_mu0() {
        let on = block(
            FrictionLaw::Growing,
            BlockFoundation::LimitedPenetration {
                stiffness: 50.0,
                depth: 0.004,
            },
        );
        assert!(on.on_the_base());
        assert_eq!(on.equilibrium_penetration(), 0.004);
        assert_eq!(on.friction_coefficient(), 0.4);
        // the base carries E′ (δ − g_b)/H − r g_b per length beyond the compliance
        assert!(on.normal_force() > 50.0 * 0.004 * on.length);
        let off = block(
            FrictionLaw::Growing,
            BlockFoundation::LimitedPenetration {
                stiffness: 50.0,
                depth: 0.02,
            },
        );
        assert!(!off.on_the_base());
        assert!((off.friction_coefficient() - 0.3).abs() < 1e-15);
    }

    #[test]
    fn motion_solves_the_rigid_friction_ode_and_sticks() {
        for law in [
            FrictionLaw::Constant,
            FrictionLaw::Growing,
            FrictionLaw::Decreasing,
        ] {
            let b = block(law, COMPLIANCE);
            let a = b.deceleration();
            assert!((b.mass() * a - b.friction_force()).abs() < 1e-14);
            let h = 1e-4;
            let t = 0.4 * b.stop_time();
            let acc = (b.slip(t + h) - 2.0 * b.slip(t) + b.slip(t - h)) / (h * h);
            assert!((acc + a).abs() < 1e-5 * a, "{law:?}");
            assert!(((b.slip(t + h) - b.slip(t - h)) / (2.0 * h) - b.velocity(t)).abs() < 1e-9);
            assert!(b.velocity(b.stop_time()).abs() < 1e-15);
            assert!((b.slip(b.stop_time()) - b.stop_distance()).abs() < 1e-15);
            assert_eq!(b.slip(2.0 * b.stop_time()), b.slip(b.stop_time()));
        }
        // the three laws: μ = 0.4, 0.3, 0.5 at η/g = 3/4
        let a: Vec<f64> = [
            FrictionLaw::Constant,
            FrictionLaw::Growing,
            FrictionLaw::Decreasing,
        ]
        .iter()
        .map(|&l| block(l, COMPLIANCE).deceleration())
        .collect();
        assert!((a[1] / a[0] - 0.75).abs() < 1e-12 && (a[2] / a[0] - 1.25).abs() < 1e-12);
    }

    /// The midpoint rule with the backward-difference friction inclusion on the rigid block, step
    /// by step: the trial slide (T = −F sign of the step's slip) is taken when consistent,
    /// otherwise the stick (d = 0, T = −2 m δu_{n−1}/k) when within the bound. Returns the step
    /// count of slides before the first stick, the slip there and δu after each step.
    fn run_rigid_midpoint(b: &SlidingBlock, k: f64, steps: usize) -> (usize, f64, Vec<f64>) {
        let (m, f) = (b.mass(), b.friction_force());
        let (mut u, mut v) = (0.0, b.speed);
        let mut slides = None;
        let mut history = Vec::new();
        for n in 1..=steps {
            let forward = v - k * f / m; // T = −F
            let backward = v + k * f / m; // T = +F
            let (d, v_new) = if 0.5 * k * (v + forward) > 0.0 {
                (0.5 * k * (v + forward), forward)
            } else if 0.5 * k * (v + backward) < 0.0 {
                (0.5 * k * (v + backward), backward)
            } else {
                assert!(
                    2.0 * m * v.abs() / k <= f * (1.0 + 1e-12),
                    "stick out of bound"
                );
                (0.0, -v)
            };
            if d == 0.0 && slides.is_none() {
                slides = Some((n - 1, u));
            }
            u += d;
            v = v_new;
            history.push(v);
        }
        let (n, s) = slides.expect("the block stops");
        (n, s, history)
    }

    #[test]
    fn discrete_stop_matches_a_direct_run_of_the_scheme_for_every_phase() {
        let b = block(FrictionLaw::Decreasing, COMPLIANCE);
        let t_star = b.stop_time();
        for steps in [16usize, 17, 32, 50, 64, 101, 128] {
            let k = 1.5 * t_star / steps as f64;
            let stop = b.discrete_stop(k);
            let (n, s, history) = run_rigid_midpoint(&b, k, steps);
            assert_eq!(n, stop.last_sliding_step, "N = {steps}");
            assert!(
                (s - stop.slip).abs() < 1e-12,
                "N = {steps}: {s} vs {}",
                stop.slip
            );
            // after the stop δu alternates ±v(t_s)
            for (i, v) in history.iter().enumerate().skip(n) {
                let sign = if (i - n) % 2 == 0 { -1.0 } else { 1.0 };
                assert!(
                    (v - sign * stop.velocity).abs() < 1e-12,
                    "N = {steps} step {i}"
                );
            }
            assert!((stop.time - t_star).abs() <= 0.5 * k + 1e-12);
        }
    }

    #[test]
    fn a_phase_of_one_third_gives_errors_k_over_3_and_a_k2_over_18() {
        let b = block(FrictionLaw::Growing, COMPLIANCE);
        let t_star = b.stop_time();
        for steps in [32usize, 64, 128, 256, 512] {
            let k = 1.5 * t_star / steps as f64;
            let stop = b.discrete_stop(k);
            let phi = stop.phase.min(1.0 - stop.phase);
            assert!(
                (phi - 1.0 / 3.0).abs() < 1e-9,
                "N = {steps}: θ = {}",
                stop.phase
            );
            assert!(((stop.time - t_star).abs() - k / 3.0).abs() < 1e-12);
            let a = b.deceleration();
            assert!(((b.stop_distance() - stop.slip) - a * k * k / 18.0).abs() < 1e-14);
            assert!((stop.velocity.abs() - a * k / 3.0).abs() < 1e-12);
        }
    }
}
