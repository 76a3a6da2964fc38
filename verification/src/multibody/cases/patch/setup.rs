//! The two blocks of the patch test as a multibody problem, and their static solve.
//!
//! Body 0 is the lower block A (bottom on rollers u_y = 0, left side u_x = 0), body 1 the upper
//! block B (left side u_x = 0, the pressure p on its top); both are P1 rectangles (squares cut
//! along the rising diagonal). The contact surfaces are A's top and B's bottom. Single-pass puts
//! one block's nodes as slaves on the other's segments; two-pass adds the pair with the roles
//! exchanged. Frictionless, Lagrange multipliers, the static equilibrium of
//! [`MultibodySolver::solve_static`].

use serde::Serialize;

use contactlab::field::Field;
use contactlab::mesh::triangle::RectangleSide;
use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::constraint::{Enforcement, PairLaw};
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{
    ContactPair, MultibodyParams, MultibodyProblem, MultibodySolver, PairMaster, StaticSolution,
};
use contactlab::model::multibody::surface::ContactSurface;
use contactlab::model::quasistatic::plane::{
    BoundarySelector, DirichletPart, Support, TractionPart,
};

use crate::exact::contact_patch::{Block, ContactPatch, Hooke};
use crate::multibody::study::{rectangle_body, LawName, MaterialSpec};

/// How the interface is enforced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Passes {
    /// One pair: the slave block's nodes on the other block's segments.
    Single { slave: Block },
    /// Both pairs (A's nodes on B, B's nodes on A).
    Two,
}

impl Passes {
    /// A short label.
    pub fn label(self) -> &'static str {
        match self {
            Passes::Single {
                slave: Block::Upper,
            } => "single-pass, B slave",
            Passes::Single {
                slave: Block::Lower,
            } => "single-pass, A slave",
            Passes::Two => "two-pass",
        }
    }
}

/// One discretization of the patch test: the exact problem and each block's cells (n_x, n_y).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PatchMesh {
    pub lower: [usize; 2],
    pub upper: [usize; 2],
}

impl PatchMesh {
    /// The interface ratio "n_A:n_B".
    pub fn ratio(&self) -> String {
        format!("{}:{}", self.lower[0], self.upper[0])
    }

    /// The smallest cell side of both blocks.
    pub fn h_min(&self, p: &ContactPatch) -> f64 {
        let l = p.length;
        (l / self.lower[0] as f64)
            .min(p.lower_height / self.lower[1] as f64)
            .min(l / self.upper[0] as f64)
            .min(p.upper_height / self.upper[1] as f64)
    }

    /// Every cell count multiplied by `m`.
    pub fn refined(&self, m: usize) -> Self {
        Self {
            lower: [self.lower[0] * m, self.lower[1] * m],
            upper: [self.upper[0] * m, self.upper[1] * m],
        }
    }
}

/// A solved patch test: the solver (its problem holds the bodies), the surfaces and the static
/// solution.
pub struct PatchRun {
    pub passes: Passes,
    pub mesh: PatchMesh,
    pub solver: MultibodySolver,
    /// A's top and B's bottom.
    pub lower_top: ContactSurface,
    pub upper_bottom: ContactSurface,
    pub solution: StaticSolution,
}

impl PatchRun {
    /// The surface of `block`.
    pub fn surface(&self, block: Block) -> &ContactSurface {
        match block {
            Block::Lower => &self.lower_top,
            Block::Upper => &self.upper_bottom,
        }
    }
}

fn linear(m: Hooke) -> MaterialSpec {
    MaterialSpec {
        law: LawName::Linear,
        young: m.young,
        poisson: m.poisson,
    }
}

/// Builds and solves the patch test `patch` on `mesh` with `passes`.
pub fn solve(
    patch: &ContactPatch,
    mesh: PatchMesh,
    passes: Passes,
    params: &MultibodyParams,
) -> Result<PatchRun, String> {
    let side = BoundarySelector::side;
    let lower = rectangle_body(
        [0.0, 0.0],
        [patch.length, patch.lower_height],
        mesh.lower,
        1.0,
        &linear(patch.lower),
        vec![
            DirichletPart {
                boundary: side(RectangleSide::Bottom),
                support: Support::FixY,
            },
            DirichletPart {
                boundary: side(RectangleSide::Left),
                support: Support::FixX,
            },
        ],
        vec![],
        [0.0, 0.0],
    )?;
    let upper = rectangle_body(
        [0.0, patch.lower_height],
        [patch.length, patch.upper_height],
        mesh.upper,
        1.0,
        &linear(patch.upper),
        vec![DirichletPart {
            boundary: side(RectangleSide::Left),
            support: Support::FixX,
        }],
        vec![TractionPart {
            boundary: side(RectangleSide::Top),
            traction: [Field::Constant(0.0), Field::Constant(-patch.pressure)],
        }],
        [0.0, 0.0],
    )?;
    let bodies = BodySet::new(vec![lower, upper]).map_err(|e| e.to_string())?;
    let lower_top = ContactSurface::new(0, bodies.body(0), &side(RectangleSide::Top), "lower.top")
        .map_err(|e| e.to_string())?;
    let upper_bottom = ContactSurface::new(
        1,
        bodies.body(1),
        &side(RectangleSide::Bottom),
        "upper.bottom",
    )
    .map_err(|e| e.to_string())?;
    let law = PairLaw {
        enforcement: Enforcement::Lagrange,
        friction: 0.0,
    };
    let on_lower = ContactPair {
        slave: upper_bottom.clone(),
        master: PairMaster::Surface(lower_top.clone()),
        law,
    };
    let on_upper = ContactPair {
        slave: lower_top.clone(),
        master: PairMaster::Surface(upper_bottom.clone()),
        law,
    };
    let pairs = match passes {
        Passes::Single {
            slave: Block::Upper,
        } => vec![on_lower],
        Passes::Single {
            slave: Block::Lower,
        } => vec![on_upper],
        Passes::Two => vec![on_lower, on_upper],
    };
    let n = bodies.dofs();
    let solver = MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs,
            scheme: MultibodyScheme::EnergyMomentum,
            final_time: 1.0,
            steps: 1,
            initial_displacement: vec![0.0; n],
            initial_velocity: vec![0.0; n],
        },
        params.clone(),
    )
    .map_err(|e| e.to_string())?;
    let solution = solver
        .solve_static(1.0)
        .map_err(|e| format!("{} on {}: {e}", passes.label(), mesh.ratio()))?;
    Ok(PatchRun {
        passes,
        mesh,
        solver,
        lower_top,
        upper_bottom,
        solution,
    })
}
