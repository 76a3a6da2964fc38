//! Problem P of Fernández & Sofonea (2004) in two dimensions: a Kelvin–Voigt body Ω ⊂ R² with
//!
//!   σ = A ε(u̇) + B ε(u),  Div σ + f0 = 0,  u = 0 (or u·e_i = 0) on Γ1,  σν = f2 on Γ2,
//!   −σ_ν = p_ν(u̇_ν) − g_ν,  σ_τ = g_τ on Γ3,  u(0) = u0          ((2.1)–(2.6)),
//!
//! where g is an optional boundary source on Γ3 (zero in the paper; manufactured solutions use it).
//! Variational form: (A ε(u̇), ε(v)) + (B ε(u), ε(v)) + ∫_Γ3 p_ν(u̇_ν) v_ν = (f0, v) + ∫_Γ2 f2·v
//! + ∫_Γ3 g·v for all v vanishing on Γ1.

use std::fmt;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::contact::normal_law::{FoundationLaw, NormalLaw};
use crate::error::{require_positive, InputError};
use crate::field::{Expression, Field};
use crate::material::plane_law::{IsotropicLinear, PlaneLaw};
use crate::mesh::triangle::{Diagonal, RectangleSide, TriangleMesh};

/// A closure deciding whether a boundary point (an edge midpoint) belongs to a boundary part.
pub type BoundaryPredicate = Arc<dyn Fn([f64; 2]) -> bool + Send + Sync>;

/// Which boundary edges a part covers.
#[derive(Clone)]
pub enum BoundarySelector {
    /// Edges tagged with one of these rectangle sides.
    Sides(Vec<RectangleSide>),
    /// Edges whose midpoint satisfies the predicate.
    Predicate(BoundaryPredicate),
    /// The edges of a named boundary group of a mesh file: sorted indices into
    /// `mesh.boundary()`.
    Edges {
        group: String,
        edges: Arc<Vec<usize>>,
    },
}

impl fmt::Debug for BoundarySelector {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BoundarySelector::Sides(s) => write!(f, "Sides({s:?})"),
            BoundarySelector::Predicate(_) => write!(f, "Predicate(..)"),
            BoundarySelector::Edges { group, edges } => {
                write!(f, "Edges({group:?}, {} edges)", edges.len())
            }
        }
    }
}

impl BoundarySelector {
    /// One side.
    pub fn side(side: RectangleSide) -> Self {
        BoundarySelector::Sides(vec![side])
    }

    /// Whether edge `e` of `mesh` belongs to the part.
    pub fn contains(&self, mesh: &TriangleMesh, e: usize) -> bool {
        let edge = &mesh.boundary()[e];
        match self {
            BoundarySelector::Sides(sides) => edge.side.is_some_and(|s| sides.contains(&s)),
            BoundarySelector::Predicate(p) => {
                let (a, b) = (mesh.nodes()[edge.nodes[0]], mesh.nodes()[edge.nodes[1]]);
                p([0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])])
            }
            BoundarySelector::Edges { edges, .. } => edges.binary_search(&e).is_ok(),
        }
    }
}

/// The displacement components a Γ1 part holds at zero.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Support {
    /// u = 0 (clamped).
    Clamped,
    /// u_x = 0 only (rollers on a vertical wall).
    FixX,
    /// u_y = 0 only (rollers on a horizontal wall).
    FixY,
}

impl Support {
    /// Whether component c (0 = x, 1 = y) is fixed.
    pub fn fixes(self, c: usize) -> bool {
        match self {
            Support::Clamped => true,
            Support::FixX => c == 0,
            Support::FixY => c == 1,
        }
    }
}

/// A Γ1 part.
#[derive(Debug, Clone)]
pub struct DirichletPart {
    pub boundary: BoundarySelector,
    pub support: Support,
}

/// A Γ2 part with its traction f2(x, y, t).
#[derive(Debug, Clone)]
pub struct TractionPart {
    pub boundary: BoundarySelector,
    pub traction: [Field; 2],
}

/// How the contact integral ∫_Γ3 p_ν(w_ν) v_ν is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactIntegration {
    /// Two Gauss points per edge (the default).
    #[default]
    Gauss2,
    /// At the nodes (lumped), with the nodal normal the length-weighted mean of the adjacent edges'.
    Nodal,
}

/// The Γ3 part: the normal damped response law and an optional boundary source g(x, y, t).
#[derive(Debug, Clone)]
pub struct ContactPart {
    pub boundary: BoundarySelector,
    pub law: Arc<dyn NormalLaw>,
    pub integration: ContactIntegration,
    pub source: Option<[Field; 2]>,
}

/// A region of the body with its own materials (a 2D physical group of a mesh file): its
/// triangles (sorted indices) take A and B from here instead of the problem's defaults.
#[derive(Debug, Clone)]
pub struct MaterialRegion {
    pub name: String,
    pub triangles: Vec<usize>,
    pub viscosity: Arc<dyn PlaneLaw>,
    pub elasticity: Arc<dyn PlaneLaw>,
}

/// The data of the plane problem.
#[derive(Debug, Clone)]
pub struct PlaneProblem {
    pub mesh: TriangleMesh,
    pub final_time: f64,
    /// A (viscosity).
    pub viscosity: Arc<dyn PlaneLaw>,
    /// B (elasticity).
    pub elasticity: Arc<dyn PlaneLaw>,
    /// Regions with their own A and B (disjoint); the triangles of no region take `viscosity`
    /// and `elasticity`. Empty for a one-material body.
    pub regions: Vec<MaterialRegion>,
    pub body_force: [Field; 2],
    pub dirichlet: Vec<DirichletPart>,
    pub traction: Vec<TractionPart>,
    pub contact: Option<ContactPart>,
    pub initial_displacement: [Field; 2],
}

/// Which part each boundary edge belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeRole {
    Free,
    Dirichlet(usize),
    Traction(usize),
    Contact,
}

impl PlaneProblem {
    /// Checks the data and assigns each boundary edge to at most one part.
    pub fn validate(&self) -> Result<Vec<EdgeRole>, InputError> {
        require_positive("final_time", self.final_time)?;
        self.viscosity.validate("viscosity")?;
        self.elasticity.validate("elasticity")?;
        let mut owner: Vec<Option<usize>> = vec![None; self.mesh.triangles().len()];
        for (r, region) in self.regions.iter().enumerate() {
            region
                .viscosity
                .validate(&format!("region[{r}].viscosity"))?;
            region
                .elasticity
                .validate(&format!("region[{r}].elasticity"))?;
            if !region.triangles.windows(2).all(|w| w[0] < w[1]) {
                return Err(InputError::new(
                    format!("region[{r}]"),
                    &region.name,
                    "sorted, distinct triangle indices",
                ));
            }
            for &t in &region.triangles {
                match owner.get_mut(t) {
                    None => {
                        return Err(InputError::new(
                            format!("region[{r}]"),
                            format!("triangle {t}"),
                            format!("triangles below {}", self.mesh.triangles().len()),
                        ))
                    }
                    Some(Some(other)) => {
                        return Err(InputError::new(
                            format!("region[{r}].group"),
                            format!("\"{}\"", region.name),
                            format!(
                                "a region disjoint from region[{other}] (\"{}\"): triangle {t} is in both",
                                self.regions[*other].name
                            ),
                        ))
                    }
                    Some(slot) => *slot = Some(r),
                }
            }
        }
        for (c, f) in self.body_force.iter().enumerate() {
            f.validate(&format!("body_force[{c}]"))?;
        }
        for (c, f) in self.initial_displacement.iter().enumerate() {
            f.validate(&format!("initial_displacement[{c}]"))?;
        }
        let mut roles = vec![EdgeRole::Free; self.mesh.boundary().len()];
        let mut assign = |e: usize, role: EdgeRole, name: &str| -> Result<(), InputError> {
            if roles[e] != EdgeRole::Free {
                let n = self.mesh.boundary()[e].nodes;
                return Err(InputError::new(
                    name,
                    format!("edge {e} (nodes {n:?})"),
                    format!("an edge not already in {:?}", roles[e]),
                ));
            }
            roles[e] = role;
            Ok(())
        };
        for e in 0..self.mesh.boundary().len() {
            for (i, d) in self.dirichlet.iter().enumerate() {
                if d.boundary.contains(&self.mesh, e) {
                    assign(e, EdgeRole::Dirichlet(i), &format!("dirichlet[{i}]"))?;
                }
            }
            for (i, t) in self.traction.iter().enumerate() {
                if t.boundary.contains(&self.mesh, e) {
                    assign(e, EdgeRole::Traction(i), &format!("traction[{i}]"))?;
                }
            }
            if let Some(c) = &self.contact {
                if c.boundary.contains(&self.mesh, e) {
                    assign(e, EdgeRole::Contact, "contact")?;
                }
            }
        }
        for (i, t) in self.traction.iter().enumerate() {
            for (c, f) in t.traction.iter().enumerate() {
                f.validate(&format!("traction[{i}].traction[{c}]"))?;
            }
            if !roles.contains(&EdgeRole::Traction(i)) {
                return Err(InputError::new(
                    format!("traction[{i}]"),
                    "(no edges)",
                    "a boundary part that selects some edges",
                ));
            }
        }
        for (i, _) in self.dirichlet.iter().enumerate() {
            if !roles.contains(&EdgeRole::Dirichlet(i)) {
                return Err(InputError::new(
                    format!("dirichlet[{i}]"),
                    "(no edges)",
                    "a boundary part that selects some edges",
                ));
            }
        }
        if let Some(c) = &self.contact {
            c.law.validate()?;
            if let Some(g) = &c.source {
                for (k, f) in g.iter().enumerate() {
                    f.validate(&format!("contact.source[{k}]"))?;
                }
            }
            if !roles.contains(&EdgeRole::Contact) {
                return Err(InputError::new(
                    "contact",
                    "(no edges)",
                    "a boundary part that selects some edges",
                ));
            }
        }
        Ok(roles)
    }

    /// Whether A and B are linear in every region (the model then factors once and condenses the
    /// contact).
    pub fn is_linear(&self) -> bool {
        self.viscosity.as_linear().is_some()
            && self.elasticity.as_linear().is_some()
            && self
                .regions
                .iter()
                .all(|r| r.viscosity.as_linear().is_some() && r.elasticity.as_linear().is_some())
    }

    /// The region of triangle `e`, if any.
    fn region_of(&self, e: usize) -> Option<&MaterialRegion> {
        self.region_index(e).map(|r| &self.regions[r])
    }

    /// The index in `regions` of the region of triangle `e`, `None` where the defaults apply.
    pub fn region_index(&self, e: usize) -> Option<usize> {
        self.regions
            .iter()
            .position(|r| r.triangles.binary_search(&e).is_ok())
    }

    /// A (viscosity) on triangle `e`.
    pub fn viscosity_of(&self, e: usize) -> &dyn PlaneLaw {
        match self.region_of(e) {
            Some(r) => r.viscosity.as_ref(),
            None => self.viscosity.as_ref(),
        }
    }

    /// B (elasticity) on triangle `e`.
    pub fn elasticity_of(&self, e: usize) -> &dyn PlaneLaw {
        match self.region_of(e) {
            Some(r) => r.elasticity.as_ref(),
            None => self.elasticity.as_ref(),
        }
    }
}

/// What varies between the runs of the paper's Test 2D (Fernández & Sofonea 2004, §4.2;
/// docs/quasistatic.md, "Test 2D"): the square Ω = (0, 6)² of a Kelvin–Voigt material with
///
///   A τ = 2η τ + μ tr(τ) I (η = 20, μ = 30),  B plane stress (E = 100, κ = 0.3),
///
/// held on the lateral sides Γ1 (clamped, or on rollers u_x = 0: the two readings of "the
/// horizontal displacements vanish"), loaded on the top Γ2 by f2 = (0, −10 (6 − x) t), f0 = 0,
/// u0 = 0, T = 1, and resting on the bottom Γ3 on the damped foundation
/// p_ν(r) = β r_+ + p0 (the lubricated law (2.8), p0 = 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Test2dParams {
    /// Squares per side (the mesh is `divisions` × `divisions` squares, each cut along the
    /// rising diagonal).
    pub divisions: usize,
    /// The damper's β of (2.8).
    pub beta: f64,
    /// The reading of Γ1.
    pub support: Support,
    pub integration: ContactIntegration,
}

impl Default for Test2dParams {
    /// The paper's figures: β = 1000, clamped sides, 2-point Gauss on Γ3, 12 × 12 squares.
    fn default() -> Self {
        Self {
            divisions: 12,
            beta: 1000.0,
            support: Support::Clamped,
            integration: ContactIntegration::Gauss2,
        }
    }
}

impl PlaneProblem {
    /// The paper's Test 2D with `p`'s mesh, β, Γ1 reading and contact integration.
    pub fn fernandez_sofonea_test_2d(p: Test2dParams) -> Result<Self, InputError> {
        let problem = PlaneProblem {
            mesh: TriangleMesh::rectangle(
                [0.0, 0.0],
                [6.0, 6.0],
                [p.divisions, p.divisions],
                Diagonal::Up,
            )?,
            final_time: 1.0,
            viscosity: Arc::new(IsotropicLinear::viscosity(30.0, 20.0)),
            elasticity: Arc::new(IsotropicLinear::plane_stress(100.0, 0.3)),
            regions: Vec::new(),
            body_force: [Field::Constant(0.0), Field::Constant(0.0)],
            dirichlet: vec![DirichletPart {
                boundary: BoundarySelector::Sides(vec![RectangleSide::Left, RectangleSide::Right]),
                support: p.support,
            }],
            traction: vec![TractionPart {
                boundary: BoundarySelector::side(RectangleSide::Top),
                traction: [
                    Field::Constant(0.0),
                    Field::Expression(Expression::parse("traction.value[1]", "-10*(6 - x)*t")?),
                ],
            }],
            contact: Some(ContactPart {
                boundary: BoundarySelector::side(RectangleSide::Bottom),
                law: Arc::new(FoundationLaw::Lubricated {
                    beta: p.beta,
                    p0: Field::Constant(2.0),
                }),
                integration: p.integration,
                source: None,
            }),
            initial_displacement: [Field::Constant(0.0), Field::Constant(0.0)],
        };
        problem.validate()?;
        Ok(problem)
    }
}
