//! The energy audit of a dynamic run: every step records the energies, the works and the
//! residuals of the discrete energy identities (Barboteu–Danan–Sofonea, "BDS", §1.6.3;
//! Hauret–Le Tallec, "HLT", Prop. 3.7), each quantity computed from its own definition.
//!
//! With E_n = ½ v_nᵀ M v_n + 𝒲(u_n) (BDS (1.47); v = δu for the midpoint-type schemes, the
//! Newmark velocity otherwise) and, per contact node i over the step n (d = u_n − u_{n−1}; the
//! forces are those the scheme applies over the step: at t_{n−1/2} / t_n for the midpoint type,
//! the trapezoidal mean for Newmark):
//!
//! | quantity | definition | from |
//! |---|---|---|
//! | p_{i,n} | o_i + s_i u_{ν,i,n} | the displacements (not the Newton iterate's p) |
//! | Φ_n | Σ_i w_i (r/2) (p_{i,n})_+², BDS (1.49) | the penetrations, written here (not the contact module's energy) |
//! | W_ext | dᵀ f̄ | the load |
//! | W_c | Σ_i ξ_i·d_i, ξ_i = compliance force − s_i w_i λ̄_i e_ν | every contact force applied |
//! | W_r | Σ_i ξ^r_i·d_i | the compliance forces alone (the tilt of (3.69) included) |
//! | D_b | −Σ_i w_i λ̄_i (p_{i,n} − p_{i,n−1}) | the multipliers λ̄ ≥ 0 of the unilateral constraint (Signorini, stage (b) of the IPM, BDS (1.44)–(1.45)) |
//! | W_τ | Σ_i ξ_{τ,i} d_{τ,i} | the friction forces |
//!
//! the residuals of one step are
//!
//! - (1.48) r_1.1 = (E_n − E_{n−1}) − W_ext − W_c − W_τ                  (BDS Prop. 1.1)
//! - (3.7)  r_3.7 = W_r + (Φ_n − Φ_{n−1})                                (HLT Prop. 3.7: the compliance force's work is exact)
//! - (1.49) r_1.3 = (E_n + Φ_n − E_{n−1} − Φ_{n−1}) − W_ext − W_τ − D_b (BDS Prop. 1.3)
//!
//! (1.49) uses no contact force: E, Φ, the load's work, the friction work and the multipliers'
//! D_b. BDS obtain Prop. 1.3 from Prop. 1.1 and the exact work of the compliance force, so in
//! exact arithmetic r_1.3 = r_1.1 + r_3.7 when the contact force is compliance plus multiplier:
//! (1.49) is the balance the paper states, (1.48) and (3.7) say which part of it failed. D_b ≤ 0
//! because an active node is held at its depth g (Signorini: g = 0) from p_{n−1} ≤ g with λ ≥ 0;
//! W_τ ≤ 0 because friction opposes the slip.
//!
//! **Tolerance.** In exact arithmetic the residuals of a conserving run vanish. Computed, a
//! step's residual has two parts:
//!
//! 1. The Newton method stops at a residual R of the step equation with ‖R‖_∞ ≤ τ s (τ = 1e−12
//!    relative to the equation's largest term); the identity then misses the work d·R of that
//!    residual, bounded by ν_j = ‖d_j‖₁ ‖R_j‖_∞ (the solver reports ‖R‖_∞; in its unknowns:
//!    the contact dofs on the condensed path). Not round-off: the solver's tolerance.
//! 2. Round-off, at most a few ε times the size s_j of the terms the step rounds. That size is
//!    not only the energy's scale E_ref (max_n (E_n + Φ_n) and the works' magnitudes): the
//!    stiffness force K u_{j−1} of the step (and the internal force of a hyperelastic body) is
//!    evaluated at the magnitude |K| |u| even when the net force is small — a bar translating as
//!    a rigid body has K u = 0, evaluated as a sum of terms (E A / h) u_i — and its round-off
//!    does work over the increment d. So s_j = E_ref + ‖K‖_∞ ‖u_j‖₂ ‖d_j‖₂ (‖K‖_∞ the largest
//!    absolute row sum of the stiffness at rest; ‖d‖₂ ‖|K||u|‖₂ bounds Σ_i |d_i| (|K||u|)_i).
//!
//! 3. The evaluation of the energies E_n and E_0 themselves: sums over the D dofs, rounded at
//!    most at D ε E_ref (a sum of D terms, Higham's γ_D); these do not accumulate (they
//!    telescope in the drift).
//!
//! The rounding errors of consecutive steps are not independent (the state changes little from
//! step to step, and so does the pattern of its rounding), so they add up coherently in the drift
//! R_n = Σ_{j≤n} r_j:
//!
//!   |R_n| ≤ C ε (D E_ref + Σ_{j≤n} s_j) + Σ_{j≤n} ν_j       ([`ROUND_OFF_CONSTANT`] C).
//!
//! A random walk (C ε √N max_j s_j) is contradicted by the measurement: at a fixed mesh the drift
//! does not shrink as N grows with N·‖d‖ fixed, and on the Signorini bar's fine-step sweep
//! (M = 25, N = 19200) it is 42 ε √N E_ref (docs/dynamic.md §2). A step's dissipated work (D_b,
//! W_τ) must be ≤ C ε s_n + ν_n.

use serde::Serialize;

/// C of the round-off part C ε Σ_j s_j of the audit's tolerance.
///
/// A step's identity sums one evaluation of each of its terms (the stiffness product and the
/// step solve, the updates u_n = u_{n−1} + d and δu_n = (2/k) d − δu_{n−1}, the energies and the
/// works), each rounded to nearest with a relative error of at most ε/2 and of either sign: a few
/// such errors on terms of size ≤ s_j give C = 2. The largest measured ratio of a drift to its
/// tolerance over every dynamic case is stated in docs/dynamic.md §2.
pub const ROUND_OFF_CONSTANT: f64 = 2.0;

/// The tolerance C ε Σ_j s_j of a drift, given the summed round-off scale Σ_j s_j.
pub fn round_off_tolerance(summed_scale: f64) -> f64 {
    ROUND_OFF_CONSTANT * f64::EPSILON * summed_scale
}

/// The compliance energy w (r/2) (p)_+² of a node of weight w and stiffness r at penetration p
/// (BDS (1.49); the penalty energy of HLT §3.6.1, 1/(2η) g_+² with η = 1/r).
pub fn compliance_energy(weight: f64, stiffness: f64, penetration: f64) -> f64 {
    let p = if penetration > 0.0 { penetration } else { 0.0 };
    weight * stiffness * p * p / 2.0
}

/// One contact node over one step, as the audit sees it (see the module docs for the sources).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NodeStep {
    /// w_i.
    pub weight: f64,
    /// s_i: p = o_i + s_i u_ν.
    pub sign: f64,
    /// r of the node's compliance force (none: Signorini).
    pub stiffness: Option<f64>,
    /// p_{i,n−1} and p_{i,n}, from the displacements.
    pub penetration: [f64; 2],
    /// The increments (d_ν, d_τ) of the node's unknowns over the step (d_τ = 0 without one).
    pub increment: [f64; 2],
    /// The generalized compliance force applied over the step, on (ν, τ).
    pub compliance: [f64; 2],
    /// λ̄ per weight: the multiplier of the unilateral constraint applied over the step.
    pub multiplier: f64,
    /// The generalized friction force applied over the step, on τ.
    pub friction: f64,
}

impl NodeStep {
    /// Φ_i at the end of the step minus Φ_i at its start.
    fn energy_change(&self) -> f64 {
        let r = self.stiffness.unwrap_or(0.0);
        compliance_energy(self.weight, r, self.penetration[1])
            - compliance_energy(self.weight, r, self.penetration[0])
    }

    /// The compliance force's work ξ^r·d.
    fn compliance_work(&self) -> f64 {
        self.compliance[0] * self.increment[0] + self.compliance[1] * self.increment[1]
    }

    /// The work of the multiplier's generalized force −s w λ̄ on the normal unknown.
    fn multiplier_force_work(&self) -> f64 {
        -self.sign * self.weight * self.multiplier * self.increment[0]
    }

    /// D_b,i = −w λ̄ (p_n − p_{n−1}).
    fn constraint_work(&self) -> f64 {
        -self.weight * self.multiplier * (self.penetration[1] - self.penetration[0])
    }
}

/// What one step gives the audit.
#[derive(Debug, Clone, Copy)]
pub struct StepInput<'a> {
    pub step: usize,
    pub time: f64,
    /// ½ v_nᵀ M v_n.
    pub kinetic: f64,
    /// 𝒲(u_n).
    pub elastic: f64,
    /// W_ext = dᵀ f̄.
    pub external_work: f64,
    /// ‖K‖_∞ ‖u_n‖₂ ‖d‖₂: the work of the stiffness force's terms over the step (module docs).
    pub stiffness_work: f64,
    /// ‖d‖₁ ‖R‖_∞ of the step's last Newton solve (its unknowns): a bound of the work d·R of
    /// the residual R at which Newton stopped.
    pub newton_work: f64,
    pub nodes: &'a [NodeStep],
}

/// One step of the audit.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct AuditRecord {
    pub step: usize,
    pub time: f64,
    /// ½ vᵀ M v at t_n.
    pub kinetic: f64,
    /// 𝒲(u_n).
    pub elastic: f64,
    /// Φ_n.
    pub penalty: f64,
    /// Cumulative works since t = 0: W_ext, W_c (every contact force), W_τ, D_b (≤ 0).
    pub external_work: f64,
    pub contact_work: f64,
    pub friction_work: f64,
    pub constraint_work: f64,
    /// This step's W_τ and D_b (each must be ≤ 0).
    pub step_friction_work: f64,
    pub step_constraint_work: f64,
    /// The identity residuals of this step (absolute).
    pub residual_1_48: f64,
    pub residual_1_49: f64,
    pub residual_3_7: f64,
    /// The running sums R_n of the residuals since t = 0 (absolute): the drift of each balance.
    pub drift_1_48: f64,
    pub drift_1_49: f64,
    pub drift_3_7: f64,
    /// ‖K‖_∞ ‖u_n‖₂ ‖d‖₂ of this step (the round-off scale's stiffness term).
    pub stiffness_work: f64,
    /// ‖d‖₁ ‖R‖_∞ of this step's last Newton solve (the stopping error's work bound).
    pub newton_work: f64,
    /// Σ w_i N_i (the total normal contact force) and the largest penetration at t_n.
    pub contact_force: f64,
    pub max_penetration: f64,
    /// Σ w_i T_i.
    pub friction_force: f64,
    pub newton_iterations: usize,
    /// Whether stage (b) of the IPM ran.
    pub stage_b: bool,
    pub active_nodes: usize,
}

impl AuditRecord {
    /// The first of the record's quantities that is not finite, with its value.
    pub fn first_non_finite(&self) -> Option<(&'static str, f64)> {
        [
            ("kinetic energy", self.kinetic),
            ("stored energy", self.elastic),
            ("penalty energy", self.penalty),
            ("external work", self.external_work),
            ("contact work", self.contact_work),
            ("friction work", self.friction_work),
            ("constraint work", self.constraint_work),
            ("round-off scale of the stiffness work", self.stiffness_work),
            ("round-off scale of the Newton work", self.newton_work),
            ("contact force", self.contact_force),
            ("penetration", self.max_penetration),
            ("friction force", self.friction_force),
        ]
        .into_iter()
        .find(|(_, v)| !v.is_finite())
    }
}

impl AuditRecord {
    /// E_n = kinetic + elastic.
    pub fn energy(&self) -> f64 {
        self.kinetic + self.elastic
    }

    /// The record of the initial state: E_0 and Φ_0 = Σ_i Φ_i(p_{i,0}) (`nodes`: each node's
    /// weight, stiffness and penetration p_0 in `penetration[1]`).
    pub fn initial(kinetic: f64, elastic: f64, nodes: &[NodeStep]) -> Self {
        Self {
            kinetic,
            elastic,
            penalty: nodes
                .iter()
                .map(|n| compliance_energy(n.weight, n.stiffness.unwrap_or(0.0), n.penetration[1]))
                .sum(),
            ..Default::default()
        }
    }

    /// The record after a step from `self` (the previous record): energies, works, residuals and
    /// drifts from their definitions (module docs). The diagnostics (forces, penetration,
    /// iterations) are the caller's.
    pub fn after(&self, input: &StepInput<'_>) -> Self {
        let (mut w_c, mut w_r, mut w_f, mut d_b, mut d_phi) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let mut penalty = 0.0;
        for n in input.nodes {
            let compliance = n.compliance_work();
            w_c += compliance + n.multiplier_force_work();
            if n.stiffness.is_some() {
                w_r += compliance;
            }
            w_f += n.friction * n.increment[1];
            d_b += n.constraint_work();
            d_phi += n.energy_change();
            penalty += compliance_energy(n.weight, n.stiffness.unwrap_or(0.0), n.penetration[1]);
        }
        let w_ext = input.external_work;
        let de = (input.kinetic + input.elastic) - self.energy();
        let r_48 = de - w_ext - w_c - w_f;
        let r_37 = w_r + d_phi;
        let r_49 = de + d_phi - w_ext - w_f - d_b;
        Self {
            step: input.step,
            time: input.time,
            kinetic: input.kinetic,
            elastic: input.elastic,
            penalty,
            external_work: self.external_work + w_ext,
            contact_work: self.contact_work + w_c,
            friction_work: self.friction_work + w_f,
            constraint_work: self.constraint_work + d_b,
            step_friction_work: w_f,
            step_constraint_work: d_b,
            residual_1_48: r_48,
            residual_1_49: r_49,
            residual_3_7: r_37,
            drift_1_48: self.drift_1_48 + r_48,
            drift_1_49: self.drift_1_49 + r_49,
            drift_3_7: self.drift_3_7 + r_37,
            stiffness_work: input.stiffness_work,
            newton_work: input.newton_work,
            ..Default::default()
        }
    }
}

/// The audit of a run (record 0 is the initial state).
#[derive(Debug, Clone, Default, Serialize)]
pub struct EnergyAudit {
    /// The body's free dofs D (the energies are sums over them: their evaluation rounds at
    /// D ε E_ref).
    pub dofs: usize,
    pub records: Vec<AuditRecord>,
}

/// Largest residuals and drifts of a run, relative to the energy scale, and each gated
/// quantity as a fraction of its round-off tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct AuditSummary {
    /// E_ref = max_n (E_n + Φ_n) and the magnitudes of the works.
    pub energy_scale: f64,
    /// D E_ref + Σ_{j≤N} s_j, s_j = E_ref + ‖K‖_∞ ‖u_j‖₂ ‖d_j‖₂: the summed scale of
    /// round-off (module docs).
    pub roundoff_scale: f64,
    /// Σ_{j≤N} ‖d_j‖₁ ‖R_j‖_∞: the summed bound of the Newton stopping error's work.
    pub newton_work: f64,
    /// max_n |r_n| / E_ref per identity (one step).
    pub max_residual_1_48: f64,
    pub max_residual_1_49: f64,
    pub max_residual_3_7: f64,
    /// max_n |R_n| / E_ref per identity (the running sums).
    pub max_drift_1_48: f64,
    pub max_drift_1_49: f64,
    pub max_drift_3_7: f64,
    /// Largest step friction work and constraint work (absolute; must be ≤ 0).
    pub max_step_friction_work: f64,
    pub max_step_constraint_work: f64,
    /// R_N of (1.49): (E + Φ)_N − (E + Φ)_0 − W_ext − W_τ − D_b over the run (absolute).
    pub drift_1_49: f64,
    pub steps: usize,
    /// What the audit gates, each ≤ 1 when it holds: max_n |R_n| / (C ε Σ_{j≤n} s_j +
    /// Σ_{j≤n} ν_j) per identity, and max_n of the step friction and constraint work /
    /// (C ε s_n + ν_n).
    pub drift_ratio_1_48: f64,
    pub drift_ratio_1_49: f64,
    pub drift_ratio_3_7: f64,
    pub friction_work_ratio: f64,
    pub constraint_work_ratio: f64,
    /// The steps whose friction work W_τ, and whose constraint work D_b, is not exactly 0: where
    /// both are 0 the sign laws have nothing to test (a frictionless run, no stage (b)).
    pub friction_steps: usize,
    pub constraint_steps: usize,
}

impl AuditSummary {
    /// The tolerance of one run's drift at its end, relative to E_ref:
    /// (C ε (D E_ref + Σ_j s_j) + Σ_j ν_j) / E_ref.
    pub fn tolerance(&self) -> f64 {
        (round_off_tolerance(self.roundoff_scale) + self.newton_work) / self.energy_scale
    }

    /// The worst of two summaries: each ratio, residual and drift the larger (each relative to
    /// its own run's scales), the most steps, the larger final drift.
    pub fn worst(&self, other: &Self) -> Self {
        let max = |a: f64, b: f64| a.max(b);
        Self {
            energy_scale: self.energy_scale.min(other.energy_scale),
            roundoff_scale: max(self.roundoff_scale, other.roundoff_scale),
            newton_work: max(self.newton_work, other.newton_work),
            max_residual_1_48: max(self.max_residual_1_48, other.max_residual_1_48),
            max_residual_1_49: max(self.max_residual_1_49, other.max_residual_1_49),
            max_residual_3_7: max(self.max_residual_3_7, other.max_residual_3_7),
            max_drift_1_48: max(self.max_drift_1_48, other.max_drift_1_48),
            max_drift_1_49: max(self.max_drift_1_49, other.max_drift_1_49),
            max_drift_3_7: max(self.max_drift_3_7, other.max_drift_3_7),
            max_step_friction_work: max(self.max_step_friction_work, other.max_step_friction_work),
            max_step_constraint_work: max(
                self.max_step_constraint_work,
                other.max_step_constraint_work,
            ),
            drift_1_49: if other.drift_1_49.abs() > self.drift_1_49.abs() {
                other.drift_1_49
            } else {
                self.drift_1_49
            },
            steps: self.steps.max(other.steps),
            drift_ratio_1_48: max(self.drift_ratio_1_48, other.drift_ratio_1_48),
            drift_ratio_1_49: max(self.drift_ratio_1_49, other.drift_ratio_1_49),
            drift_ratio_3_7: max(self.drift_ratio_3_7, other.drift_ratio_3_7),
            friction_work_ratio: max(self.friction_work_ratio, other.friction_work_ratio),
            constraint_work_ratio: max(self.constraint_work_ratio, other.constraint_work_ratio),
            friction_steps: self.friction_steps + other.friction_steps,
            constraint_steps: self.constraint_steps + other.constraint_steps,
        }
    }
}

impl EnergyAudit {
    /// The scale E_ref = max_n (E_n + Φ_n, |works|).
    pub fn energy_scale(&self) -> f64 {
        self.records
            .iter()
            .map(|r| {
                (r.energy() + r.penalty)
                    .abs()
                    .max(r.external_work.abs())
                    .max(r.contact_work.abs())
                    .max(r.friction_work.abs())
            })
            .fold(f64::MIN_POSITIVE, f64::max)
    }

    /// The summed round-off scale D E_ref + Σ_{1≤j≤n} s_j, s_j = E_ref + ‖K‖_∞ ‖u_j‖₂ ‖d_j‖₂,
    /// at every record (module docs).
    pub fn roundoff_scales(&self) -> Vec<f64> {
        let e_ref = self.energy_scale();
        let mut sum = self.dofs as f64 * e_ref;
        self.records
            .iter()
            .map(|r| {
                if r.step > 0 {
                    sum += e_ref + r.stiffness_work;
                }
                sum
            })
            .collect()
    }

    /// The tolerance of the drift at every record: C ε (D E_ref + Σ_{j≤n} s_j) + Σ_{j≤n} ν_j.
    pub fn drift_tolerances(&self) -> Vec<f64> {
        let mut newton = 0.0;
        self.roundoff_scales()
            .into_iter()
            .zip(&self.records)
            .map(|(sum, r)| {
                newton += r.newton_work;
                round_off_tolerance(sum) + newton
            })
            .collect()
    }

    /// The summary of the run's residuals.
    pub fn summary(&self) -> AuditSummary {
        let scale = self.energy_scale();
        let tolerances = self.drift_tolerances();
        let mut s = AuditSummary {
            energy_scale: scale,
            roundoff_scale: self.roundoff_scales().last().copied().unwrap_or(0.0),
            newton_work: self.records.iter().map(|r| r.newton_work).sum(),
            steps: self.records.len().saturating_sub(1),
            max_step_friction_work: f64::NEG_INFINITY,
            max_step_constraint_work: f64::NEG_INFINITY,
            friction_work_ratio: f64::NEG_INFINITY,
            constraint_work_ratio: f64::NEG_INFINITY,
            ..Default::default()
        };
        for (r, drift_tol) in self.records.iter().zip(&tolerances).skip(1) {
            s.max_residual_1_48 = s.max_residual_1_48.max(r.residual_1_48.abs() / scale);
            s.max_residual_1_49 = s.max_residual_1_49.max(r.residual_1_49.abs() / scale);
            s.max_residual_3_7 = s.max_residual_3_7.max(r.residual_3_7.abs() / scale);
            s.max_drift_1_48 = s.max_drift_1_48.max(r.drift_1_48.abs() / scale);
            s.max_drift_1_49 = s.max_drift_1_49.max(r.drift_1_49.abs() / scale);
            s.max_drift_3_7 = s.max_drift_3_7.max(r.drift_3_7.abs() / scale);
            s.friction_steps += usize::from(r.step_friction_work != 0.0);
            s.constraint_steps += usize::from(r.step_constraint_work != 0.0);
            s.max_step_friction_work = s.max_step_friction_work.max(r.step_friction_work);
            s.max_step_constraint_work = s.max_step_constraint_work.max(r.step_constraint_work);
            // the gated ratios: each drift against its tolerance, each step work against
            // C ε s_n + ‖d_n‖₁ ‖R_n‖_∞
            s.drift_ratio_1_48 = s.drift_ratio_1_48.max(r.drift_1_48.abs() / drift_tol);
            s.drift_ratio_1_49 = s.drift_ratio_1_49.max(r.drift_1_49.abs() / drift_tol);
            s.drift_ratio_3_7 = s.drift_ratio_3_7.max(r.drift_3_7.abs() / drift_tol);
            let step_tol = round_off_tolerance(scale + r.stiffness_work) + r.newton_work;
            s.friction_work_ratio = s.friction_work_ratio.max(r.step_friction_work / step_tol);
            s.constraint_work_ratio = s
                .constraint_work_ratio
                .max(r.step_constraint_work / step_tol);
        }
        if s.steps == 0 {
            s.max_step_friction_work = 0.0;
            s.max_step_constraint_work = 0.0;
            s.friction_work_ratio = 0.0;
            s.constraint_work_ratio = 0.0;
        }
        s.drift_1_49 = self.records.last().map_or(0.0, |r| r.drift_1_49);
        s
    }

    /// Whether every number of every audit record is finite (no NaN or ∞ was recorded).
    pub fn is_finite(&self) -> bool {
        self.records.iter().all(|r| {
            [
                r.time,
                r.kinetic,
                r.elastic,
                r.penalty,
                r.external_work,
                r.contact_work,
                r.friction_work,
                r.constraint_work,
                r.step_friction_work,
                r.step_constraint_work,
                r.residual_1_48,
                r.residual_1_49,
                r.residual_3_7,
                r.contact_force,
                r.max_penetration,
                r.friction_force,
            ]
            .iter()
            .all(|v| v.is_finite())
        })
    }

    /// The drift R_n of the balance (1.49) at every record, (E + Φ)_n − (E + Φ)_0 − W_ext − W_τ −
    /// D_b (zero for a conserving run; the energy error of the midpoint rule on a hyperelastic
    /// body).
    pub fn balance_drift(&self) -> Vec<(f64, f64)> {
        self.records
            .iter()
            .map(|r| (r.time, r.drift_1_49))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    //! The audit on one step of a contact node, with the solver's own force functions: each
    //! residual vanishes for the exact ingredients and fails when one is wrong — (3.7) and (1.49)
    //! for an energy-consistent force with a wrong factor, and for a tilted force (3.69) whose
    //! correction uses a wrong energy (the audit's Φ is its own, so the tilt cannot absorb it);
    //! (1.48) and (1.49) for an energy change no force did (a non-conserving internal force) —
    //! and D_b has the sign of the multiplier's work, computed from the penetrations.
    use super::*;
    use crate::contact::compliance::{energy_consistent, tilted_correction};

    const W: f64 = 0.5;
    const R: f64 = 30.0;
    const SIGN: f64 = -1.0;

    /// A node entering the foundation from p = −0.1 to 0.2 (s = −1: d_ν = −0.3) under the
    /// energy-consistent force of BDS (1.46) times `factor`.
    fn entering(factor: f64) -> NodeStep {
        let (q, p) = (-0.1, 0.2);
        let n = factor * energy_consistent(R, q, p).value;
        NodeStep {
            weight: W,
            sign: SIGN,
            stiffness: Some(R),
            penetration: [q, p],
            increment: [(p - q) / SIGN, 0.0],
            compliance: [-SIGN * W * n, 0.0],
            multiplier: 0.0,
            friction: 0.0,
        }
    }

    /// The same node sliding by d_τ = 0.4 while it enters, under the HLT (3.69) force whose
    /// correction is computed for the stiffness `r_in_force` (R: the exact force).
    fn tilted(r_in_force: f64) -> NodeStep {
        let (q, p, dt) = (-0.1, 0.2, 0.4);
        let dn = (p - q) / SIGN;
        // ν·δφ = −s d_ν, |δφ|² = d_ν² + d_τ²
        let (lam, c) = tilted_correction(r_in_force, q, p, -SIGN * dn, dn * dn + dt * dt);
        NodeStep {
            increment: [dn, dt],
            compliance: [W * (-SIGN * lam + c * dn), W * c * dt],
            ..entering(1.0)
        }
    }

    /// One step of a body that takes exactly the work the node's force did, plus `energy_error`.
    fn step(node: NodeStep, energy_error: f64) -> AuditRecord {
        let before = AuditRecord::initial(
            1.0,
            0.5,
            &[NodeStep {
                penetration: [0.0, node.penetration[0]],
                ..node
            }],
        );
        let work = node.compliance[0] * node.increment[0] + node.compliance[1] * node.increment[1];
        let input = StepInput {
            step: 1,
            time: 0.1,
            kinetic: 1.0 + work + energy_error,
            elastic: 0.5,
            external_work: 0.0,
            stiffness_work: 0.0,
            newton_work: 0.0,
            nodes: &[node],
        };
        let after = before.after(&input);
        assert!((after.penalty - compliance_energy(W, R, 0.2)).abs() < 1e-15);
        after
    }

    #[test]
    fn exact_ingredients_give_zero_residuals() {
        for node in [entering(1.0), tilted(R)] {
            let r = step(node, 0.0);
            for v in [r.residual_1_48, r.residual_1_49, r.residual_3_7] {
                assert!(v.abs() < 1e-15, "{r:?}");
            }
        }
    }

    #[test]
    fn a_wrong_contact_force_factor_fails_3_7_and_1_49_but_not_1_48() {
        // the trajectory is consistent with the force applied, whose work is not ΔΦ
        let r = step(entering(1.01), 0.0);
        assert!(r.residual_1_48.abs() < 1e-15, "{r:?}");
        assert!(r.residual_3_7.abs() > 1e-3, "{r:?}");
        assert!(r.residual_1_49.abs() > 1e-3, "{r:?}");
    }

    #[test]
    fn a_tilted_force_corrected_with_a_wrong_energy_fails_3_7() {
        // (3.69)'s correction restores the work of the energy it is given: given (r/2)·1.01 p²,
        // its work is that, and the audit's own Φ = (r/2) p² shows the difference
        let r = step(tilted(1.01 * R), 0.0);
        assert!(r.residual_1_48.abs() < 1e-15, "{r:?}");
        assert!(r.residual_3_7.abs() > 1e-3, "{r:?}");
        assert!(r.residual_1_49.abs() > 1e-3, "{r:?}");
    }

    #[test]
    fn an_energy_change_no_force_did_fails_1_48_and_1_49_but_not_3_7() {
        // a non-conserving internal force: E changes by 1e-3 more than the works
        let r = step(entering(1.0), 1e-3);
        assert!((r.residual_1_48 - 1e-3).abs() < 1e-15, "{r:?}");
        assert!((r.residual_1_49 - 1e-3).abs() < 1e-15, "{r:?}");
        assert!(r.residual_3_7.abs() < 1e-15, "{r:?}");
    }

    #[test]
    fn constraint_work_comes_from_the_multiplier_and_the_penetrations() {
        // a Signorini node (s = −1: Δp = −d_ν) caught at p = 0 from p = −0.05 by λ = 2:
        // D_b = −w λ (0 + 0.05) < 0, the work of the multiplier's force −s w λ on d_ν; a node
        // "held" from p = 0.05 > g back to 0 (a projection inconsistent with its trigger) would
        // give D_b > 0
        let caught = NodeStep {
            weight: 0.5,
            sign: -1.0,
            stiffness: None,
            penetration: [-0.05, 0.0],
            increment: [-0.05, 0.0],
            multiplier: 2.0,
            ..Default::default()
        };
        assert!((caught.constraint_work() + 0.05).abs() < 1e-16);
        assert!((caught.multiplier_force_work() - caught.constraint_work()).abs() < 1e-16);
        let pulled_back = NodeStep {
            penetration: [0.05, 0.0],
            increment: [0.05, 0.0],
            ..caught
        };
        assert!(pulled_back.constraint_work() > 0.0);
    }

    #[test]
    fn the_tolerance_sums_the_scale_of_every_step() {
        // a 2-dof body, two steps of scale E_ref = 1.5 (E + Φ), the second with a stiffness work
        // of 10
        let mut audit = EnergyAudit {
            dofs: 2,
            ..Default::default()
        };
        audit.records.push(AuditRecord::initial(1.0, 0.5, &[]));
        for w in [0.0, 10.0] {
            let prev = *audit.records.last().unwrap();
            let input = StepInput {
                step: prev.step + 1,
                time: 0.0,
                kinetic: 1.0,
                elastic: 0.5,
                external_work: 0.0,
                stiffness_work: w,
                newton_work: 0.0,
                nodes: &[],
            };
            audit.records.push(prev.after(&input));
        }
        // the two energies' evaluation (D E_ref = 2 × 1.5), then s_1 = 1.5, s_2 = 11.5
        assert_eq!(audit.roundoff_scales(), vec![3.0, 4.5, 16.0]);
        let s = audit.summary();
        assert_eq!(s.roundoff_scale, 16.0);
        assert!((s.tolerance() - ROUND_OFF_CONSTANT * f64::EPSILON * 16.0 / 1.5).abs() < 1e-30);
    }
}
