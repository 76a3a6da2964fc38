//! The gate and the tables of a self-convergence study of `dynamic_impact`: the grid
//! convergence index of the finest pair and the asymptotic ratio, per quantity.

use super::runs::{RunOutput, RunSummary};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::Table;
use crate::dynamic::cases::impact::format::{GciGate, Quantity};
use crate::stats::gci::GciResult;

/// The gate of one GCI quantity.
pub(crate) fn gci_gate(
    study: &str,
    gate: &GciGate,
    res: &Result<GciResult, String>,
) -> GateVerdict {
    let q = gate.quantity.name();
    let mut checks = Vec::new();
    match res {
        Err(e) => checks.push(Check::holds(
            &format!("{q}: {e}"),
            false,
            "an analysable sequence",
        )),
        Ok(r) => {
            let how = if r.order_verified {
                format!("observed p = {:.3}, F_s = 1.25", r.order_used)
            } else {
                format!(
                    "{:?}, observed p = {}: not verified, formal p = {} with F_s = 3",
                    r.convergence,
                    r.order.map_or("—".into(), |p| format!("{p:.3}")),
                    r.order_used
                )
            };
            checks.push(Check::at_most(
                &format!("{q}: GCI_fine (%), {how}"),
                r.gci_fine_percent.unwrap_or(f64::INFINITY),
                gate.max_percent,
            ));
            if let Some(tol) = gate.asymptotic_tolerance {
                checks.push(Check::within(
                    &format!(
                        "{q}: asymptotic ratio A = GCI_coarse/(r^p_c GCI_fine), p = {}, p_c = {}",
                        r.order.map_or("—".into(), |p| format!("{p:.3}")),
                        r.coarse_order.map_or("—".into(), |p| format!("{p:.3}"))
                    ),
                    r.asymptotic_ratio.unwrap_or(f64::INFINITY),
                    1.0,
                    tol,
                ));
            }
        }
    }
    GateVerdict::from_checks(format!("{study}: {q}"), "gci", checks, &gate.note)
}

pub(crate) fn levels_table(
    name: &str,
    factors: &[f64],
    outs: &[&RunOutput],
    s: &[RunSummary],
) -> Table {
    Table {
        title: format!("{name}: levels (mesh and step refined together)"),
        header: [
            "refinement",
            "dofs",
            "steps",
            "rebound (m/s)",
            "contact duration (s)",
            "max p (m)",
            "energy loss / E_0",
            "Newton its/step (max)",
            "loop (s)",
        ]
        .iter()
        .map(|h| h.to_string())
        .collect(),
        rows: outs
            .iter()
            .zip(s)
            .zip(factors)
            .map(|((o, s), f)| {
                vec![
                    format!("{f}"),
                    o.stats.unknowns.to_string(),
                    o.steps.to_string(),
                    format!("({:.5}, {:.5})", s.final_velocity[0], s.final_velocity[1]),
                    s.contact_duration.map_or("—".into(), |d| format!("{d:.6}")),
                    format!("{:.5e}", s.max_penetration),
                    format!("{:.4e}", -s.energy_change),
                    format!(
                        "{:.2} ({})",
                        o.stats.newton_iterations as f64 / o.steps.max(1) as f64,
                        o.stats.max_newton_iterations
                    ),
                    format!("{:.2}", o.stats.loop_seconds),
                ]
            })
            .collect(),
    }
}

pub(crate) fn gci_table(
    name: &str,
    ratio: f64,
    analysed: &[(Quantity, Result<GciResult, String>, Vec<f64>)],
) -> Table {
    let opt = |v: Option<f64>, digits: usize| v.map_or("—".into(), |v| format!("{v:.digits$}"));
    Table {
        title: format!(
            "{name}: observed order (finest three levels; coarser three: p_c), Richardson \
             extrapolation, GCI (r = {ratio}; F_s = 1.25 with the observed p when it is within \
             [p_f/2, 2 p_f], else F_s = 3 with the formal p_f: the gate's, or 1), asymptotic ratio \
             A = (f1/f2) r^(p − p_c)"
        ),
        header: [
            "quantity",
            "finest value",
            "convergence",
            "p",
            "p_c",
            "p, F_s used",
            "extrapolated",
            "GCI_fine (%)",
            "GCI_coarse (%)",
            "A",
        ]
        .iter()
        .map(|h| h.to_string())
        .collect(),
        rows: analysed
            .iter()
            .map(|(q, r, v)| match r {
                Err(e) => vec![q.name().into(), format!("{:?}", v.last()), e.clone()],
                Ok(r) => vec![
                    q.name().into(),
                    format!("{:.6e}", v.last().copied().unwrap_or(f64::NAN)),
                    format!("{:?}", r.convergence),
                    opt(r.order, 3),
                    opt(r.coarse_order, 3),
                    format!("{:.3}, {}", r.order_used, r.safety_factor),
                    opt(r.extrapolated, 6),
                    opt(r.gci_fine_percent, 4),
                    opt(r.gci_coarse_percent, 4),
                    opt(r.asymptotic_ratio, 4),
                ],
            })
            .collect(),
    }
}
