//! k̄_p → 10¹⁵: the series-spring condensation reproduces ideal contact to round-off, the generic
//! Schur complement loses digits like ε k̄_p/c̄, the uncondensed stiffness is reported.

use contactlab::model::moving::c64;
use contactlab::model::moving::string_data::ContactModel;
use contactlab::model::moving::string_model::{
    MovingStringModel, MovingStringParams, PenaltyCondensation, StringDiscretization,
};

use super::systems::{eigen, osc};
use super::StiffPenalty;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
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
        let qz = pencil_eigen(&full).map(|r| upper_half(&r.eigenvalues)).ok();
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
    Ok(StiffPenaltyData {
        prow,
        limit_err,
        schur_slope,
    })
}
