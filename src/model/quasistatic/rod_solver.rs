//! The fully discrete rod scheme, factored once and condensed onto the contact node.
//!
//! Step n (Fernández & Sofonea 2004, (3.3) for θ = 0): find w_n ∈ V^h with, for all v ∈ V^h,
//!
//!   (a + θ b k_n) (w_n,x, v_x) + b (u_{n−1,x}, v_x) + p_ν(w_n(L), τ_n) v(L) = (f0(τ_n), v),
//!   u_n = u_{n−1} + k_n w_n,
//!
//! i.e. α_n K w_n = F(τ_n) − b K u_{n−1} − p_ν(w_n(L)) e_M with α_n = a + θ b k_n and K the P1
//! stiffness of −d²/dx² with v(0) = 0. Because a and b are scalars, K is the only matrix: it is
//! factored once, and with g = K⁻¹F and z = K⁻¹e_M (z_i = x_i),
//!
//!   w_n = (g(τ_n) − b u_{n−1} − p z) / α_n,   where r = w_n(L) solves the scalar equation
//!   r + (z_M/α_n) p_ν(r, τ_n) = (g_M(τ_n) − b u_{n−1,M}) / α_n,
//!
//! which is strictly increasing in r and solved to round-off by semismooth Newton. A step is then
//! one fused pass over the M nodal values (no solve at all when the load does not depend on x and
//! t jointly).

use crate::contact::normal_law::SpaceTime;
use crate::error::{Error, InputError, SolveError};
use crate::fem::p1_interval::{constant_load_vector_into, load_vector_into, stiffness_tridiagonal};
use crate::fem::quadrature::GaussLegendre;
use crate::mesh::interval::IntervalMesh;
use crate::model::quasistatic::rod::RodProblem;
use crate::model::quasistatic::rod_output::{RodOutputRequest, RodRecorder, RodSolution};
pub use crate::model::quasistatic::rod_step::{RodObserver, RodStats, RodStep};
use crate::model::quasistatic::scheme::TimeScheme;
use crate::solve::scalar_semismooth::{solve_increasing, Evaluation, ScalarNewtonParams};
use crate::solve::tridiagonal::SymmetricTridiagonalLdlt;
use crate::time::grid::TimeGrid;

/// Parameters of the rod solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodParams {
    /// The scalar semismooth Newton method of the contact node.
    pub newton: ScalarNewtonParams,
    /// Also compute, at every t_n, the velocity v_n that the continuous problem assigns to u_n
    /// (one extra condensed solve per step). For the midpoint scheme this is the second-order
    /// velocity at t_n; w_n approximates u̇(t_{n−1/2}).
    pub post_process_velocity: bool,
    /// Gauss points per element for loads that vary in x.
    pub load_quadrature_points: usize,
}

impl Default for RodParams {
    fn default() -> Self {
        Self {
            newton: ScalarNewtonParams::default(),
            post_process_velocity: false,
            load_quadrature_points: 4,
        }
    }
}

impl RodParams {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), InputError> {
        self.newton.validate()?;
        if !(1..=16).contains(&self.load_quadrature_points) {
            return Err(InputError::new(
                "solver.load_quadrature_points",
                self.load_quadrature_points,
                "1 to 16",
            ));
        }
        Ok(())
    }
}

/// How g(τ) = K⁻¹F(τ) is obtained each step.
#[derive(Debug, Clone)]
enum LoadPath {
    /// f0 independent of t: g computed once.
    Static(Vec<f64>),
    /// f0 = φ(t): g(τ) = φ(τ) g1 with g1 = K⁻¹(∫ φ_i dx), computed once.
    TimeScaled(Vec<f64>),
    /// f0 = f0(x, t): F(τ) assembled and solved each step.
    SpaceTime,
}

/// A rod problem discretized in space and time, ready to run.
#[derive(Debug, Clone)]
pub struct RodSolver {
    problem: RodProblem,
    mesh: IntervalMesh,
    grid: TimeGrid,
    scheme: TimeScheme,
    params: RodParams,
    factor: SymmetricTridiagonalLdlt,
    quadrature: GaussLegendre,
    /// z = K⁻¹ e_M on nodes 0..M (z_0 = 0).
    z: Vec<f64>,
    load: LoadPath,
    setup_solves: usize,
}

impl RodSolver {
    /// Validates the data, factors the stiffness once and precomputes z and, where the load allows,
    /// g.
    pub fn new(
        problem: &RodProblem,
        mesh: IntervalMesh,
        grid: TimeGrid,
        scheme: TimeScheme,
        params: RodParams,
    ) -> Result<Self, Error> {
        problem.validate()?;
        params.validate()?;
        let tol = 1e-12;
        if (mesh.length() - problem.length).abs() > tol * problem.length {
            return Err(InputError::new(
                "mesh.length",
                mesh.length(),
                format!("the rod length {}", problem.length),
            )
            .into());
        }
        if (grid.final_time() - problem.final_time).abs() > tol * problem.final_time {
            return Err(InputError::new(
                "time.final_time",
                grid.final_time(),
                format!("the final time {}", problem.final_time),
            )
            .into());
        }
        let (diag, off) = stiffness_tridiagonal(&mesh);
        let factor = SymmetricTridiagonalLdlt::factor(&diag, &off, "rod stiffness K")?;
        let quadrature = GaussLegendre::new(params.load_quadrature_points)?;
        let m = mesh.elements();
        let mut z = vec![0.0; m + 1];
        z[m] = 1.0;
        factor.solve_in_place(&mut z[1..]);
        let mut setup_solves = 1;

        let dep = problem.load.dependence();
        let load = if dep.t && dep.on_space() {
            LoadPath::SpaceTime
        } else {
            let mut g = vec![0.0; m + 1];
            if dep.t {
                constant_load_vector_into(&mesh, 1.0, &mut g);
            } else if let Some(c) = problem.load.as_constant() {
                constant_load_vector_into(&mesh, c, &mut g);
            } else {
                let f = &problem.load;
                load_vector_into(&mesh, &quadrature, |x| f.eval(x, 0.0, 0.0), &mut g);
                if let Some(i) = g.iter().position(|v| !v.is_finite()) {
                    return Err(InputError::new(
                        "rod.load",
                        &problem.load,
                        format!(
                            "a load that is finite on (0, L) (not near x = {})",
                            mesh.nodes()[i]
                        ),
                    )
                    .into());
                }
            }
            g[0] = 0.0;
            factor.solve_in_place(&mut g[1..]);
            setup_solves += 1;
            if dep.t {
                LoadPath::TimeScaled(g)
            } else {
                LoadPath::Static(g)
            }
        };
        Ok(Self {
            problem: problem.clone(),
            mesh,
            grid,
            scheme,
            params,
            factor,
            quadrature,
            z,
            load,
            setup_solves,
        })
    }

    /// The mesh.
    pub fn mesh(&self) -> &IntervalMesh {
        &self.mesh
    }

    /// The time grid.
    pub fn grid(&self) -> &TimeGrid {
        &self.grid
    }

    /// The scheme.
    pub fn scheme(&self) -> TimeScheme {
        self.scheme
    }

    /// The problem.
    pub fn problem(&self) -> &RodProblem {
        &self.problem
    }

    /// Runs and records the contact-end histories, the probes and the snapshots of `request`
    /// ([`RodRecorder`]).
    pub fn solve(&self, request: &RodOutputRequest) -> Result<RodSolution, Error> {
        let mut recorder = RodRecorder::new(&self.mesh, &self.grid, self.scheme, request)?;
        let stats = self.run(&mut recorder)?;
        Ok(recorder.finish(stats))
    }

    /// Runs the scheme from t_0 to t_N, calling `observer` at n = 0 and after every step.
    pub fn run(&self, observer: &mut impl RodObserver) -> Result<RodStats, SolveError> {
        let m = self.mesh.elements();
        let nodes = self.mesh.nodes();
        let a = self.problem.viscosity;
        let b = self.problem.elasticity;
        let theta = self.scheme.theta();
        let law = self.problem.foundation.as_ref();
        let bound = self.problem.explicit_stability_bound();

        let mut stats = RodStats {
            factorizations: 1,
            stiffness_solves: self.setup_solves,
            load_path: match self.load {
                LoadPath::Static(_) => "static",
                LoadPath::TimeScaled(_) => "time_scaled",
                LoadPath::SpaceTime => "space_time",
            }
            .to_string(),
            explicit_stability_bound: (self.scheme == TimeScheme::Explicit).then_some(bound),
            ..Default::default()
        };

        let mut u: Vec<f64> = nodes
            .iter()
            .map(|&x| self.problem.initial_displacement.eval(x, 0.0, 0.0))
            .collect();
        if let Some(i) = u.iter().position(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite {
                step: 0,
                time: 0.0,
                quantity: format!("initial displacement at x = {}", nodes[i]),
                value: u[i],
                hint: String::new(),
            });
        }
        u[0] = 0.0;
        let mut w = vec![0.0; m + 1];
        let mut v = vec![0.0; m + 1];
        let mut work = vec![0.0; m + 1];

        // n = 0: the consistent initial velocity v_0 from u_0.
        let t0 = self.grid.times()[0];
        let (r0, it0) = self.velocity_at(0, t0, &u, &mut v, &mut work, &mut stats)?;
        let at0 = SpaceTime {
            x: self.problem.length,
            y: 0.0,
            t: t0,
        };
        observer.observe(&RodStep {
            n: 0,
            t: t0,
            data_time: t0,
            k: 0.0,
            nodes,
            u: &u,
            w: None,
            v: Some(&v),
            contact_velocity: r0,
            contact_stress: -law.value(r0, at0),
            newton_iterations: it0,
        });

        let mut r = r0;
        for n in 1..=self.grid.steps() {
            let t_prev = self.grid.times()[n - 1];
            let t = self.grid.times()[n];
            crate::run_control::check(|| format!("step {n} of {} (t = {t})", self.grid.steps()))?;
            crate::run_control::report_progress("steps", n as u64, self.grid.steps() as u64);
            let k = t - t_prev;
            let tau = self.scheme.data_time(t_prev, t);
            if self.scheme == TimeScheme::Explicit && k >= bound {
                stats.steps_above_stability_bound += 1;
            }
            let alpha = a + theta * b * k;
            let (g, s) = self.load_at(n, tau, &mut work, &mut stats)?;
            let at = SpaceTime {
                x: self.problem.length,
                y: 0.0,
                t: tau,
            };
            let w_star = (s * g[m] - b * u[m]) / alpha;
            let (root, iterations) = self.contact_root(n, t, w_star, self.z[m] / alpha, at, r)?;
            r = root;
            stats.newton_iterations += iterations;
            stats.max_newton_iterations = stats.max_newton_iterations.max(iterations);
            if law.derivative(r, at) > 0.0 {
                stats.active_contact_steps += 1;
            }
            let p = law.value(r, at);
            let finite = step_kernel(
                &mut u[1..],
                &mut w[1..],
                &g[1..],
                &self.z[1..],
                s,
                b,
                1.0 / alpha,
                p,
                k,
            );
            if !finite {
                // The velocity first; a finite w_n can still overflow u_n = u_{n−1} + k w_n.
                let first = |x: &[f64]| x.iter().copied().find(|v| !v.is_finite());
                let (quantity, value) = match (first(&w), first(&u)) {
                    (Some(v), _) => ("velocity w_n", v),
                    (None, Some(v)) => ("displacement u_n", v),
                    (None, None) => ("velocity w_n", f64::NAN),
                };
                let hint = if self.scheme == TimeScheme::Explicit && k >= bound {
                    format!(
                        "; the explicit step k = {k} is above the stability bound 2a/b = {bound}: \
                         use a smaller step or the implicit or midpoint scheme"
                    )
                } else {
                    String::new()
                };
                return Err(SolveError::NonFinite {
                    step: n,
                    time: t,
                    quantity: quantity.to_string(),
                    value,
                    hint,
                });
            }
            let (v_out, v_it) = if self.params.post_process_velocity {
                let (_, it) = self.velocity_at(n, t, &u, &mut v, &mut work, &mut stats)?;
                (Some(v.as_slice()), it)
            } else {
                (None, 0)
            };
            stats.steps += 1;
            observer.observe(&RodStep {
                n,
                t,
                data_time: tau,
                k,
                nodes,
                u: &u,
                w: Some(&w),
                v: v_out,
                contact_velocity: r,
                contact_stress: -p,
                newton_iterations: iterations + v_it,
            });
        }
        Ok(stats)
    }

    /// g(τ) = K⁻¹F(τ) as (vector, scale): the vector is precomputed unless the load depends on
    /// both x and t, in which case it is assembled into `work` and solved.
    fn load_at<'s>(
        &'s self,
        n: usize,
        tau: f64,
        work: &'s mut [f64],
        stats: &mut RodStats,
    ) -> Result<(&'s [f64], f64), SolveError> {
        match &self.load {
            LoadPath::Static(g) => Ok((g, 1.0)),
            LoadPath::TimeScaled(g1) => {
                let s = self.problem.load.eval(0.0, 0.0, tau);
                if !s.is_finite() {
                    return Err(non_finite_load(n, tau, s));
                }
                Ok((g1, s))
            }
            LoadPath::SpaceTime => {
                let f = &self.problem.load;
                load_vector_into(&self.mesh, &self.quadrature, |x| f.eval(x, 0.0, tau), work);
                let sum: f64 = work.iter().sum();
                if !sum.is_finite() {
                    return Err(non_finite_load(n, tau, sum));
                }
                work[0] = 0.0;
                self.factor.solve_in_place(&mut work[1..]);
                stats.stiffness_solves += 1;
                Ok((work, 1.0))
            }
        }
    }

    /// Solves r + c p_ν(r, τ) = w* for the contact node.
    fn contact_root(
        &self,
        n: usize,
        t: f64,
        w_star: f64,
        c: f64,
        at: SpaceTime,
        guess: f64,
    ) -> Result<(f64, usize), SolveError> {
        let law = self.problem.foundation.as_ref();
        let root = solve_increasing(
            |r| {
                let p = law.value(r, at);
                Evaluation {
                    value: r + c * p - w_star,
                    slope: 1.0 + c * law.derivative(r, at),
                    scale: r.abs() + (c * p).abs() + w_star.abs(),
                }
            },
            guess,
            &self.params.newton,
        );
        match root {
            Ok(root) => Ok((root.r, root.iterations)),
            Err(e) if !e.residual.is_finite() => Err(SolveError::NonFinite {
                step: n,
                time: t,
                quantity: "contact equation residual".to_string(),
                value: e.residual,
                hint: String::new(),
            }),
            Err(e) => Err(SolveError::NewtonNotConverged {
                step: n,
                time: t,
                iterations: e.iterations,
                residual: e.residual,
                tolerance: e.tolerance,
            }),
        }
    }

    /// The velocity that the continuous problem assigns to the displacement `u` at time t:
    /// a K v + b K u + p_ν(v(L), t) e_M = F(t), written into `v`. Returns (v(L), iterations).
    fn velocity_at(
        &self,
        n: usize,
        t: f64,
        u: &[f64],
        v: &mut [f64],
        work: &mut [f64],
        stats: &mut RodStats,
    ) -> Result<(f64, usize), SolveError> {
        let m = self.mesh.elements();
        let a = self.problem.viscosity;
        let b = self.problem.elasticity;
        let (g, s) = self.load_at(n, t, work, stats)?;
        let at = SpaceTime {
            x: self.problem.length,
            y: 0.0,
            t,
        };
        let w_star = (s * g[m] - b * u[m]) / a;
        let (r, it) = self.contact_root(n, t, w_star, self.z[m] / a, at, w_star)?;
        stats.newton_iterations += it;
        stats.max_newton_iterations = stats.max_newton_iterations.max(it);
        let p = self.problem.foundation.value(r, at);
        let inv_a = 1.0 / a;
        v[0] = 0.0;
        for i in 1..=m {
            v[i] = (s * g[i] - b * u[i] - p * self.z[i]) * inv_a;
        }
        Ok((r, it))
    }
}

fn non_finite_load(n: usize, t: f64, value: f64) -> SolveError {
    SolveError::NonFinite {
        step: n,
        time: t,
        quantity: "load f0".to_string(),
        value,
        hint: String::new(),
    }
}

/// One fused pass: w_i = (s g_i − b u_i − p z_i)/α, u_i ← u_i + k w_i. Returns whether every w_i
/// and every new u_i is finite (an and-reduction, which vectorizes, unlike a floating-point sum):
/// near overflow a finite w_i can still make u_i infinite, which must not reach an observer, so
/// the test is on u_i.
#[allow(clippy::too_many_arguments)]
#[inline]
fn step_kernel(
    u: &mut [f64],
    w: &mut [f64],
    g: &[f64],
    z: &[f64],
    s: f64,
    b: f64,
    inv_alpha: f64,
    p: f64,
    k: f64,
) -> bool {
    let n = u.len();
    let (w, g, z) = (&mut w[..n], &g[..n], &z[..n]);
    let mut finite = true;
    for i in 0..n {
        let wi = (s * g[i] - b * u[i] - p * z[i]) * inv_alpha;
        w[i] = wi;
        u[i] += k * wi;
        // k > 0 and u_{n−1} finite: a non-finite w_i makes u_i non-finite, so u_i tests both.
        finite &= u[i].abs() < f64::INFINITY;
    }
    finite
}
