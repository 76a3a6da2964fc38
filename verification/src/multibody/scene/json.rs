//! The JSON a multibody scene writes (`solution.json`, or `partial_solution.json` for a run that
//! stopped): the bodies (meshes), the pairs, the audit records and summary, the history, the
//! snapshots with each body's nodal displacement and velocity and the contact states.

use serde::Serialize;
use serde_json::{json, Value};

use contactlab::error::{Error as LabError, SolveError};
use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::multibody::audit::MultibodySummary;
use contactlab::model::multibody::constraint::Enforcement;
use contactlab::model::multibody::solver::{ContactState, MultibodySnapshot, PairMaster};
use contactlab::scene::multibody::MultibodyScene;

/// A body of `solution.json`.
#[derive(Debug, Serialize)]
pub struct BodyOut {
    pub name: String,
    /// The body as the solver describes it (law with its λ and μ, density, counts).
    pub description: String,
    pub nodes: Vec<[f64; 2]>,
    pub triangles: Vec<[usize; 3]>,
}

/// A solver pair of `solution.json`.
#[derive(Debug, Serialize)]
pub struct PairOut {
    /// The `[[contact_pair]]` section and whether this is its second pass.
    pub section: usize,
    pub exchanged: bool,
    pub slave: String,
    /// The master body's name, or `foundation y ≤ level`.
    pub master: String,
    pub enforcement: String,
    pub friction: f64,
    /// The slave nodes of the pair (mesh nodes of the slave body) and their tributary lengths.
    pub slave_nodes: Vec<usize>,
    pub weights: Vec<f64>,
}

/// A contact state of a snapshot.
#[derive(Debug, Serialize)]
pub struct ContactOut {
    /// The solver pair, its section and the slave body's index.
    pub pair: usize,
    pub section: usize,
    pub body: usize,
    /// The slave node (a mesh node of the slave body) and its tributary length w.
    pub node: usize,
    pub weight: f64,
    /// The master segment (absent: the foundation).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub segment: Option<usize>,
    /// The normal force λ_N of the node (the multiplier; with penalty enforcement ε g₋ at
    /// t_n), the friction force λ_T, and λ_N / w (the normal pressure).
    pub normal_force: f64,
    pub lambda_t: f64,
    pub pressure: f64,
    /// The gap at t_n and the step's slip τ₁ − τ₀.
    pub gap: f64,
    pub slip: f64,
    pub active: bool,
    pub stick: bool,
}

/// One body's state in a snapshot: nodal values (u_x, u_y interleaved per node; 0 on held
/// components).
#[derive(Debug, Serialize)]
pub struct BodyState {
    pub displacement: Vec<f64>,
    pub velocity: Vec<f64>,
}

/// A snapshot of `solution.json`.
#[derive(Debug, Serialize)]
pub struct SnapshotOut {
    pub step: usize,
    pub time: f64,
    pub bodies: Vec<BodyState>,
    pub contacts: Vec<ContactOut>,
}

/// The bodies of the scene.
pub fn bodies(scene: &MultibodyScene) -> Vec<BodyOut> {
    let set = &scene.problem.bodies;
    (0..set.len())
        .map(|b| {
            let body = set.body(b);
            BodyOut {
                name: scene.names[b].clone(),
                description: body.describe(),
                nodes: body.data().mesh.nodes().to_vec(),
                triangles: body.data().mesh.triangles().to_vec(),
            }
        })
        .collect()
}

/// The solver pairs of the scene.
pub fn pairs(scene: &MultibodyScene) -> Vec<PairOut> {
    scene
        .problem
        .pairs
        .iter()
        .zip(&scene.origins)
        .map(|(p, o)| PairOut {
            section: o.section,
            exchanged: o.exchanged,
            slave: scene.names[p.slave.body].clone(),
            master: match &p.master {
                PairMaster::Surface(s) => scene.names[s.body].clone(),
                PairMaster::Foundation(f) => format!("foundation y ≤ {}", f.level),
            },
            enforcement: match p.law.enforcement {
                Enforcement::Lagrange => "lagrange".into(),
                Enforcement::Penalty { stiffness } => format!("penalty (ε = {stiffness})"),
                Enforcement::Compliant { stiffness } => format!("compliant (ε = {stiffness})"),
            },
            friction: p.law.friction,
            slave_nodes: p.slave.nodes.clone(),
            weights: p.slave.weights.clone(),
        })
        .collect()
}

/// The normal force of a contact state: its multiplier λ_N, or with penalty enforcement (whose
/// candidates carry no multiplier) the penalty force ε g₋ at the state's gap.
pub fn normal_force(scene: &MultibodyScene, c: &ContactState) -> f64 {
    match scene.problem.pairs.get(c.pair).map(|p| p.law.enforcement) {
        Some(Enforcement::Penalty { stiffness }) => stiffness * (-c.gap).max(0.0),
        _ => c.lambda_n,
    }
}

/// A contact state with its section and body.
pub fn contact(scene: &MultibodyScene, c: &ContactState) -> ContactOut {
    let normal = normal_force(scene, c);
    ContactOut {
        pair: c.pair,
        section: scene.origins.get(c.pair).map_or(0, |o| o.section),
        body: scene.problem.pairs.get(c.pair).map_or(0, |p| p.slave.body),
        node: c.slave,
        weight: c.weight,
        segment: c.segment,
        normal_force: normal,
        lambda_t: c.lambda_t,
        pressure: normal / c.weight,
        gap: c.gap,
        slip: c.slip,
        active: c.active,
        stick: c.stick,
    }
}

/// A snapshot split into the bodies' nodal values.
pub fn snapshot(scene: &MultibodyScene, s: &MultibodySnapshot) -> SnapshotOut {
    let set = &scene.problem.bodies;
    SnapshotOut {
        step: s.step,
        time: s.time,
        bodies: (0..set.len())
            .map(|b| {
                let r = set.range(b);
                BodyState {
                    displacement: set.body(b).nodal(&s.displacement[r.clone()]),
                    velocity: set.body(b).nodal(&s.velocity[r]),
                }
            })
            .collect(),
        contacts: s.contacts.iter().map(|c| contact(scene, c)).collect(),
    }
}

/// The audit summary as JSON: the drifts relative to E_0 left out when E_0 = 0 (bodies at rest
/// and unstrained at t = 0: no relative drift is defined), with a note.
pub fn summary(s: &MultibodySummary, e0: f64) -> Value {
    let mut v = serde_json::to_value(s).unwrap_or(Value::Null);
    if e0 == 0.0 {
        if let Value::Object(o) = &mut v {
            for k in ["energy_drift", "unchanged_relative", "activation_relative"] {
                o.remove(k);
            }
            o.insert(
                "relative_drifts".into(),
                json!("undefined: E_0 = 0 (every body at rest and unstrained at t = 0)"),
            );
        }
    }
    v
}

/// A number as JSON, or its text when it is not finite.
fn finite_or_text(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        json!(x.to_string())
    }
}

/// The typed error as JSON: its message, its kind and where it happened.
pub fn error(e: &LabError) -> Value {
    let mut v = json!({ "message": e.to_string() });
    let (kind, data) = match e {
        LabError::Solve(SolveError::NewtonNotConverged {
            step,
            time,
            iterations,
            residual,
            ..
        }) => (
            "newton_not_converged",
            json!({ "step": step, "time": time, "iterations": iterations,
                    "residual": finite_or_text(*residual) }),
        ),
        LabError::Solve(SolveError::ActiveSetCycle {
            step,
            time,
            period,
            constraints,
            ..
        }) => (
            "active_set_cycle",
            json!({ "step": step, "time": time, "period": period, "constraints": constraints }),
        ),
        LabError::Solve(SolveError::NonFinite {
            step,
            time,
            quantity,
            ..
        }) => (
            "non_finite",
            json!({ "step": step, "time": time, "quantity": quantity }),
        ),
        LabError::Solve(SolveError::NoEquilibrium { step, time, reason }) => (
            "no_equilibrium",
            json!({ "step": step, "time": time, "reason": reason }),
        ),
        LabError::Solve(SolveError::Stopped { at, reason }) => {
            ("stopped", json!({ "at": at, "reason": reason }))
        }
        LabError::Solve(SolveError::Singular { operator, row, .. }) => {
            ("singular", json!({ "operator": operator, "row": row }))
        }
        LabError::Solve(_) => ("solve", json!({})),
        LabError::Input(_) => ("input", json!({})),
        LabError::Scene { .. } => ("scene", json!({})),
        LabError::Mesh(_) => ("mesh", json!({})),
    };
    if let (Value::Object(o), Value::Object(d)) = (&mut v, data) {
        o.insert("kind".into(), json!(kind));
        o.extend(d);
    }
    v
}
