//! The linear path: the step operator K_θ = A + θ k B is factored once (per step size) with the Γ3
//! dofs ordered last, and the contact is condensed onto the contact points.
//!
//! With K_θ = L Lᵀ and the Γ3 block last, the trailing block L_ΓΓ factors the Schur complement
//! S = L_ΓΓ L_ΓΓᵀ. A step with right-hand side b = F(τ) − B u_{n−1} is then
//!
//!   y = L⁻¹ b (forward pass),   b̂ = L_ΓΓ y_Γ,   solve S w_Γ + C_Γᵀ W p_ν(C_Γ w_Γ) = b̂,
//!   y_Γ ← L_ΓΓᵀ w_Γ,            w = L⁻ᵀ y (backward pass),
//!
//! one sparse solve per step whatever the contact does (the Γ3 problem is dense and small).

use faer::Mat;

use crate::contact::normal_law::{NormalLaw, SpaceTime};
use crate::error::SolveError;
use crate::fem::sparse::SymmetricPattern;
use crate::model::quasistatic::plane_contact::{
    CondensedContact, ContactFailure, ContactNewtonParams,
};
use crate::model::quasistatic::plane_dofs::PlaneDofs;
use crate::solve::sparse_cholesky::{CholeskyWorkspace, SparseCholesky};

/// A factored step operator with its condensed contact data.
#[derive(Debug)]
pub struct CondensedStep {
    pub k: f64,
    chol: SparseCholesky,
    ws: CholeskyWorkspace,
    /// Number of Γ3 solved dofs (trailing positions n − m..n of the factor order).
    m: usize,
    /// L_ΓΓ, the trailing block of the factor.
    l_gg: Mat<f64>,
    pub contact: CondensedContact,
    y: Vec<f64>,
    /// b̂ = L_ΓΓ y_Γ and the Γ velocity (warm start).
    b_hat: Vec<f64>,
    w_gamma: Vec<f64>,
    pub factor_nnz: usize,
}

impl CondensedStep {
    /// Factors `values` (upper triangle of K_θ on `dofs.pattern`) and precomputes the condensed
    /// contact operators.
    pub fn new(
        dofs: &PlaneDofs,
        values: &[f64],
        k: f64,
        contact_positions: &[SpaceTime],
    ) -> Result<Self, SolveError> {
        let n = dofs.n_solved();
        let mut chol =
            SparseCholesky::analyze(&dofs.pattern, &dofs.contact_dofs, "step operator A + θkB")?;
        chol.factor(&dofs.pattern, values)?;
        let m = dofs.contact_dofs.len();
        let ws = chol.workspace(1);
        let l_gg = chol.trailing_block(m);
        let s = &l_gg * l_gg.transpose();
        // C_Γ rows and G = C R.
        let mut rows = Vec::with_capacity(dofs.contact_points.len());
        let mut g = Vec::new();
        for point in &dofs.contact_points {
            let mut row = Vec::with_capacity(point.entries.len());
            let mut gg = 0.0;
            for &(dof, coef) in &point.entries {
                if let Some(sv) = dofs.solved[dof] {
                    let pos = chol.position(sv);
                    debug_assert!(pos >= n - m, "contact dofs are ordered last");
                    row.push((pos - (n - m), coef));
                }
                if let Some(mode) = dofs.rigid_modes.first() {
                    gg += coef * mode[dof];
                }
            }
            rows.push(row);
            if !dofs.rigid_modes.is_empty() {
                g.push(gg);
            }
        }
        let weights: Vec<f64> = dofs.contact_points.iter().map(|p| p.weight).collect();
        let factor_nnz = chol.factor_nnz();
        Ok(Self {
            k,
            chol,
            ws,
            m,
            l_gg,
            contact: CondensedContact::new(s, rows, g, weights, contact_positions.to_vec()),
            y: vec![0.0; n],
            b_hat: vec![0.0; m],
            w_gamma: vec![0.0; m],
            factor_nnz,
        })
    }

    /// One step: `b` is the right-hand side on the solved dofs; `b_rigid` the loads Rᵀ b_full on
    /// the free rigid motions. Writes the solved-dof velocity into `w` and returns (α, Newton
    /// iterations).
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        law: Option<&dyn NormalLaw>,
        t: f64,
        b: &[f64],
        b_rigid: &[f64],
        w: &mut [f64],
        alpha_guess: &[f64],
        params: &ContactNewtonParams,
    ) -> Result<(Vec<f64>, usize), ContactFailure> {
        let n = self.y.len();
        let m = self.m;
        self.chol.forward(b, &mut self.y, &mut self.ws);
        let mut alpha = vec![0.0; b_rigid.len()];
        let mut iterations = 0;
        if let (Some(law), false) = (law, self.contact.is_empty()) {
            // b̂ = L_ΓΓ y_Γ
            {
                let y_g = &self.y[n - m..];
                for i in 0..m {
                    let mut s = 0.0;
                    for j in 0..=i {
                        s += self.l_gg[(i, j)] * y_g[j];
                    }
                    self.b_hat[i] = s;
                }
            }
            match b_rigid.len() {
                0 => {
                    iterations = self.contact.solve(law, t, &self.b_hat, 0.0, &mut self.w_gamma, params)?;
                }
                1 => {
                    let (a, it) = self.contact.solve_floating(
                        law,
                        t,
                        &self.b_hat,
                        b_rigid[0],
                        &mut self.w_gamma,
                        alpha_guess[0],
                        params,
                    )?;
                    alpha[0] = a;
                    iterations = it;
                }
                q => {
                    return Err(ContactFailure::NoEquilibrium(format!(
                        "{q} rigid motions are left free by Γ1; this solver carries at most one by the contact"
                    )))
                }
            }
            // y_Γ = L_ΓΓᵀ w_Γ
            let y_g = &mut self.y[n - m..];
            for i in 0..m {
                let mut s = 0.0;
                for j in i..m {
                    s += self.l_gg[(j, i)] * self.w_gamma[j];
                }
                y_g[i] = s;
            }
        }
        self.chol.backward(&mut self.y, w, &mut self.ws);
        Ok((alpha, iterations))
    }

    /// The stored entries of the Cholesky factor.
    pub fn nnz(&self) -> usize {
        self.factor_nnz
    }

    /// Best wall time of one forward + backward pass (no contact), over `repeats`.
    pub fn time_plain_solve(&mut self, repeats: usize) -> f64 {
        let n = self.y.len();
        let b = vec![1.0; n];
        let mut x = vec![0.0; n];
        let mut best = f64::INFINITY;
        for _ in 0..repeats.max(1) {
            let start = std::time::Instant::now();
            self.chol.forward(&b, &mut self.y, &mut self.ws);
            self.chol.backward(&mut self.y, &mut x, &mut self.ws);
            best = best.min(start.elapsed().as_secs_f64());
        }
        std::hint::black_box(&x);
        best
    }
}

/// Assembles K = Σ_e area ε(φ_p) : (A_coef + θk B_coef) ε(φ_q) for linear isotropic A and B.
pub fn assemble_linear(
    dofs: &PlaneDofs,
    pattern: &SymmetricPattern,
    law: impl Fn(usize, &[f64; 3]) -> [f64; 3],
    values: &mut [f64],
) {
    values.iter_mut().for_each(|v| *v = 0.0);
    for (e, el) in dofs.elements.iter().enumerate() {
        let k = el.stiffness(|d| law(e, d));
        pattern.add_element(values, e, k.transpose().as_slice());
    }
}
