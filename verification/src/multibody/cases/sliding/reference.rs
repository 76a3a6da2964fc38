//! The exact references of `multibody_sliding`, written here (the solver computes none of them).
//!
//! **Grazing impact** ([`GrazingImpact`]). A free bar of length L (along the normal y) and
//! section A = W moves at (v_t, −v_n) onto the rigid half-plane {y ≤ 0}, its face parallel to
//! the wall, g0 = v_n t0 away. Frictionless flat contact transmits only the normal traction, so
//! the problem splits: u = (v_t t, 0) + (0, w(y, t)) with w the bar-on-wall solution
//! ([`BarWallImpact`]: contact on (t0, t0 + 2L/c) under the stress ρ c v_n, the centre's normal
//! velocity −v_n → +v_n linearly). Every particle's x-velocity is v_t at every time (P_x is
//! conserved: no x-force acts at all), and the exit angle equals the incidence angle. The
//! normal part is linear in v_n and independent of v_t.
//!
//! **Sliding off the end** ([`SlideKinematics`]). With no load, no friction and the slave face
//! exactly on the master face (g = 0, no normal relative velocity), the rigid translations
//! u_b = v_b t are the solution: no stress, no contact force. A slave node at X then lies beyond
//! the master's free end x_e by X + (v_s − v_m) t − x_e; the solver releases it once that exceeds
//! the release tolerance r h (r = 0.5: half the end segment h) (contactlab's `RELEASE_TOLERANCE`), at the
//! first step t_n = n k at which it does.

use contactlab::model::multibody::step::RELEASE_TOLERANCE;

use crate::exact::signorini_bar::BarWallImpact;

/// The bar sliding along the wall while it bounces (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrazingImpact {
    /// The normal problem (speed v_n, gap g0 = v_n t0).
    pub wall: BarWallImpact,
    /// v_t.
    pub tangential: f64,
}

impl GrazingImpact {
    /// The bar of length L, section A, density ρ, modulus E at (v_t, −v_n), first contact at t0.
    pub fn new(
        length: f64,
        area: f64,
        density: f64,
        young: f64,
        tangential: f64,
        normal: f64,
        onset: f64,
    ) -> Self {
        Self {
            wall: BarWallImpact {
                length,
                density,
                young,
                area,
                speed: normal,
                gap: normal * onset,
            },
            tangential,
        }
    }

    /// The centre-of-mass velocity (v_t, −v_n + A ρ c v_n (t − t0)⁺/m clamped at +v_n).
    pub fn centre_velocity(&self, t: f64) -> [f64; 2] {
        [self.tangential, self.wall.centre_velocity(t)]
    }

    /// Every particle's x-velocity: v_t at every time.
    pub fn particle_x_velocity(&self, _t: f64) -> f64 {
        self.tangential
    }

    /// The contact interval (t0, t0 + 2L/c).
    pub fn contact(&self) -> (f64, f64) {
        let t0 = self.wall.contact_start();
        (t0, t0 + self.wall.contact_duration())
    }

    /// The total contact force A ρ c v_n on the contact interval (normal: no x component).
    pub fn normal_force(&self, t: f64) -> f64 {
        self.wall.contact_force(t)
    }

    /// The energy ½ m (v_t² + v_n²) (all kinetic before and after the contact).
    pub fn energy(&self) -> f64 {
        0.5 * self.wall.mass() * (self.tangential.powi(2) + self.wall.speed.powi(2))
    }

    /// The angle of the velocity with the wall, atan(v_n/v_t), before and after the contact.
    pub fn angle(&self) -> f64 {
        self.wall.speed.atan2(self.tangential)
    }
}

/// The rigid slide of slave nodes past the master's free end (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct SlideKinematics {
    /// The slave contact nodes' reference x.
    pub nodes: Vec<f64>,
    /// x_e: the master's free end the slave moves towards.
    pub end: f64,
    /// h: the length of the master's end segment.
    pub segment: f64,
    /// v_s − v_m > 0 along x.
    pub speed: f64,
}

impl SlideKinematics {
    /// How far node `i` lies beyond the end at t, in units of the end segment.
    pub fn beyond(&self, i: usize, t: f64) -> f64 {
        (self.nodes[i] + self.speed * t - self.end) / self.segment
    }

    /// The first step n ≥ 1 (t_n = n k ≤ T = steps · k) at which node `i` lies beyond the end by
    /// more than the release tolerance: the step that releases it (None: it never leaves).
    pub fn release_step(&self, i: usize, k: f64, steps: usize) -> Option<usize> {
        (1..=steps).find(|&n| self.beyond(i, n as f64 * k) > RELEASE_TOLERANCE)
    }

    /// The number of slave nodes released by T = steps · k.
    pub fn released(&self, k: f64, steps: usize) -> usize {
        (0..self.nodes.len())
            .filter(|&i| self.release_step(i, k, steps).is_some())
            .count()
    }

    /// The smallest distance, in segments, of any node at any step from the release threshold:
    /// how clear the kinematic count is of a tie (a tie would leave the release to round-off).
    pub fn clearance(&self, k: f64, steps: usize) -> f64 {
        let mut least = f64::INFINITY;
        for i in 0..self.nodes.len() {
            for n in 0..=steps {
                least = least.min((self.beyond(i, n as f64 * k) - RELEASE_TOLERANCE).abs());
            }
        }
        least
    }
}

#[cfg(test)]
mod tests {
    //! The grazing impact: x-velocity v_t always, the normal rebound +v_n after 2L/c, the impulse
    //! 2 m v_n equal to force × duration, energy and angle equal before and after, the onset
    //! independent of the angle. The slide: release steps and counts by hand.
    use super::*;

    fn bar(vt: f64, vn: f64) -> GrazingImpact {
        GrazingImpact::new(1.0, 0.25, 4.0, 9.0, vt, vn, 0.1)
    }

    #[test]
    fn grazing_bar_keeps_its_tangential_velocity_and_reflects_its_normal_one() {
        let g = bar(0.1, 1e-3);
        let (t0, t1) = g.contact();
        assert!((t0 - 0.1).abs() < 1e-15);
        assert!((t1 - t0 - 2.0 / 1.5).abs() < 1e-14);
        assert_eq!(g.centre_velocity(0.0), [0.1, -1e-3]);
        let after = g.centre_velocity(t1 + 0.1);
        assert_eq!(after[0], 0.1);
        assert!((after[1] - 1e-3).abs() < 1e-17);
        for t in [0.0, 0.5 * (t0 + t1), 2.0 * t1] {
            assert_eq!(g.particle_x_velocity(t), 0.1);
        }
        // the impulse of the normal force is the change of the normal momentum 2 m v_n
        let impulse = g.normal_force(0.5 * (t0 + t1)) * (t1 - t0);
        assert!((impulse - 2.0 * g.wall.mass() * 1e-3).abs() < 1e-15);
        let e_after = 0.5 * g.wall.mass() * (after[0].powi(2) + after[1].powi(2));
        assert!((e_after - g.energy()).abs() < 1e-15 * g.energy());
        assert!((after[1].atan2(after[0]) - g.angle()).abs() < 1e-12);
    }

    #[test]
    fn grazing_onset_and_duration_are_the_same_at_every_angle() {
        for vn in [1e-1, 1e-2, 1e-3, 1e-4] {
            let g = bar(0.1, vn);
            let (t0, t1) = g.contact();
            assert!((t0 - 0.1).abs() < 1e-15, "{vn}");
            assert!((t1 - t0 - 2.0 / 1.5).abs() < 1e-14, "{vn}");
            assert!((g.normal_force(0.5) - 0.25 * 4.0 * 1.5 * vn).abs() < 1e-15);
        }
    }

    #[test]
    fn slide_releases_each_node_at_the_first_step_beyond_the_tolerance() {
        // nodes at 0, 0.27, 0.52 moving at 1 towards the end 0.6 of a segment 0.1: the threshold
        // is 0.6 + r 0.1 (r = RELEASE_TOLERANCE = 0.5: 0.65); node 0.52 passes it at t = 0.13,
        // node 0.27 at 0.38, node 0 at 0.65
        assert_eq!(
            RELEASE_TOLERANCE, 0.5,
            "the hand count below assumes r = 0.5"
        );
        let s = SlideKinematics {
            nodes: vec![0.0, 0.27, 0.52],
            end: 0.6,
            segment: 0.1,
            speed: 1.0,
        };
        assert_eq!(s.release_step(2, 0.05, 10), Some(3));
        assert_eq!(s.release_step(1, 0.05, 10), Some(8));
        assert_eq!(s.release_step(0, 0.05, 10), None);
        assert_eq!(s.released(0.05, 10), 2);
        assert_eq!(s.released(0.05, 14), 3);
        assert!((s.beyond(2, 0.2) - 1.2).abs() < 1e-12);
        // the closest approach to the threshold over steps 1..10: node 0.52 at t = 0.15 and node
        // 0.27 at t = 0.4 are 0.2 segments past it
        assert!((s.clearance(0.05, 10) - 0.2).abs() < 1e-9);
    }
}
