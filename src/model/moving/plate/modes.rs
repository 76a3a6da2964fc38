//! The non-rotating plate harmonic by harmonic: for w = W(r) cos nφ (or sin nφ) the bending
//! energy and the kinetic energy reduce to the radial matrices
//!
//! ```text
//!   K_n = D [a − n² (c + cᵀ) + n⁴ d + n² e],   M_n = ρh m          (radial.rs; per unit ∫ψ²)
//! ```
//!
//! whose generalized eigenpairs K_n Φ = ω² M_n Φ are the natural frequencies ω_{n,m} (m nodal
//! circles) and the radial mode shapes. They are the reference of the rotating plate's spectrum
//! (±iω_{n,m} − i n Ω, (72)–(74)) and the modal basis of the reduced model.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::{self_adjoint_evd, self_adjoint_evd_scratch, ComputeEigenvectors};
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::{Mat, MatRef, Par};

use crate::error::{Error, InputError, SolveError};
use crate::model::moving::plate::data::PlateProperties;
use crate::model::moving::plate::radial::{RadialBasis, RadialMatrices};
use crate::solve::dense_cholesky::cholesky_factor;
use crate::solve::quadratic_eigen::QuadraticEigenError;

/// K_n (module docs).
pub fn harmonic_stiffness(r: &RadialMatrices, plate: &PlateProperties, n: usize) -> Mat<f64> {
    let nf = n as f64;
    let (n2, n4) = (nf * nf, nf.powi(4));
    let dim = r.mass.nrows();
    Mat::from_fn(dim, dim, |i, j| {
        plate.bending_stiffness
            * (r.a[(i, j)] - n2 * (r.c[(i, j)] + r.c[(j, i)]) + n4 * r.d[(i, j)] + n2 * r.e[(i, j)])
    })
}

/// The lowest `count` eigenpairs of K Φ = λ M Φ (K symmetric, M symmetric positive definite):
/// λ ascending and Φ M-orthonormal (Φᵀ M Φ = I), by the Cholesky factor M = L Lᵀ and the
/// symmetric eigenproblem of L⁻¹ K L⁻ᵀ (faer, `Par::Seq`).
pub fn generalized_modes(
    k: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    count: usize,
    at: &str,
) -> Result<(Vec<f64>, Mat<f64>), Error> {
    let n = m.nrows();
    let l = cholesky_factor(m).map_err(|index| SolveError::Eigenproblem {
        at: at.to_string(),
        source: QuadraticEigenError::MassNotPositiveDefinite {
            row: index,
            pivot: index,
        },
    })?;
    let lower = Mat::from_fn(n, n, |i, j| if i >= j { l[(i, j)] } else { 0.0 });
    // C = L⁻¹ K L⁻ᵀ: solve L X = K, then L Cᵀ = Xᵀ
    let mut x = k.to_owned();
    solve_lower_triangular_in_place(lower.as_ref(), x.as_mut(), Par::Seq);
    let mut c = x.transpose().to_owned();
    solve_lower_triangular_in_place(lower.as_ref(), c.as_mut(), Par::Seq);
    let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
    let mut s = faer::diag::Diag::<f64>::zeros(n);
    let mut u = Mat::<f64>::zeros(n, n);
    let mut buf = MemBuffer::new(self_adjoint_evd_scratch::<f64>(
        n,
        ComputeEigenvectors::Yes,
        Par::Seq,
        Default::default(),
    ));
    self_adjoint_evd(
        c.as_ref(),
        s.as_mut(),
        Some(u.as_mut()),
        Par::Seq,
        MemStack::new(&mut buf),
        Default::default(),
    )
    .map_err(|_| SolveError::Eigenproblem {
        at: at.to_string(),
        source: QuadraticEigenError::NoConvergence {
            dimension: n,
            what: "symmetric radial eigenproblem",
        },
    })?;
    let count = count.min(n);
    let values: Vec<f64> = (0..count).map(|i| s[i]).collect();
    // Φ = L⁻ᵀ U: solve Lᵀ Φ = U by back substitution
    let mut phi = Mat::<f64>::zeros(n, count);
    for col in 0..count {
        for i in (0..n).rev() {
            let mut v = u[(i, col)];
            for j in i + 1..n {
                v -= lower[(j, i)] * phi[(j, col)];
            }
            phi[(i, col)] = v / lower[(i, i)];
        }
    }
    Ok((values, phi))
}

/// The natural frequencies ω_{n,0} < ω_{n,1} < … (the lowest `count`) of harmonic n of the
/// non-rotating plate on `elements` radial Hermite elements.
pub fn harmonic_frequencies(
    plate: &PlateProperties,
    elements: usize,
    n: usize,
    count: usize,
) -> Result<Vec<f64>, Error> {
    plate.validate()?;
    if n > 4096 {
        return Err(InputError::new("harmonic", n, "a harmonic number ≤ 4096").into());
    }
    let radial = RadialBasis::uniform(
        plate.inner_radius,
        plate.outer_radius,
        elements,
        plate.outer_edge,
    )?;
    let r = radial.matrices(plate.poisson)?;
    let k = harmonic_stiffness(&r, plate, n);
    let m = Mat::from_fn(r.mass.nrows(), r.mass.ncols(), |i, j| {
        plate.mass_per_area * r.mass[(i, j)]
    });
    let (lambda, _) =
        generalized_modes(k.as_ref(), m.as_ref(), count, &format!("harmonic n = {n}"))?;
    lambda
        .into_iter()
        .enumerate()
        .map(|(i, l)| {
            if l.is_finite() && l > 0.0 {
                Ok(l.sqrt())
            } else {
                Err(SolveError::Singular {
                    operator: format!(
                        "radial stiffness of harmonic n = {n} (ω² of mode {i} = {l:e}: \
                         the plate is not held)"
                    ),
                    row: i,
                    pivot: l,
                }
                .into())
            }
        })
        .collect()
}
