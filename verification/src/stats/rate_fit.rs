//! Observed convergence rate: least-squares fit of `ln E` against `ln p` (`p = h` or `p = k`).
//!
//! Model `E ≈ C · p^r`, i.e. `ln E = ln C + r · ln p`. Over the `n` finest levels
//! (`x_i = ln p_i`, `y_i = ln E_i`):
//!
//! ```text
//! r     = Sxy / Sxx,   Sxx = Σ (x_i − x̄)²,   Sxy = Σ (x_i − x̄)(y_i − ȳ)
//! ln C  = ȳ − r x̄
//! s²    = SSR / (n − 2),   SSR = Σ (y_i − ln C − r x_i)²
//! SE(r) = sqrt(s² / Sxx)
//! CI    = r ± t_{(1+γ)/2, n−2} · SE(r)
//! ```
//!
//! and, between consecutive levels (coarse to fine), `r_{i,i+1} = ln(E_i/E_{i+1}) / ln(p_i/p_{i+1})`.

use serde::Serialize;

use super::{check_confidence, check_positive, t_quantile, FitError};

/// Observed rate between two consecutive levels:
/// `rate = ln(E_from / E_to) / ln(from / to)`, with `from > to` (coarse to fine).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairwiseRate {
    /// Parameter value (`h` or `k`) of the coarser level, `p_i`.
    pub from: f64,
    /// Parameter value of the finer level, `p_{i+1}`.
    pub to: f64,
    /// `ln(E_i / E_{i+1}) / ln(p_i / p_{i+1})`.
    pub rate: f64,
}

/// Least-squares power-law fit `E ≈ C · p^rate` over the finest levels of a study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RateFit {
    /// Slope of `ln E` against `ln p`: `rate = Sxy / Sxx` (positive when `E` decreases with `p`).
    pub rate: f64,
    /// Intercept `ln C = ȳ − rate · x̄`.
    pub log_constant: f64,
    /// Lower end of the confidence interval `rate − t_{(1+γ)/2, n−2} · SE(rate)`
    /// (`−∞` when `n = 2`).
    pub ci_low: f64,
    /// Upper end of the confidence interval `rate + t_{(1+γ)/2, n−2} · SE(rate)`
    /// (`+∞` when `n = 2`).
    pub ci_high: f64,
    /// Confidence level `γ` of the interval, in (0, 1).
    pub confidence: f64,
    /// Number `n` of (finest) levels used in the fit.
    pub points_used: usize,
    /// Residual standard deviation `s = sqrt(SSR / (n − 2))` in log space
    /// (0 when `n = 2`: the line interpolates both points and no degree of freedom is left).
    pub residual_std: f64,
    /// Rates between every pair of consecutive levels (all levels, coarse to fine), see
    /// [`pairwise_rates`].
    pub pairwise: Vec<PairwiseRate>,
}

impl RateFit {
    /// Width of the confidence interval, `ci_high − ci_low` (`+∞` when `n = 2`).
    pub fn ci_width(&self) -> f64 {
        self.ci_high - self.ci_low
    }
}

/// Fits `ln E = ln C + rate · ln p` by least squares over the `finest` levels with the smallest
/// parameter values.
///
/// Levels may be given in any order; they are sorted by `param` descending (coarse to fine).
/// With `n = finest`, `x_i = ln p_i`, `y_i = ln E_i`:
/// `rate = Sxy / Sxx`, `ln C = ȳ − rate · x̄`, `s² = SSR / (n − 2)`,
/// `CI = rate ± t_{(1+γ)/2, n−2} · sqrt(s² / Sxx)` with `γ = confidence`.
/// For `n = 2` the interval is `(−∞, +∞)`.
/// [`RateFit::pairwise`] holds the consecutive-level rates over *all* levels.
///
/// # Errors
/// [`FitError::InvalidConfidence`] if `confidence ∉ (0, 1)`; [`FitError::LengthMismatch`] if the
/// slices differ in length; [`FitError::FinestExceedsLevels`] if `finest > param.len()`;
/// [`FitError::TooFewPoints`] if `finest < 2`; [`FitError::InvalidValue`] for a non-finite or
/// non-positive `param` or `error` value; [`FitError::DuplicateParam`] if two levels share a
/// parameter value.
pub fn fit_rate(
    param: &[f64],
    error: &[f64],
    finest: usize,
    confidence: f64,
) -> Result<RateFit, FitError> {
    check_confidence(confidence)?;
    let levels = param.len();
    if error.len() != levels {
        return Err(FitError::LengthMismatch {
            name: "error",
            found: error.len(),
            expected: levels,
        });
    }
    if finest > levels {
        return Err(FitError::FinestExceedsLevels { finest, levels });
    }
    if finest < 2 {
        return Err(FitError::TooFewPoints {
            needed: 2,
            found: finest,
        });
    }
    check_positive("param", param)?;
    check_positive("error", error)?;

    let order = coarse_to_fine(param);
    if let Some(pair) = order
        .windows(2)
        .find(|w| param[w[0]].ln() == param[w[1]].ln())
    {
        return Err(FitError::DuplicateParam {
            first: pair[0].min(pair[1]),
            second: pair[0].max(pair[1]),
            value: param[pair[0]],
        });
    }

    let used = &order[levels - finest..];
    let x: Vec<f64> = used.iter().map(|&i| param[i].ln()).collect();
    let y: Vec<f64> = used.iter().map(|&i| error[i].ln()).collect();
    let n = finest as f64;
    let x_mean = x.iter().sum::<f64>() / n;
    let y_mean = y.iter().sum::<f64>() / n;
    let sxx: f64 = x.iter().map(|xi| (xi - x_mean).powi(2)).sum();
    let sxy: f64 = x
        .iter()
        .zip(&y)
        .map(|(xi, yi)| (xi - x_mean) * (yi - y_mean))
        .sum();
    let rate = sxy / sxx;
    let log_constant = y_mean - rate * x_mean;

    let (ci_low, ci_high, residual_std) = if finest >= 3 {
        let ssr: f64 = x
            .iter()
            .zip(&y)
            .map(|(xi, yi)| (yi - log_constant - rate * xi).powi(2))
            .sum();
        let dof = finest - 2;
        let s2 = ssr / dof as f64;
        let se = (s2 / sxx).sqrt();
        let half = t_quantile(confidence, dof)? * se;
        (rate - half, rate + half, s2.sqrt())
    } else {
        (f64::NEG_INFINITY, f64::INFINITY, 0.0)
    };

    Ok(RateFit {
        rate,
        log_constant,
        ci_low,
        ci_high,
        confidence,
        points_used: finest,
        residual_std,
        pairwise: pairwise_rates(param, error),
    })
}

/// Rates between consecutive levels, coarse to fine:
/// `rate_i = ln(E_i / E_{i+1}) / ln(p_i / p_{i+1})` with the levels sorted by `param` descending.
///
/// Never fails: only the first `min(param.len(), error.len())` levels are considered, levels
/// whose `param` or `error` is not finite and strictly positive are skipped, and a pair of
/// levels with the same parameter value yields no rate. [`fit_rate`] validates its inputs first,
/// so for it every consecutive pair yields a rate.
pub fn pairwise_rates(param: &[f64], error: &[f64]) -> Vec<PairwiseRate> {
    let valid = |v: f64| v.is_finite() && v > 0.0;
    let mut levels: Vec<(f64, f64)> = param
        .iter()
        .zip(error)
        .filter(|(p, e)| valid(**p) && valid(**e))
        .map(|(&p, &e)| (p, e))
        .collect();
    levels.sort_by(|a, b| b.0.total_cmp(&a.0));
    levels
        .windows(2)
        .filter_map(|w| {
            let (p0, e0) = w[0];
            let (p1, e1) = w[1];
            let dx = p0.ln() - p1.ln();
            (dx != 0.0).then(|| PairwiseRate {
                from: p0,
                to: p1,
                rate: (e0.ln() - e1.ln()) / dx,
            })
        })
        .collect()
}

/// Indices of `param` sorted by value descending (coarse to fine); ties keep the input order.
fn coarse_to_fine(param: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..param.len()).collect();
    order.sort_by(|&i, &j| param[j].total_cmp(&param[i]));
    order
}

#[cfg(test)]
mod tests {
    // Setting: power laws E = C h^r on halving meshes, exact or with fixed ±1% perturbations.
    // Goal: pin the fitted slope, its Student-t confidence interval, the finest-level selection,
    // the pairwise rates and every typed error of `fit_rate`.
    use super::*;

    fn halving(levels: usize) -> Vec<f64> {
        (0..levels).map(|i| 0.5_f64.powi(i as i32 + 1)).collect()
    }

    /// t_{0.975, 3}, from tables (independent of statrs).
    const T_975_DOF3: f64 = 3.182_446_305_284_263;

    #[test]
    fn rate_of_exact_power_law_is_exact() {
        let h = halving(6);
        let e: Vec<f64> = h.iter().map(|h| 3.0 * h * h).collect();
        let fit = fit_rate(&h, &e, 6, 0.95).unwrap();
        assert!((fit.rate - 2.0).abs() <= 1e-12, "rate {}", fit.rate);
        assert!((fit.log_constant - 3.0_f64.ln()).abs() <= 1e-12);
        assert!(fit.ci_width() <= 1e-10, "width {}", fit.ci_width());
        assert!(fit.ci_low <= fit.rate && fit.rate <= fit.ci_high);
        assert!(fit.residual_std <= 1e-12);
        assert_eq!(fit.points_used, 6);
        assert_eq!(fit.confidence, 0.95);
    }

    #[test]
    fn noisy_power_law_matches_hand_computed_slope_and_interval() {
        let h = halving(5);
        let delta = [0.01, -0.01, 0.004, -0.006, 0.008];
        let e: Vec<f64> = h
            .iter()
            .zip(delta)
            .map(|(h, d)| 2.0 * h.powf(1.5) * (1.0 + d))
            .collect();
        let fit = fit_rate(&h, &e, 5, 0.95).unwrap();

        // Hand computation with the uncentred textbook formulas.
        let x: Vec<f64> = h.iter().map(|v| v.ln()).collect();
        let y: Vec<f64> = e.iter().map(|v| v.ln()).collect();
        let n = 5.0;
        let (sx, sy) = (x.iter().sum::<f64>(), y.iter().sum::<f64>());
        let sxx: f64 = x.iter().map(|v| v * v).sum();
        let sxy: f64 = x.iter().zip(&y).map(|(a, b)| a * b).sum();
        let slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
        let intercept = (sy - slope * sx) / n;
        let ssr: f64 = x
            .iter()
            .zip(&y)
            .map(|(a, b)| (b - intercept - slope * a).powi(2))
            .sum();
        let se = (ssr / (n - 2.0) / (sxx - sx * sx / n)).sqrt();
        let half = T_975_DOF3 * se;

        assert!(
            (fit.rate - slope).abs() <= 1e-10,
            "{} vs {}",
            fit.rate,
            slope
        );
        assert!((fit.log_constant - intercept).abs() <= 1e-10);
        assert!((fit.ci_low - (slope - half)).abs() <= 1e-9);
        assert!((fit.ci_high - (slope + half)).abs() <= 1e-9);
        assert!((fit.residual_std - (ssr / (n - 2.0)).sqrt()).abs() <= 1e-12);
        assert!(fit.ci_low < fit.rate && fit.rate < fit.ci_high);
        assert!(fit.ci_low < 1.5 && 1.5 < fit.ci_high, "{fit:?}");
        assert!(fit.ci_width() > 0.0 && fit.ci_width() < 0.1, "{fit:?}");
    }

    #[test]
    fn only_the_finest_levels_enter_the_fit() {
        // Levels given out of order; the coarsest (h = 1/2) is pre-asymptotic (rate 1 into it).
        let h = [0.125, 0.5, 0.03125, 0.25, 0.0625];
        let e: Vec<f64> = h
            .iter()
            .map(|&h: &f64| if h == 0.5 { 10.0 * h } else { 3.0 * h * h })
            .collect();
        let fine = fit_rate(&h, &e, 4, 0.95).unwrap();
        assert!((fine.rate - 2.0).abs() <= 1e-12, "{fine:?}");
        assert!(fine.ci_width() <= 1e-10);
        assert_eq!(fine.points_used, 4);
        let all = fit_rate(&h, &e, 5, 0.95).unwrap();
        assert!((all.rate - 2.0).abs() > 0.1, "{all:?}");
        // Pairwise rates cover all levels, coarse to fine, whatever `finest` is.
        assert_eq!(fine.pairwise, all.pairwise);
        assert_eq!(fine.pairwise.len(), 4);
        assert_eq!((fine.pairwise[0].from, fine.pairwise[0].to), (0.5, 0.25));
        assert!((fine.pairwise[0].rate - 2.0).abs() > 0.1);
    }

    #[test]
    fn pairwise_rates_of_power_law_equal_the_rate() {
        let h = [0.1, 0.4, 0.05, 0.2, 0.025];
        let e: Vec<f64> = h.iter().map(|h: &f64| 0.3 * h.powf(1.25)).collect();
        let rates = pairwise_rates(&h, &e);
        assert_eq!(rates.len(), 4);
        let params: Vec<(f64, f64)> = rates.iter().map(|r| (r.from, r.to)).collect();
        assert_eq!(
            params,
            vec![(0.4, 0.2), (0.2, 0.1), (0.1, 0.05), (0.05, 0.025)]
        );
        for r in &rates {
            assert!((r.rate - 1.25).abs() <= 1e-12, "{r:?}");
        }
    }

    #[test]
    fn pairwise_rates_skip_unusable_levels_without_panicking() {
        let h = [0.4, f64::NAN, 0.2, 0.2, 0.1, -1.0];
        let e = [0.16, 1.0, 0.04, 0.04, 0.01];
        let rates = pairwise_rates(&h, &e);
        // Levels 0.4, 0.2, 0.2, 0.1 survive; the duplicate pair yields no rate.
        assert_eq!(rates.len(), 2);
        assert!(rates.iter().all(|r| (r.rate - 2.0).abs() <= 1e-12));
    }

    #[test]
    fn two_points_give_infinite_interval_not_nan() {
        let fit = fit_rate(&[0.5, 0.25], &[0.5, 0.125], 2, 0.95).unwrap();
        assert!((fit.rate - 2.0).abs() <= 1e-12);
        assert_eq!(fit.ci_low, f64::NEG_INFINITY);
        assert_eq!(fit.ci_high, f64::INFINITY);
        assert!(!fit.residual_std.is_nan());
        assert_eq!(fit.points_used, 2);
    }

    #[test]
    fn two_finest_of_many_levels_give_infinite_interval() {
        let h = halving(4);
        let e: Vec<f64> = h.iter().map(|h| h * h).collect();
        let fit = fit_rate(&h, &e, 2, 0.9).unwrap();
        assert!(fit.ci_low.is_infinite() && fit.ci_high.is_infinite());
        assert_eq!(fit.pairwise.len(), 3);
    }

    #[test]
    fn length_mismatch_is_an_error() {
        assert_eq!(
            fit_rate(&[0.5, 0.25, 0.125], &[1.0, 0.5], 2, 0.95),
            Err(FitError::LengthMismatch {
                name: "error",
                found: 2,
                expected: 3
            })
        );
    }

    #[test]
    fn fewer_than_two_points_is_an_error() {
        assert_eq!(
            fit_rate(&[0.5, 0.25, 0.125], &[1.0, 0.5, 0.25], 1, 0.95),
            Err(FitError::TooFewPoints {
                needed: 2,
                found: 1
            })
        );
        assert_eq!(
            fit_rate(&[0.5], &[1.0], 1, 0.95),
            Err(FitError::TooFewPoints {
                needed: 2,
                found: 1
            })
        );
        assert_eq!(
            fit_rate(&[], &[], 0, 0.95),
            Err(FitError::TooFewPoints {
                needed: 2,
                found: 0
            })
        );
    }

    #[test]
    fn non_positive_or_non_finite_values_name_index_and_value() {
        let e = [1.0, 0.5, 0.25];
        assert_eq!(
            fit_rate(&[0.5, -0.25, 0.125], &e, 3, 0.95),
            Err(FitError::InvalidValue {
                name: "param",
                index: 1,
                value: -0.25
            })
        );
        assert_eq!(
            fit_rate(&[0.5, 0.25, f64::INFINITY], &e, 3, 0.95),
            Err(FitError::InvalidValue {
                name: "param",
                index: 2,
                value: f64::INFINITY
            })
        );
        assert_eq!(
            fit_rate(&[0.5, 0.25, 0.125], &[0.0, 0.5, 0.25], 3, 0.95),
            Err(FitError::InvalidValue {
                name: "error",
                index: 0,
                value: 0.0
            })
        );
        match fit_rate(&[0.5, 0.25, 0.125], &[1.0, f64::NAN, 0.25], 3, 0.95) {
            Err(FitError::InvalidValue { name, index, value }) => {
                assert_eq!((name, index), ("error", 1));
                assert!(value.is_nan());
            }
            other => panic!("expected InvalidValue, got {other:?}"),
        }
    }

    #[test]
    fn duplicate_param_is_an_error() {
        assert_eq!(
            fit_rate(&[0.25, 0.5, 0.25], &[1.0, 2.0, 0.9], 3, 0.95),
            Err(FitError::DuplicateParam {
                first: 0,
                second: 2,
                value: 0.25
            })
        );
    }

    #[test]
    fn confidence_outside_open_unit_interval_is_an_error() {
        let (h, e) = ([0.5, 0.25, 0.125], [1.0, 0.5, 0.25]);
        for c in [0.0, 1.0, -0.5, 1.5] {
            assert_eq!(fit_rate(&h, &e, 3, c), Err(FitError::InvalidConfidence(c)));
        }
        assert!(matches!(
            fit_rate(&h, &e, 3, f64::NAN),
            Err(FitError::InvalidConfidence(c)) if c.is_nan()
        ));
    }

    #[test]
    fn finest_beyond_level_count_is_an_error() {
        assert_eq!(
            fit_rate(&[0.5, 0.25, 0.125], &[1.0, 0.5, 0.25], 4, 0.95),
            Err(FitError::FinestExceedsLevels {
                finest: 4,
                levels: 3
            })
        );
    }

    #[test]
    fn higher_confidence_widens_the_interval() {
        let h = halving(5);
        let delta = [0.01, -0.01, 0.004, -0.006, 0.008];
        let e: Vec<f64> = h.iter().zip(delta).map(|(h, d)| h * (1.0 + d)).collect();
        let w90 = fit_rate(&h, &e, 5, 0.90).unwrap().ci_width();
        let w99 = fit_rate(&h, &e, 5, 0.99).unwrap().ci_width();
        assert!(w99 > w90 && w90 > 0.0);
    }
}
