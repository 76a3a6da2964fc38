//! Semismooth Newton for a strictly increasing scalar equation φ(r) = 0, safeguarded by bisection.
//!
//! The contact condition condensed onto one node gives φ(r) = r + c p_ν(r) − w* with c > 0 and
//! p_ν monotone and Lipschitz, so φ is strictly increasing with slope in [1, 1 + c L_p]. Newton
//! with any element of the generalized derivative converges; for piecewise-linear p_ν it lands on
//! the exact root of the correct linear piece after finitely many steps (at most two for r ↦ r_+),
//! so the step equation is solved to round-off, not to a tolerance chosen for speed.

/// Parameters of the scalar semismooth Newton method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScalarNewtonParams {
    /// Stop when |φ(r)| ≤ `relative_tolerance` · (sum of the magnitudes of the terms of φ).
    pub relative_tolerance: f64,
    /// Fail after this many iterations.
    pub max_iterations: usize,
}

impl Default for ScalarNewtonParams {
    fn default() -> Self {
        Self {
            relative_tolerance: 8.0 * f64::EPSILON,
            max_iterations: 60,
        }
    }
}

impl ScalarNewtonParams {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), crate::error::InputError> {
        if !(self.relative_tolerance.is_finite()
            && self.relative_tolerance >= f64::EPSILON
            && self.relative_tolerance < 1e-2)
        {
            return Err(crate::error::InputError::new(
                "newton.relative_tolerance",
                self.relative_tolerance,
                "a number in [machine epsilon, 1e-2)",
            ));
        }
        if self.max_iterations == 0 {
            return Err(crate::error::InputError::new(
                "newton.max_iterations",
                0,
                "at least 1",
            ));
        }
        Ok(())
    }
}

/// One evaluation of φ: value, an element of the generalized derivative, and the magnitude scale
/// (sum of absolute values of the terms) against which the residual is measured.
#[derive(Debug, Clone, Copy)]
pub struct Evaluation {
    pub value: f64,
    pub slope: f64,
    pub scale: f64,
}

/// The converged root and the number of Newton iterations it took.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Root {
    pub r: f64,
    pub iterations: usize,
}

/// Why the iteration stopped without a root.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoRoot {
    pub iterations: usize,
    pub residual: f64,
    pub tolerance: f64,
}

/// Solves φ(r) = 0 for strictly increasing φ from the guess `r0`.
///
/// Newton steps r ← r − φ(r)/φ'(r) are kept inside the bracket of sign changes seen so far;
/// a step that leaves it (possible only for non-convex φ) is replaced by bisection.
pub fn solve_increasing(
    mut phi: impl FnMut(f64) -> Evaluation,
    r0: f64,
    params: &ScalarNewtonParams,
) -> Result<Root, NoRoot> {
    let mut r = if r0.is_finite() { r0 } else { 0.0 };
    let mut lo = f64::NEG_INFINITY;
    let mut hi = f64::INFINITY;
    let mut last_residual = f64::NAN;
    let mut last_tol = f64::NAN;
    for iteration in 0..=params.max_iterations {
        let ev = phi(r);
        last_residual = ev.value.abs();
        last_tol = params.relative_tolerance * ev.scale;
        if !(ev.value.is_finite() && ev.slope.is_finite()) {
            return Err(NoRoot {
                iterations: iteration,
                residual: ev.value,
                tolerance: last_tol,
            });
        }
        if last_residual <= last_tol {
            return Ok(Root {
                r,
                iterations: iteration,
            });
        }
        if iteration == params.max_iterations {
            break;
        }
        if ev.value > 0.0 {
            hi = r;
        } else {
            lo = r;
        }
        let mut next = if ev.slope > 0.0 {
            r - ev.value / ev.slope
        } else {
            r - ev.value
        };
        if !(next > lo && next < hi) {
            next = if lo.is_finite() && hi.is_finite() {
                0.5 * (lo + hi)
            } else if lo.is_finite() {
                lo + ev.value.abs().max(1.0)
            } else {
                hi - ev.value.abs().max(1.0)
            };
        }
        let collapsed = lo.is_finite()
            && hi.is_finite()
            && hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(lo.abs());
        if next == r || collapsed {
            // The bracket has collapsed to adjacent floating-point numbers: r is the root to
            // round-off even if cancellation keeps |φ| above the relative tolerance.
            return Ok(Root {
                r: next,
                iterations: iteration + 1,
            });
        }
        r = next;
    }
    Err(NoRoot {
        iterations: params.max_iterations,
        residual: last_residual,
        tolerance: last_tol,
    })
}

#[cfg(test)]
mod tests {
    //! Scalar semismooth Newton on the condensed contact equation r + c(β r_+ + p0) = w*: the root
    //! is exact on both branches in at most two iterations, and non-convex monotone equations still
    //! converge through the bracket.
    use super::*;

    fn lubricated(c: f64, beta: f64, p0: f64, w: f64) -> impl FnMut(f64) -> Evaluation {
        move |r| {
            let p = beta * r.max(0.0) + p0;
            Evaluation {
                value: r + c * p - w,
                slope: 1.0 + c * if r > 0.0 { beta } else { 0.0 },
                scale: r.abs() + c * p.abs() + w.abs(),
            }
        }
    }

    #[test]
    fn active_branch_root_is_exact_within_two_iterations() {
        let root =
            solve_increasing(lubricated(0.5, 3.0, 1.0, 4.0), 0.0, &Default::default()).unwrap();
        // r (1 + c β) = w − c p0  →  r = 3.5 / 2.5
        assert!((root.r - 1.4).abs() < 1e-15);
        assert!(root.iterations <= 2);
    }

    #[test]
    fn inactive_branch_root_is_exact_in_one_iteration() {
        let root =
            solve_increasing(lubricated(0.5, 3.0, 6.0, 1.0), -1.0, &Default::default()).unwrap();
        assert!((root.r - (1.0 - 3.0)).abs() < 1e-15);
        assert!(root.iterations <= 1);
    }

    #[test]
    fn huge_penalty_is_solved_without_overflow() {
        let root =
            solve_increasing(lubricated(0.7, 1e12, 0.0, 2.0), 1.0, &Default::default()).unwrap();
        assert!((root.r - 2.0 / (1.0 + 0.7e12)).abs() < 1e-26);
    }

    #[test]
    fn non_convex_monotone_equation_converges() {
        // φ(r) = r + atan(5 r) − 1: increasing, Newton alone can overshoot.
        let root = solve_increasing(
            |r| Evaluation {
                value: r + (5.0 * r).atan() - 1.0,
                slope: 1.0 + 5.0 / (1.0 + 25.0 * r * r),
                scale: r.abs() + (5.0 * r).atan().abs() + 1.0,
            },
            30.0,
            &Default::default(),
        )
        .unwrap();
        assert!((root.r + (5.0 * root.r).atan() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn non_finite_equation_is_reported() {
        let err = solve_increasing(
            |_| Evaluation {
                value: f64::NAN,
                slope: 1.0,
                scale: 1.0,
            },
            0.0,
            &Default::default(),
        )
        .unwrap_err();
        assert!(err.residual.is_nan());
    }
}
