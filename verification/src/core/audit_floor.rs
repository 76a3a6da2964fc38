//! The round-off floor the audits recomputed from the state share (docs/multibody.md and
//! docs/dynamic.md, "The audit recomputed from the state").
//!
//! A sum of N terms, each rounded to nearest, in any order, differs from the exact sum by at most
//! γ_N Σ|terms| ≈ N ε Σ|terms| (Higham); the records a solver keeps and the values recomputed
//! from the state are two such sums, each with a few further rounded operations per term. The
//! floor C ε (N + 30) S, S = Σ|terms|, takes both: C = 2 for the two evaluations, 30 for the
//! operations before the sum.

/// C of the floor C ε (N + 30) S.
pub const C: f64 = 2.0;

/// C ε (N + 30) S for a sum of `terms` terms of total magnitude `magnitude` (at least the
/// smallest positive double, so that a ratio over it is finite).
pub fn floor(terms: usize, magnitude: f64) -> f64 {
    (C * f64::EPSILON * (terms as f64 + 30.0) * magnitude).max(f64::MIN_POSITIVE)
}

/// max that keeps a NaN (a NaN ratio fails every gate).
pub fn max_nan(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_nan_survives_the_maximum_and_the_floor_is_never_zero() {
        assert!(max_nan(1.0, f64::NAN).is_nan() && max_nan(f64::NAN, 1.0).is_nan());
        assert_eq!(max_nan(1.0, 2.0), 2.0);
        assert!(floor(0, 0.0) > 0.0);
        assert_eq!(floor(10, 1.0), 2.0 * f64::EPSILON * 40.0);
    }
}
