//! The case's `[scene]` as a plane scene, with the per-run changes the plane runners make
//! (mesh, damper, Γ1 reading, scheme, steps).

use contactlab::model::quasistatic::plane::Support;
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::scene::plane::{PlaneScene, PlaneSceneFile};

use crate::case::CaseFile;

/// The plane scene file of a case.
pub fn scene_file(case: &CaseFile) -> Result<PlaneSceneFile, String> {
    let table = case
        .scene
        .clone()
        .ok_or("this case needs a [scene] with model = \"plane\"")?;
    table
        .try_into()
        .map_err(|e: toml::de::Error| format!("[scene]: {e}"))
}

/// One variant of the scene.
#[derive(Debug, Clone, Copy, Default)]
pub struct Variant {
    pub divisions: Option<usize>,
    pub beta: Option<f64>,
    pub support: Option<Support>,
    pub scheme: Option<TimeScheme>,
    pub steps: Option<usize>,
    pub final_time: Option<f64>,
    pub start_at_first_equilibrium: Option<bool>,
}

/// The validated scene of `file` changed by `v`.
pub fn variant(file: &PlaneSceneFile, v: Variant) -> Result<PlaneScene, String> {
    let mut f = file.clone();
    if let Some(n) = v.divisions {
        f.geometry.divisions = [n, n];
    }
    if let (Some(b), Some(c)) = (v.beta, f.contact.as_mut()) {
        c.beta = Some(b);
    }
    if let Some(s) = v.support {
        for d in &mut f.dirichlet {
            d.support = s;
        }
    }
    if let Some(s) = v.scheme {
        f.time.scheme = s;
    }
    if let Some(n) = v.steps {
        f.time.steps = Some(n);
        f.time.times = None;
    }
    if let Some(t) = v.final_time {
        f.time.final_time = t;
    }
    if let Some(b) = v.start_at_first_equilibrium {
        f.solver.start_at_first_equilibrium = b;
    }
    PlaneScene::from_file(f).map_err(|e| e.to_string())
}
