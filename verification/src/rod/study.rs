//! The rod's study: the problem (an inline scene or a manufactured solution's own data), the exact
//! solution and the discretization options of a case, and one run at (M, N, scheme) with its
//! errors, statistics and CPU time.

use std::collections::BTreeMap;

use serde::Deserialize;

use contactlab::error::Error as LabError;
use contactlab::mesh::interval::{GradingEnd, IntervalMesh};
use contactlab::model::quasistatic::rod::RodProblem;
use contactlab::model::quasistatic::rod_solver::{RodObserver, RodParams, RodSolver, RodStep};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::scene::rod::{RodScene, RodSceneFile};
use contactlab::time::grid::TimeGrid;

use crate::core::cpu_clock::thread_cpu_seconds;
use crate::core::study::Study;
use crate::core::sweep::{Level, Measured};
use crate::exact::rod_constant_data::RodConstantData;
use crate::exact::rod_paper::{PaperP0Equals2, PaperP0Equals6};
use crate::exact::RodExactSolution;
use crate::manufactured::rod::RodManufactured;
use crate::rod::errors::RodErrorObserver;

/// `[exact]`: the solution the errors are measured against.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExactSpec {
    /// `rod_constant_data` (the family, data from the scene), `paper_4_6`, `paper_4_7`,
    /// `rod_manufactured_switching`, `rod_manufactured_receding` (these bring their own data).
    pub solution: String,
}

/// `[discretization]`: options of every run of a case (defaults: the scene's).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Discretization {
    pub mesh_grading: Option<f64>,
    pub graded_towards: Option<GradingEnd>,
    pub time_grading: Option<f64>,
    pub post_process_velocity: Option<bool>,
}

/// Why a study cannot be set up.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    #[error("scene: {0}")]
    Scene(#[from] LabError),
    #[error("exact solution `{name}`: {message}")]
    Exact { name: String, message: String },
}

/// The problem, exact solution and discretization options of a case.
pub struct RodStudy {
    pub problem: RodProblem,
    pub exact: Option<Box<dyn RodExactSolution>>,
    pub mesh_grading: f64,
    pub graded_towards: GradingEnd,
    pub time_grading: f64,
    pub scheme: TimeScheme,
    pub params: RodParams,
}

/// A case's scene table as a rod scene file: `mesh` and `time` get a placeholder level when they
/// name none (every run sets its own M and N).
pub fn case_scene_file(table: &toml::Table) -> Result<RodSceneFile, StudyError> {
    let mut t = table.clone();
    for (section, key, alternative) in [("mesh", "elements", "nodes"), ("time", "steps", "times")] {
        let entry = t
            .entry(section.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        if let toml::Value::Table(m) = entry {
            if !m.contains_key(key) && !m.contains_key(alternative) {
                m.insert(key.into(), toml::Value::Integer(1));
            }
        }
    }
    t.try_into().map_err(|e: toml::de::Error| {
        StudyError::Scene(LabError::Scene {
            source_name: "case scene".to_string(),
            message: e.to_string(),
        })
    })
}

/// The exact solution named `spec` for `problem` (manufactured solutions bring their own problem,
/// returned alongside).
pub fn exact_solution(
    spec: &ExactSpec,
    problem: Option<&RodProblem>,
) -> Result<(Box<dyn RodExactSolution>, Option<RodProblem>), StudyError> {
    let name = spec.solution.as_str();
    let need_problem = || {
        problem.ok_or_else(|| StudyError::Exact {
            name: name.to_string(),
            message: "needs a [scene] with the data".to_string(),
        })
    };
    Ok(match name {
        "rod_constant_data" => {
            let s =
                RodConstantData::for_problem(need_problem()?).map_err(|e| StudyError::Exact {
                    name: name.to_string(),
                    message: e.to_string(),
                })?;
            (Box::new(s), None)
        }
        "paper_4_6" => (Box::new(PaperP0Equals6), None),
        "paper_4_7" => (Box::new(PaperP0Equals2), None),
        "rod_manufactured_switching" => {
            let m = RodManufactured::switching();
            let p = m.problem();
            (Box::new(m), Some(p))
        }
        "rod_manufactured_receding" => {
            let m = RodManufactured::receding_smooth();
            let p = m.problem();
            (Box::new(m), Some(p))
        }
        other => {
            return Err(StudyError::Exact {
                name: other.to_string(),
                message: "unknown; known: rod_constant_data, paper_4_6, paper_4_7, \
                          rod_manufactured_switching, rod_manufactured_receding"
                    .to_string(),
            })
        }
    })
}

impl RodStudy {
    /// A study from an optional scene table, an optional exact solution and options.
    pub fn new(
        scene: Option<&toml::Table>,
        exact: Option<&ExactSpec>,
        disc: &Discretization,
    ) -> Result<Self, StudyError> {
        let parsed = match scene {
            Some(table) => {
                let file: RodSceneFile = case_scene_file(table)?;
                let scene = RodScene::from_file(file.clone())?;
                Some((file, scene))
            }
            None => None,
        };
        let (exact, manufactured_problem) = match exact {
            Some(spec) => {
                let (e, p) = exact_solution(spec, parsed.as_ref().map(|(_, s)| &s.problem))?;
                (Some(e), p)
            }
            None => (None, None),
        };
        let problem = match (manufactured_problem, &parsed) {
            (Some(p), _) => p,
            (None, Some((_, s))) => s.problem.clone(),
            (None, None) => {
                return Err(StudyError::Exact {
                    name: "(none)".into(),
                    message: "a case needs a scene or a manufactured solution".into(),
                })
            }
        };
        let file = parsed.as_ref().map(|(f, _)| f);
        let mut params = parsed.as_ref().map(|(_, s)| s.params).unwrap_or_default();
        if let Some(pp) = disc.post_process_velocity {
            params.post_process_velocity = pp;
        }
        Ok(Self {
            problem,
            exact,
            mesh_grading: disc
                .mesh_grading
                .or_else(|| file.and_then(|f| f.mesh.grading))
                .unwrap_or(1.0),
            graded_towards: disc
                .graded_towards
                .or_else(|| file.and_then(|f| f.mesh.graded_towards))
                .unwrap_or(GradingEnd::End),
            time_grading: disc
                .time_grading
                .or_else(|| file.and_then(|f| f.time.grading))
                .unwrap_or(1.0),
            scheme: file.map(|f| f.time.scheme).unwrap_or_default(),
            params,
        })
    }

    /// The mesh with M elements (the study's grading).
    pub fn mesh(&self, elements: usize) -> Result<IntervalMesh, LabError> {
        Ok(if self.mesh_grading == 1.0 {
            IntervalMesh::uniform(self.problem.length, elements)?
        } else {
            IntervalMesh::graded(
                self.problem.length,
                elements,
                self.mesh_grading,
                self.graded_towards,
            )?
        })
    }

    /// The time grid with N steps (the study's grading).
    pub fn grid(&self, steps: usize) -> Result<TimeGrid, LabError> {
        Ok(if self.time_grading == 1.0 {
            TimeGrid::uniform(self.problem.final_time, steps)?
        } else {
            TimeGrid::graded(self.problem.final_time, steps, self.time_grading)?
        })
    }

    /// The solver at (M, N, scheme).
    pub fn solver(
        &self,
        elements: usize,
        steps: usize,
        scheme: TimeScheme,
    ) -> Result<RodSolver, LabError> {
        // the memory first: a count beyond any machine (e.g. the planner's --base) is refused
        // before the mesh is built
        contactlab::scene::rod::require_rod_memory(
            elements as f64 + 1.0,
            steps as f64,
            0.0,
            0.0,
            [
                (
                    "mesh.elements (M of a run; the planner's --base M0)",
                    elements.to_string(),
                ),
                (
                    "time.steps (N of a run; the planner's --base N0)",
                    steps.to_string(),
                ),
            ],
        )?;
        RodSolver::new(
            &self.problem,
            self.mesh(elements)?,
            self.grid(steps)?,
            scheme,
            self.params,
        )
    }

    /// Runs (M, N, scheme) and measures the errors against the exact solution; without one,
    /// the values u_h(L, T) (`end_displacement`) and σ_h(L, T) (`contact_stress`).
    pub fn run_at(
        &self,
        elements: usize,
        steps: usize,
        scheme: TimeScheme,
    ) -> Result<Level, LabError> {
        let solver = self.solver(elements, steps, scheme)?;
        let (a, b) = (self.problem.viscosity, self.problem.elasticity);
        let m = elements;
        let mut sigma_end = 0.0;
        let mut level = Level::timed(elements, steps, scheme, || {
            let mut u_end = 0.0;
            let (errors, stats) = match &self.exact {
                Some(exact) => {
                    let mut obs = RodErrorObserver::new(exact.as_ref(), a, b, steps);
                    let mut both = |s: &RodStep<'_>| {
                        obs.observe(s);
                        u_end = s.u[m];
                    };
                    let stats = solver.run(&mut both)?;
                    (obs.errors(), stats)
                }
                None => {
                    let stats = solver.run(&mut |s: &RodStep<'_>| {
                        u_end = s.u[m];
                        sigma_end = s.contact_stress;
                    })?;
                    (BTreeMap::new(), stats)
                }
            };
            Ok::<_, LabError>(Measured {
                h: solver.mesh().h_max(),
                k: solver.grid().k_max(),
                errors,
                u_end,
                stats,
            })
        })?;
        if self.exact.is_none() {
            // without an exact solution, the values the planner's self-convergence fits
            level.values.insert("end_displacement".into(), level.u_end);
            level.values.insert("contact_stress".into(), sigma_end);
        }
        Ok(level)
    }
}

impl Study for RodStudy {
    type Scheme = TimeScheme;

    fn default_scheme(&self) -> TimeScheme {
        self.scheme
    }

    fn run_level(
        &self,
        elements: usize,
        steps: usize,
        scheme: TimeScheme,
        _time_error: bool,
    ) -> Result<Level, String> {
        self.run_at(elements, steps, scheme)
            .map_err(|e| e.to_string())
    }
}

/// The minimum over `repeats` runs of a solver's whole time loop (s of the calling thread's CPU
/// time, `core::cpu_clock`: the loop runs on this thread, and other processes sharing the cores
/// do not count), with an observer that only reads the contact velocity (so the loop cannot be
/// optimized away).
pub fn time_loop_seconds(solver: &RodSolver, repeats: usize) -> Result<f64, String> {
    let mut best = f64::INFINITY;
    for _ in 0..repeats.max(1) {
        let mut sink = 0.0;
        let start = thread_cpu_seconds();
        solver
            .run(&mut |s: &RodStep<'_>| sink += s.contact_velocity)
            .map_err(|e| e.to_string())?;
        best = best.min(thread_cpu_seconds() - start);
        std::hint::black_box(sink);
    }
    Ok(best)
}
