//! Statistics of convergence: rate fits and error models.
//!
//! A convergence study runs the solver at several levels (mesh size `h` and/or time step `k`),
//! measures an error `E` at each level and fits the observed convergence behaviour.
//!
//! * [`rate_fit`] — one-parameter power law `E ≈ C · p^r` (with `p = h` or `p = k`), fitted by
//!   ordinary least squares of `ln E` against `ln p` over the finest levels:
//!
//!   ```text
//!   x_i = ln p_i,  y_i = ln E_i,  i = 1..n   (the n finest levels)
//!   r   = Sxy / Sxx,        Sxx = Σ (x_i − x̄)²,  Sxy = Σ (x_i − x̄)(y_i − ȳ)
//!   ln C = ȳ − r x̄
//!   s²  = Σ (y_i − ln C − r x_i)² / (n − 2),     SE(r) = sqrt(s² / Sxx)
//!   CI  = r ± t_{(1+γ)/2, n−2} · SE(r)           (γ = confidence level)
//!   pairwise rate between consecutive levels: r_{i,i+1} = ln(E_i / E_{i+1}) / ln(p_i / p_{i+1})
//!   ```
//!
//! * [`error_model`] — joint two-term model `E(h, k) ≈ C_h h^p + C_k k^q` over all runs of a
//!   study, fitted by Levenberg–Marquardt on log residuals:
//!
//!   ```text
//!   θ = (a, p, c, q),  C_h = e^a,  C_k = e^c
//!   minimise S(θ) = Σ_i (ln E_i − ln(e^a h_i^p + e^c k_i^q))²
//!   s² = S(θ*) / (n − 4),  CI(θ_j) = θ*_j ± t_{(1+γ)/2, n−4} · sqrt(s² [(JᵀJ)⁻¹]_jj)
//!   ```
//!
//! * [`gci`] — Roache's grid convergence index of a scalar on systematically refined levels
//!   (observed order, Richardson extrapolation, the error band of the finest level).
//!
//! Both report failures through the shared typed error [`FitError`]; nothing in this module
//! panics on bad input.

pub mod cost_model;
pub mod error_model;
pub mod extrapolation;
pub mod gci;
pub mod lcg;
pub mod levels;
pub mod rate_fit;

use statrs::distribution::{ContinuousCDF, StudentsT, StudentsTError};

/// Why a rate fit or an error-model fit could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// Two input slices that must pair up element by element have different lengths.
    #[error("length mismatch: `{name}` has {found} values, expected {expected}")]
    LengthMismatch {
        /// Name of the offending slice.
        name: &'static str,
        /// Its length.
        found: usize,
        /// The length of the reference slice.
        expected: usize,
    },
    /// Fewer points than the fit needs (2 for a rate, 4 for the error model).
    #[error("too few usable points: {found}, at least {needed} needed")]
    TooFewPoints {
        /// Minimum number of points.
        needed: usize,
        /// Number of points available.
        found: usize,
    },
    /// A parameter (`h`, `k`) or error value is not finite and strictly positive, so its logarithm
    /// is undefined.
    #[error("`{name}[{index}]` = {value} is not finite and strictly positive")]
    InvalidValue {
        /// Name of the slice (`"param"`, `"error"`, `"h"`, `"k"`).
        name: &'static str,
        /// Index in the slice as given by the caller.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// Two levels share the same parameter value (the log-log abscissae coincide).
    #[error("duplicate parameter value {value} at indices {first} and {second}")]
    DuplicateParam {
        /// Index (as given by the caller) of the first occurrence.
        first: usize,
        /// Index (as given by the caller) of the second occurrence.
        second: usize,
        /// The repeated value.
        value: f64,
    },
    /// The confidence level is not in the open interval (0, 1).
    #[error("confidence level {0} is not in the open interval (0, 1)")]
    InvalidConfidence(f64),
    /// More finest levels requested than there are levels.
    #[error("finest = {finest} exceeds the number of levels ({levels})")]
    FinestExceedsLevels {
        /// Requested number of finest levels.
        finest: usize,
        /// Number of levels given.
        levels: usize,
    },
    /// The design of the study cannot determine a model parameter (e.g. all runs share the same
    /// time step, so the temporal exponent `q` is unidentifiable).
    #[error("parameter `{parameter}` is unidentifiable: {reason}")]
    Unidentifiable {
        /// The parameter that cannot be determined.
        parameter: &'static str,
        /// Why.
        reason: String,
    },
    /// The Jacobian at the fitted parameters is (numerically) rank deficient:
    /// `σ_min / σ_max` of `J` is below the threshold.
    #[error(
        "rank-deficient Jacobian at the fit (σ_min/σ_max = {ratio:e}): \
         the data do not determine all of (C_h, p, C_k, q)"
    )]
    RankDeficient {
        /// Ratio of the smallest to the largest singular value of the Jacobian.
        ratio: f64,
    },
    /// The nonlinear least-squares iteration did not converge from any starting point.
    #[error(
        "error-model fit did not converge after {iterations} iterations \
         (best objective {objective:e})"
    )]
    NotConverged {
        /// Iterations spent on the best start.
        iterations: usize,
        /// Best objective value reached, `Σ r_i²`.
        objective: f64,
    },
    /// The Student t distribution could not be built (invalid degrees of freedom).
    #[error("Student t distribution: {0}")]
    Distribution(String),
}

impl From<StudentsTError> for FitError {
    fn from(e: StudentsTError) -> Self {
        FitError::Distribution(e.to_string())
    }
}

/// Checks that the confidence level `γ` lies in the open interval (0, 1).
pub(crate) fn check_confidence(confidence: f64) -> Result<(), FitError> {
    if confidence > 0.0 && confidence < 1.0 {
        Ok(())
    } else {
        Err(FitError::InvalidConfidence(confidence))
    }
}

/// Two-sided Student t quantile `t_{(1+γ)/2, dof}` (`γ` already checked to be in (0, 1)).
pub(crate) fn t_quantile(confidence: f64, dof: usize) -> Result<f64, FitError> {
    let dist = StudentsT::new(0.0, 1.0, dof as f64)?;
    Ok(dist.inverse_cdf(0.5 * (1.0 + confidence)))
}

/// Checks that `values[i]` is finite and strictly positive for every `i`.
pub(crate) fn check_positive(name: &'static str, values: &[f64]) -> Result<(), FitError> {
    match values
        .iter()
        .enumerate()
        .find(|(_, v)| !(v.is_finite() && **v > 0.0))
    {
        Some((index, &value)) => Err(FitError::InvalidValue { name, index, value }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    // Setting: the shared helpers of the statistics module.
    // Goal: pin the Student t quantile against tables and the typed errors of the helpers.
    use super::*;

    #[test]
    fn t_quantile_matches_tables() {
        // t_{0.975, 3} = 3.182446305..., t_{0.95, 10} = 1.812461123...
        assert!((t_quantile(0.95, 3).unwrap() - 3.182_446_305_284_263).abs() < 1e-9);
        assert!((t_quantile(0.90, 10).unwrap() - 1.812_461_122_811_676).abs() < 1e-9);
    }

    #[test]
    fn zero_degrees_of_freedom_is_a_distribution_error() {
        assert!(matches!(
            t_quantile(0.95, 0),
            Err(FitError::Distribution(_))
        ));
    }

    #[test]
    fn helpers_reject_bad_confidence_and_values() {
        assert_eq!(check_confidence(0.0), Err(FitError::InvalidConfidence(0.0)));
        assert!(check_confidence(0.5).is_ok());
        assert_eq!(
            check_positive("h", &[1.0, 0.0]),
            Err(FitError::InvalidValue {
                name: "h",
                index: 1,
                value: 0.0
            })
        );
    }
}
