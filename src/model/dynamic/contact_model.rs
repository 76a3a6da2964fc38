//! Contact with a rigid foundation: the contact nodes of a body, the normal treatment and the
//! friction law.
//!
//! Contact is nodal (lumped): node i of Γ3 carries the weight w_i (half the lengths of its Γ3
//! edges in 2D, 1 at a bar's end), its penetration p_i = o_i + s_i u_{ν,i} (o_i the initial
//! penetration, s_i = ±1 the orientation of its normal dof) and, in 2D, its tangential dof. The
//! normal force on the body is w_i N_i along the foundation's outward normal, the friction force
//! w_i T_i along the tangent (BDS §2: nodal quantities).
//!
//! Normal treatments (BDS = Barboteu–Danan–Sofonea, HLT = Hauret–Le Tallec):
//!
//! | treatment                | N_i                                                          | source |
//! |--------------------------|--------------------------------------------------------------|--------|
//! | `penalty`                | r (p_n)_+                                                    | BDS (1.8) at t_n |
//! | `energy_consistent`      | r [(p_n)_+² − (p_{n−1})_+²] / (2 (p_n − p_{n−1})), exact tangent | BDS (1.46) = HLT (3.68) |
//! | `hauret_le_tallec_tilted`| force tilted along the increment to restore the work        | HLT (3.69) |
//! | `limited_penetration`    | stage (a): energy-consistent; stage (b) where p^(a) ≥ g: Signorini at depth g plus the compliance L g | BDS (1.44)–(1.45) |
//! | `signorini`              | p ≤ 0, N ≥ 0, N p = 0 (exact, semismooth Newton / active set) | BDS (1.18) with g = 0 |

use serde::{Deserialize, Serialize};

use crate::contact::friction::FrictionCoefficient;
use crate::error::{require_finite, require_positive, InputError};
use crate::model::dynamic::bar::BarBody;
use crate::model::dynamic::plane_body::PlaneBody;
use crate::model::quasistatic::plane::BoundarySelector;

/// One contact node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactNode {
    /// The mesh node.
    pub node: usize,
    /// Its free normal dof.
    pub normal_dof: usize,
    /// Its free tangential dof (2D).
    pub tangent_dof: Option<usize>,
    /// s_i: p = offset + s_i u_{ν}.
    pub sign: f64,
    /// The penetration at u = 0.
    pub offset: f64,
    /// The quadrature weight w_i.
    pub weight: f64,
}

/// The normal contact treatment.
///
/// Against a rigid plane wall the Hauret–Le Tallec force (3.68) is the energy-consistent force
/// (1.46): Δg_{n+1/2} = −ν, so only the intensity Λ_{n+1/2} = r [(p_n)_+² − (p_{n−1})_+²] /
/// (2 (p_n − p_{n−1})) remains (HLT §3.6.1). HLT Remark 3.14 leaves the correction terms out of
/// the Newton tangent to keep it symmetric in the two-body case; here the correction's derivative
/// is a scalar per node, so the exact derivative is used (symmetric, and Newton converges
/// quadratically; with the Remark 3.14 tangent r/2 H(p_{n−1/2}) Newton stalled at contact onset on
/// the 1D periodic bar, residual 5e−4 after 60 iterations).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum NormalTreatment {
    Penalty { stiffness: f64 },
    EnergyConsistent { stiffness: f64 },
    HauretLeTallecTilted { stiffness: f64 },
    LimitedPenetration { stiffness: f64, depth: f64 },
    Signorini,
}

impl NormalTreatment {
    /// The treatment's name as written in scenes.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Penalty { .. } => "penalty",
            Self::EnergyConsistent { .. } => "energy_consistent",
            Self::HauretLeTallecTilted { .. } => "hauret_le_tallec_tilted",
            Self::LimitedPenetration { .. } => "limited_penetration",
            Self::Signorini => "signorini",
        }
    }

    /// The penalty stiffness r (none for Signorini).
    pub fn stiffness(&self) -> Option<f64> {
        match *self {
            Self::Penalty { stiffness }
            | Self::EnergyConsistent { stiffness }
            | Self::HauretLeTallecTilted { stiffness }
            | Self::LimitedPenetration { stiffness, .. } => Some(stiffness),
            Self::Signorini => None,
        }
    }

    /// Whether the discrete work of the compliance force is exact (BDS Prop. 1.3, HLT Prop. 3.7).
    pub fn is_energy_consistent(&self) -> bool {
        matches!(
            self,
            Self::EnergyConsistent { .. }
                | Self::HauretLeTallecTilted { .. }
                | Self::LimitedPenetration { .. }
        )
    }

    /// The penalty energy (r/2)(p)_+² stored at penetration p (0 for Signorini).
    pub fn penalty_energy(&self, p: f64) -> f64 {
        match self.stiffness() {
            Some(r) => crate::contact::compliance::penalty_energy(r, p),
            None => 0.0,
        }
    }

    /// Checks r > 0 and g > 0; errors name `field.stiffness` / `field.depth`.
    pub fn validate(&self, field: &str) -> Result<(), InputError> {
        if let Some(r) = self.stiffness() {
            require_positive(&format!("{field}.stiffness"), r)?;
        }
        if let Self::LimitedPenetration { depth, .. } = self {
            require_positive(&format!("{field}.depth"), *depth)?;
        }
        Ok(())
    }
}

/// Which end of a bar meets the wall.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BarEnd {
    /// The end x = 0.
    Left,
    /// The end x = L.
    Right,
}

/// The foundation, its contact nodes, the normal treatment and the friction law.
#[derive(Debug, Clone)]
pub struct ContactModel {
    pub nodes: Vec<ContactNode>,
    pub treatment: NormalTreatment,
    /// None (or μ0 = 0): frictionless, no friction code runs.
    pub friction: Option<FrictionCoefficient>,
    /// The foundation's outward unit normal (into the body's side).
    pub normal: [f64; 2],
}

impl ContactModel {
    /// A wall at x = `wall` against one end of a bar: p = wall − (0 + u_0) at the left end,
    /// p = (L + u_L) − wall at the right end.
    pub fn bar_wall(
        body: &BarBody,
        end: BarEnd,
        wall: f64,
        treatment: NormalTreatment,
    ) -> Result<Self, InputError> {
        require_finite("contact.wall", wall)?;
        treatment.validate("contact.treatment")?;
        let nodes = body.data().mesh.nodes();
        let (node, sign, offset, normal) = match end {
            BarEnd::Left => (0, -1.0, wall - nodes[0], [1.0, 0.0]),
            BarEnd::Right => (
                nodes.len() - 1,
                1.0,
                nodes[nodes.len() - 1] - wall,
                [-1.0, 0.0],
            ),
        };
        let Some(normal_dof) = body.node_dof(node) else {
            return Err(InputError::new(
                "contact.end",
                format!("{end:?}"),
                "an end that is not held by a support",
            ));
        };
        Ok(Self {
            nodes: vec![ContactNode {
                node,
                normal_dof,
                tangent_dof: None,
                sign,
                offset,
                weight: body.data().area,
            }],
            treatment,
            friction: None,
            normal,
        })
    }

    /// The foundation {x2 ≤ level} under the boundary part `boundary` of a plane body:
    /// p = level − (y + u_y), tangent along x.
    pub fn plane_half_space(
        body: &PlaneBody,
        boundary: &BoundarySelector,
        level: f64,
        treatment: NormalTreatment,
        friction: Option<FrictionCoefficient>,
    ) -> Result<Self, InputError> {
        require_finite("contact.level", level)?;
        treatment.validate("contact.treatment")?;
        if let Some(f) = &friction {
            f.validate("contact.friction")?;
        }
        let mesh = &body.data().mesh;
        let mut weight = vec![0.0; mesh.nodes().len()];
        let mut order = Vec::new();
        for (e, edge) in mesh.boundary().iter().enumerate() {
            if !boundary.contains(mesh, e) {
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
        if order.is_empty() {
            return Err(InputError::new(
                "contact.boundary",
                "(no boundary edge selected)",
                "a boundary part with at least one edge",
            ));
        }
        let friction = friction.filter(|f| !f.is_zero());
        let nodes = order
            .into_iter()
            .filter_map(|n| {
                let normal_dof = body.dof(n, 1)?;
                Some(ContactNode {
                    node: n,
                    normal_dof,
                    tangent_dof: if friction.is_some()
                        || matches!(treatment, NormalTreatment::HauretLeTallecTilted { .. })
                    {
                        body.dof(n, 0)
                    } else {
                        None
                    },
                    sign: -1.0,
                    offset: level - mesh.nodes()[n][1],
                    weight: weight[n],
                })
            })
            .collect();
        Ok(Self {
            nodes,
            treatment,
            friction,
            normal: [0.0, 1.0],
        })
    }

    /// The unknowns that active constraints may prescribe, or that carry contact forces.
    pub fn dofs(&self) -> Vec<usize> {
        let mut v: Vec<usize> = self
            .nodes
            .iter()
            .flat_map(|n| std::iter::once(n.normal_dof).chain(n.tangent_dof))
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }
}
