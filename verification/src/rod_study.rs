//! A rod study: the problem, the exact solution and the discretization options of a case, and one
//! run of it at (M, N, scheme) with its errors, statistics and CPU time.

use std::collections::BTreeMap;
use std::time::Instant;

use serde::Serialize;

use contactlab::error::Error as LabError;
use contactlab::mesh::interval::{GradingEnd, IntervalMesh};
use contactlab::model::quasistatic::rod::RodProblem;
use contactlab::model::quasistatic::rod_solver::{RodParams, RodSolver};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::scene::rod::{RodScene, RodSceneFile};
use contactlab::time::grid::TimeGrid;

use crate::case::{CaseFile, DiscretizationSpec, ExactSpec};
use crate::exact::rod_constant_data::RodConstantData;
use crate::exact::rod_paper::{PaperP0Equals2, PaperP0Equals6};
use crate::exact::RodExactSolution;
use crate::manufactured::rod::RodManufactured;
use crate::rod_errors::RodErrorObserver;

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

/// One run of a study.
#[derive(Debug, Clone, Serialize)]
pub struct LevelResult {
    pub elements: usize,
    pub steps: usize,
    /// max element length.
    pub h: f64,
    /// max time step.
    pub k: f64,
    pub scheme: TimeScheme,
    /// Error functionals by name (empty without an exact solution).
    pub errors: BTreeMap<String, f64>,
    /// u_h(L, T).
    pub u_end: f64,
    /// Wall time of the solver run including the error observer (s).
    pub cpu_seconds: f64,
    /// The solver's statistics (the model's own statistics type, as JSON).
    pub stats: serde_json::Value,
}

/// Fills the mesh and time sections a case scene may omit (they are set per run).
fn complete_scene_table(table: &toml::Table) -> toml::Table {
    let mut t = table.clone();
    t.entry("mesh".to_string())
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    t.entry("time".to_string())
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    if let Some(toml::Value::Table(m)) = t.get_mut("mesh") {
        if !m.contains_key("elements") && !m.contains_key("nodes") {
            m.insert("elements".into(), toml::Value::Integer(1));
        }
    }
    if let Some(toml::Value::Table(m)) = t.get_mut("time") {
        if !m.contains_key("steps") && !m.contains_key("times") {
            m.insert("steps".into(), toml::Value::Integer(1));
        }
    }
    t
}

/// Sets a dotted key (`foundation.p0`) of a scene table.
pub fn set_dotted(table: &mut toml::Table, key: &str, value: toml::Value) {
    let mut parts: Vec<&str> = key.split('.').collect();
    let last = parts.pop().unwrap_or(key);
    let mut t = table;
    for p in parts {
        let entry = t
            .entry(p.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        if !entry.is_table() {
            *entry = toml::Value::Table(toml::Table::new());
        }
        t = match entry {
            toml::Value::Table(inner) => inner,
            _ => unreachable!("just made a table"),
        };
    }
    t.insert(last.to_string(), value);
}

/// The exact solution named `spec` for `problem` (manufactured solutions bring their own problem,
/// returned alongside).
fn exact_solution(
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
    /// The study of a case.
    pub fn from_case(case: &CaseFile) -> Result<Self, StudyError> {
        Self::new(
            case.scene.as_ref(),
            case.exact.as_ref(),
            &case.discretization,
        )
    }

    /// A study from an optional scene table, an optional exact solution and options.
    pub fn new(
        scene: Option<&toml::Table>,
        exact: Option<&ExactSpec>,
        disc: &DiscretizationSpec,
    ) -> Result<Self, StudyError> {
        let parsed = match scene {
            Some(table) => {
                let file: RodSceneFile =
                    complete_scene_table(table)
                        .try_into()
                        .map_err(|e: toml::de::Error| {
                            StudyError::Scene(LabError::Scene {
                                source_name: "case scene".to_string(),
                                message: e.to_string(),
                            })
                        })?;
                let scene = RodScene::from_file(&file)?;
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
        RodSolver::new(
            &self.problem,
            self.mesh(elements)?,
            self.grid(steps)?,
            scheme,
            self.params,
        )
    }

    /// Runs (M, N, scheme) and measures the errors against the exact solution.
    pub fn run_level(
        &self,
        elements: usize,
        steps: usize,
        scheme: TimeScheme,
    ) -> Result<LevelResult, LabError> {
        let solver = self.solver(elements, steps, scheme)?;
        let (a, b) = (self.problem.viscosity, self.problem.elasticity);
        let start = Instant::now();
        let mut u_end = 0.0;
        let m = elements;
        let (errors, stats) = match &self.exact {
            Some(exact) => {
                let mut obs = RodErrorObserver::new(exact.as_ref(), a, b, steps);
                let mut both = |s: &contactlab::model::quasistatic::rod_solver::RodStep<'_>| {
                    contactlab::model::quasistatic::rod_solver::RodObserver::observe(&mut obs, s);
                    u_end = s.u[m];
                };
                let stats = solver.run(&mut both)?;
                (obs.errors(), stats)
            }
            None => {
                let stats = solver.run(
                    &mut |s: &contactlab::model::quasistatic::rod_solver::RodStep<'_>| {
                        u_end = s.u[m];
                    },
                )?;
                (BTreeMap::new(), stats)
            }
        };
        let cpu_seconds = start.elapsed().as_secs_f64();
        Ok(LevelResult {
            elements,
            steps,
            h: solver.mesh().h_max(),
            k: solver.grid().k_max(),
            scheme,
            errors,
            u_end,
            cpu_seconds,
            stats: serde_json::to_value(&stats).unwrap_or(serde_json::Value::Null),
        })
    }
}
