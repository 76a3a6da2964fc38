//! The audit of a multibody run: per step the balance quantities of EM Table 1 and the works
//! that change them (docs/multibody.md §6).
//!
//! - Linear momentum P = Σ_I (M v)_I and angular momentum about the origin J = Σ_I x_I × (M v)_I
//!   (consistent mass: (M v)_I = Σ_J M_IJ v_J).
//! - Total energy E = ½ vᵀ M v + Σ 𝒲 (+ the penalty energy Σ P(π) with penalty enforcement).
//! - The works of the step: the normal constraints W_N = Σ λ_N (g₁ − g₀), friction
//!   W_T = Σ λ_T (τ₁ − τ₀) (≤ 0: the slip force opposes the slip), the loads W_ext.
//!
//! The energy–momentum scheme satisfies E_{n+1} − E_n = W_N + W_T + W_ext to round-off in every
//! step (its forces are discrete gradients); with no load and no foundation it conserves P and J
//! to round-off in every step, friction included (the friction forces are internal and
//! torque-free). W_N vanishes while the active set keeps its constraints (g₀ = g₁ = 0): the energy
//! is conserved in such steps. A constraint that becomes active within a step (g₀ > 0, g₁ = 0)
//! does the work −λ_N g₀ (EM §6.2: the consistency condition is violated at activation); the
//! audit reports it as `activation_work`. The midpoint rule and Newmark do not satisfy the energy
//! identity: its residual is their energy error.
//!
//! **Tolerances** (the dynamic audit's model, `model::dynamic::audit`): a step's residual has a
//! Newton part — the step equation is solved to a residual R, whose work d·R and impulse k ΣR the
//! identities miss: ν_n = ‖d‖₁ ‖R_u‖_∞ + Σ |λ| |C| / c, k ‖R_u‖₁ and k Σ |x| |R_u| — and a
//! round-off part, a few ε times the magnitudes the step rounds: s_n = the energies' and works'
//! magnitudes + Σ_i s_i |d_i| (s_i the magnitude of row i's terms) + 2 Σ |λ| |x| (a gap or a
//! tangential coordinate is computed from coordinates of size |x|, so it carries a round-off
//! ε |x| whatever its value, and a multiplier's work λ ε |x|); for the momenta k Σ_i s_i
//! and k Σ_i |x| s_i, and the sums |(M v)_I| that P and J are computed from. The drifts since
//! t = 0 are gated against C ε Σ_{j≤n} s_j + Σ_{j≤n} ν_j with C = [`ROUND_OFF_CONSTANT`].

use serde::Serialize;

/// C of the round-off part C ε Σ_j s_j of the audit's tolerances (as in the dynamic audit: a few
/// rounded evaluations of each term per step, each within ε/2 of either sign).
pub const ROUND_OFF_CONSTANT: f64 = 2.0;

/// A constraint's positive set-change work: (pair, slave node, master segment or None for the
/// foundation, whether it switched segment (else it activated), the work λ_N (g₁ − g₀)).
pub type PositiveWork = (usize, usize, Option<usize>, bool, f64);

/// Whether `x` is NaN or ±∞ (a value left out of a serialized record).
fn not_finite(x: &f64) -> bool {
    !x.is_finite()
}

/// One step's audit (record 0: the initial state).
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct MultibodyRecord {
    pub step: usize,
    pub time: f64,
    pub kinetic: f64,
    pub stored: f64,
    pub penalty: f64,
    /// kinetic + stored + penalty.
    pub energy: f64,
    pub momentum: [f64; 2],
    pub angular_momentum: f64,
    /// Σ λ_N (g₁ − g₀) of the step; with the penalty, P's jumps where a segment changed.
    pub normal_work: f64,
    /// The part of `normal_work` done by constraints that became active in the step.
    pub activation_work: f64,
    /// The part done by constraints whose master segment changed in the step (docs §3.1).
    pub switch_work: f64,
    /// Σ |λ_N| (|g₀| + |g₁|) over the constraints active at both ends of the step: what their
    /// work W_N can be where they only hold (g₀ and g₁ are zero to the constraint's tolerance).
    pub holding_gap_work: f64,
    /// Σ λ_T (τ₁ − τ₀) (≤ 0).
    pub friction_work: f64,
    /// The loads' work over the step.
    pub external_work: f64,
    /// E_{n+1} − E_n − (W_N + W_T + W_ext).
    pub identity_residual: f64,
    /// The round-off scale of the identity: the sum of the magnitudes of its terms.
    pub identity_scale: f64,
    /// What the Newton tolerance allows in the identity: ‖d‖₁ ‖R_u‖_∞ + Σ |λ| |C|/c.
    pub newton_bound: f64,
    /// Σ |(M v)_I| and Σ |x_I| |(M v)_I|: the round-off scales of P and J.
    pub momentum_scale: f64,
    pub angular_scale: f64,
    /// How far the step's Newton residual can move P and J: k ‖R_u‖₁ and k Σ |x| |R_u| (the
    /// midpoint types' M (v_{n+1} − v_n) = k (R_u − forces), and the forces have no resultant and
    /// no moment).
    pub momentum_bound: f64,
    pub angular_bound: f64,
    /// The round-off scales of the step's impulse on P and J: k Σ_i s_i and k Σ_i |x| s_i.
    pub momentum_round_off: f64,
    pub angular_round_off: f64,
    /// Candidates, active constraints, sticking and slipping ones.
    pub candidates: usize,
    pub active: usize,
    pub sticking: usize,
    pub slipping: usize,
    /// Constraints that became active, released, or switched segment in the step.
    pub activated: usize,
    pub released: usize,
    pub switches: usize,
    /// Σ λ_N and Σ λ_T at t_{n+1}.
    pub normal_force: f64,
    pub friction_force: f64,
    /// The smallest gap of a candidate at t_{n+1} (negative: penetration); left out of the
    /// serialized record when not finite (no candidate: +∞).
    #[serde(skip_serializing_if = "not_finite")]
    pub min_gap: f64,
    pub newton_iterations: usize,
    /// Σ max(0, λ_N (g₁ − g₀)) over the multiplier constraints that activated or switched
    /// segment in the step: positive set-change work, which only a node entering from inside the
    /// master does (from outside it is −λ g₀ ≤ 0, docs/multibody.md §4). Flagged by the audit.
    pub positive_set_work: f64,
    /// The part of it not done by held nodes switching segment within the step: entries from
    /// inside the master (a held node's switch at a concave kink of the master gains λ |g₀| with
    /// |g₀| ≤ its distance past the vertex times the kink's angle, and is only flagged).
    pub positive_entry_work: f64,
    /// The entering constraint with the largest such work: (pair, slave node, master segment or
    /// None for the foundation), whether it switched (else it activated), and its work (not
    /// written to results files: an absent value would read as a non-finite number there).
    #[serde(skip)]
    pub positive_worst: Option<PositiveWork>,
}

impl MultibodyRecord {
    /// The first non-finite quantity, if any (a run stops there with a typed error).
    pub fn first_non_finite(&self) -> Option<(&'static str, f64)> {
        [
            ("kinetic energy", self.kinetic),
            ("stored energy", self.stored),
            ("penalty energy", self.penalty),
            ("linear momentum (x)", self.momentum[0]),
            ("linear momentum (y)", self.momentum[1]),
            ("angular momentum", self.angular_momentum),
            ("contact work", self.normal_work),
            ("friction work", self.friction_work),
        ]
        .into_iter()
        .find(|(_, v)| !v.is_finite())
    }

    /// Whether the active set changed in the step (a constraint activated, released or switched).
    pub fn set_changed(&self) -> bool {
        self.activated + self.released + self.switches > 0
    }
}

/// What a whole run's audit shows (the maxima over its steps). The `*_ratio` fields are the
/// quantity over its tolerance (module docs): ≤ 1 is conservation to round-off.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct MultibodySummary {
    pub steps: usize,
    /// max_n |E_n − E_0| / E_0.
    pub energy_drift: f64,
    /// max_n |Σ_{j≤n} r_j| / (C ε Σ_{j≤n} s_j + Σ_{j≤n} ν_j), r the identity's residual.
    pub identity_ratio: f64,
    /// max over steps without a change of the active set of |E_{n+1} − E_n − W_ext − W_T| /
    /// (C ε s_n + ν_n + the holding constraints' gap work): energy conservation (up to the loads'
    /// and friction's work) where no constraint activates, releases or switches.
    pub unchanged_ratio: f64,
    /// The same quantity relative to E_0 (for schemes that do not conserve).
    pub unchanged_relative: f64,
    /// Σ activation work over the run (≤ 0 for constraints that close a gap) and its size
    /// relative to E_0.
    pub activation_work: f64,
    pub activation_relative: f64,
    /// Σ friction work (≤ 0), and max_n of a step's friction work over its round-off tolerance
    /// (≤ 1: friction only dissipates).
    pub friction_work: f64,
    pub friction_ratio: f64,
    /// max_n |P_n − P_0| (the larger component) and |J_n − J_0| over their tolerances; the x and
    /// y components of P apart (one may be conserved while the other meets a foundation or a
    /// load).
    pub momentum_ratio: f64,
    pub momentum_ratio_x: f64,
    pub momentum_ratio_y: f64,
    pub angular_ratio: f64,
    /// max_n |P_n − P_0| / Σ|(Mv)| and |J_n − J_0| / Σ|x||(Mv)| (relative drifts).
    pub momentum_relative: f64,
    pub angular_relative: f64,
    pub max_newton_iterations: usize,
    pub steps_with_contact: usize,
    /// Steps in which the active set changed.
    pub steps_with_set_change: usize,
    /// Σ of the steps' positive set-change work ([`MultibodyRecord::positive_set_work`]) beyond
    /// the step's round-off tolerance, relative to E_0, and the steps that booked it: the audit's
    /// flag for a constraint that re-entered from inside.
    pub positive_set_work_relative: f64,
    pub positive_set_work_steps: usize,
    /// max_n of the energy's rise over the work supplied, (E_n − E_0 − Σ_{j≤n} (W_ext + W_T)) over
    /// its tolerance ([`EnergyGuard`]; 0 when it never rose): > 1 is an energy gain.
    pub energy_rise_ratio: f64,
    /// E_N / E_0.
    pub final_energy_ratio: f64,
}

/// The energy's rise over the work supplied to it, against the identity's tolerance:
///
///   rise_n = E_n − E_0 − Σ_{j≤n} (W_ext,j + W_T,j),
///   tol_n  = C ε Σ_{j≤n} s_j + Σ_{j≤n} (ν_j + Σ |λ_N| (|g₀| + |g₁|) of the holding constraints),
///
/// with C = [`ROUND_OFF_CONSTANT`], s_j the step's round-off scale and ν_j its Newton part (module
/// docs). For the energy–momentum scheme rise_n = Σ_{j≤n} W_N,j up to the identity's residual, so
/// rise_n > tol_n means the constraints did positive work: the energy rose with nothing to supply
/// it. (The activation work −λ g₀ and the holding constraints' round-off gap work are ≤ tol.)
#[derive(Debug, Clone, Copy)]
pub struct EnergyGuard {
    e0: f64,
    supplied: f64,
    scale: f64,
    newton: f64,
}

impl EnergyGuard {
    /// The guard from the initial record.
    pub fn new(first: &MultibodyRecord) -> Self {
        Self {
            e0: first.energy,
            supplied: 0.0,
            scale: first.identity_scale,
            newton: 0.0,
        }
    }

    /// E_0.
    pub fn initial(&self) -> f64 {
        self.e0
    }

    /// Takes the next step's record; returns (rise_n, tol_n).
    pub fn step(&mut self, r: &MultibodyRecord) -> (f64, f64) {
        self.supplied += r.external_work + r.friction_work;
        self.scale +=
            r.identity_scale + r.external_work.abs() + r.friction_work.abs() + r.energy.abs();
        self.newton += r.newton_bound + r.holding_gap_work;
        let rise = r.energy - self.e0 - self.supplied;
        let tol = ROUND_OFF_CONSTANT * f64::EPSILON * self.scale + self.newton;
        (rise, tol.max(f64::MIN_POSITIVE))
    }
}

/// The run summary's warning for a scheme whose energy rose at a contact although nothing in the
/// problem supplies it: Newmark (forces at t_{n+1}) with multipliers (`multipliers`: some pair
/// carries λ_N). Its constraint forces chatter from step to step at a held contact and the
/// energy grows — ×5 to ×9 on the head-on bars at every refinement (docs/multibody.md §3.2): a
/// property of the scheme, not of the run. `None` when the energy did not rise beyond the audit's
/// tolerance ([`MultibodySummary::energy_rise_ratio`] ≤ 1) or for another scheme.
pub fn scheme_energy_warning(
    scheme: crate::model::multibody::scheme::MultibodyScheme,
    multipliers: bool,
    s: &MultibodySummary,
) -> Option<String> {
    (scheme == crate::model::multibody::scheme::MultibodyScheme::Newmark
        && multipliers
        && s.energy_rise_ratio > 1.0)
        .then(|| {
            format!(
                "the energy rose to E_N/E_0 = {:.3} with nothing to supply it: Newmark with \
                 Lagrange multipliers does not conserve energy at a contact (its constraint \
                 forces at t_(n+1) chatter from step to step; ×5 to ×9 on the head-on bars at \
                 every refinement, docs/multibody.md §3.2) — the energy_momentum scheme \
                 conserves it",
                s.final_energy_ratio
            )
        })
}

/// The round-off tolerance of one step's works: C ε s_n + ν_n.
pub fn step_tolerance(r: &MultibodyRecord) -> f64 {
    (ROUND_OFF_CONSTANT * f64::EPSILON * r.identity_scale + r.newton_bound).max(f64::MIN_POSITIVE)
}

/// The summary of a run's records.
pub fn summarize(records: &[MultibodyRecord]) -> MultibodySummary {
    let Some(first) = records.first() else {
        return MultibodySummary::default();
    };
    let eps = ROUND_OFF_CONSTANT * f64::EPSILON;
    let tiny = f64::MIN_POSITIVE;
    let e0 = first.energy.abs().max(tiny);
    let mut s = MultibodySummary {
        steps: records.len() - 1,
        ..Default::default()
    };
    let (mut drift, mut scale, mut newton) = (0.0, first.identity_scale, 0.0);
    let (mut p_round, mut p_newton, mut j_round, mut j_newton) = (0.0, 0.0, 0.0, 0.0);
    let mut friction_max = f64::NEG_INFINITY;
    let mut guard = EnergyGuard::new(first);
    let mut positive = 0.0;
    for (prev, r) in records.iter().zip(&records[1..]) {
        let (rise, tol) = guard.step(r);
        s.energy_rise_ratio = s.energy_rise_ratio.max(rise / tol);
        if r.positive_set_work > step_tolerance(r) {
            positive += r.positive_set_work;
            s.positive_set_work_steps += 1;
        }
        s.energy_drift = s.energy_drift.max((r.energy - first.energy).abs() / e0);
        drift += r.identity_residual;
        scale += r.identity_scale;
        newton += r.newton_bound;
        s.identity_ratio = s
            .identity_ratio
            .max(drift.abs() / (eps * scale + newton).max(tiny));
        let step_tol = (eps * r.identity_scale + r.newton_bound).max(tiny);
        if !r.set_changed() {
            let change = (r.energy - prev.energy - r.external_work - r.friction_work).abs();
            s.unchanged_ratio = s
                .unchanged_ratio
                .max(change / (step_tol + r.holding_gap_work));
            s.unchanged_relative = s.unchanged_relative.max(change / e0);
        } else {
            s.steps_with_set_change += 1;
        }
        s.activation_work += r.activation_work;
        s.friction_work += r.friction_work;
        friction_max = friction_max.max(r.friction_work / step_tol);
        p_round += r.momentum_round_off;
        p_newton += r.momentum_bound;
        j_round += r.angular_round_off;
        j_newton += r.angular_bound;
        let dpx = (r.momentum[0] - first.momentum[0]).abs();
        let dpy = (r.momentum[1] - first.momentum[1]).abs();
        let dp = dpx.max(dpy);
        let dj = (r.angular_momentum - first.angular_momentum).abs();
        let p_tol = eps * (first.momentum_scale + r.momentum_scale + p_round) + p_newton;
        let j_tol = eps * (first.angular_scale + r.angular_scale + j_round) + j_newton;
        s.momentum_ratio = s.momentum_ratio.max(dp / p_tol.max(tiny));
        s.momentum_ratio_x = s.momentum_ratio_x.max(dpx / p_tol.max(tiny));
        s.momentum_ratio_y = s.momentum_ratio_y.max(dpy / p_tol.max(tiny));
        s.angular_ratio = s.angular_ratio.max(dj / j_tol.max(tiny));
        s.momentum_relative = s
            .momentum_relative
            .max(dp / first.momentum_scale.max(r.momentum_scale).max(tiny));
        s.angular_relative = s
            .angular_relative
            .max(dj / first.angular_scale.max(r.angular_scale).max(tiny));
        s.max_newton_iterations = s.max_newton_iterations.max(r.newton_iterations);
        s.steps_with_contact += usize::from(r.active > 0);
    }
    s.friction_ratio = if friction_max == f64::NEG_INFINITY {
        0.0
    } else {
        friction_max
    };
    s.activation_relative = s.activation_work.abs() / e0;
    s.positive_set_work_relative = positive / e0;
    s.final_energy_ratio = records[records.len() - 1].energy / e0;
    s
}
