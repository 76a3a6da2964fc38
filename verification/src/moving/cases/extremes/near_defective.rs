//! Near-defective eigenvalues at a flutter onset (a Jordan block): no false verdicts on either
//! side, spurious real parts below the verdict tolerance, growth ∝ (p − p*)^{1/2} above.

use contactlab::model::moving::stability::{assess, Verdict, VerdictParams};
use contactlab::model::moving::string_data::ContactModel;
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};

use super::systems::{eigen, osc, ziegler, ziegler_exact};
use super::NearDefective;
use crate::core::gate::{Check, GateVerdict, RateGate};
use crate::core::report::case_report::CaseReport;
use crate::moving::study::SeriesSelect;

/// What the study measured: the 2-dof rows (signed distance, exact, computed, verdict, τ), the
/// string rows and onset, the largest spurious real parts and τ at the 2-dof onset.
pub(super) struct NearDefectiveData {
    pub(super) zrows: Vec<(f64, f64, f64, &'static str, f64)>,
    pub(super) srows: Vec<(f64, f64, &'static str, f64)>,
    pub(super) sp_star: f64,
    pub(super) max_spurious: f64,
    pub(super) string_spurious: f64,
    pub(super) tol_z: f64,
}

/// Runs the study and pushes its gates.
pub(super) fn study(
    nd: &NearDefective,
    onset_gate: &RateGate<SeriesSelect>,
    verdict: &VerdictParams,
    report: &mut CaseReport,
) -> Result<NearDefectiveData, String> {
    let p_star = 1.5;
    let mut zrows = Vec::new();
    let mut false_verdicts = 0;
    let mut max_spurious: f64 = 0.0;
    let mut above = Vec::new();
    for &d in &nd.distances {
        for side in [-1.0, 1.0] {
            let p = p_star * (1.0 + side * d);
            let (ev, _) = eigen(&ziegler(p))?;
            let a = assess(&ev, verdict);
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
        let a = assess(&ev, verdict);
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
    let tol_z = assess(&eigen(&ziegler(p_star))?.0, verdict).tolerance;
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
    report.gates.push(onset_gate.criteria.evaluate(
        "growth above a Jordan-block flutter onset ∝ (p − p*)^{1/2} (2-dof, computed)".into(),
        &above.iter().map(|x| x.0).collect::<Vec<_>>(),
        &above.iter().map(|x| x.1).collect::<Vec<_>>(),
    ));
    Ok(NearDefectiveData {
        zrows,
        srows,
        sp_star,
        max_spurious,
        string_spurious,
        tol_z,
    })
}
