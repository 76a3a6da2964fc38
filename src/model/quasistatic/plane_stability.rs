//! The explicit scheme's step bound in 2D (docs/quasistatic.md, stability note): with
//! linear A and B the explicit update is u_n = (I − k A⁻¹B) u_{n−1} + …, stable only while
//! k λ_max(A⁻¹B) < 2, with λ_max the largest eigenvalue of the symmetric pencil K_B x = λ K_A x on
//! the solved dofs.
//!
//! The bound does not degrade with h: for the isotropic forms (L τ) = a1 tr τ I + a2 τ, the
//! Rayleigh quotient τ:Bτ/τ:Aτ of any strain lies between the constitutive ratios of the deviatoric
//! (b2/a2) and volumetric ((2b1 + b2)/(2a1 + a2)) parts, so λ_max ≤ max of the two, approached as the
//! mesh resolves strains concentrated in the worse mode.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd;
use faer::{Mat, Par};

use crate::error::{Error, InputError, SolveError};
use crate::material::plane_law::IsotropicLinear;
use crate::model::quasistatic::plane_condensed::assemble_linear;
use crate::model::quasistatic::plane_solver::PlaneSolver;
use crate::solve::dense_cholesky::cholesky_factor;

/// The largest dof count for which the dense generalized eigenproblem is solved.
pub const DENSE_LIMIT: usize = 4000;

/// max(b2/a2, (2 b1 + b2)/(2 a1 + a2)): the supremum of τ:Bτ / τ:Aτ over plane strains.
pub fn constitutive_ratio(a: &IsotropicLinear, b: &IsotropicLinear) -> f64 {
    (b.a2 / a.a2).max((2.0 * b.a1 + b.a2) / (2.0 * a.a1 + a.a2))
}

/// λ_max of K_B x = λ K_A x on the solved dofs of a linear problem (dense: Cholesky of K_A, then the
/// eigenvalues of L⁻¹ K_B L⁻ᵀ).
pub fn explicit_stability_eigenvalue(solver: &PlaneSolver) -> Result<f64, Error> {
    let problem = solver.problem();
    if !problem.is_linear() {
        return Err(InputError::new(
            "viscosity",
            "(nonlinear)",
            "linear A and B for the explicit bound k λ_max(A⁻¹B) < 2",
        )
        .into());
    }
    let dofs = solver.dofs();
    let n = dofs.n_solved();
    if n > DENSE_LIMIT {
        return Err(InputError::new(
            "mesh",
            format!("{n} dofs"),
            format!("at most {DENSE_LIMIT} dofs for the dense eigenproblem"),
        )
        .into());
    }
    // the linear law of element e (checked linear above)
    let dense = |law: &dyn Fn(usize) -> Option<IsotropicLinear>| -> Mat<f64> {
        let mut values = vec![0.0; dofs.pattern.nnz()];
        assemble_linear(
            dofs,
            &dofs.pattern,
            |el, e| law(el).map_or([0.0; 3], |l| l.apply(e)),
            &mut values,
        );
        let mut m = Mat::<f64>::zeros(n, n);
        let (cp, ri) = (dofs.pattern.col_ptr(), dofs.pattern.row_idx());
        for j in 0..n {
            for k in cp[j]..cp[j + 1] {
                m[(ri[k], j)] = values[k];
                m[(j, ri[k])] = values[k];
            }
        }
        m
    };
    let (ka, kb) = (
        dense(&|e| problem.viscosity_of(e).as_linear().copied()),
        dense(&|e| problem.elasticity_of(e).as_linear().copied()),
    );
    // every factorization sequential (`Par::Seq`): the same bits whatever the thread count
    let mut l = cholesky_factor(ka.as_ref()).map_err(|row| SolveError::Singular {
        operator: "K_A (viscosity)".into(),
        row,
        pivot: ka[(row, row)],
    })?;
    for j in 1..n {
        for i in 0..j {
            l[(i, j)] = 0.0;
        }
    }
    // C = L⁻¹ (K_B / s) L⁻ᵀ with s ≈ max |K_B|: the eigenvalues scale with s, and the scaled
    // matrix keeps the tridiagonal QR away from subnormal numbers (young = 1e-308 once made it
    // iterate for ever) and from overflow.
    let mut s_b = 0.0f64;
    for j in 0..n {
        for i in 0..n {
            s_b = s_b.max(kb[(i, j)].abs());
        }
    }
    if !s_b.is_finite() {
        return Err(SolveError::NonFinite {
            step: 0,
            time: 0.0,
            quantity: "elastic stiffness K_B (the explicit bound's eigenproblem)".into(),
            value: s_b,
            hint: "; check elasticity: its moduli overflow the stiffness".into(),
        }
        .into());
    }
    if s_b == 0.0 {
        return Ok(0.0);
    }
    // a power of 2: the scaling is exact, the eigenvalues' bits those of the unscaled problem
    let s_b = 2f64.powi(s_b.log2().round() as i32);
    let mut c = kb;
    for j in 0..n {
        for i in 0..n {
            c[(i, j)] /= s_b;
        }
    }
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(
        l.as_ref(),
        c.as_mut(),
        faer::Par::Seq,
    );
    let mut ct = c.transpose().to_owned();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(
        l.as_ref(),
        ct.as_mut(),
        faer::Par::Seq,
    );
    if let Some(v) = (0..n)
        .flat_map(|j| (0..n).map(move |i| (i, j)))
        .map(|(i, j)| ct[(i, j)])
        .find(|v| !v.is_finite())
    {
        return Err(SolveError::NonFinite {
            step: 0,
            time: 0.0,
            quantity: "L⁻¹ K_B L⁻ᵀ (the explicit bound's eigenproblem)".into(),
            value: v,
            hint: "; the viscosity K_A is too small against the elasticity K_B".into(),
        }
        .into());
    }
    let mut s = faer::diag::Diag::<f64>::zeros(n);
    let mut buf = MemBuffer::new(evd::self_adjoint_evd_scratch::<f64>(
        n,
        evd::ComputeEigenvectors::No,
        Par::Seq,
        Default::default(),
    ));
    evd::self_adjoint_evd(
        ct.as_ref(),
        s.as_mut(),
        None,
        Par::Seq,
        MemStack::new(&mut buf),
        Default::default(),
    )
    .map_err(|_| SolveError::Singular {
        operator: "L⁻¹ K_B L⁻ᵀ (eigenvalues did not converge)".into(),
        row: 0,
        pivot: f64::NAN,
    })?;
    // faer returns the eigenvalues in nondecreasing order
    (0..n)
        .map(|i| s[i])
        .reduce(f64::max)
        .map(|l| l * s_b)
        .ok_or_else(|| InputError::new("mesh", "0 dofs", "at least one free dof").into())
}
