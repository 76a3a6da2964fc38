//! The step equation seen by the semismooth Newton method: the body part R_b(d) of the residual
//! as a function of the step increment d = u_n − u_{n−1}, its (symmetric) Jacobian, and linear
//! solves with some increments prescribed (active constraints eliminated).
//!
//! Every scheme's step equation has the form (see [`crate::model::dynamic::scheme`])
//!
//!   R(d) = α M d + F̄(d) − b − ξ(d) = 0,
//!
//! α = 4/k² (Newmark) or 2/k² (midpoint rule, Gonzalez), F̄ the scheme's internal force, b the
//! step's constant data and ξ the contact forces (added by the Newton method). Two operators:
//!
//! - [`FullStep`]: all free dofs, the Jacobian α M + θ K_T assembled into the body's sparse pattern
//!   and factored with a symbolic analysis done once (numeric refactorization per iteration);
//! - [`CondensedStep`]: a linear body, where A = α M + θ K is factored once with the contact dofs
//!   last and the step is condensed onto them: with A = L Lᵀ, y = L⁻¹ b and C = L_ΓΓ L_ΓΓᵀ (the
//!   Schur complement on the contact dofs Γ) the step equation on Γ is C d_Γ − L_ΓΓ y_Γ − ξ(d_Γ)
//!   = 0, solved densely; the remaining increments follow from one backward pass with
//!   y_Γ ← L_ΓΓᵀ d_Γ. One sparse solve per step whatever the contact does.

use std::sync::Arc;

use faer::linalg::solvers::{Llt, Solve};
use faer::{Mat, Side};

use crate::error::SolveError;
use crate::model::dynamic::body::ElasticBody;
use crate::model::dynamic::scheme::DynamicScheme;
use crate::solve::sparse_cholesky::{CholeskyWorkspace, FactorKind, SparseCholesky};
use crate::solve::sparse_lu::SparseLu;

/// The linearized step equation without its contact terms.
pub trait StepOperator {
    /// Number of unknowns.
    fn len(&self) -> usize;

    /// Whether there are no unknowns.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// r = R_b(d), and in `terms` the sum of the absolute values of the terms of each row of r —
    /// inertia, internal force (with its stress's own round-off scale,
    /// [`ElasticBody::internal_force_terms`]) and the step data b — from which the Newton method
    /// computes the round-off floor of the row; returns the largest term (the scale of the
    /// relative test), or `None` when d gives an inadmissible state (neo-Hooke with det F ≤ 0).
    fn body_residual(&mut self, d: &[f64], r: &mut [f64], terms: &mut [f64]) -> Option<f64>;

    /// Starts the Jacobian at d (the body part).
    fn begin_jacobian(&mut self, d: &[f64]);

    /// Adds v to the diagonal entry of unknown i.
    fn add_diagonal(&mut self, i: usize, v: f64);

    /// The diagonal entry of the body Jacobian at unknown i (the constant operator of a linear
    /// body, or the last Jacobian started).
    fn diagonal(&self, i: usize) -> f64;

    /// Solves J Δ = rhs in place, with Δ_j = c prescribed for each (j, c) in `fixed` (eliminated
    /// symmetrically). Errors on a singular, indefinite or non-finite matrix.
    fn solve(&mut self, fixed: &[(usize, f64)], rhs: &mut [f64]) -> Result<(), SolveError>;

    /// Numeric factorizations so far.
    fn factorizations(&self) -> usize;

    /// Of those, the factorizations of an indefinite matrix (LBLᵀ instead of LLᵀ).
    fn indefinite_factorizations(&self) -> usize {
        0
    }
}

/// Where F̄ is evaluated and with which tangent weight θ.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Evaluation {
    /// F_int(u_{n−1} + d), θ = 1 (Newmark).
    End,
    /// F_int(u_{n−1} + d/2), θ = 1/2 (midpoint rule).
    Midpoint,
    /// F^algo(u_{n−1}, u_{n−1} + d) (Gonzalez).
    DiscreteGradient,
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// The full step operator on all free dofs.
#[derive(Debug)]
pub struct FullStep {
    body: Arc<dyn ElasticBody>,
    evaluation: Evaluation,
    alpha: f64,
    /// u_{n−1} and the step's constant data b.
    u_prev: Vec<f64>,
    b: Vec<f64>,
    /// α M (+ θ K for a linear body) and the current Jacobian.
    base: Vec<f64>,
    values: Vec<f64>,
    chol: SparseCholesky,
    ws: CholeskyWorkspace,
    scratch_u: Vec<f64>,
    scratch_f: Vec<f64>,
    scratch_rhs: Vec<f64>,
    /// u_{n−1} + d of the last Jacobian, and the exact tangent's skew part there with its LU
    /// (Gonzalez on a nonlinear body, once the symmetric tangent is indefinite).
    jacobian_u: Vec<f64>,
    skew: Vec<f64>,
    lu: Option<Box<SparseLu>>,
    lu_factorizations: usize,
    /// For each unknown that may be constrained: the (other unknown, slot) entries of its row.
    rows: Vec<Option<Vec<(usize, usize)>>>,
    diag_slots: Vec<usize>,
    factorizations: usize,
    /// |α M + θ K| and |K| (a linear body), |M| (entrywise), the step data's row terms
    /// |b_i| + Σ_j |K_ij u_{n−1,j}| (a linear body) and scratch for |d| and force terms.
    abs_base: Vec<f64>,
    abs_stiffness: Vec<f64>,
    abs_mass: Vec<f64>,
    b_terms: Vec<f64>,
    scratch_abs: Vec<f64>,
    scratch_terms: Vec<f64>,
}

impl FullStep {
    /// The operator for `scheme` with step k; `constrainable` lists the unknowns that active
    /// constraints may prescribe (the contact dofs).
    pub fn new(
        body: Arc<dyn ElasticBody>,
        scheme: DynamicScheme,
        k: f64,
        constrainable: &[usize],
    ) -> Result<Self, SolveError> {
        let n = body.dofs();
        let pattern = body.pattern().clone();
        let (alpha, theta, evaluation) = match scheme {
            DynamicScheme::Newmark => (4.0 / (k * k), 1.0, Evaluation::End),
            DynamicScheme::Midpoint => (2.0 / (k * k), 0.5, Evaluation::Midpoint),
            DynamicScheme::Gonzalez => (2.0 / (k * k), 0.5, Evaluation::DiscreteGradient),
        };
        let mut base: Vec<f64> = body.mass().iter().map(|m| alpha * m).collect();
        if let Some(kv) = body.linear_stiffness() {
            for (b, kk) in base.iter_mut().zip(kv) {
                *b += theta * kk;
            }
        }
        let chol = SparseCholesky::analyze(&pattern, &[], "dynamic step Jacobian αM + θK_T")?;
        let ws = chol.workspace(1);
        let mut rows: Vec<Option<Vec<(usize, usize)>>> = vec![None; n];
        for &j in constrainable {
            rows[j] = Some(Vec::new());
        }
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        for col in 0..n {
            for s in cp[col]..cp[col + 1] {
                let row = ri[s];
                if row == col {
                    continue;
                }
                if let Some(list) = rows[row].as_mut() {
                    list.push((col, s));
                }
                if let Some(list) = rows[col].as_mut() {
                    list.push((row, s));
                }
            }
        }
        let diag_slots = (0..n)
            .map(|i| {
                pattern.diagonal_slot(i).ok_or(SolveError::Singular {
                    operator: "dynamic step Jacobian (no diagonal entry)".into(),
                    row: i,
                    pivot: 0.0,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let values = base.clone();
        let abs_base = base.iter().map(|v| v.abs()).collect();
        let abs_stiffness = body
            .linear_stiffness()
            .map_or_else(Vec::new, |kv| kv.iter().map(|v| v.abs()).collect());
        let abs_mass = body.mass().iter().map(|v| v.abs()).collect();
        Ok(Self {
            body,
            evaluation,
            alpha,
            u_prev: vec![0.0; n],
            b: vec![0.0; n],
            base,
            values,
            chol,
            ws,
            scratch_u: vec![0.0; n],
            scratch_f: vec![0.0; n],
            scratch_rhs: vec![0.0; n],
            jacobian_u: vec![0.0; n],
            skew: Vec::new(),
            lu: None,
            lu_factorizations: 0,
            rows,
            diag_slots,
            factorizations: 0,
            abs_base,
            abs_stiffness,
            abs_mass,
            b_terms: vec![0.0; n],
            scratch_abs: vec![0.0; n],
            scratch_terms: vec![0.0; n],
        })
    }

    /// Sets the step data: u_{n−1} and b. For a linear body F̄(d) = K u_{n−1} + θ K d, so the
    /// constant part −K u_{n−1} is folded into b here.
    pub fn prepare(&mut self, u_prev: &[f64], b: &[f64]) {
        self.u_prev.copy_from_slice(u_prev);
        self.b.copy_from_slice(b);
        for (t, bi) in self.b_terms.iter_mut().zip(b) {
            *t = bi.abs();
        }
        if let Some(k) = self.body.linear_stiffness() {
            self.body
                .pattern()
                .symmetric_mul(k, u_prev, &mut self.scratch_f);
            for (bi, ku) in self.b.iter_mut().zip(&self.scratch_f) {
                *bi -= ku;
            }
            for (a, u) in self.scratch_abs.iter_mut().zip(u_prev) {
                *a = u.abs();
            }
            self.body.pattern().symmetric_mul(
                &self.abs_stiffness,
                &self.scratch_abs,
                &mut self.scratch_terms,
            );
            for (t, ku) in self.b_terms.iter_mut().zip(&self.scratch_terms) {
                *t += ku;
            }
        }
    }

    /// The factor's nonzeros.
    pub fn factor_nnz(&self) -> usize {
        self.chol.factor_nnz()
    }
}

impl StepOperator for FullStep {
    fn len(&self) -> usize {
        self.u_prev.len()
    }

    fn body_residual(&mut self, d: &[f64], r: &mut [f64], terms: &mut [f64]) -> Option<f64> {
        let pattern = self.body.pattern();
        for (a, di) in self.scratch_abs.iter_mut().zip(d) {
            *a = di.abs();
        }
        if self.body.is_linear() {
            pattern.symmetric_mul(&self.base, d, r);
            pattern.symmetric_mul(&self.abs_base, &self.scratch_abs, terms);
            let s = max_abs(r).max(max_abs(&self.b));
            for (ri, bi) in r.iter_mut().zip(&self.b) {
                *ri -= bi;
            }
            for (ti, t) in terms.iter_mut().zip(&self.b_terms) {
                *ti += t;
            }
            return Some(s);
        }
        pattern.symmetric_mul(&self.abs_mass, &self.scratch_abs, terms);
        pattern.symmetric_mul(self.body.mass(), d, r);
        let ok = match self.evaluation {
            Evaluation::End | Evaluation::Midpoint => {
                let w = if self.evaluation == Evaluation::End {
                    1.0
                } else {
                    0.5
                };
                for ((u, p), di) in self.scratch_u.iter_mut().zip(&self.u_prev).zip(d) {
                    *u = p + w * di;
                }
                self.body
                    .internal_force(&self.scratch_u, &mut self.scratch_f)
            }
            Evaluation::DiscreteGradient => {
                for ((u, p), di) in self.scratch_u.iter_mut().zip(&self.u_prev).zip(d) {
                    *u = p + di;
                }
                self.body.discrete_gradient_force(
                    &self.u_prev,
                    &self.scratch_u,
                    &mut self.scratch_f,
                )
            }
        };
        if !ok {
            return None;
        }
        let u0 = if self.evaluation == Evaluation::DiscreteGradient {
            &self.u_prev
        } else {
            &self.scratch_u
        };
        self.body
            .internal_force_terms(u0, &self.scratch_u, &mut self.scratch_terms);
        let mut s: f64 = max_abs(&self.b);
        for i in 0..r.len() {
            let m = self.alpha * r[i];
            s = s.max(m.abs()).max(self.scratch_f[i].abs());
            r[i] = m + self.scratch_f[i] - self.b[i];
            terms[i] = self.alpha * terms[i] + self.scratch_terms[i] + self.b[i].abs();
        }
        Some(s)
    }

    fn begin_jacobian(&mut self, d: &[f64]) {
        self.values.copy_from_slice(&self.base);
        if self.body.is_linear() {
            return;
        }
        match self.evaluation {
            Evaluation::End => {
                for ((u, p), di) in self.scratch_u.iter_mut().zip(&self.u_prev).zip(d) {
                    *u = p + di;
                }
                self.body
                    .add_tangent(&self.scratch_u, 1.0, &mut self.values);
            }
            Evaluation::Midpoint => {
                for ((u, p), di) in self.scratch_u.iter_mut().zip(&self.u_prev).zip(d) {
                    *u = p + 0.5 * di;
                }
                self.body
                    .add_tangent(&self.scratch_u, 0.5, &mut self.values);
            }
            Evaluation::DiscreteGradient => {
                for ((u, p), di) in self.scratch_u.iter_mut().zip(&self.u_prev).zip(d) {
                    *u = p + di;
                }
                self.jacobian_u.copy_from_slice(&self.scratch_u);
                self.body.add_discrete_gradient_tangent(
                    &self.u_prev,
                    &self.scratch_u,
                    1.0,
                    &mut self.values,
                );
            }
        }
    }

    fn add_diagonal(&mut self, i: usize, v: f64) {
        self.values[self.diag_slots[i]] += v;
    }

    fn diagonal(&self, i: usize) -> f64 {
        self.values[self.diag_slots[i]]
    }

    fn solve(&mut self, fixed: &[(usize, f64)], rhs: &mut [f64]) -> Result<(), SolveError> {
        for &(j, c) in fixed {
            let Some(row) = self.rows[j].as_ref() else {
                return Err(SolveError::Singular {
                    operator: "dynamic step Jacobian (constraint on a non-contact dof)".into(),
                    row: j,
                    pivot: f64::NAN,
                });
            };
            for &(i, slot) in row {
                rhs[i] -= self.values[slot] * c;
                self.values[slot] = 0.0;
            }
        }
        for &(j, c) in fixed {
            rhs[j] = self.values[self.diag_slots[j]] * c;
        }
        self.scratch_rhs.copy_from_slice(rhs);
        self.factorizations += 1;
        let exact_is_unsymmetric =
            self.evaluation == Evaluation::DiscreteGradient && !self.body.is_linear();
        let result = if exact_is_unsymmetric {
            self.chol.factor(self.body.pattern(), &self.values)
        } else {
            self.chol
                .factor_symmetric(self.body.pattern(), &self.values)
        };
        match result {
            Ok(()) if self.chol.kind() == FactorKind::Llt => {
                self.chol.solve_in_place(rhs, &mut self.ws);
                return Ok(());
            }
            Ok(()) => {
                self.chol.solve_in_place(rhs, &mut self.ws);
                let pattern = self.body.pattern();
                pattern.symmetric_mul(&self.values, rhs, &mut self.scratch_f);
            }
            Err(SolveError::Singular { pivot, .. }) if exact_is_unsymmetric && pivot.is_nan() => {
                self.solve_exact_tangent(fixed, rhs)?;
            }
            Err(e) => return Err(e),
        }
        // the indefinite paths are accepted by their backward error (LBLᵀ pivots only inside
        // supernodes; an LU pivot can be tiny)
        let (mut r, mut scale) = (0.0f64, max_abs(&self.scratch_rhs));
        for (ax, b) in self.scratch_f.iter().zip(&self.scratch_rhs) {
            r = r.max((ax - b).abs());
            scale = scale.max(ax.abs());
        }
        let accepted = r <= INDEFINITE_BACKWARD_ERROR * scale; // false for NaN
        if !accepted {
            return Err(SolveError::Singular {
                operator: format!(
                    "dynamic step Jacobian αM + θK_T (indefinite; the solve's residual is \
                     {:.1e} of the right-hand side's scale, above {INDEFINITE_BACKWARD_ERROR:.0e})",
                    r / scale
                ),
                row: 0,
                pivot: f64::NAN,
            });
        }
        Ok(())
    }

    fn factorizations(&self) -> usize {
        self.factorizations
    }

    fn indefinite_factorizations(&self) -> usize {
        self.chol.indefinite_factorizations() + self.lu_factorizations
    }
}

impl FullStep {
    /// The Newton step with the exact (unsymmetric) tangent of Gonzalez's discrete gradient,
    /// J = αM + ∂F^algo/∂u1 (+ contact slopes; ∂Π^algo/∂F1 → ½ ∂P/∂F as F1 → F0): the symmetric part is `values` (constraints
    /// already eliminated there), the skew part is assembled at the last Jacobian's state and
    /// eliminated on the same rows; J is factored by sparse LU. Leaves J Δ in `scratch_f`.
    fn solve_exact_tangent(
        &mut self,
        fixed: &[(usize, f64)],
        rhs: &mut [f64],
    ) -> Result<(), SolveError> {
        if self.lu.is_none() {
            self.lu = Some(Box::new(SparseLu::analyze(
                self.body.pattern(),
                "dynamic step Jacobian αM + θ∂F^algo/∂u1 (exact, unsymmetric)",
            )?));
            self.skew = vec![0.0; self.values.len()];
        }
        self.skew.iter_mut().for_each(|w| *w = 0.0);
        self.body
            .add_discrete_gradient_skew(&self.u_prev, &self.jacobian_u, 1.0, &mut self.skew);
        rhs.copy_from_slice(&self.scratch_rhs);
        for &(j, c) in fixed {
            if let Some(row) = self.rows[j].as_ref() {
                // J_ij = S_ij + W_ij above the diagonal (i < j), S_ji − W_ji below it
                for &(i, slot) in row {
                    let sign = if i < j { 1.0 } else { -1.0 };
                    rhs[i] -= sign * self.skew[slot] * c;
                    self.skew[slot] = 0.0;
                }
            }
        }
        for &(j, c) in fixed {
            rhs[j] = self.values[self.diag_slots[j]] * c;
        }
        self.scratch_rhs.copy_from_slice(rhs);
        let Some(lu) = self.lu.as_mut() else {
            unreachable!("analyzed above")
        };
        lu.factor_solve(&self.values, &self.skew, rhs)?;
        lu.mul(rhs, &mut self.scratch_f);
        self.lu_factorizations += 1;
        Ok(())
    }
}

/// The largest relative residual ‖A x − b‖_∞ / max(‖b‖_∞, ‖A x‖_∞) accepted from an indefinite
/// solve (LBLᵀ or LU): a stable solve leaves a few n ε; 1e-8 still gives Newton a direction
/// accurate to 8 digits.
const INDEFINITE_BACKWARD_ERROR: f64 = 1e-8;

/// The step of a linear body condensed onto its contact dofs Γ.
#[derive(Debug)]
pub struct CondensedStep {
    n: usize,
    /// Contact dofs, in the order of the condensed unknowns.
    gamma: Vec<usize>,
    chol: SparseCholesky,
    ws: CholeskyWorkspace,
    /// L_ΓΓ and C = L_ΓΓ L_ΓΓᵀ.
    l_gg: Mat<f64>,
    c: Mat<f64>,
    /// Linear part K (for −K u_{n−1} in b).
    y: Vec<f64>,
    /// L_ΓΓ y_Γ of the current step.
    c0: Vec<f64>,
    /// |L_ΓΓ| |L_ΓΓ|ᵀ (the row terms of forming C) and Σ_j |L_ij y_j| (those of c0): the
    /// round-off scales of the condensed residual's rows.
    abs_c: Mat<f64>,
    c0_terms: Vec<f64>,
    jac: Mat<f64>,
    scratch: Vec<f64>,
    b: Vec<f64>,
    body: Arc<dyn ElasticBody>,
    factorizations: usize,
}

impl CondensedStep {
    /// Factors A = α M + θ K once with the dofs `gamma` last (a linear body only).
    pub fn new(
        body: Arc<dyn ElasticBody>,
        scheme: DynamicScheme,
        k: f64,
        gamma: &[usize],
    ) -> Result<Self, SolveError> {
        let Some(kv) = body.linear_stiffness() else {
            return Err(SolveError::Singular {
                operator: "condensed step (the body is not linear)".into(),
                row: 0,
                pivot: f64::NAN,
            });
        };
        let n = body.dofs();
        let (alpha, theta) = match scheme {
            DynamicScheme::Newmark => (4.0 / (k * k), 1.0),
            DynamicScheme::Midpoint | DynamicScheme::Gonzalez => (2.0 / (k * k), 0.5),
        };
        let a: Vec<f64> = body
            .mass()
            .iter()
            .zip(kv)
            .map(|(m, kk)| alpha * m + theta * kk)
            .collect();
        let mut chol = SparseCholesky::analyze(body.pattern(), gamma, "dynamic step αM + θK")?;
        chol.factor(body.pattern(), &a)?;
        let m = gamma.len();
        // the condensed unknowns in factor order: position − (n − m)
        let mut order: Vec<(usize, usize)> = gamma
            .iter()
            .map(|&g| (chol.position(g) - (n - m), g))
            .collect();
        order.sort_unstable();
        let gamma: Vec<usize> = order.iter().map(|&(_, g)| g).collect();
        let l_gg = chol.trailing_block(m);
        let c = &l_gg * l_gg.transpose();
        let abs_l = Mat::<f64>::from_fn(m, m, |i, j| l_gg[(i, j)].abs());
        let abs_c = &abs_l * abs_l.transpose();
        let ws = chol.workspace(1);
        Ok(Self {
            n,
            gamma,
            chol,
            ws,
            l_gg,
            jac: c.clone(),
            c,
            y: vec![0.0; n],
            c0: vec![0.0; m],
            abs_c,
            c0_terms: vec![0.0; m],
            scratch: vec![0.0; n],
            b: vec![0.0; n],
            body,
            factorizations: 1,
        })
    }

    /// The contact dofs in the order of the condensed unknowns (unknown i is dof `gamma()[i]`).
    pub fn gamma(&self) -> &[usize] {
        &self.gamma
    }

    /// The step data u_{n−1} and b: one forward pass, y = L⁻¹ (b − K u_{n−1}), c0 = L_ΓΓ y_Γ.
    pub fn prepare(&mut self, u_prev: &[f64], b: &[f64]) {
        let kv = self.body.linear_stiffness().unwrap_or(&[]);
        self.body
            .pattern()
            .symmetric_mul(kv, u_prev, &mut self.scratch);
        for ((bi, src), ku) in self.b.iter_mut().zip(b).zip(&self.scratch) {
            *bi = src - ku;
        }
        self.chol.forward(&self.b, &mut self.y, &mut self.ws);
        let m = self.gamma.len();
        let first = self.n - m;
        for i in 0..m {
            let mut s = 0.0;
            let mut abs = 0.0;
            for j in 0..=i {
                let t = self.l_gg[(i, j)] * self.y[first + j];
                s += t;
                abs += t.abs();
            }
            self.c0[i] = s;
            self.c0_terms[i] = abs;
        }
    }

    /// The full increment d from the condensed one: y_Γ ← L_ΓΓᵀ d_Γ, then the backward pass.
    pub fn finish(&mut self, d_gamma: &[f64], d: &mut [f64]) {
        let m = self.gamma.len();
        let first = self.n - m;
        for j in 0..m {
            let mut s = 0.0;
            for i in j..m {
                s += self.l_gg[(i, j)] * d_gamma[i];
            }
            self.y[first + j] = s;
        }
        self.chol.backward(&mut self.y, d, &mut self.ws);
    }

    /// The sparse factor's nonzeros.
    pub fn factor_nnz(&self) -> usize {
        self.chol.factor_nnz()
    }
}

impl StepOperator for CondensedStep {
    fn len(&self) -> usize {
        self.gamma.len()
    }

    fn body_residual(&mut self, d: &[f64], r: &mut [f64], terms: &mut [f64]) -> Option<f64> {
        let m = self.gamma.len();
        let mut s: f64 = max_abs(&self.c0);
        for i in 0..m {
            let mut acc = 0.0;
            let mut abs = 0.0;
            for j in 0..m {
                acc += self.c[(i, j)] * d[j];
                abs += self.abs_c[(i, j)] * d[j].abs();
            }
            s = s.max(acc.abs());
            r[i] = acc - self.c0[i];
            terms[i] = abs + self.c0_terms[i];
        }
        Some(s)
    }

    fn begin_jacobian(&mut self, _d: &[f64]) {
        self.jac.copy_from(&self.c);
    }

    fn add_diagonal(&mut self, i: usize, v: f64) {
        self.jac[(i, i)] += v;
    }

    fn diagonal(&self, i: usize) -> f64 {
        self.c[(i, i)]
    }

    fn solve(&mut self, fixed: &[(usize, f64)], rhs: &mut [f64]) -> Result<(), SolveError> {
        let m = self.gamma.len();
        for &(j, c) in fixed {
            for i in 0..m {
                if i != j {
                    rhs[i] -= self.jac[(i, j)] * c;
                    self.jac[(i, j)] = 0.0;
                    self.jac[(j, i)] = 0.0;
                }
            }
        }
        for &(j, c) in fixed {
            rhs[j] = self.jac[(j, j)] * c;
        }
        if self
            .jac
            .as_ref()
            .col_iter()
            .any(|col| col.iter().any(|v| !v.is_finite()))
        {
            return Err(SolveError::Singular {
                operator: "condensed contact Jacobian (non-finite entry)".into(),
                row: 0,
                pivot: f64::NAN,
            });
        }
        let llt = Llt::new(self.jac.as_ref(), Side::Lower).map_err(|_| SolveError::Singular {
            operator: "condensed contact Jacobian".into(),
            row: 0,
            pivot: f64::NAN,
        })?;
        self.factorizations += 1;
        let mut x = Mat::<f64>::zeros(m, 1);
        for i in 0..m {
            x[(i, 0)] = rhs[i];
        }
        let sol = llt.solve(&x);
        for i in 0..m {
            rhs[i] = sol[(i, 0)];
        }
        Ok(())
    }

    fn factorizations(&self) -> usize {
        self.factorizations
    }
}
