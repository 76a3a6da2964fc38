//! The companion-form solver of (λ² M + λ C + K) x = 0 for a symmetric positive definite M:
//! M factored once, the scaled companion A_γ solved by faer's dense eigensolver or the small
//! eigenvalue-only kernel, eigenvectors with their backward errors on request.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::linalg::evd::{self, ComputeEigenvectors};
use faer::{c64, Conj, Mat, MatRef, Par};

use crate::solve::balance::balance;
use crate::solve::dense_cholesky::cholesky_factor;
use crate::solve::quadratic_eigen::types::{
    check_square, frobenius_norm, EigenKernel, QuadraticEigen, QuadraticEigenError,
    QuadraticEigenParams, QuadraticEigenStats,
};
use crate::solve::small_eigenvalues::SmallEigenWorkspace;

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
        let mut factor = cholesky_factor(mass).map_err(|index| {
            QuadraticEigenError::MassNotPositiveDefinite {
                row: index,
                pivot: index,
            }
        })?;
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
        } else {
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
        }
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
