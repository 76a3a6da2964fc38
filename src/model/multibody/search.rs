//! Contact search: which master segment a slave node is paired with.
//!
//! The broad phase is an R*-tree (the `rstar` crate) of the master segments' bounding boxes in the
//! current configuration, built in bulk once per step; a slave node queries the boxes that meet
//! the square of half-side `margin` around it. The narrow phase is ours: the closest-point
//! projection onto each candidate segment (EM (13)–(16)),
//!
//!   ξ = a·(x_s − x_1)/|a|²,   g = n·(x_s − x_1),   a = x_2 − x_1,  n = (a_y, −a_x)/|a|,
//!
//! the distance from x_s to the segment (|g| where 0 ≤ ξ ≤ 1, to the nearer end elsewhere), and
//! the pairing with the nearest segment among those the node lies outside of or has penetrated by
//! less than `margin` (ties: the lower segment index — the search is deterministic).

use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, AABB};

/// The narrow phase's result for one slave node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The master segment (its index in the surface).
    pub segment: usize,
    /// ξ of the projection (0 and 1 at the segment's ends).
    pub xi: f64,
    /// The signed gap g (positive outside the master).
    pub gap: f64,
    /// The distance from the node to the segment.
    pub distance: f64,
}

/// The projection of `p` onto the segment x1 → x2.
pub fn project(p: [f64; 2], x1: [f64; 2], x2: [f64; 2], segment: usize) -> Projection {
    let a = [x2[0] - x1[0], x2[1] - x1[1]];
    let b = [p[0] - x1[0], p[1] - x1[1]];
    let aa = a[0] * a[0] + a[1] * a[1];
    let len = aa.sqrt();
    let xi = (a[0] * b[0] + a[1] * b[1]) / aa;
    let gap = (b[0] * a[1] - b[1] * a[0]) / len;
    let distance = if xi < 0.0 {
        (b[0] * b[0] + b[1] * b[1]).sqrt()
    } else if xi > 1.0 {
        ((p[0] - x2[0]).powi(2) + (p[1] - x2[1]).powi(2)).sqrt()
    } else {
        gap.abs()
    };
    Projection {
        segment,
        xi,
        gap,
        distance,
    }
}

type Entry = GeomWithData<Rectangle<[f64; 2]>, usize>;

/// The broad phase over one master surface's segments in one configuration.
#[derive(Debug)]
pub struct SegmentTree {
    tree: RTree<Entry>,
    /// The segments' end positions.
    ends: Vec<[[f64; 2]; 2]>,
}

impl SegmentTree {
    /// The tree of the segments with end positions `ends`.
    pub fn new(ends: Vec<[[f64; 2]; 2]>) -> Self {
        let entries: Vec<Entry> = ends
            .iter()
            .enumerate()
            .map(|(s, e)| {
                let lo = [e[0][0].min(e[1][0]), e[0][1].min(e[1][1])];
                let hi = [e[0][0].max(e[1][0]), e[0][1].max(e[1][1])];
                GeomWithData::new(Rectangle::from_corners(lo, hi), s)
            })
            .collect();
        Self {
            tree: RTree::bulk_load(entries),
            ends,
        }
    }

    /// The end positions of segment `s`.
    pub fn ends(&self, s: usize) -> [[f64; 2]; 2] {
        self.ends[s]
    }

    /// The segment `p` is paired with: the nearest among those within `margin` of it, on whose
    /// outer side it lies or which it has penetrated by less than `margin`; `None` if there is none.
    pub fn closest(&self, p: [f64; 2], margin: f64) -> Option<Projection> {
        let query = AABB::from_corners(
            [p[0] - margin, p[1] - margin],
            [p[0] + margin, p[1] + margin],
        );
        let mut best: Option<Projection> = None;
        for entry in self.tree.locate_in_envelope_intersecting(&query) {
            let s = entry.data;
            let [x1, x2] = self.ends[s];
            let pr = project(p, x1, x2, s);
            if pr.distance > margin || pr.gap < -margin {
                continue;
            }
            let better = match &best {
                None => true,
                Some(b) => {
                    pr.distance < b.distance
                        || (pr.distance == b.distance && pr.segment < b.segment)
                }
            };
            if better {
                best = Some(pr);
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    //! The projection's ξ, gap and distance on a known segment; the tree finds the nearest segment
    //! of a zigzag and nothing beyond the margin, the same as a search over every segment.
    use super::*;

    #[test]
    fn projection_onto_a_segment_walked_right_to_left() {
        // a body below y = 0 walked from x = 1 to x = 0 (body on the left): outward normal +y
        let p = project([0.25, 0.1], [1.0, 0.0], [0.0, 0.0], 7);
        assert!((p.xi - 0.75).abs() < 1e-15);
        assert!((p.gap - 0.1).abs() < 1e-15);
        assert!((p.distance - 0.1).abs() < 1e-15);
        let q = project([-0.3, -0.4], [1.0, 0.0], [0.0, 0.0], 7);
        assert!(q.xi > 1.0);
        assert!((q.distance - 0.5).abs() < 1e-15);
    }

    #[test]
    fn tree_search_equals_the_search_over_every_segment() {
        let n = 40;
        let ends: Vec<[[f64; 2]; 2]> = (0..n)
            .map(|i| {
                let x = |k: usize| [1.0 - k as f64 / n as f64, 0.05 * ((k % 2) as f64)];
                [x(i), x(i + 1)]
            })
            .collect();
        let tree = SegmentTree::new(ends.clone());
        for k in 0..200 {
            let p = [
                -0.1 + 1.2 * (k as f64 * 0.618).fract(),
                -0.05 + 0.3 * (k as f64 * 0.377).fract(),
            ];
            let margin = 0.04;
            let brute = ends
                .iter()
                .enumerate()
                .map(|(s, e)| project(p, e[0], e[1], s))
                .filter(|pr| pr.distance <= margin && pr.gap >= -margin)
                .min_by(|a, b| {
                    a.distance
                        .total_cmp(&b.distance)
                        .then(a.segment.cmp(&b.segment))
                });
            assert_eq!(tree.closest(p, margin), brute, "point {p:?}");
        }
    }
}
