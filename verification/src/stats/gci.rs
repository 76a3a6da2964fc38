//! Self-convergence of a scalar quantity on systematically refined resolutions: Roache's grid
//! convergence index (Roache 1994, 1998; the procedure of Celik et al., J. Fluids Eng. 130
//! (2008) 078001).
//!
//! Levels f_1 (finest), f_2, f_3, … are computed with mesh and step refined together by a
//! constant ratio r > 1 (h_{i+1} = r h_i). With ε_21 = f_2 − f_1 and ε_32 = f_3 − f_2:
//!
//!   R = ε_21 / ε_32                          (0 < R < 1: monotone; −1 < R < 0: oscillatory)
//!   p = ln|ε_32 / ε_21| / ln r               (observed order, from the three finest levels)
//!   f_ext = (r^p f_1 − f_2) / (r^p − 1)      (Richardson extrapolation)
//!   GCI_fine = F_s |ε_21 / f_1| / (r^p − 1), F_s = 1.25   (the fine level's relative error band)
//!   GCI_coarse = F_s |ε_32 / f_2| / (r^p − 1).
//!
//! Asymptotic range. Roache's check GCI_coarse ≈ r^p GCI_fine is empty when p is observed on the
//! same three levels: then GCI_coarse / (r^p GCI_fine) = f_1/f_2 identically. With four levels
//! the check is made informative by taking p from the coarser triple (f_2, f_3, f_4), p_c:
//!
//!   A = GCI_coarse(p_c) / (r^{p_c} GCI_fine(p_c)) = (f_1/f_2) r^{p − p_c},
//!
//! which is 1 (up to f_1/f_2) exactly when the finer and the coarser triples show the same order.
//!
//! Order not verified. When the three finest levels do not show an order compatible with the
//! formal one p_f (no monotone or oscillatory convergence, or p outside [p_f/2, 2 p_f], e.g. when
//! the finest pair agrees to the noise of the quantity), the GCI falls back to Roache's
//! two-level form with the formal order and the larger safety factor F_s = 3:
//! GCI_fine = 3 |ε_21 / f_1| / (r^{p_f} − 1).

use serde::Serialize;

/// Roache's safety factor for studies with three or more levels and an observed order.
pub const SAFETY_FACTOR: f64 = 1.25;

/// Roache's safety factor when the order is not verified (two levels, formal order).
pub const FALLBACK_SAFETY_FACTOR: f64 = 3.0;

/// How the three finest levels approach the limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Convergence {
    /// 0 < R < 1.
    Monotone,
    /// −1 < R < 0 (p from |R|).
    Oscillatory,
    /// |R| ≥ 1: the differences do not shrink.
    Divergent,
    /// ε_21 = ε_32 = 0: the quantity is the same on every level (e.g. saturated at a bound).
    Constant,
}

/// The self-convergence analysis of one quantity.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GciResult {
    /// Values from the coarsest to the finest level.
    pub values: Vec<f64>,
    pub ratio: f64,
    pub convergence: Convergence,
    /// p from the three finest levels (None when constant or divergent).
    pub order: Option<f64>,
    /// p_c from the next three (with four or more levels).
    pub coarse_order: Option<f64>,
    /// Whether p is compatible with the formal order (in [p_f/2, 2 p_f]).
    pub order_verified: bool,
    /// The order and the safety factor of the GCI (p and 1.25, or p_f and 3).
    pub order_used: f64,
    pub safety_factor: f64,
    pub extrapolated: Option<f64>,
    /// In per cent.
    pub gci_fine_percent: Option<f64>,
    pub gci_coarse_percent: Option<f64>,
    /// A of the module documentation (four or more levels).
    pub asymptotic_ratio: Option<f64>,
}

/// Why a quantity cannot be analysed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GciError {
    #[error("{0} levels: at least 3 are needed")]
    TooFewLevels(usize),
    #[error("refinement ratio {0}: must be finite and > 1")]
    Ratio(f64),
    #[error("formal order {0}: must be finite and > 0")]
    FormalOrder(f64),
    #[error("value {index} = {value} is not finite")]
    NonFinite { index: usize, value: f64 },
}

/// The observed order from three levels (fine, medium, coarse) and the convergence type.
fn order_of(fine: f64, medium: f64, coarse: f64, ratio: f64) -> (Convergence, Option<f64>) {
    let (e21, e32) = (medium - fine, coarse - medium);
    if e21 == 0.0 && e32 == 0.0 {
        return (Convergence::Constant, None);
    }
    if e32 == 0.0 {
        return (Convergence::Divergent, None);
    }
    let r = e21 / e32;
    let kind = if r.abs() >= 1.0 {
        Convergence::Divergent
    } else if r > 0.0 {
        Convergence::Monotone
    } else if r < 0.0 {
        Convergence::Oscillatory
    } else {
        // e21 = 0 with e32 ≠ 0: converged on the two finest levels (order unbounded)
        return (Convergence::Monotone, None);
    };
    match kind {
        Convergence::Divergent => (kind, None),
        _ => (kind, Some((e32 / e21).abs().ln() / ratio.ln())),
    }
}

/// GCI (per cent) of the pair (fine, coarse) with order p and safety factor `fs`.
fn gci(fine: f64, coarse: f64, ratio: f64, p: f64, fs: f64) -> f64 {
    100.0 * fs * ((coarse - fine) / fine).abs() / (ratio.powf(p) - 1.0)
}

/// The analysis of `values` (coarsest first) refined by `ratio` between levels, with the formal
/// order `formal` of the quantity.
pub fn analyse(values: &[f64], ratio: f64, formal: f64) -> Result<GciResult, GciError> {
    if values.len() < 3 {
        return Err(GciError::TooFewLevels(values.len()));
    }
    if !(ratio.is_finite() && ratio > 1.0) {
        return Err(GciError::Ratio(ratio));
    }
    if !(formal.is_finite() && formal > 0.0) {
        return Err(GciError::FormalOrder(formal));
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(GciError::NonFinite {
            index: i,
            value: values[i],
        });
    }
    let n = values.len();
    let (f1, f2, f3) = (values[n - 1], values[n - 2], values[n - 3]);
    let (convergence, order) = order_of(f1, f2, f3, ratio);
    let coarse_order = if n >= 4 {
        order_of(f2, f3, values[n - 4], ratio).1
    } else {
        None
    };
    let verified = matches!(convergence, Convergence::Constant)
        || order.is_some_and(|p| (0.5 * formal..=2.0 * formal).contains(&p));
    let (p, fs) = match order {
        Some(p) if verified => (p, SAFETY_FACTOR),
        _ => (formal, FALLBACK_SAFETY_FACTOR),
    };
    let extrapolated = match convergence {
        Convergence::Constant => Some(f1),
        Convergence::Divergent => None,
        _ => Some((ratio.powf(p) * f1 - f2) / (ratio.powf(p) - 1.0)),
    };
    let (gci_fine, gci_coarse) = match convergence {
        Convergence::Constant => (0.0, 0.0),
        _ => (gci(f1, f2, ratio, p, fs), gci(f2, f3, ratio, p, fs)),
    };
    let asymptotic_ratio = coarse_order.filter(|_| verified).map(|pc| {
        gci(f2, f3, ratio, pc, SAFETY_FACTOR)
            / (ratio.powf(pc) * gci(f1, f2, ratio, pc, SAFETY_FACTOR))
    });
    Ok(GciResult {
        values: values.to_vec(),
        ratio,
        convergence,
        order,
        coarse_order,
        order_verified: verified,
        order_used: p,
        safety_factor: fs,
        extrapolated,
        gci_fine_percent: Some(gci_fine),
        gci_coarse_percent: Some(gci_coarse),
        asymptotic_ratio,
    })
}

#[cfg(test)]
mod tests {
    //! The GCI formulas on sequences with a known limit and order: f(h) = f* + C h^p.
    use super::*;

    fn sequence(limit: f64, c: f64, p: f64, h0: f64, ratio: f64, levels: usize) -> Vec<f64> {
        (0..levels)
            .map(|i| limit + c * (h0 / ratio.powi(i as i32)).powf(p))
            .collect()
    }

    #[test]
    fn exact_power_law_gives_its_order_limit_and_gci() {
        let v = sequence(2.0, 0.5, 2.0, 0.4, 2.0, 4);
        let g = analyse(&v, 2.0, 2.0).unwrap();
        assert_eq!(g.convergence, Convergence::Monotone);
        assert!(g.order_verified && g.safety_factor == SAFETY_FACTOR);
        assert!((g.order.unwrap() - 2.0).abs() < 1e-10);
        assert!((g.coarse_order.unwrap() - 2.0).abs() < 1e-10);
        assert!((g.extrapolated.unwrap() - 2.0).abs() < 1e-12);
        // GCI_fine = 1.25 |f2 − f1|/f1 / 3, with f1 = 2 + 0.5·0.05², f2 = 2 + 0.5·0.1²
        let (f1, f2) = (2.0 + 0.5 * 0.05f64.powi(2), 2.0 + 0.5 * 0.1f64.powi(2));
        let expected = 100.0 * 1.25 * (f2 - f1) / f1 / 3.0;
        assert!((g.gci_fine_percent.unwrap() - expected).abs() < 1e-12);
        // same order on both triples: A = f1/f2
        assert!((g.asymptotic_ratio.unwrap() - f1 / f2).abs() < 1e-12);
    }

    #[test]
    fn pre_asymptotic_coarse_level_moves_the_asymptotic_ratio_away_from_one() {
        let mut v = sequence(1.0, 1.0, 1.0, 0.2, 2.0, 4);
        // the coarsest level is far off: the coarse triple shows another order
        v[0] += 0.3;
        let g = analyse(&v, 2.0, 1.0).unwrap();
        assert!((g.order.unwrap() - 1.0).abs() < 1e-10);
        assert!(g.coarse_order.unwrap() > 2.0);
        assert!((g.asymptotic_ratio.unwrap() - 1.0).abs() > 0.5);
    }

    #[test]
    fn oscillatory_divergent_and_constant_sequences_are_classified() {
        let osc = analyse(&[1.0 + 0.4, 1.0 - 0.2, 1.0 + 0.1], 2.0, 1.0).unwrap();
        assert_eq!(osc.convergence, Convergence::Oscillatory);
        assert!((osc.order.unwrap() - 1.0).abs() < 1e-12);
        let div = analyse(&[1.0, 1.1, 1.3], 2.0, 1.0).unwrap();
        assert_eq!(div.convergence, Convergence::Divergent);
        assert!(div.order.is_none() && div.extrapolated.is_none());
        let flat = analyse(&[5e-4; 3], 2.0, 1.0).unwrap();
        assert_eq!(flat.convergence, Convergence::Constant);
        assert_eq!(flat.gci_fine_percent, Some(0.0));
    }

    #[test]
    fn unverified_order_falls_back_to_the_formal_order_with_safety_factor_three() {
        // divergent: the differences grow
        let div = analyse(&[1.0, 1.1, 1.3], 2.0, 1.0).unwrap();
        assert!(!div.order_verified);
        let expected = 100.0 * 3.0 * (0.2 / 1.3) / 1.0;
        assert!((div.gci_fine_percent.unwrap() - expected).abs() < 1e-12);
        // an observed order far above the formal one (the finest pair agrees by accident)
        let fast = analyse(&[1.0, 1.1, 1.1001], 2.0, 1.0).unwrap();
        assert!(fast.order.unwrap() > 2.0 && !fast.order_verified);
        assert_eq!(fast.order_used, 1.0);
        assert!(fast.asymptotic_ratio.is_none());
    }

    #[test]
    fn bad_inputs_are_typed_errors() {
        assert_eq!(
            analyse(&[1.0, 2.0], 2.0, 1.0),
            Err(GciError::TooFewLevels(2))
        );
        assert_eq!(
            analyse(&[1.0, 2.0, 3.0], 1.0, 1.0),
            Err(GciError::Ratio(1.0))
        );
        assert_eq!(
            analyse(&[1.0, 2.0, 3.0], 2.0, 0.0),
            Err(GciError::FormalOrder(0.0))
        );
        assert!(matches!(
            analyse(&[1.0, f64::NAN, 3.0], 2.0, 1.0),
            Err(GciError::NonFinite { index: 1, .. })
        ));
    }
}
