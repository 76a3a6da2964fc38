//! What a scene's audit may claim ([`Claims`] of the multibody study), read from the scene:
//! the energy identity for the energy–momentum scheme; P_x, P_y where no support, traction, body
//! force or foundation acts along the component; J where both are free, every law is objective
//! and the scheme is of midpoint type. The summary prints each ratio with whether it is claimed.

use serde::Serialize;

use contactlab::model::multibody::solver::PairMaster;
use contactlab::scene::field_spec::FieldSpec;
use contactlab::scene::multibody::MultibodyScene;

use crate::multibody::study::Claims;

/// The claims of a scene, with the reason of each component that is not free.
#[derive(Debug, Clone, Serialize)]
pub struct SceneClaims {
    /// E_{n+1} − E_n = W_N + W_T + W_ext to round-off (energy–momentum).
    pub identity: bool,
    /// P_x, P_y conserved.
    pub momentum: [bool; 2],
    /// J conserved.
    pub angular: bool,
    /// Why a component of P is not conserved (empty where it is).
    pub reasons: [String; 2],
}

/// The claims of `scene`.
pub fn of(scene: &MultibodyScene) -> SceneClaims {
    let mut reasons = [Vec::new(), Vec::new()];
    for (b, body) in scene.file.body.iter().enumerate() {
        let name = &scene.names[b];
        for d in &body.dirichlet {
            for (c, r) in reasons.iter_mut().enumerate() {
                if d.support.fixes(c) {
                    r.push(format!("{name} is held"));
                }
            }
        }
        if !body.traction.is_empty() {
            for r in reasons.iter_mut() {
                r.push(format!("{name} is loaded by a traction"));
            }
        }
        for (c, f) in body.body_force.iter().enumerate() {
            if !matches!(f, FieldSpec::Number(x) if *x == 0.0) {
                reasons[c].push(format!("{name} has a body force"));
            }
        }
    }
    for p in &scene.problem.pairs {
        if let PairMaster::Foundation(_) = p.master {
            reasons[1].push("a foundation".to_string());
            if p.law.friction > 0.0 {
                reasons[0].push("a foundation with friction".to_string());
            }
        }
    }
    let free = [reasons[0].is_empty(), reasons[1].is_empty()];
    let objective = scene.file.body.iter().all(|b| b.material.law != "linear");
    let c = Claims::of(scene.problem.scheme, free, objective);
    let reason = |r: &mut Vec<String>| {
        r.dedup();
        r.join(", ")
    };
    let [mut rx, mut ry] = reasons;
    SceneClaims {
        identity: c.identity,
        momentum: c.momentum,
        angular: c.angular,
        reasons: [reason(&mut rx), reason(&mut ry)],
    }
}

impl SceneClaims {
    /// Why J is not conserved (empty where it is).
    pub fn angular_reason(&self, scene: &MultibodyScene) -> String {
        if self.angular {
            String::new()
        } else if !(self.momentum[0] && self.momentum[1]) {
            "external forces act".into()
        } else if !scene.problem.scheme.is_midpoint_type() {
            "Newmark does not conserve it".into()
        } else {
            "a linear (non-objective) law".into()
        }
    }
}
