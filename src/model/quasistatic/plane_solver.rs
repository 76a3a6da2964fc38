//! The plane Kelvin–Voigt scheme in time: w_n solves
//!
//!   (A ε(w_n), ε(v)) + (B ε(u_{n−1} + θ k_n w_n), ε(v)) + j(w_n, v) = (f(τ_n), v)   for all v,
//!   u_n = u_{n−1} + k_n w_n
//!
//! (Fernández & Sofonea 2004, (3.3) for θ = 0). The model picks the path from what the problem
//! contains: linear A and B → the condensed path (factor A + θkB once per step size, condense the
//! contact onto Γ3, one sparse solve per step); nonlinear A or B → a full semismooth Newton method.

use std::collections::BTreeMap;

use crate::contact::normal_law::SpaceTime;
use crate::error::{Error, InputError, SolveError};
use crate::model::quasistatic::plane::PlaneProblem;
use crate::model::quasistatic::plane_condensed::{assemble_linear, CondensedStep};
use crate::model::quasistatic::plane_contact::{ContactFailure, ContactNewtonParams};
use crate::model::quasistatic::plane_dofs::PlaneDofs;
use crate::model::quasistatic::plane_newton::{NewtonFailure, NewtonParams, NewtonStep};
use crate::model::quasistatic::plane_output::{PlaneOutputRequest, PlaneRecorder, PlaneSolution};
pub use crate::model::quasistatic::plane_step::{PlaneObserver, PlaneStats, PlaneStep};
use crate::model::quasistatic::scheme::TimeScheme;
use crate::time::grid::TimeGrid;

/// Which solver path to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SolverPath {
    /// Condensed when A and B are linear, Newton otherwise.
    #[default]
    Auto,
    /// Factor once and condense onto Γ3 (linear A and B only).
    Condensed,
    /// Full semismooth Newton on the whole system.
    Newton,
}

/// Parameters of the plane solver.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlaneParams {
    pub path: SolverPath,
    pub contact_newton: ContactNewtonParams,
    pub newton: NewtonParams,
    /// When Γ1 leaves a rigid motion free and the first steps have no equilibrium (the load cannot
    /// yet be balanced by the contact), skip them — the body stays at u0 — and start the scheme at
    /// the first step that has one. Without it, such a step is a [`SolveError::NoEquilibrium`].
    pub start_at_first_equilibrium: bool,
}

/// A plane problem discretized in space and time.
#[derive(Debug)]
pub struct PlaneSolver {
    problem: PlaneProblem,
    dofs: PlaneDofs,
    grid: TimeGrid,
    scheme: TimeScheme,
    params: PlaneParams,
    path: SolverPath,
    /// Condensed step operators by step size (bits of k).
    condensed: BTreeMap<u64, CondensedStep>,
    newton: Option<NewtonStep>,
    static_load: Vec<f64>,
    has_dynamic_load: bool,
}

impl PlaneSolver {
    /// Validates, builds the dofs and chooses the path.
    pub fn new(
        problem: &PlaneProblem,
        grid: TimeGrid,
        scheme: TimeScheme,
        params: PlaneParams,
    ) -> Result<Self, Error> {
        let roles = problem.validate()?;
        if (grid.final_time() - problem.final_time).abs() > 1e-12 * problem.final_time {
            return Err(InputError::new(
                "time.final_time",
                grid.final_time(),
                format!("the final time {}", problem.final_time),
            )
            .into());
        }
        let dofs = PlaneDofs::new(problem, roles)?;
        let path = match (params.path, problem.is_linear()) {
            (SolverPath::Auto, true) | (SolverPath::Condensed, true) => SolverPath::Condensed,
            (SolverPath::Auto, false) | (SolverPath::Newton, _) => SolverPath::Newton,
            (SolverPath::Condensed, false) => {
                return Err(InputError::new(
                    "solver.path",
                    "condensed",
                    "\"newton\" or \"auto\": the condensed path needs linear A and B",
                )
                .into())
            }
        };
        if path == SolverPath::Newton && !dofs.rigid_modes.is_empty() {
            return Err(InputError::new(
                "dirichlet",
                format!("{} rigid motion(s) left free by Γ1", dofs.rigid_modes.len()),
                "a Γ1 that holds every rigid motion for the Newton path (only the condensed path carries a free motion by the contact)",
            )
            .into());
        }
        // u0 must vanish on Γ1.
        for d in 0..2 * dofs.n_nodes {
            if dofs.fixed[d] {
                let p = problem.mesh.nodes()[d / 2];
                let v = problem.initial_displacement[d % 2].eval(p[0], p[1], 0.0);
                if v != 0.0 {
                    return Err(InputError::new(
                        format!("initial_displacement[{}]", d % 2),
                        format!("{v} at ({}, {})", p[0], p[1]),
                        "u0 = 0 on Γ1",
                    )
                    .into());
                }
            }
        }
        let mut static_load = vec![0.0; 2 * dofs.n_nodes];
        dofs.load_into(problem, 0.0, &|f| !f.dependence().t, &mut static_load);
        let has_dynamic_load = problem.body_force.iter().any(|f| f.dependence().t)
            || problem
                .traction
                .iter()
                .any(|t| t.traction.iter().any(|f| f.dependence().t))
            || problem
                .contact
                .as_ref()
                .and_then(|c| c.source.as_ref())
                .is_some_and(|g| g.iter().any(|f| f.dependence().t));
        Ok(Self {
            problem: problem.clone(),
            dofs,
            grid,
            scheme,
            params,
            path,
            condensed: BTreeMap::new(),
            newton: None,
            static_load,
            has_dynamic_load,
        })
    }

    /// The discrete structure.
    pub fn dofs(&self) -> &PlaneDofs {
        &self.dofs
    }

    /// The problem.
    pub fn problem(&self) -> &PlaneProblem {
        &self.problem
    }

    /// The time grid.
    pub fn grid(&self) -> &TimeGrid {
        &self.grid
    }

    /// The scheme.
    pub fn scheme(&self) -> TimeScheme {
        self.scheme
    }

    /// The path the model chose.
    pub fn path(&self) -> SolverPath {
        self.path
    }

    /// The time of one forward-and-backward solve with the factored step operator (the first step
    /// size), best of `repeats`: the reference for the cost of a step.
    pub fn time_sparse_solve(&mut self, repeats: usize) -> Result<f64, SolveError> {
        let k = self.grid.step(1);
        let op = self.condensed_for(k)?;
        Ok(op.time_plain_solve(repeats))
    }

    fn contact_positions(&self) -> Vec<SpaceTime> {
        self.dofs
            .contact_points
            .iter()
            .map(|p| SpaceTime {
                x: p.position[0],
                y: p.position[1],
                t: 0.0,
            })
            .collect()
    }

    /// The step size k_n = t_n − t_{n−1} as the solver uses it: a step within the rounding of the
    /// times, |k − k_c| ≤ 2 ε (|t_n| + |t_{n−1}|), of an already factored size k_c is k_c. A uniform
    /// grid t_n = T n / N stores each t_n rounded to ε t_n, so its step sizes differ by up to
    /// ≈ 2 ε T (500 ε k at N = 1000): without this, each distinct bit pattern would be factored
    /// again (five to nine factorizations of A + θkB for N = 20 … 1000). The change of k is at the
    /// round-off of the times themselves.
    fn step_size(&self, t_prev: f64, t: f64) -> f64 {
        let k = t - t_prev;
        let tol = 2.0 * f64::EPSILON * (t.abs() + t_prev.abs());
        self.condensed
            .values()
            .map(|c| c.k)
            .find(|&kc| (kc - k).abs() <= tol)
            .unwrap_or(k)
    }

    /// The explicit scheme with linear laws is stable while k λ_max(A⁻¹B) < 2, and λ_max is at most
    /// the largest constitutive ratio max(b2/a2, (2b1 + b2)/(2a1 + a2)) over the elements
    /// (docs/quasistatic.md): a largest step at or above 2 / ratio may be unstable, stated here
    /// (the iterates then grow by |1 − kλ| per step; a run long enough overflows into a typed
    /// error, a short one would end quietly).
    fn explicit_step_warning(&self) -> Option<String> {
        if self.scheme != TimeScheme::Explicit || !self.problem.is_linear() {
            return None;
        }
        let ratio = (0..self.problem.mesh.triangles().len())
            .filter_map(|e| {
                let a = self.problem.viscosity_of(e).as_linear()?;
                let b = self.problem.elasticity_of(e).as_linear()?;
                Some(crate::model::quasistatic::plane_stability::constitutive_ratio(a, b))
            })
            .fold(0.0f64, f64::max);
        let k = self.grid.k_max();
        (k * ratio >= 2.0).then(|| {
            format!(
                "explicit scheme: the largest step k = {k:e} is at or above 2 / max(b2/a2, (2b1 + b2)/(2a1 + a2)) = {:e}, \
                 the stability bound's guaranteed range; the iterates may grow by |1 − kλ| per step \
                 (use more steps, or scheme = \"midpoint\" or \"implicit\")",
                2.0 / ratio
            )
        })
    }

    /// The factored condensed operator for step size k (built on first use).
    fn condensed_for(&mut self, k: f64) -> Result<&mut CondensedStep, SolveError> {
        let theta_k = self.scheme.theta() * k;
        let key = if theta_k == 0.0 { 0 } else { k.to_bits() };
        if !self.condensed.contains_key(&key) {
            let problem = &self.problem;
            let linear = |e: usize| match (
                problem.viscosity_of(e).as_linear(),
                problem.elasticity_of(e).as_linear(),
            ) {
                (Some(a), Some(b)) => (*a, *b),
                _ => unreachable!("the condensed path is chosen for linear laws only"),
            };
            let mut values = vec![0.0; self.dofs.pattern.nnz()];
            assemble_linear(
                &self.dofs,
                &self.dofs.pattern,
                |el, e| {
                    let (a, b) = linear(el);
                    let sa = a.apply(e);
                    let sb = b.apply(e);
                    [
                        sa[0] + theta_k * sb[0],
                        sa[1] + theta_k * sb[1],
                        sa[2] + theta_k * sb[2],
                    ]
                },
                &mut values,
            );
            let positions = self.contact_positions();
            let step = CondensedStep::new(&self.dofs, &values, k, &positions)?;
            self.condensed.insert(key, step);
        }
        Ok(self.condensed.get_mut(&key).expect("inserted above"))
    }

    /// F(τ) over all dofs into `out`.
    fn load(&self, tau: f64, out: &mut [f64], work: &mut [f64]) {
        out.copy_from_slice(&self.static_load);
        if self.has_dynamic_load {
            self.dofs
                .load_into(&self.problem, tau, &|f| f.dependence().t, work);
            for (o, w) in out.iter_mut().zip(work.iter()) {
                *o += w;
            }
        }
    }

    /// out −= Σ_e B ε(u) : ε(φ) (all dofs).
    fn subtract_elastic_forces(&self, u: &[f64], out: &mut [f64]) {
        let tri = self.problem.mesh.triangles();
        for (e, el) in self.dofs.elements.iter().enumerate() {
            let b = self.problem.elasticity_of(e);
            let t = tri[e];
            let ul: [f64; 6] = std::array::from_fn(|p| u[2 * t[p / 2] + p % 2]);
            let f = el.internal_forces(&b.stress(&el.strain(&ul)));
            for p in 0..6 {
                out[2 * t[p / 2] + p % 2] -= f[p];
            }
        }
    }

    /// Runs and records the snapshots of `request` and the contact histories
    /// ([`PlaneRecorder`]).
    pub fn solve(&mut self, request: &PlaneOutputRequest) -> Result<PlaneSolution, Error> {
        self.solve_or_partial(request).map_err(|(e, _)| e)
    }

    /// [`Self::solve`], and on a failure of the run the solution recorded up to it (the steps
    /// observed; statistics left at zero) with the error.
    pub fn solve_or_partial(
        &mut self,
        request: &PlaneOutputRequest,
    ) -> Result<PlaneSolution, (Error, Option<Box<PlaneSolution>>)> {
        let mut recorder = PlaneRecorder::new(&self.problem, &self.dofs, &self.grid, request)
            .map_err(|e| (e.into(), None))?;
        match self.run(&mut recorder) {
            Ok(stats) => Ok(recorder.finish(stats)),
            Err(e) => Err((
                e.into(),
                Some(Box::new(recorder.finish(PlaneStats::default()))),
            )),
        }
    }

    /// Runs from t_0 to t_N, calling `observer` at n = 0 and after every step.
    pub fn run(&mut self, observer: &mut impl PlaneObserver) -> Result<PlaneStats, SolveError> {
        let nn = self.dofs.n_nodes;
        let ns = self.dofs.n_solved();
        let nc = self.dofs.contact_points.len();
        let q = self.dofs.rigid_modes.len();
        let mut stats = PlaneStats {
            path: match self.path {
                SolverPath::Newton => "newton",
                _ => "condensed",
            }
            .to_string(),
            dofs: ns,
            contact_points: nc,
            free_rigid_motions: q,
            warnings: self.explicit_step_warning().into_iter().collect(),
            ..Default::default()
        };
        let mut u: Vec<f64> = (0..2 * nn)
            .map(|d| {
                let p = self.problem.mesh.nodes()[d / 2];
                if self.dofs.fixed[d] {
                    0.0
                } else {
                    self.problem.initial_displacement[d % 2].eval(p[0], p[1], 0.0)
                }
            })
            .collect();
        if let Some(d) = u.iter().position(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite {
                step: 0,
                time: 0.0,
                quantity: format!("initial displacement at node {}", d / 2),
                value: u[d],
                hint: String::new(),
            });
        }
        let mut w_full = vec![0.0; 2 * nn];
        let mut w = vec![0.0; ns];
        let mut r = vec![0.0; nc];
        let mut pressures = vec![0.0; nc];
        let mut alpha = vec![0.0; q];
        let mut b_full = vec![0.0; 2 * nn];
        let mut b = vec![0.0; ns];
        let mut work = vec![0.0; 2 * nn];
        observer.observe(&PlaneStep {
            n: 0,
            t: self.grid.times()[0],
            data_time: self.grid.times()[0],
            k: 0.0,
            u: &u,
            w: None,
            contact_velocity: &r,
            contact_pressure: &pressures,
            newton_iterations: 0,
            skipped: false,
        });
        let mut started = false;
        // Why the last skipped step had no equilibrium (a run that skips every step is an error).
        let mut last_skip: Option<(usize, f64, String)> = None;
        for n in 1..=self.grid.steps() {
            let t_prev = self.grid.times()[n - 1];
            let t = self.grid.times()[n];
            crate::run_control::check(|| format!("step {n} of {} (t = {t})", self.grid.steps()))?;
            crate::run_control::report_progress("steps", n as u64, self.grid.steps() as u64);
            let k = self.step_size(t_prev, t);
            let tau = self.scheme.data_time(t_prev, t);
            self.load(tau, &mut b_full, &mut work);
            // the Newton iterations of the step, or None for a step skipped before the first
            // equilibrium
            let iterations = match self.path {
                SolverPath::Newton => {
                    if self.newton.is_none() {
                        self.newton = Some(NewtonStep::new(&self.dofs)?);
                    }
                    let theta_k = self.scheme.theta() * k;
                    let newton = self.newton.as_mut().expect("created above");
                    let before = newton.factorizations;
                    let it = newton
                        .solve(
                            &self.problem,
                            &self.dofs,
                            &u,
                            theta_k,
                            &b_full,
                            tau,
                            &mut w,
                            &self.params.newton,
                        )
                        .map_err(|e| match e {
                            NewtonFailure::NotConverged {
                                iterations,
                                residual,
                                floor,
                            } => SolveError::NewtonNotConverged {
                                step: n,
                                time: t,
                                iterations,
                                residual,
                                // the effective threshold: the floor where it is above the tolerance
                                tolerance: self.params.newton.relative_tolerance.max(floor),
                            },
                            NewtonFailure::Singular(e) => e,
                            NewtonFailure::Stopped(SolveError::Stopped { at, reason }) => {
                                SolveError::Stopped {
                                    at: format!(
                                        "step {n} of {} (t = {t}), {at}",
                                        self.grid.steps()
                                    ),
                                    reason,
                                }
                            }
                            NewtonFailure::Stopped(e) => e,
                            NewtonFailure::NonFinite => SolveError::NonFinite {
                                step: n,
                                time: t,
                                quantity: "Newton residual".into(),
                                value: f64::NAN,
                                hint: String::new(),
                            },
                        })?;
                    stats.factorizations += newton.factorizations - before;
                    stats.floor_stops = newton.floor_stops;
                    // contact state for the observer
                    if let Some(c) = &self.problem.contact {
                        for (g, pt) in self.dofs.contact_points.iter().enumerate() {
                            r[g] = pt
                                .entries
                                .iter()
                                .map(|&(d, coef)| {
                                    coef * self.dofs.solved[d].map(|s| w[s]).unwrap_or(0.0)
                                })
                                .sum();
                            let at = SpaceTime {
                                x: pt.position[0],
                                y: pt.position[1],
                                t: tau,
                            };
                            pressures[g] = c.law.value(r[g], at);
                        }
                    }
                    for (d, wf) in w_full.iter_mut().enumerate() {
                        *wf = self.dofs.solved[d].map(|s| w[s]).unwrap_or(0.0);
                    }
                    Some(it)
                }
                _ => {
                    self.subtract_elastic_forces(&u, &mut b_full);
                    for (s, &d) in self.dofs.solved_dofs.iter().enumerate() {
                        b[s] = b_full[d];
                    }
                    let b_rigid: Vec<f64> = self
                        .dofs
                        .rigid_modes
                        .iter()
                        .map(|m| {
                            m.iter()
                                .zip(&b_full)
                                .zip(&self.dofs.fixed)
                                .filter(|(_, f)| !**f)
                                .map(|((a, b), _)| a * b)
                                .sum()
                        })
                        .collect();
                    let law = self.problem.contact.as_ref().map(|c| c.law.clone());
                    let params = self.params.contact_newton;
                    let factored_before = self.condensed.len();
                    let op = self.condensed_for(k)?;
                    let outcome =
                        op.solve(law.as_deref(), tau, &b, &b_rigid, &mut w, &alpha, &params);
                    stats.factor_nnz = op.nnz();
                    let contact_fact = op.contact.factorizations;
                    pressures.copy_from_slice(&op.contact.pressures()[..nc]);
                    r.copy_from_slice(&op.contact.velocities()[..nc]);
                    if self.condensed.len() > factored_before {
                        stats.factorizations += 1;
                    }
                    stats.contact_factorizations = stats.contact_factorizations.max(contact_fact);
                    stats.floor_stops =
                        self.condensed.values().map(|c| c.contact.floor_stops).sum();
                    match outcome {
                        Ok((a, it)) => {
                            alpha = a;
                            for (d, wf) in w_full.iter_mut().enumerate() {
                                let mut v = self.dofs.solved[d].map(|s| w[s]).unwrap_or(0.0);
                                for (j, mode) in self.dofs.rigid_modes.iter().enumerate() {
                                    v += alpha[j] * mode[d];
                                }
                                *wf = v;
                            }
                            Some(it)
                        }
                        Err(ContactFailure::NoEquilibrium(reason)) => {
                            if self.params.start_at_first_equilibrium && !started {
                                last_skip = Some((n, t, reason));
                                None
                            } else {
                                return Err(SolveError::NoEquilibrium {
                                    step: n,
                                    time: t,
                                    reason,
                                });
                            }
                        }
                        Err(ContactFailure::NotConverged {
                            iterations,
                            residual,
                            floor,
                        }) => {
                            return Err(SolveError::NewtonNotConverged {
                                step: n,
                                time: t,
                                iterations,
                                residual,
                                // the effective threshold: the floor where it is above the tolerance
                                tolerance: params.relative_tolerance.max(floor),
                            });
                        }
                        Err(ContactFailure::NonFinite) => {
                            return Err(SolveError::NonFinite {
                                step: n,
                                time: t,
                                quantity: "condensed contact problem".into(),
                                value: f64::NAN,
                                hint: String::new(),
                            })
                        }
                    }
                }
            };
            match iterations {
                None => {
                    stats.skipped_steps.push(n);
                    w_full.iter_mut().for_each(|v| *v = 0.0);
                    r.iter_mut().for_each(|v| *v = 0.0);
                }
                Some(iterations) => {
                    started = true;
                    let mut finite = true;
                    for (ui, wi) in u.iter_mut().zip(&w_full) {
                        *ui += k * wi;
                        finite &= ui.abs() < f64::INFINITY;
                    }
                    if !finite {
                        let (bound, hint) = (self.scheme == TimeScheme::Explicit, "; the explicit scheme is stable only for k λ_max(A⁻¹B) < 2: use a smaller step or the implicit or midpoint scheme");
                        return Err(SolveError::NonFinite {
                            step: n,
                            time: t,
                            quantity: "displacement u_n".into(),
                            value: u
                                .iter()
                                .copied()
                                .find(|v| !v.is_finite())
                                .unwrap_or(f64::NAN),
                            hint: if bound {
                                hint.to_string()
                            } else {
                                String::new()
                            },
                        });
                    }
                    stats.newton_iterations += iterations;
                    stats.max_newton_iterations = stats.max_newton_iterations.max(iterations);
                }
            }
            stats.steps += 1;
            observer.observe(&PlaneStep {
                n,
                t,
                data_time: tau,
                k,
                u: &u,
                w: Some(&w_full),
                contact_velocity: &r,
                contact_pressure: &pressures,
                newton_iterations: iterations.unwrap_or(0),
                skipped: iterations.is_none(),
            });
        }
        if let Some(nt) = &self.newton {
            stats.factor_nnz = stats.factor_nnz.max(nt.nnz());
        }
        // Every step skipped: nothing was solved, and an all-zero solution must not pass for one.
        if let (false, Some((step, time, reason))) = (started, last_skip) {
            return Err(SolveError::NoEquilibrium {
                step,
                time,
                reason: format!(
                    "no step of the run has an equilibrium (all {} skipped with \
                     start_at_first_equilibrium); the last: {reason}",
                    stats.skipped_steps.len()
                ),
            });
        }
        Ok(stats)
    }
}
