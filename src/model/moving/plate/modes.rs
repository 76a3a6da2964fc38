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
/// λ ascending and Φ M-orthonormal (Φᵀ M Φ = I).
///
/// The low modes are computed as the largest eigenvalues μ = 1/λ of the inverse problem: with
/// the Cholesky factor of the stiffness K = L Lᵀ, the symmetric matrix C = L⁻¹ M L⁻ᵀ has the
/// eigenpairs (μ, U), λ = 1/μ and Φ = L⁻ᵀ U / √μ. A backward-stable symmetric eigensolver
/// moves each μ by at most ε ‖C‖ = ε μ_max = ε/λ_min, so the lowest λ comes out to relative
/// round-off whatever the mesh. The direct reduction through the mass factor, L_M⁻¹ K L_M⁻ᵀ,
/// moves each λ by ε λ_max instead: a relative error ε λ_max/λ ∝ h⁻⁴ for a fourth-order
/// operator, which exceeds the discretization error past about 64 radial Hermite elements
/// (issue 31). The highest eigenvalues, which no caller reads as physical, pay the price of the
/// inverse form (relative error ε λ/λ_min).
///
/// When K is not positive definite (a plate that is not held; a zero or negative pivot) the
/// reduction through M's factor is used, whose eigenvalues then show the non-positive λ.
pub fn generalized_modes(
    k: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    count: usize,
    at: &str,
) -> Result<(Vec<f64>, Mat<f64>), Error> {
    if let Err(index) = cholesky_factor(m) {
        return Err(mass_not_positive_definite(index, at));
    }
    let Ok(lk) = cholesky_factor(k) else {
        return generalized_modes_by_mass(k, m, count, at);
    };
    inverse_modes(lower_triangle(&lk).as_ref(), m, count, at)
}

/// The lowest `count` eigenpairs of K Φ = λ M Φ from the lower factor L of K = L Lᵀ: the
/// largest eigenpairs (μ, U) of L⁻¹ M L⁻ᵀ, λ = 1/μ, Φ = L⁻ᵀ U / √μ.
fn inverse_modes(
    lower: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    count: usize,
    at: &str,
) -> Result<(Vec<f64>, Mat<f64>), Error> {
    let n = m.nrows();
    let (mu, u) = symmetric_eigen(&reduce(lower, m), at)?;
    let count = count.min(n);
    // μ ascending: λ_i = 1/μ_{n−1−i}
    let values: Vec<f64> = (0..count).map(|i| 1.0 / mu[n - 1 - i]).collect();
    let mut phi = Mat::<f64>::zeros(n, count);
    for col in 0..count {
        let src = n - 1 - col;
        let scale = 1.0 / mu[src].sqrt();
        back_substitute(lower, u.as_ref(), src, phi.as_mut(), col, scale);
    }
    Ok((values, phi))
}

/// The typed error for a mass matrix without a Cholesky factor.
fn mass_not_positive_definite(index: usize, at: &str) -> Error {
    SolveError::Eigenproblem {
        at: at.to_string(),
        source: QuadraticEigenError::MassNotPositiveDefinite {
            row: index,
            pivot: index,
        },
    }
    .into()
}

/// The lower triangle of a Cholesky factor (the strictly upper part zeroed).
fn lower_triangle(l: &Mat<f64>) -> Mat<f64> {
    let n = l.nrows();
    Mat::from_fn(n, n, |i, j| if i >= j { l[(i, j)] } else { 0.0 })
}

/// L⁻¹ A L⁻ᵀ, symmetrized (solve L X = A, then L Cᵀ = Xᵀ).
fn reduce(lower: MatRef<'_, f64>, a: MatRef<'_, f64>) -> Mat<f64> {
    let n = a.nrows();
    let mut x = a.to_owned();
    solve_lower_triangular_in_place(lower, x.as_mut(), Par::Seq);
    let mut c = x.transpose().to_owned();
    solve_lower_triangular_in_place(lower, c.as_mut(), Par::Seq);
    Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]))
}

/// The eigenvalues (ascending) and orthonormal eigenvectors of the symmetric `c` (faer,
/// `Par::Seq`).
fn symmetric_eigen(c: &Mat<f64>, at: &str) -> Result<(Vec<f64>, Mat<f64>), Error> {
    let n = c.nrows();
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
    Ok(((0..n).map(|i| s[i]).collect(), u))
}

/// Column `dst` of `phi` = `scale` · L⁻ᵀ (column `src` of `u`), by back substitution.
fn back_substitute(
    lower: MatRef<'_, f64>,
    u: MatRef<'_, f64>,
    src: usize,
    mut phi: faer::MatMut<'_, f64>,
    dst: usize,
    scale: f64,
) {
    let n = lower.nrows();
    for i in (0..n).rev() {
        let mut v = scale * u[(i, src)];
        for j in i + 1..n {
            v -= lower[(j, i)] * phi[(j, dst)];
        }
        phi[(i, dst)] = v / lower[(i, i)];
    }
}

/// The reduction through the mass factor M = L Lᵀ (the eigenproblem of L⁻¹ K L⁻ᵀ): the path
/// for a stiffness that is not positive definite (see [`generalized_modes`]).
fn generalized_modes_by_mass(
    k: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    count: usize,
    at: &str,
) -> Result<(Vec<f64>, Mat<f64>), Error> {
    let n = m.nrows();
    let l = cholesky_factor(m).map_err(|index| mass_not_positive_definite(index, at))?;
    let lower = lower_triangle(&l);
    let (values, u) = symmetric_eigen(&reduce(lower.as_ref(), k), at)?;
    let count = count.min(n);
    let mut phi = Mat::<f64>::zeros(n, count);
    for col in 0..count {
        back_substitute(lower.as_ref(), u.as_ref(), col, phi.as_mut(), col, 1.0);
    }
    Ok((values[..count].to_vec(), phi))
}

/// The upper triangular R with RᵀR = K_n (`RadialBasis::strain_rows`: K_n = BᵀB), by Givens
/// rotations of B's rows into R one row at a time (a backward-stable QR of B that never forms
/// BᵀB): each row has at most four consecutive nonzeros (one element's dofs), so R has upper
/// bandwidth three and each row costs at most 16 rotated pairs.
pub fn stiffness_factor(
    radial: &RadialBasis,
    plate: &PlateProperties,
    n: usize,
) -> Result<Mat<f64>, Error> {
    let dim = radial.len();
    let mut r = Mat::<f64>::zeros(dim, dim);
    let mut v = vec![0.0; dim];
    radial.strain_rows(
        plate.poisson,
        n,
        plate.bending_stiffness,
        |dofs, coefficients| {
            let (mut first, mut last) = (usize::MAX, 0);
            for (d, &c) in dofs.iter().zip(coefficients) {
                if let Some(g) = *d {
                    v[g] = c;
                    first = first.min(g);
                    last = last.max(g);
                }
            }
            if first == usize::MAX {
                return;
            }
            for k in first..=last {
                let (a, b) = (r[(k, k)], v[k]);
                if b == 0.0 {
                    continue;
                }
                let norm = a.hypot(b);
                let (c, s) = (a / norm, b / norm);
                for j in k..=last {
                    let (rj, vj) = (r[(k, j)], v[j]);
                    r[(k, j)] = c * rj + s * vj;
                    v[j] = c * vj - s * rj;
                }
                v[k] = 0.0;
            }
            for x in &mut v[first..=last] {
                *x = 0.0;
            }
        },
    )?;
    Ok(r)
}

/// The lowest `count` eigenpairs of harmonic n, K_n Φ = λ M_n Φ (λ ascending, Φᵀ M_n Φ = I),
/// through the stiffness factor R = [`stiffness_factor`] (K_n = RᵀR, never formed): the
/// largest eigenvalues μ = 1/λ of R⁻ᵀ M_n R⁻¹ (as in [`generalized_modes`]). The rounding of
/// B's entries and the QR perturb λ by about ε ‖B‖ √λ, i.e. relatively ε √(λ_max/λ), the square
/// root of what forming K_n costs (ε λ_max/λ ∝ h⁻⁴ for entries rounded before the
/// cancellation of a smooth mode's energy): at 512 elements ≈ 1e-10 instead of ≈ 1e-6.
/// A factor with a zero pivot (a plate that is not held) falls back to [`generalized_modes`].
pub fn harmonic_modes(
    radial: &RadialBasis,
    r: &RadialMatrices,
    plate: &PlateProperties,
    n: usize,
    count: usize,
    at: &str,
) -> Result<(Vec<f64>, Mat<f64>), Error> {
    let m = Mat::from_fn(r.mass.nrows(), r.mass.ncols(), |i, j| {
        plate.mass_per_area * r.mass[(i, j)]
    });
    let dim = m.nrows();
    if let Err(index) = cholesky_factor(m.as_ref()) {
        return Err(mass_not_positive_definite(index, at));
    }
    let upper = stiffness_factor(radial, plate, n)?;
    let largest = (0..dim).map(|i| upper[(i, i)].abs()).fold(0.0, f64::max);
    let held = (0..dim).all(|i| upper[(i, i)] > f64::EPSILON * dim as f64 * largest);
    if !held {
        let k = harmonic_stiffness(r, plate, n);
        return generalized_modes(k.as_ref(), m.as_ref(), count, at);
    }
    let lower = upper.transpose().to_owned();
    inverse_modes(lower.as_ref(), m.as_ref(), count, at)
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
    let at = format!("harmonic n = {n}");
    let (mut lambda, _) = harmonic_modes(&radial, &r, plate, n, count, &at)?;
    // Asked for the upper half of the spectrum too: there the direct reduction through the
    // mass factor (absolute round-off ε λ_max) beats the inverse one (relative ε λ/λ_min);
    // each eigenvalue is taken from the reduction whose error is smaller, the crossover at
    // λ = √(λ_min λ_max).
    if 2 * count > radial.len() && !lambda.is_empty() {
        let k = harmonic_stiffness(&r, plate, n);
        let m = Mat::from_fn(r.mass.nrows(), r.mass.ncols(), |i, j| {
            plate.mass_per_area * r.mass[(i, j)]
        });
        let (direct, _) = generalized_modes_by_mass(k.as_ref(), m.as_ref(), count, &at)?;
        let top = direct.last().copied().unwrap_or(0.0);
        let crossover = (lambda[0] * top).max(0.0).sqrt();
        for (l, d) in lambda.iter_mut().zip(&direct) {
            if *d > crossover {
                *l = *d;
            }
        }
    }
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

#[cfg(test)]
mod tests {
    //! Setting: the default annulus on 12 elements, every outer edge, harmonics 0 … 5. Goal: the
    //! stiffness factor reproduces K_n (RᵀR = K_n to the round-off of forming K_n), and the
    //! inverse and direct reductions agree on the low frequencies of a coarse mesh.
    use super::*;
    use crate::model::moving::plate::data::OuterEdge;

    #[test]
    fn stiffness_factor_squares_to_the_harmonic_stiffness() {
        for edge in [
            OuterEdge::Free,
            OuterEdge::Clamped,
            OuterEdge::SimplySupported,
        ] {
            let plate = PlateProperties {
                outer_edge: edge,
                ..Default::default()
            };
            let radial = RadialBasis::uniform(0.2, 1.0, 12, edge).unwrap();
            let r = radial.matrices(plate.poisson).unwrap();
            for n in 0..=5 {
                let k = harmonic_stiffness(&r, &plate, n);
                let f = stiffness_factor(&radial, &plate, n).unwrap();
                let dim = k.nrows();
                // |K| entrywise bounds the rounding of forming K: a few ε per term
                let scale = (0..dim)
                    .flat_map(|i| (0..dim).map(move |j| (i, j)))
                    .map(|(i, j)| k[(i, j)].abs())
                    .fold(0.0, f64::max);
                for i in 0..dim {
                    for j in 0..dim {
                        let rtr: f64 = (0..dim).map(|l| f[(l, i)] * f[(l, j)]).sum();
                        assert!(
                            (rtr - k[(i, j)]).abs() <= 64.0 * f64::EPSILON * scale,
                            "{edge:?}, n = {n}, ({i}, {j}): {rtr} vs {}",
                            k[(i, j)]
                        );
                        if i > j {
                            assert_eq!(f[(i, j)], 0.0);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn factor_path_and_mass_path_agree_on_a_coarse_mesh() {
        let plate = PlateProperties::default();
        let radial = RadialBasis::uniform(0.2, 1.0, 8, plate.outer_edge).unwrap();
        let r = radial.matrices(plate.poisson).unwrap();
        let m = Mat::from_fn(r.mass.nrows(), r.mass.ncols(), |i, j| {
            plate.mass_per_area * r.mass[(i, j)]
        });
        for n in 0..=3 {
            let (by_factor, phi) = harmonic_modes(&radial, &r, &plate, n, 3, "test").unwrap();
            let k = harmonic_stiffness(&r, &plate, n);
            let (by_mass, _) = generalized_modes_by_mass(k.as_ref(), m.as_ref(), 3, "t").unwrap();
            // κ = λ_max/λ_min ≈ 1e6 on 8 elements: the mass path is good to ε κ ≈ 1e-10
            for (a, b) in by_factor.iter().zip(&by_mass) {
                assert!((a - b).abs() <= 1e-9 * b, "n = {n}: {a} vs {b}");
            }
            // Φᵀ M Φ = I
            for p in 0..3 {
                for q in 0..3 {
                    let mut s = 0.0;
                    for i in 0..m.nrows() {
                        for j in 0..m.nrows() {
                            s += phi[(i, p)] * m[(i, j)] * phi[(j, q)];
                        }
                    }
                    let expect = if p == q { 1.0 } else { 0.0 };
                    assert!((s - expect).abs() < 1e-10, "n = {n}: ({p}, {q}) = {s}");
                }
            }
        }
    }
}
