//! A slave block sliding along a master block and off its free end (frictionless, no load, one
//! pass), in two variants:
//! - unloaded (v_a = 0, the faces exactly touching): the exact solution is rigid translation
//!   ([`super::reference::SlideKinematics`]): every node keeps its initial velocity, no stress, no
//!   contact force, and each slave node is released in the step the kinematics give;
//! - loaded (the slave also approaches at v_a: the interface is compressed while the nodes slide
//!   and leave the end under load): P is the setup's m_s (v_t, −v_a) at every step, the energy
//!   never rises above E_0 (the energy–momentum scheme: conserved except the activation work
//!   −λ g₀ ≤ 0; a released node simply has no constraint in its step, so the release does no
//!   work), and the nodes that passed the end by T are the ones released.
//!
//! What it catches: a release that applies an impulse (the velocities or P would jump), segment
//! switching that jumps the gap (a contact force or a stress would appear in the unloaded
//! slide), a node lost by the search (released early) or kept past the end (released late).

use contactlab::model::multibody::solver::PairMaster;

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::multibody::audit_state::{state_audit_checks, state_audit_gate};
use crate::multibody::cases::sliding::format::{SlideOffSpec, SlidingCase};
use crate::multibody::cases::sliding::reference::SlideKinematics;
use crate::multibody::cases::sliding::setup::{observe, slide, Observed, MASTER, SLAVE};
use crate::multibody::study::{audit_checks, audit_gate, Claims};
use crate::plot::{Figure, Series};

/// The smallest distance (in end segments) of a node from the release threshold at any step
/// that the case's timing must keep, so that the kinematic release step is not decided by
/// round-off (unloaded) or by the O(v_a/c) x-motion of the loaded bodies (loaded).
const CLEARANCE: f64 = 1e-3;

/// One variant's measurements.
struct Variant {
    name: &'static str,
    approach: f64,
    run: Observed,
    kinematics: SlideKinematics,
    /// max_{n,i} |v_i(t_n) − v_i(0)| / (ε v_t), both bodies.
    velocity: f64,
    /// max_n stored energy / E_0, max_n Σ λ_N (over A ρ c v_t).
    stored: f64,
    force: f64,
    /// max_n |P(t_n) − P_setup| / (ε m_s |v|).
    momentum: f64,
    /// max_n (E_n − E_0) / (ε E_0) (reported), and (E(T) − E_0)/E_0.
    rise: f64,
    loss: f64,
    /// max |ΔE| / (ε E_0) over the steps that release a node and neither activate nor switch one.
    release_work: f64,
    /// The switch work of every step with one, over E_0.
    switch_work: Vec<f64>,
    /// max_n |E_n − E_0| / (ε E_0).
    drift: f64,
    /// Slave nodes first unlisted at step n (solver) and the kinematic release steps.
    first_unlisted: Vec<Option<usize>>,
    expected: Vec<Option<usize>>,
}

/// The slave's bottom nodes (reference x, in the slave surface's order) sliding at v_t towards
/// the master's right end x_e = L_m, whose end segment is h = L_m / M_m.
fn kinematics(s: &SlideOffSpec, nodes: Vec<f64>) -> SlideKinematics {
    SlideKinematics {
        nodes,
        end: s.master.size[0],
        segment: s.master.size[0] / s.master.divisions[0] as f64,
        speed: s.tangential_speed,
    }
}

fn measure(
    file: &SlidingCase,
    s: &SlideOffSpec,
    name: &'static str,
    approach: f64,
) -> Result<Variant, String> {
    let solver = slide(file, s, approach)?;
    // the slave surface's node order and reference x, to map the solver's list to the kinematics
    let pair = solver.problem().pairs.first().ok_or("no pair")?;
    if !matches!(pair.master, PairMaster::Surface(_)) {
        return Err("the slide's master is not a surface".into());
    }
    let xs: Vec<f64> = pair
        .slave
        .nodes
        .iter()
        .map(|&n| solver.problem().bodies.reference(SLAVE, n)[0])
        .collect();
    let run = observe(&solver, &file.material).map_err(|e| format!("{name}: {e}"))?;
    let kin = kinematics(s, xs);
    let eps = f64::EPSILON;
    let vt = s.tangential_speed;
    let first = run.steps.first().ok_or("no steps")?;
    let mut velocity = 0.0f64;
    let ms = file.density * s.slave.size[0] * s.slave.size[1];
    let p_setup = [ms * vt, -ms * approach];
    let speed = vt.hypot(approach);
    let mut momentum = 0.0f64;
    let mut force = 0.0f64;
    for st in &run.steps {
        for b in [MASTER, SLAVE] {
            for (v, v0) in st.velocity[b].iter().zip(&first.velocity[b]) {
                velocity = velocity.max((v[0] - v0[0]).abs()).max((v[1] - v0[1]).abs());
            }
        }
        for c in 0..2 {
            let p = st.momentum[MASTER][c] + st.momentum[SLAVE][c];
            momentum = momentum.max((p - p_setup[c]).abs());
        }
        force = force.max(st.normal_force.abs());
    }
    let e0 = run.records.first().map_or(f64::NAN, |r| r.energy);
    let stored = run.records.iter().map(|r| r.stored).fold(0.0, f64::max) / e0;
    let rise = run
        .records
        .iter()
        .map(|r| r.energy - e0)
        .fold(f64::NEG_INFINITY, f64::max)
        / (eps * e0);
    let loss = run.records.last().map_or(f64::NAN, |r| r.energy - e0) / e0;
    let release_work = run
        .records
        .windows(2)
        .filter(|w| w[1].released > 0 && w[1].activated == 0 && w[1].switches == 0)
        .map(|w| (w[1].energy - w[0].energy).abs())
        .fold(0.0, f64::max)
        / (eps * e0);
    let switch_work: Vec<f64> = run
        .records
        .iter()
        .filter(|r| r.switches > 0 && r.switch_work != 0.0)
        .map(|r| r.switch_work / e0)
        .collect();
    let drift = run
        .records
        .iter()
        .map(|r| (r.energy - e0).abs())
        .fold(0.0, f64::max)
        / (eps * e0);
    let steps = run.steps.len() - 1;
    let first_unlisted = (0..kin.nodes.len())
        .map(|i| (1..=steps).find(|&n| !run.steps[n].listed[i]))
        .collect();
    let expected = (0..kin.nodes.len())
        .map(|i| kin.release_step(i, run.k, steps))
        .collect();
    let side_force = file.density * file.wave_speed() * vt * s.slave.size[0];
    Ok(Variant {
        name,
        approach,
        velocity: velocity / (eps * vt),
        stored,
        force: force / side_force,
        momentum: momentum / (eps * ms * speed),
        rise,
        loss,
        release_work,
        switch_work,
        drift,
        first_unlisted,
        expected,
        kinematics: kin,
        run,
    })
}

/// The study: its gates, table and plots into `report`.
pub fn study(
    file: &SlidingCase,
    s: &SlideOffSpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let (unloaded, loaded) = rayon::join(
        || measure(file, s, "unloaded", 0.0),
        || measure(file, s, "loaded", s.approach_speed),
    );
    let variants = [unloaded?, loaded?];
    let mut exact = Vec::new();
    let mut releases = Vec::new();
    let mut audit = Vec::new();
    let mut state = Vec::new();
    let mut rows = Vec::new();
    for v in &variants {
        let steps = v.run.steps.len() - 1;
        let clearance = v.kinematics.clearance(v.run.k, steps);
        if clearance < CLEARANCE {
            return Err(format!(
                "slide_off: a slave node comes within {clearance:e} end segments of the release \
                 threshold at a step (choose slide_off.start or final_time clear of it: ≥ {CLEARANCE})"
            ));
        }
        let label = v.name;
        if v.approach == 0.0 {
            exact.push(Check::at_most(
                &format!("{label}: max_(n,i) |v_i(t_n) − v_i(0)| / (ε v_t), both bodies"),
                v.velocity,
                s.velocity_round_off,
            ));
            exact.push(Check::at_most(
                &format!("{label}: max_n stored energy / (ε² E_0)"),
                v.stored / f64::EPSILON.powi(2),
                s.stored_round_off,
            ));
            exact.push(Check::at_most(
                &format!("{label}: max_n |Σ λ_N| / (ε A_s ρ c v_t)"),
                v.force / f64::EPSILON,
                s.force_round_off,
            ));
            exact.push(Check::at_most(
                &format!("{label}: max_n |E_n − E_0| / (ε E_0)"),
                v.drift,
                s.energy_round_off,
            ));
            let mismatched = v
                .first_unlisted
                .iter()
                .zip(&v.expected)
                .filter(|(a, b)| a != b)
                .count();
            releases.push(Check::holds(
                &format!(
                    "{label}: every slave node released in the kinematic step ({mismatched} of {} differ)",
                    v.expected.len()
                ),
                mismatched == 0,
                "each node's first step off the candidate list = the first step past x_e + r h (r = RELEASE_TOLERANCE)",
            ));
        }
        exact.push(Check::at_most(
            &format!("{label}: max_n |P(t_n) − m_s (v_t, −v_a)| / (ε m_s |v|)"),
            v.momentum,
            s.momentum_round_off,
        ));
        exact.push(Check::at_most(
            &format!(
                "{label}: max |ΔE| / (ε E_0) over the steps that only release (the release does no work)"
            ),
            v.release_work,
            s.energy_round_off,
        ));
        let solver_count = v.first_unlisted.iter().filter(|n| n.is_some()).count();
        let kinematic = v.kinematics.released(v.run.k, steps);
        releases.push(Check::holds(
            &format!(
                "{label}: slave nodes released by T: {solver_count}, past the end by T: {kinematic}"
            ),
            solver_count == kinematic && kinematic > 0,
            "equal and > 0",
        ));
        releases.push(Check::holds(
            &format!("{label}: every record finite"),
            v.run.records.iter().all(|r| r.first_non_finite().is_none()),
            "finite",
        ));
        let claims = Claims {
            unchanged: false,
            ..Claims::of(
                contactlab::model::multibody::scheme::MultibodyScheme::EnergyMomentum,
                [true, true],
                false,
            )
        };
        audit.extend(audit_checks(label, &v.run.summary, claims));
        state.extend(state_audit_checks(label, &v.run.state, claims));
        let fmt_steps = |x: &[Option<usize>]| {
            x.iter()
                .map(|n| n.map_or("–".to_string(), |n| n.to_string()))
                .collect::<Vec<_>>()
                .join(" ")
        };
        rows.push(vec![
            label.to_string(),
            format!("{}", v.approach),
            format!("{:.2}", v.velocity),
            format!("{:.2e}", v.stored),
            format!("{:.2e}", v.force),
            format!("{:.2}", v.momentum),
            format!("{:.2}", v.rise),
            format!("{:.3e}", v.loss),
            format!("{:.2}", v.release_work),
            if v.switch_work.is_empty() {
                "none".into()
            } else {
                format!(
                    "{} steps, {:.2e} … {:.2e}",
                    v.switch_work.len(),
                    v.switch_work.iter().copied().fold(f64::INFINITY, f64::min),
                    v.switch_work
                        .iter()
                        .copied()
                        .fold(f64::NEG_INFINITY, f64::max)
                )
            },
            fmt_steps(&v.first_unlisted),
            fmt_steps(&v.expected),
            format!(
                "{} / {} / {}",
                v.run.stats.releases, v.run.stats.switches, solver_count
            ),
            format!(
                "{:.2e} / {:.2e} / {:.2e}",
                v.run.summary.identity_ratio,
                v.run.summary.momentum_ratio_x,
                v.run.summary.momentum_ratio_y
            ),
            format!("{:.2e}", clearance),
        ]);
    }
    report.gates.push(GateVerdict::from_checks(
        "slide-off: rigid translation exact without load; P = the setup's, no energy gain with load".into(),
        "reference",
        exact,
        &s.note,
    ));
    report.gates.push(GateVerdict::from_checks(
        "slide-off: the released nodes are the ones the kinematics put past the end".into(),
        "reference",
        releases,
        &s.note,
    ));
    report
        .gates
        .push(state_audit_gate("slide-off: state-recomputed audit", state));
    report.gates.push(audit_gate(
        "slide-off: audit",
        audit,
        "free bodies: P_x, P_y conserved; the energy–momentum identity (its normal work counts \
         the candidates that remain: a released node does no work). ΔE = 0 between set changes \
         is not claimed (the held gap's round-off, docs/multibody.md)",
    ));
    let k = variants[0].run.k;
    report.tables.push(Table {
        title: format!(
            "slide-off (v_t = {}, k = {k:.5}, master end x_e = {}, end segment h = {}; release at x > x_e + r h, r = RELEASE_TOLERANCE)",
            s.tangential_speed,
            s.master.size[0],
            s.master.size[0] / s.master.divisions[0] as f64
        ),
        header: [
            "variant",
            "v_a",
            "max |v − v0|/(ε v_t)",
            "max stored/E_0",
            "max Σλ_N/(A ρ c v_t)",
            "max |P − P_setup|/(ε m_s|v|)",
            "max (E − E_0)/(ε E_0)",
            "(E(T) − E_0)/E_0",
            "release-only steps: max |ΔE|/(ε E_0)",
            "switch work / E_0 (steps with one)",
            "release steps (solver)",
            "release steps (kinematics)",
            "releases / switches / nodes released",
            "identity / P_x / P_y ratios",
            "clearance (segments)",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    });
    plots(file, &variants, s, ctx, report)
}

fn plots(
    file: &SlidingCase,
    variants: &[Variant],
    s: &SlideOffSpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let floor = |v: f64| v.max(1e-18);
    let vt = s.tangential_speed;
    let mut listed = Figure::new("slide-off: slave nodes on the master")
        .x_label("t")
        .y_label("candidates (slave nodes not released)");
    let mut deviation = Figure::new("slide-off: velocity deviation")
        .x_label("t")
        .y_label("max_i |v_i − v_i(0)| / v_t")
        .semilog_y();
    let mut force = Figure::new("slide-off: contact force and energy")
        .x_label("t")
        .y_label("Σ λ_N / (A ρ c v_a),  (E − E_0)/E_0 × 100");
    for (i, v) in variants.iter().enumerate() {
        let n = v.kinematics.nodes.len();
        listed = listed.series(
            Series::markers(
                format!("{}: solver", v.name),
                v.run.steps.iter().skip(1).map(|st| {
                    (
                        st.time,
                        st.listed.iter().filter(|l| **l).count() as f64 + 0.1 * i as f64,
                    )
                }),
            )
            .color(i),
        );
        listed = listed.series(
            Series::line(
                format!("{}: kinematics", v.name),
                v.run.steps.iter().enumerate().skip(1).map(|(step, st)| {
                    let on = (0..n)
                        .filter(|&j| v.expected[j].is_none_or(|r| r > step))
                        .count();
                    (st.time, on as f64 + 0.1 * i as f64)
                }),
            )
            .color(i)
            .dashed(),
        );
        let first = &v.run.steps[0];
        deviation = deviation.series(
            Series::line(
                v.name,
                v.run.steps.iter().map(|st| {
                    let mut d = 0.0f64;
                    for b in [MASTER, SLAVE] {
                        for (a, a0) in st.velocity[b].iter().zip(&first.velocity[b]) {
                            d = d.max((a[0] - a0[0]).abs()).max((a[1] - a0[1]).abs());
                        }
                    }
                    (st.time, floor(d / vt))
                }),
            )
            .color(i),
        );
        if v.approach > 0.0 {
            let scale = file.density * file.wave_speed() * v.approach * s.slave.size[0];
            let e0 = v.run.records[0].energy;
            force = force.series(
                Series::line(
                    format!("{}: Σ λ_N / (A ρ c v_a)", v.name),
                    v.run
                        .steps
                        .iter()
                        .map(|st| (st.time, st.normal_force / scale)),
                )
                .color(i),
            );
            force = force.series(
                Series::line(
                    format!("{}: 100 (E − E_0)/E_0", v.name),
                    v.run
                        .records
                        .iter()
                        .map(|r| (r.time, 100.0 * (r.energy - e0) / e0)),
                )
                .color(i)
                .dashed(),
            );
        }
    }
    ctx.panels(
        report,
        "slide_off",
        "slide-off: the release against the kinematics; the velocity deviation; the loaded variant's force and energy",
        &[listed, deviation, force],
        3,
    )
}
