//! Undamped gyroscopic–circulatory systems are almost surely unstable: every random point is, the
//! trace identity Σ Re λ = −tr(M⁻¹C) = 0 holds to round-off, and damping can stabilize.

use contactlab::model::moving::stability::{assess, Verdict, VerdictParams};
use contactlab::model::moving::string_data::ContactModel;
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};

use super::systems::{eigen, osc};
use super::Undamped;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::stats::lcg::Lcg;

/// What the study measured: per point (v̄, p, max Re λ undamped, max Re λ damped) and the counts.
pub(super) struct UndampedData {
    pub(super) pts: Vec<(f64, f64, f64, f64)>,
    pub(super) unstable: usize,
    pub(super) stable_damped: usize,
    pub(super) worst_trace: f64,
}

/// Runs the study and pushes its gate.
pub(super) fn study(
    un: &Undamped,
    verdict: &VerdictParams,
    report: &mut CaseReport,
) -> Result<UndampedData, String> {
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
        let a = assess(&ev, verdict);
        let rho = a.spectral_scale;
        let trace: f64 = ev.iter().map(|l| l.re).sum::<f64>();
        worst_trace = worst_trace.max(trace.abs() / (ev.len() as f64 * f64::EPSILON * rho));
        if a.verdict.is_unstable() {
            unstable += 1;
        }
        min_growth = min_growth.min(a.max_real_part);
        let dd = osc(v, un.damping, ContactModel::Ideal, p / 2.0);
        let (evd, _) = eigen(&um.system(&dd).map_err(|e| e.to_string())?)?;
        let ad = assess(&evd, verdict);
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
            Check::at_most("|Σ Re λ| in units of n ε max|λ| (n eigenvalues; Σ λ = −tr(M⁻¹C) = 0)", worst_trace, un.trace_round_off),
        ],
        &format!("with ᾱ = {} the same points are stable at {stable_damped} of {}: damping, not the gyroscopic terms, can stabilize", un.damping, un.points),
    ));
    Ok(UndampedData {
        pts,
        unstable,
        stable_damped,
        worst_trace,
    })
}
