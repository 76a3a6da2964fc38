//! The two blocks as a multibody problem: the bodies (P1, consistent mass, gravity), the pairs
//! (the upper block's bottom as slave on the lower block's top with friction μ; the lower block's
//! bottom on the frictionless rigid foundation), the static equilibrium under gravity the runs
//! start from, and the launch.

use contactlab::mesh::triangle::RectangleSide;
use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::constraint::{Enforcement, PairLaw};
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{
    ContactPair, MultibodyParams, MultibodyProblem, MultibodySolver, PairMaster,
};
use contactlab::model::multibody::surface::{ContactSurface, Foundation};
use contactlab::model::quasistatic::plane::BoundarySelector;

use crate::multibody::cases::friction::format::{BlocksSpec, RectSpec};
use crate::multibody::study::{rectangle_body, MaterialSpec};

/// Body indices.
pub const LOWER: usize = 0;
pub const UPPER: usize = 1;
/// Pair indices: the blocks' interface and the foundation.
pub const INTERFACE: usize = 0;
pub const BASE: usize = 1;

/// The blocks' problem (without its time data) and its equilibrium.
#[derive(Debug, Clone)]
pub struct Setting {
    pub bodies: BodySet,
    /// The blocks' material (for the audit recomputed from the state).
    pub material: MaterialSpec,
    pub pairs: Vec<ContactPair>,
    /// The static equilibrium under gravity (free dofs).
    pub equilibrium: Vec<f64>,
    /// The launch: each block in rigid translation with its speed.
    pub velocity: Vec<f64>,
    /// Newton iterations of the static solve.
    pub static_iterations: usize,
}

fn body(
    r: &RectSpec,
    spec: &BlocksSpec,
) -> Result<std::sync::Arc<contactlab::model::dynamic::plane_body::PlaneBody>, String> {
    rectangle_body(
        r.origin,
        r.size,
        r.divisions,
        spec.density,
        &spec.material,
        vec![],
        vec![],
        [0.0, -spec.gravity],
    )
}

/// The pairs with friction μ between the blocks.
fn pairs(bodies: &BodySet, spec: &BlocksSpec, mu: f64) -> Result<Vec<ContactPair>, String> {
    let e = |x: contactlab::error::InputError| x.to_string();
    let side = |b: usize, s: RectangleSide, f: &str| {
        ContactSurface::new(b, bodies.body(b), &BoundarySelector::side(s), f).map_err(e)
    };
    let lagrange = |friction: f64| PairLaw {
        enforcement: Enforcement::Lagrange,
        friction,
    };
    Ok(vec![
        ContactPair {
            slave: side(UPPER, RectangleSide::Bottom, "blocks.upper")?,
            master: PairMaster::Surface(side(LOWER, RectangleSide::Top, "blocks.lower")?),
            law: lagrange(mu),
        },
        ContactPair {
            slave: side(LOWER, RectangleSide::Bottom, "blocks.lower")?,
            master: PairMaster::Foundation(Foundation::horizontal(spec.lower.origin[1])),
            law: lagrange(0.0),
        },
    ])
}

impl Setting {
    /// The bodies, pairs, equilibrium and launch of `spec`.
    pub fn new(spec: &BlocksSpec) -> Result<Self, String> {
        let bodies = BodySet::new(vec![body(&spec.lower, spec)?, body(&spec.upper, spec)?])
            .map_err(|e| e.to_string())?;
        let n = bodies.dofs();
        let pairs = pairs(&bodies, spec, spec.friction)?;
        let statics = MultibodySolver::new(
            MultibodyProblem {
                bodies: bodies.clone(),
                pairs: pairs.clone(),
                scheme: MultibodyScheme::EnergyMomentum,
                final_time: 1.0,
                steps: 1,
                initial_displacement: vec![0.0; n],
                initial_velocity: vec![0.0; n],
            },
            MultibodyParams::default(),
        )
        .map_err(|e| e.to_string())?;
        let sol = statics
            .solve_static(0.0)
            .map_err(|e| format!("the static equilibrium under gravity: {e}"))?;
        let mut velocity = vec![0.0; n];
        bodies.rigid_velocity(
            LOWER,
            [spec.lower_speed, 0.0],
            0.0,
            [0.0, 0.0],
            &mut velocity,
        );
        bodies.rigid_velocity(
            UPPER,
            [spec.upper_speed, 0.0],
            0.0,
            [0.0, 0.0],
            &mut velocity,
        );
        Ok(Self {
            bodies,
            material: spec.material,
            pairs,
            equilibrium: sol.displacement,
            velocity,
            static_iterations: sol.iterations,
        })
    }

    /// The solver of a run with `scheme`, N = `steps` up to T = `final_time`.
    pub fn solver(
        &self,
        scheme: MultibodyScheme,
        final_time: f64,
        steps: usize,
    ) -> Result<MultibodySolver, String> {
        MultibodySolver::new(
            MultibodyProblem {
                bodies: self.bodies.clone(),
                pairs: self.pairs.clone(),
                scheme,
                final_time,
                steps,
                initial_displacement: self.equilibrium.clone(),
                initial_velocity: self.velocity.clone(),
            },
            MultibodyParams::default(),
        )
        .map_err(|e| e.to_string())
    }
}
