//! Exact 1D benchmarks of dynamic contact (`docs/dynamic.md` §5).
//!
//! **The periodic Signorini bar** ([`PeriodicSignoriniBar`]; the benchmark of GetFEM's 1D dynamic
//! contact demo, also Doyen–Ern–Piperno 2011): x ∈ (0, 1), ρ = E = 1,
//!
//!   u_tt = u_xx,  u(1, t) = 0,
//!   u(0, t) ≥ 0,  σ(0, t) = u_x(0, t) ≤ 0,  u(0, t) σ(0, t) = 0   (Signorini at x = 0),
//!   u(x, 0) = (1 − x)/2,  u_t(x, 0) = 0.
//!
//! The initial data are incompatible at the free end (u_x(0, 0) = −1/2 while the end is free):
//! the solution is piecewise affine in (x, t), continuous, with kinks along the characteristics
//! x = ±t + c. It is 3-periodic. With τ = t mod 3, k = ⌊τ⌋, φ = τ − k and the zones
//! Z1: φ < x, φ ≤ 1 − x;  Z2: φ ≥ x, φ ≤ 1 − x;  Z3: φ < x, φ > 1 − x;  Z4: φ ≥ x, φ > 1 − x,
//!
//! | k | Z1       | Z2        | Z3        | Z4        |
//! |---|----------|-----------|-----------|-----------|
//! | 0 | (1−x)/2  | (1−φ)/2   | (1−x)/2   | (1−φ)/2   |
//! | 1 | −φ/2     | −x/2      | (x−1)/2   | (φ−1)/2   |
//! | 2 | φ/2      | φ/2       | (1−x)/2   | (1−x)/2   |
//!
//! (docs/dynamic.md §5). Derivation (checked by the tests below): on [0, 1] the end is free (u(0) > 0) and
//! d'Alembert with the even extension at x = 0 and the odd one at x = 1 gives the first row; at
//! t = 1 the bar is undeformed with u_t = −1/2 everywhere; on [1, 2] the end is held (odd
//! extensions at both ends), the contact stress is u_x(0, t) = −1/2 < 0; at t = 2 the bar is
//! undeformed with u_t = +1/2, a held end would now pull (u_x(0) = +1/2 > 0), so it is released;
//! on [2, 3] the free end (even extension) brings back u(x, 3) = (1 − x)/2, u_t = 0. Hence
//!
//!   u(0, t) = (1 − t)/2 on [0, 1], 0 on [1, 2], (t − 2)/2 on [2, 3];
//!   σ(0, t) = −1/2 on (1, 2), 0 otherwise;
//!
//! and in every zone |u_t| + |u_x| = 1/2 with one of them zero, so the energy density
//! ½ (u_t² + u_x²) is 1/8 everywhere and E(t) = ½ ∫₀¹ (u_t² + u_x²) dx = 1/8 at all times.
//!
//! **The free bar hitting a rigid wall** ([`BarWallImpact`], docs/dynamic.md §5): a bar (0, L), free at
//! both ends, moving with u_t = −v0 towards a wall at distance g0 ≥ 0 from its left end, wave
//! speed c = √(E/ρ). Contact starts at t0 = g0/v0; a compression wave σ = −ρ c v0 runs to the
//! free end, reflects as an unloading wave and reaches the wall at t0 + 2L/c, when the bar is
//! again undeformed and moves with +v0 everywhere: contact lasts 2L/c, the contact force is
//! A ρ c v0 throughout, and all the energy ½ ρ A L v0² returns as kinetic energy.

/// The period of the periodic Signorini bar.
pub const PERIOD: f64 = 3.0;

/// The energy ½ ∫ (u_t² + u_x²) of the periodic Signorini bar at every time.
pub const ENERGY: f64 = 0.125;

/// u and its first derivatives at one (x, t) (one-sided where a kink passes: the zone rules pick
/// a side, see [`PeriodicSignoriniBar::state`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarState {
    pub u: f64,
    pub u_x: f64,
    pub u_t: f64,
}

/// The periodic Signorini bar of docs/dynamic.md §5 (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PeriodicSignoriniBar;

/// u = a + b x + c φ in each (row k, zone) of the table of docs/dynamic.md §5: [a, b, c].
const AFFINE: [[[f64; 3]; 4]; 3] = [
    // k = 0: (1−x)/2, (1−φ)/2, (1−x)/2, (1−φ)/2
    [
        [0.5, -0.5, 0.0],
        [0.5, 0.0, -0.5],
        [0.5, -0.5, 0.0],
        [0.5, 0.0, -0.5],
    ],
    // k = 1: −φ/2, −x/2, (x−1)/2, (φ−1)/2
    [
        [0.0, 0.0, -0.5],
        [0.0, -0.5, 0.0],
        [-0.5, 0.5, 0.0],
        [-0.5, 0.0, 0.5],
    ],
    // k = 2: φ/2, φ/2, (1−x)/2, (1−x)/2
    [
        [0.0, 0.0, 0.5],
        [0.0, 0.0, 0.5],
        [0.5, -0.5, 0.0],
        [0.5, -0.5, 0.0],
    ],
];

impl PeriodicSignoriniBar {
    /// (k, φ) of t: τ = t mod 3, k = ⌊τ⌋ ∈ {0, 1, 2}, φ = τ − k ∈ [0, 1).
    pub fn phase(t: f64) -> (usize, f64) {
        let tau = t.rem_euclid(PERIOD);
        let k = (tau.floor() as usize).min(2);
        (k, tau - k as f64)
    }

    /// The zone index (0 = Z1 … 3 = Z4) of x at phase φ.
    fn zone(x: f64, phi: f64) -> usize {
        match (phi >= x, phi > 1.0 - x) {
            (false, false) => 0,
            (true, false) => 1,
            (false, true) => 2,
            (true, true) => 3,
        }
    }

    /// u, u_x, u_t at (x, t), x ∈ [0, 1], from the table of docs/dynamic.md §5. On a kink the zone rules of the
    /// spec decide the side; at x = 0 they give the limit x → 0⁺ (zone Z2), so `state(0, t).u_x`
    /// is the contact stress.
    pub fn state(&self, x: f64, t: f64) -> BarState {
        let (k, phi) = Self::phase(t);
        let [a, b, c] = AFFINE[k][Self::zone(x, phi)];
        BarState {
            u: a + b * x + c * phi,
            u_x: b,
            u_t: c,
        }
    }

    /// u(x, t).
    pub fn displacement(&self, x: f64, t: f64) -> f64 {
        self.state(x, t).u
    }

    /// u(0, t) = (1 − τ)/2 on [0, 1], 0 on [1, 2], (τ − 2)/2 on [2, 3] (τ = t mod 3).
    pub fn contact_displacement(&self, t: f64) -> f64 {
        self.state(0.0, t).u
    }

    /// σ(0, t) = u_x(0⁺, t): −1/2 while the end is held (τ ∈ [1, 2)), 0 otherwise.
    pub fn contact_stress(&self, t: f64) -> f64 {
        self.state(0.0, t).u_x
    }

    /// The contact impulse ∫₀ᵗ −σ(0, s) ds (the momentum the obstacle gives the bar): 1/2 per
    /// period, gained at rate 1/2 on [1, 2] mod 3.
    pub fn contact_impulse(&self, t: f64) -> f64 {
        let periods = (t / PERIOD).floor();
        let tau = t - periods * PERIOD;
        0.5 * periods + 0.5 * (tau - 1.0).clamp(0.0, 1.0)
    }

    /// The points of (0, 1) where u(·, t), u_x and u_t may jump in slope or value: x = φ and
    /// x = 1 − φ (sorted; both in [0, 1]).
    pub fn kinks(&self, t: f64) -> [f64; 2] {
        let (_, phi) = Self::phase(t);
        let (a, b) = (phi, 1.0 - phi);
        [a.min(b), a.max(b)]
    }

    /// The energy ½ ∫₀¹ (u_t² + u_x²) dx: 1/8 at every time (module docs).
    pub fn energy(&self) -> f64 {
        ENERGY
    }
}

/// Pieces of [a, b] between the kinks of the exact solution at time t, for exact integration of
/// piecewise polynomials: calls `f(x_left, x_right)` for each piece.
fn pieces(a: f64, b: f64, kinks: &[f64], mut f: impl FnMut(f64, f64)) {
    let mut left = a;
    for &c in kinks {
        if c > left && c < b {
            f(left, c);
            left = c;
        }
    }
    f(left, b);
}

/// ∫ of the square of an affine function over a piece of length `len` with end values e0, e1.
fn affine_square(len: f64, e0: f64, e1: f64) -> f64 {
    len * (e0 * e0 + e0 * e1 + e1 * e1) / 3.0
}

/// The errors of a P1 field against the periodic Signorini bar at time t, integrated exactly
/// (the elements are split at the kinks x = φ, 1 − φ, where every integrand is polynomial).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FieldErrors {
    /// ‖u_h − u(t)‖_L².
    pub displacement_l2: f64,
    /// ‖u_h,x − u_x(t)‖_L².
    pub strain_l2: f64,
    /// ‖v_h − u_t(t)‖_L² (v_h the scheme's nodal velocity, P1).
    pub velocity_l2: f64,
}

impl FieldErrors {
    /// (‖e_t‖² + ‖e_x‖²)^½: the energy-norm error (ρ = E = 1).
    pub fn energy_norm(&self) -> f64 {
        self.velocity_l2.hypot(self.strain_l2)
    }
}

impl PeriodicSignoriniBar {
    /// The exact errors of the P1 fields with nodal values `u` and `v` on the mesh `nodes` (of
    /// (0, 1)) at time t.
    pub fn field_errors(&self, nodes: &[f64], u: &[f64], v: &[f64], t: f64) -> FieldErrors {
        let kinks = self.kinks(t);
        let (mut eu, mut ex, mut ev) = (0.0, 0.0, 0.0);
        for e in 0..nodes.len().saturating_sub(1) {
            let (a, b) = (nodes[e], nodes[e + 1]);
            let h = b - a;
            let slope_u = (u[e + 1] - u[e]) / h;
            let slope_v = (v[e + 1] - v[e]) / h;
            pieces(a, b, &kinks, |x0, x1| {
                let len = x1 - x0;
                let mid = self.state(0.5 * (x0 + x1), t);
                let uh = |x: f64| u[e] + slope_u * (x - a);
                let vh = |x: f64| v[e] + slope_v * (x - a);
                // u is continuous: its end values on the piece are the exact ones; u_t and u_x
                // are constant on the piece (the value at its midpoint)
                eu += affine_square(
                    len,
                    uh(x0) - self.displacement(x0, t),
                    uh(x1) - self.displacement(x1, t),
                );
                ex += len * (slope_u - mid.u_x).powi(2);
                ev += affine_square(len, vh(x0) - mid.u_t, vh(x1) - mid.u_t);
            });
        }
        FieldErrors {
            displacement_l2: eu.sqrt(),
            strain_l2: ex.sqrt(),
            velocity_l2: ev.sqrt(),
        }
    }
}

/// The free bar hitting a rigid wall (docs/dynamic.md §5; module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarWallImpact {
    pub length: f64,
    pub density: f64,
    pub young: f64,
    pub area: f64,
    /// The approach speed v0 > 0 (the bar moves with −v0).
    pub speed: f64,
    /// The initial gap g0 ≥ 0 between the left end and the wall.
    pub gap: f64,
}

impl BarWallImpact {
    /// c = √(E/ρ).
    pub fn wave_speed(&self) -> f64 {
        (self.young / self.density).sqrt()
    }

    /// t0 = g0/v0.
    pub fn contact_start(&self) -> f64 {
        self.gap / self.speed
    }

    /// 2L/c.
    pub fn contact_duration(&self) -> f64 {
        2.0 * self.length / self.wave_speed()
    }

    /// The contact stress magnitude ρ c v0 (compressive).
    pub fn contact_stress(&self) -> f64 {
        self.density * self.wave_speed() * self.speed
    }

    /// The contact force A ρ c v0 while in contact, 0 otherwise.
    pub fn contact_force(&self, t: f64) -> f64 {
        let t0 = self.contact_start();
        if t > t0 && t < t0 + self.contact_duration() {
            self.area * self.contact_stress()
        } else {
            0.0
        }
    }

    /// The mass ρ A L.
    pub fn mass(&self) -> f64 {
        self.density * self.area * self.length
    }

    /// The velocity of the centre of mass: −v0 before contact, +v0 after, linear in between
    /// (the force is constant): −v0 + (A ρ c v0 / (ρ A L)) (t − t0).
    pub fn centre_velocity(&self, t: f64) -> f64 {
        let s = (t - self.contact_start()).clamp(0.0, self.contact_duration());
        -self.speed + self.area * self.contact_stress() * s / self.mass()
    }

    /// The energy ½ ρ A L v0² (all kinetic before and after contact).
    pub fn energy(&self) -> f64 {
        0.5 * self.mass() * self.speed * self.speed
    }

    /// The rebound velocity +v0.
    pub fn rebound_velocity(&self) -> f64 {
        self.speed
    }
}

#[cfg(test)]
mod tests {
    //! The periodic Signorini bar against the problem it claims to solve: the wave equation in
    //! the weak sense (the characteristic-parallelogram rule u(x, t+s) + u(x, t−s) = u(x+s, t) +
    //! u(x−s, t), which every weak solution of u_tt = u_xx satisfies, across kinks too), u_x and
    //! u_t against finite differences, u(1, t) = 0, the Signorini conditions at x = 0, the initial
    //! data, the energy 1/8 by quadrature at several times, periodicity and the closed
    //! forms of u(0, t) and σ(0, t). Then the exact error integration and the wall impact.
    use super::*;

    const BAR: PeriodicSignoriniBar = PeriodicSignoriniBar;

    /// A deterministic sequence in [0, 1) (golden-ratio rotation).
    fn samples(n: usize, seed: f64) -> impl Iterator<Item = f64> {
        (0..n).map(move |i| (seed + i as f64 * 0.618_033_988_749_894_9).fract())
    }

    #[test]
    fn parallelogram_rule_of_the_wave_equation_holds_everywhere_inside() {
        let mut checked = 0;
        for (i, x) in samples(400, 0.1).enumerate() {
            let t = 9.0 * (0.37 + i as f64 * 0.414_213_562_373).fract();
            let s = 0.5 * (0.23 + i as f64 * 0.732_050_807_568_877).fract();
            if x - s <= 0.0 || x + s >= 1.0 {
                continue;
            }
            let lhs = BAR.displacement(x, t + s) + BAR.displacement(x, t - s);
            let rhs = BAR.displacement(x + s, t) + BAR.displacement(x - s, t);
            assert!(
                (lhs - rhs).abs() < 1e-14,
                "x {x} t {t} s {s}: {lhs} vs {rhs}"
            );
            checked += 1;
        }
        assert!(checked > 100);
    }

    #[test]
    fn derivatives_match_finite_differences_away_from_kinks() {
        let d = 1e-6;
        for (i, x) in samples(300, 0.3).enumerate() {
            let t = 9.0 * (0.11 + i as f64 * 0.414_213_562_373).fract();
            let (_, phi) = PeriodicSignoriniBar::phase(t);
            let near = |a: f64, b: f64| (a - b).abs() < 10.0 * d;
            if near(x, phi) || near(x, 1.0 - phi) || near(phi, 0.0) || near(phi, 1.0) {
                continue;
            }
            if !(10.0 * d..1.0 - 10.0 * d).contains(&x) {
                continue;
            }
            let s = BAR.state(x, t);
            let ux = (BAR.displacement(x + d, t) - BAR.displacement(x - d, t)) / (2.0 * d);
            let ut = (BAR.displacement(x, t + d) - BAR.displacement(x, t - d)) / (2.0 * d);
            assert!((ux - s.u_x).abs() < 1e-8, "u_x at ({x}, {t})");
            assert!((ut - s.u_t).abs() < 1e-8, "u_t at ({x}, {t})");
        }
    }

    #[test]
    fn solution_is_continuous_across_the_kinks() {
        for t in samples(200, 0.7).map(|s| 9.0 * s) {
            for c in BAR.kinks(t) {
                for x in [c - 1e-12, c + 1e-12] {
                    if (0.0..=1.0).contains(&x) {
                        assert!((BAR.displacement(x, t) - BAR.displacement(c, t)).abs() < 1e-11);
                    }
                }
            }
            // and in time across the phase switches
            for k in 0..9 {
                let tk = k as f64;
                let x = (t / 9.0).fract();
                let jump = BAR.displacement(x, tk - 1e-12) - BAR.displacement(x, tk + 1e-12);
                assert!(jump.abs() < 1e-11, "jump at t = {tk}, x = {x}");
            }
        }
    }

    #[test]
    fn right_end_is_held_and_left_end_satisfies_signorini() {
        for t in samples(500, 0.05).map(|s| 12.0 * s) {
            assert_eq!(BAR.displacement(1.0, t), 0.0, "u(1, {t})");
            let u0 = BAR.contact_displacement(t);
            let sigma = BAR.contact_stress(t);
            assert!(u0 >= 0.0, "u(0, {t}) = {u0}");
            assert!(sigma <= 0.0, "σ(0, {t}) = {sigma}");
            assert_eq!(u0 * sigma, 0.0, "complementarity at t = {t}");
            // σ(0) is the limit of u_x from inside
            assert_eq!(sigma, BAR.state(1e-9, t).u_x, "σ(0, {t}) vs u_x(0⁺)");
        }
    }

    #[test]
    fn contact_displacement_and_stress_are_the_spec_closed_forms() {
        for t in samples(500, 0.2).map(|s| 9.0 * s) {
            let tau = t.rem_euclid(3.0);
            let u0 = if tau <= 1.0 {
                (1.0 - tau) / 2.0
            } else if tau <= 2.0 {
                0.0
            } else {
                (tau - 2.0) / 2.0
            };
            let sigma = if (1.0..2.0).contains(&tau) { -0.5 } else { 0.0 };
            assert!((BAR.contact_displacement(t) - u0).abs() < 1e-14, "t = {t}");
            assert_eq!(BAR.contact_stress(t), sigma, "t = {t}");
        }
    }

    #[test]
    fn initial_data_and_periodicity() {
        for x in samples(100, 0.4) {
            let s = BAR.state(x, 0.0);
            assert!((s.u - (1.0 - x) / 2.0).abs() < 1e-15);
            assert_eq!(s.u_t, 0.0);
            for t in [0.3, 1.7, 2.45] {
                for p in 1..4 {
                    let a = BAR.displacement(x, t);
                    let b = BAR.displacement(x, t + PERIOD * p as f64);
                    assert!((a - b).abs() < 1e-12, "periodicity at ({x}, {t})");
                }
            }
        }
    }

    #[test]
    fn energy_is_one_eighth_by_quadrature_at_several_times() {
        // midpoint quadrature on a fine grid (exact up to the few cells cut by a kink)
        let n = 20_000;
        for t in [0.0, 0.3, 0.5, 1.0, 1.25, 1.9, 2.2, 2.75, 4.1, 7.3] {
            let e: f64 = (0..n)
                .map(|i| {
                    let s = BAR.state((i as f64 + 0.5) / n as f64, t);
                    0.5 * (s.u_t * s.u_t + s.u_x * s.u_x) / n as f64
                })
                .sum();
            assert!((e - ENERGY).abs() < 1e-12, "E({t}) = {e}");
        }
    }

    #[test]
    fn contact_impulse_integrates_the_contact_stress() {
        let n = 90_000;
        let dt = 9.0 / n as f64;
        let mut impulse = 0.0;
        for i in 0..n {
            impulse -= BAR.contact_stress((i as f64 + 0.5) * dt) * dt;
            let t = (i + 1) as f64 * dt;
            assert!((impulse - BAR.contact_impulse(t)).abs() <= dt, "t = {t}");
        }
        assert!((BAR.contact_impulse(9.0) - 1.5).abs() < 1e-12);
    }

    #[test]
    fn field_errors_vanish_for_the_interpolant_at_kink_aligned_times_and_match_quadrature() {
        let m = 40;
        let nodes: Vec<f64> = (0..=m).map(|i| i as f64 / m as f64).collect();
        // at t = 0.25 the kinks φ = 0.25, 0.75 are mesh nodes: the interpolant is exact
        let t = 0.25;
        let u: Vec<f64> = nodes.iter().map(|&x| BAR.displacement(x, t)).collect();
        let e = BAR.field_errors(&nodes, &u, &u, t);
        assert!(e.displacement_l2 < 1e-15 && e.strain_l2 < 1e-15);
        // at a generic time the exact integration matches a fine quadrature
        let t = 1.234_567;
        let u: Vec<f64> = nodes
            .iter()
            .map(|&x| BAR.displacement(x, t) + 0.01 * x)
            .collect();
        let v: Vec<f64> = nodes.iter().map(|&x| x * x).collect();
        let e = BAR.field_errors(&nodes, &u, &v, t);
        let n = 400_000;
        let (mut qu, mut qx, mut qv) = (0.0, 0.0, 0.0);
        for i in 0..n {
            let x = (i as f64 + 0.5) / n as f64;
            let el = ((x * m as f64) as usize).min(m - 1);
            let s = (x - nodes[el]) * m as f64;
            let uh = u[el] + s * (u[el + 1] - u[el]);
            let vh = v[el] + s * (v[el + 1] - v[el]);
            let uxh = (u[el + 1] - u[el]) * m as f64;
            let ex = BAR.state(x, t);
            qu += (uh - ex.u).powi(2) / n as f64;
            qx += (uxh - ex.u_x).powi(2) / n as f64;
            qv += (vh - ex.u_t).powi(2) / n as f64;
        }
        assert!((e.displacement_l2 - qu.sqrt()).abs() < 1e-7);
        assert!((e.strain_l2 - qx.sqrt()).abs() < 1e-5);
        assert!((e.velocity_l2 - qv.sqrt()).abs() < 1e-5);
    }

    #[test]
    fn wall_impact_balances_momentum_and_energy() {
        let w = BarWallImpact {
            length: 2.0,
            density: 4.0,
            young: 9.0,
            area: 0.5,
            speed: 0.3,
            gap: 0.06,
        };
        assert!((w.wave_speed() - 1.5).abs() < 1e-15);
        assert!((w.contact_start() - 0.2).abs() < 1e-15);
        assert!((w.contact_duration() - 8.0 / 3.0).abs() < 1e-15);
        // impulse of the contact force = momentum change 2 m v0
        let impulse = w.area * w.contact_stress() * w.contact_duration();
        assert!((impulse - 2.0 * w.mass() * w.speed).abs() < 1e-14);
        assert!((w.centre_velocity(100.0) - w.rebound_velocity()).abs() < 1e-15);
        assert!((w.centre_velocity(0.0) + w.speed).abs() < 1e-15);
        // the contact stress is the characteristic relation σ = ρ c [u_t] with [u_t] = v0
        assert!((w.contact_stress() - w.density * w.wave_speed() * w.speed).abs() < 1e-15);
        assert_eq!(w.contact_force(0.1), 0.0);
        assert_eq!(w.contact_force(1.0), w.area * w.contact_stress());
        assert_eq!(w.contact_force(3.0), 0.0);
    }
}
