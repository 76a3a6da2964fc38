//! `moving_envelope`: the moving-continua family at the edges of its range (issue 31), each
//! point against an independent reference or a typed error naming the limit.
//!
//! - Thick string, flutter onset read from the verdict (bisection in p on
//!   `assess_resolved(..).verdict`, the library's own reading) for sine bases of N functions and
//!   P1 / Hermite meshes of M elements, against the continuum's onset p* (the characteristic
//!   function with the jump conditions at ā, `exact::thick_string_continuum`, computed here):
//!   the pairwise rates in N (in h) must be 1 within the tolerance of `moving_flutter`'s
//!   issue-16 onset gate; and the discretization warning must say what is true — the number
//!   of unstable eigenvalues above ω_res at 1.5 p* does not fall with N (they are the basis's).
//! - The rotating plate's non-rotating frequencies (n = 0 … N, m = 0, 1) and its lowest critical
//!   speed on M radial elements against the Bessel roots (`exact::plate_annulus`): the finest M
//!   at least as accurate as M = 64 and within the discretization model e(64)(64/M)^r, r the rate
//!   of the coarse pair.
//! - The thin undamped string at speeds near 0 and near the critical v̄ = 1, and past it: below
//!   v̄ = 1 the verdict is the continuum's (marginal: λ_n = inπ(1 − v̄²) in closed form); past it
//!   the fixed-fixed string is overdetermined and its Ritz models flutter with a growth rate
//!   that grows with N (issue 31, `resolution.rs`), so the verdict must carry the supercritical
//!   warning, whose growth rate is checked against two sines in closed form and must not fall
//!   with N; the lowest frequency converges in N towards π|1 − v̄²| at every speed.
//! - Past the range: typed errors naming the key (a plate mesh beyond 4000 radial elements, a
//!   bushing on a guide, a negative penalty stiffness).

use std::path::Path;

use serde::{Deserialize, Serialize};

use contactlab::model::moving::finite_element_basis::ElementKind;
use contactlab::model::moving::linearized::assess_point;
use contactlab::model::moving::plate::modes::harmonic_frequencies;
use contactlab::model::moving::plate::{OuterEdge, PlateProperties};
use contactlab::model::moving::resolution::model_resolution_limit;
use contactlab::model::moving::stability::{assess_resolved, Verdict, VerdictParams};
use contactlab::model::moving::string_data::{ContactModel, MovingStringData};
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};

use crate::core::context::RunContext;
use crate::core::format::{at_least, invalid, positive, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::exact::plate_annulus::{AnnularPlate, OuterEdge as ExactEdge};
use crate::exact::thick_string_continuum::continuum_onset;
use crate::exact::thick_string_galerkin::ThickString;
use crate::moving::study::{flutter_onset, model_eigenvalues, Bushing};

/// The case format of `moving_envelope`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeCase {
    pub onset: OnsetEdge,
    pub plate: PlateEdge,
    pub speeds: SpeedEdge,
}

/// `[onset]`: the thick string (ideal contact) and the bases swept.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OnsetEdge {
    pub speed: f64,
    pub damping: f64,
    pub stiffness: f64,
    pub mass: f64,
    pub position: f64,
    pub sine_modes: Vec<usize>,
    #[serde(default)]
    pub p1_elements: Vec<usize>,
    #[serde(default)]
    pub hermite_elements: Vec<usize>,
    /// |pairwise rate − 1| ≤ this.
    pub rate_tolerance: f64,
}

/// `[plate]`: the free-edge annulus of `moving_plate` on these meshes (the first two are the
/// coarse pair of the error model, the second is the M = 64 reference level).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PlateEdge {
    pub elements: Vec<usize>,
    pub harmonics: usize,
}

/// `[speeds]`: the thin undamped string (no oscillator).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedEdge {
    pub modes: Vec<usize>,
    pub speeds: Vec<f64>,
}

impl EnvelopeCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        let o = &self.onset;
        at_least(p, "onset.sine_modes", &o.sine_modes, 2)?;
        positive(p, "onset.rate_tolerance", o.rate_tolerance)?;
        for (k, list) in [
            ("onset.p1_elements", &o.p1_elements),
            ("onset.hermite_elements", &o.hermite_elements),
        ] {
            if list.len() == 1 {
                return Err(invalid(p, k, list.len(), "none or at least 2 levels"));
            }
        }
        at_least(p, "plate.elements", &self.plate.elements, 3)?;
        if self.plate.harmonics < 2 {
            return Err(invalid(
                p,
                "plate.harmonics",
                self.plate.harmonics,
                "at least 2",
            ));
        }
        at_least(p, "speeds.modes", &self.speeds.modes, 2)?;
        at_least(p, "speeds.speeds", &self.speeds.speeds, 1)?;
        Ok(())
    }
}

/// One basis level of the onset sweep.
#[derive(Debug, Clone, Serialize)]
struct OnsetLevel {
    basis: String,
    size: usize,
    onset: f64,
    error: f64,
    /// Unstable eigenvalues above ω_res at 1.5 p*.
    unresolved_at_1_5p: usize,
}

/// The verdict's onset: the smallest p at which `assess_resolved` (default parameters) says
/// unstable, by bisection to 1e-7 relative (below 1e-3 of the errors measured).
fn verdict_onset(
    o: &OnsetEdge,
    disc: StringDiscretization,
    p_star: f64,
) -> Result<(f64, usize), String> {
    let model = MovingStringModel::new(disc, Default::default()).map_err(|e| e.to_string())?;
    let limit = model_resolution_limit(&model, o.speed);
    let bushing = Bushing {
        stiffness: o.stiffness,
        mass: o.mass,
        position: o.position,
    };
    let assess = |p: f64| -> Result<_, String> {
        let d = bushing.data(o.speed, o.damping, ContactModel::Ideal, p / o.stiffness);
        let ev = model_eigenvalues(&model, &d)?;
        Ok(assess_resolved(&ev, &VerdictParams::default(), limit))
    };
    let sign = |p: f64| -> Result<f64, String> {
        Ok(if assess(p)?.verdict.is_unstable() {
            1.0
        } else {
            -1.0
        })
    };
    let onset = flutter_onset(sign, "p", 0.5 * p_star, 1e-7, 1e3)?;
    Ok((onset, assess(1.5 * p_star)?.unresolved.count))
}

fn rates(sizes: &[usize], errors: &[f64]) -> Vec<f64> {
    sizes
        .windows(2)
        .zip(errors.windows(2))
        .map(|(n, e)| (e[0] / e[1]).ln() / (n[1] as f64 / n[0] as f64).ln())
        .collect()
}

fn onset_gates(o: &OnsetEdge, report: &mut CaseReport) -> Result<Vec<OnsetLevel>, String> {
    let thick = ThickString {
        speed: o.speed,
        damping: o.damping,
        stiffness: o.stiffness,
        mass: o.mass,
        position: o.position,
        control: 0.0,
        patch: 0.0,
    };
    let p_star = continuum_onset(&thick, 60, 6, 1.0, 200)?
        .ok_or("the continuum has no flutter onset below p = 1")?
        .onset;
    let fe = |kind, elements| StringDiscretization::FiniteElements { kind, elements };
    let series: Vec<(&str, Vec<(usize, StringDiscretization)>)> = vec![
        (
            "sine",
            o.sine_modes
                .iter()
                .map(|&n| (n, StringDiscretization::Sine { modes: n }))
                .collect(),
        ),
        (
            "p1",
            o.p1_elements
                .iter()
                .map(|&m| (m, fe(ElementKind::P1, m)))
                .collect(),
        ),
        (
            "hermite",
            o.hermite_elements
                .iter()
                .map(|&m| (m, fe(ElementKind::Hermite, m)))
                .collect(),
        ),
    ];
    let mut levels = Vec::new();
    let mut checks = Vec::new();
    for (name, plan) in series.into_iter().filter(|s| !s.1.is_empty()) {
        let mut errs = Vec::new();
        let mut counts = Vec::new();
        for &(size, disc) in &plan {
            let (onset, unresolved) = verdict_onset(o, disc, p_star)?;
            let error = (onset - p_star).abs();
            errs.push(error);
            counts.push(unresolved);
            levels.push(OnsetLevel {
                basis: name.to_string(),
                size,
                onset,
                error,
                unresolved_at_1_5p: unresolved,
            });
        }
        let sizes: Vec<usize> = plan.iter().map(|l| l.0).collect();
        let pairs = sizes.len() - 1;
        for (k, ((w, e), r)) in sizes
            .windows(2)
            .zip(errs.windows(2))
            .zip(rates(&sizes, &errs))
            .enumerate()
        {
            let what = format!(
                "{name} {} → {}: pairwise rate of |onset − p*| ({:.3e} → {:.3e})",
                w[0], w[1], e[0], e[1]
            );
            checks.push(if k + 1 == pairs {
                Check::within(&what, r, 1.0, o.rate_tolerance)
            } else {
                Check::at_least(&what, r, 1.0 - o.rate_tolerance)
            });
        }
        checks.push(Check::holds(
            &format!("{name}: unstable eigenvalues above ω_res at 1.5 p* for sizes {sizes:?}: {counts:?}"),
            counts.windows(2).all(|c| c[1] >= c[0]),
            "not falling with the basis size (the warning says refinement does not remove them)",
        ));
    }
    report.gates.push(GateVerdict::from_checks(
        format!("thick string: the verdict's flutter onset against the continuum's p* = {p_star:.9}"),
        "exact",
        checks,
        "the characteristic function of the thick string with the jump conditions at ā (exact::thick_string_continuum); rate 1: the eigenfunctions jump at ā",
    ));
    Ok(levels)
}

/// One plate level: the largest relative error of ω_{n,m} and of the lowest critical speed.
#[derive(Debug, Clone, Serialize)]
struct PlateLevel {
    elements: usize,
    frequency_error: f64,
    critical_speed_error: f64,
}

fn plate_gates(edge: &PlateEdge, report: &mut CaseReport) -> Result<Vec<PlateLevel>, String> {
    let plate = PlateProperties {
        outer_edge: OuterEdge::Free,
        ..Default::default()
    };
    let exact = AnnularPlate::annulus(
        plate.inner_radius,
        plate.outer_radius,
        plate.poisson,
        ExactEdge::Free,
    );
    let refs = (0..=edge.harmonics)
        .map(|n| exact.natural_frequencies(n, 2, plate.bending_stiffness, plate.mass_per_area))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())?;
    let crit_exact = (1..refs.len())
        .map(|n| refs[n][0] / n as f64)
        .fold(f64::INFINITY, f64::min);
    let mut levels = Vec::new();
    for &m in &edge.elements {
        let (mut err, mut crit) = (0.0f64, f64::INFINITY);
        for (n, reference) in refs.iter().enumerate() {
            let w = harmonic_frequencies(&plate, m, n, 2).map_err(|e| e.to_string())?;
            for (wh, we) in w.iter().zip(reference) {
                err = err.max((wh - we).abs() / we);
            }
            if n >= 1 {
                crit = crit.min(w[0] / n as f64);
            }
        }
        levels.push(PlateLevel {
            elements: m,
            frequency_error: err,
            critical_speed_error: (crit - crit_exact).abs() / crit_exact,
        });
    }
    let (a, b) = (&levels[0], &levels[1]);
    let ratio = b.elements as f64 / a.elements as f64;
    let r_f = (a.frequency_error / b.frequency_error).ln() / ratio.ln();
    let r_c = (a.critical_speed_error / b.critical_speed_error).ln() / ratio.ln();
    let mut checks = Vec::new();
    for l in &levels[2..] {
        let scale = b.elements as f64 / l.elements as f64;
        checks.push(Check::at_most(
            &format!(
                "M = {}: max relative error of ω_{{n,m}} (n ≤ {}, m ≤ 1) / that at M = {}",
                l.elements, edge.harmonics, b.elements
            ),
            l.frequency_error / b.frequency_error,
            1.0,
        ));
        checks.push(Check::at_most(
            &format!(
                "M = {}: that error / the model e({})·({}/M)^{r_f:.3}",
                l.elements, b.elements, b.elements
            ),
            l.frequency_error / (b.frequency_error * scale.powf(r_f)),
            1.0,
        ));
        checks.push(Check::at_most(
            &format!("M = {}: relative error of the lowest critical speed min ω_{{n,0}}/n / the model e({})·({}/M)^{r_c:.3}", l.elements, b.elements, b.elements),
            l.critical_speed_error / (b.critical_speed_error * scale.powf(r_c)).min(b.critical_speed_error),
            1.0,
        ));
    }
    report.gates.push(GateVerdict::from_checks(
        "rotating plate: fine radial meshes at least as accurate as M = 64, at the rate 4 model".into(),
        "exact",
        checks,
        "the roots of the exact 4 × 4 Bessel determinant (exact::plate_annulus); the error model extrapolates the coarse pair's rate (which approaches 4 from below)",
    ));
    Ok(levels)
}

/// One speed point of the thin undamped string.
#[derive(Debug, Clone, Serialize)]
struct SpeedPoint {
    speed: f64,
    modes: usize,
    verdict: Verdict,
    /// ||λ₁| − π|1 − v̄²|| / π|1 − v̄²|.
    lowest_error: f64,
    /// Past |v̄| = 1: the supercritical warning's discrete growth rate (absent: no warning).
    #[serde(skip_serializing_if = "Option::is_none")]
    discrete_growth_rate: Option<f64>,
}

/// The growth rate of two sines in closed form, written here: det(λ²I + 2v̄λT + K) =
/// (λ² + k₁)(λ² + k₂) + (16v̄λ/3)² with k_n = (1 − v̄²)(nπ)² (T₁₂ = −8/3 = −T₂₁), a quadratic
/// in μ = λ²; Re λ = max |Re √μ| (0 when both μ are real and negative: marginal).
fn two_sine_growth_rate(v: f64) -> f64 {
    let pi2 = std::f64::consts::PI.powi(2);
    let (k1, k2) = ((1.0 - v * v) * pi2, 4.0 * (1.0 - v * v) * pi2);
    let b = k1 + k2 + (16.0 * v / 3.0).powi(2);
    let disc = contactlab::model::moving::c64::new(b * b - 4.0 * k1 * k2, 0.0).sqrt();
    [(disc - b) * 0.5, (-disc - b) * 0.5]
        .iter()
        .map(|mu| mu.sqrt().re.abs())
        .fold(0.0, f64::max)
}

fn thin_string(speed: f64) -> MovingStringData {
    MovingStringData {
        speed,
        damping: 0.0,
        oscillator: None,
    }
}

/// Past |v̄| = 1: the warning's growth rate of two sines against the closed form (round-off
/// floor 64 ε ρ, ρ = max |λ|), and the growth rate over N not falling (the warning's claim).
fn supercritical_checks(v: f64, s: &SpeedEdge, rates: &[f64]) -> Result<Vec<Check>, String> {
    let model = MovingStringModel::new(StringDiscretization::Sine { modes: 2 }, Default::default())
        .map_err(|e| e.to_string())?;
    let ev = model_eigenvalues(&model, &thin_string(v))?;
    let a = assess_point(&model, &thin_string(v), &ev, &VerdictParams::default());
    let exact = two_sine_growth_rate(v);
    let computed = a.supercritical.map_or(f64::NAN, |w| w.discrete_growth_rate);
    let floor = 64.0 * f64::EPSILON * a.spectral_scale;
    Ok(vec![
        Check::at_most(
            &format!(
                "v̄ = {v}, two sines: the warning's growth rate {computed:.6e} − the closed form's {exact:.6e} (64 ε ρ = {floor:.1e})"
            ),
            (computed - exact).abs(),
            floor,
        ),
        Check::holds(
            &format!(
                "v̄ = {v}: the discrete growth rate over N = {:?}: {}",
                s.modes,
                rates
                    .iter()
                    .map(|r| format!("{r:.3e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            rates.windows(2).all(|r| r[1] >= r[0]),
            "not falling with N (the warning: refinement does not remove it)",
        ),
    ])
}

fn speed_gates(s: &SpeedEdge, report: &mut CaseReport) -> Result<Vec<SpeedPoint>, String> {
    let mut points = Vec::new();
    let mut checks = Vec::new();
    for &v in &s.speeds {
        let exact = std::f64::consts::PI * (1.0 - v * v).abs();
        let supercritical = v.abs() > 1.0;
        let (mut errors, mut rates) = (Vec::new(), Vec::new());
        for &n in &s.modes {
            let model =
                MovingStringModel::new(StringDiscretization::Sine { modes: n }, Default::default())
                    .map_err(|e| e.to_string())?;
            let d = thin_string(v);
            let ev = model_eigenvalues(&model, &d)?;
            let a = assess_point(&model, &d, &ev, &VerdictParams::default());
            let lowest = ev
                .iter()
                .filter(|l| l.im > 0.0)
                .map(|l| l.im)
                .fold(f64::INFINITY, f64::min);
            let error = (lowest - exact).abs() / exact;
            let rate = a.supercritical.map(|w| w.discrete_growth_rate);
            checks.push(if supercritical {
                Check::holds(
                    &format!(
                        "v̄ = {v}, N = {n}: verdict {} with the supercritical warning (discrete growth rate {:.3e}; λ₁ error {error:.2e})",
                        a.verdict.name(),
                        rate.unwrap_or(f64::NAN)
                    ),
                    rate.is_some(),
                    "the warning stated: the continuum is marginal, the verdict is the discrete model's",
                )
            } else {
                Check::holds(
                    &format!(
                        "v̄ = {v}, N = {n}: verdict {} (λ₁ error {error:.2e}), no supercritical warning",
                        a.verdict.name()
                    ),
                    a.verdict == Verdict::Marginal && rate.is_none(),
                    "marginal, without the warning",
                )
            });
            errors.push(error);
            rates.extend(rate);
            points.push(SpeedPoint {
                speed: v,
                modes: n,
                verdict: a.verdict,
                lowest_error: error,
                discrete_growth_rate: rate,
            });
        }
        let floor = 64.0 * f64::EPSILON;
        checks.push(Check::holds(
            &format!(
                "v̄ = {v}: λ₁'s error over N = {:?}: {}",
                s.modes,
                errors
                    .iter()
                    .map(|e| format!("{e:.2e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            errors.windows(2).all(|e| e[1] <= e[0].max(floor)),
            "not growing with N (above the round-off floor 64 ε)",
        ));
        if supercritical {
            checks.extend(supercritical_checks(v, s, &rates)?);
        }
    }
    report.gates.push(GateVerdict::from_checks(
        "thin undamped string near v̄ = 0, near and past v̄ = 1: the continuum's verdict below it, the supercritical warning past it, converging frequency".into(),
        "exact",
        checks,
        "λ_n = inπ(1 − v̄²): imaginary for every v̄ ≠ 1. Past v̄ = 1 the fixed-fixed string is overdetermined (characteristics v̄ ± 1 of one sign) and its Ritz models are not marginal: the verdict must carry the warning, whose growth rate is the closed form's for two sines (written here) and does not fall with N",
    ));
    Ok(points)
}

/// Past the range: each input must be refused with a typed error naming its key.
fn limit_gates(report: &mut CaseReport) -> Result<(), String> {
    let mut checks = Vec::new();
    let plate = PlateProperties::default();
    let e = harmonic_frequencies(&plate, 4001, 2, 1)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    checks.push(Check::holds(
        &format!("4001 radial elements: {e}"),
        e.contains("discretization.elements"),
        "a typed error naming discretization.elements",
    ));
    let model =
        MovingStringModel::new(StringDiscretization::Sine { modes: 10 }, Default::default())
            .map_err(|e| e.to_string())?;
    let bushing = Bushing {
        stiffness: 4.2,
        mass: 0.35,
        position: 1.0,
    };
    let e = model
        .system(&bushing.data(0.37, 0.03, ContactModel::Ideal, 0.0))
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    checks.push(Check::holds(
        &format!("a bushing on the guide ā = 1: {e}"),
        e.contains("oscillator.position"),
        "a typed error naming oscillator.position",
    ));
    let soft = Bushing {
        position: 0.41,
        ..bushing
    };
    let e = model
        .system(&soft.data(0.37, 0.03, ContactModel::Penalty { stiffness: -1.0 }, 0.0))
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    checks.push(Check::holds(
        &format!("a negative penalty stiffness: {e}"),
        e.contains("oscillator.penalty_stiffness"),
        "a typed error naming oscillator.penalty_stiffness",
    ));
    report.gates.push(GateVerdict::from_checks(
        "past the range: typed errors naming the key".into(),
        "exact",
        checks,
        "the limits stated in docs/moving_continua.md, Range",
    ));
    Ok(())
}

#[derive(Debug, Clone, Serialize)]
struct EnvelopeData {
    onsets: Vec<OnsetLevel>,
    plate: Vec<PlateLevel>,
    speeds: Vec<SpeedPoint>,
}

/// Runs the case.
pub fn run(case: &EnvelopeCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let onsets = onset_gates(&case.onset, report)?;
    let plate = plate_gates(&case.plate, report)?;
    let speeds = speed_gates(&case.speeds, report)?;
    limit_gates(report)?;
    ctx.write_data(
        report,
        &EnvelopeData {
            onsets,
            plate,
            speeds,
        },
    )
}
