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
}
