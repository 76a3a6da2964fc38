//! The case format of `multibody_impact`: two rings, the runs, the large-step runs, the
//! self-convergence study and the work–precision study.

use std::path::Path;

use serde::{Deserialize, Serialize};

use contactlab::model::multibody::scheme::MultibodyScheme;

use crate::core::format::{invalid, positive, CaseError};
use crate::multibody::study::MaterialSpec;

/// The case body of `multibody_impact`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImpactCase {
    /// The rings' law (both rings).
    pub material: MaterialSpec,
    pub density: f64,
    /// The two rings (index 0 carries the slave surface: its outer boundary).
    #[serde(rename = "ring")]
    pub rings: Vec<RingSpec>,
    /// T (after the separation) and the steps at resolution 1.
    pub final_time: f64,
    pub steps: usize,
    /// The runs at resolution 1 (their audits gated).
    #[serde(rename = "run")]
    pub runs: Vec<RunSpec>,
    /// Runs at a large step (the midpoint rule's blow-up).
    pub large_step: Option<LargeStepSpec>,
    /// The self-convergence study.
    pub gci: Option<GciSpec>,
    /// The work–precision study.
    pub work_precision: Option<WorkPrecisionSpec>,
    /// The audit's injected-defect controls on one run's records.
    pub audit_control: Option<AuditControlSpec>,
    /// Draw the first run's rings at six times (a run of its own).
    #[serde(default)]
    pub snapshots: bool,
}

/// `[[ring]]`: an annulus with its P1 mesh at resolution 1 and its initial rigid motion.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RingSpec {
    pub center: [f64; 2],
    pub inner: f64,
    pub outer: f64,
    /// Cells across and around at resolution 1 (multiplied by the resolution factor).
    pub radial: usize,
    pub around: usize,
    pub velocity: [f64; 2],
    #[serde(default)]
    pub angular_velocity: f64,
}

impl RingSpec {
    /// The ring with every length and velocity times `s`.
    pub fn at_size(&self, s: f64) -> Self {
        Self {
            center: self.center.map(|x| s * x),
            inner: s * self.inner,
            outer: s * self.outer,
            velocity: self.velocity.map(|x| s * x),
            ..*self
        }
    }
}

/// `[[run]]`: a scheme and a friction coefficient at resolution 1.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSpec {
    pub name: String,
    pub scheme: MultibodyScheme,
    #[serde(default)]
    pub friction: f64,
    /// The midpoint rule's energy error in steps without a change of the active set must be at
    /// least this (relative to E_0): the scheme that does not conserve is seen not to.
    pub min_energy_error: Option<f64>,
    /// The conserving penalty P = (ε/2)(g₋)² with this ε per slave node instead of the
    /// multipliers (frictionless only).
    pub penalty: Option<f64>,
    /// Gate: max_n |E_n − E_0 − Σ_{j≤n} (switch work)_j| / E_0 at most this (the conserving
    /// penalty with the energy–momentum scheme: no activation loss, E = K + U + P conserved in
    /// every step but where a penetrated node changes master segment and its P is measured
    /// from another line).
    pub max_other_energy_change: Option<f64>,
    /// The similar problem at this size s: every length and velocity times s, the modulus and
    /// the penalty's ε times s² (angular velocities, times, strains and E_n/E_0 unchanged;
    /// `runs::Job::size`). Default 1.
    pub size: Option<f64>,
    /// With `size`: the run at size 1 this one must reproduce — rebound velocities / s, the
    /// contact duration and (E_N − E_0)/E_0 within `similarity_tolerance` (relative).
    pub similar_to: Option<String>,
    pub similarity_tolerance: Option<f64>,
}

/// `[audit_control]`: the records of the run `run` given, at their last step, a defect of
/// `defect` tolerances in each audited quantity in turn (`crate::multibody::audit_reference`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AuditControlSpec {
    pub run: String,
    /// In units of the quantity's tolerance (> 1: the audit must flag it).
    pub defect: f64,
}

/// `[large_step]`: the runs at `steps` steps over T (k large against the contact duration).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LargeStepSpec {
    pub steps: usize,
    /// The energy–momentum run must complete with |E_N − E_0| at most the run's activation and
    /// switch work plus this fraction of E_0 (its energy changes only where constraints close).
    pub max_other_energy_change: f64,
    /// The midpoint run must stop with a typed error or end with |E_N − E_0| / E_0 at least this.
    pub min_midpoint_energy_error: f64,
}

/// `[gci]`: the energy–momentum run (frictionless) refined in mesh and step together.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GciSpec {
    /// Resolution factors, coarsest first, a constant ratio apart (≥ 3 levels).
    pub factors: Vec<f64>,
    /// The formal order of the quantities (the schemes are second order in k; P1 first order in
    /// h for stresses, second for displacements; the rebound is a global quantity).
    pub formal_order: f64,
    /// Gate: GCI_fine in per cent at most this, per quantity.
    pub max_percent: f64,
    /// Gate (four levels or more): the asymptotic ratio within 1 ± this.
    pub asymptotic_tolerance: Option<f64>,
    #[serde(default)]
    pub note: String,
}

/// `[work_precision]`: the schemes over resolution factors, against the finest GCI level's
/// extrapolated rebound.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkPrecisionSpec {
    pub schemes: Vec<MultibodyScheme>,
    pub factors: Vec<f64>,
    /// Gate: `cheaper` reaches `baseline`'s finest error with at most this fraction of its work
    /// (dof-steps), or None for no such gate.
    pub baseline: Option<MultibodyScheme>,
    pub cheaper: Option<MultibodyScheme>,
    pub max_work_ratio: Option<f64>,
    #[serde(default)]
    pub note: String,
}

impl ImpactCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        positive(p, "density", self.density)?;
        positive(p, "final_time", self.final_time)?;
        positive(p, "material.young", self.material.young)?;
        if self.material.law().is_err() {
            return Err(invalid(
                p,
                "material.poisson",
                self.material.poisson,
                "in (−1, 1/2)",
            ));
        }
        if self.rings.len() != 2 {
            return Err(invalid(p, "ring", self.rings.len(), "two [[ring]] tables"));
        }
        for (i, r) in self.rings.iter().enumerate() {
            positive(p, &format!("ring[{i}].inner"), r.inner)?;
            if r.outer.partial_cmp(&r.inner) != Some(std::cmp::Ordering::Greater) {
                return Err(invalid(p, &format!("ring[{i}].outer"), r.outer, "> inner"));
            }
            if r.radial == 0 || r.around < 3 {
                return Err(invalid(
                    p,
                    &format!("ring[{i}].around"),
                    r.around,
                    "radial ≥ 1, around ≥ 3",
                ));
            }
        }
        if self.steps == 0 {
            return Err(invalid(p, "steps", 0, "≥ 1"));
        }
        if self.runs.is_empty() {
            return Err(invalid(p, "run", 0, "at least one [[run]]"));
        }
        for (i, r) in self.runs.iter().enumerate() {
            if !(r.friction.is_finite() && r.friction >= 0.0) {
                return Err(invalid(
                    p,
                    &format!("run[{i}].friction"),
                    r.friction,
                    "μ ≥ 0",
                ));
            }
            if let Some(e) = r.penalty {
                if !(e.is_finite() && e > 0.0) {
                    return Err(invalid(p, &format!("run[{i}].penalty"), e, "ε > 0"));
                }
                if r.friction != 0.0 {
                    return Err(invalid(
                        p,
                        &format!("run[{i}].friction"),
                        r.friction,
                        "0 with a penalty (friction needs a normal multiplier)",
                    ));
                }
            }
            if let Some(s) = r.size {
                positive(p, &format!("run[{i}].size"), s)?;
                let reference = r
                    .similar_to
                    .as_ref()
                    .and_then(|n| self.runs.iter().find(|x| &x.name == n));
                match reference {
                    Some(x)
                        if x.size.unwrap_or(1.0) == 1.0
                            && x.scheme == r.scheme
                            && x.friction == r.friction
                            && x.penalty == r.penalty => {}
                    _ => {
                        return Err(invalid(
                            p,
                            &format!("run[{i}].similar_to"),
                            format!("{:?}", r.similar_to),
                            "the name of a [[run]] at size 1 with the same scheme, friction and penalty",
                        ))
                    }
                }
                match r.similarity_tolerance {
                    Some(t) => positive(p, &format!("run[{i}].similarity_tolerance"), t)?,
                    None => {
                        return Err(invalid(
                            p,
                            &format!("run[{i}].similarity_tolerance"),
                            "(missing)",
                            "a relative tolerance with `size`",
                        ))
                    }
                }
            }
            if let Some(m) = r.max_other_energy_change {
                positive(p, &format!("run[{i}].max_other_energy_change"), m)?;
            }
        }
        if let Some(a) = &self.audit_control {
            if !self.runs.iter().any(|r| r.name == a.run) {
                return Err(invalid(
                    p,
                    "audit_control.run",
                    &a.run,
                    "the name of a [[run]]",
                ));
            }
            if !(a.defect.is_finite() && a.defect > 1.0) {
                return Err(invalid(
                    p,
                    "audit_control.defect",
                    a.defect,
                    "> 1 (a defect the audit must flag)",
                ));
            }
        }
        if let Some(g) = &self.gci {
            if g.factors.len() < 3 {
                return Err(invalid(p, "gci.factors", g.factors.len(), "≥ 3 levels"));
            }
            let r = g.factors[1] / g.factors[0];
            if r.partial_cmp(&1.0) != Some(std::cmp::Ordering::Greater)
                || g.factors
                    .windows(2)
                    .any(|w| ((w[1] / w[0]) - r).abs() > 1e-12 * r)
            {
                return Err(invalid(
                    p,
                    "gci.factors",
                    format!("{:?}", g.factors),
                    "increasing by a constant ratio",
                ));
            }
            positive(p, "gci.formal_order", g.formal_order)?;
            positive(p, "gci.max_percent", g.max_percent)?;
        }
        if let Some(w) = &self.work_precision {
            if w.schemes.is_empty() || w.factors.len() < 2 {
                return Err(invalid(
                    p,
                    "work_precision.factors",
                    w.factors.len(),
                    "≥ 2 factors and ≥ 1 scheme",
                ));
            }
            if self.gci.is_none() {
                return Err(invalid(
                    p,
                    "work_precision",
                    "(no [gci])",
                    "a [gci] study (its extrapolation is the reference)",
                ));
            }
        }
        Ok(())
    }
}
