//! The impact speed over decades: the head-on bars at v (the gap 2 v t0: the same onset). The
//! linear law makes the continuous and the discrete problem linear in v (u ∝ v, λ ∝ v; the
//! gap's geometric nonlinearity is O(v/c) only through the transverse motion), so the contact
//! duration 2L/c, the rebound ∓v and the plateau stress ρ c v are the same relative to v at
//! every speed: the errors against the exact solution must agree across the decades. What this
//! catches: absolute tolerances (Newton's, the active set's, the release's) that are not scaled
//! with the motion, which would shift the release or stop Newton early at the small speeds.

use rayon::prelude::*;

use contactlab::model::multibody::constraint::Enforcement;

use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::Table;
use crate::multibody::audit_state::{state_audit_checks, state_audit_gate};
use crate::multibody::cases::bars::measure::{measure, Measured};
use crate::multibody::cases::extremes::format::{ExtremesCase, SpeedsSpec};
use crate::multibody::cases::extremes::setup::{build, RunSpec};
use crate::multibody::study::{audit_checks, audit_gate, Claims};

/// The errors compared across the speeds.
const COMPARED: [&str; 3] = [
    "final_velocity_error",
    "duration_error",
    "plateau_stress_error",
];

/// One speed's run: v, its measurements, its audit checks, its unchanged-set energy ratio and
/// its state-recomputed audit checks.
type SpeedRun = (f64, Measured, Vec<Check>, f64, Vec<Check>);

/// The study's gates and table.
pub fn study(file: &ExtremesCase, spec: &SpeedsSpec) -> Result<(Vec<GateVerdict>, Table), String> {
    let c = file.wave_speed();
    let speeds = spec.speeds.clone();
    let runs: Vec<SpeedRun> = speeds
        .par_iter()
        .map(|&v| {
            let run = RunSpec::ordinary(file, v, Enforcement::Lagrange);
            let solver = build(file, &run)?;
            let exact = file.bars.exact(file.material.young, v);
            let (recorded, measured) = measure(&solver, &exact, v, &file.material)
                .map_err(|e| format!("speed {v}: {e}"))?;
            let claims = Claims {
                unchanged: false,
                ..Claims::of(run.scheme, [true, true], false)
            };
            let audit = audit_checks(&format!("v = {v:e}"), &recorded.summary, claims);
            let state = state_audit_checks(&format!("v = {v:e}"), &recorded.state, claims);
            Ok((v, measured, audit, recorded.summary.unchanged_ratio, state))
        })
        .collect::<Result<_, String>>()?;
    let v_min = speeds.iter().copied().fold(f64::INFINITY, f64::min);
    let reference = runs
        .iter()
        .find(|r| r.0 == v_min)
        .map(|r| r.1.clone())
        .ok_or("no run at the smallest speed")?;
    let err = |m: &Measured, name: &str| m.error(name).unwrap_or(f64::NAN);
    let mut spread = Vec::new();
    let mut rebound = Vec::new();
    let mut audit = Vec::new();
    let mut state = Vec::new();
    let mut rows = Vec::new();
    for (v, m, a, unchanged, st) in &runs {
        for name in COMPARED {
            if *v == v_min {
                continue;
            }
            spread.push(Check::at_most(
                &format!("v = {v:e}: |{name}(v) − {name}(v_min)| / (v/c)"),
                (err(m, name) - err(&reference, name)).abs() / (v / c),
                spec.nonlinearity,
            ));
        }
        rebound.push(Check::at_most(
            &format!("v = {v:e}: |v_b(T)/v ∓ 1| (final_velocity_error)"),
            err(m, "final_velocity_error"),
            spec.rebound_ceiling,
        ));
        audit.extend(a.iter().cloned());
        state.extend(st.iter().cloned());
        let mut row = vec![format!("{v:e}")];
        row.extend(COMPARED.iter().map(|n| format!("{:.6e}", err(m, n))));
        row.push(format!("{:.6}", m.final_velocities[0] / v));
        row.push(format!("{unchanged:.3e}"));
        rows.push(row);
    }
    let gates = vec![
        GateVerdict::from_checks(
            format!(
                "speeds: the relative errors independent of v up to O(v/c) (v_min = {v_min:e})"
            ),
            "reference",
            spread,
            &spec.note,
        ),
        GateVerdict::from_checks(
            "speeds: the rebound ∓v at every speed".into(),
            "reference",
            rebound,
            &spec.note,
        ),
        audit_gate(
            "speeds: audit at every speed",
            audit,
            "free bars: P_x, P_y conserved and the energy–momentum identity at every speed (each \
             ratio is a drift over its round-off tolerance: scale-free). ΔE = 0 between set \
             changes is reported, not claimed, in this study: its ratio grows like 1/v (the \
             case's explanation)",
        ),
        state_audit_gate("speeds: state-recomputed audit at every speed", state),
    ];
    let mut header = vec!["v".to_string()];
    header.extend(COMPARED.iter().map(|s| s.to_string()));
    header.push("v_left(T)/v".into());
    header.push("unchanged-set energy ratio (reported)".into());
    let table = Table {
        title: "speeds over decades (Lagrange, energy–momentum; gap 2 v t0)".into(),
        header,
        rows,
    };
    Ok((gates, table))
}
