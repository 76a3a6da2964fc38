//! Penalty → ∞ against the multipliers: the head-on bars with the penalty P = (ε/2)(g₋)² per
//! slave node, ε = f · E (H/rows)/h, against the Lagrange run of the same mesh, step and scheme.
//!
//! **Rate.** At a fixed mesh and step the discrete penalty problem is a regular perturbation of
//! the multipliers' one: each step solves R(u) − Gᵀλ = 0 with λ = ε (−g)⁺ instead of g = 0 on
//! the active set, i.e. the constraint row g + λ/ε = 0: a perturbation of size ‖λ‖/ε of a
//! nonsingular saddle point system, so every step's state differs by O(1/ε) and so does the
//! rebound v(T) (as long as the active sets agree: the gate's level rule leaves out a
//! pre-asymptotic coarse ε). Expected rate 1 in 1/ε.
//!
//! **The penetration is the force over ε.** On the plateau of the contact the exact interface
//! force is A σ_c = A ρ c v (A = H per unit thickness, `exact::bar_impact`); the penalty carries
//! it as Σ_i ε (−g_i)⁺, so ε ⟨Σ (−g)⁺⟩ / (A σ_c) → 1 with the bars' plateau error (≤ 1e-4,
//! `multibody_bars`) plus the O(1/ε) delay of the spring, both independent of how the solver
//! computes the force (λ is not reported for the penalty: the gate reads the gaps).

use rayon::prelude::*;

use contactlab::model::multibody::constraint::Enforcement;

use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::Table;
use crate::exact::bar_impact::TwoBarImpact;
use crate::multibody::cases::extremes::format::{ExtremesCase, PenaltySpec};
use crate::multibody::cases::extremes::observe::{observe, Observed};
use crate::multibody::cases::extremes::setup::{build, RunSpec};
use crate::multibody::study::{audit_checks, audit_gate, Claims};

/// ε of the factor `f`: f · E (H/rows)/h.
pub fn stiffness(file: &ExtremesCase, f: f64) -> f64 {
    let b = &file.bars;
    f * file.material.young * (b.height / b.rows as f64) / b.h()
}

/// The study's gates and table.
pub fn study(file: &ExtremesCase, spec: &PenaltySpec) -> Result<(Vec<GateVerdict>, Table), String> {
    let v = file.bars.speed;
    let mut laws = vec![Enforcement::Lagrange];
    laws.extend(spec.factors.iter().map(|&f| Enforcement::Penalty {
        stiffness: stiffness(file, f),
    }));
    let outcomes: Vec<(RunSpec, Result<Observed, String>)> = laws
        .par_iter()
        .map(|&law| {
            let run = RunSpec {
                scheme: spec.scheme,
                ..RunSpec::ordinary(file, v, law)
            };
            (run, build(file, &run).and_then(|s| observe(&s)))
        })
        .collect();
    let mut runs = Vec::new();
    let mut failures = Vec::new();
    for (i, (run, outcome)) in outcomes.into_iter().enumerate() {
        match outcome {
            Ok(o) => runs.push((run, o)),
            Err(e) if i == 0 => return Err(format!("penalty study, the Lagrange run: {e}")),
            Err(e) => failures.push(Check::holds(
                &format!("f = {:e}: the run ends ({e})", spec.factors[i - 1]),
                false,
                "completes",
            )),
        }
    }
    if !failures.is_empty() {
        return Ok((
            vec![GateVerdict::from_checks(
                "penalty: every run ends".into(),
                "structure",
                failures,
                &spec.force_note,
            )],
            Table {
                title: "penalty".into(),
                header: vec![],
                rows: vec![],
            },
        ));
    }
    let exact = file.bars.exact(file.material.young, v);
    let force = exact.area() * exact.contact_stress();
    let (t0, t1) = (exact.contact_start(), exact.contact_end());
    let (a, b) = (t0 + 0.25 * (t1 - t0), t0 + 0.75 * (t1 - t0));
    let reference = runs[0].1.final_velocities();
    let mut inverse = Vec::new();
    let mut differences = Vec::new();
    let mut force_checks = Vec::new();
    let mut audit = audit_checks(
        "Lagrange",
        &runs[0].1.summary,
        Claims::of(runs[0].0.scheme, [true, true], false),
    );
    let mut rows = Vec::new();
    for (&f, (run, o)) in spec.factors.iter().zip(&runs[1..]) {
        let eps = stiffness(file, f);
        let vt = o.final_velocities();
        let diff = (0..2)
            .map(|i| (vt[i] - reference[i]).abs() / v)
            .fold(0.0, f64::max);
        let ratio = eps * o.mean_penetration(run.step, a, b) / force;
        inverse.push(1.0 / f);
        differences.push(diff);
        force_checks.push(Check::within(
            &format!("f = {f:e}: ε ⟨Σ (−g)⁺⟩ / (A σ_c)"),
            ratio,
            1.0,
            spec.force_tolerance,
        ));
        audit.extend(audit_checks(
            &format!("f = {f:e}"),
            &o.summary,
            Claims::of(run.scheme, [true, true], false),
        ));
        rows.push(vec![
            format!("{f:e}"),
            format!("{eps:.4e}"),
            format!("{:.6}", vt[0] / v),
            format!("{diff:.4e}"),
            format!("{:.6}", ratio),
            format!("{:.4e}", o.max_penetration()),
            format!("{:.4e}", o.max_penetration() * eps / force),
            format!("{}", o.solution.stats.newton_iterations),
        ]);
    }
    rows.insert(
        0,
        vec![
            "Lagrange".into(),
            "∞".into(),
            format!("{:.6}", reference[0] / v),
            "0".into(),
            "—".into(),
            format!("{:.4e}", runs[0].1.max_penetration()),
            "—".into(),
            format!("{}", runs[0].1.solution.stats.newton_iterations),
        ],
    );
    let gates = vec![
        spec.rate.evaluate(
            "penalty → ∞: |v_ε(T) − v_λ(T)| / v against 1/ε".into(),
            &inverse,
            &differences,
        ),
        GateVerdict::from_checks(
            "penalty: the penetration carries the exact force, ε ⟨Σ (−g)⁺⟩ = A ρ c v".into(),
            "reference",
            force_checks,
            &spec.force_note,
        ),
        audit_gate(
            "penalty and Lagrange runs: audit",
            audit,
            "free bars: P_x, P_y conserved; energy–momentum: the energy identity (with the \
             penalty energy in E) and ΔE = 0 between set changes; J not claimed (linear law)",
        ),
    ];
    let table = Table {
        title: format!(
            "penalty → ∞ (ε = f · E (H/rows)/h; v = {v}, A σ_c = {force:.6}; plateau [{a:.4}, {b:.4}])"
        ),
        header: [
            "f",
            "ε",
            "v_left(T)/v",
            "|v_ε − v_λ|/v at T",
            "ε ⟨Σ(−g)⁺⟩/(Aσ_c)",
            "max penetration",
            "ε · max penetration / (Aσ_c)",
            "Newton iterations",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    };
    Ok((gates, table))
}
