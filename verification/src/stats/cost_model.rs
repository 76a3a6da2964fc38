//! The cost model of a discretization: the work of a run as a power law in its size,
//!
//! ```text
//! t ≈ c · M^a · N^b,   ln t_i = ln c + a ln M_i + b ln N_i + r_i
//! ```
//!
//! (M the dofs or elements, N the steps), fitted by linear least squares in log space. With the
//! design matrix X (rows (1, ln M_i, ln N_i)) and `n ≥ 4` runs, `s² = Σ r_i² / (n − 3)` and the
//! confidence intervals are `θ_j ± t_{(1+γ)/2, n−3} · sqrt(s² [(XᵀX)⁻¹]_jj)` (infinite at
//! `n = 3`). For a time-stepping solver whose step costs O(M^a) (a = 1 for a banded or condensed
//! solve), b = 1: the exponents are reported so that a user sees what the pilots measured.

use nalgebra::{Matrix3, Vector3};
use serde::Serialize;

use super::{check_confidence, check_positive, t_quantile, FitError};

/// Result of [`fit_cost_model`]: `t ≈ c M^a N^b`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CostModelFit {
    /// `ln c`.
    pub log_constant: f64,
    /// Exponent of the size M and its confidence interval.
    pub a: f64,
    pub a_ci: (f64, f64),
    /// Exponent of the steps N and its confidence interval.
    pub b: f64,
    pub b_ci: (f64, f64),
    /// Confidence level of the intervals.
    pub confidence: f64,
    /// Runs used.
    pub points_used: usize,
    /// Residual standard deviation in log space (0 at n = 3).
    pub residual_std: f64,
}

impl CostModelFit {
    /// The predicted cost `c M^a N^b`.
    pub fn predict(&self, size: f64, steps: f64) -> f64 {
        (self.log_constant + self.a * size.ln() + self.b * steps.ln()).exp()
    }
}

/// Fits `t ≈ c M^a N^b` to runs `(M_i, N_i, t_i)` (module docs).
///
/// # Errors
/// [`FitError::InvalidConfidence`], [`FitError::LengthMismatch`], [`FitError::TooFewPoints`]
/// (n < 3), [`FitError::InvalidValue`] (a non-finite or non-positive value),
/// [`FitError::Unidentifiable`] (all runs share M, or N), [`FitError::RankDeficient`] (ln M and
/// ln N collinear over the runs).
pub fn fit_cost_model(
    size: &[f64],
    steps: &[f64],
    cost: &[f64],
    confidence: f64,
) -> Result<CostModelFit, FitError> {
    check_confidence(confidence)?;
    let n = size.len();
    for (name, len) in [("steps", steps.len()), ("cost", cost.len())] {
        if len != n {
            return Err(FitError::LengthMismatch {
                name,
                found: len,
                expected: n,
            });
        }
    }
    if n < 3 {
        return Err(FitError::TooFewPoints {
            needed: 3,
            found: n,
        });
    }
    check_positive("size", size)?;
    check_positive("steps", steps)?;
    check_positive("cost", cost)?;
    for (parameter, v) in [("a", size), ("b", steps)] {
        if v.iter().all(|&x| x == v[0]) {
            return Err(FitError::Unidentifiable {
                parameter,
                reason: format!("all {n} runs share the value {}", v[0]),
            });
        }
    }
    let mut xtx = Matrix3::zeros();
    let mut xty = Vector3::zeros();
    for i in 0..n {
        let x = Vector3::new(1.0, size[i].ln(), steps[i].ln());
        xtx += x * x.transpose();
        xty += x * cost[i].ln();
    }
    let eig = xtx.symmetric_eigenvalues();
    let (lo, hi) = (eig.min(), eig.max());
    if !(lo > 0.0 && lo / hi >= 1e-12) {
        return Err(FitError::RankDeficient {
            ratio: if hi > 0.0 { lo / hi } else { 0.0 },
        });
    }
    let inverse = xtx
        .try_inverse()
        .ok_or(FitError::RankDeficient { ratio: lo / hi })?;
    let theta = inverse * xty;
    let ss: f64 = (0..n)
        .map(|i| {
            let r = cost[i].ln() - theta[0] - theta[1] * size[i].ln() - theta[2] * steps[i].ln();
            r * r
        })
        .sum();
    let (residual_std, half) = if n > 3 {
        let s2 = ss / (n - 3) as f64;
        let t = t_quantile(confidence, n - 3)?;
        (s2.sqrt(), [1, 2].map(|j| t * (s2 * inverse[(j, j)]).sqrt()))
    } else {
        (0.0, [f64::INFINITY; 2])
    };
    Ok(CostModelFit {
        log_constant: theta[0],
        a: theta[1],
        a_ci: (theta[1] - half[0], theta[1] + half[0]),
        b: theta[2],
        b_ci: (theta[2] - half[1], theta[2] + half[1]),
        confidence,
        points_used: n,
        residual_std,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exact_power_law_is_recovered_with_zero_residual() {
        let (mut m, mut n, mut t) = (Vec::new(), Vec::new(), Vec::new());
        for &mi in &[10.0, 20.0, 40.0] {
            for &ni in &[50.0, 100.0, 200.0] {
                m.push(mi);
                n.push(ni);
                t.push(3e-6 * f64::powf(mi, 1.3) * f64::powf(ni, 0.9));
            }
        }
        let f = fit_cost_model(&m, &n, &t, 0.95).unwrap();
        assert!((f.a - 1.3).abs() < 1e-12, "{f:?}");
        assert!((f.b - 0.9).abs() < 1e-12, "{f:?}");
        assert!((f.log_constant - 3e-6f64.ln()).abs() < 1e-10, "{f:?}");
        assert!(f.residual_std < 1e-10, "{f:?}");
        assert!(
            (f.predict(80.0, 400.0) / (3e-6 * 80f64.powf(1.3) * 400f64.powf(0.9)) - 1.0).abs()
                < 1e-10
        );
    }

    #[test]
    fn noisy_data_give_intervals_that_contain_the_truth() {
        // a deterministic ±5 % multiplicative noise
        let noise = [1.05, 0.96, 1.02, 0.97, 1.04, 0.99, 1.01, 0.95, 1.03];
        let (mut m, mut n, mut t) = (Vec::new(), Vec::new(), Vec::new());
        let mut i = 0;
        for &mi in &[8.0, 16.0, 32.0] {
            for &ni in &[25.0, 50.0, 100.0] {
                m.push(mi);
                n.push(ni);
                t.push(1e-5 * mi * ni * noise[i]);
                i += 1;
            }
        }
        let f = fit_cost_model(&m, &n, &t, 0.95).unwrap();
        assert!(f.a_ci.0 < 1.0 && 1.0 < f.a_ci.1, "{f:?}");
        assert!(f.b_ci.0 < 1.0 && 1.0 < f.b_ci.1, "{f:?}");
        assert!(f.residual_std > 0.0 && f.residual_std < 0.1);
    }

    #[test]
    fn collinear_or_constant_designs_are_refused() {
        let e = fit_cost_model(&[1.0, 2.0, 4.0], &[3.0, 3.0, 3.0], &[1.0, 2.0, 4.0], 0.95);
        assert!(matches!(
            e,
            Err(FitError::Unidentifiable { parameter: "b", .. })
        ));
        let e = fit_cost_model(&[1.0, 2.0, 4.0], &[2.0, 4.0, 8.0], &[1.0, 2.0, 4.0], 0.95);
        assert!(matches!(e, Err(FitError::RankDeficient { .. })), "{e:?}");
        let e = fit_cost_model(&[1.0, 2.0], &[1.0, 2.0], &[1.0, 2.0], 0.95);
        assert!(matches!(e, Err(FitError::TooFewPoints { .. })));
    }
}
