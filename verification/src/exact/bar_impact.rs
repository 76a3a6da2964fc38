//! Exact 1D impacts of two free elastic bars of the same material and section (docs/multibody.md;
//! d'Alembert's solution of u_tt = c² u_xx, c = √(E/ρ), by the method of characteristics).
//!
//! **The end-loaded free bar** ([`EndLoadedBar`]). A bar Y ∈ (0, ℓ), free at Y = ℓ, at rest, is
//! pushed at Y = 0 by the pressure ρ c a while s ∈ (0, w/c) (then released). The pressure sends
//! the right-running pulse u_t = a, σ = −ρ c a (a right-running wave has σ = −ρ c u_t, a
//! left-running one σ = +ρ c u_t) of length w. With the pulse profile
//! p(ξ) = a · 1_(0, w)(ξ) and its primitive P(ξ) = a · clamp(ξ, 0, w), the images at the free
//! end Y = ℓ (σ = 0: the reflection keeps u_t and flips σ) and at Y = 0 once the load is off give
//!
//!   u_t(Y, s) = Σ_{j≥0} [ p(cs − Y − 2jℓ) + p(cs + Y − 2(j+1)ℓ) ],
//!   σ(Y, s)   = −ρ c Σ_{j≥0} [ p(cs − Y − 2jℓ) − p(cs + Y − 2(j+1)ℓ) ],
//!   u(Y, s)   = (1/c) Σ_{j≥0} [ P(cs − Y − 2jℓ) + P(cs + Y − 2(j+1)ℓ) ]
//!
//! (σ(ℓ, s) = 0 term by term; at Y = 0 the sum telescopes to σ(0, s) = −ρ c p(cs): the applied
//! pressure). The momentum grows by the impulse: the centre-of-mass velocity is
//! c a clamp(s, 0, w/c)/ℓ, and the energy by the work ρ c a² · clamp(s, 0, w/c) (per unit area).
//!
//! **Two bars head-on** ([`HeadOnBars`]): two bars of length L at +v and −v, their ends g0 apart.
//! By symmetry the mid-plane does not move and carries the contact stress: each bar is the free
//! bar hitting a rigid wall at g0/2 ([`BarWallImpact`]): contact from t0 = g0/(2v) for 2L/c, the
//! stress ρ c v, each bar's centre velocity ±v → ∓v linearly, rebound at ∓v, all the energy
//! ρ A L v² kinetic again. In each bar's frame of the end-loaded bar: a = v, w = 2L.
//!
//! **A striker hitting a longer target** ([`StrikerTarget`]): a striker of length L1 at speed v
//! hits a target of length L2 ≥ L1 at rest, ends g0 apart. At contact (t0 = g0/v) the impedances
//! are equal, so the interface moves at v/2 and carries σ = −ρ c v/2 (continuity of u_t and σ
//! across the characteristics from both sides: v − σ/(ρc)·(−1)… i.e. v* = (v + 0)/2,
//! σ* = −ρ c (v − 0)/2). The compression wave runs through the striker, reflects at its free end
//! as an unloading wave and returns at t0 + 2L1/c: the striker is then at rest and unstressed, the
//! interface stress vanishes and the contact force ends (the faces stay touching without force
//! until the target's pulse, reflected at its far end, returns at t0 + 2L2/c and its end leaves
//! at speed v: no second contact). Each bar is the end-loaded bar with a = v/2, w = 2L1: the
//! striker's velocity is v − u_t, the target's u_t; the target carries the rectangular pulse of
//! length 2L1 (u_t = v/2, σ = −ρ c v/2) and the momentum ρ A L1 v, the striker none; the energy
//! ½ ρ A L1 v² passes to the target at the rate ρ A c v²/4.

use crate::exact::signorini_bar::BarWallImpact;

/// The free bar (0, ℓ) pushed at Y = 0 (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndLoadedBar {
    /// ℓ.
    pub length: f64,
    /// c = √(E/ρ).
    pub wave_speed: f64,
    /// ρ (for the stress ρ c u_t).
    pub density: f64,
    /// a: the particle velocity in the pulse.
    pub amplitude: f64,
    /// w: the pulse length (the load lasts w/c).
    pub width: f64,
}

/// u, u_t and σ at one point (the change caused by the load, in the bar's own direction Y).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WaveState {
    pub u: f64,
    pub u_t: f64,
    /// The axial stress (tension positive).
    pub stress: f64,
}

impl EndLoadedBar {
    fn pulse(&self, xi: f64) -> f64 {
        if xi > 0.0 && xi < self.width {
            self.amplitude
        } else {
            0.0
        }
    }

    fn primitive(&self, xi: f64) -> f64 {
        self.amplitude * xi.clamp(0.0, self.width)
    }

    /// u, u_t, σ at (Y, s), s the time since the load began (zero for s ≤ 0).
    pub fn state(&self, y: f64, s: f64) -> WaveState {
        let (c, l) = (self.wave_speed, self.length);
        let mut out = WaveState::default();
        if s <= 0.0 {
            return out;
        }
        let cs = c * s;
        let mut j = 0.0;
        // terms vanish once both arguments are ≤ 0: cs − Y − 2jℓ ≤ 0 for j > cs/(2ℓ)
        while 2.0 * j * l <= cs + l {
            let right = cs - y - 2.0 * j * l;
            let left = cs + y - 2.0 * (j + 1.0) * l;
            out.u_t += self.pulse(right) + self.pulse(left);
            out.stress -= self.density * c * (self.pulse(right) - self.pulse(left));
            out.u += (self.primitive(right) + self.primitive(left)) / c;
            j += 1.0;
        }
        out
    }

    /// The centre-of-mass velocity c a clamp(s, 0, w/c)/ℓ (the impulse over the mass).
    pub fn centre_velocity(&self, s: f64) -> f64 {
        let c = self.wave_speed;
        c * self.amplitude * s.clamp(0.0, self.width / c) / self.length
    }

    /// The energy per unit area ρ c a² clamp(s, 0, w/c) (the work of the load).
    pub fn energy(&self, s: f64) -> f64 {
        let c = self.wave_speed;
        self.density * c * self.amplitude.powi(2) * s.clamp(0.0, self.width / c)
    }
}

/// What the multibody case measures of an impact of two bars: the left bar (index 0) moves
/// towards the right bar (index 1); x is the axis of the bars, positions in each bar are
/// distances from its contact end.
pub trait TwoBarImpact {
    /// c = √(E/ρ).
    fn wave_speed(&self) -> f64;
    /// The time the ends meet.
    fn contact_start(&self) -> f64;
    /// The time the contact force ends.
    fn contact_end(&self) -> f64;
    /// The compressive contact stress while the force acts.
    fn contact_stress(&self) -> f64;
    /// The section A (per unit thickness in plane strain: the height).
    fn area(&self) -> f64;
    /// The contact force A σ_c on (start, end), 0 outside.
    fn contact_force(&self, t: f64) -> f64 {
        if t > self.contact_start() && t < self.contact_end() {
            self.area() * self.contact_stress()
        } else {
            0.0
        }
    }
    /// Each bar's centre-of-mass velocity (x component).
    fn centre_velocities(&self, t: f64) -> [f64; 2];
    /// Each bar's energy (kinetic + elastic).
    fn energies(&self, t: f64) -> [f64; 2];
    /// The total energy (constant).
    fn energy(&self) -> f64 {
        let e = self.energies(0.0);
        e[0] + e[1]
    }
    /// The masses ρ A L of the bars.
    fn masses(&self) -> [f64; 2];
    /// The x velocity and the axial stress of bar `b` at distance `d` from its contact end at t.
    fn field(&self, b: usize, d: f64, t: f64) -> WaveState;
}

/// Two equal bars meeting head-on at ±v (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadOnBars {
    pub length: f64,
    pub density: f64,
    pub young: f64,
    pub area: f64,
    /// v > 0: the left bar moves at +v, the right one at −v.
    pub speed: f64,
    /// g0 ≥ 0 between the ends.
    pub gap: f64,
}

impl HeadOnBars {
    /// The right bar as a free bar hitting a wall at the mid-plane, g0/2 away.
    pub fn wall(&self) -> BarWallImpact {
        BarWallImpact {
            length: self.length,
            density: self.density,
            young: self.young,
            area: self.area,
            speed: self.speed,
            gap: 0.5 * self.gap,
        }
    }

    /// Each bar as the end-loaded bar (a = v, w = 2L).
    pub fn loaded(&self) -> EndLoadedBar {
        EndLoadedBar {
            length: self.length,
            wave_speed: self.wall().wave_speed(),
            density: self.density,
            amplitude: self.speed,
            width: 2.0 * self.length,
        }
    }
}

impl TwoBarImpact for HeadOnBars {
    fn wave_speed(&self) -> f64 {
        self.wall().wave_speed()
    }
    fn contact_start(&self) -> f64 {
        self.wall().contact_start()
    }
    fn contact_end(&self) -> f64 {
        let w = self.wall();
        w.contact_start() + w.contact_duration()
    }
    fn contact_stress(&self) -> f64 {
        self.wall().contact_stress()
    }
    fn area(&self) -> f64 {
        self.area
    }
    fn centre_velocities(&self, t: f64) -> [f64; 2] {
        let v = self.wall().centre_velocity(t);
        [-v, v]
    }
    fn energies(&self, _t: f64) -> [f64; 2] {
        let e = self.wall().energy();
        [e, e]
    }
    fn masses(&self) -> [f64; 2] {
        let m = self.wall().mass();
        [m, m]
    }
    fn field(&self, b: usize, d: f64, t: f64) -> WaveState {
        let s = self.loaded().state(d, t - self.contact_start());
        // the left bar (b = 0) moves at +v and is pushed towards −x; the right one the reverse
        let sign = if b == 0 { -1.0 } else { 1.0 };
        WaveState {
            u: -sign * self.speed * t + sign * s.u,
            u_t: -sign * self.speed + sign * s.u_t,
            stress: s.stress,
        }
    }
}

/// A striker of length L1 at speed v hitting a target of length L2 ≥ L1 at rest (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrikerTarget {
    pub striker_length: f64,
    pub target_length: f64,
    pub density: f64,
    pub young: f64,
    pub area: f64,
    /// v > 0: the striker's speed towards the target.
    pub speed: f64,
    /// g0 ≥ 0 between the ends.
    pub gap: f64,
}

impl StrikerTarget {
    fn c(&self) -> f64 {
        (self.young / self.density).sqrt()
    }

    /// The striker (b = 0) or the target (b = 1) as the end-loaded bar: a = v/2, w = 2 L1.
    pub fn loaded(&self, b: usize) -> EndLoadedBar {
        EndLoadedBar {
            length: if b == 0 {
                self.striker_length
            } else {
                self.target_length
            },
            wave_speed: self.c(),
            density: self.density,
            amplitude: 0.5 * self.speed,
            width: 2.0 * self.striker_length,
        }
    }

    /// The interface velocity v/2 while in contact.
    pub fn interface_velocity(&self) -> f64 {
        0.5 * self.speed
    }

    /// The striker's final velocity (0) and the target's final centre velocity v L1/L2.
    pub fn final_velocities(&self) -> [f64; 2] {
        [0.0, self.speed * self.striker_length / self.target_length]
    }

    /// The time the target's reflected pulse returns to its contact end (t0 + 2 L2/c): its end
    /// leaves the striker.
    pub fn separation(&self) -> f64 {
        self.contact_start() + 2.0 * self.target_length / self.c()
    }
}

impl TwoBarImpact for StrikerTarget {
    fn wave_speed(&self) -> f64 {
        self.c()
    }
    fn contact_start(&self) -> f64 {
        self.gap / self.speed
    }
    fn contact_end(&self) -> f64 {
        self.contact_start() + 2.0 * self.striker_length / self.c()
    }
    fn contact_stress(&self) -> f64 {
        0.5 * self.density * self.c() * self.speed
    }
    fn area(&self) -> f64 {
        self.area
    }
    fn centre_velocities(&self, t: f64) -> [f64; 2] {
        let s = t - self.contact_start();
        [
            self.speed - self.loaded(0).centre_velocity(s),
            self.loaded(1).centre_velocity(s),
        ]
    }
    fn energies(&self, t: f64) -> [f64; 2] {
        let s = t - self.contact_start();
        let e0 = 0.5 * self.density * self.area * self.striker_length * self.speed.powi(2);
        let moved = self.area * self.loaded(1).energy(s);
        [e0 - moved, moved]
    }
    fn masses(&self) -> [f64; 2] {
        let m = self.density * self.area;
        [m * self.striker_length, m * self.target_length]
    }
    fn field(&self, b: usize, d: f64, t: f64) -> WaveState {
        let s = self.loaded(b).state(d, t - self.contact_start());
        if b == 0 {
            // pushed towards −x
            WaveState {
                u: self.speed * t - s.u,
                u_t: self.speed - s.u_t,
                stress: s.stress,
            }
        } else {
            s
        }
    }
}

#[cfg(test)]
mod tests {
    //! The closed forms against independent checks: a characteristic (upwind, Courant 1) solver of
    //! the two bars with unilateral contact written here — exact on a grid that carries the
    //! fronts, so its cell values, forces, centre velocities and energies must match to
    //! round-off; momentum and energy of the fields by quadrature; the free end and the load of
    //! the end-loaded bar; the limit L2 = L1 against the head-on pair in the centre-of-mass frame.
    use super::*;

    /// Two bars on cells of size Δx = c Δt, the characteristic variables r = u_t − σ/(ρc) (moving
    /// at +c) and l = u_t + σ/(ρc) (at −c) shifted one cell per step (exact at Courant 1), free
    /// far ends (σ = 0: the outgoing variable equals the incoming one), and at the facing ends
    /// unilateral contact: bonded (full transmission, σ* = ρc (l_R − r_L)/2) when the gap is
    /// closed and σ* ≤ 0, free ends otherwise (the gap changes at l_R − r_L).
    struct Upwind {
        rho_c: f64,
        dt: f64,
        /// r and l of the left bar (cell 0 at its far end) and of the right bar (cell 0 at its
        /// contact end).
        r: [Vec<f64>; 2],
        l: [Vec<f64>; 2],
        gap: f64,
    }

    impl Upwind {
        fn new(cells: [usize; 2], velocities: [f64; 2], rho_c: f64, dt: f64, gap: f64) -> Self {
            Self {
                rho_c,
                dt,
                r: [vec![velocities[0]; cells[0]], vec![velocities[1]; cells[1]]],
                l: [vec![velocities[0]; cells[0]], vec![velocities[1]; cells[1]]],
                gap,
            }
        }

        /// One step; returns the contact stress σ* of the step (0 when free).
        fn step(&mut self) -> f64 {
            let [n1, n2] = [self.r[0].len(), self.r[1].len()];
            let (r_l, l_r) = (self.r[0][n1 - 1], self.l[1][0]);
            let bonded = (l_r - r_l) * 0.5 * self.rho_c;
            let (out_l, out_r, stress) = if self.gap <= 1e-14 && bonded <= 0.0 {
                (l_r, r_l, bonded)
            } else {
                self.gap += self.dt * (l_r - r_l);
                (r_l, l_r, 0.0)
            };
            let (r0, l0) = (self.r.clone(), self.l.clone());
            for b in 0..2 {
                let n = r0[b].len();
                for i in 1..n {
                    self.r[b][i] = r0[b][i - 1];
                }
                for i in 0..n - 1 {
                    self.l[b][i] = l0[b][i + 1];
                }
            }
            // far ends: free
            self.r[0][0] = l0[0][0];
            self.l[1][n2 - 1] = r0[1][n2 - 1];
            // facing ends
            self.l[0][n1 - 1] = out_l;
            self.r[1][0] = out_r;
            stress
        }

        fn velocity(&self, b: usize, i: usize) -> f64 {
            0.5 * (self.r[b][i] + self.l[b][i])
        }

        fn stress(&self, b: usize, i: usize) -> f64 {
            0.5 * self.rho_c * (self.l[b][i] - self.r[b][i])
        }
    }

    /// Runs the upwind solver of `exact` on cells Δx = L1/n and compares at every step.
    fn compare(exact: &dyn TwoBarImpact, lengths: [f64; 2], velocities: [f64; 2], n: usize) {
        let (c, area) = (exact.wave_speed(), exact.area());
        let dx = lengths[0] / n as f64;
        let dt = dx / c;
        let cells = [n, (lengths[1] / dx).round() as usize];
        let masses = exact.masses();
        let rho = masses[0] / (area * lengths[0]);
        let gap = exact.contact_start() * (velocities[0] - velocities[1]);
        let mut up = Upwind::new(cells, velocities, rho * c, dt, gap);
        let steps = (4.0 * lengths[1] / c / dt) as usize;
        let mut compared = 0;
        for step in 0..steps {
            let t = step as f64 * dt;
            for b in 0..2 {
                let (mut p, mut e) = (0.0, 0.0);
                for i in 0..cells[b] {
                    let d = if b == 0 {
                        (cells[0] - i) as f64 - 0.5
                    } else {
                        i as f64 + 0.5
                    } * dx;
                    let f = exact.field(b, d, t);
                    let (v, s) = (up.velocity(b, i), up.stress(b, i));
                    assert!((v - f.u_t).abs() < 1e-12, "u_t bar {b} cell {i} t {t}");
                    assert!((s - f.stress).abs() < 1e-11, "σ bar {b} cell {i} t {t}");
                    p += rho * area * dx * v;
                    e += 0.5 * area * dx * (rho * v * v + s * s / (rho * c * c));
                }
                let vc = exact.centre_velocities(t)[b];
                assert!((p / masses[b] - vc).abs() < 1e-12, "v_cm bar {b} t {t}");
                assert!((e - exact.energies(t)[b]).abs() < 1e-12, "E bar {b} t {t}");
            }
            let stress = up.step();
            let force = exact.contact_force(t + 0.5 * dt);
            assert!((-area * stress - force).abs() < 1e-12, "force at t {t}");
            compared += 1;
        }
        // 4 L2/c: past the release, the target's far-end reflection and its return
        assert!(compared >= 4 * n);
    }

    fn striker(l2: f64) -> StrikerTarget {
        StrikerTarget {
            striker_length: 1.0,
            target_length: l2,
            density: 4.0,
            young: 9.0,
            area: 0.25,
            speed: 0.1,
            // onset after 3 cells of Δt = (1/20)/1.5 at the relative speed 0.1
            gap: 0.1 * 3.0 / 30.0,
        }
    }

    #[test]
    fn striker_matches_the_characteristic_solver_step_by_step() {
        for l2 in [1.0, 2.0, 2.5] {
            compare(&striker(l2), [1.0, l2], [0.1, 0.0], 20);
        }
    }

    #[test]
    fn head_on_matches_the_characteristic_solver_step_by_step() {
        let h = HeadOnBars {
            length: 1.0,
            density: 4.0,
            young: 9.0,
            area: 0.25,
            speed: 0.1,
            gap: 0.2 * 3.0 / 30.0,
        };
        compare(&h, [1.0, 1.0], [0.1, -0.1], 20);
    }

    #[test]
    fn end_loaded_bar_is_free_at_its_far_end_and_carries_the_load_at_its_near_end() {
        let b = EndLoadedBar {
            length: 2.0,
            wave_speed: 1.5,
            density: 4.0,
            amplitude: 0.05,
            width: 1.2,
        };
        for i in 0..400 {
            let s = 0.013 + i as f64 * 0.0317;
            assert_eq!(b.state(b.length, s).stress, 0.0, "σ(ℓ, {s})");
            let cs = b.wave_speed * s;
            let load = if cs < b.width { b.amplitude } else { 0.0 };
            let near = b.state(1e-9, s).stress;
            if (cs - b.width).abs() > 1e-6 && (cs % (2.0 * b.length)) > 1e-6 {
                assert!(
                    (near + b.density * b.wave_speed * load).abs() < 1e-12,
                    "σ(0⁺, {s}) = {near}"
                );
            }
        }
    }

    #[test]
    fn momentum_and_energy_of_the_fields_match_the_closed_forms() {
        let st = striker(2.0);
        let n = 20_000;
        for t in [0.0, 0.2, 0.5, 0.9, 1.3, 1.6, 2.2, 3.1] {
            let mut total_p = 0.0;
            for (b, len) in [(0, st.striker_length), (1, st.target_length)] {
                let dx = len / n as f64;
                let (mut p, mut e) = (0.0, 0.0);
                for i in 0..n {
                    let f = st.field(b, (i as f64 + 0.5) * dx, t);
                    p += st.density * st.area * f.u_t * dx;
                    e += 0.5
                        * st.area
                        * dx
                        * (st.density * f.u_t.powi(2) + f.stress.powi(2) / st.young);
                }
                assert!((p / st.masses()[b] - st.centre_velocities(t)[b]).abs() < 1e-4 * st.speed);
                assert!(
                    (e - st.energies(t)[b]).abs() < 1e-4 * st.energy(),
                    "E bar {b} t {t}"
                );
                total_p += p;
            }
            let p0 = st.density * st.area * st.striker_length * st.speed;
            assert!((total_p - p0).abs() < 1e-4 * p0, "P at {t}");
        }
        // after the release: the striker at rest, the target with the momentum ρ A L1 v
        let t = st.contact_end() + 0.1;
        assert_eq!(st.centre_velocities(t), st.final_velocities());
        assert!(
            (st.masses()[1] * st.final_velocities()[1] - st.density * st.area * st.speed).abs()
                < 1e-15
        );
        let e = st.energies(t);
        assert!(e[0].abs() < 1e-15 && (e[1] - st.energy()).abs() < 1e-15);
    }

    #[test]
    fn equal_lengths_are_the_head_on_pair_in_the_centre_of_mass_frame() {
        let st = striker(1.0);
        let h = HeadOnBars {
            length: 1.0,
            density: st.density,
            young: st.young,
            area: st.area,
            speed: 0.5 * st.speed,
            gap: st.gap,
        };
        assert!((st.contact_start() - h.contact_start()).abs() < 1e-15);
        assert!((st.contact_end() - h.contact_end()).abs() < 1e-15);
        assert!((st.contact_stress() - h.contact_stress()).abs() < 1e-15);
        assert_eq!(st.final_velocities(), [0.0, st.speed]);
        for i in 0..200 {
            let t = i as f64 * 0.0123;
            let (a, b) = (st.centre_velocities(t), h.centre_velocities(t));
            for k in 0..2 {
                assert!((a[k] - 0.5 * st.speed - b[k]).abs() < 1e-15, "t {t}");
                let d = (i % 17) as f64 / 17.0 + 0.01;
                let (fa, fb) = (st.field(k, d, t), h.field(k, d, t));
                assert!((fa.u_t - 0.5 * st.speed - fb.u_t).abs() < 1e-15);
                assert!((fa.stress - fb.stress).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn head_on_is_the_wall_impact_of_each_bar() {
        let h = HeadOnBars {
            length: 2.0,
            density: 4.0,
            young: 9.0,
            area: 0.5,
            speed: 0.3,
            gap: 0.12,
        };
        let w = h.wall();
        assert!((h.contact_start() - 0.2).abs() < 1e-15);
        assert!((h.contact_end() - h.contact_start() - 2.0 * 2.0 / 1.5).abs() < 1e-14);
        assert!((h.contact_force(1.0) - 0.5 * 4.0 * 1.5 * 0.3).abs() < 1e-15);
        let (after, before) = (h.centre_velocities(10.0), h.centre_velocities(0.0));
        assert!((after[0] + 0.3).abs() < 1e-15 && (after[1] - 0.3).abs() < 1e-15);
        assert!((before[0] - 0.3).abs() < 1e-15 && (before[1] + 0.3).abs() < 1e-15);
        // the impulse of the force is each bar's momentum change 2 m v
        let impulse = h.contact_force(1.0) * (h.contact_end() - h.contact_start());
        assert!((impulse - 2.0 * w.mass() * h.speed).abs() < 1e-14);
        assert!((h.energy() - 2.0 * w.energy()).abs() < 1e-15);
    }
}
