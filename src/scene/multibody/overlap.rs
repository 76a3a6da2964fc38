//! The bodies' overlap at t = 0: a slave node of a `[[contact_pair]]` that lies inside the master
//! body (or below the foundation), or a master-part node that lies inside the slave body, by more
//! than the round-off of the geometry. A contact constraint g ≥ 0 that starts violated is not a
//! contact the scheme can model — the multipliers push the node out within the first step and
//! the energy that does so comes from nowhere (overlapping head-on bars ended at 33 E₀) — so a
//! scene whose bodies overlap is refused with the pair, the node and the depth, unless the pair
//! asks for a resolved start (`initial_overlap = "resolve"`): each penetrating slave node is then
//! moved to its closest point on the master's boundary (the foundation's line) as an initial
//! displacement, which the run starts from with the stored energy that displacement carries.
//!
//! **Detection.** A node x is in the master body when it lies in the closure of one of its
//! triangles (the signed distances of x to the three edge lines all ≥ −tol); its depth is then
//! the negative gap of NTS, d = min −g over the master part's segments that x projects onto with
//! g < 0 (the closest-point projection of `model::multibody::search`; a corner node of the slave
//! lies on the master's side lines, so the distance to the whole boundary would miss it), or,
//! where there is none, its distance to the nearest segment of the part. Against the foundation {y ≤ level}, d = level − y. The node overlaps when d > tol, with
//!
//!   tol = 1e-12 · h + 8 ε X,
//!
//! h the longest segment of the pair's two parts and X the largest coordinate magnitude of the
//! pair's nodes: 1e-12 h is far below any physical overlap and far above the round-off of an
//! exactly touching start (a gap computed from coordinates of size X carries a few ε X), so bodies
//! that touch (g = 0, written in decimal) are accepted.

use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, AABB};

use crate::error::{Error, InputError};
use crate::model::multibody::bodies::BodySet;
use crate::model::multibody::search::project;
use crate::model::multibody::solver::{ContactPair, PairMaster};
use crate::model::multibody::surface::ContactSurface;
use crate::scene::multibody::format::InitialOverlap;
use crate::scene::multibody::pairs::PairOrigin;

/// One overlapping node at t = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overlap {
    /// The solver pair.
    pub pair: usize,
    /// Whether the node is a master-part node inside the slave body (else a slave node inside the
    /// master body or below the foundation).
    pub reverse: bool,
    /// The node (of the slave body, or of the master body when `reverse`) and its position.
    pub node: usize,
    pub position: [f64; 2],
    /// d > tol: the distance from the node to the boundary of the body it is in.
    pub depth: f64,
    /// The closest point of that boundary (where a resolved start puts a slave node).
    pub closest: [f64; 2],
    pub tolerance: f64,
}

/// A triangle's bounding box with its corners.
type TriangleEntry = GeomWithData<Rectangle<[f64; 2]>, [[f64; 2]; 3]>;

/// A body's triangles in the configuration u, as an R*-tree of their boxes, and the segments of
/// the boundary part facing the other body.
struct BodyGeometry {
    tree: RTree<TriangleEntry>,
    segments: Vec<[[f64; 2]; 2]>,
}

impl BodyGeometry {
    fn new(bodies: &BodySet, part: &ContactSurface, u: &[f64]) -> Self {
        let b = part.body;
        let mesh = &bodies.body(b).data().mesh;
        let x = |n: usize| bodies.position(b, n, u);
        let entries = mesh
            .triangles()
            .iter()
            .map(|t| {
                let p = [x(t[0]), x(t[1]), x(t[2])];
                let lo = [
                    p[0][0].min(p[1][0]).min(p[2][0]),
                    p[0][1].min(p[1][1]).min(p[2][1]),
                ];
                let hi = [
                    p[0][0].max(p[1][0]).max(p[2][0]),
                    p[0][1].max(p[1][1]).max(p[2][1]),
                ];
                GeomWithData::new(Rectangle::from_corners(lo, hi), p)
            })
            .collect();
        let segments = part.segments.iter().map(|s| [x(s[0]), x(s[1])]).collect();
        Self {
            tree: RTree::bulk_load(entries),
            segments,
        }
    }

    /// Whether p lies in the closure of a triangle, each edge line's signed distance ≥ −tol.
    fn contains(&self, p: [f64; 2], tol: f64) -> bool {
        let query = AABB::from_corners([p[0] - tol, p[1] - tol], [p[0] + tol, p[1] + tol]);
        self.tree
            .locate_in_envelope_intersecting(&query)
            .any(|e| in_triangle(p, &e.data, tol))
    }

    /// The depth of p (in the body) under the part: the smallest −g over the segments it projects
    /// onto (ξ ∈ [0, 1] up to tol) with g < 0, else its distance to the nearest segment; and the
    /// point of that segment where a resolved start puts it.
    fn depth(&self, p: [f64; 2], tol: f64) -> (f64, [f64; 2]) {
        let mut under: Option<(f64, [f64; 2])> = None;
        let mut nearest = (f64::INFINITY, p);
        for (s, [x1, x2]) in self.segments.iter().enumerate() {
            let pr = project(p, *x1, *x2, s);
            let len = ((x2[0] - x1[0]).powi(2) + (x2[1] - x1[1]).powi(2)).sqrt();
            let slack = tol / len.max(f64::MIN_POSITIVE);
            let xi = pr.xi.clamp(0.0, 1.0);
            let foot = [x1[0] + xi * (x2[0] - x1[0]), x1[1] + xi * (x2[1] - x1[1])];
            if pr.gap < 0.0
                && pr.xi >= -slack
                && pr.xi <= 1.0 + slack
                && under.is_none_or(|(d, _)| -pr.gap < d)
            {
                under = Some((-pr.gap, foot));
            }
            if pr.distance < nearest.0 {
                nearest = (pr.distance, foot);
            }
        }
        under.unwrap_or(nearest)
    }
}

/// p in the closure of the triangle t (either orientation) up to tol.
fn in_triangle(p: [f64; 2], t: &[[f64; 2]; 3], tol: f64) -> bool {
    let area2 =
        (t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[1][1] - t[0][1]) * (t[2][0] - t[0][0]);
    let sign = if area2 >= 0.0 { 1.0 } else { -1.0 };
    (0..3).all(|i| {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        let e = [b[0] - a[0], b[1] - a[1]];
        let len = (e[0] * e[0] + e[1] * e[1]).sqrt();
        let cross = e[0] * (p[1] - a[1]) - e[1] * (p[0] - a[0]);
        len == 0.0 || sign * cross / len >= -tol
    })
}

/// tol = 1e-12 · h + 8 ε X of a pair (module docs).
fn tolerance(bodies: &BodySet, pair: &ContactPair, u: &[f64]) -> f64 {
    let mut h = pair.slave.longest_segment(bodies.body(pair.slave.body));
    let mut size = 0.0f64;
    let mut grow = |b: usize, nodes: &[usize]| {
        for &n in nodes {
            let x = bodies.position(b, n, u);
            size = size.max(x[0].abs()).max(x[1].abs());
        }
    };
    grow(pair.slave.body, &pair.slave.nodes);
    match &pair.master {
        PairMaster::Surface(m) => {
            h = h.max(m.longest_segment(bodies.body(m.body)));
            grow(m.body, &m.nodes);
        }
        PairMaster::Foundation(f) => size = size.max(f.level.abs()),
    }
    1e-12 * h + 8.0 * f64::EPSILON * size
}

/// Every node that overlaps at u (module docs), pair by pair.
pub fn overlaps(bodies: &BodySet, pairs: &[ContactPair], u: &[f64]) -> Vec<Overlap> {
    let mut out = Vec::new();
    for (p, pair) in pairs.iter().enumerate() {
        let tol = tolerance(bodies, pair, u);
        let sb = pair.slave.body;
        match &pair.master {
            PairMaster::Foundation(f) => {
                for &n in &pair.slave.nodes {
                    let x = bodies.position(sb, n, u);
                    let depth = f.level - (f.normal[0] * x[0] + f.normal[1] * x[1]);
                    if depth > tol {
                        out.push(Overlap {
                            pair: p,
                            reverse: false,
                            node: n,
                            position: x,
                            depth,
                            closest: [x[0] + depth * f.normal[0], x[1] + depth * f.normal[1]],
                            tolerance: tol,
                        });
                    }
                }
            }
            PairMaster::Surface(m) => {
                for (inside, nodes, reverse) in [(m, &pair.slave, false), (&pair.slave, m, true)] {
                    let geometry = BodyGeometry::new(bodies, inside, u);
                    for &n in &nodes.nodes {
                        let x = bodies.position(nodes.body, n, u);
                        if !geometry.contains(x, tol) {
                            continue;
                        }
                        let (depth, closest) = geometry.depth(x, tol);
                        if depth > tol {
                            out.push(Overlap {
                                pair: p,
                                reverse,
                                node: n,
                                position: x,
                                depth,
                                closest,
                                tolerance: tol,
                            });
                        }
                    }
                }
            }
        }
    }
    out
}

/// The bodies of solver pair `p` as the user named them: (slave, master or the foundation).
fn pair_names(pair: &ContactPair, names: &[String]) -> (String, String) {
    let slave = format!("\"{}\"", names[pair.slave.body]);
    let master = match &pair.master {
        PairMaster::Surface(m) => format!("\"{}\"", names[m.body]),
        PairMaster::Foundation(f) => format!("the foundation y ≤ {}", f.level),
    };
    (slave, master)
}

/// The error for the deepest overlap of the first pair that has one.
fn overlap_error(
    found: &[Overlap],
    pairs: &[ContactPair],
    origins: &[PairOrigin],
    names: &[String],
    after_resolve: bool,
) -> Option<InputError> {
    let first = found.first()?;
    let deepest = found
        .iter()
        .filter(|o| o.pair == first.pair)
        .fold(*first, |a, o| if o.depth > a.depth { *o } else { a });
    let count = found.iter().filter(|o| o.pair == first.pair).count();
    let pair = &pairs[deepest.pair];
    let origin = origins[deepest.pair];
    let (mut slave, mut master) = pair_names(pair, names);
    if origin.exchanged {
        // the second pass: the section's master is this pair's slave
        std::mem::swap(&mut slave, &mut master);
    }
    let (node_body, inside) = match (deepest.reverse, origin.exchanged) {
        (false, false) | (true, true) => (slave.clone(), master.clone()),
        (true, false) | (false, true) => (master.clone(), slave.clone()),
    };
    let [x, y] = deepest.position;
    let value = format!(
        "(at t = 0, {count} node(s) of {slave} and {master} overlap: the deepest, node {} of \
         {node_body} at ({x}, {y}), lies {:e} inside {inside}{})",
        deepest.node,
        deepest.depth,
        if after_resolve {
            " after the resolved start moved the slave nodes"
        } else {
            ""
        }
    );
    let expected = if after_resolve {
        format!(
            "bodies that a resolved start separates (it moves only the slave nodes onto the \
             master; here a node is still {:e} deep, more than the round-off tolerance {:e} = \
             1e-12 × the longest segment + 8 ε × the largest coordinate): move the bodies apart",
            deepest.depth, deepest.tolerance
        )
    } else {
        format!(
            "bodies that do not overlap at t = 0 (a depth above the round-off tolerance {:e} = \
             1e-12 × the longest segment + 8 ε × the largest coordinate is an overlap; touching, \
             g = 0, is accepted): move the bodies apart (the keys that place them: each body's \
             origin, center or offset and its size; the pair's slave and master sides or group; \
             a foundation's level), or write initial_overlap = \"resolve\" in the section to \
             start with the slave nodes moved onto the master",
            deepest.tolerance
        )
    };
    Some(InputError::new(
        format!("contact_pair[{}]", origin.section),
        value,
        expected,
    ))
}

/// The initial displacement of a scene: zero, or where the pairs with `initial_overlap =
/// "resolve"` have slave nodes inside their master, those nodes moved to the closest boundary
/// point; then no pair may overlap (else the typed error of [`overlap_error`]).
pub(super) fn initial_displacement(
    bodies: &BodySet,
    pairs: &[ContactPair],
    origins: &[PairOrigin],
    names: &[String],
    modes: &[InitialOverlap],
) -> Result<Vec<f64>, Error> {
    let mut u = vec![0.0; bodies.dofs()];
    let found = overlaps(bodies, pairs, &u);
    if found.is_empty() {
        return Ok(u);
    }
    let resolving = |o: &Overlap| modes[origins[o.pair].section] == InitialOverlap::Resolve;
    if let Some(e) = overlap_error(
        &found
            .iter()
            .copied()
            .filter(|o| !resolving(o))
            .collect::<Vec<_>>(),
        pairs,
        origins,
        names,
        false,
    ) {
        return Err(e.into());
    }
    for o in found.iter().filter(|o| !o.reverse) {
        let b = pairs[o.pair].slave.body;
        let x0 = bodies.reference(b, o.node);
        for c in 0..2 {
            let shift = o.closest[c] - x0[c];
            match bodies.dof(b, o.node, c) {
                Some(d) => u[d] = shift,
                None if (o.closest[c] - o.position[c]).abs() > o.tolerance => {
                    return Err(InputError::new(
                        format!("contact_pair[{}].initial_overlap", origins[o.pair].section),
                        "\"resolve\"",
                        format!(
                            "\"error\" here: node {} of \"{}\" overlaps by {:e} but its component \
                             {c} is held by a support, so a resolved start cannot move it",
                            o.node, names[b], o.depth
                        ),
                    )
                    .into());
                }
                None => {}
            }
        }
    }
    for b in 0..bodies.len() {
        if !bodies.body(b).admissible(&u[bodies.range(b)]) {
            let section = found
                .iter()
                .find(|o| !o.reverse && pairs[o.pair].slave.body == b)
                .map_or(0, |o| origins[o.pair].section);
            return Err(InputError::new(
                format!("contact_pair[{section}].initial_overlap"),
                "\"resolve\"",
                format!(
                    "an overlap shallower than the elements of \"{}\": moving its slave nodes \
                     onto the master inverts an element (det F ≤ 0); move the bodies apart",
                    names[b]
                ),
            )
            .into());
        }
    }
    let left = overlaps(bodies, pairs, &u);
    match overlap_error(&left, pairs, origins, names, true) {
        Some(e) => Err(e.into()),
        None => Ok(u),
    }
}
