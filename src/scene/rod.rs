//! The rod scene (`model = "rod"`): problem T1D with general data, its discretization and outputs.
//!
//! ```toml
//! model = "rod"
//! title = "Fernández–Sofonea rod, p0 = 6"
//!
//! [rod]
//! length = 1.0                 # L (m)
//! final_time = 0.5             # T (s)
//! viscosity = 1.0              # a (N·s/m)
//! elasticity = 1.0             # b (N/m)
//! load = 10.0                  # f0 (N/m): a number or an expression of x and t, e.g. "10*(1 + x*t)"
//! initial_displacement = 0.0   # u0 (m): a number or an expression of x, with u0(0) = 0
//!
//! [foundation]
//! law = "lubricated"           # "linear" (2.7) β r | "lubricated" (2.8) β r_+ + p0 | "prescribed" (2.9) S
//! beta = 1.0                   # β (N·s/m), linear and lubricated
//! p0 = 6.0                     # oil pressure (N), lubricated: a number or an expression of t
//! # stress = "2 + t"           # S (N), prescribed: a number or an expression of t
//!
//! [mesh]
//! elements = 100               # M
//! grading = 1.0                # power-law exponent q ≥ 1 (1: uniform)
//! graded_towards = "end"       # "start" (x = 0) or "end" (x = L)
//! # nodes = [0.0, 0.3, 1.0]    # explicit nodes instead of elements/grading
//!
//! [time]
//! steps = 50                   # N
//! grading = 1.0                # t_n = T (n/N)^q
//! # times = [0.0, 0.1, 0.5]    # explicit times instead of steps/grading
//! scheme = "explicit"          # "explicit" (the paper's) | "implicit" | "midpoint"
//!
//! [output]
//! times = [0.1, 0.25, 0.5]     # snapshot times (grid times)
//! probes = [0.25, 0.5, 1.0]    # points whose displacement history is recorded
//! post_process_velocity = false
//! vtk = false                  # `verify scene` also writes ParaView files (.vtu line series, .pvd)
//!
//! [solver]
//! newton_relative_tolerance = 1.7763568394002505e-15
//! newton_max_iterations = 60
//! load_quadrature_points = 4
//!
//! # [exact]                    # optional, for the verification suite only:
//! # solution = "paper_4_6"     # `verify scene` then also writes the errors against it
//! ```

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::contact::normal_law::FoundationLaw;
use crate::error::{Error, InputError};
use crate::mesh::interval::{GradingEnd, IntervalMesh};
use crate::model::quasistatic::rod::RodProblem;
use crate::model::quasistatic::rod_output::{RodOutputRequest, RodSolution};
use crate::model::quasistatic::rod_solver::{RodParams, RodSolver};
use crate::model::quasistatic::scheme::TimeScheme;
use crate::scene::common::{check_model, parse_toml};
use crate::scene::field_spec::FieldSpec;
use crate::solve::scalar_semismooth::ScalarNewtonParams;
use crate::time::grid::TimeGrid;

/// The file format of a rod scene (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RodSceneFile {
    /// `"rod"`: the quasistatic Kelvin–Voigt rod, problem T1D of Fernández & Sofonea
    /// (docs/quasistatic.md).
    pub model: String,
    /// A title for the reports and plots (default: none).
    #[serde(default)]
    pub title: String,
    /// `[rod]`: the rod, its material and its data.
    pub rod: RodSection,
    /// `[foundation]`: the foundation law p_ν at the contact end x = L.
    pub foundation: FoundationSection,
    /// `[mesh]`: the mesh of (0, L): `elements` (with `grading`) or explicit `nodes`.
    pub mesh: MeshSection,
    /// `[time]`: the time grid of [0, T] (`steps` with `grading`, or explicit `times`) and the
    /// scheme.
    pub time: TimeSection,
    /// `[output]`: what is recorded besides the end history: snapshots and probes.
    #[serde(default)]
    pub output: OutputSection,
    /// `[solver]`: the Newton iteration at the contact end and the load quadrature.
    #[serde(default)]
    pub solver: SolverSection,
    /// `[exact]`: the exact solution the verification suite measures this scene against
    /// (`verify scene` then writes `errors.json`). The solver does not read it.
    pub exact: Option<toml::Table>,
}

/// `[rod]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RodSection {
    /// L > 0 (m): the rod is (0, L), clamped at x = 0 and in contact at x = L.
    pub length: f64,
    /// T > 0 (s): the end of the time interval.
    pub final_time: f64,
    /// a > 0 (N·s/m): the viscous modulus of σ = a u_xt + b u_x (docs/quasistatic.md, Test T1D).
    pub viscosity: f64,
    /// b > 0 (N/m): the elastic modulus of σ = a u_xt + b u_x.
    pub elasticity: f64,
    /// f0 (N/m), the body force of σ_x + f0 = 0: a number or an expression of x and t (default 0).
    #[serde(default)]
    pub load: FieldSpec,
    /// u0 (m): a number or an expression of x, with u0(0) = 0 (default 0).
    #[serde(default)]
    pub initial_displacement: FieldSpec,
}

/// `[foundation]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FoundationSection {
    /// The foundation law p_ν(r) of the end velocity r (docs/quasistatic.md): `"linear"` (2.7) β r,
    /// `"lubricated"` (2.8) β r_+ + p0, or `"prescribed"` (2.9) S.
    pub law: String,
    /// β ≥ 0 (N·s/m), the damper of laws `"linear"` and `"lubricated"` (required there, refused for
    /// `"prescribed"`).
    pub beta: Option<f64>,
    /// p0 (N), the oil pressure of law `"lubricated"` (required there, refused otherwise): a number
    /// ≥ 0 or an expression of t.
    pub p0: Option<FieldSpec>,
    /// S (N), the prescribed normal stress of law `"prescribed"` (required there, refused
    /// otherwise): a number or an expression of t.
    pub stress: Option<FieldSpec>,
}

/// `[mesh]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSection {
    /// M ≥ 1: the number of elements (uniform, or graded by `grading`); either this or `nodes`.
    pub elements: Option<usize>,
    /// q in [1, 10] with ε M^q < 1 (q < 36/ln M: 7.83 at 100 elements, 5.22 at 1000; the
    /// smallest element's relative round-off): power-law grading x_i = L (i/M)^q, mirrored when
    /// refined towards x = L (default 1: uniform).
    pub grading: Option<f64>,
    /// The end a graded mesh refines towards (default `"end"`, the contact).
    pub graded_towards: Option<GradingEnd>,
    /// Explicit nodes 0 = x_0 < … < x_M = L instead of `elements`.
    pub nodes: Option<Vec<f64>>,
}

/// `[time]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSection {
    /// N ≥ 1: the number of steps (uniform, or graded by `grading`); either this or `times`.
    pub steps: Option<usize>,
    /// q in [1, 10]: power-law graded times t_n = T (n/N)^q, small steps near t = 0 (default 1:
    /// uniform).
    pub grading: Option<f64>,
    /// Explicit times 0 = t_0 < … < t_N = T instead of `steps`.
    pub times: Option<Vec<f64>>,
    /// The time treatment of the elastic term B ε(u) (docs/quasistatic.md, the fully discrete
    /// scheme; default `"explicit"`, the paper's).
    #[serde(default)]
    pub scheme: TimeScheme,
}

/// `[output]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    /// Snapshot times, each a time of the grid: u, w (and v) at every node there (default: none).
    #[serde(default)]
    pub times: Vec<f64>,
    /// Points of [0, L] whose displacement is recorded at every step (default: none).
    #[serde(default)]
    pub probes: Vec<f64>,
    /// Also compute at each t_n the velocity the continuous problem assigns to u_n: one more solve
    /// per step, second order for `"midpoint"` (default false).
    #[serde(default)]
    pub post_process_velocity: bool,
    /// `verify scene` also writes one `.vtu` (line cells over the interval mesh) per snapshot
    /// and a `.pvd` collection (ParaView): displacement, velocity, the contact quantities.
    #[serde(default)]
    pub vtk: bool,
}

/// `[solver]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSection {
    /// The relative tolerance of the semismooth Newton iteration for the end velocity, in [machine
    /// ε, 1e-2) (default 8ε ≈ 1.8e-15).
    pub newton_relative_tolerance: Option<f64>,
    /// The most Newton iterations per step, ≥ 1 (default 60).
    pub newton_max_iterations: Option<usize>,
    /// Gauss points per element for loads that vary in x, 1 to 16 (default 4).
    pub load_quadrature_points: Option<usize>,
}

/// A validated rod scene.
#[derive(Debug, Clone)]
pub struct RodScene {
    pub title: String,
    pub problem: RodProblem,
    pub mesh: IntervalMesh,
    pub grid: TimeGrid,
    pub scheme: TimeScheme,
    pub params: RodParams,
    pub output: RodOutputRequest,
    /// The scene's `[exact]` table, for the verification suite (not read by the solver).
    pub exact: Option<toml::Table>,
    /// `[output] vtk`: `verify scene` also writes ParaView files (not read by the solver).
    pub vtk: bool,
}

impl RodScene {
    /// Parses and validates a scene from TOML text; `source_name` (a file name) labels errors.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Self, Error> {
        Self::from_file(parse_toml(text, source_name)?)
    }

    /// Validates a parsed scene file.
    pub fn from_file(file: RodSceneFile) -> Result<Self, Error> {
        check_model(&file.model, "rod")?;
        let foundation = foundation_law(&file.foundation)?;
        let problem = RodProblem {
            length: file.rod.length,
            final_time: file.rod.final_time,
            viscosity: file.rod.viscosity,
            elasticity: file.rod.elasticity,
            load: file.rod.load.to_field("rod.load")?,
            initial_displacement: file
                .rod
                .initial_displacement
                .to_field("rod.initial_displacement")?,
            foundation: Arc::new(foundation),
        };
        problem.validate()?;
        rod_memory(&file)?;
        let mesh = mesh(&file.mesh, problem.length)?;
        let grid = grid(&file.time, problem.final_time)?;
        let mut params = RodParams {
            post_process_velocity: file.output.post_process_velocity,
            ..RodParams::default()
        };
        let defaults = ScalarNewtonParams::default();
        params.newton.relative_tolerance = file
            .solver
            .newton_relative_tolerance
            .unwrap_or(defaults.relative_tolerance);
        params.newton.max_iterations = file
            .solver
            .newton_max_iterations
            .unwrap_or(defaults.max_iterations);
        if let Some(q) = file.solver.load_quadrature_points {
            params.load_quadrature_points = q;
        }
        params.validate().map_err(|e| {
            if e.field.starts_with("newton.") {
                InputError {
                    field: e.field.replacen("newton.", "solver.newton_", 1),
                    ..e
                }
            } else {
                e
            }
        })?;
        Ok(Self {
            title: file.title.clone(),
            problem,
            mesh,
            grid,
            scheme: file.time.scheme,
            params,
            output: RodOutputRequest {
                snapshot_times: file.output.times.clone(),
                probes: file.output.probes.clone(),
            },
            exact: file.exact.clone(),
            vtk: file.output.vtk,
        })
    }

    /// The solver of this scene (factored, ready to run).
    pub fn solver(&self) -> Result<RodSolver, Error> {
        RodSolver::new(
            &self.problem,
            self.mesh.clone(),
            self.grid.clone(),
            self.scheme,
            self.params,
        )
    }

    /// Solves the scene and records its outputs.
    pub fn solve(&self) -> Result<RodSolution, Error> {
        self.solver()?.solve(&self.output)
    }
}

/// The bytes a rod run holds, from the counts alone (before the mesh is built): see
/// [`require_rod_memory`]; `snapshots` counts the distinct output times.
fn rod_memory(file: &RodSceneFile) -> Result<(), Error> {
    let nodes = match (&file.mesh.nodes, file.mesh.elements) {
        (Some(n), _) => n.len() as f64,
        (None, Some(m)) => m as f64 + 1.0,
        (None, None) => return Ok(()),
    };
    let steps = match (&file.time.times, file.time.steps) {
        (Some(t), _) => t.len() as f64,
        (None, Some(n)) => n as f64,
        (None, None) => return Ok(()),
    };
    let mesh = match (&file.mesh.nodes, file.mesh.elements) {
        (Some(n), _) => format!("({} nodes)", n.len()),
        (None, m) => m.unwrap_or_default().to_string(),
    };
    let time = match (&file.time.times, file.time.steps) {
        (Some(t), _) => format!("({} times)", t.len()),
        (None, n) => n.unwrap_or_default().to_string(),
    };
    let snapshots = crate::scene::memory::distinct_times(&file.output.times) as f64;
    require_rod_memory(
        nodes,
        steps,
        snapshots,
        file.output.probes.len() as f64,
        [("mesh.elements", mesh), ("time.steps", time)],
    )
}

/// The bytes a rod run of `nodes` nodes and `steps` steps holds and writes, against the memory
/// and disk limits ([`crate::scene::memory::RunSize`]): per node about 16 vectors of the solver;
/// per snapshot u, w, v at the nodes; per step the contact-end histories (6 values) and the
/// probes — each recorded number as a double and as text. `keys` name the mesh count and the
/// step count as the user wrote them (a scene's keys, or the planner's `--base`); the one whose
/// term dominates is named.
pub fn require_rod_memory(
    nodes: f64,
    steps: f64,
    snapshots: f64,
    probes: f64,
    keys: [(&str, String); 2],
) -> Result<(), Error> {
    use crate::scene::memory::{RunSize, TEXT_BYTES};
    let [(mesh_key, mesh), (time_key, time)] = keys;
    let run = RunSize {
        mesh_key: (mesh_key.to_string(), mesh),
        outputs: snapshots,
        steps,
        memory: [
            8.0 * 16.0 * nodes,
            3.0 * nodes * (8.0 + TEXT_BYTES),
            (6.0 + probes) * (8.0 + TEXT_BYTES),
        ],
        disk: [
            TEXT_BYTES * nodes,
            3.0 * nodes * TEXT_BYTES,
            (6.0 + probes) * TEXT_BYTES,
        ],
        memory_how: "16 MiB + 8 B × 16 (M + 1) + 48 B × [3 (M + 1) × snapshots + (N + 1)(6 + \
                     probes)]",
        disk_how: "40 B a number: 3 (M + 1) × snapshots + (N + 1)(6 + probes)",
    };
    // the steps' key as written (a planner's pilot names --base, not time.steps)
    let named = |e: crate::error::InputError| {
        if e.field == "time.steps" {
            crate::error::InputError {
                field: time_key.to_string(),
                value: time.clone(),
                ..e
            }
        } else {
            e
        }
    };
    run.require().map_err(named)?;
    Ok(())
}

/// The rod's foundation law; its p0 and S act at the one contact point x = L and are functions of
/// t alone (Fernández & Sofonea (2.8), (2.9)): an expression in x or y is an error, not a value
/// silently taken at x = L.
fn foundation_law(f: &FoundationSection) -> Result<FoundationLaw, Error> {
    for (key, spec) in [("foundation.p0", &f.p0), ("foundation.stress", &f.stress)] {
        if let Some(spec) = spec {
            let d = spec.to_field(key)?.dependence();
            if d.on_space() {
                let written = match spec {
                    FieldSpec::Number(v) => v.to_string(),
                    FieldSpec::Expression(e) => format!("\"{e}\""),
                };
                return Err(InputError::new(
                    key,
                    written,
                    "a number or an expression of t alone (the rod's contact is the point x = L)",
                )
                .into());
            }
        }
    }
    Ok(crate::scene::foundation::foundation_law(
        "foundation",
        &f.law,
        f.beta,
        f.p0.as_ref(),
        f.stress.as_ref(),
    )?)
}

fn mesh(m: &MeshSection, length: f64) -> Result<IntervalMesh, InputError> {
    match (&m.nodes, m.elements) {
        (Some(_), Some(_)) => Err(InputError::new(
            "mesh.nodes",
            "(given with mesh.elements)",
            "either mesh.nodes or mesh.elements, not both",
        )),
        (Some(nodes), None) => {
            let mesh = IntervalMesh::from_nodes(nodes.clone())?;
            if (mesh.length() - length).abs() > 1e-12 * length {
                return Err(InputError::new(
                    format!("mesh.nodes[{}]", nodes.len() - 1),
                    mesh.length(),
                    format!("the rod length {length}"),
                ));
            }
            Ok(mesh)
        }
        (None, Some(elements)) => {
            let q = m.grading.unwrap_or(1.0);
            if q == 1.0 {
                IntervalMesh::uniform(length, elements)
            } else {
                IntervalMesh::graded(
                    length,
                    elements,
                    q,
                    m.graded_towards.unwrap_or(GradingEnd::End),
                )
                .map_err(|e| InputError {
                    // the mesh's own names are the scene's, except its grading exponent
                    field: if e.field == "grading.exponent" {
                        "mesh.grading".into()
                    } else {
                        e.field.clone()
                    },
                    ..e
                })
            }
        }
        (None, None) => Err(InputError::new(
            "mesh.elements",
            "(missing)",
            "a number of elements >= 1 (or mesh.nodes)",
        )),
    }
}

fn grid(t: &TimeSection, final_time: f64) -> Result<TimeGrid, InputError> {
    match (&t.times, t.steps) {
        (Some(_), Some(_)) => Err(InputError::new(
            "time.times",
            "(given with time.steps)",
            "either time.times or time.steps, not both",
        )),
        (Some(times), None) => {
            let grid = TimeGrid::from_times(times.clone())?;
            if (grid.final_time() - final_time).abs() > 1e-12 * final_time {
                return Err(InputError::new(
                    format!("time.times[{}]", times.len() - 1),
                    grid.final_time(),
                    format!("the final time {final_time}"),
                ));
            }
            Ok(grid)
        }
        (None, Some(steps)) => {
            let q = t.grading.unwrap_or(1.0);
            if q == 1.0 {
                TimeGrid::uniform(final_time, steps)
            } else {
                TimeGrid::graded(final_time, steps, q)
            }
        }
        (None, None) => Err(InputError::new(
            "time.steps",
            "(missing)",
            "a number of steps >= 1 (or time.times)",
        )),
    }
}

#[cfg(test)]
mod tests {
    //! Rod scenes: the documented example parses; typos, missing keys and bad values are errors
    //! that name the field.
    use super::*;

    #[test]
    fn a_grading_past_round_off_names_mesh_grading_and_the_elements() {
        let text = PAPER.replace("elements = 100\n", "elements = 100\ngrading = 10.0\n");
        let err = RodScene::from_toml_str(&text, "g.toml")
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("mesh.grading = 10"), "{err}");
        assert!(
            err.contains("100 elements") && err.contains("q < 7.83"),
            "{err}"
        );
        let ok = PAPER.replace("elements = 100\n", "elements = 10\ngrading = 10.0\n");
        assert!(RodScene::from_toml_str(&ok, "g.toml").is_ok());
    }

    const PAPER: &str = r#"
model = "rod"
title = "paper p0 = 6"
[rod]
length = 1.0
final_time = 0.5
viscosity = 1.0
elasticity = 1.0
load = 10
[foundation]
law = "lubricated"
beta = 1.0
p0 = 6.0
[mesh]
elements = 100
[time]
steps = 50
[output]
times = [0.25, 0.5]
probes = [0.25, 1.0]
"#;

    #[test]
    fn paper_scene_parses_and_solves() {
        let scene = RodScene::from_toml_str(PAPER, "paper.toml").unwrap();
        let sol = scene.solve().unwrap();
        assert_eq!(sol.snapshots.len(), 2);
        assert!((sol.end_displacement[50] + 0.394993932862).abs() < 1e-11);
    }

    #[test]
    fn misspelt_key_is_an_error() {
        let text = PAPER.replace("viscosity", "viscosty");
        let err = RodScene::from_toml_str(&text, "x.toml").unwrap_err();
        assert!(matches!(err, Error::Scene { .. }), "{err}");
        assert!(err.to_string().contains("viscosty"), "{err}");
    }

    #[test]
    fn negative_viscosity_names_the_field_and_value() {
        let text = PAPER.replace("viscosity = 1.0", "viscosity = -2.0");
        match RodScene::from_toml_str(&text, "x.toml").unwrap_err() {
            Error::Input(e) => {
                assert_eq!(e.field, "rod.viscosity");
                assert_eq!(e.value, "-2");
            }
            other => panic!("{other}"),
        }
    }

    #[test]
    fn unknown_law_and_missing_p0_are_errors() {
        let text = PAPER.replace("\"lubricated\"", "\"sticky\"");
        assert!(RodScene::from_toml_str(&text, "x")
            .unwrap_err()
            .to_string()
            .contains("foundation.law"));
        let text = PAPER.replace("p0 = 6.0", "");
        assert!(RodScene::from_toml_str(&text, "x")
            .unwrap_err()
            .to_string()
            .contains("foundation.p0"));
    }

    #[test]
    fn snapshot_time_off_the_grid_is_an_error() {
        let text = PAPER.replace("times = [0.25, 0.5]", "times = [0.255]");
        let err = RodScene::from_toml_str(&text, "x")
            .unwrap()
            .solve()
            .unwrap_err();
        assert!(err.to_string().contains("output.times[0]"), "{err}");
    }

    #[test]
    fn expression_load_takes_the_space_time_path() {
        let text = PAPER.replace("load = 10", "load = \"10*(1 + x*t)\"");
        let sol = RodScene::from_toml_str(&text, "x")
            .unwrap()
            .solve()
            .unwrap();
        assert_eq!(sol.stats.load_path, "space_time");
    }
}
