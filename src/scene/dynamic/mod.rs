//! The dynamic scene (`model = "dynamic"`): an elastic body thrown at (or resting on) a rigid
//! foundation — body shape and mesh, hyperelastic material, scheme, contact treatment, friction,
//! initial state and outputs (Barboteu–Danan–Sofonea (1.14)–(1.20)).
//!
//! ```toml
//! model = "dynamic"
//! title = "neo-Hookean ring thrown obliquely at the foundation"
//!
//! [body]
//! shape = "annulus"            # "bar" | "rectangle" | "disk" | "annulus" | "gmsh" (file =
//!                               # "part.msh" relative to the scene file, optional scale, offset;
//!                               # boundary parts then may select group = "name" of the file)
//! center = [0.0, 0.52]         # disk, annulus
//! inner = 0.3                  # annulus
//! outer = 0.5                  # annulus; disk: radius = 0.5, rings = 12
//! radial = 4                   # annulus
//! around = 64                  # annulus
//! # rectangle: origin = [0, 0], size = [1, 1], divisions = [8, 8], diagonal = "up"
//! # bar: length = 1.0, elements = 100, area = 1.0, supports = ["right"]
//! density = 1000.0
//! mass = "consistent"          # "consistent" | "lumped"
//!
//! [material]                   # "linear" | "st_venant_kirchhoff" | "neo_hooke" (plane strain)
//! law = "neo_hooke"            # bar: "linear" | "st_venant_kirchhoff", young only
//! young = 1e6
//! poisson = 0.3
//!
//! [time]
//! final_time = 0.06
//! steps = 600
//! scheme = "gonzalez"          # "newmark" | "midpoint" | "gonzalez"
//!
//! [initial]
//! velocity = [4.0, -8.0]       # numbers or expressions of x, y (bar: one value, e.g. -1.0)
//! displacement = [0.0, 0.0]
//!
//! [body_force]
//! value = [0.0, 0.0]           # numbers or expressions of x, y, t (bar: one value)
//!
//! [[dirichlet]]                # 2D: sides (rectangle) or where = "expression > 0 on the part"
//! where = "y - 0.999"
//! support = "clamped"
//!
//! [[traction]]
//! sides = ["top"]
//! value = [0.0, "-100*t"]
//!
//! [contact]
//! level = 0.0                  # 2D: the foundation {x2 ≤ level}
//! where = "0.52 - y"           # 2D: the candidate contact boundary (default: all of it)
//! # bar: end = "left", wall = 0.0
//! treatment = "limited_penetration"   # "penalty" | "energy_consistent" (= "hauret_le_tallec")
//!                                      # | "hauret_le_tallec_tilted" | "limited_penetration" | "signorini"
//! stiffness = 1e9              # r (all but signorini)
//! depth = 5e-4                 # g (limited_penetration)
//!
//! [contact.friction]           # optional (2D): "constant" | "growing" (μ1 of (1.13)) | "decreasing" (μ2)
//! law = "growing"
//! mu0 = 0.3
//! depth = 5e-4                 # g of (1.13); default: contact.depth
//!
//! # [[region]]                 # gmsh: a 2D physical group with its own density and/or material
//! # group = "core"             # (a key left out is the body's: body.density, [material]'s keys;
//! # density = 2000.0           # regions must not overlap)
//! # material = { law = "st_venant_kirchhoff", young = 5e6 }
//!
//! [output]
//! times = [0.01, 0.02]         # snapshots of the displacement
//! vtk = false                  # `verify scene` also writes ParaView files (.vtu per time, .pvd)
//!
//! [solver]
//! tolerance = 1e-12
//! max_iterations = 60
//! path = "auto"                # "auto" (the model decides) | "full" (for comparisons)
//! ```
//!
//! `format` holds the file format, `body` the validated body, `bar` and `plane` the validation of
//! the two kinds of body, `contact` the contact treatment and friction; this module puts a scene
//! together.

mod bar;
mod body;
mod contact;
mod format;
mod plane;

use std::sync::Arc;

use crate::error::{Error, InputError};
use crate::model::dynamic::body::ElasticBody;
use crate::model::dynamic::newton::NewtonParams;
use crate::model::dynamic::solver::{
    DynamicParams, DynamicProblem, DynamicSolution, DynamicSolver,
};
use crate::scene::common::{check_model, parse_toml, reject_keys};

pub use body::SceneBody;
pub use format::{
    BodySection, DynamicContactSection, DynamicInitialSection, DynamicMaterialSection,
    DynamicOutputSection, DynamicRegionSection, DynamicSceneFile, DynamicSolverSection,
    DynamicTimeSection, FrictionSection, RegionMaterialSection, ValueSection, ValueSpec,
};

/// A validated dynamic scene.
#[derive(Debug, Clone)]
pub struct DynamicScene {
    pub title: String,
    pub body: SceneBody,
    pub problem: DynamicProblem,
    pub params: DynamicParams,
    pub file: DynamicSceneFile,
}

impl DynamicScene {
    /// Parses and validates a scene from TOML text; `source_name` labels errors.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Self, Error> {
        Self::from_file(parse_toml(text, source_name)?)
    }

    /// Validates a parsed scene file.
    pub fn from_file(file: DynamicSceneFile) -> Result<Self, Error> {
        check_model(&file.model, "dynamic")?;
        dynamic_memory(&file)?;
        let b = &file.body;
        let given = [
            ("length", b.length.is_some()),
            ("elements", b.elements.is_some()),
            ("area", b.area.is_some()),
            ("supports", b.supports.is_some()),
            ("origin", b.origin.is_some()),
            ("size", b.size.is_some()),
            ("divisions", b.divisions.is_some()),
            ("diagonal", b.diagonal.is_some()),
            ("center", b.center.is_some()),
            ("radius", b.radius.is_some()),
            ("rings", b.rings.is_some()),
            ("inner", b.inner.is_some()),
            ("outer", b.outer.is_some()),
            ("radial", b.radial.is_some()),
            ("around", b.around.is_some()),
            ("file", b.file.is_some()),
            ("scale", b.scale.is_some()),
            ("offset", b.offset.is_some()),
        ];
        let (body, contact, u0, v0) = if b.shape == "bar" {
            let allowed = ["length", "elements", "area", "supports"];
            reject_keys("body", ("shape", "bar"), &given, &allowed)?;
            if let Some(r) = file.region.first() {
                return Err(InputError::new(
                    "region[0].group",
                    format!("\"{}\"", r.group),
                    "a plane body read from a Gmsh file (body.shape = \"gmsh\") to name its \
                     regions",
                )
                .into());
            }
            bar::bar(&file)?
        } else {
            let (mesh, gmsh) = plane::mesh(b, &given, file.base_dir.as_deref())?;
            if gmsh.is_some() {
                // a Gmsh body's counts are known once the file is read (the reader bounds the
                // file and its counts): the estimate before the operators are built
                let written = format!(
                    "{} ({} nodes)",
                    b.file.as_deref().unwrap_or_default(),
                    mesh.nodes().len()
                );
                require_run_memory(&file, "body.file", written, mesh.nodes().len() as f64, 2.0)?;
            }
            plane::plane(&file, (mesh, gmsh))?
        };
        let dyn_body: Arc<dyn ElasticBody> = match &body {
            SceneBody::Bar(b) => b.clone(),
            SceneBody::Plane(p) => p.clone(),
        };
        let mut newton = NewtonParams::default();
        if let Some(t) = file.solver.tolerance {
            newton.tolerance = t;
        }
        if let Some(m) = file.solver.max_iterations {
            newton.max_iterations = m;
        }
        let force_full_path = match file.solver.path.as_deref() {
            None | Some("auto") => false,
            Some("full") => true,
            Some(other) => {
                return Err(InputError::new(
                    "solver.path",
                    format!("\"{other}\""),
                    "\"auto\" or \"full\"",
                )
                .into())
            }
        };
        // the final time first: output times are checked against it
        crate::error::require_positive("time.final_time", file.time.final_time)?;
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
        let params = DynamicParams {
            newton,
            force_full_path,
            snapshot_times: file.output.times.clone(),
        };
        let problem = DynamicProblem {
            body: dyn_body,
            contact,
            scheme: file.time.scheme,
            final_time: file.time.final_time,
            steps: file.time.steps,
            initial_displacement: u0,
            initial_velocity: v0,
        };
        // validate everything the solver checks, now
        DynamicSolver::new(problem.clone(), params.clone())?;
        Ok(Self {
            title: file.title.clone(),
            body,
            problem,
            params,
            file,
        })
    }

    /// The solver of the scene.
    pub fn solver(&self) -> Result<DynamicSolver, Error> {
        DynamicSolver::new(self.problem.clone(), self.params.clone())
    }

    /// Runs the scene.
    pub fn solve(&self) -> Result<DynamicSolution, Error> {
        self.solver()?.solve()
    }
}

/// The bytes a dynamic run holds and writes, from the counts alone (before the mesh is built):
/// see [`require_run_memory`]. The node count by shape: bar M + 1, rectangle
/// (n_x + 1)(n_y + 1), disk at most 4 (rings + 1)², annulus (radial + 1) × around; a Gmsh body
/// the node count of its file, once read.
fn dynamic_memory(file: &DynamicSceneFile) -> Result<(), Error> {
    let b = &file.body;
    let (field, written, nodes, dim) = match b.shape.as_str() {
        "bar" => (
            "body.elements".to_string(),
            b.elements.unwrap_or_default().to_string(),
            b.elements.map_or(0.0, |n| n as f64) + 1.0,
            1.0,
        ),
        // "gmsh": checked once the file is read, from its node count (require_run_memory)
        _ => match b.plane_shape().node_estimate("body") {
            Some((field, written, nodes)) => (field, written, nodes, 2.0),
            None => return Ok(()),
        },
    };
    require_run_memory(file, &field, written, nodes, dim)
}

/// The estimate of [`dynamic_memory`] for a body of `nodes` nodes in `dim` dimensions, against
/// the memory and disk limits ([`crate::scene::memory::RunSize`]); `field` and `written` name the
/// key that sets the size. Per mesh the operators and factor, 8 B × dofs (70 + 4 log₂ dofs); per
/// distinct output time 5 copies of a state (the solver's snapshot, the recorder's displacement,
/// velocity and forces, the nodal copy written) and the displacement's text in solution.json,
/// with `vtk` 6 more vectors and their text in the frame; per step the audit record (16 values)
/// and its text in energy_audit.json and the plots (30 numbers measured).
fn require_run_memory(
    file: &DynamicSceneFile,
    field: &str,
    written: String,
    nodes: f64,
    dim: f64,
) -> Result<(), Error> {
    use crate::scene::memory::{distinct_times, RunSize, TEXT_BYTES};
    let dofs = dim * nodes;
    let vtk = if file.output.vtk { 1.0 } else { 0.0 };
    let run = RunSize {
        mesh_key: (field.to_string(), written),
        outputs: distinct_times(&file.output.times) as f64,
        steps: file.time.steps as f64,
        memory: [
            8.0 * dofs * (70.0 + 4.0 * dofs.max(2.0).log2()),
            dofs * (8.0 * 5.0 + TEXT_BYTES + vtk * 6.0 * (8.0 + TEXT_BYTES)),
            8.0 * 16.0 + 30.0 * TEXT_BYTES,
        ],
        disk: [
            TEXT_BYTES * 3.0 * dofs,
            dofs * TEXT_BYTES * (1.0 + 6.0 * vtk),
            30.0 * TEXT_BYTES,
        ],
        memory_how: "16 MiB + 8 B × dofs (70 + 4 log₂ dofs) + output times × dofs × \
                     (5 × 8 B + 40 B of text; VTK: 6 × 48 B) + (N + 1) × (16 × 8 B + 30 × 40 B)",
        disk_how: "40 B a number: output times × dofs (1, VTK 7) + (N + 1) × 30",
    };
    run.require()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    //! Dynamic scenes: the documented example parses and runs; misplaced and missing keys are
    //! named in the errors.
    use super::*;

    const RING: &str = r#"
model = "dynamic"
title = "ring"
[body]
shape = "annulus"
center = [0.0, 0.502]
inner = 0.3
outer = 0.5
radial = 2
around = 24
density = 1000.0
[material]
law = "neo_hooke"
young = 1e6
poisson = 0.3
[time]
final_time = 0.004
steps = 8
scheme = "gonzalez"
[initial]
velocity = [4.0, -8.0]
[contact]
level = 0.0
where = "0.502 - y"
treatment = "limited_penetration"
stiffness = 1e9
depth = 5e-4
[contact.friction]
law = "growing"
mu0 = 0.3
"#;

    #[test]
    fn a_level_inside_the_body_names_contact_level_and_the_depth() {
        let text = RING.replace("level = 0.0", "level = 1e3");
        let err = DynamicScene::from_toml_str(&text, "ring")
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("contact.level = 1000"), "{err}");
        assert!(err.contains("below the level"), "{err}");
        // inside the layer of limited penetration is admitted; one layer deeper is not
        let inside = RING.replace("level = 0.0", "level = 0.0024");
        assert!(DynamicScene::from_toml_str(&inside, "ring").is_ok());
        let deeper = RING.replace("level = 0.0", "level = 0.0026");
        assert!(DynamicScene::from_toml_str(&deeper, "ring").is_err());
    }

    #[test]
    fn ring_scene_parses_and_runs() {
        let scene = DynamicScene::from_toml_str(RING, "ring").expect("valid scene");
        let sol = scene.solve().expect("runs");
        assert_eq!(sol.audit.records.len(), 9);
        assert!(matches!(scene.body, SceneBody::Plane(_)));
    }

    #[test]
    fn key_of_another_shape_is_named() {
        let text = RING.replace("radial = 2", "radial = 2\nradius = 0.5");
        let err = DynamicScene::from_toml_str(&text, "ring").unwrap_err();
        assert!(err.to_string().contains("body.radius"), "{err}");
    }

    #[test]
    fn missing_stiffness_is_named() {
        let text = RING.replace("stiffness = 1e9\n", "");
        let err = DynamicScene::from_toml_str(&text, "ring").unwrap_err();
        assert!(err.to_string().contains("contact.stiffness"), "{err}");
    }

    #[test]
    fn newmark_with_energy_consistent_force_is_rejected() {
        let text = RING.replace("scheme = \"gonzalez\"", "scheme = \"newmark\"");
        let err = DynamicScene::from_toml_str(&text, "ring").unwrap_err();
        assert!(err.to_string().contains("scheme"), "{err}");
    }

    #[test]
    fn bar_scene_parses() {
        let text = r#"
model = "dynamic"
[body]
shape = "bar"
length = 1.0
elements = 20
supports = ["right"]
density = 1.0
[material]
law = "linear"
young = 1.0
[time]
final_time = 1.0
steps = 20
scheme = "midpoint"
[initial]
displacement = "(1 - x)/2"
[contact]
end = "left"
wall = 0.0
treatment = "signorini"
"#;
        let scene = DynamicScene::from_toml_str(text, "bar").expect("valid bar scene");
        assert!(matches!(scene.body, SceneBody::Bar(_)));
        scene.solve().expect("runs");
    }
}
