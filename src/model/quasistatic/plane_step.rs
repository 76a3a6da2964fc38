//! What a plane run shows its observer: the state after each step ([`PlaneStep`]), the observer
//! trait, and the run's statistics. A module of its own so that the outputs
//! ([`crate::model::quasistatic::plane_output`]) and the solver depend on it, not on each other.

/// Statistics of a run.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct PlaneStats {
    /// `condensed` or `newton`.
    pub path: String,
    pub dofs: usize,
    pub contact_points: usize,
    pub steps: usize,
    /// Sparse numeric factorizations (condensed: one per distinct step size; Newton: one per
    /// iteration).
    pub factorizations: usize,
    /// Stored entries of the Cholesky factor.
    pub factor_nnz: usize,
    /// Dense factorizations of the reduced contact Jacobian (condensed path).
    pub contact_factorizations: usize,
    pub newton_iterations: usize,
    pub max_newton_iterations: usize,
    /// Newton solves that stopped at the computed round-off floor of their residual, above the
    /// requested tolerance (converged: the residual cannot be computed more accurately).
    pub floor_stops: usize,
    /// What the run could not rule out (e.g. an explicit step above the stability bound).
    pub warnings: Vec<String>,
    /// Steps skipped for lack of equilibrium (with `start_at_first_equilibrium`).
    pub skipped_steps: Vec<usize>,
    /// Rigid motions left free by Γ1 (carried by the contact).
    pub free_rigid_motions: usize,
}

/// What the observer sees after each step (and at t_0).
#[derive(Debug, Clone, Copy)]
pub struct PlaneStep<'a> {
    pub n: usize,
    pub t: f64,
    pub data_time: f64,
    pub k: f64,
    /// u_n at all nodes, interleaved (u_x, u_y).
    pub u: &'a [f64],
    /// w_n at all nodes (`None` at n = 0).
    pub w: Option<&'a [f64]>,
    /// Normal velocities and pressures p_ν at the contact points.
    pub contact_velocity: &'a [f64],
    pub contact_pressure: &'a [f64],
    pub newton_iterations: usize,
    /// The step was skipped for lack of equilibrium.
    pub skipped: bool,
}

/// Receives every step.
pub trait PlaneObserver {
    fn observe(&mut self, step: &PlaneStep<'_>);
}

impl<F: FnMut(&PlaneStep<'_>)> PlaneObserver for F {
    fn observe(&mut self, step: &PlaneStep<'_>) {
        self(step)
    }
}
