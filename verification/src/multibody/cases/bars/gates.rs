//! The gates of a `multibody_bars` case: rate gates on the fitted rates, ceilings on the finest
//! level, contact durations within a number of steps, the finest error against the prediction
//! of the error model from the coarser levels, and the audit of every run.

use crate::core::gate::{Check, GateVerdict};
use crate::multibody::audit_state::{state_audit_checks, state_audit_gate};
use crate::multibody::cases::bars::format::{airy_width_steps, BarsCase};
use crate::multibody::cases::bars::run::{parameter, series, Outcome};
use crate::multibody::study::{audit_checks, audit_gate, Claims};

/// The error `name` of every outcome of a series.
fn errors(s: &[&Outcome], name: &str) -> Vec<f64> {
    s.iter()
        .map(|o| o.measured.error(name).unwrap_or(f64::NAN))
        .collect()
}

/// Every gate of the case.
pub fn gates(file: &BarsCase, outcomes: &[Outcome]) -> Vec<GateVerdict> {
    let mut out = Vec::new();
    for g in &file.gates {
        let sel = &g.select;
        let s = series(file, outcomes, &sel.sweep, &sel.family);
        let Some(sweep) = file.sweeps.iter().find(|x| x.name == sel.sweep) else {
            continue;
        };
        let p: Vec<f64> = s.iter().map(|o| parameter(sweep, o)).collect();
        let against = if sweep.against_k() { "k" } else { "h" };
        out.push(g.criteria.evaluate(
            format!("{}/{}: {} vs {against}", sel.sweep, sel.family, sel.error),
            &p,
            &errors(&s, &sel.error),
        ));
    }
    for c in &file.ceilings {
        let s = series(file, outcomes, &c.sweep, &c.family);
        let finest = errors(&s, &c.error).last().copied().unwrap_or(f64::NAN);
        out.push(GateVerdict::from_checks(
            format!("{}/{}: {} on the finest level", c.sweep, c.family, c.error),
            "ceiling",
            vec![Check::at_most(&c.error, finest, c.ceiling)],
            &c.note,
        ));
    }
    for w in &file.withins {
        let s = series(file, outcomes, &w.sweep, &w.family);
        let finest = errors(&s, &w.error).last().copied().unwrap_or(f64::NAN);
        out.push(GateVerdict::from_checks(
            format!("{}/{}: {} on the finest level", w.sweep, w.family, w.error),
            "reference",
            vec![Check::within(&w.error, finest, w.value, w.tolerance)],
            &w.note,
        ));
    }
    for d in &file.durations {
        let s = series(file, outcomes, &d.sweep, &d.family);
        let checks = s
            .iter()
            .map(|o| {
                let conf = &file.configurations[o.job.configuration];
                let exact = conf.exact(file.families[o.job.family].material(&file.material).young);
                let tc = exact.contact_end() - exact.contact_start();
                let measured = o.measured.end - o.measured.start;
                let h = conf.striker_length / o.level.elements as f64;
                let s_a = airy_width_steps(exact.wave_speed(), h, o.k, tc);
                Check::at_most(
                    &format!(
                        "M = {}: |T_c − {tc:.6}| / k (T_c = {measured:.6}, k = {:.3e}; ≤ {} Airy widths s_A = {s_a:.3} + 1 step)",
                        o.level.elements, o.k, d.airy_widths
                    ),
                    (measured - tc).abs() / o.k,
                    d.airy_widths * s_a + 1.0,
                )
            })
            .collect();
        out.push(GateVerdict::from_checks(
            format!("{}/{}: contact duration in steps", d.sweep, d.family),
            "reference",
            checks,
            &d.note,
        ));
    }
    for p in &file.predictions {
        let s = series(file, outcomes, &p.sweep, &p.family);
        let Some(sweep) = file.sweeps.iter().find(|x| x.name == p.sweep) else {
            continue;
        };
        let h: Vec<f64> = s.iter().map(|o| parameter(sweep, o)).collect();
        let e = errors(&s, &p.error);
        let n = e.len();
        let checks = if n < 3 || e.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
            vec![Check::holds(
                "at least 3 levels with finite positive errors",
                false,
                "a valid series",
            )]
        } else {
            let log_c = (0..n - 1)
                .map(|i| e[i].ln() - p.rate * h[i].ln())
                .sum::<f64>()
                / (n - 1) as f64;
            let predicted = (log_c + p.rate * h[n - 1].ln()).exp();
            vec![Check::at_most(
                &format!(
                    "finest {} vs {} × the prediction {predicted:e} of E = C h^{} from the coarser levels",
                    p.error, p.factor, p.rate
                ),
                e[n - 1],
                p.factor * predicted,
            )]
        };
        out.push(GateVerdict::from_checks(
            format!(
                "{}/{}: {} against the model's prediction",
                p.sweep, p.family, p.error
            ),
            "reference",
            checks,
            &p.note,
        ));
    }
    out.extend(audit_gates(file, outcomes));
    out
}

/// One audit gate per (sweep, family): every level's claimed ratios ≤ 1.
fn audit_gates(file: &BarsCase, outcomes: &[Outcome]) -> Vec<GateVerdict> {
    let mut out = Vec::new();
    for sweep in &file.sweeps {
        for fam in &sweep.families {
            let s = series(file, outcomes, &sweep.name, fam);
            let mut checks = Vec::new();
            for o in &s {
                checks.extend(audit_checks(
                    &format!("M = {}, k = {:.3e}", o.level.elements, o.k),
                    &o.summary,
                    o.claims,
                ));
            }
            let claims: Claims = s.first().map(|o| o.claims).unwrap_or_default();
            let note = audit_note(claims);
            out.push(audit_gate(
                &format!("{}/{}: audit", sweep.name, fam),
                checks,
                &note,
            ));
            let state = s
                .iter()
                .flat_map(|o| {
                    state_audit_checks(
                        &format!("M = {}, k = {:.3e}", o.level.elements, o.k),
                        &o.state,
                        o.claims,
                    )
                })
                .collect();
            out.push(state_audit_gate(
                &format!("{}/{}: state-recomputed audit", sweep.name, fam),
                state,
            ));
        }
    }
    out
}

/// What an audit gate claims and why.
fn audit_note(c: Claims) -> String {
    let mut parts = vec![
        "the bars are free (no support, no load, no foundation): P_x and P_y are conserved by \
         every scheme (the contact forces are equal and opposite)"
            .to_string(),
    ];
    if c.identity {
        parts.push(
            "the energy–momentum scheme: E_{n+1} − E_n = W_N to round-off in every step, and \
             ΔE = 0 in steps without a change of the active set"
                .into(),
        );
    }
    if c.angular {
        parts.push("an objective law with a midpoint-type scheme: J conserved".into());
    } else {
        parts.push(
            "J is not claimed (the linear law is not objective, or Newmark's forces at t_{n+1})"
                .into(),
        );
    }
    parts.join("; ")
}
