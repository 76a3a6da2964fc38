//! The block of both settings as the solver sees it: the rectangle's P1 body with its supports
//! and loads, the foundation under its bottom with a family's treatment and friction, its
//! initial state and its solver.

use std::sync::Arc;

use contactlab::contact::friction::FrictionCoefficient;
use contactlab::field::Field;
use contactlab::material::hyperelastic::{
    Hyperelastic2d, LinearElastic, NeoHooke, StVenantKirchhoff,
};
use contactlab::mesh::triangle::{Diagonal, RectangleSide, TriangleMesh};
use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::dynamic::contact_model::{ContactModel, NormalTreatment};
use contactlab::model::dynamic::newton::NewtonParams;
use contactlab::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::{DynamicParams, DynamicProblem, DynamicSolver};
use contactlab::model::quasistatic::plane::{
    BoundarySelector, DirichletPart, Support, TractionPart,
};

use crate::dynamic::cases::friction::format::{FamilySpec, Treatment};
use crate::exact::coulomb_friction::FrictionLaw;

/// The rectangle and its material.
pub(crate) struct Shape<'a> {
    pub(crate) size: [f64; 2],
    pub(crate) divisions: [usize; 2],
    pub(crate) density: f64,
    pub(crate) law: &'a str,
    pub(crate) young: f64,
    pub(crate) poisson: f64,
}

/// How the block is held and loaded.
pub(crate) enum Hold {
    /// Rollers on the top (u_y = 0), the foundation at level δ.
    Rollers { level: f64 },
    /// A pressure p on the top, the foundation at level 0.
    Pressure { pressure: f64 },
}

/// A built run: the solver, the body and the contact model.
pub(crate) struct BuiltRun {
    pub(crate) solver: DynamicSolver,
    pub(crate) body: Arc<PlaneBody>,
    pub(crate) contact: ContactModel,
}

/// The solver's friction coefficient of a family (the same numbers as the case's reference).
fn solver_friction(f: &FamilySpec) -> FrictionCoefficient {
    let (mu0, depth) = (f.mu0, f.depth.unwrap_or(f64::INFINITY));
    match f.law {
        FrictionLaw::Constant => FrictionCoefficient::Constant { mu0 },
        FrictionLaw::Growing => FrictionCoefficient::Growing { mu0, depth },
        FrictionLaw::Decreasing => FrictionCoefficient::Decreasing { mu0, depth },
    }
}

/// The solver's normal treatment of a family with compliance r.
fn solver_treatment(f: &FamilySpec, stiffness: f64) -> NormalTreatment {
    match f.treatment {
        Treatment::Penalty => NormalTreatment::Penalty { stiffness },
        Treatment::EnergyConsistent => NormalTreatment::EnergyConsistent { stiffness },
        Treatment::LimitedPenetration => NormalTreatment::LimitedPenetration {
            stiffness,
            depth: f.base.unwrap_or(f64::INFINITY),
        },
    }
}

/// The run of family `f` on the block: `initial(x, y)` gives the displacement and velocity of
/// each node, `steps` uniform steps to `final_time`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn build(
    shape: &Shape<'_>,
    hold: &Hold,
    family: &FamilySpec,
    stiffness: f64,
    scheme: DynamicScheme,
    (final_time, steps): (f64, usize),
    tolerance: f64,
    initial: &dyn Fn(f64, f64) -> ([f64; 2], [f64; 2]),
    full_path: bool,
) -> Result<BuiltRun, String> {
    let mesh = TriangleMesh::rectangle([0.0, 0.0], shape.size, shape.divisions, Diagonal::Up)
        .map_err(|e| e.to_string())?;
    let (e, nu) = (shape.young, shape.poisson);
    let law: Arc<dyn Hyperelastic2d> = match shape.law {
        "linear" => Arc::new(LinearElastic::from_young_poisson(e, nu).map_err(|e| e.to_string())?),
        "st_venant_kirchhoff" => {
            Arc::new(StVenantKirchhoff::from_young_poisson(e, nu).map_err(|e| e.to_string())?)
        }
        "neo_hooke" => Arc::new(NeoHooke::from_young_poisson(e, nu).map_err(|e| e.to_string())?),
        other => return Err(format!("unknown law {other}")),
    };
    let top = || BoundarySelector::side(RectangleSide::Top);
    let (dirichlet, traction, level) = match *hold {
        Hold::Rollers { level } => (
            vec![DirichletPart {
                boundary: top(),
                support: Support::FixY,
            }],
            Vec::new(),
            level,
        ),
        Hold::Pressure { pressure } => (
            Vec::new(),
            vec![TractionPart {
                boundary: top(),
                traction: [Field::Constant(0.0), Field::Constant(-pressure)],
            }],
            0.0,
        ),
    };
    let nodes = mesh.nodes().to_vec();
    let body = Arc::new(
        PlaneBody::new(PlaneBodyData {
            mesh,
            density: shape.density,
            law,
            dirichlet,
            traction,
            body_force: [Field::Constant(0.0), Field::Constant(0.0)],
            mass: MassMatrix::Consistent,
            regions: Vec::new(),
        })
        .map_err(|e| e.to_string())?,
    );
    let contact = ContactModel::plane_half_space(
        &body,
        &BoundarySelector::side(RectangleSide::Bottom),
        level,
        solver_treatment(family, stiffness),
        Some(solver_friction(family)),
    )
    .map_err(|e| e.to_string())?;
    let (mut u0, mut v0) = (Vec::new(), Vec::new());
    for p in &nodes {
        let (u, v) = initial(p[0], p[1]);
        u0.extend_from_slice(&u);
        v0.extend_from_slice(&v);
    }
    let problem = DynamicProblem {
        body: body.clone() as Arc<dyn ElasticBody>,
        contact: Some(contact.clone()),
        scheme,
        final_time,
        steps,
        initial_displacement: body.from_nodal(&u0),
        initial_velocity: body.from_nodal(&v0),
    };
    let params = DynamicParams {
        newton: NewtonParams {
            tolerance,
            ..NewtonParams::default()
        },
        force_full_path: full_path,
        snapshot_times: Vec::new(),
    };
    let solver = DynamicSolver::new(problem, params).map_err(|e| e.to_string())?;
    Ok(BuiltRun {
        solver,
        body,
        contact,
    })
}

/// P = (Σ over the x dofs, Σ over the y dofs) of M v: the momentum of the body (the consistent
/// mass couples like components only, and its rows sum to the lumped masses).
pub(crate) fn momentum(body: &PlaneBody, v: &[f64], scratch: &mut [f64]) -> [f64; 2] {
    body.pattern().symmetric_mul(body.mass(), v, scratch);
    let mut p = [0.0; 2];
    for node in 0..body.data().mesh.nodes().len() {
        for (c, pc) in p.iter_mut().enumerate() {
            if let Some(d) = body.dof(node, c) {
                *pc += scratch[d];
            }
        }
    }
    p
}
