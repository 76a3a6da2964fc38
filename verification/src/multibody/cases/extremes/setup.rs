//! The two head-on bars of a `multibody_extremes` run: [−g0/2 − L, −g0/2] × [0, H] at +v and
//! [g0/2, g0/2 + L] × [0, H] at −v, P1 triangles (h = L/M), the left bar's right end (slave
//! nodes) against the right bar's left end (master segments), one pass, with the enforcement and
//! scheme of the run.

use contactlab::mesh::triangle::RectangleSide;
use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::constraint::{Enforcement, PairLaw};
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{
    ContactPair, MultibodyParams, MultibodyProblem, MultibodySolver, PairMaster,
};
use contactlab::model::multibody::surface::ContactSurface;
use contactlab::model::quasistatic::plane::BoundarySelector;

use crate::multibody::cases::extremes::format::ExtremesCase;
use crate::multibody::study::rectangle_body;

/// What varies between the runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunSpec {
    pub speed: f64,
    pub enforcement: Enforcement,
    pub scheme: MultibodyScheme,
    pub step: f64,
    pub steps: usize,
}

impl RunSpec {
    /// A run at the case's ordinary step k = courant · h / c to the case's final time.
    pub fn ordinary(file: &ExtremesCase, speed: f64, enforcement: Enforcement) -> Self {
        let step = file.bars.courant * file.bars.h() / file.wave_speed();
        let steps = (file.bars.final_time / step - 1e-9).ceil().max(1.0) as usize;
        Self {
            speed,
            enforcement,
            scheme: MultibodyScheme::EnergyMomentum,
            step,
            steps,
        }
    }
}

/// The solver of one run.
pub fn build(file: &ExtremesCase, run: &RunSpec) -> Result<MultibodySolver, String> {
    let b = &file.bars;
    let gap = 2.0 * run.speed * b.onset;
    let body = |x0: f64| {
        rectangle_body(
            [x0, 0.0],
            [b.length, b.height],
            [b.elements, b.rows],
            b.density,
            &file.material,
            vec![],
            vec![],
            [0.0, 0.0],
        )
    };
    let left = body(-0.5 * gap - b.length)?;
    let right = body(0.5 * gap)?;
    let bodies = BodySet::new(vec![left, right]).map_err(|e| e.to_string())?;
    let surface = |i: usize, side: RectangleSide, field: &str| {
        ContactSurface::new(i, bodies.body(i), &BoundarySelector::side(side), field)
            .map_err(|e| e.to_string())
    };
    let slave = surface(0, RectangleSide::Right, "left bar's right end")?;
    let master = surface(1, RectangleSide::Left, "right bar's left end")?;
    let pairs = vec![ContactPair {
        slave,
        master: PairMaster::Surface(master),
        law: PairLaw {
            enforcement: run.enforcement,
            friction: 0.0,
        },
    }];
    let n = bodies.dofs();
    let mut v = vec![0.0; n];
    bodies.rigid_velocity(0, [run.speed, 0.0], 0.0, [0.0, 0.0], &mut v);
    bodies.rigid_velocity(1, [-run.speed, 0.0], 0.0, [0.0, 0.0], &mut v);
    MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs,
            scheme: run.scheme,
            final_time: run.step * run.steps as f64,
            steps: run.steps,
            initial_displacement: vec![0.0; n],
            initial_velocity: v,
        },
        MultibodyParams::default(),
    )
    .map_err(|e| e.to_string())
}
