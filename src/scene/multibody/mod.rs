//! The multibody scene: a dynamic scene (`model = "dynamic"`) whose bodies are written as
//! `[[body]]` sections — several plane-strain hyperelastic bodies in node-to-segment contact with
//! each other and with a rigid foundation, Lagrange multipliers or penalty, Coulomb friction,
//! and the energy–momentum scheme (the energy–momentum paper, "EM"; [`crate::model::multibody`]).
//! A dynamic scene with one `[body]` table stays the one-body scene of [`crate::scene::dynamic`]
//! with its fast paths; `[[body]]` with a single body runs that body through the multibody
//! solver.
//!
//! ```toml
//! model = "dynamic"
//! title = "two neo-Hookean rings in oblique impact"
//!
//! [[body]]
//! name = "left"                # default "body 0", "body 1", … (unique)
//! shape = "annulus"            # "rectangle" | "disk" | "annulus" | "gmsh", with the shape keys
//! center = [-1.1, 0.0]         # of the dynamic scene's [body] (a Gmsh file is relative to the
//! inner = 0.6                  # scene file)
//! outer = 1.0
//! radial = 4
//! around = 48
//! density = 1.0
//! mass = "consistent"          # "consistent" | "lumped"
//! material = { law = "neo_hooke", young = 20.0, poisson = 0.3 }  # "linear" | "st_venant_kirchhoff"
//! velocity = [1.0, 0.0]        # the initial rigid motion v + ω e_z × (X − c)
//! angular_velocity = 0.0       # ω
//! # spin_center = [-1.1, 0.0]  # c (default: the body's centre of mass)
//! body_force = [0.0, 0.0]      # numbers or expressions of x, y, t
//! # [[body.dirichlet]]         # as the dynamic scene's [[dirichlet]] (sides / where / group)
//! # [[body.traction]]          # as its [[traction]]
//!
//! [[body]]
//! name = "right"
//! shape = "annulus"
//! center = [1.1, 0.5]
//! inner = 0.6
//! outer = 1.0
//! radial = 4
//! around = 48
//! density = 1.0
//! material = { law = "neo_hooke", young = 20.0, poisson = 0.3 }
//! velocity = [-1.0, 0.0]
//!
//! [[contact_pair]]
//! slave = { body = "left", where = "(x + 1.1)^2 + y^2 - 0.64" }    # or sides = [...], group = "…"
//! master = { body = "right", where = "(x - 1.1)^2 + (y - 0.5)^2 - 0.64" }  # (default: all of it)
//! # foundation = { level = 0.0 }   # instead of master: the rigid half-plane {y ≤ level}
//! pass = "single"              # "single" | "two" (the roles exchanged as a second pair)
//! enforcement = "lagrange"     # "lagrange" | "penalty" (with stiffness = ε > 0)
//! friction = 0.0               # Coulomb's μ ≥ 0 (needs lagrange)
//! initial_overlap = "error"    # "error" | "resolve": bodies overlapping at t = 0 are refused,
//!                              # or start with the slave nodes moved onto the master
//!
//! [time]
//! final_time = 1.0
//! steps = 200
//! scheme = "energy_momentum"   # "energy_momentum" (default) | "midpoint" | "newmark"
//!
//! [output]
//! times = [0.0, 0.5, 1.0]
//! vtk = false
//!
//! [solver]                     # defaults: MultibodyParams::default()
//! tolerance = 1e-12
//! max_iterations = 60
//! search_margin = 1.0
//! max_switches = 4
//! ```
//!
//! `format` holds the file format, `body` the validation of one body, `pairs` that of the
//! contact pairs, `memory` the estimate made before anything is allocated; this module puts a
//! scene together.

mod body;
mod format;
mod memory;
mod overlap;
mod pairs;

use crate::error::{require_positive, Error, InputError};
use crate::model::dynamic::newton::NewtonParams;
use crate::model::multibody::bodies::BodySet;
use crate::model::multibody::solver::{
    MultibodyParams, MultibodyProblem, MultibodySolution, MultibodySolver,
};
use crate::scene::common::{check_model, parse_toml};

pub use format::{
    BodyMaterialSection, ContactPairSection, EnforcementName, InitialOverlap, MultibodyBodySection,
    MultibodyOutputSection, MultibodySceneFile, MultibodySolverSection, MultibodyTimeSection,
    PairFoundationSection, PairSideSection, Pass,
};
pub use overlap::{overlaps, Overlap};
pub use pairs::PairOrigin;

/// A validated multibody scene.
#[derive(Debug, Clone)]
pub struct MultibodyScene {
    pub title: String,
    /// The bodies' names, in the order of the problem's bodies.
    pub names: Vec<String>,
    pub problem: MultibodyProblem,
    pub params: MultibodyParams,
    /// For each pair of the problem, the `[[contact_pair]]` section it comes from.
    pub origins: Vec<PairOrigin>,
    pub file: MultibodySceneFile,
}

impl MultibodyScene {
    /// Parses and validates a scene from TOML text; `source_name` labels errors.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Self, Error> {
        Self::from_file(parse_toml(text, source_name)?)
    }

    /// Validates a parsed scene file.
    pub fn from_file(file: MultibodySceneFile) -> Result<Self, Error> {
        check_model(&file.model, "dynamic")?;
        if file.body.is_empty() {
            return Err(InputError::new("body", "[]", "at least one [[body]] section").into());
        }
        let names = body::names(&file.body)?;
        // the final time first: output times are checked against it
        require_positive("time.final_time", file.time.final_time)?;
        if file.time.steps == 0 {
            return Err(InputError::new("time.steps", 0, "at least 1 step").into());
        }
        for (i, t) in file.output.times.iter().enumerate() {
            if !(t.is_finite() && *t >= 0.0 && *t <= file.time.final_time) {
                return Err(InputError::new(
                    format!("output.times[{i}]"),
                    t,
                    format!("a time in [0, final_time = {}]", file.time.final_time),
                )
                .into());
            }
        }
        let params = params(&file)?;
        // the memory from the keys' counts (a Gmsh body counts once its file is read)
        let estimates: Vec<Option<(String, String, f64)>> = file
            .body
            .iter()
            .enumerate()
            .map(|(i, b)| b.plane_shape().node_estimate(&format!("body[{i}]")))
            .collect();
        let sizes = |counts: &dyn Fn(usize) -> f64| -> (Vec<f64>, Vec<(String, String)>) {
            estimates
                .iter()
                .enumerate()
                .map(|(i, e)| match e {
                    Some((field, written, _)) => (counts(i), (field.clone(), written.clone())),
                    None => (
                        counts(i),
                        (
                            format!("body[{i}].file"),
                            file.body[i].file.clone().unwrap_or_default(),
                        ),
                    ),
                })
                .unzip()
        };
        let (nodes, fields) = sizes(&|i| estimates[i].as_ref().map_or(0.0, |e| e.2));
        memory::require_run_memory(&file, &nodes, &fields)?;
        let mut meshes = Vec::with_capacity(file.body.len());
        for (i, b) in file.body.iter().enumerate() {
            meshes.push(body::mesh(i, b, file.base_dir.as_deref())?);
        }
        if meshes.iter().any(|(_, g)| g.is_some()) {
            // the node counts of the Gmsh files, once read, before the operators are built
            let (nodes, mut fields) = sizes(&|i| meshes[i].0.nodes().len() as f64);
            for (i, (m, g)) in meshes.iter().enumerate() {
                if g.is_some() {
                    fields[i].1 = format!("{} ({} nodes)", fields[i].1, m.nodes().len());
                }
            }
            memory::require_run_memory(&file, &nodes, &fields)?;
        }
        let mut bodies = Vec::with_capacity(meshes.len());
        let mut gmsh = Vec::with_capacity(meshes.len());
        for (i, (mesh, g)) in meshes.into_iter().enumerate() {
            bodies.push(body::plane_body(i, &file.body[i], (mesh, g.as_ref()))?);
            gmsh.push(g);
        }
        let bodies = BodySet::new(bodies)?;
        let (pairs, origins) = pairs::pairs(&file.contact_pair, &names, &bodies, &gmsh)?;
        let mut params = params;
        params.allow_energy_gain = origins
            .iter()
            .map(|o| file.contact_pair[o.section].allow_energy_gain)
            .collect();
        let initial_velocity = body::initial_velocity(&file.body, &bodies)?;
        let modes: Vec<_> = file
            .contact_pair
            .iter()
            .map(|c| c.initial_overlap)
            .collect();
        let initial_displacement =
            overlap::initial_displacement(&bodies, &pairs, &origins, &names, &modes)?;
        let problem = MultibodyProblem {
            initial_displacement,
            initial_velocity,
            bodies,
            pairs,
            scheme: file.time.scheme,
            final_time: file.time.final_time,
            steps: file.time.steps,
        };
        // validate everything the solver checks, now
        MultibodySolver::new(problem.clone(), params.clone())?;
        Ok(Self {
            title: file.title.clone(),
            names,
            problem,
            params,
            origins,
            file,
        })
    }

    /// The solver of the scene.
    pub fn solver(&self) -> Result<MultibodySolver, Error> {
        MultibodySolver::new(self.problem.clone(), self.params.clone())
    }

    /// Runs the scene.
    pub fn solve(&self) -> Result<MultibodySolution, Error> {
        self.solver()?.solve()
    }
}

/// The solver parameters of `[solver]` and `[output] times` (defaults:
/// [`MultibodyParams::default`]); errors name `solver.*`.
fn params(file: &MultibodySceneFile) -> Result<MultibodyParams, InputError> {
    let mut params = MultibodyParams {
        snapshot_times: file.output.times.clone(),
        ..MultibodyParams::default()
    };
    let s = &file.solver;
    let mut newton = NewtonParams::default();
    if let Some(t) = s.tolerance {
        if !(t.is_finite() && t > 0.0 && t < 1.0) {
            return Err(InputError::new("solver.tolerance", t, "a number in (0, 1)"));
        }
        newton.tolerance = t;
    }
    if let Some(m) = s.max_iterations {
        if m == 0 {
            return Err(InputError::new("solver.max_iterations", m, "at least 1"));
        }
        newton.max_iterations = m;
    }
    params.newton = newton;
    if let Some(m) = s.search_margin {
        params.search_margin = require_positive("solver.search_margin", m)?;
    }
    if let Some(m) = s.max_switches {
        params.max_switches = m;
    }
    Ok(params)
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod overlap_tests;
