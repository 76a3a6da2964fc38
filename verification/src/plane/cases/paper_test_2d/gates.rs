//! The gates of `plane_paper_test_2d`: the rollers reading's missing equilibrium as a typed error
//! and the steps skipped for it, the rigid sinking against its closed form, and the mesh
//! convergence of each gated quantity by Roache's grid convergence index
//! ([`crate::stats::gci`]). None of them compares with the paper: the paper's numbers are set
//! beside ours in the report, not gated.

use contactlab::error::{Error as LabError, SolveError};
use contactlab::model::quasistatic::plane::Support;

use super::format::{Expect, GciGateSpec, PaperTestSpec, Reading};
use super::runs::PaperTestRun;
use crate::core::gate::{Check, GateVerdict};
use crate::plane::scene::{variant, Variant};
use crate::stats::gci::{analyse, Convergence, GciResult};

/// The plain rollers scheme (no start at the first equilibrium) must stop at step 1 with the
/// missing equilibrium named.
pub fn plain_rollers_stop(
    scene: &toml::Table,
    spec: &PaperTestSpec,
) -> Result<GateVerdict, String> {
    let scene = variant(
        scene,
        Variant {
            support: Some(Support::FixX),
            start_at_first_equilibrium: Some(false),
            divisions: Some(spec.meshes[0]),
            beta: Some(spec.von_mises_beta),
            ..Default::default()
        },
    )?;
    let outcome = scene.solve();
    let (ok, text) = match &outcome {
        Err(e @ LabError::Solve(SolveError::NoEquilibrium { step, reason, .. })) => {
            (*step == 1 && reason.contains("12.0"), e.to_string())
        }
        Err(e) => (false, e.to_string()),
        Ok(_) => (false, "ran without error".to_string()),
    };
    Ok(GateVerdict::from_checks(
        "rollers, plain scheme: stops at step 1 with the missing equilibrium named".into(),
        "paper_test",
        vec![Check::holds(
            &format!("error: {text}"),
            ok,
            "SolveError::NoEquilibrium at step 1 naming the 12 N bound",
        )],
        "no NaN, no 1e12-sized update: a typed error with step, time and why",
    ))
}

/// Every rollers run skips exactly the steps whose load 180 t_n is below p0 |Γ3| = 12 N (k from
/// the scene), and no clamped run skips a step.
pub fn skipped_steps(runs: &[PaperTestRun], k: f64, steps: usize) -> GateVerdict {
    let expected: Vec<usize> = (1..=steps)
        .filter(|&n| 180.0 * n as f64 * k < 12.0)
        .collect();
    let rollers_ok = runs
        .iter()
        .filter(|r| r.reading == Reading::Rollers)
        .all(|r| r.skipped_steps == expected);
    let clamped_ok = runs
        .iter()
        .filter(|r| r.reading == Reading::Clamped)
        .all(|r| r.skipped_steps.is_empty());
    GateVerdict::from_checks(
        "rollers variant starts at the first step with an equilibrium".into(),
        "paper_test",
        vec![
            Check::holds(
                &format!("every rollers run skips exactly steps {expected:?} (180 t_n < 12 N)"),
                rollers_ok,
                "the steps without equilibrium, and no others",
            ),
            Check::holds(
                "no clamped run skips a step",
                clamped_ok,
                "clamped is well posed",
            ),
        ],
        "",
    )
}

/// The mean sinking of Γ3 of every rollers run against its closed form (runs::module docs), to
/// `factor` · ε · N relative (the round-off of N accumulated steps).
pub fn rigid_sinking(runs: &[PaperTestRun], steps: usize, factor: f64) -> GateVerdict {
    let limit = factor * f64::EPSILON * steps as f64;
    let mut checks = Vec::new();
    for r in runs.iter().filter(|r| r.reading == Reading::Rollers) {
        let name = format!(
            "rollers {0}×{0}, β = {1}: mean u_y on Γ3 {2:.10} vs the closed form",
            r.divisions, r.beta, r.contact_line_mean
        );
        match r.sinking_closed_form {
            Some(c) => checks.push(Check::at_most(
                &format!(
                    "{name} {c:.10} (receding share {:.2e}): relative difference",
                    r.receding_share
                ),
                ((r.contact_line_mean - c) / c).abs(),
                limit,
            )),
            None => checks.push(Check::holds(
                &format!("{name}: a closed form"),
                false,
                "law (2.8) with constant p0 and no body force",
            )),
        }
    }
    GateVerdict::from_checks(
        "rollers: the mean sinking of Γ3 equals its closed form −(1/L) Σ_n k [(R(τ_n) − p0 L)/β − S_n]".into(),
        "paper_test",
        checks,
        "the vertical translation is in V^h: the pressures carry the whole load in every step",
    )
}

/// The values of `q` for one reading and β on the meshes, coarsest first.
pub fn series(
    runs: &[PaperTestRun],
    meshes: &[usize],
    reading: Reading,
    beta: f64,
    q: super::format::Quantity,
) -> Vec<f64> {
    meshes
        .iter()
        .filter_map(|&n| {
            runs.iter()
                .find(|r| r.reading == reading && r.divisions == n && r.beta == beta)
                .map(|r| r.value(q))
        })
        .collect()
}

/// The GCI analysis of a series (with the formal order `formal`).
pub fn gci_of(values: &[f64], ratio: f64, formal: f64) -> Result<GciResult, String> {
    analyse(values, ratio, formal).map_err(|e| e.to_string())
}

/// One `[[paper_test.gci]]` gate.
pub fn gci_gate(g: &GciGateSpec, values: &[f64], ratio: f64) -> GateVerdict {
    let name = format!(
        "{}, β = {}: {} under mesh refinement ({:?})",
        g.reading.name(),
        g.beta,
        g.quantity.name(),
        g.expect
    );
    let q = g.quantity.name();
    let mut checks = Vec::new();
    match gci_of(values, ratio, g.formal_order) {
        Err(e) => checks.push(Check::holds(
            &format!("{q}: {e}"),
            false,
            "an analysable sequence",
        )),
        Ok(r) => {
            let order = r.order.map_or("—".into(), |p| format!("{p:.3}"));
            match g.expect {
                Expect::Diverges => {
                    let n = values.len();
                    let (d1, d2) = (values[n - 1] - values[n - 2], values[n - 2] - values[n - 3]);
                    checks.push(Check::at_least(
                        &format!(
                            "{q}: |f1 − f2| / |f2 − f3| on the finest three levels ({values:.4?})"
                        ),
                        (d1 / d2).abs(),
                        1.0,
                    ));
                }
                Expect::Converges => {
                    checks.push(Check::holds(
                        &format!(
                            "{q}: {:?}, observed order p = {order} (formal {})",
                            r.convergence, g.formal_order
                        ),
                        r.order_verified
                            && matches!(
                                r.convergence,
                                Convergence::Monotone | Convergence::Oscillatory
                            ),
                        &format!(
                            "monotone or oscillatory with p in [{}, {}]",
                            0.5 * g.formal_order,
                            2.0 * g.formal_order
                        ),
                    ));
                    push_gci_bound(&mut checks, g, &r);
                    if let Some(tol) = g.asymptotic_tolerance {
                        checks.push(Check::within(
                            &format!(
                                "{q}: asymptotic ratio A = GCI_coarse/(r^p_c GCI_fine), p = {order}, p_c = {}",
                                r.coarse_order.map_or("—".into(), |p| format!("{p:.3}"))
                            ),
                            r.asymptotic_ratio.unwrap_or(f64::INFINITY),
                            1.0,
                            tol,
                        ));
                    }
                }
                Expect::ConvergesUnverified => {
                    checks.push(Check::holds(
                        &format!(
                            "{q}: {:?} (observed p = {order}; the GCI uses the formal order {} with F_s = {})",
                            r.convergence, r.order_used, r.safety_factor
                        ),
                        !matches!(r.convergence, Convergence::Divergent),
                        "the differences shrink",
                    ));
                    push_gci_bound(&mut checks, g, &r);
                }
            }
        }
    }
    GateVerdict::from_checks(name, "gci", checks, &g.note)
}

fn push_gci_bound(checks: &mut Vec<Check>, g: &GciGateSpec, r: &GciResult) {
    checks.push(Check::at_most(
        &format!(
            "{}: GCI_fine (%) with p = {:.3}, F_s = {}",
            g.quantity.name(),
            r.order_used,
            r.safety_factor
        ),
        r.gci_fine_percent.unwrap_or(f64::INFINITY),
        g.max_percent.unwrap_or(0.0),
    ));
}
