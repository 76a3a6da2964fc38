//! The bodies of `multibody_sliding` and what a run observes.
//!
//! Grazing: the bar [0, W] × [g0, g0 + L] (P1, `columns` × `elements`) at (v_t, −v_n), its
//! bottom (slave nodes) on the rigid foundation {y ≤ 0}, Lagrange multipliers, no friction.
//! Slide-off: the master [0, L_m] × [−H_m, 0] at rest and the slave [x_s, x_s + L_s] × [0, H_s]
//! at (v_t, −v_a), the slave's bottom against the master's top, one pass, no friction, no load.
//! Both run the energy–momentum scheme with k = courant · h / c.

use contactlab::mesh::triangle::RectangleSide;
use contactlab::model::multibody::audit::{MultibodyRecord, MultibodySummary};
use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::constraint::{Enforcement, PairLaw};
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{
    ContactPair, MultibodyParams, MultibodyProblem, MultibodySolver, MultibodyStats, PairMaster,
};
use contactlab::model::multibody::surface::{ContactSurface, Foundation};
use contactlab::model::quasistatic::plane::BoundarySelector;

use crate::multibody::audit_state::{StateAudit, StateAuditor};
use crate::multibody::cases::sliding::format::{GrazingSpec, SlideOffSpec, SlidingCase};
use crate::multibody::errors::centre_velocity;
use crate::multibody::study::{rectangle_body, MaterialSpec};

/// The body indices of the slide: the master and the slave.
pub const MASTER: usize = 0;
pub const SLAVE: usize = 1;

const FRICTIONLESS: PairLaw = PairLaw {
    enforcement: Enforcement::Lagrange,
    friction: 0.0,
};

/// One step's observations.
#[derive(Debug, Clone, Default)]
pub struct Step {
    pub time: f64,
    /// Each body's centre-of-mass velocity.
    pub centre: Vec<[f64; 2]>,
    /// Each body's momentum Σ_I (M v)_I.
    pub momentum: Vec<[f64; 2]>,
    /// Every node's velocity (x, y), body by body.
    pub velocity: Vec<Vec<[f64; 2]>>,
    /// Σ λ_N, the active constraints, the released ones (audit record).
    pub normal_force: f64,
    pub active: usize,
    pub released: usize,
    /// Which slave contact nodes (in the order of the pair's slave surface) are candidates after
    /// the step (a released node is not).
    pub listed: Vec<bool>,
}

/// A run with its observations.
#[derive(Debug, Clone)]
pub struct Observed {
    pub records: Vec<MultibodyRecord>,
    pub summary: MultibodySummary,
    /// The audit recomputed from the state (`crate::multibody::audit_state`).
    pub state: StateAudit,
    pub stats: MultibodyStats,
    pub steps: Vec<Step>,
    /// The step size.
    pub k: f64,
}

/// Runs `solver`, observing every step.
pub fn observe(solver: &MultibodySolver, material: &MaterialSpec) -> Result<Observed, String> {
    let problem = solver.problem();
    let mut auditor = StateAuditor::new(problem, &vec![*material; problem.bodies.len()], &[])?;
    let bodies = &problem.bodies;
    let slave_nodes = problem
        .pairs
        .first()
        .map(|p| p.slave.nodes.clone())
        .unwrap_or_default();
    let mut scratch = vec![0.0; bodies.dofs()];
    let mut steps = Vec::new();
    let solution = solver
        .solve_with(&mut |view| {
            auditor.observe(view);
            let centre: Vec<[f64; 2]> = (0..bodies.len())
                .map(|b| centre_velocity(bodies, b, view.velocity, &mut scratch))
                .collect();
            // scratch = M v after centre_velocity
            let momentum = (0..bodies.len())
                .map(|b| {
                    let mut p = [0.0; 2];
                    for node in 0..bodies.body(b).data().mesh.nodes().len() {
                        for (c, pc) in p.iter_mut().enumerate() {
                            if let Some(d) = bodies.dof(b, node, c) {
                                *pc += scratch[d];
                            }
                        }
                    }
                    p
                })
                .collect();
            let velocity = (0..bodies.len())
                .map(|b| {
                    (0..bodies.body(b).data().mesh.nodes().len())
                        .map(|node| {
                            let v = |c| bodies.dof(b, node, c).map_or(0.0, |d| view.velocity[d]);
                            [v(0), v(1)]
                        })
                        .collect()
                })
                .collect();
            let listed = slave_nodes
                .iter()
                .map(|n| view.contacts.iter().any(|c| c.pair == 0 && c.slave == *n))
                .collect();
            steps.push(Step {
                time: view.time,
                centre,
                momentum,
                velocity,
                normal_force: view.record.normal_force,
                active: view.record.active,
                released: view.record.released,
                listed,
            });
        })
        .map_err(|e| e.to_string())?;
    Ok(Observed {
        state: auditor.finish()?,
        summary: solution.summary(),
        records: solution.records,
        stats: solution.stats,
        steps,
        k: solver.step_size(),
    })
}

/// The number of steps of a run to `final_time` at k = courant · h / c (rounded up).
pub fn steps_to(final_time: f64, k: f64) -> usize {
    (final_time / k - 1e-9).ceil().max(1.0) as usize
}

/// The grazing bar's step k = courant · (L/elements) / c.
pub fn grazing_step(file: &SlidingCase, g: &GrazingSpec) -> f64 {
    file.courant * g.length / g.elements as f64 / file.wave_speed()
}

/// The grazing bar at (v_t, −v_n), g0 = v_n t0.
pub fn grazing(
    file: &SlidingCase,
    g: &GrazingSpec,
    vt: f64,
    vn: f64,
) -> Result<MultibodySolver, String> {
    let bar = rectangle_body(
        [0.0, vn * g.onset],
        [g.width, g.length],
        [g.columns, g.elements],
        file.density,
        &file.material,
        vec![],
        vec![],
        [0.0, 0.0],
    )?;
    let bodies = BodySet::new(vec![bar]).map_err(|e| e.to_string())?;
    let slave = ContactSurface::new(
        0,
        bodies.body(0),
        &BoundarySelector::side(RectangleSide::Bottom),
        "grazing: the bar's bottom",
    )
    .map_err(|e| e.to_string())?;
    let pairs = vec![ContactPair {
        slave,
        master: PairMaster::Foundation(Foundation::horizontal(0.0)),
        law: FRICTIONLESS,
    }];
    let n = bodies.dofs();
    let mut v = vec![0.0; n];
    bodies.rigid_velocity(0, [vt, -vn], 0.0, [0.0, 0.0], &mut v);
    let k = grazing_step(file, g);
    let steps = steps_to(g.final_time, k);
    MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs,
            scheme: MultibodyScheme::EnergyMomentum,
            final_time: k * steps as f64,
            steps,
            initial_displacement: vec![0.0; n],
            initial_velocity: v,
        },
        MultibodyParams::default(),
    )
    .map_err(|e| e.to_string())
}

/// The slide's step k = courant · (H_s / rows of the slave) / c (the normal element size).
pub fn slide_step(file: &SlidingCase, s: &SlideOffSpec) -> f64 {
    file.courant * s.slave.size[1] / s.slave.divisions[1] as f64 / file.wave_speed()
}

/// The slide with the slave at (v_t, −approach).
pub fn slide(
    file: &SlidingCase,
    s: &SlideOffSpec,
    approach: f64,
) -> Result<MultibodySolver, String> {
    let block = |origin: [f64; 2], b: &crate::multibody::cases::sliding::format::BlockSpec| {
        rectangle_body(
            origin,
            b.size,
            b.divisions,
            file.density,
            &file.material,
            vec![],
            vec![],
            [0.0, 0.0],
        )
    };
    let master = block([0.0, -s.master.size[1]], &s.master)?;
    let slave = block([s.start, 0.0], &s.slave)?;
    let bodies = BodySet::new(vec![master, slave]).map_err(|e| e.to_string())?;
    let side = |b: usize, side: RectangleSide, field: &str| {
        ContactSurface::new(b, bodies.body(b), &BoundarySelector::side(side), field)
            .map_err(|e| e.to_string())
    };
    let pairs = vec![ContactPair {
        slave: side(
            SLAVE,
            RectangleSide::Bottom,
            "slide_off: the slave's bottom",
        )?,
        master: PairMaster::Surface(side(
            MASTER,
            RectangleSide::Top,
            "slide_off: the master's top",
        )?),
        law: FRICTIONLESS,
    }];
    let n = bodies.dofs();
    let mut v = vec![0.0; n];
    bodies.rigid_velocity(
        SLAVE,
        [s.tangential_speed, -approach],
        0.0,
        [0.0, 0.0],
        &mut v,
    );
    let k = slide_step(file, s);
    let steps = steps_to(s.final_time, k);
    MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs,
            scheme: MultibodyScheme::EnergyMomentum,
            final_time: k * steps as f64,
            steps,
            initial_displacement: vec![0.0; n],
            initial_velocity: v,
        },
        MultibodyParams::default(),
    )
    .map_err(|e| e.to_string())
}
