//! `moving_extremes`: stability analysis at the edges.
//!
//! - v̄ → 1: the spectrum scales with 1 − v̄² (K(v̄) = (1 − v̄²)K₀). The ratio ω₁/(π(1 − v̄²))
//!   converges to its v̄ = 1 limit linearly in δ = 1 − v̄ down to δ = 1e-8: no digits are lost
//!   to the shrinking stiffness (the companion's scaling γ = sqrt(‖K‖/‖M‖) absorbs it; its norm,
//!   the conditioning, is reported).
//! - k̄_p → 10¹⁵: the series-spring condensation reproduces the ideal contact to round-off; the
//!   generic Schur complement loses digits like ε k̄_p/c̄ (observed slope 1); the uncondensed
//!   stiffness has condition number ∝ k̄_p (reported).
//! - Undamped gyroscopic–circulatory systems (ᾱ = 0, v̄ ≠ 0, p ≠ 0) are almost surely unstable
//!   (Kirillov 2007; Lakhadanov 1975): Σ Re λ = −tr(M⁻¹C) = 0 forces an unstable eigenvalue
//!   unless every one sits exactly on the axis, which the broken Hamiltonian symmetry does not
//!   allow. Every random point is unstable, and the trace identity holds to round-off.
//! - Near-defective eigenvalues: approaching the flutter onset of a circulatory system (two
//!   imaginary eigenvalues collide in a Jordan block), the computed real parts below the onset
//!   stay below the verdict tolerance τ (no false flutter), and above it the growth rate rises
//!   like (p − p*)^{1/2}; verdicts are wrong nowhere, and `Marginal` only in the blind zone
//!   where the true growth rate is below τ.

use std::path::Path;

use nalgebra::Complex;
use serde::{Deserialize, Serialize};

use contactlab::model::moving::c64;
use contactlab::model::moving::stability::{assess, Verdict, VerdictParams};
use contactlab::model::moving::string_data::{ContactModel, MovingStringData, OscillatorData};
use contactlab::model::moving::string_model::{
    MovingStringModel, MovingStringParams, PenaltyCondensation, StringDiscretization,
};
use contactlab::model::moving::system::MovingSystem;
use contactlab::model::moving::Mat;
use contactlab::solve::quadratic_eigen::{solve_generalized_quadratic_eigen, QuadraticEigenParams};

use crate::core::context::RunContext;
use crate::core::format::positive;
use crate::core::format::CaseError;
use crate::core::gate::RateGate;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::moving::errors::upper_half;
use crate::moving::study::SeriesSelect;
use crate::plot::{Figure, Series};
use crate::stats::lcg::Lcg;
use crate::stats::rate_fit::fit_rate;

/// The case format of `moving_extremes`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtremesCase {
    pub critical_speed: CriticalSpeed,
    pub critical_speed_gate: RateGate<SeriesSelect>,
    pub stiff_penalty: StiffPenalty,
    pub undamped: Undamped,
    pub near_defective: NearDefective,
    pub onset_gate: RateGate<SeriesSelect>,
}

/// `[critical_speed]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CriticalSpeed {
    pub modes: usize,
    /// δ = 1 − v̄, decades (so successive differences are 0.9 C δ).
    pub distances: Vec<f64>,
    /// Below this δ the differences are round-off: checked against ε/δ instead.
    pub round_off_below: f64,
    /// |Δr| ≤ this × ε/δ there.
    pub conditioning_factor: f64,
}

/// `[stiff_penalty]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StiffPenalty {
    pub modes: usize,
    pub penalties: Vec<f64>,
    /// Series springs against ideal contact with c_eff: relative eigenvalue difference.
    pub series_tolerance: f64,
    /// Series springs at the largest k̄_p against ideal contact (c_eff = c̄ to round-off).
    pub limit_tolerance: f64,
    /// The Schur error's log–log slope against k̄_p must lie within this of 1.
    pub schur_slope_tolerance: f64,
}

/// `[undamped]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Undamped {
    pub modes: usize,
    pub points: usize,
    pub speed_range: [f64; 2],
    pub control_range: [f64; 2],
    /// |Σ Re λ| / (2n max |λ|) at most this.
    pub trace_tolerance: f64,
    /// The same points with this damping (reported: damping can stabilize).
    pub damping: f64,
}

/// `[near_defective]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct NearDefective {
    /// Relative distances (p − p*)/p* approached from both sides.
    pub distances: Vec<f64>,
    pub string_modes: usize,
}

impl ExtremesCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        self.critical_speed_gate
            .criteria
            .check(p, "critical_speed_gate")?;
        self.onset_gate.criteria.check(p, "onset_gate")?;
        positive(
            p,
            "stiff_penalty.series_tolerance",
            self.stiff_penalty.series_tolerance,
        )?;
        positive(
            p,
            "stiff_penalty.limit_tolerance",
            self.stiff_penalty.limit_tolerance,
        )?;
        positive(p, "undamped.trace_tolerance", self.undamped.trace_tolerance)?;
        if self.undamped.points == 0 || self.near_defective.distances.len() < 3 {
            return Err(crate::core::format::invalid(
                p,
                "undamped.points",
                self.undamped.points,
                ">= 1 (and >= 3 distances)",
            ));
        }
        Ok(())
    }
}

fn eigen(s: &MovingSystem) -> Result<(Vec<c64>, f64), String> {
    let r = s
        .eigen(QuadraticEigenParams::default())
        .map_err(|e| e.to_string())?;
    Ok((r.eigenvalues, r.stats.companion_norm))
}

fn osc(speed: f64, damping: f64, contact: ContactModel, friction: f64) -> MovingStringData {
    MovingStringData {
        speed,
        damping,
        oscillator: Some(OscillatorData {
            stiffness: 2.0,
            mass: 0.5,
            position: 0.3,
            contact,
            friction,
        }),
    }
}

/// The 2-dof circulatory system q̈ + (K + pN) q = 0, K = diag(1, 4), N = [0 1; −1 0]:
/// λ² = −(2.5 ± sqrt(2.25 − p²)), a Jordan block at p* = 3/2.
fn ziegler(p: f64) -> MovingSystem {
    let mut s = MovingSystem::zeros(vec!["q1".into(), "q2".into()]);
    s.mass = Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { 0.0 });
    s.stiffness = Mat::from_fn(2, 2, |i, j| if i == j { [1.0, 4.0][i] } else { 0.0 });
    s.circulatory = Mat::from_fn(2, 2, |i, j| match (i, j) {
        (0, 1) => p,
        (1, 0) => -p,
        _ => 0.0,
    });
    s
}

/// The exact max Re λ of [`ziegler`].
fn ziegler_exact(p: f64) -> f64 {
    let disc = Complex::new(2.25 - p * p, 0.0).sqrt();
    [Complex::new(2.5, 0.0) + disc, Complex::new(2.5, 0.0) - disc]
        .iter()
        .map(|mu| (-mu).sqrt().re.abs())
        .fold(0.0, f64::max)
}

/// Runs the case.
pub fn run(case: &ExtremesCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let verdict = VerdictParams::default();
    // v̄ → 1.
    let cs = &case.critical_speed;
    let model = MovingStringModel::new(
        StringDiscretization::Sine { modes: cs.modes },
        Default::default(),
    )
    .map_err(|e| e.to_string())?;
    let mut rows = Vec::new();
    for &d in &cs.distances {
        let v = 1.0 - d;
        let s = model
            .system(&MovingStringData::string(v, 0.0))
            .map_err(|e| e.to_string())?;
        let (ev, norm) = eigen(&s)?;
        let w1 = upper_half(&ev)[0].im;
        rows.push((d, w1 / (std::f64::consts::PI * (1.0 - v * v)), norm));
    }
    // r(δ) = r0 + C δ + O(δ²) with δ = 10⁻ᵏ: successive differences 0.9 C δ, rate 1, until the
    // round-off of the small eigenvalue ω₁ ≈ 2πδ — relative error ~ ε/δ — takes over.
    let diffs: Vec<(f64, f64)> = rows
        .windows(2)
        .map(|w| (w[0].0, (w[0].1 - w[1].1).abs()))
        .collect();
    let resolved: Vec<&(f64, f64)> = diffs.iter().filter(|x| x.0 >= cs.round_off_below).collect();
    report
        .gates
        .push(case.critical_speed_gate.criteria.evaluate(
            format!(
                "v̄ → 1: ω₁/(π(1 − v̄²)) converges linearly in δ = 1 − v̄ (δ ≥ {:.0e})",
                cs.round_off_below
            ),
            &resolved.iter().map(|x| x.0).collect::<Vec<_>>(),
            &resolved.iter().map(|x| x.1.max(1e-300)).collect::<Vec<_>>(),
        ));
    let worst_cond = diffs
        .iter()
        .filter(|x| x.0 < cs.round_off_below)
        .map(|x| x.1 / (f64::EPSILON / x.0))
        .fold(0.0, f64::max);
    report.gates.push(GateVerdict::from_checks(
        "v̄ → 1: conditioning of the small eigenvalues".into(),
        "extreme",
        vec![Check::at_most(
            &format!("δ < {:.0e}: |Δr| / (ε/δ) (relative accuracy of ω₁ in units of ε/δ)", cs.round_off_below),
            worst_cond,
            cs.conditioning_factor,
        )],
        "ω₁ → 0 like 2πδ while the companion's norm grows like δ^{-1/2}: the relative accuracy of ω₁ degrades like ε/δ, and at δ = 1e-8 it is still ~1e-9, far below the discretization error",
    ));

    // k̄_p → 10¹⁵.
    let sp = &case.stiff_penalty;
    let disc = StringDiscretization::Sine { modes: sp.modes };
    let series = MovingStringModel::new(disc, Default::default()).map_err(|e| e.to_string())?;
    let schur = MovingStringModel::new(
        disc,
        MovingStringParams {
            condensation: PenaltyCondensation::Schur,
        },
    )
    .map_err(|e| e.to_string())?;
    let ideal = upper_half(
        &eigen(
            &series
                .system(&osc(0.4, 0.0, ContactModel::Ideal, 0.1))
                .map_err(|e| e.to_string())?,
        )?
        .0,
    );
    let mut prow = Vec::new();
    let mut series_worst: f64 = 0.0;
    for &kp in &sp.penalties {
        let d = osc(0.4, 0.0, ContactModel::Penalty { stiffness: kp }, 0.1);
        let c_eff = 2.0 / (1.0 + 2.0 / kp);
        let mut eff = osc(0.4, 0.0, ContactModel::Ideal, 0.1);
        if let Some(o) = eff.oscillator.as_mut() {
            o.stiffness = c_eff;
        }
        let reference = upper_half(&eigen(&series.system(&eff).map_err(|e| e.to_string())?)?.0);
        let a = upper_half(&eigen(&series.system(&d).map_err(|e| e.to_string())?)?.0);
        let b = upper_half(&eigen(&schur.system(&d).map_err(|e| e.to_string())?)?.0);
        let full = series.system_with_bushing(&d).map_err(|e| e.to_string())?;
        let qz = solve_generalized_quadratic_eigen(
            full.mass.as_ref(),
            full.velocity_matrix().as_ref(),
            full.stiffness_matrix().as_ref(),
            1e-10,
        )
        .map(|r| upper_half(&r.eigenvalues))
        .ok();
        let rel = |x: &[c64]| -> f64 {
            (0..4)
                .map(|k| {
                    x.get(k).map_or(f64::INFINITY, |l| {
                        (l - reference[k]).norm() / reference[k].norm()
                    })
                })
                .fold(0.0, f64::max)
        };
        let (ea, eb) = (rel(&a), rel(&b));
        let eq = qz.as_deref().map_or(f64::NAN, rel);
        series_worst = series_worst.max(ea);
        // cond(K_full) by the ratio of extreme |eigenvalues| of the symmetric part.
        let k = full.stiffness_matrix();
        let kn = k.norm_l2();
        prow.push((kp, ea, eb, eq, kn / 2.0));
    }
    let last = sp.penalties.last().copied().unwrap_or(1.0);
    let limit = upper_half(
        &eigen(
            &series
                .system(&osc(
                    0.4,
                    0.0,
                    ContactModel::Penalty { stiffness: last },
                    0.1,
                ))
                .map_err(|e| e.to_string())?,
        )?
        .0,
    );
    let limit_err = (0..4)
        .map(|k| (limit[k] - ideal[k]).norm() / ideal[k].norm())
        .fold(0.0, f64::max);
    let big: Vec<&(f64, f64, f64, f64, f64)> = prow
        .iter()
        .filter(|x| x.0 >= 1e6 && x.2 > 0.0 && x.2 < 1e-1)
        .collect();
    let schur_fit = fit_rate(
        &big.iter().map(|x| 1.0 / x.0).collect::<Vec<_>>(),
        &big.iter().map(|x| x.2).collect::<Vec<_>>(),
        big.len(),
        0.95,
    );
    let schur_slope = schur_fit.as_ref().map_or(f64::NAN, |f| -f.rate);
    report.gates.push(GateVerdict::from_checks(
        "k̄_p → 10¹⁵: condensation without cancellation".into(),
        "extreme",
        vec![
            Check::at_most(
                "series springs vs ideal contact with c_eff, every k̄_p: max relative eigenvalue difference",
                series_worst,
                sp.series_tolerance,
            ),
            Check::at_most(
                &format!("series springs at k̄_p = {last:.0e} vs ideal contact (c_eff = c̄ to round-off)"),
                limit_err,
                sp.limit_tolerance,
            ),
            Check::within(
                "generic Schur complement: log–log slope of its error against k̄_p (round-off ε k̄_p/c̄)",
                schur_slope,
                1.0,
                sp.schur_slope_tolerance,
            ),
        ],
        "k_yy = c̄ + k̄_p: the Schur complement k̄_p − k̄_p²/(c̄ + k̄_p) cancels log10(k̄_p/c̄) digits; c̄/(1 + c̄/k̄_p) does not",
    ));

    // Undamped gyroscopic–circulatory systems.
    let un = &case.undamped;
    let um = MovingStringModel::new(
        StringDiscretization::Sine { modes: un.modes },
        Default::default(),
    )
    .map_err(|e| e.to_string())?;
    let mut rng = Lcg(2009);
    let (mut unstable, mut stable_damped, mut min_growth, mut worst_trace) =
        (0, 0, f64::INFINITY, 0.0f64);
    let mut pts = Vec::new();
    for _ in 0..un.points {
        let v = un.speed_range[0] + (un.speed_range[1] - un.speed_range[0]) * rng.next_unit();
        let p = un.control_range[0] + (un.control_range[1] - un.control_range[0]) * rng.next_unit();
        let d = osc(v, 0.0, ContactModel::Ideal, p / 2.0);
        let (ev, _) = eigen(&um.system(&d).map_err(|e| e.to_string())?)?;
        let a = assess(&ev, &verdict);
        let rho = a.spectral_scale;
        let trace: f64 = ev.iter().map(|l| l.re).sum::<f64>();
        worst_trace = worst_trace.max(trace.abs() / (ev.len() as f64 * rho));
        if a.verdict.is_unstable() {
            unstable += 1;
        }
        min_growth = min_growth.min(a.max_real_part);
        let dd = osc(v, un.damping, ContactModel::Ideal, p / 2.0);
        let (evd, _) = eigen(&um.system(&dd).map_err(|e| e.to_string())?)?;
        let ad = assess(&evd, &verdict);
        if ad.verdict == Verdict::Stable {
            stable_damped += 1;
        }
        pts.push((v, p, a.max_real_part, ad.max_real_part));
    }
    report.gates.push(GateVerdict::from_checks(
        "undamped gyroscopic–circulatory systems are almost surely unstable".into(),
        "extreme",
        vec![
            Check::holds(
                &format!("{unstable} of {} random points (ᾱ = 0, v̄ ∈ {:?}, p ∈ {:?}) unstable; smallest growth {min_growth:.3e}", un.points, un.speed_range, un.control_range),
                unstable == un.points,
                "all",
            ),
            Check::at_most("|Σ Re λ| / (2n max|λ|) (= −tr(M⁻¹C) = 0)", worst_trace, un.trace_tolerance),
        ],
        &format!("with ᾱ = {} the same points are stable at {stable_damped} of {}: damping, not the gyroscopic terms, can stabilize", un.damping, un.points),
    ));

    // Near-defective eigenvalues.
    let nd = &case.near_defective;
    let p_star = 1.5;
    let mut zrows = Vec::new();
    let mut false_verdicts = 0;
    let mut max_spurious: f64 = 0.0;
    let mut above = Vec::new();
    for &d in &nd.distances {
        for side in [-1.0, 1.0] {
            let p = p_star * (1.0 + side * d);
            let (ev, _) = eigen(&ziegler(p))?;
            let a = assess(&ev, &verdict);
            let exact = ziegler_exact(p);
            let ok = if exact > 2.0 * a.tolerance {
                a.verdict == Verdict::Flutter
            } else if exact < 0.5 * a.tolerance {
                a.verdict == Verdict::Marginal
            } else {
                a.verdict != Verdict::Divergence && a.verdict != Verdict::Stable
            };
            if !ok {
                false_verdicts += 1;
            }
            if side < 0.0 {
                max_spurious = max_spurious.max(a.max_real_part.abs());
            } else if exact > 10.0 * a.tolerance {
                above.push((d, a.max_real_part));
            }
            zrows.push((
                side * d,
                exact,
                a.max_real_part,
                a.verdict.name(),
                a.tolerance,
            ));
        }
    }
    // The string: v̄ = 0, ᾱ = 0, friction: circulatory only; find p* by bisection on the first
    // complex pair of M⁻¹K (the QEP's eigenvalues leave the axis exactly there).
    let sm = MovingStringModel::new(
        StringDiscretization::Sine {
            modes: nd.string_modes,
        },
        Default::default(),
    )
    .map_err(|e| e.to_string())?;
    let string_max_re = |p: f64| -> Result<(f64, Verdict, f64), String> {
        let (ev, _) = eigen(
            &sm.system(&osc(0.0, 0.0, ContactModel::Ideal, p / 2.0))
                .map_err(|e| e.to_string())?,
        )?;
        let a = assess(&ev, &verdict);
        Ok((a.max_real_part, a.verdict, a.tolerance))
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    while string_max_re(hi)?.0 < 1e-3 {
        lo = hi;
        hi *= 2.0;
        if hi > 1e6 {
            return Err("no flutter onset of the circulatory string below p = 1e6".into());
        }
    }
    // Bisection on the sign pattern far from round-off, then refine on 1e-7 relative growth.
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if string_max_re(mid)?.0 > 1e-9 * mid.max(1.0) {
            hi = mid;
        } else {
            lo = mid;
        }
        if hi - lo < 1e-15 * hi {
            break;
        }
    }
    let sp_star = 0.5 * (lo + hi);
    let mut srows = Vec::new();
    let mut string_spurious: f64 = 0.0;
    let mut string_false = 0;
    for &d in &nd.distances {
        if d < 1e-9 {
            continue; // p* is known to ~1e-9 relative only (growth threshold of the bisection)
        }
        for side in [-1.0, 1.0] {
            let p = sp_star * (1.0 + side * d);
            let (re, v, tol) = string_max_re(p)?;
            if side < 0.0 {
                string_spurious = string_spurious.max(re.abs());
                if v != Verdict::Marginal {
                    string_false += 1;
                }
            } else if re > 2.0 * tol && v != Verdict::Flutter {
                string_false += 1;
            }
            srows.push((side * d, re, v.name(), tol));
        }
    }
    let tol_z = assess(&eigen(&ziegler(p_star))?.0, &verdict).tolerance;
    report.gates.push(GateVerdict::from_checks(
        "near-defective eigenvalues at flutter onset: no false verdicts".into(),
        "extreme",
        vec![
            Check::holds(
                &format!("2-dof Ziegler-type system, p = 1.5(1 ± d), d = {:.0e} … {:.0e}: {false_verdicts} wrong verdicts", nd.distances[0], nd.distances[nd.distances.len() - 1]),
                false_verdicts == 0,
                "0 (Flutter iff exact Re λ > 2τ, Marginal iff < τ/2)",
            ),
            Check::at_most(
                "2-dof: largest spurious |Re λ| below the onset, relative to τ",
                max_spurious / tol_z,
                1.0,
            ),
            Check::holds(
                &format!("circulatory string (N = {}, p* = {sp_star:.10}): {string_false} wrong verdicts", nd.string_modes),
                string_false == 0,
                "0",
            ),
        ],
        "τ = 1e-7 max|λ| ≈ 7 sqrt(ε) max|λ|: a Jordan block splits by at most O(sqrt(ε)) max|λ| under round-off",
    ));
    report.gates.push(case.onset_gate.criteria.evaluate(
        "growth above a Jordan-block flutter onset ∝ (p − p*)^{1/2} (2-dof, computed)".into(),
        &above.iter().map(|x| x.0).collect::<Vec<_>>(),
        &above.iter().map(|x| x.1).collect::<Vec<_>>(),
    ));

    // Plots.
    let fz = Figure::new("near-defective: max Re λ around the flutter onset p* = 1.5 (2-dof)")
        .x_label("|p − p*|/p*")
        .y_label("|max Re λ|")
        .log_log()
        .series(
            Series::line_markers(
                "above p*: computed",
                zrows.iter().filter(|r| r.0 > 0.0).map(|r| (r.0, r.2.abs())),
            )
            .color(1),
        )
        .series(
            Series::line(
                "above p*: exact",
                zrows.iter().filter(|r| r.0 > 0.0).map(|r| (r.0, r.1)),
            )
            .color(6)
            .dashed(),
        )
        .series(
            Series::line_markers(
                "below p*: spurious (exact 0)",
                zrows
                    .iter()
                    .filter(|r| r.0 < 0.0)
                    .map(|r| (-r.0, r.2.abs().max(1e-18))),
            )
            .color(0),
        )
        .horizontal_line(tol_z, "verdict tolerance τ")
        .horizontal_line(f64::EPSILON.sqrt() * 2.5f64.sqrt(), "sqrt(ε)·|λ|")
        .reference_slope(0.5, "slope 1/2");
    let fs = Figure::new(format!(
        "near-defective: circulatory string, N = {}",
        nd.string_modes
    ))
    .x_label("|p − p*|/p*")
    .y_label("|max Re λ|")
    .log_log()
    .series(
        Series::line_markers(
            "above p*",
            srows
                .iter()
                .filter(|r| r.0 > 0.0)
                .map(|r| (r.0, r.1.abs().max(1e-18))),
        )
        .color(1),
    )
    .series(
        Series::line_markers(
            "below p* (exact 0)",
            srows
                .iter()
                .filter(|r| r.0 < 0.0)
                .map(|r| (-r.0, r.1.abs().max(1e-18))),
        )
        .color(0),
    )
    .horizontal_line(srows.first().map_or(1e-6, |r| r.3), "τ");
    ctx.panels(
        report,
        "near_defective",
        "Near-defective eigenvalues: below the onset the computed real parts (exactly 0) stay under τ; above it the growth follows (p − p*)^{1/2}",
        &[fz, fs],
        2,
    )?;
    let fp = Figure::new("k̄_p → 10¹⁵: eigenvalue error of the condensations")
        .x_label("k̄_p")
        .y_label("max relative eigenvalue difference (vs ideal with c_eff)")
        .log_log()
        .series(
            Series::line_markers("series springs", prow.iter().map(|r| (r.0, r.1.max(1e-17))))
                .color(2),
        )
        .series(
            Series::line_markers(
                "generic Schur complement",
                prow.iter().map(|r| (r.0, r.2.max(1e-17))),
            )
            .color(1),
        )
        .series(
            Series::line_markers(
                "QZ on the DAE (uncondensed)",
                prow.iter().map(|r| (r.0, r.3.max(1e-17))),
            )
            .color(0),
        )
        .series(
            Series::line(
                "ε‖K_full‖/c̄ (conditioning)",
                prow.iter().map(|r| (r.0, r.4 * f64::EPSILON)),
            )
            .color(6)
            .dashed(),
        );
    let c_fit = resolved.last().map_or(1.0, |x| x.1 / x.0);
    let fv = Figure::new("v̄ → 1: ω₁/(π(1 − v̄²)) converges linearly in δ")
        .x_label("δ = 1 − v̄")
        .y_label("|r(δ) − r(δ/10)|")
        .log_log()
        .series(Series::line_markers("successive differences", diffs.iter().copied()).color(0))
        .series(
            Series::line(
                "C δ (discretization)",
                diffs.iter().map(|x| (x.0, c_fit * x.0)),
            )
            .color(1)
            .dashed(),
        )
        .series(
            Series::line(
                "ε/δ (round-off of ω₁ ≈ 2πδ)",
                diffs.iter().map(|x| (x.0, f64::EPSILON / x.0)),
            )
            .color(6)
            .dashed(),
        );
    ctx.panels(report, "conditioning", "Conditioning at the extremes: v̄ → 1 (round-off ε/δ of the vanishing frequencies) and k̄_p → 10¹⁵ (series springs exact; Schur and QZ lose digits like ε‖K_full‖/c̄)", &[fv, fp], 2)?;
    let fu = Figure::new(format!(
        "undamped (ᾱ = 0) vs damped (ᾱ = {}): max Re λ at random (v̄, p)",
        un.damping
    ))
    .x_label("p")
    .y_label("max Re λ")
    .series(Series::markers("ᾱ = 0", pts.iter().map(|x| (x.1, x.2))).color(1))
    .series(
        Series::markers(
            format!("ᾱ = {}", un.damping),
            pts.iter().map(|x| (x.1, x.3)),
        )
        .color(2),
    )
    .horizontal_line(0.0, "");
    ctx.plot(report, "undamped", &fu)?;

    #[derive(Serialize)]
    struct Data<'a> {
        critical_speed: &'a [(f64, f64, f64)],
        stiff_penalty: &'a [(f64, f64, f64, f64, f64)],
        series_limit_error: f64,
        schur_slope: f64,
        undamped_points: &'a [(f64, f64, f64, f64)],
        undamped_unstable: usize,
        damped_stable: usize,
        trace_defect: f64,
        ziegler: &'a [(f64, f64, f64, &'static str, f64)],
        string_onset: f64,
        string_rows: &'a [(f64, f64, &'static str, f64)],
        max_spurious_real_part: f64,
        string_max_spurious_real_part: f64,
    }
    ctx.write_data(
        report,
        &Data {
            critical_speed: &rows,
            stiff_penalty: &prow,
            series_limit_error: limit_err,
            schur_slope,
            undamped_points: &pts,
            undamped_unstable: unstable,
            damped_stable: stable_damped,
            trace_defect: worst_trace,
            ziegler: &zrows,
            string_onset: sp_star,
            string_rows: &srows,
            max_spurious_real_part: max_spurious,
            string_max_spurious_real_part: string_spurious,
        },
    )
}
