//! A block sliding on a larger block with Coulomb friction, the larger one on a frictionless
//! foundation: the two-body friction benchmark of the multibody family (docs/multibody.md).
//!
//! **Setting.** Two rigid bodies under gravity g: the upper block (mass m₁) rests on the lower
//! block (mass m₂), which rests on a frictionless horizontal foundation. Between them Coulomb
//! friction with coefficient μ. At t = 0 the upper block moves along x with v₁(0), the lower
//! one with v₂(0); the relative velocity w = v₁ − v₂ starts at w₀ ≠ 0.
//!
//! **Motion.** The normal force between the blocks is N = m₁ g (the upper block does not move
//! vertically). While they slip, the friction force F = μ N opposes the relative motion: with
//! σ = sign w₀,
//!
//!   m₁ v̇₁ = −σ F,   m₂ v̇₂ = +σ F,   ẇ = −σ F (1/m₁ + 1/m₂) = −σ a,
//!   a = μ g (1 + m₁/m₂),
//!
//! so |w| falls linearly at the rate a until t* = |w₀|/a, after a slip s* = w₀²/(2a). The
//! foundation acts only vertically and gravity is vertical: the horizontal momentum
//! P = m₁ v₁ + m₂ v₂ is conserved, and from t* on both blocks move with V = P/(m₁ + m₂)
//! (stick: no horizontal force acts on the pair, and the friction force needed to keep them
//! together is 0 ≤ μ N). The dissipated energy is the work of the friction force on the slip,
//!
//!   D(t) = F s(t),   D* = F s* = ½ m_r w₀²,   m_r = m₁ m₂/(m₁ + m₂),
//!
//! the kinetic energy of the relative motion (the kinetic energy ½ P²/(m₁ + m₂) of the centre of
//! mass is untouched).
//!
//! **The midpoint-type schemes** (the implicit midpoint rule and the energy–momentum scheme, EM
//! (58)–(67)) with the constraint rows at t_{n+1}: the step's momentum equations are
//! m_i (v_{i,n+1} − v_{i,n})/k = forces of the step (λ_T constant over the step), the increments
//! d_i = k (v_{i,n} + v_{i,n+1})/2, and the friction of the step obeys the return map of EM
//! (50)–(52) on the step's slip τ₁ − τ₀ = d₁ − d₂ with the bound μ λ_N, λ_N the step's normal
//! force (= m₁ g: the upper block stays level). For the relative motion this is exactly the
//! one-body sliding block of `exact/sliding_block.rs` with the reduced mass m_r and the force
//! μ m₁ g: a step slides iff its mean relative velocity (w_n + w_{n+1})/2 = w(t_{n+1/2}) has the
//! sign of w₀, i.e. t_{n+1/2} < t*; the first step with t_{n−1/2} ≥ t* sticks (its stick force
//! 2 m_r |w_{n−1}|/k ≤ F because |w(t_{n−1})| ≤ a k/2), and so does every later step, with w
//! alternating ±w(t_s). Hence the discrete stop t_s = t_{n_s − 1} (n_s that first sticking step,
//! n_s = ⌈t*/k + 1/2⌉), the slip s(t_s) and the dissipation D(t_s) = F s(t_s) =
//! ½ m_r (w₀² − w(t_s)²): the kinetic energy ½ m_r w(t_s)² of the alternating relative velocity
//! is never dissipated. With t*/k = N* + θ, φ = min(θ, 1 − θ) (θ ≠ ½), the errors are
//! |t_s − t*| = φ k, |w(t_s)| = φ a k, s* − s(t_s) = a φ² k²/2 and D* − D(t_s) = ½ m_r (φ a k)²:
//! orders 1, 1, 2 and 2 in k, their constants set by the phase. T = (3/2) t* with N steps not a
//! multiple of 3 gives t*/k = 2N/3, φ = 1/3 on every level: the stop time's error is exactly k/3.
//!
//! The centre velocities follow v₁ = v₁(0) − σ F t/m₁, v₂ = v₂(0) + σ F t/m₂ at every t_n ≤ t_s
//! (a constant force is integrated exactly), and after the stop they alternate about V:
//! v₁ = V ± m₂/(m₁ + m₂) w(t_s), v₂ = V ∓ m₁/(m₁ + m₂) w(t_s).
//!
//! **What is exact.** The elastic blocks of a case depart from this rigid motion by their
//! deformation: the shear lag of the friction traction (the bottom of the upper block lags its
//! top by δ_s = τ H₁/(2G), τ = F/L₁) and the vertical compressions under the weights (which the
//! moving load shifts on the lower block). The case chooses the blocks stiff enough, and starts
//! them from the static equilibrium under gravity, so that these are far below every error it
//! gates (the case files give the numbers, [`TwoBlockSlide::shear_lag`] and
//! [`TwoBlockSlide::compression`]).

use serde::Serialize;

/// The two-block slide (module docs). Index 1: the upper block; 2: the lower block.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TwoBlockSlide {
    /// m₁, m₂.
    pub upper_mass: f64,
    pub lower_mass: f64,
    /// μ between the blocks.
    pub friction: f64,
    /// g.
    pub gravity: f64,
    /// v₁(0), v₂(0) along x.
    pub upper_speed: f64,
    pub lower_speed: f64,
}

/// The discrete stop of a midpoint-type scheme at step k (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TwoBlockStop {
    /// n_s − 1: the last step that slides.
    pub last_sliding_step: usize,
    /// t_s = (n_s − 1) k.
    pub time: f64,
    /// s(t_s): the slip (its sign is that of w₀).
    pub slip: f64,
    /// w(t_s): the relative velocity that alternates in sign after the stop.
    pub relative_velocity: f64,
    /// D(t_s) = F |s(t_s)|.
    pub dissipation: f64,
    /// θ = frac(t*/k).
    pub phase: f64,
}

impl TwoBlockSlide {
    /// σ = sign w₀.
    fn sigma(&self) -> f64 {
        if self.initial_relative_velocity() >= 0.0 {
            1.0
        } else {
            -1.0
        }
    }

    /// w₀ = v₁(0) − v₂(0).
    pub fn initial_relative_velocity(&self) -> f64 {
        self.upper_speed - self.lower_speed
    }

    /// N = m₁ g.
    pub fn normal_force(&self) -> f64 {
        self.upper_mass * self.gravity
    }

    /// F = μ N.
    pub fn friction_force(&self) -> f64 {
        self.friction * self.normal_force()
    }

    /// m_r = m₁ m₂/(m₁ + m₂).
    pub fn reduced_mass(&self) -> f64 {
        self.upper_mass * self.lower_mass / (self.upper_mass + self.lower_mass)
    }

    /// a = μ g (1 + m₁/m₂) = F/m_r: the rate at which |w| falls.
    pub fn relative_deceleration(&self) -> f64 {
        self.friction * self.gravity * (1.0 + self.upper_mass / self.lower_mass)
    }

    /// t* = |w₀|/a.
    pub fn stop_time(&self) -> f64 {
        self.initial_relative_velocity().abs() / self.relative_deceleration()
    }

    /// |s*| = w₀²/(2a).
    pub fn stop_distance(&self) -> f64 {
        let w0 = self.initial_relative_velocity();
        w0 * w0 / (2.0 * self.relative_deceleration())
    }

    /// P = m₁ v₁(0) + m₂ v₂(0).
    pub fn momentum(&self) -> f64 {
        self.upper_mass * self.upper_speed + self.lower_mass * self.lower_speed
    }

    /// V = P/(m₁ + m₂): the common velocity after the stop.
    pub fn common_velocity(&self) -> f64 {
        self.momentum() / (self.upper_mass + self.lower_mass)
    }

    /// w(t) = w₀ − σ a t until t*, then 0.
    pub fn relative_velocity(&self, t: f64) -> f64 {
        let t = t.clamp(0.0, self.stop_time());
        self.initial_relative_velocity() - self.sigma() * self.relative_deceleration() * t
    }

    /// s(t) = w₀ t − σ a t²/2 until t*, then s* (signed).
    pub fn slip(&self, t: f64) -> f64 {
        let t = t.clamp(0.0, self.stop_time());
        self.initial_relative_velocity() * t
            - 0.5 * self.sigma() * self.relative_deceleration() * t * t
    }

    /// [v₁(t), v₂(t)]: the centre velocities (rigid motion).
    pub fn velocities(&self, t: f64) -> [f64; 2] {
        let t = t.clamp(0.0, self.stop_time());
        let f = self.sigma() * self.friction_force();
        [
            self.upper_speed - f * t / self.upper_mass,
            self.lower_speed + f * t / self.lower_mass,
        ]
    }

    /// D(t) = F |s(t)|: the energy friction has dissipated.
    pub fn dissipation(&self, t: f64) -> f64 {
        self.friction_force() * self.slip(t).abs()
    }

    /// D* = ½ m_r w₀².
    pub fn total_dissipation(&self) -> f64 {
        let w0 = self.initial_relative_velocity();
        0.5 * self.reduced_mass() * w0 * w0
    }

    /// The stop of a midpoint-type scheme with step k (module docs): n_s = ⌈t*/k + 1/2⌉.
    pub fn discrete_stop(&self, k: f64) -> TwoBlockStop {
        let t_star = self.stop_time();
        let n_s = (t_star / k + 0.5).ceil().max(1.0) as usize;
        let time = (n_s - 1) as f64 * k;
        let w0 = self.initial_relative_velocity();
        let sa = self.sigma() * self.relative_deceleration();
        let slip = w0 * time - 0.5 * sa * time * time;
        TwoBlockStop {
            last_sliding_step: n_s - 1,
            time,
            slip,
            relative_velocity: w0 - sa * time,
            dissipation: self.friction_force() * slip.abs(),
            phase: (t_star / k).fract(),
        }
    }

    /// [v₁, v₂] of the scheme after step n (module docs): the rigid motion up to the stop,
    /// then V ± the alternating parts (+ for n − n_s even… the sign of w_n).
    pub fn discrete_velocities(&self, k: f64, n: usize) -> [f64; 2] {
        let stop = self.discrete_stop(k);
        if n <= stop.last_sliding_step {
            // the constant force integrated exactly up to t_s, which may lie past t* (by less
            // than k/2): not clamped at t* as the continuum's velocities are
            let t = n as f64 * k;
            let f = self.sigma() * self.friction_force();
            return [
                self.upper_speed - f * t / self.upper_mass,
                self.lower_speed + f * t / self.lower_mass,
            ];
        }
        // w alternates: −w(t_s) after the first sticking step, +w(t_s) after the next, …
        let sign = if (n - stop.last_sliding_step) % 2 == 1 {
            -1.0
        } else {
            1.0
        };
        let w = sign * stop.relative_velocity;
        let m = self.upper_mass + self.lower_mass;
        let v = self.common_velocity();
        [v + self.lower_mass / m * w, v - self.upper_mass / m * w]
    }

    /// δ_s = τ H₁/(2G), τ = F/L₁: the quasi-static shear lag of the upper block's bottom behind
    /// its top under the friction traction (the scale of its departure from the rigid motion).
    pub fn shear_lag(&self, length: f64, height: f64, shear_modulus: f64) -> f64 {
        self.friction_force() / length * height / (2.0 * shear_modulus)
    }

    /// The compressions of the blocks under gravity, ρ g H₁²/(2E′) (the upper block's own
    /// weight) and (m₁ g/L₁ + ρ g H₂/2) H₂/E′ (the lower block under the upper one): the
    /// scale of the vertical deformation the moving load shifts.
    pub fn compression(
        &self,
        density: f64,
        upper: [f64; 2],
        lower_height: f64,
        plane_strain_modulus: f64,
    ) -> f64 {
        let g = self.gravity;
        let own = density * g * upper[1] * upper[1] / (2.0 * plane_strain_modulus);
        let under = (self.normal_force() / upper[0] + 0.5 * density * g * lower_height)
            * lower_height
            / plane_strain_modulus;
        own + under
    }
}

#[cfg(test)]
mod tests {
    //! The two-block slide against the problem it solves: the ODE, the momentum, the stop and
    //! the dissipation; and the discrete stop against a direct run of the midpoint rule with the
    //! friction return map on the two rigid blocks, written here as a scalar loop.
    use super::*;

    fn slide(v1: f64, v2: f64) -> TwoBlockSlide {
        TwoBlockSlide {
            upper_mass: 0.5,
            lower_mass: 2.0,
            friction: 0.3,
            gravity: 1.0,
            upper_speed: v1,
            lower_speed: v2,
        }
    }

    #[test]
    fn motion_solves_the_two_body_friction_ode_and_conserves_momentum() {
        for (v1, v2) in [(0.75, 0.0), (0.2, 0.9), (-0.3, 0.1)] {
            let s = slide(v1, v2);
            let f = s.friction_force();
            let sigma = s.initial_relative_velocity().signum();
            let h = 1e-5;
            let t = 0.4 * s.stop_time();
            let [a1p, a2p] = s.velocities(t + h);
            let [a1m, a2m] = s.velocities(t - h);
            assert!(((a1p - a1m) / (2.0 * h) * s.upper_mass + sigma * f).abs() < 1e-9);
            assert!(((a2p - a2m) / (2.0 * h) * s.lower_mass - sigma * f).abs() < 1e-9);
            for t in [0.0, 0.3 * s.stop_time(), s.stop_time(), 3.0 * s.stop_time()] {
                let [u, l] = s.velocities(t);
                assert!((s.upper_mass * u + s.lower_mass * l - s.momentum()).abs() < 1e-15);
                assert!((u - l - s.relative_velocity(t)).abs() < 1e-15);
            }
            let [u, l] = s.velocities(s.stop_time());
            assert!((u - s.common_velocity()).abs() < 1e-14);
            assert!((l - s.common_velocity()).abs() < 1e-14);
            assert!((s.slip(s.stop_time()).abs() - s.stop_distance()).abs() < 1e-15);
            // ṡ = w
            let t = 0.7 * s.stop_time();
            let ds = (s.slip(t + h) - s.slip(t - h)) / (2.0 * h);
            assert!((ds - s.relative_velocity(t)).abs() < 1e-9);
        }
        let s = slide(0.75, 0.0);
        assert!((s.relative_deceleration() - 0.375).abs() < 1e-15);
        assert!((s.stop_time() - 2.0).abs() < 1e-15);
    }

    #[test]
    fn dissipation_is_the_relative_kinetic_energy() {
        for (v1, v2) in [(0.75, 0.0), (0.2, 0.9)] {
            let s = slide(v1, v2);
            let ke = |[u, l]: [f64; 2]| 0.5 * (s.upper_mass * u * u + s.lower_mass * l * l);
            let lost = ke(s.velocities(0.0)) - ke(s.velocities(s.stop_time()));
            assert!((lost - s.total_dissipation()).abs() < 1e-15);
            assert!((s.dissipation(s.stop_time()) - s.total_dissipation()).abs() < 1e-15);
            let t = 0.35 * s.stop_time();
            let lost_t = ke(s.velocities(0.0)) - ke(s.velocities(t));
            assert!((lost_t - s.dissipation(t)).abs() < 1e-15);
        }
    }

    /// The midpoint rule on the two rigid blocks with the friction return map on the step's slip
    /// d₁ − d₂ and the bound μ m₁ g: the trial slide (force −σ F on the upper block) when its
    /// slip has the sign σ, the reverse slide when consistent, else the stick (d₁ = d₂). Returns
    /// the last sliding step, the slip there and [v₁, v₂] after each step.
    fn run_rigid_midpoint(s: &TwoBlockSlide, k: f64, steps: usize) -> (usize, f64, Vec<[f64; 2]>) {
        let (m1, m2, f) = (s.upper_mass, s.lower_mass, s.friction_force());
        let (mut v1, mut v2) = (s.upper_speed, s.lower_speed);
        let mut slip = 0.0;
        let mut stop = None;
        let mut history = Vec::new();
        for n in 1..=steps {
            let slide_with = |t: f64| (v1 + k * t / m1, v2 - k * t / m2);
            let mut chosen = None;
            for t in [-f, f] {
                let (a, b) = slide_with(t);
                let d = 0.5 * k * ((v1 + a) - (v2 + b));
                // the force opposes the slip: t = −F sign d
                if d != 0.0 && t == -f * d.signum() {
                    chosen = Some((a, b, d));
                }
            }
            let (a, b, d) = match chosen {
                Some(c) => c,
                None => {
                    // stick: d₁ = d₂ and equal and opposite forces T: the relative velocity
                    // reverses, w_{n+1} = −w_n, with T = −2 m_r w_n/k within the bound
                    let w = v1 - v2;
                    let t = -2.0 * s.reduced_mass() * w / k;
                    assert!(
                        t.abs() <= f * (1.0 + 1e-12),
                        "stick out of bound at step {n}"
                    );
                    let (a, b) = slide_with(t);
                    (a, b, 0.0)
                }
            };
            if d == 0.0 && stop.is_none() {
                stop = Some((n - 1, slip));
            }
            slip += d;
            v1 = a;
            v2 = b;
            history.push([v1, v2]);
        }
        let (n, sl) = stop.expect("the blocks stick");
        (n, sl, history)
    }

    #[test]
    fn discrete_stop_matches_a_direct_run_of_the_scheme_for_every_phase() {
        for (v1, v2) in [(0.75, 0.0), (0.1, 0.8)] {
            let s = slide(v1, v2);
            let t_star = s.stop_time();
            for steps in [16usize, 17, 32, 50, 64, 101, 128] {
                let k = 1.5 * t_star / steps as f64;
                let stop = s.discrete_stop(k);
                let (n, sl, history) = run_rigid_midpoint(&s, k, steps);
                assert_eq!(n, stop.last_sliding_step, "N = {steps}");
                assert!((sl - stop.slip).abs() < 1e-12, "N = {steps}");
                assert!((stop.time - t_star).abs() <= 0.5 * k + 1e-12);
                for (i, v) in history.iter().enumerate() {
                    let e = s.discrete_velocities(k, i + 1);
                    assert!(
                        (v[0] - e[0]).abs() < 1e-12 && (v[1] - e[1]).abs() < 1e-12,
                        "N = {steps} step {}: {v:?} vs {e:?}",
                        i + 1
                    );
                }
                // the dissipation is the relative kinetic energy lost
                let w = stop.relative_velocity;
                let w0 = s.initial_relative_velocity();
                assert!(
                    (stop.dissipation - 0.5 * s.reduced_mass() * (w0 * w0 - w * w)).abs() < 1e-14
                );
            }
        }
    }

    #[test]
    fn a_phase_of_one_third_gives_errors_k_over_3() {
        let s = slide(0.75, 0.0);
        let (t_star, a) = (s.stop_time(), s.relative_deceleration());
        for steps in [32usize, 64, 128, 256, 512, 1000] {
            let k = 1.5 * t_star / steps as f64;
            let stop = s.discrete_stop(k);
            let phi = stop.phase.min(1.0 - stop.phase);
            assert!((phi - 1.0 / 3.0).abs() < 1e-9, "N = {steps}");
            assert!(((stop.time - t_star).abs() - k / 3.0).abs() < 1e-12);
            assert!((stop.relative_velocity.abs() - a * k / 3.0).abs() < 1e-12);
            assert!(((s.stop_distance() - stop.slip) - a * k * k / 18.0).abs() < 1e-14);
            let lost = s.total_dissipation() - stop.dissipation;
            assert!((lost - 0.5 * s.reduced_mass() * (a * k / 3.0).powi(2)).abs() < 1e-15);
        }
    }
}
