//! One run of the two-ring impact: the problem at a resolution factor (cells around and across and
//! steps multiplied by it), solved with its step records, and the quantities an experiment would
//! report — each ring's rebound (centre-of-mass) velocity at T, the contact interval — with the
//! run's CPU time.

use std::sync::Arc;

use contactlab::field::Field;
use contactlab::mesh::generators::annulus;
use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};
use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::constraint::{Enforcement, PairLaw};
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{
    ContactPair, MultibodyParams, MultibodyProblem, MultibodySolver, PairMaster,
};
use contactlab::model::multibody::surface::ContactSurface;
use contactlab::model::quasistatic::plane::BoundarySelector;

use crate::core::cpu_clock::thread_cpu_seconds;
use crate::multibody::cases::impact::format::{ImpactCase, RingSpec, RunSpec};
use crate::multibody::errors::contact_interval;
use crate::multibody::study::{run_recorded, RecordedRun};

/// What to run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Job {
    pub scheme: MultibodyScheme,
    pub friction: f64,
    pub factor: f64,
    /// The steps over T (None: the case's steps times the factor).
    pub steps: Option<usize>,
    /// The conserving penalty's stiffness ε per slave node (None: Lagrange multipliers).
    pub penalty: Option<f64>,
    /// The similar problem at size s: every length and velocity times s, the modulus and the
    /// penalty's ε times s² (so the wave speed is s c and every time, strain and E_n/E_0 is the
    /// same; the rebound velocities are s times). A check that no tolerance or guard of the
    /// solver carries a length scale of its own.
    pub size: f64,
}

impl Job {
    /// The job of a `[[run]]` at resolution 1.
    pub fn of(run: &RunSpec) -> Self {
        Self {
            scheme: run.scheme,
            friction: run.friction,
            factor: 1.0,
            steps: None,
            penalty: run.penalty,
            size: run.size.unwrap_or(1.0),
        }
    }
}

/// The reported quantities of a run.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Quantities {
    /// Each ring's centre-of-mass velocity at T.
    pub rebound: [[f64; 2]; 2],
    /// Last active time − first active time + k (None: no contact).
    pub contact_duration: Option<f64>,
    /// No constraint active in the last 10 % of the steps.
    pub separated: bool,
}

/// A completed run.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub job: Job,
    pub steps: usize,
    pub dofs: usize,
    pub run: RecordedRun,
    pub quantities: Quantities,
    pub cpu_seconds: f64,
}

impl Outcome {
    /// dofs × steps: the deterministic measure of work.
    pub fn dof_steps(&self) -> f64 {
        self.dofs as f64 * self.steps as f64
    }
}

fn scaled(n: usize, factor: f64) -> usize {
    ((n as f64 * factor).round() as usize).max(1)
}

/// A ring's body; at `size` s the modulus is E s² (the similarity of `Job::size`).
fn ring(c: &ImpactCase, r: &RingSpec, factor: f64, size: f64) -> Result<Arc<PlaneBody>, String> {
    let mut material = c.material;
    material.young *= size * size;
    let mesh = annulus(
        r.center,
        r.inner,
        r.outer,
        scaled(r.radial, factor),
        scaled(r.around, factor),
    )
    .map_err(|e| e.to_string())?;
    let body = PlaneBody::new(PlaneBodyData {
        mesh,
        density: c.density,
        law: material.law()?,
        dirichlet: vec![],
        traction: vec![],
        body_force: [Field::Constant(0.0), Field::Constant(0.0)],
        mass: MassMatrix::Consistent,
        regions: vec![],
    })
    .map_err(|e| e.to_string())?;
    Ok(Arc::new(body))
}

/// The outer boundary of a ring: the edges whose midpoints lie beyond the mean radius.
fn outer(r: &RingSpec) -> BoundarySelector {
    let (c, mid) = (r.center, 0.5 * (r.inner + r.outer));
    BoundarySelector::Predicate(Arc::new(move |x: [f64; 2]| {
        ((x[0] - c[0]).powi(2) + (x[1] - c[1]).powi(2)).sqrt() > mid
    }))
}

/// The solver of a job: ring 0's outer boundary (slave) against ring 1's (master), single pass,
/// Lagrange multipliers or the conserving penalty.
pub fn solver(c: &ImpactCase, job: &Job) -> Result<MultibodySolver, String> {
    let rings = [c.rings[0].at_size(job.size), c.rings[1].at_size(job.size)];
    let bodies = BodySet::new(vec![
        ring(c, &rings[0], job.factor, job.size)?,
        ring(c, &rings[1], job.factor, job.size)?,
    ])
    .map_err(|e| e.to_string())?;
    let slave = ContactSurface::new(0, bodies.body(0), &outer(&rings[0]), "ring[0]")
        .map_err(|e| e.to_string())?;
    let master = ContactSurface::new(1, bodies.body(1), &outer(&rings[1]), "ring[1]")
        .map_err(|e| e.to_string())?;
    let n = bodies.dofs();
    let mut v = vec![0.0; n];
    for (b, r) in rings.iter().enumerate() {
        let centre = bodies.centre_of_mass(b);
        bodies.rigid_velocity(b, r.velocity, r.angular_velocity, centre, &mut v);
    }
    let steps = job.steps.unwrap_or_else(|| scaled(c.steps, job.factor));
    MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs: vec![ContactPair {
                slave,
                master: PairMaster::Surface(master),
                law: PairLaw {
                    enforcement: job.penalty.map_or(Enforcement::Lagrange, |e| {
                        Enforcement::Penalty {
                            stiffness: e * job.size * job.size,
                        }
                    }),
                    friction: job.friction,
                },
            }],
            scheme: job.scheme,
            final_time: c.final_time,
            steps,
            initial_displacement: vec![0.0; n],
            initial_velocity: v,
        },
        MultibodyParams::default(),
    )
    .map_err(|e| e.to_string())
}

/// Runs a job.
pub fn run_job(c: &ImpactCase, job: &Job) -> Result<Outcome, String> {
    let s = solver(c, job)?;
    let start = thread_cpu_seconds();
    // the rings' material as `ring` builds it (E s² at size s)
    let mut material = c.material;
    material.young *= job.size * job.size;
    let run = run_recorded(&s, &[material; 2])?;
    let cpu_seconds = thread_cpu_seconds() - start;
    let steps = s.problem().steps;
    let records = &run.solution.records;
    let k = s.step_size();
    let last = run.history.last().ok_or("no step recorded")?;
    let tail = (steps / 10).max(1);
    let quantities = Quantities {
        rebound: [last.velocities[0], last.velocities[1]],
        contact_duration: contact_interval(records).map(|(a, b)| b - a + k),
        separated: records.iter().rev().take(tail).all(|r| r.active == 0),
    };
    Ok(Outcome {
        job: *job,
        steps,
        dofs: s.problem().bodies.dofs(),
        run,
        quantities,
        cpu_seconds,
    })
}
