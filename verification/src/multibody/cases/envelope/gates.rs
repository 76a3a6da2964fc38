//! The gates of a `multibody_envelope` case ([`super`] states each one's reason): (a) the range's
//! outcomes, (b) the rebound's rate in h with its confidence interval and the error model's
//! ceiling, (c) E_T ≤ E_0 within the energy sum's round-off floor, (d) the momentum within its
//! round-off floor — (c) and (d) recomputed from the states ([`super::energy`]).

use crate::core::gate::{Check, GateVerdict};
use crate::multibody::cases::envelope::energy::{energy_floor, momentum_floor};
use crate::multibody::cases::envelope::format::EnvelopeCase;
use crate::multibody::cases::envelope::points::{Ending, PointRun, Source};

/// Whether a run is inside the range (a sweep marked inside, or a resolved overlapping start).
pub fn inside(file: &EnvelopeCase, r: &PointRun) -> bool {
    match r.source {
        Source::Sweep { sweep, .. } => file.sweeps[sweep].inside,
        Source::Overlap { overlap } => file.overlaps[overlap].resolve,
    }
}

/// Every gate of the case.
pub fn gates(file: &EnvelopeCase, runs: &[PointRun]) -> Vec<GateVerdict> {
    let mut out = vec![outcome_gate(file, runs)];
    out.extend(rate_gates(file, runs));
    out.push(energy_gate(file, runs));
    out.push(momentum_gate(file, runs));
    out
}

/// (a) Inside: completed (a Newmark warning inside would fail); past: one of the declared
/// outcomes; a refused overlap: its message names what it must.
fn outcome_gate(file: &EnvelopeCase, runs: &[PointRun]) -> GateVerdict {
    let checks = runs
        .iter()
        .map(|r| {
            let got = r.outcomes();
            let shown = match &r.ending {
                Ending::Failed { message, .. } => format!("{}: {message}", got.join(", ")),
                Ending::Completed => got.join(", "),
            };
            let (passed, limit) = match r.source {
                Source::Sweep { sweep, .. } if file.sweeps[sweep].inside => (
                    got == ["completed"] || got == ["completed", "audit_flag"],
                    "completed".to_string(),
                ),
                Source::Sweep { sweep, .. } => {
                    let expect = &file.sweeps[sweep].expect;
                    let ok = got.iter().any(|g| expect.contains(g));
                    (ok, format!("one of {}", expect.join(", ")))
                }
                Source::Overlap { overlap } => {
                    let o = &file.overlaps[overlap];
                    if o.resolve {
                        (got == ["completed"], "completed".to_string())
                    } else {
                        let named = match &r.ending {
                            Ending::Failed { kind, message } => {
                                kind == "overlap_error"
                                    && o.expect.iter().all(|t| message.contains(t.as_str()))
                            }
                            Ending::Completed => false,
                        };
                        (
                            named,
                            format!("overlap_error naming {}", o.expect.join(", ")),
                        )
                    }
                }
            };
            Check::holds(&format!("{} → {shown}", r.label), passed, &limit)
        })
        .collect();
    GateVerdict::from_checks(
        "(a) every point inside the range completes; every point past it ends as the docs state"
            .into(),
        "range",
        checks,
        "a point past the range must end with the typed error or the warning docs/multibody.md §13 \
         names for it — never a quiet answer",
    )
}

/// (b) The rebound's error against h at each speed of a `[[rate]]`'s sweep.
fn rate_gates(file: &EnvelopeCase, runs: &[PointRun]) -> Vec<GateVerdict> {
    let mut out = Vec::new();
    for rate in &file.rates {
        let Some(s) = file.sweeps.iter().position(|x| x.name == rate.select.sweep) else {
            continue;
        };
        for &speed in &file.sweeps[s].speeds {
            let (mut h, mut e) = (Vec::new(), Vec::new());
            for r in runs {
                if let Source::Sweep {
                    sweep,
                    speed: v,
                    elements,
                    ..
                } = r.source
                {
                    if sweep == s && v == speed {
                        h.push(file.bars.h(elements));
                        e.push(r.rebound_error().unwrap_or(f64::NAN));
                    }
                }
            }
            out.push(rate.criteria.evaluate(
                format!(
                    "(b) {}: v/c = {speed}: rebound error |v(T) ∓ v|/v vs h",
                    rate.select.sweep
                ),
                &h,
                &e,
            ));
        }
    }
    out
}

/// (c) E_T − E_0 ≤ the round-off floor of the energy sums, for every completed point inside.
fn energy_gate(file: &EnvelopeCase, runs: &[PointRun]) -> GateVerdict {
    let checks = runs
        .iter()
        .filter(|r| inside(file, r))
        .map(|r| match (&r.start, &r.end) {
            (Some(a), Some(b)) => Check::at_most(
                &format!("{}: E_T − E_0 (recomputed)", r.label),
                b.energy - a.energy,
                energy_floor(file.energy_round_off, a, b, r.steps),
            ),
            _ => Check::holds(&format!("{}: E_T", r.label), false, "a final state"),
        })
        .collect();
    GateVerdict::from_checks(
        "(c) E(T) ≤ E_0 within the energy sum's round-off (recomputed from the states)".into(),
        "conservation",
        checks,
        "the energy–momentum step changes the energy only by the activation work −λ g₀ ≤ 0 of a \
         constraint closing a gap from outside (EM §6.2): nothing may add energy",
    )
}

/// (d) |P_T − P_0| ≤ the round-off floor of the momentum sums, for every completed point.
fn momentum_gate(file: &EnvelopeCase, runs: &[PointRun]) -> GateVerdict {
    let checks = runs
        .iter()
        .filter_map(|r| {
            let (a, b) = (r.start.as_ref()?, r.end.as_ref()?);
            let dp = (b.momentum[0] - a.momentum[0])
                .abs()
                .max((b.momentum[1] - a.momentum[1]).abs());
            Some(Check::at_most(
                &format!("{}: |P_T − P_0| (recomputed)", r.label),
                dp,
                momentum_floor(file.momentum_round_off, a, b, r.steps),
            ))
        })
        .collect();
    GateVerdict::from_checks(
        "(d) the linear momentum conserved to round-off (recomputed from the states)".into(),
        "conservation",
        checks,
        "the bars are free: the contact forces are equal and opposite and a free body's internal \
         forces sum to zero, for every scheme (Newmark included)",
    )
}
