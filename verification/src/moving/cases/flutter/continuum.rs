//! The program's thick string against the continuum (`exact::thick_string_continuum`): its lowest
//! eigenvalues at a control parameter p converge to the roots of the characteristic function, and
//! its flutter onset, read from the resolved eigenvalues, converges to the continuum's.
//!
//! The continuum's roots are found independently of the program: the starting guesses are the
//! independent sine-Galerkin model's eigenvalues at p = 0, refined to roots of F and followed in p
//! by continuation (`track_in_control`). Expected rates (the eigenfunctions jump at ā, their
//! slopes too): the sine basis converges at rate 1 in 1/N (the sine series of a jump), P1 with ā
//! on a node at rate 2 in h, Hermite cubics with ā on a node at rate 1 (C¹ functions cannot jump
//! or kink at a point).
//!
//! The onset: p* = the smallest p at which a followed branch of the continuum crosses into
//! Re λ > 0 (bisection of its crossing step). The program's onset at N sine functions is read from
//! its *resolved* eigenvalues, Im λ < Nπ(1 − |v̄|): mode n carries the wavenumbers nπ(1 ± v̄), so N
//! sines resolve n ≤ N/(1 + |v̄|), i.e. frequencies below nπ(1 − v̄²) = Nπ(1 − |v̄|). Above that
//! limit the discrete spectrum is the basis's, and its friction-driven instabilities are artefacts
//! (issue 16).

use nalgebra::Complex;
use rayon::prelude::*;
use serde::Serialize;

use contactlab::model::moving::finite_element_basis::ElementKind;
use contactlab::model::moving::resolution::model_resolution_limit;
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};

use super::discrete::program_eigenvalues;
use super::format::{Continuum, ParameterSet};
use crate::core::gate::{Check, GateVerdict};
use crate::exact::thick_string_continuum::{
    continuum_onset, roots_at_rest as exact_roots_at_rest, track_in_control,
};
use crate::moving::study::flutter_onset;

type C64 = Complex<f64>;

/// The reference-model size whose eigenvalues at p = 0 start the continuum's roots.
const GUESS_MODES: usize = 60;
/// Continuation steps from p = 0 to the compared control parameter.
const TRACK_STEPS: usize = 40;
/// Tracking steps of the onset search in (0, onset_max].
const ONSET_STEPS: usize = 200;

/// One discretization level against the continuum.
#[derive(Debug, Clone, Serialize)]
pub struct ContinuumLevel {
    pub set: String,
    pub basis: String,
    pub size: usize,
    pub h: f64,
    /// Relative error of each compared root.
    pub mode_errors: Vec<f64>,
    pub error: f64,
}

/// The continuum's onset of one set and the program's resolved onsets.
#[derive(Debug, Clone, Serialize)]
pub struct OnsetStudy {
    pub set: String,
    /// p* and the critical root there.
    pub onset: f64,
    pub critical: [f64; 2],
    /// The largest Re λ of the other followed branches at p*.
    pub others_max_re: f64,
    /// (N, resolved onset, onset from every eigenvalue).
    pub program: Vec<(usize, f64, f64)>,
    /// The finite-element onsets from resolved eigenvalues: (basis, elements M, resolved onset).
    pub elements: Vec<(String, usize, f64)>,
}

/// The roots of the continuum of `set` at p = 0 near the reference model's lowest `count`
/// frequencies (`exact::thick_string_continuum::roots_at_rest`).
fn roots_at_rest(set: &ParameterSet, count: usize) -> Result<Vec<C64>, String> {
    exact_roots_at_rest(&set.at(0.0), GUESS_MODES, count).map_err(|e| format!("{}: {e}", set.name))
}

/// The program's discretizations of the study of `set`: (basis, size, h, discretization).
fn plans(set: &ParameterSet) -> Vec<(&'static str, usize, f64, StringDiscretization)> {
    let fe = |kind, m| StringDiscretization::FiniteElements { kind, elements: m };
    let mut v = Vec::new();
    for &n in &set.sine_modes {
        v.push((
            "sine",
            n,
            1.0 / n as f64,
            StringDiscretization::Sine { modes: n },
        ));
    }
    for &m in &set.p1_elements {
        v.push(("p1", m, 1.0 / m as f64, fe(ElementKind::P1, m)));
    }
    for &m in &set.hermite_elements {
        v.push(("hermite", m, 1.0 / m as f64, fe(ElementKind::Hermite, m)));
    }
    v
}

/// The eigenvalue levels of every set and basis against the continuum at p = `c.control`
/// (levels in parallel; each depends only on its own inputs).
pub fn levels(sets: &[ParameterSet], c: &Continuum) -> Result<Vec<ContinuumLevel>, String> {
    let mut jobs = Vec::new();
    for s in sets {
        let start = roots_at_rest(s, c.modes_checked)?;
        let controls: Vec<f64> = (0..=TRACK_STEPS)
            .map(|i| c.control * i as f64 / TRACK_STEPS as f64)
            .collect();
        let mut exact = Vec::new();
        for g in start {
            let path = track_in_control(&s.at(0.0), g, &controls)?;
            exact.push(path[TRACK_STEPS]);
        }
        for plan in plans(s) {
            jobs.push((s, exact.clone(), plan));
        }
    }
    jobs.par_iter()
        .map(|(s, exact, (basis, size, h, disc))| {
            let model =
                MovingStringModel::new(*disc, Default::default()).map_err(|e| e.to_string())?;
            let ev = program_eigenvalues(&model, &s.at(c.control))?;
            let mode_errors: Vec<f64> = exact
                .iter()
                .map(|r| {
                    ev.iter()
                        .map(|l| (l - r).norm())
                        .fold(f64::INFINITY, f64::min)
                        / r.norm()
                })
                .collect();
            Ok(ContinuumLevel {
                set: s.name.clone(),
                basis: basis.to_string(),
                size: *size,
                h: *h,
                error: mode_errors.iter().copied().fold(0.0, f64::max),
                mode_errors,
            })
        })
        .collect()
}

/// The continuum onset of `set` and the program's sine onsets (resolved, and from every
/// eigenvalue), with the check that the critical root sits on the axis and the other branches
/// are stable there.
pub fn onsets(set: &ParameterSet, c: &Continuum) -> Result<(OnsetStudy, Check), String> {
    let found = continuum_onset(
        &set.at(0.0),
        GUESS_MODES,
        c.onset_branches,
        c.onset_max,
        ONSET_STEPS,
    )
    .map_err(|e| format!("{}: {e}", set.name))?
    .ok_or_else(|| {
        format!(
            "{}: no branch becomes unstable below p = {}",
            set.name, c.onset_max
        )
    })?;
    let (p_star, crit, others, followed) = (
        found.onset,
        found.critical,
        found.others_max_re,
        found.branches,
    );
    let program = set
        .sine_modes
        .par_iter()
        .map(|&n| {
            let (a, b) = program_onsets(set, StringDiscretization::Sine { modes: n }, p_star)?;
            Ok((n, a, b))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let fe = |kind, elements| StringDiscretization::FiniteElements { kind, elements };
    let element_plans: Vec<(&str, usize, StringDiscretization)> = set
        .onset_p1_elements
        .iter()
        .map(|&m| ("p1", m, fe(ElementKind::P1, m)))
        .chain(
            set.onset_hermite_elements
                .iter()
                .map(|&m| ("hermite", m, fe(ElementKind::Hermite, m))),
        )
        .collect();
    let elements = element_plans
        .par_iter()
        .map(|&(basis, m, disc)| {
            let (a, _) = program_onsets(set, disc, p_star)?;
            Ok((basis.to_string(), m, a))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let check = Check::holds(
        &format!(
            "{}: continuum p* = {p_star:.9}, λ* = {:.3e} + {:.9}i; the other {} followed branches at p*: max Re λ = {others:.3e}",
            set.name,
            crit.re,
            crit.im,
            followed - 1
        ),
        crit.re.abs() <= 1e-9 * crit.norm() && others < 0.0,
        "the critical root on the imaginary axis, every other followed branch stable",
    );
    Ok((
        OnsetStudy {
            set: set.name.clone(),
            onset: p_star,
            critical: [crit.re, crit.im],
            others_max_re: others,
            program,
            elements,
        },
        check,
    ))
}

/// The largest N whose onset from every eigenvalue (shown in the figure, not gated) is computed:
/// it needs a bisection over the whole p range.
const EVERY_EIGENVALUE_UP_TO: usize = 200;

/// The program's onsets with the discretization `disc`: (from the resolved eigenvalues, from
/// every eigenvalue (sine bases of N ≤ [`EVERY_EIGENVALUE_UP_TO`] functions, else NaN)).
///
/// The resolved onset: the zero of g(p) = max{Re λ : |Im λ| ≤ ω_res}, ω_res = k_max(1 − |v̄|)
/// (the library's definition, `model::moving::resolution`: k_max = Nπ for N sines, Mπ for M
/// elements of either kind), by the secant method
/// from p*, 1.01 p* (`p_star`, the continuum's onset, only starts the iteration) to
/// |Δp| ≤ 1e-9 p, confirmed by g < 0 at (1 − 1e-6) p and at 1/4, 1/2, 3/4 of it, and g > 0 at
/// (1 + 1e-6) p; without that confirmation, bisection from p*/2 to a relative bracket of 1e-6
/// (far below the discretization errors measured, ≥ 1e-3). The onset from every eigenvalue:
/// bisection to 1e-4.
fn program_onsets(
    set: &ParameterSet,
    disc: StringDiscretization,
    p_star: f64,
) -> Result<(f64, f64), String> {
    let model = MovingStringModel::new(disc, Default::default()).map_err(|e| e.to_string())?;
    let limit = model_resolution_limit(&model, set.speed);
    let resolved = |p: f64| -> Result<f64, String> {
        let ev = program_eigenvalues(&model, &set.at(p))?;
        Ok(ev
            .iter()
            .filter(|l| l.im.abs() <= limit)
            .map(|l| l.re)
            .fold(f64::NEG_INFINITY, f64::max))
    };
    let every = |p: f64| -> Result<f64, String> {
        let ev = program_eigenvalues(&model, &set.at(p))?;
        Ok(ev.iter().map(|l| l.re).fold(f64::NEG_INFINITY, f64::max))
    };
    let (mut p0, mut p1) = (p_star, 1.01 * p_star);
    let (mut g0, mut g1) = (resolved(p0)?, resolved(p1)?);
    for _ in 0..40 {
        if g1 == g0 || (p1 - p0).abs() <= 1e-9 * p1.abs() {
            break;
        }
        let p2 = p1 - g1 * (p1 - p0) / (g1 - g0);
        (p0, g0) = (p1, g1);
        p1 = p2;
        g1 = resolved(p1)?;
    }
    let mut confirmed = p1.is_finite()
        && p1 > 0.0
        && resolved(p1 * (1.0 + 1e-6))? > 0.0
        && resolved(p1 * (1.0 - 1e-6))? < 0.0;
    for f in [0.25, 0.5, 0.75] {
        confirmed = confirmed && resolved(f * p1)? < 0.0;
    }
    let a = if confirmed {
        p1
    } else {
        flutter_onset(resolved, "p", 0.5 * p_star, 1e-6, 1e3)?
    };
    let every_eigenvalue =
        matches!(disc, StringDiscretization::Sine { modes } if modes <= EVERY_EIGENVALUE_UP_TO);
    let b = if every_eigenvalue {
        flutter_onset(every, "p", 0.5 * p_star, 1e-4, 1e3)?
    } else {
        f64::NAN
    };
    Ok((a, b))
}

/// The gate on the continuum onsets (one check per set).
pub fn onset_gate(checks: Vec<Check>) -> GateVerdict {
    GateVerdict::from_checks(
        "the continuum's flutter onsets (roots followed from p = 0)".into(),
        "exact",
        checks,
        "the characteristic function of the thick string with the jump conditions at ā; its roots followed in p by continuation",
    )
}
