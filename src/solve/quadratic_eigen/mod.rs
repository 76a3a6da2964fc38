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
//!
//! `types` holds the parameters, results and errors and the input checks of both solvers,
//! `companion` the solver of the companion form, `pencil` the QZ path.

mod companion;
mod pencil;
mod types;

pub use companion::{solve_quadratic_eigen, QuadraticEigenSolver};
pub use pencil::solve_generalized_quadratic_eigen;
pub use types::{
    frobenius_norm, EigenKernel, QuadraticEigen, QuadraticEigenError, QuadraticEigenParams,
    QuadraticEigenStats,
};

#[cfg(test)]
mod tests {
    //! Setting: small quadratic problems with known spectra. Goal: the companion solve returns
    //! them to round-off, with and without scaling, and fails with typed errors on bad input.
    use super::*;
    use faer::{c64, Mat};

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
