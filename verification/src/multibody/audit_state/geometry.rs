//! Node-to-segment geometry written HERE (docs/multibody.md §2 and "The audit recomputed from
//! the state"): a slave point x_s against a master segment x_1 → x_2 walked with its body on the
//! left, a = x_2 − x_1, b = x_s − x_1,
//!
//!   g = (b_x a_y − b_y a_x)/|a|   (the signed distance from the segment's line, positive outside),
//!   ξ = a·b/|a|²                   (the closest point x_1 + ξ a on the line),
//!
//! and the rigid foundation {x·n ≤ level} as the segment from p = level n to p + (−n_y, n_x)
//! (outward normal n, unit length).

use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::solver::{ContactPair, PairMaster};

/// The current position X + u of a body's mesh node (held components read u = 0).
pub fn position(bodies: &BodySet, body: usize, node: usize, u: &[f64]) -> [f64; 2] {
    let x = bodies.body(body).data().mesh.nodes()[node];
    [0, 1].map(|c| x[c] + bodies.dof(body, node, c).map_or(0.0, |d| u[d]))
}

/// The slave point and the master segment's two points of a candidate at displacement u;
/// `None` when the segment index is not one of the master's.
pub fn local_points(
    bodies: &BodySet,
    pair: &ContactPair,
    slave: usize,
    segment: Option<usize>,
    u: &[f64],
) -> Option<[[f64; 2]; 3]> {
    let xs = position(bodies, pair.slave.body, slave, u);
    match (&pair.master, segment) {
        (PairMaster::Surface(m), Some(s)) => {
            let [n1, n2] = *m.segments.get(s)?;
            Some([
                xs,
                position(bodies, m.body, n1, u),
                position(bodies, m.body, n2, u),
            ])
        }
        (PairMaster::Foundation(f), None) => {
            let [nx, ny] = f.normal;
            let p = [nx * f.level, ny * f.level];
            Some([xs, p, [p[0] - ny, p[1] + nx]])
        }
        _ => None,
    }
}

/// (g, ξ, |a|) of the three points (module docs).
pub fn gap_xi_length(x: &[[f64; 2]; 3]) -> (f64, f64, f64) {
    let a = [x[2][0] - x[1][0], x[2][1] - x[1][1]];
    let b = [x[0][0] - x[1][0], x[0][1] - x[1][1]];
    let aa = a[0] * a[0] + a[1] * a[1];
    let len = aa.sqrt();
    (
        (b[0] * a[1] - b[1] * a[0]) / len,
        (a[0] * b[0] + a[1] * b[1]) / aa,
        len,
    )
}

/// The largest coordinate of the three points: a gap computed from them rounds by a few ε times it.
pub fn size(x: &[[f64; 2]; 3]) -> f64 {
    x.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gap_is_the_signed_distance_outside_a_segment_walked_with_its_body_on_the_left() {
        // segment from (1, 0) to (0, 0): the body on its left is below (y < 0), outside is y > 0
        let (g, xi, len) = gap_xi_length(&[[0.25, 0.5], [1.0, 0.0], [0.0, 0.0]]);
        assert_eq!((g, xi, len), (0.5, 0.75, 1.0));
        let (g, _, _) = gap_xi_length(&[[0.25, -0.125], [1.0, 0.0], [0.0, 0.0]]);
        assert_eq!(g, -0.125);
    }
}
