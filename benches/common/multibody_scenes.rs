//! The problems of the multibody benchmarks: two thin neo-Hookean rings pressed together, and one
//! ring of the same size on the rigid foundation.

use std::sync::Arc;

use contactlab::error::Error;
use contactlab::field::Field;
use contactlab::material::hyperelastic::NeoHooke;
use contactlab::mesh::generators::annulus;
use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};
use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::constraint::{Enforcement, PairLaw};
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{
    ContactPair, MultibodyParams, MultibodyProblem, MultibodySolver, PairMaster,
};
use contactlab::model::multibody::surface::{ContactSurface, Foundation};
use contactlab::model::quasistatic::plane::BoundarySelector;

/// The step size of the benchmarks.
pub const STEP: f64 = 1e-3;

fn ring(center: [f64; 2], radial: usize, around: usize) -> Result<Arc<PlaneBody>, Error> {
    Ok(Arc::new(PlaneBody::new(PlaneBodyData {
        mesh: annulus(center, 0.95, 1.0, radial, around)?,
        density: 1.0,
        law: Arc::new(NeoHooke::from_young_poisson(100.0, 0.3)?),
        dirichlet: vec![],
        traction: vec![],
        body_force: [Field::Constant(0.0), Field::Constant(0.0)],
        mass: MassMatrix::Consistent,
        regions: vec![],
    })?))
}

/// The outer boundary of a ring centred at c.
fn outer(c: [f64; 2]) -> BoundarySelector {
    BoundarySelector::Predicate(Arc::new(move |x: [f64; 2]| {
        ((x[0] - c[0]).powi(2) + (x[1] - c[1]).powi(2)).sqrt() > 0.975
    }))
}

/// Two rings touching at (1, 0): 2 × 1000 cells (6000 dofs) and 3 × 500 cells (4000 dofs),
/// approaching at relative speed 1; the slave surface is the first ring's outer boundary (1000
/// nodes). `steps` energy–momentum steps of 1e-3.
pub fn two_rings(steps: usize) -> Result<MultibodySolver, Error> {
    let (ca, cb) = ([0.0, 0.0], [2.0, 0.0]);
    let bodies = BodySet::new(vec![ring(ca, 2, 1000)?, ring(cb, 3, 500)?])?;
    let slave = ContactSurface::new(0, bodies.body(0), &outer(ca), "slave")?;
    let master = ContactSurface::new(1, bodies.body(1), &outer(cb), "master")?;
    let n = bodies.dofs();
    let mut v = vec![0.0; n];
    bodies.rigid_velocity(0, [0.5, 0.0], 0.0, ca, &mut v);
    bodies.rigid_velocity(1, [-0.5, 0.0], 0.0, cb, &mut v);
    MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs: vec![ContactPair {
                slave,
                master: PairMaster::Surface(master),
                law: PairLaw {
                    enforcement: Enforcement::Lagrange,
                    friction: 0.0,
                },
            }],
            scheme: MultibodyScheme::EnergyMomentum,
            final_time: STEP * steps as f64,
            steps,
            initial_displacement: vec![0.0; n],
            initial_velocity: v,
        },
        MultibodyParams::default(),
    )
}

/// One ring of 4 × 1000 cells (10 000 dofs) touching the foundation {y ≤ 0} and moving down at 1.
pub fn one_ring_on_foundation(steps: usize) -> Result<MultibodySolver, Error> {
    let c = [0.0, 1.0];
    let bodies = BodySet::new(vec![ring(c, 4, 1000)?])?;
    let slave = ContactSurface::new(0, bodies.body(0), &outer(c), "slave")?;
    let n = bodies.dofs();
    let mut v = vec![0.0; n];
    bodies.rigid_velocity(0, [0.0, -1.0], 0.0, c, &mut v);
    MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs: vec![ContactPair {
                slave,
                master: PairMaster::Foundation(Foundation::horizontal(0.0)),
                law: PairLaw {
                    enforcement: Enforcement::Lagrange,
                    friction: 0.0,
                },
            }],
            scheme: MultibodyScheme::EnergyMomentum,
            final_time: STEP * steps as f64,
            steps,
            initial_displacement: vec![0.0; n],
            initial_velocity: v,
        },
        MultibodyParams::default(),
    )
}
