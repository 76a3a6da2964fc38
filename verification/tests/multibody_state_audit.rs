//! The multibody audit recomputed from the state (`contactlab_verify::multibody::audit_state`)
//! against the defects the solver's own books cannot see.
//!
//! Setting: the bars of `multibody_bars` (L = 1, H = 0.1, E = ρ = 1, ν = 0, one row, gap 0.02,
//! k = h/c, single pass, Lagrange multipliers). Goal: (1) Newmark with multipliers, whose energy
//! rises to ≈ 3 E₀ at M = 40 (docs/multibody.md §3.2), fails the recomputed energy bound that a
//! conserving run is gated with; (2) records that book an energy gain as activation work, flip
//! the sign of the activation work (with or without W_N), or carry a wrong sign of P or K fail the comparison of the
//! records with the state, while the same run's unaltered records pass it; (3) multipliers of the
//! wrong sign at an activation, or a force left on a released constraint, fail the sign laws.

use contactlab::model::multibody::audit::MultibodyRecord;
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{ContactState, MultibodySolver, MultibodyStepView};
use contactlab_verify::multibody::audit_state::{state_audit_checks, StateAudit, StateAuditor};
use contactlab_verify::multibody::cases::bars::setup::{build, Geometry, Level, Treatment};
use contactlab_verify::multibody::study::{run_recorded, Claims, LawName, MaterialSpec};

const MATERIAL: MaterialSpec = MaterialSpec {
    law: LawName::Linear,
    young: 1.0,
    poisson: 0.0,
};

/// The bars with M elements; `striker`: the left bar moves at v = 0.1 onto the resting right
/// one (P ≠ 0), else both meet head-on at ±0.1.
fn bars(elements: usize, scheme: MultibodyScheme, striker: bool) -> MultibodySolver {
    let g = Geometry {
        left_length: 1.0,
        right_length: 1.0,
        height: 0.1,
        density: 1.0,
        gap: 0.02,
        left_velocity: 0.1,
        right_velocity: if striker { 0.0 } else { -0.1 },
    };
    let h = 1.0 / elements as f64;
    let level = Level {
        elements,
        rows: 1,
        step: h,
        steps: (2.6 / h).round() as usize,
    };
    build(
        &g,
        &MATERIAL,
        &level,
        Treatment {
            scheme,
            two_pass: false,
        },
    )
    .unwrap()
}

/// Every view of a run, kept: (u, v, contacts, record) per step.
type Kept = Vec<(Vec<f64>, Vec<f64>, Vec<ContactState>, MultibodyRecord)>;

fn keep(solver: &MultibodySolver) -> Kept {
    let mut kept = Vec::new();
    solver
        .solve_with(&mut |v| {
            kept.push((
                v.displacement.to_vec(),
                v.velocity.to_vec(),
                v.contacts.to_vec(),
                *v.record,
            ))
        })
        .unwrap();
    kept
}

/// The state audit of kept views whose records `alter` changed (step index, record).
fn replay(
    solver: &MultibodySolver,
    kept: &Kept,
    alter: impl Fn(usize, &mut MultibodyRecord),
) -> StateAudit {
    replay_states(solver, kept, |n, r, _| alter(n, r))
}

/// The state audit of kept views whose records and contact states `alter` changed.
fn replay_states(
    solver: &MultibodySolver,
    kept: &Kept,
    alter: impl Fn(usize, &mut MultibodyRecord, &mut Vec<ContactState>),
) -> StateAudit {
    let mut auditor = StateAuditor::new(solver.problem(), &[MATERIAL; 2], &[]).unwrap();
    for (n, (u, v, c, r)) in kept.iter().enumerate() {
        let mut record = *r;
        let mut contacts = c.clone();
        alter(n, &mut record, &mut contacts);
        auditor.observe(&MultibodyStepView {
            step: n,
            time: record.time,
            displacement: u,
            velocity: v,
            contacts: &contacts,
            record: &record,
        });
    }
    auditor.finish().unwrap()
}

fn conserving_claims() -> Claims {
    Claims::of(MultibodyScheme::EnergyMomentum, [true, true], false)
}

#[test]
fn newmark_with_multipliers_gaining_three_e0_fails_the_recomputed_energy_bound() {
    let solver = bars(40, MultibodyScheme::Newmark, false);
    let run = run_recorded(&solver, &[MATERIAL; 2]).unwrap();
    let a = run.state;
    eprintln!(
        "Newmark, M = 40: E_N/E_0 = {:.3} (max {:.3}); recomputed rise/tol = {:.3e}, entries' \
         positive work/floor = {:.3e}, records/state K,V,E {:.3e}, W {:.3e}; the solver's \
         identity ratio {:.3e}, activation work {:.3e} E_0",
        a.final_energy_ratio,
        a.max_energy_ratio,
        a.energy_rise_ratio,
        a.entry_work_ratio,
        a.energy_record_ratio,
        a.work_record_ratio,
        run.summary.identity_ratio,
        run.summary.activation_work / a.initial_energy
    );
    assert!(a.max_energy_ratio > 2.0, "{a:?}");
    assert!(a.energy_rise_ratio > 1e6, "{a:?}");
    let checks = state_audit_checks("newmark", &a, conserving_claims());
    let failed: Vec<_> = checks.iter().filter(|c| !c.passed).collect();
    assert!(
        failed.iter().any(|c| c.name.contains("allowed gains")),
        "{checks:?}"
    );
    // the records agree with the state: the gain is real, not a bookkeeping error
    assert!(
        a.energy_record_ratio <= 1.0 && a.work_record_ratio <= 1.0,
        "{a:?}"
    );
}

#[test]
fn energy_momentum_bars_pass_every_recomputed_check() {
    let solver = bars(20, MultibodyScheme::EnergyMomentum, true);
    let kept = keep(&solver);
    let a = replay(&solver, &kept, |_, _| {});
    eprintln!("energy–momentum striker, M = 20: {a:?}");
    let checks = state_audit_checks("em", &a, conserving_claims());
    assert!(checks.iter().all(|c| c.passed), "{checks:?}");
    assert!(a.entry_steps > 0 && a.release_steps > 0, "{a:?}");
}

#[test]
fn an_energy_gain_booked_as_activation_work_fails_the_record_comparison() {
    let solver = bars(20, MultibodyScheme::EnergyMomentum, true);
    let kept = keep(&solver);
    let first = kept
        .iter()
        .position(|k| k.3.activation_work != 0.0)
        .expect("an activation");
    let e0 = kept[0].3.energy;
    // from the first activation on, the records say E rose by 2.1 E_0 and book it as the
    // activation's work: the solver's identity E_n − E_{n−1} = W holds in the altered records
    let a = replay(&solver, &kept, |n, r| {
        if n >= first {
            r.energy += 2.1 * e0;
            r.kinetic += 2.1 * e0;
        }
        if n == first {
            r.activation_work += 2.1 * e0;
            r.normal_work += 2.1 * e0;
        }
    });
    eprintln!(
        "gain booked as activation: K,V,E records/state {:.3e}, W {:.3e}",
        a.energy_record_ratio, a.work_record_ratio
    );
    assert!(
        a.energy_record_ratio > 1e6 && a.work_record_ratio > 1e6,
        "{a:?}"
    );
}

#[test]
fn a_flipped_sign_of_the_activation_work_fails_the_record_comparison() {
    let solver = bars(20, MultibodyScheme::EnergyMomentum, true);
    let kept = keep(&solver);
    let a = replay(&solver, &kept, |_, r| {
        r.normal_work -= 2.0 * r.activation_work;
        r.activation_work = -r.activation_work;
    });
    eprintln!(
        "activation sign flipped: W records/state {:.3e}",
        a.work_record_ratio
    );
    assert!(a.work_record_ratio > 1e6, "{a:?}");
}

#[test]
fn activation_work_booked_with_the_wrong_sign_alone_fails_the_set_change_comparison() {
    // W_N intact, only its set changes' part flipped (the solver's booking of
    // `activation_work`, mutated): the record's total agrees with the state, the split does not
    let solver = bars(20, MultibodyScheme::EnergyMomentum, true);
    let kept = keep(&solver);
    let clean = replay(&solver, &kept, |_, _| {});
    let a = replay(&solver, &kept, |_, r| {
        r.activation_work = -r.activation_work
    });
    eprintln!(
        "activation split flipped: W records/state {:.3e} (clean {:.3e})",
        a.work_record_ratio, clean.work_record_ratio
    );
    assert!(clean.work_record_ratio <= 1.0, "{clean:?}");
    assert!(a.work_record_ratio > 1e6, "{a:?}");
}

#[test]
fn a_wrong_sign_of_the_recorded_momentum_or_kinetic_energy_fails_the_record_comparison() {
    let solver = bars(20, MultibodyScheme::EnergyMomentum, true);
    let kept = keep(&solver);
    let p = replay(&solver, &kept, |_, r| r.momentum[0] = -r.momentum[0]);
    let k = replay(&solver, &kept, |_, r| r.kinetic = -r.kinetic);
    eprintln!(
        "P_x sign flipped: P,J records/state {:.3e}; K sign flipped: K,V,E {:.3e}",
        p.momentum_record_ratio, k.energy_record_ratio
    );
    assert!(p.momentum_record_ratio > 1e6, "{p:?}");
    assert!(k.energy_record_ratio > 1e6, "{k:?}");
}

#[test]
fn a_multiplier_of_the_wrong_sign_at_an_activation_fails_the_entry_sign_law() {
    // M = 15: the faces meet at t = 0.1 = 1.5 k, inside a step (g₀ > 0 at the activation)
    let solver = bars(15, MultibodyScheme::EnergyMomentum, false);
    let kept = keep(&solver);
    let first = kept
        .iter()
        .position(|k| k.3.activation_work < 0.0)
        .expect("an activation that closes a gap");
    let a = replay_states(&solver, &kept, |n, _, contacts| {
        if n == first {
            contacts.iter_mut().for_each(|c| c.lambda_n = -c.lambda_n);
        }
    });
    eprintln!(
        "λ flipped at the activation: entries' positive work/floor {:.3e}",
        a.entry_work_ratio
    );
    assert!(a.entry_work_ratio > 1e6, "{a:?}");
}

#[test]
fn a_force_left_on_a_released_constraint_fails_the_release_law() {
    let solver = bars(20, MultibodyScheme::EnergyMomentum, false);
    let kept = keep(&solver);
    // the first step in which a constraint active before is inactive: give it its last force
    let (n, key, lambda) = (1..kept.len())
        .find_map(|n| {
            kept[n].2.iter().find_map(|c| {
                let before = kept[n - 1]
                    .2
                    .iter()
                    .find(|b| b.pair == c.pair && b.slave == c.slave && b.active)?;
                (!c.active).then_some((n, (c.pair, c.slave), before.lambda_n))
            })
        })
        .expect("a release");
    let a = replay_states(&solver, &kept, |m, _, contacts| {
        if m == n {
            for c in contacts.iter_mut().filter(|c| (c.pair, c.slave) == key) {
                c.lambda_n = lambda;
            }
        }
    });
    eprintln!(
        "force left on a release: releases' |work|/floor {:.3e}",
        a.release_work_ratio
    );
    assert!(a.release_work_ratio > 1e3, "{a:?}");
}
