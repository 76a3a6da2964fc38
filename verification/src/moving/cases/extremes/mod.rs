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

mod critical_speed;
mod format;
mod near_defective;
mod stiff_penalty;
mod systems;
mod undamped;

use serde::Serialize;

use contactlab::model::moving::stability::VerdictParams;

use crate::core::context::RunContext;
use crate::core::report::case_report::CaseReport;
use crate::plot::{Figure, Series};
pub use format::{CriticalSpeed, ExtremesCase, NearDefective, StiffPenalty, Undamped};

use critical_speed::CriticalSpeedData;
use near_defective::NearDefectiveData;
use stiff_penalty::StiffPenaltyData;
use undamped::UndampedData;

/// Runs the case.
pub fn run(case: &ExtremesCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let verdict = VerdictParams::default();
    let CriticalSpeedData { rows, diffs, c_fit } =
        critical_speed::study(&case.critical_speed, &case.critical_speed_gate, report)?;
    let StiffPenaltyData {
        prow,
        limit_err,
        schur_slope,
    } = stiff_penalty::study(&case.stiff_penalty, report)?;
    let un = &case.undamped;
    let UndampedData {
        pts,
        unstable,
        stable_damped,
        worst_trace,
    } = undamped::study(un, &verdict, report)?;
    let nd = &case.near_defective;
    let NearDefectiveData {
        zrows,
        srows,
        sp_star,
        max_spurious,
        string_spurious,
        tol_z,
    } = near_defective::study(nd, &case.onset_gate, &verdict, report)?;

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
