//! The sliding block's runs (`[slide]`): one family at one step count, measured against
//! [`crate::exact::sliding_block::SlidingBlock`].
//!
//! | quantity | definition |
//! |---|---|
//! | `stop_time_error` | \|t_s − t*\| / t*, t_s = t_{n_s − 1} with n_s the first step in which no contact node slips |
//! | `stop_distance_error` | \|s_h(T) − s*\| / s*, s_h the contact nodes' mean slip (weights w_i) |
//! | `post_stop_velocity` | max over n ≥ n_s of \|P_x,n\| / (m v0): the velocity that alternates after the stop (exact: ±v(t_s)) |
//! | `stop_step_offset` | (n_s − 1) minus the last sliding step of the midpoint rule on the rigid block |
//! | `slip_after_stop` | max over nodes and n ≥ n_s of \|u_x,i(t_n) − u_x,i(t_s)\| |
//! | `slide_velocity_error` | max over the steps before the stop (both exact and discrete) of \|P_x,n/m − v(t_n)\| / v0 |
//! | `penetration_deviation` | max over steps and nodes of \|p_i − η\| / η |
//!
//! A node slips in a step when its tangential increment exceeds the block's shear lag δ_s: the
//! rigid model cannot resolve less (at the stop the elastic block's reaction is not uniform, and
//! an edge node may slip by ~1e−11 while the block stops), and the last genuine slide of the
//! rigid block moves by at least a k²/6 (module docs of `exact/sliding_block.rs`), far above
//! δ_s in every case. A block that still slips at T is taken to stop after T (its stop step is
//! then N, and the errors are lower bounds).

use std::collections::BTreeMap;

use serde::Serialize;

use contactlab::model::dynamic::audit::AuditSummary;
use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::dynamic::solver::{DynamicStats, StepView};

use crate::dynamic::cases::friction::block::{build, momentum, Hold, Shape};
use crate::dynamic::cases::friction::format::{FamilySpec, SlideSpec};
use crate::exact::sliding_block::{DiscreteStop, SlidingBlock};

/// One run of the sliding block.
#[derive(Debug, Clone, Serialize)]
pub struct SlideRun {
    pub family: String,
    pub steps: usize,
    pub k: f64,
    /// The rigid midpoint stop predicted for this k.
    pub predicted: DiscreteStop,
    /// n_s − 1 observed.
    pub last_sliding_step: usize,
    pub errors: BTreeMap<String, f64>,
    pub audit: AuditSummary,
    pub stats: DynamicStats,
    /// (t, mean slip, P_x/m) per step.
    #[serde(skip)]
    pub history: Vec<[f64; 3]>,
}

/// Runs family `f` with N = `steps` (T = duration × t*).
pub fn run(spec: &SlideSpec, f: &FamilySpec, steps: usize) -> Result<SlideRun, String> {
    let exact = spec.block(f);
    let final_time = spec.duration * exact.stop_time();
    let k = final_time / steps as f64;
    let shape = Shape {
        size: [spec.length, spec.height],
        divisions: spec.divisions,
        density: spec.density,
        law: "linear",
        young: spec.young,
        poisson: spec.poisson,
    };
    let v0 = spec.speed;
    let built = build(
        &shape,
        &Hold::Rollers {
            level: exact.squeeze(),
        },
        f,
        spec.stiffness,
        spec.scheme,
        (final_time, steps),
        spec.tolerance(),
        &|x, y| (exact.equilibrium_displacement(x, y), [v0, 0.0]),
        false,
    )?;
    let label = format!("{} (N = {steps})", f.name);
    let nodes = built
        .contact
        .nodes
        .iter()
        .filter_map(|c| c.tangent_dof.map(|t| (t, c.weight)))
        .collect();
    let mut m = Measure::new(&exact, nodes);
    let mut scratch = vec![0.0; built.body.dofs()];
    let solution = built
        .solver
        .solve_with(&mut |view: &StepView<'_>| {
            let p = momentum(&built.body, view.velocity, &mut scratch);
            m.observe(view, p[0]);
        })
        .map_err(|e| format!("{label}: {e}"))?;
    // a block that still slips at T is taken to stop after it: its errors are then lower bounds
    // and the stop-step gate fails
    let n_s = m.first_stuck.unwrap_or(steps + 1);
    let predicted = exact.discrete_stop(k);
    let t_s = (n_s - 1) as f64 * k;
    let slip_end = m.history.last().map_or(0.0, |h| h[1]);
    let (t_star, s_star) = (exact.stop_time(), exact.stop_distance());
    let errors: BTreeMap<String, f64> = [
        ("stop_time_error", (t_s - t_star).abs() / t_star),
        ("stop_distance_error", (slip_end - s_star).abs() / s_star),
        ("post_stop_velocity", m.post_stop_velocity / v0),
        (
            "stop_step_offset",
            (n_s - 1) as f64 - predicted.last_sliding_step as f64,
        ),
        ("slip_after_stop", m.slip_after_stop),
        ("slide_velocity_error", m.slide_velocity_error / v0),
        ("penetration_deviation", m.penetration_deviation),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect();
    Ok(SlideRun {
        family: f.name.clone(),
        steps,
        k,
        predicted,
        last_sliding_step: n_s - 1,
        errors,
        audit: solution.audit.summary(),
        stats: solution.stats,
        history: m.history,
    })
}

/// The running measurements of one run.
struct Measure<'a> {
    exact: &'a SlidingBlock,
    /// (tangential dof, weight) of each contact node.
    nodes: Vec<(usize, f64)>,
    initial: Vec<f64>,
    previous: Vec<f64>,
    at_stop: Vec<f64>,
    first_stuck: Option<usize>,
    post_stop_velocity: f64,
    slip_after_stop: f64,
    slide_velocity_error: f64,
    penetration_deviation: f64,
    history: Vec<[f64; 3]>,
}

impl<'a> Measure<'a> {
    fn new(exact: &'a SlidingBlock, nodes: Vec<(usize, f64)>) -> Self {
        Self {
            exact,
            nodes,
            initial: Vec::new(),
            previous: Vec::new(),
            at_stop: Vec::new(),
            first_stuck: None,
            post_stop_velocity: 0.0,
            slip_after_stop: 0.0,
            slide_velocity_error: 0.0,
            penetration_deviation: 0.0,
            history: Vec::new(),
        }
    }

    fn observe(&mut self, view: &StepView<'_>, px: f64) {
        let u: Vec<f64> = self
            .nodes
            .iter()
            .map(|&(t, _)| view.displacement[t])
            .collect();
        if view.step == 0 {
            self.initial = u.clone();
            self.previous = u.clone();
        }
        let total: f64 = self.nodes.iter().map(|&(_, w)| w).sum();
        let slip = self
            .nodes
            .iter()
            .zip(u.iter().zip(&self.initial))
            .map(|(&(_, w), (x, x0))| w * (x - x0))
            .sum::<f64>()
            / total;
        let v = px / self.exact.mass();
        let t = view.time;
        self.history.push([t, slip, v]);
        let eta = self.exact.equilibrium_penetration();
        for f in view.forces {
            self.penetration_deviation = self.penetration_deviation.max((f.p - eta).abs() / eta);
        }
        if view.step > 0 {
            let lag = self.exact.shear_lag();
            let slips = u
                .iter()
                .zip(&self.previous)
                .any(|(a, b)| (a - b).abs() > lag);
            match self.first_stuck {
                None if !slips => {
                    self.first_stuck = Some(view.step);
                    self.at_stop = self.previous.clone();
                }
                None => {
                    if t <= self.exact.stop_time() {
                        self.slide_velocity_error = self
                            .slide_velocity_error
                            .max((v - self.exact.velocity(t)).abs());
                    }
                }
                Some(_) => {}
            }
            if self.first_stuck.is_some() {
                self.post_stop_velocity = self.post_stop_velocity.max(v.abs());
                for (a, b) in u.iter().zip(&self.at_stop) {
                    self.slip_after_stop = self.slip_after_stop.max((a - b).abs());
                }
            }
        }
        self.previous = u;
    }
}
