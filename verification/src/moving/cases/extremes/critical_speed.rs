//! v̄ → 1: the ratio ω₁/(π(1 − v̄²)) converges linearly in δ = 1 − v̄ until the round-off of the
//! vanishing frequency (ε/δ) takes over; the rate gate and the conditioning gate.

use contactlab::model::moving::string_data::MovingStringData;
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};

use super::systems::eigen;
use super::CriticalSpeed;
use crate::core::gate::{Check, GateVerdict, RateGate};
use crate::core::report::case_report::CaseReport;
use crate::moving::errors::lowest_oscillating;
use crate::moving::study::SeriesSelect;

/// What the study measured: (δ, ω₁/(π(1 − v̄²)), companion norm) and the successive differences.
pub(super) struct CriticalSpeedData {
    pub(super) rows: Vec<(f64, f64, f64)>,
    pub(super) diffs: Vec<(f64, f64)>,
    /// The slope C of the discretization part, from the last resolved difference.
    pub(super) c_fit: f64,
}

/// Runs the study and pushes its gates.
pub(super) fn study(
    cs: &CriticalSpeed,
    gate: &RateGate<SeriesSelect>,
    report: &mut CaseReport,
) -> Result<CriticalSpeedData, String> {
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
        let w1 = lowest_oscillating(&ev, 1, &format!("v̄ = 1 − {d}"))?[0].im;
        rows.push((d, w1 / (std::f64::consts::PI * (1.0 - v * v)), norm));
    }
    // r(δ) = r0 + C δ + O(δ²) with δ = 10⁻ᵏ: successive differences 0.9 C δ, rate 1, until the
    // round-off of the small eigenvalue ω₁ ≈ 2πδ — relative error ~ ε/δ — takes over.
    let diffs: Vec<(f64, f64)> = rows
        .windows(2)
        .map(|w| (w[0].0, (w[0].1 - w[1].1).abs()))
        .collect();
    let resolved: Vec<&(f64, f64)> = diffs.iter().filter(|x| x.0 >= cs.round_off_below).collect();
    report.gates.push(gate.criteria.evaluate(
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
    Ok(CriticalSpeedData {
        c_fit: resolved.last().map_or(1.0, |x| x.1 / x.0),
        rows,
        diffs,
    })
}
