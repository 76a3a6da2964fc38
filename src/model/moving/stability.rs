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
//!
//! Discretized continua: only the eigenvalues below the basis's resolution limit ω_res
//! (`resolution.rs`) stand for the continuum. [`assess_resolved`] reads the verdict from them
//! alone and reports the unstable eigenvalues above ω_res separately (their count, frequency range
//! and largest real part) as a discretization warning — never as the system's verdict.

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
    /// Read the verdict from the resolved eigenvalues only (the default; `resolution.rs`).
    /// `false` reads every eigenvalue: for a low-order model meant as the model itself (a
    /// one-mode string), not as an approximation of the continuum.
    pub resolved_only: bool,
}

impl Default for VerdictParams {
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-7,
            absolute_tolerance: 1e-12,
            resolved_only: true,
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
    /// The resolution limit ω_res: the verdict reads the eigenvalues with |Im λ| ≤ ω_res
    /// (infinite: every eigenvalue; then absent from the JSON, which has no ∞).
    #[serde(skip_serializing_if = "is_infinite")]
    pub resolution_limit: f64,
    /// The discretization warning: the unstable eigenvalues (Re λ > τ) above ω_res.
    pub unresolved: UnresolvedInstability,
}

fn is_infinite(x: &f64) -> bool {
    x.is_infinite()
}

/// Unstable eigenvalues above the resolution limit: the basis's, not the continuum's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct UnresolvedInstability {
    /// Their number (0: no warning).
    pub count: usize,
    /// The smallest and largest |Im λ| among them (0 when there are none).
    pub frequency_from: f64,
    pub frequency_to: f64,
    /// Their largest real part (0 when there are none).
    pub max_real_part: f64,
}

impl UnresolvedInstability {
    /// True when some eigenvalue above the resolution limit is unstable.
    pub fn is_present(&self) -> bool {
        self.count > 0
    }
}

/// Classifies the eigenvalues (see the module docs); every eigenvalue counts. An empty spectrum
/// is `Marginal`.
pub fn assess(eigenvalues: &[c64], params: &VerdictParams) -> StabilityAssessment {
    assess_resolved(eigenvalues, params, f64::INFINITY)
}

/// Classifies the eigenvalues with |Im λ| ≤ `resolution_limit` (see the module docs) and
/// reports the unstable ones above it as [`UnresolvedInstability`]; with
/// `params.resolved_only = false` the limit is ignored (every eigenvalue counts). The tolerance τ
/// is taken from the whole spectrum (the round-off of the eigensolver scales with all of it). No
/// resolved eigenvalue: `Marginal`.
pub fn assess_resolved(
    eigenvalues: &[c64],
    params: &VerdictParams,
    resolution_limit: f64,
) -> StabilityAssessment {
    let resolution_limit = if params.resolved_only {
        resolution_limit
    } else {
        f64::INFINITY
    };
    let rho = eigenvalues.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let tol = (params.relative_tolerance * rho).max(params.absolute_tolerance);
    let mut crit: Option<c64> = None;
    let (mut unstable, mut real_unstable) = (0, 0);
    let mut unresolved = UnresolvedInstability {
        count: 0,
        frequency_from: f64::INFINITY,
        frequency_to: 0.0,
        max_real_part: f64::NEG_INFINITY,
    };
    for &l in eigenvalues {
        let resolved = l.im.abs() <= resolution_limit;
        if !resolved {
            if l.re > tol {
                unresolved.count += 1;
                unresolved.frequency_from = unresolved.frequency_from.min(l.im.abs());
                unresolved.frequency_to = unresolved.frequency_to.max(l.im.abs());
                unresolved.max_real_part = unresolved.max_real_part.max(l.re);
            }
            continue;
        }
        if crit.is_none_or(|c| l.re > c.re || (l.re == c.re && l.im.abs() < c.im.abs())) {
            crit = Some(l);
        }
        if l.re > tol {
            unstable += 1;
            if l.im.abs() <= tol {
                real_unstable += 1;
            }
        }
    }
    if unresolved.count == 0 {
        unresolved.frequency_from = 0.0;
        unresolved.max_real_part = 0.0;
    }
    let crit = crit.unwrap_or(c64::new(0.0, 0.0));
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
        resolution_limit,
        unresolved,
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
    fn unstable_eigenvalues_above_the_resolution_limit_are_a_warning_not_the_verdict() {
        let p = VerdictParams::default();
        let spectrum = [
            c(-0.1, 3.0),
            c(-0.1, -3.0),
            c(0.5, 90.0),
            c(0.5, -90.0),
            c(0.2, 70.0),
            c(0.2, -70.0),
        ];
        let a = assess_resolved(&spectrum, &p, 50.0);
        assert_eq!(a.verdict, Verdict::Stable);
        assert_eq!((a.critical_re, a.critical_im), (-0.1, 3.0));
        assert_eq!(a.unstable_eigenvalues, 0);
        assert_eq!(a.unresolved.count, 4);
        assert_eq!(
            (a.unresolved.frequency_from, a.unresolved.frequency_to),
            (70.0, 90.0)
        );
        assert_eq!(a.unresolved.max_real_part, 0.5);
        // τ from the whole spectrum
        assert_eq!(a.tolerance, 1e-7 * c(0.5, 90.0).norm());
        // an unstable resolved eigenvalue decides; the warning stays
        let b = assess_resolved(&[c(0.01, 40.0), c(0.01, -40.0), c(0.5, 90.0)], &p, 50.0);
        assert_eq!(b.verdict, Verdict::Flutter);
        assert_eq!((b.unstable_eigenvalues, b.unresolved.count), (2, 1));
        // the limit itself is resolved; real eigenvalues always are
        let e = assess_resolved(&[c(0.3, 0.0), c(-0.2, 50.0)], &p, 50.0);
        assert_eq!(e.verdict, Verdict::Divergence);
        assert_eq!(
            assess_resolved(&[c(0.3, 0.0)], &p, 0.0).verdict,
            Verdict::Divergence
        );
        // without a limit: the plain verdict
        assert_eq!(assess(&spectrum, &p).verdict, Verdict::Flutter);
        let every = VerdictParams {
            resolved_only: false,
            ..p
        };
        assert_eq!(
            assess_resolved(&spectrum, &every, 50.0).verdict,
            Verdict::Flutter
        );
        assert!(!assess(&spectrum, &p).unresolved.is_present());
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
