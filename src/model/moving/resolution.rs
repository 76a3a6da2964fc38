//! The resolution limit of a discretized moving string: which eigenvalues of the discrete model
//! stand for eigenvalues of the string, and which belong to the basis.
//!
//! On the axially moving string (dimensionless, wave speed 1, transport speed v̄), a free wave
//! w = e^{λτ + ikξ} has λ = i k (±1 − v̄): a vibration of frequency ω is carried by the two
//! wavenumbers ω / (1 − |v̄|) (the wave against the transport) and ω / (1 + |v̄|) (with it). The
//! mode n of the fixed string, ω_n = nπ(1 − v̄²), thus carries nπ(1 ± v̄) (the paper's modes (41)).
//!
//! The finest wave a basis carries: N half-waves for N sine functions, k_max = Nπ; one half-wave
//! per element on a mesh of M elements of size h = 1/M, k_max = π/h = Mπ (the mesh's Nyquist
//! wavenumber), whatever the element's degree — the cubic Hermite element's second function per
//! node improves the accuracy below π/h, it does not extend the range: the upper half of its
//! spectrum is the element's optical branch, with no counterpart in the string (measured in
//! `moving_flutter`: with 2Mπ in place of Mπ, spurious Hermite modes flutter at a p independent of
//! M). A discrete eigenvalue stands for the string only if the string's waves at its frequency
//! fit:
//!
//! ```text
//!   |Im λ| ≤ ω_res = k_max · |1 − |v̄||.
//! ```
//!
//! Above ω_res the discrete spectrum is the basis's: its eigenvalues have no continuous
//! counterpart, and a friction term that is unbounded on H¹ — the thick string's point moment
//! (p/2)(w(ā) − u) δw'(ā), which grows with the wavenumber — can make them unstable for any
//! friction (verified in `moving_flutter`: every unstable eigenvalue of the sine model above
//! ω_res, none below, at the continuum's onset). A verdict therefore reads the eigenvalues below
//! ω_res only; the unstable ones above it are reported separately as a discretization warning
//! ([`crate::model::moving::stability::assess_resolved`]).
//!
//! Real eigenvalues (divergence, |Im λ| = 0) always count. At |v̄| = 1 exactly, ω_res = 0: only
//! real eigenvalues are read (the string has lost its stiffness there).
//!
//! Past the critical speed, |v̄| > 1, no resolution limit helps (issue 31). The string
//! w_tt + 2v̄ w_ξt − (1 − v̄²) w_ξξ = 0 carries its waves at the characteristic speeds v̄ ± 1,
//! which then have the same sign: every wave enters at the upstream guide and leaves at the
//! downstream one. Fixing w = 0 at both guides puts one condition where two are needed and one
//! where none may be: the initial-boundary value problem is overdetermined (initial data must
//! satisfy w(1, τ) = 0 along the outgoing characteristics). Its eigenvalue problem still has
//! the imaginary eigenvalues λ_n = inπ(1 − v̄²) — the continuum is formally marginal — but a Ritz
//! model, whose coordinates are not bound by that constraint, is not: N sines at v̄ = 1.5 have
//! complex pairs with Re λ = 14.0, 18.8, 24.2 for N = 20, 40, 80 (0.94 |λ|, 10⁷ times their
//! band, at |Im λ| ≈ 4.9 between the exact λ₁ = 3.93 and λ₂ = 7.85, far below ω_res), P1 and
//! Hermite meshes too (P1: a real λ = 38.7, 77.5, 184 for M = 20, 40, 80); already two sines
//! flutter at v̄ = 1.5, in closed form. The growth rate does not fall with refinement — it grows,
//! the mark of an ill-posed limit — while λ₁ still converges (errors 1.4e-4, 1.8e-5, 2.3e-6).
//! The discrete instability appears once N(v̄² − 1) exceeds about 0.5 (none up to N = 160 at
//! v̄ = 1.001; from N = 40 at v̄ = 1.01). A verdict past |v̄| = 1 is therefore the discrete
//! model's; [`supercritical_speed`] marks those speeds and the verdicts carry a
//! [`crate::model::moving::stability::SupercriticalWarning`].

use std::f64::consts::PI;

use crate::model::moving::string_model::{MovingStringModel, StringDiscretization};

/// The largest wavenumber k_max carried by `discretization` (module docs): Nπ for N sine
/// functions, Mπ for M elements of any kind.
pub fn wavenumber_limit(discretization: StringDiscretization) -> f64 {
    let half_waves = match discretization {
        StringDiscretization::Sine { modes } => modes,
        StringDiscretization::FiniteElements { elements, .. } => elements,
    };
    half_waves as f64 * PI
}

/// The resolution limit ω_res = k_max |1 − |v̄|| of `discretization` at the transport speed
/// `speed` (module docs).
pub fn resolution_limit(discretization: StringDiscretization, speed: f64) -> f64 {
    wavenumber_limit(discretization) * (1.0 - speed.abs()).abs()
}

/// `Some(speed)` past the critical speed, |v̄| > 1, where the verdict is the discrete model's
/// and not the continuum's (module docs); `None` otherwise (|v̄| = 1 itself is the critical
/// speed: ω_res = 0, only real eigenvalues are read).
pub fn supercritical_speed(speed: f64) -> Option<f64> {
    (speed.abs() > 1.0).then_some(speed)
}

/// The resolution limit of `model`'s discretization at the speed `speed`.
pub fn model_resolution_limit(model: &MovingStringModel, speed: f64) -> f64 {
    resolution_limit(model.discretization(), speed)
}

#[cfg(test)]
mod tests {
    //! Setting: the fixed string's exact modes ω_n = nπ(1 − v̄²). Goal: mode n is resolved by N
    //! functions exactly when its faster wavenumber nπ(1 + |v̄|) fits under Nπ.
    use super::*;

    #[test]
    fn mode_n_is_resolved_when_its_wavenumbers_fit() {
        for &v in &[0.0, 0.3, -0.5, 0.9] {
            let big_n = 40;
            let limit = resolution_limit(StringDiscretization::Sine { modes: big_n }, v);
            for n in 1..=big_n {
                let omega = n as f64 * PI * (1.0 - v * v);
                let fits = n as f64 * (1.0 + f64::abs(v)) <= big_n as f64 * (1.0 + 1e-12);
                assert_eq!(omega <= limit * (1.0 + 1e-12), fits, "v̄ = {v}, n = {n}");
            }
        }
    }

    #[test]
    fn supercritical_speeds_use_the_distance_from_one() {
        let sine = StringDiscretization::Sine { modes: 10 };
        assert!((resolution_limit(sine, 1.3) - 10.0 * PI * 0.3).abs() < 1e-12);
        assert_eq!(resolution_limit(sine, 1.0), 0.0);
    }

    #[test]
    fn elements_of_any_degree_resolve_one_half_wave_each() {
        use crate::model::moving::finite_element_basis::ElementKind;
        for kind in [ElementKind::P1, ElementKind::Hermite] {
            let fe = StringDiscretization::FiniteElements { kind, elements: 50 };
            assert!((wavenumber_limit(fe) - 50.0 * PI).abs() < 1e-12);
        }
    }

    /// Two sines, v̄ = 1.5: det(λ²I + 2v̄λT + K) = (λ² + k₁)(λ² + k₂) + (16v̄λ/3)², k_n =
    /// (1 − v̄²)(nπ)²: a quadratic in μ = λ² with complex roots, so Re λ = |Re √μ| ≠ 0.
    fn two_sine_growth_rate(v: f64) -> f64 {
        let (k1, k2) = ((1.0 - v * v) * PI * PI, 4.0 * (1.0 - v * v) * PI * PI);
        let b = k1 + k2 + (16.0 * v / 3.0).powi(2);
        let disc = faer::c64::new(b * b - 4.0 * k1 * k2, 0.0).sqrt();
        [(-b + disc) * 0.5, (-b - disc) * 0.5]
            .iter()
            .map(|mu| mu.sqrt().re.abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn past_the_critical_speed_the_verdict_carries_the_supercritical_warning() {
        use crate::model::moving::linearized::assess_point;
        use crate::model::moving::stability::{Verdict, VerdictParams};
        use crate::model::moving::string_data::MovingStringData;
        let params = VerdictParams::default();
        let model =
            MovingStringModel::new(StringDiscretization::Sine { modes: 2 }, Default::default())
                .unwrap();
        for v in [0.5, 1.5, -1.5] {
            let d = MovingStringData {
                speed: v,
                damping: 0.0,
                oscillator: None,
            };
            let ev = model.system(&d).unwrap().eigen(Default::default()).unwrap();
            let a = assess_point(&model, &d, &ev.eigenvalues, &params);
            if v.abs() < 1.0 {
                assert_eq!(a.verdict, Verdict::Marginal);
                assert!(a.supercritical.is_none());
                continue;
            }
            // the discrete model's flutter is the closed form's, not round-off
            let exact = two_sine_growth_rate(v);
            let w = a.supercritical.expect("the warning past |v̄| = 1");
            // (its pair lies above ω_res = 2π(|v̄| − 1) here: the warning, not the verdict, says it)
            assert_eq!((w.speed, w.unstable_eigenvalues), (v, 2));
            let floor = 64.0 * f64::EPSILON * a.spectral_scale;
            assert!(
                (w.discrete_growth_rate - exact).abs() <= floor,
                "{w:?} vs {exact}"
            );
        }
        assert_eq!(supercritical_speed(1.0), None);
        assert_eq!(supercritical_speed(1.001), Some(1.001));
    }
}
