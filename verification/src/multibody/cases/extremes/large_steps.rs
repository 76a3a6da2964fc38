//! Steps of several contact durations: the head-on bars at k = m · 2L/c. A step longer than the
//! contact cannot resolve the waves, so no accuracy is claimed; what must survive is structure.
//! The energy–momentum scheme: P_x, P_y conserved to round-off (the contact forces are equal
//! and opposite at every k), the energy never above E_0 (conserved between set changes, and the
//! activation work −λ g₀ of a constraint closing a gap within a step is ≤ 0: EM §6.2), no
//! penetration beyond the Newton tolerance (the multipliers enforce g ≥ 0 at t_{n+1}), and the
//! run ends (or stops with a typed error, never a NaN). The midpoint rule is reported for
//! contrast (no gate: its energy is not controlled at a change of the active set).

use rayon::prelude::*;

use contactlab::model::multibody::constraint::Enforcement;
use contactlab::model::multibody::scheme::MultibodyScheme;

use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::Table;
use crate::multibody::audit_state::{state_audit_checks, state_audit_gate};
use crate::multibody::cases::extremes::format::{ExtremesCase, LargeStepsSpec};
use crate::multibody::cases::extremes::observe::{observe, Observed};
use crate::multibody::cases::extremes::setup::{build, RunSpec};
use crate::multibody::study::{audit_checks, audit_gate, Claims};

/// The study's gates and table.
pub fn study(
    file: &ExtremesCase,
    spec: &LargeStepsSpec,
) -> Result<(Vec<GateVerdict>, Table), String> {
    let v = file.bars.speed;
    let duration = 2.0 * file.bars.length / file.wave_speed();
    let mut jobs = Vec::new();
    for &m in &spec.multiples {
        for scheme in [MultibodyScheme::EnergyMomentum, MultibodyScheme::Midpoint] {
            let step = m * duration;
            let steps = ((file.bars.final_time / step - 1e-9).ceil() as usize).max(spec.min_steps);
            jobs.push((
                m,
                RunSpec {
                    speed: v,
                    enforcement: Enforcement::Lagrange,
                    scheme,
                    step,
                    steps,
                },
            ));
        }
    }
    let runs: Vec<(f64, RunSpec, Result<Observed, String>)> = jobs
        .par_iter()
        .map(|&(m, run)| {
            (
                m,
                run,
                build(file, &run).and_then(|s| observe(&s, &file.material)),
            )
        })
        .collect();
    let mut structure = Vec::new();
    let mut audit = Vec::new();
    let mut state = Vec::new();
    let mut rows = Vec::new();
    for (m, run, outcome) in &runs {
        let em = run.scheme == MultibodyScheme::EnergyMomentum;
        let label = format!("k = {m} · 2L/c, {:?}", run.scheme);
        let o = match outcome {
            Ok(o) => o,
            Err(e) => {
                if em {
                    structure.push(Check::holds(
                        &format!("{label}: the run ends ({e})"),
                        false,
                        "completes",
                    ));
                }
                rows.push(vec![format!("{m}"), format!("{:?}", run.scheme), e.clone()]);
                continue;
            }
        };
        let records = &o.solution.records;
        let e0 = records.first().map_or(f64::NAN, |r| r.energy);
        let rise = records
            .iter()
            .map(|r| (r.energy - e0) / e0)
            .fold(f64::NEG_INFINITY, f64::max);
        let e_end = records.last().map_or(f64::NAN, |r| r.energy) / e0;
        let finite = records.iter().all(|r| r.first_non_finite().is_none());
        let penetration = o.max_penetration() / (v * run.step);
        let vt = o.final_velocities();
        if em {
            structure.push(Check::holds(
                &format!("{label}: the run ends with finite records"),
                finite,
                "finite",
            ));
            structure.push(Check::at_most(
                &format!("{label}: max_n (E_n − E_0)/E_0"),
                rise,
                spec.energy_rise,
            ));
            structure.push(Check::at_most(
                &format!("{label}: max_n max(−g, 0) / (v k)"),
                penetration,
                spec.penetration,
            ));
            let claims = Claims::of(run.scheme, [true, true], false);
            audit.extend(audit_checks(&label, &o.summary, claims));
            state.extend(state_audit_checks(&label, &o.state, claims));
        }
        rows.push(vec![
            format!("{m}"),
            format!("{:?}", run.scheme),
            format!("k = {:.4}, {} steps", run.step, run.steps),
            format!("{rise:.3e}"),
            format!("{e_end:.6}"),
            format!("{penetration:.3e}"),
            format!("({:.5}, {:.5})", vt[0] / v, vt[1] / v),
            format!(
                "{:.2e} / {:.2e}",
                o.summary.momentum_ratio_x, o.summary.momentum_ratio_y
            ),
            format!("{}", o.solution.stats.newton_iterations),
        ]);
    }
    let gates = vec![
        GateVerdict::from_checks(
            "large steps (energy–momentum): finite, no energy gain, no penetration".into(),
            "structure",
            structure,
            &spec.note,
        ),
        audit_gate(
            "large steps (energy–momentum): audit",
            audit,
            "free bars: P_x, P_y conserved at every k; the energy identity and ΔE = 0 between \
             set changes hold whatever the step",
        ),
        state_audit_gate(
            "large steps (energy–momentum): state-recomputed audit",
            state,
        ),
    ];
    let table = Table {
        title: "steps of several contact durations 2L/c (midpoint: reported only)".into(),
        header: [
            "k / (2L/c)",
            "scheme",
            "step",
            "max (E_n − E_0)/E_0",
            "E(T)/E_0",
            "max penetration / (v k)",
            "v(T)/v (left, right)",
            "P_x / P_y ratios",
            "Newton iterations",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    };
    Ok((gates, table))
}
