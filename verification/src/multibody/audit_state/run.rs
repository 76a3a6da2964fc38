//! The state-recomputed audit of one run: an observer of the solver's steps ([`StateAuditor`])
//! that recomputes every audited quantity from the state (module docs of `super`), compares the
//! step records with it, and gates the sign laws ([`state_audit_checks`]).
//!
//! Floors and tolerances, per step n (C = 2, N the terms of a sum):
//! - a record against its recomputed value: |rec − state| over C ε (N + 30) S, S the sum of the
//!   magnitudes of the recomputed terms (`super::sums`; for a work Σ |λ (g₁ − g₀)| plus the gaps'
//!   rounding 16 |λ| |x| per constraint, for W_ext Σ |f_i d_i| plus Σ |f_i| (|u_{n−1,i}| + |u_{n,i}|),
//!   d = u_n − u_{n−1} being rounded);
//! - a sign law (entries' positive work Σ max(0, λ (g₁ − g₀)), the step's friction work, the
//!   releases' |work|): over its own gaps' floor C ε Σ |λ| (|g₀| + |g₁| + 16 |x|) plus the step's
//!   Newton part, ν_n + C ε s_n (the solver's reported residual bound and round-off scale — the
//!   only solver numbers used, and only as slack: a gained energy is never among them);
//! - the recomputed identity |E_n − E_0 − Σ_{j≤n} (W_N + W_T + W_ext)_j| and the energy's rise
//!   E_n − E_0 − Σ_{j≤n} (W_ext + allowed gains)_j over tol_n = floor(E_n) + floor(E_0) +
//!   Σ_{j≤n} (floor(W_j) + Σ_holding |λ| (|g₀| + |g₁|) + ν_j + C ε s_j).

use crate::core::audit_floor::{floor, max_nan, C};
use std::collections::BTreeMap;

use serde::Serialize;

use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::multibody::audit::MultibodyRecord;
use contactlab::model::multibody::constraint::Enforcement;
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{ContactState, MultibodyProblem, MultibodyStepView};

use super::geometry::{gap_xi_length, local_points, size};
use super::sums::{plane_law, state_sums, StateSums};
use crate::core::gate::{Check, GateVerdict};
use crate::manufactured::strain_energy::PlaneLaw;
use crate::multibody::spec::{Claims, MaterialSpec};

/// A gap computed from coordinates of size |x| rounds by at most this many ε |x| (a cross
/// product, a square root and a quotient: a generous count).
const GAP_ROUNDING: f64 = 16.0;

/// What the state-recomputed audit of a run shows. The `*_ratio` fields are maxima over the
/// steps of a difference or a sign law's value over its floor (module docs): ≤ 1 passes.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct StateAudit {
    pub steps: usize,
    /// Records against the state: K, V (+ penalty) and E; P (larger component) and J; the
    /// step's W_N, W_T and W_ext.
    pub energy_record_ratio: f64,
    pub momentum_record_ratio: f64,
    pub work_record_ratio: f64,
    /// Sign laws on the recomputed works: an entry's positive work, friction's step work, the
    /// releases' |work|.
    pub entry_work_ratio: f64,
    pub friction_sign_ratio: f64,
    pub release_work_ratio: f64,
    /// The recomputed identity's drift and the energy's rise over E_0 + W_ext + allowed gains.
    pub identity_ratio: f64,
    pub energy_rise_ratio: f64,
    /// Recomputed E_0, max_n E_n / E_0 and E_N / E_0.
    pub initial_energy: f64,
    pub max_energy_ratio: f64,
    pub final_energy_ratio: f64,
    /// Σ of the recomputed entries' work (≤ 0) and of the allowed gains, over E_0.
    pub entry_work_relative: f64,
    pub allowed_gain_relative: f64,
    /// Steps with an entry, with friction, with a release.
    pub entry_steps: usize,
    pub friction_steps: usize,
    pub release_steps: usize,
}

/// The previous step's state.
struct Previous {
    u: Vec<f64>,
    contacts: BTreeMap<(usize, usize), ContactState>,
    energy: f64,
    load: Vec<f64>,
}

/// The recomputed works of one step.
#[derive(Debug, Default)]
struct StepWorks {
    /// W_N (multipliers' λ (g₁ − g₀) and the penalty's booked jump) and its magnitude.
    normal: f64,
    friction: f64,
    magnitude: f64,
    terms: usize,
    /// The gaps' rounding Σ 16 |λ| |x| and the holding constraints' Σ |λ| (|g₀| + |g₁|).
    rounding: f64,
    holding: f64,
    /// Entries' positive work and its floor (without the Newton part); the entries' total.
    entry_positive: f64,
    entry_total: f64,
    entry_floor: f64,
    entries: usize,
    friction_magnitude: f64,
    friction_terms: usize,
    release: f64,
    release_floor: f64,
    releases: usize,
    /// Gains booked and allowed (docs): held nodes' switches, the penalty's booked jumps,
    /// positive set changes of pairs that allow a gain, the compliant multiplier's held work.
    allowed: f64,
    /// The penalty's jump where no segment changed (not booked, not allowed): part of the
    /// recomputed identity all the same.
    penalty_unbooked: f64,
    /// The set changes' part of W_N, the record's activation + switch work: the work of every
    /// constraint active at t_n that was not held on the same segment at t_{n−1} (entries,
    /// re-pairings, held nodes' switches), with the penalty's booked jumps.
    set_change: f64,
    /// Σ |λ (g₁ − g₀)| of the constraints whose switch inside the step the state cannot show.
    set_change_unseen: f64,
}

/// The auditor: feed it every step's view ([`Self::observe`]), then [`Self::finish`].
pub struct StateAuditor<'a> {
    problem: &'a MultibodyProblem,
    laws: Vec<PlaneLaw>,
    k: f64,
    allow_gain: Vec<bool>,
    previous: Option<Previous>,
    /// floor(E_0).
    initial_floor: f64,
    /// Σ_j (floor(W_j) + holding_j + ν_j + C ε s_j) and the running sums of the works.
    slack: f64,
    supplied: f64,
    identity_sum: f64,
    entry_work: f64,
    allowed: f64,
    audit: StateAudit,
    error: Option<String>,
}

impl<'a> StateAuditor<'a> {
    /// The auditor of `problem`'s run, body b of material `materials[b]`; `allow_gain[p]`: pair p
    /// allows an energy gain (`allow_energy_gain`). Errors: a count of materials other than the
    /// bodies', or a body with material regions (not recomputed here).
    pub fn new(
        problem: &'a MultibodyProblem,
        materials: &[MaterialSpec],
        allow_gain: &[bool],
    ) -> Result<Self, String> {
        let bodies = &problem.bodies;
        if materials.len() != bodies.len() {
            return Err(format!(
                "state audit: {} materials for {} bodies",
                materials.len(),
                bodies.len()
            ));
        }
        if let Some(b) = (0..bodies.len()).find(|&b| !bodies.body(b).data().regions.is_empty()) {
            return Err(format!(
                "state audit: body {b} has material regions (not recomputed)"
            ));
        }
        Ok(Self {
            problem,
            laws: materials.iter().map(plane_law).collect(),
            k: problem.final_time / problem.steps as f64,
            allow_gain: allow_gain.to_vec(),
            previous: None,
            initial_floor: 0.0,
            slack: 0.0,
            supplied: 0.0,
            identity_sum: 0.0,
            entry_work: 0.0,
            allowed: 0.0,
            audit: StateAudit::default(),
            error: None,
        })
    }

    /// Takes one step's view (the initial state first).
    pub fn observe(&mut self, view: &MultibodyStepView<'_>) {
        if self.error.is_none() {
            if let Err(e) = self.step(view) {
                self.error = Some(format!("state audit, step {}: {e}", view.step));
            }
        }
    }

    /// The audit of the steps observed.
    pub fn finish(self) -> Result<StateAudit, String> {
        match self.error {
            Some(e) => Err(e),
            None if self.previous.is_none() => Err("state audit: no step observed".into()),
            None => Ok(self.audit),
        }
    }

    /// The loads f(t) of every body, stacked.
    fn load(&self, t: f64) -> Vec<f64> {
        let bodies = &self.problem.bodies;
        let mut f = vec![0.0; bodies.dofs()];
        for (b, body) in bodies.bodies().iter().enumerate() {
            body.load_into(t, &mut f[bodies.range(b)]);
        }
        f
    }

    /// The penalty energy Σ (ε/2) (g₋)² of `contacts` (with their segments) at u, and its floor.
    fn penalty(
        &self,
        contacts: &BTreeMap<(usize, usize), ContactState>,
        u: &[f64],
    ) -> Result<(f64, f64), String> {
        let (mut p, mut magnitude, mut n) = (0.0, 0.0, 0);
        for c in contacts.values() {
            let pair = &self.problem.pairs[c.pair];
            let Enforcement::Penalty { stiffness } = pair.law.enforcement else {
                continue;
            };
            let x = local_points(&self.problem.bodies, pair, c.slave, c.segment, u)
                .ok_or_else(|| format!("pair {} has no master segment {:?}", c.pair, c.segment))?;
            let g = gap_xi_length(&x).0.min(0.0);
            p += 0.5 * stiffness * g * g;
            magnitude += 0.5 * stiffness * g * g + stiffness * g.abs() * GAP_ROUNDING * size(&x);
            n += 1;
        }
        Ok((p, floor(n, magnitude)))
    }

    fn step(&mut self, view: &MultibodyStepView<'_>) -> Result<(), String> {
        let bodies = &self.problem.bodies;
        let (u, v, rec) = (view.displacement, view.velocity, view.record);
        let sums = state_sums(bodies, &self.laws, u, v)?;
        let contacts: BTreeMap<(usize, usize), ContactState> = view
            .contacts
            .iter()
            .map(|c| ((c.pair, c.slave), *c))
            .collect();
        let (penalty, penalty_floor) = self.penalty(&contacts, u)?;
        let energy = sums.kinetic + sums.stored + penalty;
        let energy_floor = self.compare_state(&sums, penalty, penalty_floor, rec);
        let load = self.load(if self.problem.scheme == MultibodyScheme::Newmark {
            view.time
        } else {
            view.time + 0.5 * self.k
        });
        let Some(prev) = self.previous.take() else {
            self.audit.initial_energy = energy;
            self.initial_floor = energy_floor;
            self.audit.max_energy_ratio = 1.0;
            self.audit.final_energy_ratio = 1.0;
            self.previous = Some(Previous {
                u: u.to_vec(),
                contacts,
                energy,
                load,
            });
            return Ok(());
        };
        let w = self.works(&prev, &contacts, u)?;
        let (w_ext, ext_floor) = self.external_work(&prev, u, view.time);
        self.compare_works(&w, w_ext, ext_floor, rec);
        self.sign_laws(&w, rec);
        self.energy_laws(&prev, &w, w_ext, ext_floor, energy, energy_floor, rec);
        self.audit.steps += 1;
        self.previous = Some(Previous {
            u: u.to_vec(),
            contacts,
            energy,
            load,
        });
        Ok(())
    }

    /// K, V, E, P, J of the record against the state; returns E's floor.
    fn compare_state(
        &mut self,
        s: &StateSums,
        penalty: f64,
        penalty_floor: f64,
        rec: &MultibodyRecord,
    ) -> f64 {
        let n = 3 * s.terms;
        let (fk, fv) = (floor(n, s.kinetic_size), floor(n, s.stored_size));
        let fe = fk + fv + penalty_floor;
        let energy = [
            (rec.kinetic - s.kinetic).abs() / fk,
            (rec.stored - s.stored).abs() / fv,
            (rec.penalty - penalty).abs() / penalty_floor,
            (rec.energy - (s.kinetic + s.stored + penalty)).abs() / fe,
        ];
        let momentum = [
            (rec.momentum[0] - s.momentum[0]).abs() / floor(n, s.momentum_size[0]),
            (rec.momentum[1] - s.momentum[1]).abs() / floor(n, s.momentum_size[1]),
            (rec.angular_momentum - s.angular).abs() / floor(n, s.angular_size),
        ];
        let a = &mut self.audit;
        a.energy_record_ratio = energy.into_iter().fold(a.energy_record_ratio, max_nan);
        a.momentum_record_ratio = momentum.into_iter().fold(a.momentum_record_ratio, max_nan);
        fe
    }

    /// W_ext = f·d (f at t_{n−½}, or the mean of both ends for Newmark) and its floor.
    fn external_work(&self, prev: &Previous, u: &[f64], t: f64) -> (f64, f64) {
        let f_end = (self.problem.scheme == MultibodyScheme::Newmark).then(|| self.load(t));
        let (mut w, mut magnitude) = (0.0, 0.0);
        for (i, (u1, u0)) in u.iter().zip(&prev.u).enumerate() {
            let f = match &f_end {
                Some(f1) => 0.5 * (prev.load[i] + f1[i]),
                None => prev.load[i],
            };
            let d = u1 - u0;
            w += f * d;
            magnitude += (f * d).abs() + f.abs() * (u0.abs() + u1.abs());
        }
        (w, floor(u.len(), magnitude))
    }

    /// The record's works against the recomputed ones.
    fn compare_works(&mut self, w: &StepWorks, w_ext: f64, ext_floor: f64, rec: &MultibodyRecord) {
        let f_n = floor(w.terms, w.magnitude) + C * f64::EPSILON * w.rounding;
        let f_t = floor(w.friction_terms, w.friction_magnitude);
        let ratios = [
            (rec.normal_work - w.normal).abs() / f_n,
            (rec.activation_work + rec.switch_work - w.set_change).abs()
                / (f_n + w.set_change_unseen),
            (rec.friction_work - w.friction).abs() / f_t,
            (rec.external_work - w_ext).abs() / ext_floor,
        ];
        let a = &mut self.audit;
        a.work_record_ratio = ratios.into_iter().fold(a.work_record_ratio, max_nan);
    }

    /// The sign laws of the step's recomputed works (module docs).
    fn sign_laws(&mut self, w: &StepWorks, rec: &MultibodyRecord) {
        let newton = C * f64::EPSILON * rec.identity_scale + rec.newton_bound;
        let a = &mut self.audit;
        if w.entries > 0 {
            a.entry_steps += 1;
            a.entry_work_ratio = max_nan(
                a.entry_work_ratio,
                w.entry_positive / (w.entry_floor + newton).max(f64::MIN_POSITIVE),
            );
        }
        if w.friction_terms > 0 {
            a.friction_steps += 1;
            let f = C * f64::EPSILON * w.friction_magnitude + newton;
            a.friction_sign_ratio =
                max_nan(a.friction_sign_ratio, w.friction / f.max(f64::MIN_POSITIVE));
        }
        if w.releases > 0 {
            a.release_steps += 1;
            let f = C * f64::EPSILON * w.release_floor + newton;
            a.release_work_ratio = max_nan(
                a.release_work_ratio,
                w.release.abs() / f.max(f64::MIN_POSITIVE),
            );
        }
        self.entry_work += w.entry_total;
    }

    /// The recomputed identity and the energy's rise over E_0 + W_ext + the allowed gains.
    #[allow(clippy::too_many_arguments)]
    fn energy_laws(
        &mut self,
        prev: &Previous,
        w: &StepWorks,
        w_ext: f64,
        ext_floor: f64,
        energy: f64,
        energy_floor: f64,
        rec: &MultibodyRecord,
    ) {
        self.slack += floor(w.terms, w.magnitude)
            + C * f64::EPSILON * w.rounding
            + ext_floor
            + w.holding
            + rec.newton_bound
            + C * f64::EPSILON * rec.identity_scale;
        self.identity_sum +=
            energy - prev.energy - (w.normal + w.penalty_unbooked + w.friction + w_ext);
        self.supplied += w_ext;
        self.allowed += w.allowed;
        let e0 = self.audit.initial_energy;
        let tol = (self.slack + energy_floor + self.initial_floor).max(f64::MIN_POSITIVE);
        let a = &mut self.audit;
        a.identity_ratio = max_nan(a.identity_ratio, self.identity_sum.abs() / tol);
        let rise = energy - e0 - self.supplied - self.allowed;
        a.energy_rise_ratio = max_nan(a.energy_rise_ratio, rise / tol);
        let e0 = e0.abs().max(f64::MIN_POSITIVE);
        a.max_energy_ratio = max_nan(a.max_energy_ratio, energy / e0);
        a.final_energy_ratio = energy / e0;
        a.entry_work_relative = self.entry_work / e0;
        a.allowed_gain_relative = self.allowed / e0;
    }
}

impl StateAuditor<'_> {
    /// The recomputed works of the step n − 1 → n from λ at t_n and the gaps of the step's
    /// pairing at both ends (module docs of `super`).
    fn works(
        &self,
        prev: &Previous,
        contacts: &BTreeMap<(usize, usize), ContactState>,
        u: &[f64],
    ) -> Result<StepWorks, String> {
        let bodies = &self.problem.bodies;
        let eps = C * f64::EPSILON;
        let mut w = StepWorks::default();
        let mut penalty_switched = false;
        for (key, c) in contacts {
            let pair = &self.problem.pairs[c.pair];
            let before = prev.contacts.get(key);
            let missing = || format!("pair {} has no master segment {:?}", c.pair, c.segment);
            let x0 = local_points(bodies, pair, c.slave, c.segment, &prev.u).ok_or_else(missing)?;
            let x1 = local_points(bodies, pair, c.slave, c.segment, u).ok_or_else(missing)?;
            let (g0, xi0, l0) = gap_xi_length(&x0);
            let (g1, xi1, _) = gap_xi_length(&x1);
            let sz = size(&x0).max(size(&x1));
            let same = before.is_some_and(|b| b.segment == c.segment);
            let compliant = match pair.law.enforcement {
                Enforcement::Penalty { .. } => {
                    penalty_switched |= before.is_some() && !same;
                    continue;
                }
                Enforcement::Lagrange => false,
                Enforcement::Compliant { .. } => true,
            };
            let lambda = c.lambda_n;
            let work = lambda * (g1 - g0);
            // the state shows a set change for an active constraint not held on the same
            // segment; for the others (inactive at t_n, or held on the same segment at both
            // ends) it cannot tell a switch inside the step from none: their |work| bounds
            // what the record may book as set-change work beyond ours
            if c.active && !(same && before.is_some_and(|b| b.active)) {
                w.set_change += work;
            } else {
                w.set_change_unseen += work.abs();
            }
            let gaps = lambda.abs() * (g0.abs() + g1.abs() + GAP_ROUNDING * sz);
            w.normal += work;
            w.magnitude += work.abs();
            w.terms += 1;
            w.rounding += GAP_ROUNDING * lambda.abs() * sz;
            let held = before.is_some_and(|b| b.active);
            let allow = self.allow_gain.get(c.pair).copied().unwrap_or(false);
            // re-paired from outside: listed on another segment at t_{n−1} with a gap ≥ 0 there
            // (its g₀ against the new line is the master vertex's non-smoothness)
            let repaired = before.is_some_and(|b| !same && b.gap >= 0.0);
            if c.active && !held && repaired {
                w.allowed += work.max(0.0);
            } else if c.active && !held {
                w.entries += 1;
                w.entry_total += work;
                w.entry_positive += work.max(0.0);
                w.entry_floor += eps * gaps;
                if allow {
                    w.allowed += work.max(0.0);
                }
            } else if c.active && !same {
                // a held node's switch: the master vertex's non-smoothness (§8), allowed
                w.allowed += work.max(0.0);
            } else if c.active {
                w.holding += lambda.abs() * (g0.abs() + g1.abs());
                if compliant {
                    w.allowed += work.max(0.0);
                }
            } else if held {
                w.releases += 1;
                w.release += work;
                w.release_floor += gaps;
            }
            if c.lambda_t != 0.0 || (c.active && pair.law.has_friction()) {
                let wt = c.lambda_t * l0 * (xi1 - xi0);
                w.friction += wt;
                w.friction_terms += 1;
                w.friction_magnitude += wt.abs()
                    + c.lambda_t.abs() * (l0 * (xi0.abs() + xi1.abs()) + GAP_ROUNDING * sz);
            }
        }
        // a constraint that left the candidates was released with λ = 0: no work
        w.releases += prev
            .contacts
            .iter()
            .filter(|(key, b)| b.active && !contacts.contains_key(key))
            .count();
        let (p_new, _) = self.penalty(contacts, &prev.u)?;
        let (p_old, _) = self.penalty(&prev.contacts, &prev.u)?;
        let jump = p_new - p_old;
        if penalty_switched && jump != 0.0 {
            w.normal += jump;
            w.set_change += jump;
            w.magnitude += p_new.abs() + p_old.abs();
            w.terms += contacts.len() + prev.contacts.len();
            w.allowed += jump.max(0.0);
        } else {
            w.penalty_unbooked = jump;
        }
        Ok(w)
    }
}

/// The state-recomputed audit's checks of a run (each ≤ 1): the records against the state
/// always; the sign laws where the run had an entry, friction or a release; the recomputed
/// identity and the energy's rise where the scheme claims the energy identity.
pub fn state_audit_checks(label: &str, a: &StateAudit, claims: Claims) -> Vec<Check> {
    let mut checks = vec![
        Check::at_most(
            &format!(
                "{label}: max_n |K, V, E (record) − recomputed from (u, v)| / round-off floor"
            ),
            a.energy_record_ratio,
            1.0,
        ),
        Check::at_most(
            &format!("{label}: max_n |P, J (record) − recomputed from (u, v)| / round-off floor"),
            a.momentum_record_ratio,
            1.0,
        ),
        Check::at_most(
            &format!(
                "{label}: max_n |W_N, its set changes' part, W_T, W_ext (record) − recomputed \
                 from λ, gaps, f·d| / round-off floor"
            ),
            a.work_record_ratio,
            1.0,
        ),
    ];
    if a.entry_steps > 0 {
        checks.push(Check::at_most(
            &format!("{label}: max_n entries' positive work Σ max(0, λ (g₁ − g₀)) / floor (≤ 0)"),
            a.entry_work_ratio,
            1.0,
        ));
    }
    if a.friction_steps > 0 && claims.friction_sign {
        checks.push(Check::at_most(
            &format!("{label}: max_n recomputed friction work Σ λ_T ℓ₀ Δξ / floor (≤ 0)"),
            a.friction_sign_ratio,
            1.0,
        ));
    }
    if a.release_steps > 0 {
        checks.push(Check::at_most(
            &format!("{label}: max_n releases' |work| / floor (= 0)"),
            a.release_work_ratio,
            1.0,
        ));
    }
    if claims.identity {
        checks.push(Check::at_most(
            &format!("{label}: max_n |E_n − E_0 − Σ (W_N + W_T + W_ext)| recomputed / tolerance"),
            a.identity_ratio,
            1.0,
        ));
        checks.push(Check::at_most(
            &format!(
                "{label}: max_n (E_n − E_0 − Σ W_ext − allowed gains) recomputed / tolerance \
                 (E_N/E_0 = {:.6})",
                a.final_energy_ratio
            ),
            a.energy_rise_ratio,
            1.0,
        ));
    }
    checks
}

/// What the state-recomputed audit gate recomputes (its reason).
pub const STATE_AUDIT_NOTE: &str = "the audit recomputed from the state: K = ½ vᵀMv, P and J \
    from a P1 mass assembled in the verification crate, the stored energy by the linear, St \
    Venant–Kirchhoff and neo-Hooke laws written there, the contact works Σ λ_N (g₁ − g₀) and \
    Σ λ_T ℓ₀ (ξ₁ − ξ₀) from the multipliers and the gaps of its own node-to-segment geometry, \
    W_ext = f·d — from the displacements, velocities and multipliers only; the solver's records \
    must agree with them within C ε (N + 30) Σ|terms|, an entering constraint's work must be ≤ 0, \
    friction's ≤ 0, a release's 0, and (energy–momentum) E never above E₀ + W_ext + the booked, \
    allowed gains (docs/multibody.md, \"The audit recomputed from the state\")";

/// The gate of a case's state-recomputed audit checks.
pub fn state_audit_gate(name: &str, checks: Vec<Check>) -> GateVerdict {
    GateVerdict::from_checks(name.to_string(), "energy audit", checks, STATE_AUDIT_NOTE)
}
