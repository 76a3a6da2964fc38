//! One run of an impact scene (BDS §1.7): the scene file with the run's scheme, contact treatment
//! and resolution, solved with a per-step record of the quantities the impact case reports —
//! centre-of-mass velocity (total momentum / total mass, with the consistent mass matrix),
//! total normal and friction forces Σ w N, Σ w T, largest penetration, energy — and the summary
//! derived from it: contact interval, rebound velocity, energy changes, momentum drift in flight.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use contactlab::model::dynamic::audit::EnergyAudit;
use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::dynamic::plane_body::PlaneBody;
use contactlab::model::dynamic::record::{conserving, Conserving};
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::DynamicStats;
use contactlab::scene::dynamic::{DynamicScene, DynamicSceneFile, SceneBody};

use crate::core::overrides;
use crate::dynamic::audit_state::{AuditSpec, StateAudit, StateAuditor};

/// The normal contact treatment of a run (the scene's stiffness r and depth g are used).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Treatment {
    /// r (p_n)_+ at t_n (BDS (1.8)).
    Penalty,
    /// BDS (1.46) = HLT (3.68): exact discrete work.
    EnergyConsistent,
    /// HLT (3.69): λ_{n+1/2} ν tilted along the contact point's increment so that its work is
    /// exact; differs from (3.68) when a node slides while it enters or leaves.
    HauretLeTallecTilted,
    /// The improved penalized method, stages (a) and (b) (BDS (1.44)–(1.46)).
    LimitedPenetration,
    /// Exact non-penetration (BDS (1.18) with g = 0).
    Signorini,
}

impl Treatment {
    /// The name as written in scenes.
    pub fn name(self) -> &'static str {
        match self {
            Self::Penalty => "penalty",
            Self::EnergyConsistent => "energy_consistent",
            Self::HauretLeTallecTilted => "hauret_le_tallec_tilted",
            Self::LimitedPenetration => "limited_penetration",
            Self::Signorini => "signorini",
        }
    }

    /// Whether the compliance force has an exact discrete work (BDS Prop. 1.3, HLT Prop. 3.7).
    pub fn is_energy_consistent(self) -> bool {
        matches!(
            self,
            Self::EnergyConsistent | Self::HauretLeTallecTilted | Self::LimitedPenetration
        )
    }
}

/// What to run: scheme, treatment, resolution factor (mesh divisions and steps multiplied
/// together) and an optional step count at factor 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Job {
    pub scheme: DynamicScheme,
    pub treatment: Treatment,
    pub factor: f64,
    pub steps: Option<usize>,
    pub snapshots: bool,
}

/// One step's record.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct StepRecord {
    pub time: f64,
    /// Centre-of-mass velocity (total momentum / total mass).
    pub velocity: [f64; 2],
    /// Σ w_i N_i and Σ w_i T_i.
    pub normal_force: f64,
    pub friction_force: f64,
    pub max_penetration: f64,
    /// E_n + Φ_n.
    pub energy: f64,
    pub stage_b: bool,
    pub newton_iterations: usize,
}

/// The result of one run.
#[derive(Debug, Clone)]
pub struct RunOutput {
    pub job: Job,
    pub body: Arc<PlaneBody>,
    pub steps: usize,
    pub final_time: f64,
    pub history: Vec<StepRecord>,
    pub audit: EnergyAudit,
    pub stats: DynamicStats,
    pub snapshots: Vec<(f64, Vec<f64>)>,
    /// The audit recomputed from the state (`crate::dynamic::audit_state`), or why it could not
    /// be made.
    pub state: Result<StateAudit, String>,
    /// The identities the problem claims (`contactlab::model::dynamic::record::conserving`).
    pub claims: Conserving,
}

/// `value × factor`, which must be a positive integer.
fn scaled(field: &str, value: usize, factor: f64) -> Result<usize, String> {
    let v = value as f64 * factor;
    if (v - v.round()).abs() > 1e-9 || v.round() < 1.0 {
        return Err(format!(
            "{field} = {value} × refinement {factor} = {v} is not a positive integer"
        ));
    }
    Ok(v.round() as usize)
}

/// The case's scene: its table (what the jobs override) and the same table parsed (what they
/// read: the values that are refined).
#[derive(Debug, Clone)]
pub struct SceneSource {
    pub table: toml::Table,
    pub file: DynamicSceneFile,
}

impl SceneSource {
    /// The scene of a job: the scene table with the job's scheme, treatment, refinement and
    /// snapshot times as dotted-key overrides (the core's mechanism), parsed by the scene format.
    pub fn variant(&self, job: &Job, snapshot_times: &[f64]) -> Result<DynamicSceneFile, String> {
        variant(&self.table, &self.file, job, snapshot_times)
    }
}

fn variant(
    table: &toml::Table,
    file: &DynamicSceneFile,
    job: &Job,
    snapshot_times: &[f64],
) -> Result<DynamicSceneFile, String> {
    let int = |v: usize| toml::Value::Integer(v as i64);
    let mut set = toml::Table::new();
    set.insert("time.scheme".into(), job.scheme.name().into());
    let b = &file.body;
    for (name, slot) in [
        ("body.rings", b.rings),
        ("body.radial", b.radial),
        ("body.around", b.around),
    ] {
        if let Some(v) = slot {
            set.insert(name.into(), int(scaled(name, v, job.factor)?));
        }
    }
    if let Some(d) = b.divisions {
        set.insert(
            "body.divisions".into(),
            toml::Value::Array(vec![
                int(scaled("body.divisions", d[0], job.factor)?),
                int(scaled("body.divisions", d[1], job.factor)?),
            ]),
        );
    }
    let steps = scaled(
        "time.steps",
        job.steps.unwrap_or(file.time.steps),
        job.factor,
    )?;
    set.insert("time.steps".into(), int(steps));
    let c = file
        .contact
        .as_ref()
        .ok_or("the impact scene needs a [contact] section")?;
    set.insert("contact.treatment".into(), job.treatment.name().into());
    let signorini = job.treatment == Treatment::Signorini;
    if signorini {
        // the friction law keeps the layer depth g of (1.13)
        if let Some(depth) = c.friction.as_ref().and_then(|fr| fr.depth.or(c.depth)) {
            set.insert("contact.friction.depth".into(), toml::Value::Float(depth));
        }
    }
    let times = if job.snapshots { snapshot_times } else { &[] };
    set.insert(
        "output.times".into(),
        toml::Value::Array(times.iter().map(|&t| toml::Value::Float(t)).collect()),
    );
    let mut t = overrides::applied(table, &set).map_err(|e| e.to_string())?;
    if signorini {
        for key in ["contact.stiffness", "contact.depth"] {
            overrides::remove(&mut t, key).map_err(|e| e.to_string())?;
        }
    }
    t.try_into()
        .map_err(|e: toml::de::Error| format!("the scene of {}: {e}", job.treatment.name()))
}

/// The total mass per direction and the vectors 1_x, 1_y on the free dofs.
fn unit_translations(body: &PlaneBody) -> [Vec<f64>; 2] {
    let n = body.dofs();
    let nodes = body.data().mesh.nodes().len();
    std::array::from_fn(|c| {
        let mut v = vec![0.0; n];
        for i in 0..nodes {
            if let Some(d) = body.dof(i, c) {
                v[d] = 1.0;
            }
        }
        v
    })
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Runs a job of the scene `file`.
pub fn run_job(
    source: &SceneSource,
    job: &Job,
    snapshot_times: &[f64],
) -> Result<RunOutput, String> {
    let scene =
        DynamicScene::from_file(source.variant(job, snapshot_times)?).map_err(|e| e.to_string())?;
    let SceneBody::Plane(body) = &scene.body else {
        return Err("the impact case needs a plane body (disk, annulus or rectangle)".into());
    };
    let body = body.clone();
    let ones = unit_translations(&body);
    let pattern = body.pattern();
    let mut m1 = vec![0.0; body.dofs()];
    let mass: [f64; 2] = std::array::from_fn(|c| {
        pattern.symmetric_mul(body.mass(), &ones[c], &mut m1);
        dot(&m1, &ones[c])
    });
    let mut mv = vec![0.0; body.dofs()];
    let mut history = Vec::with_capacity(scene.problem.steps + 1);
    let mut auditor = AuditSpec::of_scene(&scene.file)
        .and_then(|spec| StateAuditor::new(&body, &scene.problem, spec));
    let sol = scene
        .solver()
        .map_err(|e| e.to_string())?
        .solve_with(&mut |v| {
            if let Ok(a) = &mut auditor {
                a.observe(v);
            }
            pattern.symmetric_mul(body.mass(), v.velocity, &mut mv);
            history.push(StepRecord {
                time: v.time,
                velocity: [dot(&mv, &ones[0]) / mass[0], dot(&mv, &ones[1]) / mass[1]],
                normal_force: v.record.contact_force,
                friction_force: v.record.friction_force,
                max_penetration: v.record.max_penetration,
                energy: v.record.energy() + v.record.penalty,
                stage_b: v.record.stage_b,
                newton_iterations: v.record.newton_iterations,
            });
        })
        .map_err(|e| e.to_string())?;
    let state = auditor.and_then(StateAuditor::finish);
    let claims = conserving(&scene.problem);
    Ok(RunOutput {
        job: *job,
        body,
        steps: scene.problem.steps,
        final_time: scene.problem.final_time,
        history,
        audit: sol.audit,
        stats: sol.stats,
        snapshots: sol.snapshots,
        state,
        claims,
    })
}

/// The contact interval of a run: first and last contact times, linearly interpolated where the
/// largest penetration crosses 0 (compliance treatments: N > 0 ⇔ p > 0); for Signorini, where
/// p ≤ 0 always, the first and last steps with Σ w N > 0 (quantized by k).
pub fn contact_interval(history: &[StepRecord], signorini: bool) -> Option<(f64, f64)> {
    let indicator = |r: &StepRecord| {
        if signorini {
            r.normal_force
        } else {
            r.max_penetration
        }
    };
    let first = history.iter().position(|r| indicator(r) > 0.0)?;
    let last = history.iter().rposition(|r| indicator(r) > 0.0)?;
    if last + 1 >= history.len() {
        return None;
    }
    let cross = |a: &StepRecord, b: &StepRecord| {
        let (fa, fb) = (indicator(a), indicator(b));
        a.time + (b.time - a.time) * fa / (fa - fb)
    };
    let start = if first == 0 || signorini {
        history[first].time
    } else {
        cross(&history[first - 1], &history[first])
    };
    let end = if signorini {
        history[last].time
    } else {
        cross(&history[last], &history[last + 1])
    };
    Some((start, end))
}

/// The summary of a run.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct RunSummary {
    /// Contact interval (None: still in contact at T, or never in contact).
    pub contact: Option<(f64, f64)>,
    pub contact_duration: Option<f64>,
    /// Centre-of-mass velocity at t = 0 and at T (the rebound, once separated).
    pub initial_velocity: [f64; 2],
    pub final_velocity: [f64; 2],
    pub max_penetration: f64,
    pub max_normal_force: f64,
    /// (E + Φ)_0, and the relative changes of the run: total, friction work, constraint work.
    pub initial_energy: f64,
    pub energy_change: f64,
    pub friction_work: f64,
    pub constraint_work: f64,
    /// Largest relative change of the momentum in flight (before first and after last contact).
    pub momentum_drift: f64,
    pub stage_b_steps: usize,
}

/// Largest |p_n − p_a| / |p_a| over a range of records (p = the centre-of-mass velocity).
fn drift(records: &[StepRecord]) -> f64 {
    let Some(a) = records.first() else {
        return 0.0;
    };
    let norm = |v: [f64; 2]| v[0].hypot(v[1]);
    records
        .iter()
        .map(|r| {
            norm([r.velocity[0] - a.velocity[0], r.velocity[1] - a.velocity[1]]) / norm(a.velocity)
        })
        .fold(0.0, f64::max)
}

impl RunOutput {
    /// The summary (see [`RunSummary`]).
    pub fn summary(&self) -> RunSummary {
        let h = &self.history;
        let signorini = self.job.treatment == Treatment::Signorini;
        let contact = contact_interval(h, signorini);
        let first = h.first().copied().unwrap_or_default();
        let last = h.last().copied().unwrap_or_default();
        let e0 = first.energy;
        let rec = self.audit.records.last().copied().unwrap_or_default();
        // flight: before the first step with a contact force, and from the second step after
        // the last one (Newmark's velocity update still averages the last contact acceleration)
        let touching = |r: &StepRecord| r.normal_force > 0.0 || r.max_penetration > 0.0;
        let first_contact = h.iter().position(touching).unwrap_or(h.len());
        let after = h
            .iter()
            .rposition(touching)
            .map_or(0, |i| i + 2)
            .min(h.len());
        let momentum_drift = drift(&h[..first_contact]).max(drift(&h[after..]));
        RunSummary {
            contact,
            contact_duration: contact.map(|(a, b)| b - a),
            initial_velocity: first.velocity,
            final_velocity: last.velocity,
            max_penetration: h
                .iter()
                .map(|r| r.max_penetration)
                .fold(f64::NEG_INFINITY, f64::max),
            max_normal_force: h.iter().map(|r| r.normal_force).fold(0.0, f64::max),
            initial_energy: e0,
            energy_change: (last.energy - e0) / e0,
            friction_work: rec.friction_work / e0,
            constraint_work: rec.constraint_work / e0,
            momentum_drift,
            stage_b_steps: self.stats.stage_b_steps,
        }
    }

    /// The largest Green–Lagrange strain norm |E| = |FᵀF − I|/2 over the triangles of a
    /// displacement (free dofs).
    pub fn max_green_strain(&self, u: &[f64]) -> f64 {
        (0..self.body.elements().len())
            .map(|e| {
                let f = self.body.deformation_gradient(u, e);
                (0.5 * (f.transpose() * f - nalgebra::Matrix2::identity())).norm()
            })
            .fold(0.0, f64::max)
    }

    /// Green–Lagrange strain norms per triangle.
    pub fn green_strains(&self, u: &[f64]) -> Vec<f64> {
        (0..self.body.elements().len())
            .map(|e| {
                let f = self.body.deformation_gradient(u, e);
                (0.5 * (f.transpose() * f - nalgebra::Matrix2::identity())).norm()
            })
            .collect()
    }

    /// The label of the run's scheme and treatment.
    pub fn label(&self) -> String {
        format!("{} + {}", self.job.scheme.name(), self.job.treatment.name())
    }
}

#[cfg(test)]
mod tests {
    //! The contact interval is interpolated where the penetration changes sign, and a run still
    //! in contact at T has none.
    use super::*;

    fn rec(time: f64, p: f64) -> StepRecord {
        StepRecord {
            time,
            max_penetration: p,
            normal_force: p.max(0.0),
            ..Default::default()
        }
    }

    #[test]
    fn contact_interval_interpolates_the_sign_changes() {
        let h = vec![
            rec(0.0, -1.0),
            rec(1.0, 1.0),
            rec(2.0, 3.0),
            rec(3.0, 1.0),
            rec(4.0, -3.0),
        ];
        let (a, b) = contact_interval(&h, false).unwrap();
        assert!((a - 0.5).abs() < 1e-15 && (b - 3.25).abs() < 1e-15);
        let (a, b) = contact_interval(&h, true).unwrap();
        assert_eq!((a, b), (1.0, 3.0));
    }

    #[test]
    fn run_in_contact_at_the_end_has_no_interval() {
        let h = vec![rec(0.0, -1.0), rec(1.0, 1.0), rec(2.0, 3.0)];
        assert!(contact_interval(&h, false).is_none());
    }
}
