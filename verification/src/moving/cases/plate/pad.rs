//! `moving_plate_pad`: the stationary pad on the rotating plate (issue "the rotating Kirchhoff
//! plate … and the friction pad on it").
//!
//! - Frictionless spring, (Ω, k_p) map: below the lowest critical speed Ω_c = min_n ω_{n,0}/n
//!   the total stiffness K_b + Ω² K_T + k_p v vᵀ is positive definite (checked by Cholesky), so
//!   by Lagrange–Dirichlet with gyroscopic forces (Thomson–Tait) no point can be unstable; above
//!   Ω_c the stationary spring destabilizes (Iwan & Moeller): both directions are gated.
//! - Friction with damping α, (Ω, μ) map: the rank-one line path (`RankOneLine`) against faer
//!   point by point; every point of a coarse grid confirmed by integrating the linear system in
//!   time (RK4, `check_growth`).
//! - The pad's stiffness against the virtual work written here (`pad_limits.rs`), the onset μ*
//!   converged in the basis, k_p → ∞ against the constrained plate, N = 20 harmonics without a
//!   false verdict.

use serde::Serialize;

use contactlab::model::moving::linearized::LinearizedModel;
use contactlab::model::moving::plate::{PlateData, PlateParameter, RotatingPlateModel};
use contactlab::model::moving::stability::{StabilityAssessment, Verdict};
use contactlab::model::moving::stability_map::{
    stability_map, GridAxis, StabilityMap, StabilityMapParams,
};
use contactlab::solve::quadratic_eigen::{EigenKernel, QuadraticEigenParams};

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::moving::cases::plate::common::{
    lowest_critical_speed, plate_model, positive_definite, spectrum,
};
use crate::moving::cases::plate::pad_format::{PadCase, TimeCheckSection};
use crate::moving::cases::plate::pad_limits;
use crate::moving::plots::verdict_color;
use crate::moving::study::{check_growth, GrowthCheck};
use crate::plot::{Figure, Series};

/// One time-checked point.
#[derive(Debug, Clone, Serialize)]
pub struct TimeRow {
    pub angular_speed: f64,
    pub friction: f64,
    pub stiffness: f64,
    pub verdict: Verdict,
    pub check: GrowthCheck,
}

/// What the case writes to data.json.
#[derive(Debug, Clone, Serialize)]
struct Data {
    critical_speed: f64,
    critical_harmonic: usize,
    spring_onsets: Vec<(f64, f64)>,
    spring_time_checks: Vec<TimeRow>,
    time_checks: Vec<TimeRow>,
    limits: pad_limits::LimitsData,
}

/// The verdicts of a map as coloured markers.
pub fn verdict_figure(
    title: &str,
    x_label: &str,
    y_label: &str,
    map: &StabilityMap<PlateParameter>,
) -> Figure {
    let nx = map.x.values.len();
    let mut f = Figure::new(title).x_label(x_label).y_label(y_label);
    for v in Verdict::ALL {
        let pts: Vec<(f64, f64)> = map
            .points
            .iter()
            .enumerate()
            .filter(|(_, a)| a.verdict == v)
            .map(|(i, _)| (map.x.values[i % nx], map.y.values[i / nx]))
            .collect();
        if !pts.is_empty() {
            f = f.series(Series::markers(v.name(), pts).color(verdict_color(v)));
        }
    }
    f
}

fn map_params(kernel: EigenKernel) -> StabilityMapParams {
    StabilityMapParams {
        eigen: QuadraticEigenParams {
            kernel,
            ..Default::default()
        },
        ..Default::default()
    }
}

/// Integrates the system at `d` (assessed as `a`) from a pseudo-random state (`seed`) long
/// enough for the critical mode to dominate: e^{-separation} of the others' share is left after
/// separation / gap (gap: max Re λ minus the largest real part below it by more than the check's
/// tolerance — modes within the tolerance may share the lead), within [duration, max_duration].
fn time_check(
    model: &RotatingPlateModel,
    d: &PlateData,
    a: &StabilityAssessment,
    t: &TimeCheckSection,
    seed: u64,
) -> Result<TimeRow, String> {
    let system = model.system(d).map_err(|e| e.to_string())?;
    let ev = spectrum(model, d, false)?.eigenvalues;
    let within = t.absolute_tolerance + t.relative_tolerance * a.max_real_part.abs();
    let next = ev
        .iter()
        .map(|l| l.re)
        .filter(|&r| r < a.max_real_part - within)
        .fold(f64::NEG_INFINITY, f64::max);
    let gap = a.max_real_part - next;
    let duration = (t.separation / gap).clamp(t.duration, t.max_duration);
    let (check, _) = check_growth(&system, a.max_real_part, a.spectral_scale, duration, seed)?;
    Ok(TimeRow {
        angular_speed: d.angular_speed,
        friction: d.pad.map_or(0.0, |p| p.friction),
        stiffness: d.pad.map_or(0.0, |p| p.stiffness),
        verdict: a.verdict,
        check,
    })
}

/// |σ_obs − max Re λ| beyond the check's tolerance (> 0: a miss).
fn miss(r: &TimeRow, t: &TimeCheckSection) -> f64 {
    (r.check.observed - r.check.predicted).abs()
        - (t.absolute_tolerance + t.relative_tolerance * r.check.predicted.abs())
}

/// Runs the case.
pub fn run(case: &PadCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let plate = case.plate.properties();
    let b = case.basis;
    let model = plate_model(plate, b.harmonics, b.elements, Some(b.radial_modes))?;
    let (omega_c, n_c) = lowest_critical_speed(&plate, b.elements, b.harmonics)?;
    let (spring_onsets, spring_time_checks) = spring(case, &model, omega_c, n_c, ctx, report)?;
    let time_checks = friction(case, &model, ctx, report)?;
    let limits = pad_limits::run(case, &model, omega_c, ctx, report)?;
    ctx.write_data(
        report,
        &Data {
            critical_speed: omega_c,
            critical_harmonic: n_c,
            spring_onsets,
            spring_time_checks,
            time_checks,
            limits,
        },
    )
}

/// Per k_p the first unstable Ω (NaN: none), and the time checks of the map's verdict kinds.
type SpringResult = (Vec<(f64, f64)>, Vec<TimeRow>);

/// The frictionless pad: stable below Ω_c (theorem), destabilized above (both gated).
fn spring(
    case: &PadCase,
    model: &RotatingPlateModel,
    omega_c: f64,
    n_c: usize,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<SpringResult, String> {
    let s = case.spring;
    let base = PlateData {
        angular_speed: 0.0,
        damping: 0.0,
        pad: Some(case.pad.with_friction(0.0)),
    };
    let x = GridAxis::linspace(
        PlateParameter::AngularSpeed,
        0.0,
        s.speed_factor_to * omega_c,
        s.speeds,
    )
    .map_err(|e| e.to_string())?;
    let y = GridAxis::linspace(
        PlateParameter::PadStiffness,
        0.0,
        s.stiffness_to,
        s.stiffnesses,
    )
    .map_err(|e| e.to_string())?;
    let map = stability_map(model, &base, &x, &y, &map_params(EigenKernel::SmallDense))
        .map_err(|e| e.to_string())?;
    let nx = x.values.len();
    let (mut below_unstable, mut below_indefinite, mut above_unstable) = (0, 0, 0);
    let mut onsets = Vec::new();
    for (iy, &kp) in y.values.iter().enumerate() {
        let mut onset = f64::NAN;
        for (ix, &om) in x.values.iter().enumerate() {
            let a = map.points[iy * nx + ix];
            if om < omega_c {
                below_unstable += usize::from(a.verdict.is_unstable());
                let mut d = base;
                d.angular_speed = om;
                if let Some(p) = d.pad.as_mut() {
                    p.stiffness = kp;
                }
                let k = model
                    .system(&d)
                    .map_err(|e| e.to_string())?
                    .stiffness_matrix();
                below_indefinite += usize::from(!positive_definite(&k));
            } else if a.verdict.is_unstable() {
                above_unstable += 1;
                if onset.is_nan() {
                    onset = om;
                }
            }
        }
        onsets.push((kp, onset));
    }
    // k_p = 0 just above Ω_c: the plate's own stiffness is indefinite (the threshold is Ω_c)
    let just_above = PlateData {
        angular_speed: omega_c * (1.0 + 1e-6),
        damping: 0.0,
        pad: None,
    };
    let k_above = model
        .system(&just_above)
        .map_err(|e| e.to_string())?
        .stiffness_matrix();
    let rows_with_instability = onsets
        .iter()
        .filter(|(k, o)| *k > 0.0 && o.is_finite())
        .count();
    let rows_with_pad = onsets.iter().filter(|(k, _)| *k > 0.0).count();
    report.gates.push(GateVerdict::from_checks(
        format!(
            "frictionless pad: stable below the critical speed Ω_c = ω_{{{n_c},0}}/{n_c} = {omega_c:.6}, destabilized above"
        ),
        "theorem",
        vec![
            Check::at_most(
                "points with Ω < Ω_c where K_b + Ω²K_T + k_p v vᵀ is not positive definite (Cholesky)",
                below_indefinite as f64,
                0.0,
            ),
            Check::at_most(
                "unstable points with Ω < Ω_c (Lagrange–Dirichlet with gyroscopic forces)",
                below_unstable as f64,
                0.0,
            ),
            Check::holds(
                "K_b + Ω²K_T indefinite at Ω = Ω_c (1 + 1e-6) without pad",
                !positive_definite(&k_above),
                "the threshold of the theorem is Ω_c",
            ),
            Check::at_least(
                &format!(
                    "rows k_p > 0 with an unstable point in Ω_c < Ω ≤ {}Ω_c ({above_unstable} points)",
                    s.speed_factor_to
                ),
                rows_with_instability as f64,
                rows_with_pad as f64,
            ),
        ],
        "Thomson–Tait: positive definite stiffness + any skew G, no damping, no circulatory force ⇒ stable; a stationary spring on a rotating disc destabilizes above the critical speed (Iwan & Moeller)",
    ));
    // every kind of verdict of this map confirmed in time: its first point of each kind
    let mut kinds = Vec::new();
    for v in Verdict::ALL {
        if let Some(i) = map.points.iter().position(|a| a.verdict == v) {
            let mut d = base;
            d.angular_speed = x.values[i % nx];
            if let Some(p) = d.pad.as_mut() {
                p.stiffness = y.values[i / nx];
            }
            kinds.push(time_check(
                model,
                &d,
                &map.points[i],
                &case.time_check,
                500 + i as u64,
            )?);
        }
    }
    let t = &case.time_check;
    let failing = kinds
        .iter()
        .filter(|r| miss(r, t).is_nan() || miss(r, t) > 0.0)
        .count();
    report.gates.push(GateVerdict::from_checks(
        format!(
            "every kind of verdict of the (Ω, k_p) map confirmed by RK4: {}",
            kinds
                .iter()
                .map(|r| format!(
                    "{} at (Ω, k_p) = ({:.4}, {}): max Re λ = {:.3e}, observed {:.3e}",
                    r.verdict.name(),
                    r.angular_speed,
                    r.stiffness,
                    r.check.predicted,
                    r.check.observed
                ))
                .collect::<Vec<_>>()
                .join("; ")
        ),
        "independent",
        vec![
            Check::at_most(
                &format!(
                    "points outside {} + {}·|max Re λ|",
                    t.absolute_tolerance, t.relative_tolerance
                ),
                failing as f64,
                0.0,
            ),
            Check::at_least("kinds of verdict checked", kinds.len() as f64, 2.0),
        ],
        "the first point of each verdict in the map, integrated from a pseudo-random state",
    ));
    let f = verdict_figure("frictionless pad: verdicts over (Ω, k_p)", "Ω", "k_p", &map)
        .vertical_line(omega_c, "Ω_c = min ω_{n,0}/n");
    ctx.plot(report, "pad_spring_map", &f)?;
    Ok((onsets, kinds))
}

/// The (Ω, μ) map with damping: lines against faer, and a coarse grid in time.
fn friction(
    case: &PadCase,
    model: &RotatingPlateModel,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<Vec<TimeRow>, String> {
    let fr = case.friction;
    let base = PlateData {
        angular_speed: fr.speed_from,
        damping: fr.damping,
        pad: Some(case.pad.with_friction(0.0)),
    };
    let axis = |p, from, to, n| GridAxis::linspace(p, from, to, n).map_err(|e| e.to_string());
    let x = axis(
        PlateParameter::AngularSpeed,
        fr.speed_from,
        fr.speed_to,
        fr.speeds,
    )?;
    let y = axis(PlateParameter::Friction, 0.0, fr.friction_to, fr.frictions)?;
    let fast = stability_map(model, &base, &x, &y, &map_params(EigenKernel::SmallDense))
        .map_err(|e| e.to_string())?;
    let reference = stability_map(model, &base, &x, &y, &map_params(EigenKernel::Faer))
        .map_err(|e| e.to_string())?;
    let n2 = 2.0 * model.dimension() as f64;
    let (mut differ, mut worst) = (0, 0.0f64);
    for (a, r) in fast.points.iter().zip(&reference.points) {
        differ += usize::from(a.verdict != r.verdict);
        worst = worst.max(
            (a.max_real_part - r.max_real_part).abs() / (n2 * f64::EPSILON * r.spectral_scale),
        );
    }
    report.gates.push(GateVerdict::from_checks(
        format!(
            "(Ω, μ) map, {} × {} points: rank-one lines (one Hessenberg reduction per Ω) against faer point by point",
            fr.speeds, fr.frictions
        ),
        "exact",
        vec![
            Check::at_most("points whose verdicts differ", differ as f64, 0.0),
            Check::at_most(
                "max |Δ max Re λ| in units of 2n ε ρ",
                worst,
                fr.kernel_round_off,
            ),
        ],
        "the line path applies exact similarity transformations: the same eigenvalues to round-off",
    ));
    // every point of a coarse grid in time
    let t = case.time_check;
    let tx = axis(
        PlateParameter::AngularSpeed,
        fr.speed_from,
        fr.speed_to,
        t.speeds,
    )?;
    let ty = axis(PlateParameter::Friction, 0.0, fr.friction_to, t.frictions)?;
    let coarse = stability_map(model, &base, &tx, &ty, &map_params(EigenKernel::Faer))
        .map_err(|e| e.to_string())?;
    let mut rows = Vec::new();
    let nx = tx.values.len();
    for (i, a) in coarse.points.iter().enumerate() {
        let mut d = base;
        d.angular_speed = tx.values[i % nx];
        if let Some(p) = d.pad.as_mut() {
            p.friction = ty.values[i / nx];
        }
        rows.push(time_check(model, &d, a, &t, 1000 + i as u64)?);
    }
    let miss = |r: &TimeRow| {
        (r.check.observed - r.check.predicted).abs()
            - (t.absolute_tolerance + t.relative_tolerance * r.check.predicted.abs())
    };
    let failing = rows
        .iter()
        .filter(|r| miss(r).is_nan() || miss(r) > 0.0)
        .count();
    let worst_row = rows
        .iter()
        .map(|r| (r.check.observed - r.check.predicted).abs())
        .fold(0.0, f64::max);
    let kinds: Vec<String> = Verdict::ALL
        .iter()
        .map(|v| {
            format!(
                "{} {}",
                rows.iter().filter(|r| r.verdict == *v).count(),
                v.name()
            )
        })
        .collect();
    let flutter = rows
        .iter()
        .filter(|r| r.verdict == Verdict::Flutter)
        .count();
    let stable = rows.iter().filter(|r| r.verdict == Verdict::Stable).count();
    report.gates.push(GateVerdict::from_checks(
        format!(
            "every verdict of a {} × {} (Ω, μ) grid confirmed by RK4 over t ∈ [{}, {}]: observed growth = max Re λ",
            t.speeds, t.frictions, t.duration, t.max_duration
        ),
        "independent",
        vec![
            Check::at_most(
                &format!(
                    "points outside {} + {}·|max Re λ| (largest |σ_obs − max Re λ| = {worst_row:.2e}; {})",
                    t.absolute_tolerance,
                    t.relative_tolerance,
                    kinds.join(", ")
                ),
                failing as f64,
                0.0,
            ),
            Check::holds(
                "both stable and fluttering points checked",
                flutter > 0 && stable > 0,
                "the grid crosses the flutter boundary",
            ),
        ],
        "growth of ln ‖(q, q̇)‖ through the peaks of ten windows of the last half",
    ));
    let mut f = verdict_figure(
        &format!(
            "pad with friction, α = {}: verdicts over (Ω, μ)",
            fr.damping
        ),
        "Ω",
        "μ",
        &fast,
    );
    f = f.series(
        Series::markers(
            "time-checked points",
            rows.iter().map(|r| (r.angular_speed, r.friction)),
        )
        .color(7),
    );
    let g = Figure::new("time checks: observed growth against max Re λ")
        .x_label("max Re λ")
        .y_label("observed growth rate")
        .series(
            Series::markers(
                "points of the grid",
                rows.iter().map(|r| (r.check.predicted, r.check.observed)),
            )
            .color(1),
        )
        .series(
            Series::line("observed = predicted", {
                let lo = rows
                    .iter()
                    .map(|r| r.check.predicted)
                    .fold(f64::INFINITY, f64::min);
                let hi = rows
                    .iter()
                    .map(|r| r.check.predicted)
                    .fold(f64::NEG_INFINITY, f64::max);
                vec![(lo, lo), (hi, hi)]
            })
            .color(6)
            .dashed(),
        );
    ctx.panels(
        report,
        "pad_friction_map",
        "The pad with Coulomb friction: verdicts over (Ω, μ) (rank-one lines), and every point of the coarse grid integrated in time",
        &[f, g],
        2,
    )?;
    Ok(rows)
}
