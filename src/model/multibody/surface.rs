//! Contact surfaces: the boundary part of a body that carries slave nodes or master segments
//! (EM §3: the slave–master concept), and the rigid foundation as a fixed master line.
//!
//! A master surface is a chain of boundary edges, each walked with its body on the left, so that
//! the outward normal of the segment x_1 → x_2 is n = (a_y, −a_x)/|a|, a = x_2 − x_1, and the gap
//! g = n·(x_s − x_1) is positive outside the master body ([`super::invariants`]). Consecutive
//! segments share a node; a slave node that slides past a segment's end moves to the neighbour
//! there (segment switching), and leaves the master where there is none.

use crate::error::InputError;
use crate::model::dynamic::plane_body::PlaneBody;
use crate::model::quasistatic::plane::BoundarySelector;

/// The selected boundary part of one body.
#[derive(Debug, Clone)]
pub struct ContactSurface {
    /// The body (its index in the body set).
    pub body: usize,
    /// The segments (mesh nodes, the body on the left from `[0]` to `[1]`).
    pub segments: Vec<[usize; 2]>,
    /// The segment before (ending at this one's first node) and after (starting at its second).
    pub previous: Vec<Option<usize>>,
    pub next: Vec<Option<usize>>,
    /// The distinct nodes of the part, in order of first appearance.
    pub nodes: Vec<usize>,
    /// Each node's tributary length: half the reference lengths of its segments.
    pub weights: Vec<f64>,
}

impl ContactSurface {
    /// The part of `body`'s boundary that `selector` selects; `field` names the selector in
    /// errors. At least one edge must be selected.
    pub fn new(
        index: usize,
        body: &PlaneBody,
        selector: &BoundarySelector,
        field: &str,
    ) -> Result<Self, InputError> {
        let mesh = &body.data().mesh;
        let segments: Vec<[usize; 2]> = mesh
            .boundary()
            .iter()
            .enumerate()
            .filter(|(e, _)| selector.contains(mesh, *e))
            .map(|(_, edge)| edge.nodes)
            .collect();
        if segments.is_empty() {
            return Err(InputError::new(
                field,
                "(no boundary edge selected)",
                "a boundary part with at least one edge",
            ));
        }
        let nn = mesh.nodes().len();
        let mut starting = vec![None; nn];
        let mut ending = vec![None; nn];
        for (s, seg) in segments.iter().enumerate() {
            starting[seg[0]] = Some(s);
            ending[seg[1]] = Some(s);
        }
        let previous = segments.iter().map(|seg| ending[seg[0]]).collect();
        let next = segments.iter().map(|seg| starting[seg[1]]).collect();
        let mut weight = vec![0.0; nn];
        let mut nodes = Vec::new();
        for seg in &segments {
            let (a, b) = (mesh.nodes()[seg[0]], mesh.nodes()[seg[1]]);
            let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            for &n in seg {
                if weight[n] == 0.0 {
                    nodes.push(n);
                }
                weight[n] += 0.5 * len;
            }
        }
        let weights = nodes.iter().map(|&n| weight[n]).collect();
        Ok(Self {
            body: index,
            segments,
            previous,
            next,
            nodes,
            weights,
        })
    }

    /// The longest segment in the reference configuration.
    pub fn longest_segment(&self, body: &PlaneBody) -> f64 {
        let x = body.data().mesh.nodes();
        self.segments
            .iter()
            .map(|s| ((x[s[1]][0] - x[s[0]][0]).powi(2) + (x[s[1]][1] - x[s[0]][1]).powi(2)).sqrt())
            .fold(0.0, f64::max)
    }
}

/// The rigid foundation {x·n ≤ level}, n the unit normal pointing into the bodies' side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Foundation {
    pub normal: [f64; 2],
    pub level: f64,
}

impl Foundation {
    /// The half-plane {y ≤ level}.
    pub fn horizontal(level: f64) -> Self {
        Self {
            normal: [0.0, 1.0],
            level,
        }
    }

    /// Two fixed points x_1, x_2 of its boundary line, one unit apart, walked with the foundation
    /// on the left (a = x_2 − x_1 = (−n_y, n_x), so that (a_y, −a_x) = n): the master segment of
    /// the invariant formulation, for which g = n·x_s − level and ξ = a·(x_s − x_1) are linear in
    /// x_s (their discrete gradients are their gradients).
    pub fn segment(&self) -> [[f64; 2]; 2] {
        let [nx, ny] = self.normal;
        let p = [nx * self.level, ny * self.level];
        // the direction a with outward normal (a_y, −a_x) = n: a = (−n_y, n_x)
        [p, [p[0] - ny, p[1] + nx]]
    }
}
