//! The quadratic eigenproblem (λ² M + λ C + K) x = 0 through its first-order companion form.
//!
//! The linearized equations of a moving continuum, M q̈ + C q̇ + K q = 0 with C = α D + v G and
//! K = K(v) + K_c + p (K_f + N) (Hetzler 2009, (33), (86), (103), (108)), have the solutions
//! q = x e^{λτ} with (λ² M + λ C + K) x = 0. With M symmetric positive definite and y = (x, μ x),
//! λ = γ μ, the problem is the standard eigenproblem of the companion matrix
//!
//! ```text
//!   A_γ y = μ y,   A_γ = [ 0          I        ]
//!                        [ −M⁻¹K/γ²   −M⁻¹C/γ  ]      (Tisseur & Meerbergen 2001, §3.4)
//! ```
//!
//! where γ = sqrt(‖K‖_F / ‖M‖_F) is the eigenvalue scaling of Fan, Lin & Van Dooren (2004,
//! §3): it makes the scaled coefficients M, C/γ, K/γ² of comparable size, so that a backward
//! stable eigensolver of A_γ is backward stable for the quadratic problem (without it the
//! companion's norm grows with the largest stiffness, (Nπ)² for N string modes, and so does the
//! round-off that moves an eigenvalue off the imaginary axis). M⁻¹ is applied through a Cholesky
//! factor computed once per mass matrix; the companion is solved by faer's dense real
//! eigensolver (Hessenberg reduction and Francis double-shift QR), always with `Par::Seq`, so
//! that the result is bit-identical whatever the thread count: parallelism belongs to the
//! callers (over parameter points, see `model::moving::stability_map`).
//!
//! A singular mass matrix (a massless coordinate such as the penalty bushing of (90)) has no
//! companion of this form: condense the massless coordinates first, or use
//! [`solve_generalized_quadratic_eigen`], which solves the pencil
//! `[0 I; −K −C] y = λ [I 0; 0 M] y` by faer's QZ algorithm and discards the infinite
//! eigenvalues.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::linalg::evd::{self, ComputeEigenvectors};
use faer::linalg::gevd;
use faer::{c64, Conj, Mat, MatRef, Par};

use crate::solve::balance::balance;
use crate::solve::small_eigenvalues::SmallEigenWorkspace;

/// Which dense eigensolver runs on the companion matrix.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EigenKernel {
    /// faer's dense real eigensolver (Hessenberg reduction and Francis QR, `Par::Seq`): the
    /// reference, and the only kernel that computes eigenvectors.
    #[default]
    Faer,
    /// The eigenvalue-only kernel of `solve::small_eigenvalues` (Householder + Francis QR on an
    /// L1-resident row-major array), ≈ 2× faster for orders ≈ 40: the stability maps' kernel.
    SmallDense,
}

/// Options of the quadratic eigensolver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadraticEigenParams {
    /// Also compute the eigenvectors x (unit 2-norm), and their backward errors.
    pub compute_eigenvectors: bool,
    /// Scale the eigenvalue by γ = sqrt(‖K‖_F/‖M‖_F) (Fan, Lin & Van Dooren 2004). Leave on.
    pub scale: bool,
    /// Balance the companion matrix by a diagonal similarity with powers of 2 (exact in
    /// floating point; Parlett & Reinsch 1969, LAPACK dgebal) before the QR algorithm: rows and
    /// columns of comparable norm reduce the round-off of small eigenvalues and the number of QR
    /// sweeps. Applied to eigenvalue-only solves.
    pub balance: bool,
    /// Largest accepted relative symmetry defect ‖M − Mᵀ‖_F / ‖M‖_F of the mass matrix.
    pub mass_symmetry_tolerance: f64,
    /// The dense eigensolver (eigenvectors always use faer).
    pub kernel: EigenKernel,
}

impl Default for QuadraticEigenParams {
    fn default() -> Self {
        Self {
            compute_eigenvectors: false,
            scale: true,
            balance: true,
            mass_symmetry_tolerance: 1e-12,
            kernel: EigenKernel::Faer,
        }
    }
}

impl QuadraticEigenParams {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), QuadraticEigenError> {
        let t = self.mass_symmetry_tolerance;
        if !(t.is_finite() && (0.0..1.0).contains(&t)) {
            return Err(QuadraticEigenError::InvalidParameter {
                field: "mass_symmetry_tolerance".into(),
                value: t,
                expected: "a finite number in [0, 1)".into(),
            });
        }
        Ok(())
    }
}

/// What the solve did and how well.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct QuadraticEigenStats {
    /// n, the number of coordinates.
    pub dimension: usize,
    /// The eigenvalue scaling γ (1 without scaling).
    pub scaling: f64,
    /// ‖A_γ‖_F of the scaled companion matrix.
    pub companion_norm: f64,
    /// (max/min diagonal of the Cholesky factor of M)²: a lower bound of the condition number of M.
    pub mass_condition_bound: f64,
    /// Largest backward error η(x, λ) = ‖(λ²M + λC + K)x‖ / ((|λ|²‖M‖ + |λ|‖C‖ + ‖K‖)‖x‖) over
    /// the eigenpairs (Tisseur 2000, Thm 1); 0 when the eigenvectors were not computed.
    pub max_backward_error: f64,
    /// Eigenvalues discarded as infinite (generalized solver only).
    pub infinite_eigenvalues: usize,
}

/// The eigenvalues (and eigenvectors) of a quadratic eigenproblem.
#[derive(Debug, Clone)]
pub struct QuadraticEigen {
    /// The 2n eigenvalues (fewer for a singular mass: the finite ones), in the eigensolver's order;
    /// complex ones come in adjacent conjugate pairs.
    pub eigenvalues: Vec<c64>,
    /// The n × (number of eigenvalues) matrix of eigenvectors x (unit 2-norm), column j for
    /// eigenvalue j, when asked for.
    pub eigenvectors: Option<Mat<c64>>,
    pub stats: QuadraticEigenStats,
}

/// Why a quadratic eigenproblem could not be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QuadraticEigenError {
    /// A matrix of the wrong shape.
    #[error("invalid {matrix}: {rows}×{cols}, expected {expected}×{expected}")]
    Shape {
        matrix: &'static str,
        rows: usize,
        cols: usize,
        expected: usize,
    },
    /// A NaN or infinite entry.
    #[error("invalid {matrix}[{row}, {col}] = {value}: expected a finite number")]
    NonFinite {
        matrix: &'static str,
        row: usize,
        col: usize,
        value: f64,
    },
    /// The mass matrix is not symmetric.
    #[error(
        "invalid mass matrix: relative symmetry defect ‖M − Mᵀ‖/‖M‖ = {defect:e}, expected <= {tolerance:e}"
    )]
    MassNotSymmetric { defect: f64, tolerance: f64 },
    /// The mass matrix is singular or indefinite (a massless coordinate: condense it, or use the
    /// generalized solver).
    #[error(
        "singular or indefinite mass matrix: Cholesky pivot {pivot} at row {row}; condense massless \
         coordinates or use the generalized (QZ) solver"
    )]
    MassNotPositiveDefinite { row: usize, pivot: usize },
    /// The dense eigensolver reached its iteration limit.
    #[error("the dense eigensolver did not converge on the {dimension}×{dimension} {what}")]
    NoConvergence {
        dimension: usize,
        what: &'static str,
    },
    /// An invalid parameter of the solver.
    #[error("invalid {field} = {value}: expected {expected}")]
    InvalidParameter {
        field: String,
        value: f64,
        expected: String,
    },
}

fn check_square(
    matrix: &'static str,
    a: MatRef<'_, f64>,
    n: usize,
) -> Result<(), QuadraticEigenError> {
    if a.nrows() != n || a.ncols() != n {
        return Err(QuadraticEigenError::Shape {
            matrix,
            rows: a.nrows(),
            cols: a.ncols(),
            expected: n,
        });
    }
    for j in 0..n {
        for i in 0..n {
            let v = a[(i, j)];
            if !v.is_finite() {
                return Err(QuadraticEigenError::NonFinite {
                    matrix,
                    row: i,
                    col: j,
                    value: v,
                });
            }
        }
    }
    Ok(())
}

/// ‖A‖_F.
pub fn frobenius_norm(a: MatRef<'_, f64>) -> f64 {
    let mut s = 0.0;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            s += a[(i, j)] * a[(i, j)];
        }
    }
    s.sqrt()
}

/// A solver for one mass matrix: factors M once (Cholesky, `Par::Seq`) and then solves
/// (λ² M + λ C + K) x = 0 for any C and K, reusing its buffers (no allocation per solve when
/// eigenvectors are not requested and the output vector has capacity).
#[derive(Debug)]
pub struct QuadraticEigenSolver {
    n: usize,
    params: QuadraticEigenParams,
    /// The lower Cholesky factor L of M = L Lᵀ.
    factor: Mat<f64>,
    mass: Mat<f64>,
    mass_norm: f64,
    mass_condition_bound: f64,
    companion: Mat<f64>,
    rhs: Mat<f64>,
    s_re: faer::diag::Diag<f64>,
    s_im: faer::diag::Diag<f64>,
    vectors: Mat<f64>,
    buffer: Buffer,
    small: Option<SmallEigenWorkspace>,
}

/// The faer workspace (its type has no `Debug`).
struct Buffer(MemBuffer);

impl std::fmt::Debug for Buffer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("MemBuffer")
    }
}

impl QuadraticEigenSolver {
    /// Checks and factors the mass matrix M (symmetric positive definite).
    pub fn new(
        mass: MatRef<'_, f64>,
        params: QuadraticEigenParams,
    ) -> Result<Self, QuadraticEigenError> {
        params.validate()?;
        let n = mass.nrows();
        check_square("mass matrix", mass, n)?;
        let mass_norm = frobenius_norm(mass);
        let mut defect = 0.0;
        for j in 0..n {
            for i in 0..n {
                defect += (mass[(i, j)] - mass[(j, i)]).powi(2);
            }
        }
        let defect = if mass_norm > 0.0 {
            defect.sqrt() / mass_norm
        } else {
            0.0
        };
        if defect > params.mass_symmetry_tolerance {
            return Err(QuadraticEigenError::MassNotSymmetric {
                defect,
                tolerance: params.mass_symmetry_tolerance,
            });
        }
        let mut factor = mass.to_owned();
        {
            let mut buf = MemBuffer::new(llt::factor::cholesky_in_place_scratch::<f64>(
                n,
                Par::Seq,
                Default::default(),
            ));
            llt::factor::cholesky_in_place(
                factor.as_mut(),
                Default::default(),
                Par::Seq,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .map_err(|e| match e {
                llt::factor::LltError::NonPositivePivot { index } => {
                    QuadraticEigenError::MassNotPositiveDefinite {
                        row: index,
                        pivot: index,
                    }
                }
            })?;
        }
        let (mut dmax, mut dmin) = (0.0f64, f64::INFINITY);
        for i in 0..n {
            let d = factor[(i, i)].abs();
            dmax = dmax.max(d);
            dmin = dmin.min(d);
            for j in i + 1..n {
                factor[(i, j)] = 0.0;
            }
        }
        let mass_condition_bound = if n == 0 { 1.0 } else { (dmax / dmin).powi(2) };
        let want = if params.compute_eigenvectors {
            ComputeEigenvectors::Yes
        } else {
            ComputeEigenvectors::No
        };
        let scratch = evd::evd_scratch::<f64>(
            2 * n,
            ComputeEigenvectors::No,
            want,
            Par::Seq,
            Default::default(),
        )
        .or(llt::solve::solve_in_place_scratch::<f64>(
            n,
            2 * n,
            Par::Seq,
        ));
        Ok(Self {
            n,
            params,
            factor,
            mass: mass.to_owned(),
            mass_norm,
            mass_condition_bound,
            companion: Mat::zeros(2 * n, 2 * n),
            rhs: Mat::zeros(n, 2 * n),
            s_re: faer::diag::Diag::zeros(2 * n),
            s_im: faer::diag::Diag::zeros(2 * n),
            vectors: if params.compute_eigenvectors {
                Mat::zeros(2 * n, 2 * n)
            } else {
                Mat::zeros(0, 0)
            },
            buffer: Buffer(MemBuffer::new(scratch)),
            small: (params.kernel == EigenKernel::SmallDense && !params.compute_eigenvectors)
                .then(|| SmallEigenWorkspace::new(2 * n)),
        })
    }

    /// The number of coordinates n.
    pub fn dimension(&self) -> usize {
        self.n
    }

    /// Solves (λ² M + λ C + K) x = 0.
    pub fn solve(
        &mut self,
        damping: MatRef<'_, f64>,
        stiffness: MatRef<'_, f64>,
    ) -> Result<QuadraticEigen, QuadraticEigenError> {
        let mut eigenvalues = Vec::with_capacity(2 * self.n);
        let mut stats = self.eigenvalues_into(damping, stiffness, &mut eigenvalues)?;
        let eigenvectors = if self.params.compute_eigenvectors {
            let (x, eta) = self.eigenvectors(damping, stiffness, &eigenvalues);
            stats.max_backward_error = eta;
            Some(x)
        } else {
            None
        };
        Ok(QuadraticEigen {
            eigenvalues,
            eigenvectors,
            stats,
        })
    }

    /// The scaled companion matrix A_γ of (C, K) as a row-major array (not balanced), and γ.
    pub fn scaled_companion(
        &mut self,
        damping: MatRef<'_, f64>,
        stiffness: MatRef<'_, f64>,
    ) -> Result<(Vec<f64>, f64), QuadraticEigenError> {
        let gamma = self.fill_companion(damping, stiffness)?;
        let m = 2 * self.n;
        let mut out = vec![0.0; m * m];
        for i in 0..m {
            for j in 0..m {
                out[i * m + j] = self.companion[(i, j)];
            }
        }
        Ok((out, gamma))
    }

    /// Overwrites `rhs` (length n) with M⁻¹ rhs.
    pub fn solve_mass(&mut self, rhs: &mut [f64]) {
        let n = self.n;
        let mut col = Mat::<f64>::from_fn(n, 1, |i, _| rhs[i]);
        llt::solve::solve_in_place_with_conj(
            self.factor.as_ref(),
            Conj::No,
            col.as_mut(),
            Par::Seq,
            MemStack::new(&mut self.buffer.0),
        );
        for (i, r) in rhs.iter_mut().enumerate() {
            *r = col[(i, 0)];
        }
    }

    /// Builds A_γ in `self.companion`; returns γ.
    fn fill_companion(
        &mut self,
        damping: MatRef<'_, f64>,
        stiffness: MatRef<'_, f64>,
    ) -> Result<f64, QuadraticEigenError> {
        let n = self.n;
        check_square("damping matrix", damping, n)?;
        check_square("stiffness matrix", stiffness, n)?;
        let k_norm = frobenius_norm(stiffness);
        let c_norm = frobenius_norm(damping);
        let gamma = if !self.params.scale || self.mass_norm == 0.0 {
            1.0
        } else if k_norm > 0.0 {
            (k_norm / self.mass_norm).sqrt()
        } else if c_norm > 0.0 {
            c_norm / self.mass_norm
        } else {
            1.0
        };
        for j in 0..n {
            for i in 0..n {
                self.rhs[(i, j)] = stiffness[(i, j)];
                self.rhs[(i, n + j)] = damping[(i, j)];
            }
        }
        {
            let stack = MemStack::new(&mut self.buffer.0);
            llt::solve::solve_in_place_with_conj(
                self.factor.as_ref(),
                Conj::No,
                self.rhs.as_mut(),
                Par::Seq,
                stack,
            );
        }
        let a = &mut self.companion;
        let (g1, g2) = (1.0 / gamma, 1.0 / (gamma * gamma));
        for j in 0..2 * n {
            for i in 0..2 * n {
                a[(i, j)] = 0.0;
            }
        }
        for i in 0..n {
            a[(i, n + i)] = 1.0;
            for j in 0..n {
                a[(n + i, j)] = -g2 * self.rhs[(i, j)];
                a[(n + i, n + j)] = -g1 * self.rhs[(i, n + j)];
            }
        }
        Ok(gamma)
    }

    /// Solves for the eigenvalues only, writing them into `out` (cleared first).
    pub fn eigenvalues_into(
        &mut self,
        damping: MatRef<'_, f64>,
        stiffness: MatRef<'_, f64>,
        out: &mut Vec<c64>,
    ) -> Result<QuadraticEigenStats, QuadraticEigenError> {
        let n = self.n;
        let gamma = self.fill_companion(damping, stiffness)?;
        let a = &mut self.companion;
        if self.params.balance && !self.params.compute_eigenvectors {
            balance(a, None);
        }
        let companion_norm = frobenius_norm(a.as_ref());
        if !companion_norm.is_finite() {
            return Err(QuadraticEigenError::NonFinite {
                matrix: "companion matrix (M⁻¹K, M⁻¹C)",
                row: 0,
                col: 0,
                value: companion_norm,
            });
        }
        if let Some(ws) = self.small.as_mut() {
            let m = 2 * n;
            let dst = ws.matrix_mut();
            for i in 0..m {
                for j in 0..m {
                    dst[i * m + j] = self.companion[(i, j)];
                }
            }
            let (re, im) = (
                self.s_re.column_vector_mut().try_as_col_major_mut(),
                self.s_im.column_vector_mut().try_as_col_major_mut(),
            );
            let (Some(re), Some(im)) = (re, im) else {
                unreachable!("faer diagonals are contiguous")
            };
            ws.eigenvalues(re.as_slice_mut(), im.as_slice_mut())
                .map_err(|_| QuadraticEigenError::NoConvergence {
                    dimension: m,
                    what: "companion matrix (small dense kernel)",
                })?;
            out.clear();
            for i in 0..m {
                out.push(c64::new(gamma * self.s_re[i], gamma * self.s_im[i]));
            }
            return Ok(QuadraticEigenStats {
                dimension: n,
                scaling: gamma,
                companion_norm,
                mass_condition_bound: self.mass_condition_bound,
                max_backward_error: 0.0,
                infinite_eigenvalues: 0,
            });
        }
        let stack = MemStack::new(&mut self.buffer.0);
        let vectors = if self.params.compute_eigenvectors {
            Some(self.vectors.as_mut())
        } else {
            None
        };
        evd::evd_real(
            self.companion.as_ref(),
            self.s_re.as_mut(),
            self.s_im.as_mut(),
            None,
            vectors,
            Par::Seq,
            stack,
            Default::default(),
        )
        .map_err(|_| QuadraticEigenError::NoConvergence {
            dimension: 2 * n,
            what: "companion matrix",
        })?;
        out.clear();
        for i in 0..2 * n {
            out.push(c64::new(gamma * self.s_re[i], gamma * self.s_im[i]));
        }
        Ok(QuadraticEigenStats {
            dimension: n,
            scaling: gamma,
            companion_norm,
            mass_condition_bound: self.mass_condition_bound,
            max_backward_error: 0.0,
            infinite_eigenvalues: 0,
        })
    }

    /// The x parts of the companion eigenvectors (real storage: a complex pair occupies columns
    /// j, j+1 as real and imaginary parts), normalized, with the largest backward error.
    fn eigenvectors(
        &self,
        damping: MatRef<'_, f64>,
        stiffness: MatRef<'_, f64>,
        eigenvalues: &[c64],
    ) -> (Mat<c64>, f64) {
        let n = self.n;
        let mut x = Mat::<c64>::zeros(n, 2 * n);
        let mut j = 0;
        while j < 2 * n {
            if self.s_im[j] == 0.0 {
                for i in 0..n {
                    x[(i, j)] = c64::new(self.vectors[(i, j)], 0.0);
                }
                j += 1;
            } else {
                for i in 0..n {
                    let (re, im) = (self.vectors[(i, j)], self.vectors[(i, j + 1)]);
                    x[(i, j)] = c64::new(re, im);
                    if j + 1 < 2 * n {
                        x[(i, j + 1)] = c64::new(re, -im);
                    }
                }
                j += 2;
            }
        }
        let mass = self.mass.as_ref();
        let (mn, cn, kn) = (
            self.mass_norm,
            frobenius_norm(damping),
            frobenius_norm(stiffness),
        );
        let mut worst = 0.0f64;
        for (col, &lambda) in eigenvalues.iter().enumerate() {
            let norm: f64 = (0..n).map(|i| x[(i, col)].norm_sqr()).sum::<f64>().sqrt();
            if norm > 0.0 {
                for i in 0..n {
                    x[(i, col)] /= norm;
                }
            }
            let eta = backward_error(mass, damping, stiffness, lambda, x.as_ref(), col);
            let denom = lambda.norm_sqr() * mn + lambda.norm() * cn + kn;
            if denom > 0.0 {
                worst = worst.max(eta / denom);
            }
        }
        (x, worst)
    }
}

/// ‖(λ²M + λC + K) x_col‖₂ (x_col of unit norm).
fn backward_error(
    m: MatRef<'_, f64>,
    c: MatRef<'_, f64>,
    k: MatRef<'_, f64>,
    lambda: c64,
    x: MatRef<'_, c64>,
    col: usize,
) -> f64 {
    let n = m.nrows();
    let l2 = lambda * lambda;
    let mut s = 0.0;
    for i in 0..n {
        let mut r = c64::new(0.0, 0.0);
        for j in 0..n {
            let coeff = l2 * m[(i, j)] + lambda * c[(i, j)] + c64::new(k[(i, j)], 0.0);
            r += coeff * x[(j, col)];
        }
        s += r.norm_sqr();
    }
    s.sqrt()
}

/// Solves (λ² M + λ C + K) x = 0 once (see [`QuadraticEigenSolver`]).
pub fn solve_quadratic_eigen(
    mass: MatRef<'_, f64>,
    damping: MatRef<'_, f64>,
    stiffness: MatRef<'_, f64>,
    params: QuadraticEigenParams,
) -> Result<QuadraticEigen, QuadraticEigenError> {
    QuadraticEigenSolver::new(mass, params)?.solve(damping, stiffness)
}

/// Solves (λ² M + λ C + K) x = 0 for a symmetric positive *semi*-definite M (massless
/// coordinates) through the generalized companion pencil
/// `[0 I; −K −C] y = λ [I 0; 0 M] y`, by faer's QZ algorithm (`Par::Seq`). Eigenvalues with
/// |β| ≤ `infinite_tolerance`·|α| (α/β = λ) are infinite — one per massless coordinate for the
/// DAEs of this crate — and are dropped; the finite ones are returned. No scaling is applied.
pub fn solve_generalized_quadratic_eigen(
    mass: MatRef<'_, f64>,
    damping: MatRef<'_, f64>,
    stiffness: MatRef<'_, f64>,
    infinite_tolerance: f64,
) -> Result<QuadraticEigen, QuadraticEigenError> {
    let n = mass.nrows();
    check_square("mass matrix", mass, n)?;
    check_square("damping matrix", damping, n)?;
    check_square("stiffness matrix", stiffness, n)?;
    if !(infinite_tolerance.is_finite() && infinite_tolerance > 0.0) {
        return Err(QuadraticEigenError::InvalidParameter {
            field: "infinite_tolerance".into(),
            value: infinite_tolerance,
            expected: "a finite number > 0".into(),
        });
    }
    let mut a = Mat::<f64>::zeros(2 * n, 2 * n);
    let mut b = Mat::<f64>::zeros(2 * n, 2 * n);
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        b[(i, i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = -stiffness[(i, j)];
            a[(n + i, n + j)] = -damping[(i, j)];
            b[(n + i, n + j)] = mass[(i, j)];
        }
    }
    let companion_norm = frobenius_norm(a.as_ref());
    let mut s_re = faer::diag::Diag::<f64>::zeros(2 * n);
    let mut s_im = faer::diag::Diag::<f64>::zeros(2 * n);
    let mut beta = faer::diag::Diag::<f64>::zeros(2 * n);
    // faer 0.24.4's gevd_real returns zero α and β for most eigenvalues of pencils of order
    // ≳ 40 when no eigenvectors are requested (reproduced at order 44 with B = I); with the right
    // eigenvectors requested it is correct. Request them.
    let mut vectors = Mat::<f64>::zeros(2 * n, 2 * n);
    let mut buf = MemBuffer::new(gevd::gevd_scratch::<f64>(
        2 * n,
        ComputeEigenvectors::No,
        ComputeEigenvectors::Yes,
        Par::Seq,
        Default::default(),
    ));
    gevd::gevd_real(
        a.as_mut(),
        b.as_mut(),
        s_re.as_mut(),
        s_im.as_mut(),
        beta.as_mut(),
        None,
        Some(vectors.as_mut()),
        Par::Seq,
        MemStack::new(&mut buf),
        Default::default(),
    )
    .map_err(|_| QuadraticEigenError::NoConvergence {
        dimension: 2 * n,
        what: "generalized companion pencil",
    })?;
    let mut eigenvalues = Vec::with_capacity(2 * n);
    let mut infinite = 0;
    // A complex pair occupies i, i+1 with α = re ± i·im and the common β = beta[i].
    let mut i = 0;
    while i < 2 * n {
        let pair = s_im[i] != 0.0 && i + 1 < 2 * n;
        let alpha = c64::new(s_re[i], s_im[i]);
        let b = beta[i];
        let count = if pair { 2 } else { 1 };
        if b.abs() <= infinite_tolerance * alpha.norm() {
            infinite += count;
        } else {
            eigenvalues.push(alpha / b);
            if pair {
                eigenvalues.push(alpha.conj() / b);
            }
        }
        i += count;
    }
    Ok(QuadraticEigen {
        eigenvalues,
        eigenvectors: None,
        stats: QuadraticEigenStats {
            dimension: n,
            scaling: 1.0,
            companion_norm,
            mass_condition_bound: f64::INFINITY,
            max_backward_error: 0.0,
            infinite_eigenvalues: infinite,
        },
    })
}

#[cfg(test)]
mod tests {
    //! Setting: small quadratic problems with known spectra. Goal: the companion solve returns
    //! them to round-off, with and without scaling, and fails with typed errors on bad input.
    use super::*;

    fn diag(v: &[f64]) -> Mat<f64> {
        Mat::from_fn(v.len(), v.len(), |i, j| if i == j { v[i] } else { 0.0 })
    }

    #[test]
    fn undamped_oscillators_have_eigenvalues_plus_minus_i_omega() {
        let m = diag(&[1.0, 2.0]);
        let c = Mat::<f64>::zeros(2, 2);
        let k = diag(&[4.0, 18.0]);
        let r =
            solve_quadratic_eigen(m.as_ref(), c.as_ref(), k.as_ref(), Default::default()).unwrap();
        let mut im: Vec<f64> = r.eigenvalues.iter().map(|l| l.im).collect();
        im.sort_by(f64::total_cmp);
        for (a, b) in im.iter().zip([-3.0, -2.0, 2.0, 3.0]) {
            assert!((a - b).abs() < 1e-14, "{a} vs {b}");
        }
        assert!(r.eigenvalues.iter().all(|l| l.re.abs() < 1e-14));
    }

    #[test]
    fn damped_scalar_oscillator_matches_the_quadratic_formula() {
        // λ² + 3λ + 2 = 0: λ = −1, −2 (overdamped); λ² + 0.2λ + 1: −0.1 ± i sqrt(0.99).
        for (c, k, expect) in [
            (3.0, 2.0, [c64::new(-1.0, 0.0), c64::new(-2.0, 0.0)]),
            (
                0.2,
                1.0,
                [
                    c64::new(-0.1, 0.99f64.sqrt()),
                    c64::new(-0.1, -0.99f64.sqrt()),
                ],
            ),
        ] {
            for scale in [true, false] {
                let params = QuadraticEigenParams {
                    scale,
                    compute_eigenvectors: true,
                    ..Default::default()
                };
                let r = solve_quadratic_eigen(
                    diag(&[1.0]).as_ref(),
                    diag(&[c]).as_ref(),
                    diag(&[k]).as_ref(),
                    params,
                )
                .unwrap();
                for e in expect {
                    assert!(r.eigenvalues.iter().any(|l| (l - e).norm() < 1e-14));
                }
                assert!(r.stats.max_backward_error < 1e-15);
            }
        }
    }

    #[test]
    fn singular_mass_is_a_typed_error_and_the_generalized_solver_drops_infinite_eigenvalues() {
        // q̈ + q − y = 0 (mass 1), 0·ÿ + 2y − q = 0: y = q/2, q̈ + q/2 = 0, λ = ±i/√2.
        let m = diag(&[1.0, 0.0]);
        let c = Mat::<f64>::zeros(2, 2);
        let k = Mat::from_fn(2, 2, |i, j| [[1.0, -1.0], [-1.0, 2.0]][i][j]);
        let e = solve_quadratic_eigen(m.as_ref(), c.as_ref(), k.as_ref(), Default::default())
            .unwrap_err();
        assert!(matches!(
            e,
            QuadraticEigenError::MassNotPositiveDefinite { row: 1, .. }
        ));
        let r =
            solve_generalized_quadratic_eigen(m.as_ref(), c.as_ref(), k.as_ref(), 1e-12).unwrap();
        assert_eq!(r.eigenvalues.len(), 2);
        assert_eq!(r.stats.infinite_eigenvalues, 2);
        for l in &r.eigenvalues {
            assert!(
                l.re.abs() < 1e-14 && (l.im.abs() - 0.5f64.sqrt()).abs() < 1e-14,
                "{:?}",
                r.eigenvalues
            );
        }
    }

    #[test]
    fn generalized_solver_is_right_for_pencils_of_order_44() {
        // 22 uncoupled unit oscillators ω_k = k and one massless spring: finite λ = ±ik.
        let n = 23;
        let m = Mat::from_fn(n, n, |i, j| if i == j && i < 22 { 1.0 } else { 0.0 });
        let k = Mat::from_fn(n, n, |i, j| {
            if i == j {
                if i < 22 {
                    ((i + 1) * (i + 1)) as f64
                } else {
                    1.0
                }
            } else {
                0.0
            }
        });
        let c = Mat::<f64>::zeros(n, n);
        let r =
            solve_generalized_quadratic_eigen(m.as_ref(), c.as_ref(), k.as_ref(), 1e-12).unwrap();
        assert_eq!(r.eigenvalues.len(), 44);
        for kk in 1..=22 {
            assert!(r
                .eigenvalues
                .iter()
                .any(|l| (l - c64::new(0.0, kk as f64)).norm() < 1e-10 * kk as f64));
        }
    }

    #[test]
    fn nan_and_wrong_shapes_are_named() {
        let mut k = diag(&[1.0, 1.0]);
        k[(1, 0)] = f64::NAN;
        let m = diag(&[1.0, 1.0]);
        let e = solve_quadratic_eigen(m.as_ref(), m.as_ref(), k.as_ref(), Default::default())
            .unwrap_err();
        assert!(matches!(
            e,
            QuadraticEigenError::NonFinite {
                matrix: "stiffness matrix",
                row: 1,
                col: 0,
                ..
            }
        ));
        let e = solve_quadratic_eigen(
            m.as_ref(),
            diag(&[1.0]).as_ref(),
            m.as_ref(),
            Default::default(),
        )
        .unwrap_err();
        assert!(e.to_string().contains("damping matrix: 1×1, expected 2×2"));
        let mut skew = diag(&[1.0, 1.0]);
        skew[(0, 1)] = 0.5;
        let e = solve_quadratic_eigen(skew.as_ref(), m.as_ref(), m.as_ref(), Default::default())
            .unwrap_err();
        assert!(matches!(e, QuadraticEigenError::MassNotSymmetric { .. }));
    }
}
