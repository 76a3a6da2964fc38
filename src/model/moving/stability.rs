//! Stability verdicts from the eigenvalues of (λ² M + λ C + K) x = 0.
//!
//! The trivial solution is asymptotically stable when every Re λ < 0 and unstable when some
//! Re λ > 0: by divergence when that eigenvalue is real (a static buckling-type instability), by
//! flutter when it belongs to a complex pair (Hetzler 2009, §4.2; Huseyin 1978). Eigenvalues on
//! the imaginary axis (undamped gyroscopic or conservative systems) leave it marginal.
//!
//! Round-off decides nothing here: an eigenvalue λ counts as off the axis only when
//! |Re λ| > τ(λ), its own marginal band
//!
//! ```text
//!   τ(λ) = max(τ_rel |λ|, C n ε ρ, τ_abs),   ρ = max |λ| over the computed spectrum (order n).
//! ```
//!
//! The default τ_rel = 1e-7 ≈ 7 sqrt(ε) covers a defective double eigenvalue (a Jordan block, as
//! at the onset of flutter of an undamped circulatory system, where two imaginary eigenvalues
//! collide), which splits by up to O(sqrt(ε)) of its own scale under a relative perturbation of
//! order ε; the verification case `moving_extremes` approaches such Jordan blocks to 1e-14 and
//! measures at most 4e-10 ρ below the onset (exact real part 0). C n ε ρ (C =
//! [`BACKWARD_ERROR_CONSTANT`]) is the normwise backward error of the QR algorithm on the order-n
//! companion matrix: the floor of a simple eigenvalue's absolute error, which decides near
//! λ = 0 (a divergence crossing). The price is a blind zone: a true growth or decay rate below
//! τ(λ) is reported `Marginal`, never as a wrong kind of (in)stability.
//!
//! Why the band is each eigenvalue's own and not τ_rel ρ (issue 31): a discretized continuum's
//! ρ grows with the basis (ρ ≈ 4.3 N for N sines on the thick string of issue 16, from the
//! unresolved top of the spectrum; the resolved part alone still ≈ 2 N), while the decisive
//! eigenvalue — a low string mode at |λ| ≈ 2 — does not. A band τ_rel ρ shifts the verdict's
//! flutter onset by τ_rel ρ / (d Re λ/dp) ∝ N, which overtakes the O(1/N) discretization error:
//! 1.7e-3 at N = 160 with every eigenvalue's ρ (the onset's pairwise rates 0.87, 0.40, −0.32,
//! −0.76 over N = 20 … 320), and still 7.6e-4 with the resolved eigenvalues' ρ (against an error
//! of 4.4e-4). With τ(λ) the shift is τ_rel |λ*| / (d Re λ/dp) ≈ 5e-6 for every N.
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
    /// Every Re λ < −τ(λ): asymptotically stable.
    Stable,
    /// No Re λ > τ(λ) and some Re λ within ±τ(λ): on the imaginary axis to round-off (neutral).
    Marginal,
    /// A real eigenvalue > τ(λ) (the largest unstable one).
    Divergence,
    /// A complex pair with Re λ > τ(λ) (the largest unstable one).
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
    /// τ_rel: relative to each eigenvalue's modulus |λ|.
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
    /// The band τ(λ) of the eigenvalue that decided the verdict (the unstable one with the
    /// largest real part, else the one with the largest real part).
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
    /// The model's warning that this verdict is the discrete model's and not the continuum's
    /// (the string past its critical speed, `resolution.rs`); `None` when the model has none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub supercritical: Option<SupercriticalWarning>,
}

/// The string between fixed guides past its critical speed |v̄| > 1 (`resolution.rs`,
/// [`crate::model::moving::resolution::supercritical_speed`]): the continuum's eigenvalues
/// λ_n = inπ(1 − v̄²) are imaginary (marginal), but the verdict is the discrete model's, whose
/// growth rate does not fall with refinement (it grows: measured in `moving_envelope`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SupercriticalWarning {
    /// The transport speed v̄ (|v̄| > 1).
    pub speed: f64,
    /// The discrete model's growth rate: max Re λ over the eigenvalues with Re λ > τ(λ), every
    /// one of them (resolved or not); 0 when none is unstable.
    pub discrete_growth_rate: f64,
    /// The number of those eigenvalues.
    pub unstable_eigenvalues: usize,
}

impl StabilityAssessment {
    /// Attaches the supercritical warning at the speed `speed` (|v̄| > 1), reading the discrete
    /// growth rate from every eigenvalue against its own band τ(λ) ([`marginal_band`]).
    pub fn flag_supercritical(&mut self, speed: f64, eigenvalues: &[c64], params: &VerdictParams) {
        let rho = eigenvalues.iter().map(|l| l.norm()).fold(0.0, f64::max);
        let unstable: Vec<f64> = eigenvalues
            .iter()
            .filter(|l| l.re > marginal_band(**l, params, eigenvalues.len(), rho))
            .map(|l| l.re)
            .collect();
        self.supercritical = Some(SupercriticalWarning {
            speed,
            discrete_growth_rate: unstable.iter().copied().fold(0.0, f64::max),
            unstable_eigenvalues: unstable.len(),
        });
    }
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

/// The constant C of the round-off floor C n ε ρ of a simple eigenvalue (module docs): the
/// normwise backward error of the QR algorithm on the order-n companion matrix, O(n ε ‖A‖).
pub const BACKWARD_ERROR_CONSTANT: f64 = 8.0;

/// The marginal band of one eigenvalue λ: τ(λ) = max(τ_rel |λ|, C n ε ρ, τ_abs) (module docs),
/// with ρ = max |λ| over the whole computed spectrum of order n.
pub fn marginal_band(lambda: c64, params: &VerdictParams, order: usize, rho: f64) -> f64 {
    let floor = BACKWARD_ERROR_CONSTANT * order as f64 * f64::EPSILON * rho;
    (params.relative_tolerance * lambda.norm())
        .max(floor)
        .max(params.absolute_tolerance)
}

/// Classifies the eigenvalues with |Im λ| ≤ `resolution_limit` (see the module docs) and
/// reports the unstable ones above it as [`UnresolvedInstability`]; with
/// `params.resolved_only = false` the limit is ignored (every eigenvalue counts). Each
/// eigenvalue is judged against its own band τ(λ) ([`marginal_band`]): unstable when
/// Re λ > τ(λ), real when |Im λ| ≤ τ(λ); the verdict is that of the unstable resolved
/// eigenvalue with the largest real part (divergence if it is real, flutter otherwise), else
/// `Stable` when every resolved Re λ < −τ(λ), else `Marginal`. No resolved eigenvalue:
/// `Marginal`.
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
    let band = |l: c64| marginal_band(l, params, eigenvalues.len(), rho);
    let mut crit: Option<c64> = None;
    let mut worst_unstable: Option<c64> = None;
    let mut all_stable = true;
    let (mut unstable, mut real_unstable) = (0, 0);
    let mut unresolved = UnresolvedInstability {
        count: 0,
        frequency_from: f64::INFINITY,
        frequency_to: 0.0,
        max_real_part: f64::NEG_INFINITY,
    };
    for &l in eigenvalues {
        let tol = band(l);
        if l.im.abs() > resolution_limit {
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
        all_stable &= l.re < -tol;
        if l.re > tol {
            unstable += 1;
            if l.im.abs() <= tol {
                real_unstable += 1;
            }
            if worst_unstable
                .is_none_or(|c| l.re > c.re || (l.re == c.re && l.im.abs() < c.im.abs()))
            {
                worst_unstable = Some(l);
            }
        }
    }
    if unresolved.count == 0 {
        unresolved.frequency_from = 0.0;
        unresolved.max_real_part = 0.0;
    }
    let (verdict, decisive) = match (worst_unstable, crit) {
        (Some(w), _) if w.im.abs() <= band(w) => (Verdict::Divergence, w),
        (Some(w), _) => (Verdict::Flutter, w),
        (None, Some(c)) if all_stable => (Verdict::Stable, c),
        (None, Some(c)) => (Verdict::Marginal, c),
        (None, None) => (Verdict::Marginal, c64::new(0.0, 0.0)),
    };
    let crit = crit.unwrap_or(c64::new(0.0, 0.0));
    StabilityAssessment {
        verdict,
        max_real_part: crit.re,
        critical_re: crit.re,
        critical_im: crit.im.abs(),
        tolerance: band(decisive),
        unstable_eigenvalues: unstable,
        real_unstable_eigenvalues: real_unstable,
        spectral_scale: rho,
        resolution_limit,
        unresolved,
        supercritical: None,
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
        // τ of the deciding eigenvalue, its own modulus
        assert_eq!(a.tolerance, 1e-7 * c(-0.1, 3.0).norm());
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
    fn a_low_modes_growth_is_judged_on_its_own_scale_whatever_the_top_of_the_spectrum() {
        // a growth rate of 1e-6 on |λ| = 2 (band 2e-7) is flutter whether or not the basis
        // carries eigenvalues up to 1e4 (old band τ_rel ρ = 1e-3: marginal)
        let p = VerdictParams::default();
        let low = [c(1e-6, 2.0), c(1e-6, -2.0), c(-0.01, 5.0), c(-0.01, -5.0)];
        assert_eq!(assess(&low, &p).verdict, Verdict::Flutter);
        let mut wide = low.to_vec();
        wide.extend([c(-0.01, 1e4), c(-0.01, -1e4)]);
        let a = assess(&wide, &p);
        assert_eq!(a.verdict, Verdict::Flutter);
        assert_eq!(a.tolerance, 1e-7 * c(1e-6, 2.0).norm());
        // an eigenvalue within its band is marginal even below a larger stable one's band
        let m = assess(&[c(1e-8, 2.0), c(-5e-6, 100.0)], &p);
        assert_eq!(m.verdict, Verdict::Marginal);
        // the unstable eigenvalue with the largest real part decides the kind
        let d = assess(&[c(1e-3, 0.0), c(5e-4, 7.0), c(-1.0, 1e4)], &p);
        assert_eq!(d.verdict, Verdict::Divergence);
        // near λ = 0 the band is the eigensolver's floor C n ε ρ
        let z = assess(&[c(1e-13, 0.0), c(-0.1, 1e3)], &p);
        assert_eq!(z.verdict, Verdict::Marginal);
        assert_eq!(
            z.tolerance,
            BACKWARD_ERROR_CONSTANT * 2.0 * f64::EPSILON * c(-0.1, 1e3).norm()
        );
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
