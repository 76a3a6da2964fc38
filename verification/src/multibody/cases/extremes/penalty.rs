//! Penalty → ∞ against the multipliers: the head-on bars with a stiffness ε = f · E (H/rows)/h
//! per slave node, against the Lagrange run of the same mesh, step and scheme, in the two
//! penalty forms the solver offers (docs/multibody.md §3.1).
//!
//! **The compliant multiplier** (`Enforcement::Compliant`): λ_N = ε (−g₁)⁺ at t_(n+1), solved
//! like the multipliers with the row c (g₁ + λ_N/ε). Each step solves R(u) − Gᵀλ = 0 with
//! g + λ/ε = 0 on the active set instead of g = 0: a perturbation of size ‖λ‖/ε of a nonsingular
//! saddle-point system, so every step's state differs by O(1/ε) and so does the rebound v(T)
//! (as long as the active sets agree: the gate's level rule leaves out a pre-asymptotic coarse
//! ε). Expected rate 1 in 1/ε. On the plateau of the contact the exact interface force is
//! A σ_c = A ρ c v (A = H per unit thickness, `exact::bar_impact`); the compliant multiplier
//! carries it as Σ_i ε (−g_i)⁺, so ε ⟨Σ (−g)⁺⟩ / (A σ_c) → 1 with the bars' plateau error
//! (≤ 1e-4, `multibody_bars`) plus the O(1/ε) delay of the spring, read from the gaps, not from
//! the solver's multipliers.
//!
//! **The conserving penalty** (`Enforcement::Penalty`, P = (ε/2)(g₋)², the secant force
//! s(g₀, g₁) ∇̄g of the energy–momentum scheme): the discrete energy E = K + U + P is conserved
//! exactly in every step — there is no activation loss — so E_n = E_0 = ρ L H v² (both bars'
//! kinetic energy, computed here from the setup) to round-off, the gate. It does *not* tend to
//! the multipliers' run at a fixed step: the penalty adds a contact mode of frequency
//! ω = √(ε/m) (m the contact node's mass), and once ω k ≫ 1 the scheme (an A-stable,
//! non-dissipative rule) keeps the energy put into that mode at the first contact as an
//! unresolved oscillation of the contact nodes, while the multipliers dissipate it (the
//! activation work −λ g₀, EM §6.2). The table reports |v_ε − v_λ| and the penetration, which
//! scales like v √(m/ε) (the node's kinetic energy stored in the spring), not like λ/ε.

use rayon::prelude::*;

use contactlab::model::multibody::constraint::Enforcement;
use contactlab::model::multibody::scheme::MultibodyScheme;

use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::Table;
use crate::exact::bar_impact::TwoBarImpact;
use crate::multibody::audit_state::{state_audit_checks, state_audit_gate};
use crate::multibody::cases::extremes::format::{ConservingSpec, ExtremesCase, PenaltySpec};
use crate::multibody::cases::extremes::observe::{observe, Observed};
use crate::multibody::cases::extremes::setup::{build, RunSpec};
use crate::multibody::study::{audit_checks, audit_gate, Claims};

/// ε of the factor `f`: f · E (H/rows)/h.
pub fn stiffness(file: &ExtremesCase, f: f64) -> f64 {
    let b = &file.bars;
    f * file.material.young * (b.height / b.rows as f64) / b.h()
}

/// The runs of the study with their factors (∞ for the multipliers): the Lagrange reference, the
/// compliant multipliers, the conserving penalties, then the penalty with each other scheme (in
/// this order; `spec.scheme` unless named).
fn runs(file: &ExtremesCase, spec: &PenaltySpec) -> Vec<(Enforcement, MultibodyScheme, f64)> {
    let penalty = |f: f64| Enforcement::Penalty {
        stiffness: stiffness(file, f),
    };
    let mut runs = vec![(Enforcement::Lagrange, spec.scheme, f64::INFINITY)];
    runs.extend(spec.factors.iter().map(|&f| {
        let law = Enforcement::Compliant {
            stiffness: stiffness(file, f),
        };
        (law, spec.scheme, f)
    }));
    if let Some(c) = &spec.conserving {
        runs.extend(c.factors.iter().map(|&f| (penalty(f), spec.scheme, f)));
        for &scheme in &c.other_schemes {
            runs.extend(c.other_factors.iter().map(|&f| (penalty(f), scheme, f)));
        }
    }
    runs
}

fn label(law: &Enforcement, scheme: MultibodyScheme, f: f64) -> String {
    match law {
        Enforcement::Lagrange => "Lagrange".into(),
        Enforcement::Compliant { .. } => format!("compliant f = {f:e}"),
        Enforcement::Penalty { .. } if scheme == MultibodyScheme::EnergyMomentum => {
            format!("conserving f = {f:e}")
        }
        Enforcement::Penalty { .. } => format!("penalty ({}) f = {f:e}", scheme.name()),
    }
}

/// The study's gates and tables.
pub fn study(
    file: &ExtremesCase,
    spec: &PenaltySpec,
) -> Result<(Vec<GateVerdict>, Vec<Table>), String> {
    let v = file.bars.speed;
    let planned = runs(file, spec);
    let outcomes: Vec<(RunSpec, Result<Observed, String>)> = planned
        .par_iter()
        .map(|&(law, scheme, _)| {
            let run = RunSpec {
                scheme,
                ..RunSpec::ordinary(file, v, law)
            };
            (
                run,
                build(file, &run).and_then(|s| observe(&s, &file.material)),
            )
        })
        .collect();
    let mut runs = Vec::new();
    let mut failures = Vec::new();
    for (i, (run, outcome)) in outcomes.into_iter().enumerate() {
        match outcome {
            Ok(o) => runs.push((run, o)),
            Err(e) if i == 0 => return Err(format!("penalty study, the Lagrange run: {e}")),
            Err(e) => failures.push(Check::holds(
                &format!(
                    "{}: the run ends ({e})",
                    label(&planned[i].0, planned[i].1, planned[i].2)
                ),
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
            Vec::new(),
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
    let lagrange_claims = Claims::of(runs[0].0.scheme, [true, true], false);
    let mut audit = audit_checks("Lagrange", &runs[0].1.summary, lagrange_claims);
    let mut state = state_audit_checks("Lagrange", &runs[0].1.state, lagrange_claims);
    // E_0: both bars' kinetic energy ½ (2 ρ L H) v² (the bars start apart)
    let e0 = file.bars.density * file.bars.length * file.bars.height * v * v;
    let ctx = RowContext {
        reference,
        v,
        force,
        plateau: (a, b),
        e0,
    };
    let mut compliant_rows = vec![row(
        &ctx,
        "Lagrange",
        f64::INFINITY,
        runs[0].0.step,
        &runs[0].1,
    )];
    let mut conserving_rows = compliant_rows.clone();
    let mut energy_checks = Vec::new();
    let (mut conserving_inverse, mut penetrations) = (Vec::new(), Vec::new());
    // the penalty with the other schemes: per scheme, E(T)/E_0 − 1 at each factor and the rows
    let mut others: Vec<(MultibodyScheme, Vec<f64>, Vec<Vec<String>>)> = Vec::new();
    for (i, (run, o)) in runs.iter().enumerate().skip(1) {
        let (law, scheme, f) = planned[i];
        let eps = stiffness(file, f);
        let name = label(&law, scheme, f);
        let vt = o.final_velocities();
        let diff = (0..2)
            .map(|j| (vt[j] - reference[j]).abs() / v)
            .fold(0.0, f64::max);
        let r = row(&ctx, &format!("{f:e}"), eps, run.step, o);
        match law {
            Enforcement::Penalty { .. } if scheme != spec.scheme => {
                // not a discrete gradient: the momenta are gated (a central pair force has no
                // resultant), and the energy the force puts into the contact
                let claims = Claims {
                    identity: false,
                    unchanged: false,
                    ..Claims::of(run.scheme, [true, true], false)
                };
                audit.extend(audit_checks(&name, &o.summary, claims));
                state.extend(state_audit_checks(&name, &o.state, claims));
                let at = match others.iter().position(|x| x.0 == scheme) {
                    Some(at) => at,
                    None => {
                        others.push((scheme, Vec::new(), Vec::new()));
                        others.len() - 1
                    }
                };
                let et = o.solution.records.last().map_or(f64::NAN, |x| x.energy);
                others[at].1.push(et / e0 - 1.0);
                others[at].2.push(r);
            }
            Enforcement::Compliant { .. } => {
                inverse.push(1.0 / f);
                differences.push(diff);
                force_checks.push(Check::within(
                    &format!("{name}: ε ⟨Σ (−g)⁺⟩ / (A σ_c)"),
                    eps * o.mean_penetration(run.step, a, b) / force,
                    1.0,
                    spec.force_tolerance,
                ));
                // the held gap is −λ/ε, not 0: the compliant spring works in steps without a
                // set change, so ΔE = 0 there is not claimed
                let claims = Claims {
                    unchanged: false,
                    ..Claims::of(run.scheme, [true, true], false)
                };
                audit.extend(audit_checks(&name, &o.summary, claims));
                state.extend(state_audit_checks(&name, &o.state, claims));
                compliant_rows.push(r);
            }
            _ => {
                let drift = o
                    .solution
                    .records
                    .iter()
                    .map(|rec| (rec.energy - e0).abs() / e0)
                    .fold(0.0, f64::max);
                if let Some(c) = &spec.conserving {
                    energy_checks.push(Check::at_most(
                        &format!("{name}: max_n |E_n − E_0| / E_0"),
                        drift,
                        c.energy_tolerance,
                    ));
                    // the audit's own drift (from its first record) is the same number: the two
                    // differ only in E_0 (the record's ½ vᵀMv against ρ L H v²), by round-off
                    energy_checks.push(Check::at_most(
                        &format!("{name}: |audit's energy drift − max_n |E_n − E_0| / E_0|"),
                        (o.summary.energy_drift - drift).abs(),
                        64.0 * f64::EPSILON,
                    ));
                }
                conserving_inverse.push(1.0 / f);
                penetrations.push(o.max_penetration());
                let claims = Claims::of(run.scheme, [true, true], false);
                audit.extend(audit_checks(&name, &o.summary, claims));
                state.extend(state_audit_checks(&name, &o.state, claims));
                conserving_rows.push(r);
            }
        }
    }
    let mut gates = vec![
        spec.rate.evaluate(
            "penalty → ∞ (compliant multiplier): |v_ε(T) − v_λ(T)| / v against 1/ε".into(),
            &inverse,
            &differences,
        ),
        GateVerdict::from_checks(
            "compliant multiplier: the penetration carries the exact force, ε ⟨Σ (−g)⁺⟩ = A ρ c v"
                .into(),
            "reference",
            force_checks,
            &spec.force_note,
        ),
    ];
    if let Some(ConservingSpec {
        note,
        penetration_rate,
        other_min_energy_gain,
        ..
    }) = &spec.conserving
    {
        gates.push(penetration_rate.evaluate(
            "conserving penalty: max penetration against 1/ε (the contact nodes' kinetic energy \
             in the spring: rate ½)"
                .into(),
            &conserving_inverse,
            &penetrations,
        ));
        if !others.is_empty() {
            let checks = others
                .iter()
                .map(|(scheme, gains, _)| {
                    Check::at_least(
                        &format!(
                            "{}: max over ε of E(T)/E_0 − 1 (E_0 = ρ L H v² from the setup)",
                            scheme.name()
                        ),
                        gains.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                        *other_min_energy_gain,
                    )
                })
                .collect();
            gates.push(GateVerdict::from_checks(
                "the penalty force at a point (midpoint, Newmark) gains energy at the contact"
                    .into(),
                "extreme",
                checks,
                "P′(g) ∇g evaluated at x_(n+½) or x_(n+1) is not a discrete gradient of P: a node \
                 can cross deep into the spring within a step the force does not see, and leave \
                 it pushed by the full spring — the energy grows with ε (EM §1's motivation); the \
                 secant form conserves it (the gate above)",
            ));
        }
        gates.push(GateVerdict::from_checks(
            "conserving penalty: E_n = E_0 = ρ L H v² at every step (no activation loss)".into(),
            "identity",
            energy_checks,
            note,
        ));
    }
    gates.push(state_audit_gate(
        "penalty and Lagrange runs: state-recomputed audit",
        state,
    ));
    gates.push(audit_gate(
        "penalty and Lagrange runs: audit",
        audit,
        "free bars: P_x, P_y conserved; energy–momentum: the energy identity (with the \
         penalty energy in E); ΔE = 0 between set changes for the multipliers and the \
         conserving penalty (the compliant spring works); J not claimed (linear law)",
    ));
    let header = [
        "f",
        "ε",
        "v_left(T)/v",
        "|v_ε − v_λ|/v at T",
        "ε ⟨Σ(−g)⁺⟩/(Aσ_c)",
        "max penetration",
        "ε · max penetration / (Aσ_c)",
        "E(T)/E_0",
        "Newton iterations",
    ]
    .map(String::from)
    .to_vec();
    let mut tables = vec![Table {
        title: format!(
            "penalty → ∞, compliant multiplier λ_N = ε (−g₁)⁺ (ε = f · E (H/rows)/h; v = {v}, \
             A σ_c = {force:.6}; plateau [{a:.4}, {b:.4}])"
        ),
        header: header.clone(),
        rows: compliant_rows,
    }];
    if spec.conserving.is_some() {
        tables.push(Table {
            title: format!(
                "penalty → ∞, conserving penalty P = (ε/2)(g₋)² (energy–momentum; E_0 = {e0:.6e})"
            ),
            header,
            rows: conserving_rows,
        });
    }
    for (scheme, _, rows) in others {
        let mut all = vec![tables[0].rows[0].clone()];
        all.extend(rows);
        tables.push(Table {
            title: format!(
                "penalty → ∞, P = (ε/2)(g₋)² with the {} scheme (the force P′(g) ∇g at its \
                 evaluation point: E not conserved; E_0 = {e0:.6e})",
                scheme.name()
            ),
            header: tables[0].header.clone(),
            rows: all,
        });
    }
    Ok((gates, tables))
}

/// What every row is compared with.
struct RowContext {
    reference: [f64; 2],
    v: f64,
    force: f64,
    plateau: (f64, f64),
    e0: f64,
}

/// One table row: `name`'s run `o` with stiffness `eps` (∞: the multipliers) and step `k`.
fn row(ctx: &RowContext, name: &str, eps: f64, k: f64, o: &Observed) -> Vec<String> {
    let vt = o.final_velocities();
    let diff = (0..2)
        .map(|j| (vt[j] - ctx.reference[j]).abs() / ctx.v)
        .fold(0.0, f64::max);
    let finite = eps.is_finite();
    let (a, b) = ctx.plateau;
    let et = o.solution.records.last().map_or(f64::NAN, |r| r.energy);
    let or_dash = |x: String| if finite { x } else { "—".into() };
    vec![
        name.into(),
        if finite {
            format!("{eps:.4e}")
        } else {
            "∞".into()
        },
        format!("{:.6}", vt[0] / ctx.v),
        if finite {
            format!("{diff:.4e}")
        } else {
            "0".into()
        },
        or_dash(format!(
            "{:.6}",
            eps * o.mean_penetration(k, a, b) / ctx.force
        )),
        format!("{:.4e}", o.max_penetration()),
        or_dash(format!("{:.4e}", o.max_penetration() * eps / ctx.force)),
        format!("{:.10}", et / ctx.e0),
        format!("{}", o.solution.stats.newton_iterations),
    ]
}
