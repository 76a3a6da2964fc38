//! k̄_p → 10¹⁵: the series-spring condensation reproduces the independent sine-Galerkin model
//! (`exact::thick_string_galerkin`) with the spring c_eff = c̄k̄_p/(c̄ + k̄_p) and the friction
//! μh̄ c_eff — two springs in series, and the penalty friction force (μk̄_ph̄/2)(w(ā) − y_c) =
//! (μh̄/2) c_eff (w(ā) − u) — to round-off, and ideal contact in the limit; the generic Schur
//! complement loses digits like ε k̄_p/c̄, the uncondensed stiffness is reported.

use contactlab::model::moving::c64;
use contactlab::model::moving::string_data::ContactModel;
use contactlab::model::moving::string_model::{
    MovingStringModel, MovingStringParams, PenaltyCondensation, StringDiscretization,
};

use super::systems::{eigen, osc};
use super::StiffPenalty;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::exact::thick_string_galerkin::ThickString;
use crate::moving::bounds::agreement;
use crate::moving::errors::upper_half;
use crate::moving::study::pencil_eigen;
use crate::stats::rate_fit::fit_rate;

/// What the study measured: per k̄_p (k̄_p, series error, Schur error, QZ error, ‖K_full‖/2).
pub(super) struct StiffPenaltyData {
    pub(super) prow: Vec<(f64, f64, f64, f64, f64)>,
    pub(super) limit_err: f64,
    pub(super) schur_slope: f64,
}

/// Runs the study and pushes its gate.
pub(super) fn study(
    sp: &StiffPenalty,
    report: &mut CaseReport,
) -> Result<StiffPenaltyData, String> {
    let disc = StringDiscretization::Sine { modes: sp.modes };
    let series = MovingStringModel::new(disc, Default::default()).map_err(|e| e.to_string())?;
    let schur = MovingStringModel::new(
        disc,
        MovingStringParams {
            condensation: PenaltyCondensation::Schur,
        },
    )
    .map_err(|e| e.to_string())?;
    // The independent model of the standard oscillator (systems.rs: c̄ = 2, m̄ = 1/2, ā = 0.3)
    // at v̄ = 0.4, ᾱ = 0, μh̄ = 0.1, with the spring c.
    let reference = |c: f64| ThickString {
        speed: 0.4,
        damping: 0.0,
        stiffness: c,
        mass: 0.5,
        position: 0.3,
        control: 0.1 * c,
        patch: 0.0,
    };
    let to_c = |v: &[c64]| -> Vec<nalgebra::Complex<f64>> {
        v.iter()
            .map(|z| nalgebra::Complex::new(z.re, z.im))
            .collect()
    };
    let mut prow = Vec::new();
    let mut series_worst: f64 = 0.0;
    for &kp in &sp.penalties {
        let d = osc(0.4, 0.0, ContactModel::Penalty { stiffness: kp }, 0.1);
        let c_eff = 2.0 * kp / (2.0 + kp);
        let g = reference(c_eff).galerkin(sp.modes);
        let series_ev = eigen(&series.system(&d).map_err(|e| e.to_string())?)?.0;
        let agreed = agreement(&g.first_order()?, &g.eigenvalues()?, &to_c(&series_ev), 0.0)?;
        series_worst = series_worst.max(agreed.ratio);
        let mut eff = osc(0.4, 0.0, ContactModel::Ideal, 0.1);
        if let Some(o) = eff.oscillator.as_mut() {
            o.stiffness = c_eff;
        }
        let reference_ev = upper_half(&eigen(&series.system(&eff).map_err(|e| e.to_string())?)?.0);
        let b = upper_half(&eigen(&schur.system(&d).map_err(|e| e.to_string())?)?.0);
        let full = series.system_with_bushing(&d).map_err(|e| e.to_string())?;
        let qz = pencil_eigen(&full).map(|r| upper_half(&r.eigenvalues)).ok();
        let rel = |x: &[c64]| -> f64 {
            (0..4)
                .map(|k| {
                    x.get(k).map_or(f64::INFINITY, |l| {
                        (l - reference_ev[k]).norm() / reference_ev[k].norm()
                    })
                })
                .fold(0.0, f64::max)
        };
        let eb = rel(&b);
        let eq = qz.as_deref().map_or(f64::NAN, rel);
        let k = full.stiffness_matrix();
        let kn = k.norm_l2();
        prow.push((kp, agreed.ratio, eb, eq, kn / 2.0));
    }
    let last = sp.penalties.last().copied().unwrap_or(1.0);
    let limit_ev = eigen(
        &series
            .system(&osc(
                0.4,
                0.0,
                ContactModel::Penalty { stiffness: last },
                0.1,
            ))
            .map_err(|e| e.to_string())?,
    )?
    .0;
    let ideal_ref = reference(2.0).galerkin(sp.modes);
    let a_ideal = ideal_ref.first_order()?;
    let shift = (&reference(2.0 * last / (2.0 + last))
        .galerkin(sp.modes)
        .first_order()?
        - &a_ideal)
        .norm();
    let limit_err = agreement(&a_ideal, &ideal_ref.eigenvalues()?, &to_c(&limit_ev), shift)?.ratio;
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
                "series springs vs the independent model with c_eff = c̄k̄_p/(c̄ + k̄_p) and friction μh̄ c_eff, every k̄_p: max |Δλ| / (κ(λ) n ε ‖A‖_F)",
                series_worst,
                sp.series_round_off,
            ),
            Check::at_most(
                &format!("series springs at k̄_p = {last:.0e} vs the independent model with ideal contact (c̄): max |Δλ| / (κ(λ)(n ε ‖A‖_F + ‖A(c_eff) − A(c̄)‖_F))"),
                limit_err,
                sp.series_round_off,
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
    Ok(StiffPenaltyData {
        prow,
        limit_err,
        schur_slope,
    })
}
