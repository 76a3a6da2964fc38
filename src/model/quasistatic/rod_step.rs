//! What a rod run shows its observer: the state after each step ([`RodStep`]), the observer
//! trait, and the run's statistics. A module of its own so that the outputs
//! ([`crate::model::quasistatic::rod_output`]) and the solver depend on it, not on each other.

/// Statistics of a run.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct RodStats {
    /// Time steps taken.
    pub steps: usize,
    /// Total semismooth Newton iterations of the contact equation (all steps and post-processing).
    pub newton_iterations: usize,
    /// The most Newton iterations in one solve.
    pub max_newton_iterations: usize,
    /// Steps with the foundation's damping active (p_ν'(w_n(L)) > 0).
    pub active_contact_steps: usize,
    /// Factorizations of the stiffness (always 1).
    pub factorizations: usize,
    /// Triangular solve pairs with the stiffness factor (setup and per-step loads).
    pub stiffness_solves: usize,
    /// How the load enters each step: `static`, `time_scaled` or `space_time`.
    pub load_path: String,
    /// The explicit scheme's step bound 2a/b, if the scheme is explicit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub explicit_stability_bound: Option<f64>,
    /// Steps with k_n ≥ 2a/b (explicit scheme only).
    pub steps_above_stability_bound: usize,
}

/// What the observer sees after each step (and at t_0).
#[derive(Debug, Clone, Copy)]
pub struct RodStep<'a> {
    /// The step index n (0 for the initial state).
    pub n: usize,
    /// t_n.
    pub t: f64,
    /// τ_n, the time at which the step's data were evaluated (t_n, or t_{n−1/2} for midpoint).
    pub data_time: f64,
    /// k_n (0 at n = 0).
    pub k: f64,
    /// The mesh nodes x_0..x_M.
    pub nodes: &'a [f64],
    /// u_n at the nodes (u_n(x_0) = 0).
    pub u: &'a [f64],
    /// The scheme's velocity w_n at the nodes (`None` at n = 0).
    pub w: Option<&'a [f64]>,
    /// The post-processed velocity v_n at t_n (always at n = 0: the consistent initial velocity;
    /// at n ≥ 1 when requested).
    pub v: Option<&'a [f64]>,
    /// The normal velocity of the contact node: w_n(L) (v_0(L) at n = 0).
    pub contact_velocity: f64,
    /// The contact stress σ(L) = −p_ν(contact velocity).
    pub contact_stress: f64,
    /// Newton iterations of this step's contact equation.
    pub newton_iterations: usize,
}

/// Receives every step of a run, without copies.
pub trait RodObserver {
    /// Called at n = 0 and after each step.
    fn observe(&mut self, step: &RodStep<'_>);
}

impl<F: FnMut(&RodStep<'_>)> RodObserver for F {
    fn observe(&mut self, step: &RodStep<'_>) {
        self(step)
    }
}
