//! The foundation and Γ3 written HERE: the half-space {y ≤ level} of a dynamic scene's
//! `[contact]`, the boundary edges its `sides`, `where` (an edge whose midpoint makes the
//! expression positive) or none (every boundary edge) select, the nodal weights
//! w_i = Σ ½ |e| over the selected edges e at node i, and the penetration
//! p_i = level − (y_i + u_{y,i}) of node i from the displacement alone.
//!
//! A node whose y component is held (Dirichlet) cannot move: the solver leaves it out of its
//! contact nodes, and so does this audit. A `group` of a Gmsh file is not read here (a scene
//! selecting Γ3 by group is refused by the auditor, not guessed).

use contactlab::field::Expression;
use contactlab::mesh::triangle::{RectangleSide, TriangleMesh};
use contactlab::model::dynamic::plane_body::PlaneBody;
use contactlab::scene::dynamic::DynamicContactSection;

/// Which boundary edges form Γ3.
#[derive(Clone)]
pub enum Gamma3 {
    /// Every boundary edge.
    All,
    /// The edges of these sides of a rectangle.
    Sides(Vec<RectangleSide>),
    /// The edges whose midpoint makes the expression positive.
    Where(Expression),
}

impl std::fmt::Debug for Gamma3 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::All => write!(f, "All"),
            Self::Sides(s) => write!(f, "Sides({s:?})"),
            Self::Where(_) => write!(f, "Where(..)"),
        }
    }
}

impl Gamma3 {
    /// Γ3 of a scene's `[contact]`.
    pub fn of(c: &DynamicContactSection) -> Result<Self, String> {
        if c.group.is_some() {
            return Err("Γ3 selected by a Gmsh group (not read by the state audit)".into());
        }
        match (&c.where_, c.sides.is_empty()) {
            (Some(text), _) => Ok(Self::Where(
                Expression::parse("contact.where", text).map_err(|e| e.to_string())?,
            )),
            (None, false) => Ok(Self::Sides(c.sides.clone())),
            (None, true) => Ok(Self::All),
        }
    }

    fn contains(&self, mesh: &TriangleMesh, e: usize) -> bool {
        let edge = &mesh.boundary()[e];
        match self {
            Self::All => true,
            Self::Sides(sides) => edge.side.is_some_and(|s| sides.contains(&s)),
            Self::Where(expr) => {
                let (a, b) = (mesh.nodes()[edge.nodes[0]], mesh.nodes()[edge.nodes[1]]);
                expr.eval(0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.0) > 0.0
            }
        }
    }
}

/// A node of Γ3 as the audit sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gamma3Node {
    pub node: usize,
    pub weight: f64,
    /// Reference height y_i, and the free dofs of u_y and u_x (x: `None` where held).
    pub y: f64,
    pub y_dof: usize,
    pub x_dof: Option<usize>,
}

/// The nodes of Γ3 with free y components, in the order of first appearance over the boundary
/// edges, with their weights.
pub fn gamma3_nodes(body: &PlaneBody, gamma3: &Gamma3) -> Vec<Gamma3Node> {
    let mesh = &body.data().mesh;
    let mut weight = vec![0.0; mesh.nodes().len()];
    let mut order = Vec::new();
    for (e, edge) in mesh.boundary().iter().enumerate() {
        if !gamma3.contains(mesh, e) {
            continue;
        }
        let (a, b) = (mesh.nodes()[edge.nodes[0]], mesh.nodes()[edge.nodes[1]]);
        let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        for &n in &edge.nodes {
            if weight[n] == 0.0 {
                order.push(n);
            }
            weight[n] += 0.5 * len;
        }
    }
    order
        .into_iter()
        .filter_map(|n| {
            Some(Gamma3Node {
                node: n,
                weight: weight[n],
                y: mesh.nodes()[n][1],
                y_dof: body.dof(n, 1)?,
                x_dof: body.dof(n, 0),
            })
        })
        .collect()
}

/// p = level − (y + u_y) and the size |level| + |y| + |u_y| of its operands (p rounds by a few
/// ε times it).
pub fn penetration(level: f64, node: &Gamma3Node, u: &[f64]) -> (f64, f64) {
    let uy = u[node.y_dof];
    (level - (node.y + uy), level.abs() + node.y.abs() + uy.abs())
}
