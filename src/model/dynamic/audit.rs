//! The energy audit of a dynamic run: every step records the energies, the works and the
//! residuals of the discrete energy identities (Barboteu–Danan–Sofonea, "BDS", §1.6.3;
//! Hauret–Le Tallec, "HLT", Prop. 3.7).
//!
//! With E_n = ½ v_nᵀ M v_n + 𝒲(u_n) (BDS (1.47); v = δu for the midpoint-type schemes, the
//! Newmark velocity otherwise), d = u_n − u_{n−1}, Φ_n = Σ_i w_i (r/2) (p_{i,n})_+² the penalty
//! energy, and the step works
//!
//!   W_ext = dᵀ f̄,  W_c = Σ_i ξ_{ν,i}·d (normal, incl. multipliers),  W_τ = Σ_i ξ_{τ,i} d_τ,i,
//!
//! (f̄, ξ̄ the forces the scheme applies over the step: at t_{n−1/2} / t_n for the midpoint type,
//! the trapezoidal mean for Newmark), the residuals are
//!
//! - (1.48) r_1.1 = (E_n − E_{n−1}) − W_ext − W_c − W_τ          (BDS Prop. 1.1)
//! - (1.49) r_1.3 = (E_n + Φ_n − E_{n−1} − Φ_{n−1}) − W_ext − W_τ − D_b   (BDS Prop. 1.3)
//! - r_3.7 = Σ_{compliance nodes} (ξ_ν·d + ΔΦ_i)                   (HLT Prop. 3.7: exact work)
//!
//! with D_b = Σ_{constrained nodes} (ξ_ν·d + ΔΦ_i) the work of the unilateral constraints
//! (Signorini, stage (b) of the IPM), which must be ≤ 0, as must W_τ. For the midpoint rule with
//! a linear law and for Gonzalez's scheme r_1.1 vanishes to round-off; with an energy-consistent
//! contact force r_1.3 and r_3.7 do too. Newmark and the midpoint rule show their drift here.

use serde::Serialize;

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
    /// Cumulative works since t = 0.
    pub external_work: f64,
    pub contact_work: f64,
    pub friction_work: f64,
    /// Cumulative D_b (≤ 0).
    pub constraint_work: f64,
    /// This step's W_τ and D_b (each must be ≤ 0).
    pub step_friction_work: f64,
    pub step_constraint_work: f64,
    /// The identity residuals of this step (absolute).
    pub residual_1_48: f64,
    pub residual_1_49: f64,
    pub residual_3_7: f64,
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
    /// E_n = kinetic + elastic.
    pub fn energy(&self) -> f64 {
        self.kinetic + self.elastic
    }
}

/// The audit of a run (record 0 is the initial state).
#[derive(Debug, Clone, Default, Serialize)]
pub struct EnergyAudit {
    pub records: Vec<AuditRecord>,
}

/// Largest residuals of a run, relative to the energy scale.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct AuditSummary {
    /// max_n (E_n + Φ_n) and the magnitudes of the works: the scale of round-off.
    pub energy_scale: f64,
    pub max_residual_1_48: f64,
    pub max_residual_1_49: f64,
    pub max_residual_3_7: f64,
    /// Largest step friction work and constraint work (must be ≤ 0; positive values are
    /// violations).
    pub max_step_friction_work: f64,
    pub max_step_constraint_work: f64,
    /// (E + Φ)_N − (E + Φ)_0 − W_ext − W_τ − D_b: the drift of the balance (1.49) over the run.
    pub drift_1_49: f64,
    pub steps: usize,
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

    /// The summary of the run's residuals.
    pub fn summary(&self) -> AuditSummary {
        let scale = self.energy_scale();
        let mut s = AuditSummary {
            energy_scale: scale,
            steps: self.records.len().saturating_sub(1),
            max_step_friction_work: f64::NEG_INFINITY,
            max_step_constraint_work: f64::NEG_INFINITY,
            ..Default::default()
        };
        for r in self.records.iter().skip(1) {
            s.max_residual_1_48 = s.max_residual_1_48.max(r.residual_1_48.abs() / scale);
            s.max_residual_1_49 = s.max_residual_1_49.max(r.residual_1_49.abs() / scale);
            s.max_residual_3_7 = s.max_residual_3_7.max(r.residual_3_7.abs() / scale);
            s.max_step_friction_work = s.max_step_friction_work.max(r.step_friction_work);
            s.max_step_constraint_work = s.max_step_constraint_work.max(r.step_constraint_work);
        }
        if s.steps == 0 {
            s.max_step_friction_work = 0.0;
            s.max_step_constraint_work = 0.0;
        }
        if let (Some(first), Some(last)) = (self.records.first(), self.records.last()) {
            s.drift_1_49 = (last.energy() + last.penalty)
                - (first.energy() + first.penalty)
                - last.external_work
                - last.friction_work
                - last.constraint_work;
        }
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

    /// The drift of the balance (1.49) at every record: (E + Φ)_n − (E + Φ)_0 − W_ext − W_τ − D_b
    /// (zero for a conserving run; the energy error of the midpoint rule on a hyperelastic body).
    pub fn balance_drift(&self) -> Vec<(f64, f64)> {
        let Some(first) = self.records.first() else {
            return Vec::new();
        };
        let e0 = first.energy() + first.penalty;
        self.records
            .iter()
            .map(|r| {
                (
                    r.time,
                    r.energy() + r.penalty
                        - e0
                        - r.external_work
                        - r.friction_work
                        - r.constraint_work,
                )
            })
            .collect()
    }
}
