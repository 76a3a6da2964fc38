//! The nonlinear path: a full semismooth Newton method with a line search on the whole system,
//! for nonlinear A or B. Each iteration assembles the residual
//!
//!   R(w) = Σ_e [A(ε(w)) + B(ε(u_{n−1} + θ k w))] : ε(φ) + Cᵀ W p_ν(C w) − F(τ)
//!
//! and the generalized Jacobian J = K_A(w) + θ k K_B + Cᵀ W diag(p_ν'(C w)) C on the element
//! pattern (the contact couples only the dofs of one edge), refactors J numerically on the symbolic
//! analysis done once, and backtracks on ‖R‖ (Armijo).

use crate::contact::normal_law::SpaceTime;
use crate::error::SolveError;
use crate::fem::triangle_p1::Sym2;
use crate::model::quasistatic::plane::PlaneProblem;
use crate::model::quasistatic::plane_dofs::PlaneDofs;
use crate::solve::sparse_cholesky::{CholeskyWorkspace, SparseCholesky};

/// Parameters of the full Newton method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonParams {
    /// Stop when ‖R‖∞ ≤ tolerance · (‖F‖∞ + ‖internal forces‖∞ + ‖contact forces‖∞), or at the
    /// residual's round-off floor (see [`NewtonStep`]).
    pub relative_tolerance: f64,
    pub max_iterations: usize,
}

impl Default for NewtonParams {
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-11,
            max_iterations: 50,
        }
    }
}

/// The assembled state of one Newton path.
#[derive(Debug)]
pub struct NewtonStep {
    chol: SparseCholesky,
    ws: CholeskyWorkspace,
    jac: Vec<f64>,
    res: Vec<f64>,
    dw: Vec<f64>,
    trial: Vec<f64>,
    pub factorizations: usize,
    /// The round-off floor of ‖R‖∞ relative to its scale: (√q + 2) ε, q the largest number of
    /// terms summed into one row (element forces, contact forces, the load).
    floor: f64,
    /// Solves stopped at the round-off floor (no decrease along the Newton direction).
    pub floor_stops: usize,
}

/// Where a Newton solve stopped.
#[derive(Debug, Clone, PartialEq)]
pub enum NewtonFailure {
    /// `residual` and `floor` relative to the residual's scale.
    NotConverged {
        iterations: usize,
        residual: f64,
        floor: f64,
    },
    Singular(SolveError),
    NonFinite,
    /// The run's stop request ([`crate::run_control::check`]) at an iteration: a step of a large
    /// mesh can take many seconds of iterations, each checks.
    Stopped(SolveError),
}

impl NewtonStep {
    /// The symbolic analysis of the element pattern.
    pub fn new(dofs: &PlaneDofs) -> Result<Self, SolveError> {
        let chol = SparseCholesky::analyze(&dofs.pattern, &[], "Newton Jacobian")?;
        let n = dofs.n_solved();
        let ws = chol.workspace(1);
        let mut terms = vec![1usize; n];
        for el in &dofs.element_dofs {
            for i in el.iter().flatten() {
                terms[*i] += 1;
            }
        }
        for pt in &dofs.contact_points {
            for &(d, _) in &pt.entries {
                if let Some(i) = dofs.solved[d] {
                    terms[i] += 1;
                }
            }
        }
        let q = terms.iter().copied().max().unwrap_or(1) as f64;
        Ok(Self {
            chol,
            ws,
            jac: vec![0.0; dofs.pattern.nnz()],
            res: vec![0.0; n],
            dw: vec![0.0; n],
            trial: vec![0.0; n],
            factorizations: 0,
            floor: (q.sqrt() + 2.0) * f64::EPSILON,
            floor_stops: 0,
        })
    }

    /// Stored entries of the Jacobian's Cholesky factor.
    pub fn nnz(&self) -> usize {
        self.chol.factor_nnz()
    }

    /// R(w) into `self.res` (solved dofs) and, if `jacobian`, J into `self.jac`. Returns the
    /// residual scale.
    #[allow(clippy::too_many_arguments)]
    fn assemble(
        &mut self,
        problem: &PlaneProblem,
        dofs: &PlaneDofs,
        u_prev: &[f64],
        w: &[f64],
        theta_k: f64,
        load: &[f64],
        tau: f64,
        jacobian: bool,
    ) -> f64 {
        let tri = problem.mesh.triangles();
        self.res.iter_mut().for_each(|v| *v = 0.0);
        if jacobian {
            self.jac.iter_mut().for_each(|v| *v = 0.0);
        }
        let value = |x: &[f64], d: usize| dofs.solved[d].map(|s| x[s]).unwrap_or(0.0);
        let mut internal_scale = 0.0f64;
        for (e, el) in dofs.elements.iter().enumerate() {
            let t = tri[e];
            let mut wl = [0.0; 6];
            let mut ul = [0.0; 6];
            for p in 0..6 {
                let d = 2 * t[p / 2] + p % 2;
                wl[p] = value(w, d);
                ul[p] = u_prev[d] + theta_k * wl[p];
            }
            let (ew, eu) = (el.strain(&wl), el.strain(&ul));
            let (law_a, law_b) = (problem.viscosity_of(e), problem.elasticity_of(e));
            let sa = law_a.stress(&ew);
            let sb = law_b.stress(&eu);
            let s: Sym2 = [sa[0] + sb[0], sa[1] + sb[1], sa[2] + sb[2]];
            let f = el.internal_forces(&s);
            for p in 0..6 {
                if let Some(i) = dofs.element_dofs[e][p] {
                    self.res[i] += f[p];
                    internal_scale = internal_scale.max(f[p].abs());
                }
            }
            if jacobian {
                let k = el.stiffness(|d| {
                    let a = law_a.tangent_apply(&ew, d);
                    let b = law_b.tangent_apply(&eu, d);
                    [
                        a[0] + theta_k * b[0],
                        a[1] + theta_k * b[1],
                        a[2] + theta_k * b[2],
                    ]
                });
                dofs.pattern
                    .add_element(&mut self.jac, e, k.transpose().as_slice());
            }
        }
        let mut contact_scale = 0.0f64;
        if let Some(c) = &problem.contact {
            let law = c.law.as_ref();
            for pt in &dofs.contact_points {
                let r: f64 = pt.entries.iter().map(|&(d, coef)| coef * value(w, d)).sum();
                let at = SpaceTime {
                    x: pt.position[0],
                    y: pt.position[1],
                    t: tau,
                };
                let p = law.value(r, at);
                let dp = law.derivative(r, at);
                for &(d, coef) in &pt.entries {
                    if let Some(i) = dofs.solved[d] {
                        self.res[i] += pt.weight * p * coef;
                        contact_scale = contact_scale.max((pt.weight * p * coef).abs());
                    }
                }
                if jacobian && dp != 0.0 {
                    for &(d1, c1) in &pt.entries {
                        for &(d2, c2) in &pt.entries {
                            if let (Some(i), Some(j)) = (dofs.solved[d1], dofs.solved[d2]) {
                                if i <= j {
                                    if let Some(slot) = dofs.pattern.slot(i, j) {
                                        self.jac[slot] += pt.weight * dp * c1 * c2;
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        let mut load_scale = 0.0f64;
        for (s, &d) in dofs.solved_dofs.iter().enumerate() {
            self.res[s] -= load[d];
            load_scale = load_scale.max(load[d].abs());
        }
        internal_scale + contact_scale + load_scale
    }

    /// Solves R(w) = 0 from the guess in `w` (solved dofs). Returns the iteration count.
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        problem: &PlaneProblem,
        dofs: &PlaneDofs,
        u_prev: &[f64],
        theta_k: f64,
        load: &[f64],
        tau: f64,
        w: &mut [f64],
        params: &NewtonParams,
    ) -> Result<usize, NewtonFailure> {
        let norm = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for it in 0..=params.max_iterations {
            crate::run_control::check(|| format!("Newton iteration {it}"))
                .map_err(NewtonFailure::Stopped)?;
            let scale = self.assemble(problem, dofs, u_prev, w, theta_k, load, tau, true);
            let r0 = norm(&self.res);
            if !r0.is_finite() {
                return Err(NewtonFailure::NonFinite);
            }
            let relative = r0 / scale.max(f64::MIN_POSITIVE);
            if relative <= params.relative_tolerance {
                return Ok(it);
            }
            if relative <= self.floor {
                self.floor_stops += 1;
                return Ok(it);
            }
            if it == params.max_iterations {
                return Err(NewtonFailure::NotConverged {
                    iterations: it,
                    residual: relative,
                    floor: self.floor,
                });
            }
            self.chol
                .factor(&dofs.pattern, &self.jac)
                .map_err(NewtonFailure::Singular)?;
            self.factorizations += 1;
            for (d, r) in self.dw.iter_mut().zip(&self.res) {
                *d = -r;
            }
            self.chol.solve_in_place(&mut self.dw, &mut self.ws);
            let r0_2: f64 = self.res.iter().map(|v| v * v).sum::<f64>().sqrt();
            let mut lambda = 1.0;
            loop {
                for i in 0..w.len() {
                    self.trial[i] = w[i] + lambda * self.dw[i];
                }
                let trial = std::mem::take(&mut self.trial);
                self.assemble(problem, dofs, u_prev, &trial, theta_k, load, tau, false);
                self.trial = trial;
                let r1: f64 = self.res.iter().map(|v| v * v).sum::<f64>().sqrt();
                if r1 <= (1.0 - 1e-4 * lambda) * r0_2 {
                    break;
                }
                if lambda < 1e-6 {
                    if r1 >= r0_2 {
                        // No decrease along the Newton direction even at λ = 2⁻²⁰: the residual
                        // is at its round-off, whatever the estimate of the floor says.
                        self.floor_stops += 1;
                        return Ok(it + 1);
                    }
                    break;
                }
                lambda *= 0.5;
            }
            w.copy_from_slice(&self.trial);
        }
        unreachable!("the loop returns")
    }
}
