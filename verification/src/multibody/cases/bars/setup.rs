//! The two plane-strain bars of a `multibody_bars` run: the left bar (the striker, or one of the
//! head-on pair) [−g0/2 − L1, −g0/2] × [0, H] and the right bar [g0/2, g0/2 + L2] × [0, H], P1
//! triangles of size h = L1/M along the bars and H/rows across, free (no support, no load), each
//! in rigid translation at its speed; the left bar's right end (slave nodes) against the right
//! bar's left end (master segments), and with two passes also the reverse pair.

use contactlab::mesh::triangle::RectangleSide;
use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::constraint::{Enforcement, PairLaw};
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{
    ContactPair, MultibodyParams, MultibodyProblem, MultibodySolver, PairMaster,
};
use contactlab::model::multibody::surface::ContactSurface;
use contactlab::model::quasistatic::plane::BoundarySelector;

use crate::multibody::study::{rectangle_body, MaterialSpec};

/// The physical setting of one configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// L1 (the left bar) and L2 (the right bar).
    pub left_length: f64,
    pub right_length: f64,
    /// H (the section: the area per unit thickness).
    pub height: f64,
    pub density: f64,
    /// g0: the initial distance between the facing ends.
    pub gap: f64,
    /// The x velocities of the left and right bar (rigid translations).
    pub left_velocity: f64,
    pub right_velocity: f64,
}

/// One discretization level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Level {
    /// M: elements along the left bar (h = L1/M; the right bar has L2/h).
    pub elements: usize,
    /// Elements across the height.
    pub rows: usize,
    /// The time step k.
    pub step: f64,
    /// N: steps (the run ends at N k).
    pub steps: usize,
}

impl Level {
    /// h = L1/M.
    pub fn h(&self, g: &Geometry) -> f64 {
        g.left_length / self.elements as f64
    }

    /// The level with M elements, k = courant · h / c and N = ⌈T/k⌉ steps (the run ends at
    /// N k ≥ T: k is exactly courant · h / c, so that the contact onset has the same phase in
    /// the step on every level of a sweep whose k halves).
    pub fn with_courant(
        g: &Geometry,
        elements: usize,
        rows: usize,
        courant: f64,
        wave_speed: f64,
        final_time: f64,
    ) -> Self {
        let h = g.left_length / elements as f64;
        let step = courant * h / wave_speed;
        let steps = (final_time / step - 1e-9).ceil().max(1.0) as usize;
        Self {
            elements,
            rows,
            step,
            steps,
        }
    }

    /// N k.
    pub fn final_time(&self) -> f64 {
        self.steps as f64 * self.step
    }

    /// The right bar's elements L2/h (L2/L1 M, rounded: the case checks that it is whole).
    pub fn right_elements(&self, g: &Geometry) -> usize {
        (g.right_length / self.h(g)).round() as usize
    }
}

/// The contact treatment of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Treatment {
    pub scheme: MultibodyScheme,
    /// Two passes: also the right bar's end nodes against the left bar's end segments.
    pub two_pass: bool,
}

/// The solver of one run.
pub fn build(
    g: &Geometry,
    material: &MaterialSpec,
    level: &Level,
    treatment: Treatment,
) -> Result<MultibodySolver, String> {
    let (l1, l2, hgt) = (g.left_length, g.right_length, g.height);
    let m2 = level.right_elements(g);
    let left = rectangle_body(
        [-0.5 * g.gap - l1, 0.0],
        [l1, hgt],
        [level.elements, level.rows],
        g.density,
        material,
        vec![],
        vec![],
        [0.0, 0.0],
    )?;
    let right = rectangle_body(
        [0.5 * g.gap, 0.0],
        [l2, hgt],
        [m2, level.rows],
        g.density,
        material,
        vec![],
        vec![],
        [0.0, 0.0],
    )?;
    let bodies = BodySet::new(vec![left, right]).map_err(|e| e.to_string())?;
    let surface = |b: usize, side: RectangleSide, field: &str| {
        ContactSurface::new(b, bodies.body(b), &BoundarySelector::side(side), field)
            .map_err(|e| e.to_string())
    };
    let left_end = surface(0, RectangleSide::Right, "left bar's right end")?;
    let right_end = surface(1, RectangleSide::Left, "right bar's left end")?;
    let law = PairLaw {
        enforcement: Enforcement::Lagrange,
        friction: 0.0,
    };
    let mut pairs = vec![ContactPair {
        slave: left_end.clone(),
        master: PairMaster::Surface(right_end.clone()),
        law,
    }];
    if treatment.two_pass {
        pairs.push(ContactPair {
            slave: right_end,
            master: PairMaster::Surface(left_end),
            law,
        });
    }
    let n = bodies.dofs();
    let mut v = vec![0.0; n];
    bodies.rigid_velocity(0, [g.left_velocity, 0.0], 0.0, [0.0, 0.0], &mut v);
    bodies.rigid_velocity(1, [g.right_velocity, 0.0], 0.0, [0.0, 0.0], &mut v);
    MultibodySolver::new(
        MultibodyProblem {
            bodies,
            pairs,
            scheme: treatment.scheme,
            final_time: level.final_time(),
            steps: level.steps,
            initial_displacement: vec![0.0; n],
            initial_velocity: v,
        },
        MultibodyParams::default(),
    )
    .map_err(|e| e.to_string())
}
