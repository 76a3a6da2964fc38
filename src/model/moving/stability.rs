//! Stability verdicts from the eigenvalues of (λ² M + λ C + K) x = 0.
//!
//! The trivial solution is asymptotically stable when every Re λ < 0 and unstable when some
//! Re λ > 0: by divergence when that eigenvalue is real (a static buckling-type instability), by
//! flutter when it belongs to a complex pair (Hetzler 2009, §4.2; Huseyin 1978). Eigenvalues on
//! the imaginary axis (undamped gyroscopic or conservative systems) leave it marginal.
//!
//! Round-off decides nothing here: an eigenvalue counts as off the axis only when
//! |Re λ| > τ = max(τ_rel · ρ, τ_abs), ρ = max |λ| (the spectral scale). The default
//! τ_rel = 1e-7 ≈ 7 sqrt(ε) covers the worst case of the QR algorithm on the scaled companion
//! matrix: a simple eigenvalue moves by O(κ ε ρ), but a defective double eigenvalue (a Jordan
//! block, as at the onset of flutter of a circulatory system, where two imaginary eigenvalues
//! collide) splits by up to O(sqrt(ε) ρ) ≈ 1.5e-8 ρ. The verification case `moving_extremes`
//! approaches such Jordan blocks to 1e-14 and measures at most 4e-10 ρ below the onset (exact
//! real part 0). The price is a blind zone: a true growth or decay rate below τ is reported
//! `Marginal`, never as a wrong kind of (in)stability.

use faer::c64;
use serde::{Deserialize, Serialize};

use crate::error::InputError;

/// The verdict on the trivial solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Every Re λ < −τ: asymptotically stable.
    Stable,
    /// max Re λ within ±τ of zero: on the imaginary axis to round-off (neutral).
    Marginal,
    /// A real eigenvalue > τ.
    Divergence,
    /// A complex pair with Re λ > τ.
    Flutter,
}

impl Verdict {
    /// All verdicts, in a fixed order (for tables and legends).
    pub const ALL: [Verdict; 4] = [
        Verdict::Stable,
        Verdict::Marginal,
        Verdict::Divergence,
        Verdict::Flutter,
    ];

    /// The lowercase name.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Stable => "stable",
            Verdict::Marginal => "marginal",
            Verdict::Divergence => "divergence",
            Verdict::Flutter => "flutter",
        }
    }

    /// True for divergence and flutter.
    pub fn is_unstable(self) -> bool {
        matches!(self, Verdict::Divergence | Verdict::Flutter)
    }
}

/// The round-off tolerance of the verdicts (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerdictParams {
    /// τ_rel: relative to the spectral scale ρ = max |λ|.
    pub relative_tolerance: f64,
    /// τ_abs: the floor when ρ is tiny.
    pub absolute_tolerance: f64,
}

impl Default for VerdictParams {
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-7,
            absolute_tolerance: 1e-12,
        }
    }
}

impl VerdictParams {
    /// Checks the tolerances.
    pub fn validate(&self) -> Result<(), InputError> {
        for (f, v) in [
            ("stability.relative_tolerance", self.relative_tolerance),
            ("stability.absolute_tolerance", self.absolute_tolerance),
        ] {
            if !(v.is_finite() && (0.0..1.0).contains(&v)) {
                return Err(InputError::new(f, v, "a number in [0, 1)"));
            }
        }
        Ok(())
    }
}

/// The verdict and the numbers behind it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StabilityAssessment {
    pub verdict: Verdict,
    /// max Re λ (the growth rate of the fastest-growing solution).
    pub max_real_part: f64,
    /// The eigenvalue with the largest real part (Im ≥ 0 of a conjugate pair).
    pub critical_re: f64,
    pub critical_im: f64,
    /// τ used.
    pub tolerance: f64,
    /// The number of eigenvalues with Re λ > τ.
    pub unstable_eigenvalues: usize,
    /// The number of those that are real (|Im λ| ≤ τ).
    pub real_unstable_eigenvalues: usize,
    /// ρ = max |λ|.
    pub spectral_scale: f64,
}

/// Classifies the eigenvalues (see the module docs). An empty spectrum is `Marginal`.
pub fn assess(eigenvalues: &[c64], params: &VerdictParams) -> StabilityAssessment {
    let rho = eigenvalues.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let tol = (params.relative_tolerance * rho).max(params.absolute_tolerance);
    let mut crit = c64::new(f64::NEG_INFINITY, 0.0);
    let (mut unstable, mut real_unstable) = (0, 0);
    for &l in eigenvalues {
        if l.re > crit.re || (l.re == crit.re && l.im.abs() < crit.im.abs()) {
            crit = l;
        }
        if l.re > tol {
            unstable += 1;
            if l.im.abs() <= tol {
                real_unstable += 1;
            }
        }
    }
    if eigenvalues.is_empty() {
        crit = c64::new(0.0, 0.0);
    }
    let verdict = if crit.re > tol {
        if crit.im.abs() <= tol {
            Verdict::Divergence
        } else {
            Verdict::Flutter
        }
    } else if crit.re < -tol {
        Verdict::Stable
    } else {
        Verdict::Marginal
    };
    StabilityAssessment {
        verdict,
        max_real_part: crit.re,
        critical_re: crit.re,
        critical_im: crit.im.abs(),
        tolerance: tol,
        unstable_eigenvalues: unstable,
        real_unstable_eigenvalues: real_unstable,
        spectral_scale: rho,
    }
}

#[cfg(test)]
mod tests {
    //! Setting: hand-made spectra. Goal: each verdict, and round-off-sized real parts do not make
    //! an instability.
    use super::*;

    fn c(re: f64, im: f64) -> c64 {
        c64::new(re, im)
    }

    #[test]
    fn each_verdict_from_a_hand_made_spectrum() {
        let p = VerdictParams::default();
        let v = |e: &[c64]| assess(e, &p).verdict;
        assert_eq!(v(&[c(-0.1, 3.0), c(-0.1, -3.0)]), Verdict::Stable);
        assert_eq!(v(&[c(1e-12, 3.0), c(1e-12, -3.0)]), Verdict::Marginal);
        assert_eq!(v(&[c(0.2, 0.0), c(-0.2, 0.0)]), Verdict::Divergence);
        assert_eq!(v(&[c(0.01, 5.0), c(0.01, -5.0)]), Verdict::Flutter);
        let a = assess(&[c(0.01, 5.0), c(0.01, -5.0), c(0.3, 0.0)], &p);
        assert_eq!(a.verdict, Verdict::Divergence);
        assert_eq!(
            (a.unstable_eigenvalues, a.real_unstable_eigenvalues),
            (3, 1)
        );
        assert_eq!(assess(&[], &p).verdict, Verdict::Marginal);
    }

    #[test]
    fn tolerances_are_validated() {
        let p = VerdictParams {
            relative_tolerance: -1.0,
            ..Default::default()
        };
        assert_eq!(
            p.validate().unwrap_err().field,
            "stability.relative_tolerance"
        );
    }
}
