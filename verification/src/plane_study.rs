//! A plane study: a manufactured solution with the case's discretization options, and one run of
//! it at (n × n squares, N steps, scheme) with its errors — including, where asked, the time error
//! against a run on the same mesh with a much smaller step.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

use contactlab::model::quasistatic::plane::ContactIntegration;
use contactlab::model::quasistatic::plane_solver::{PlaneParams, PlaneSolver, SolverPath};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::time::grid::TimeGrid;

use crate::manufactured::plane::PlaneManufactured;
use crate::plane_errors::{l2_difference, PlaneErrorObserver};
use crate::rod_study::LevelResult;

/// The reference u_N of one mesh, computed once.
type Reference = Arc<OnceLock<Result<Vec<f64>, String>>>;

/// The problem and options of a plane convergence case.
pub struct PlaneStudy {
    pub exact: PlaneManufactured,
    pub integration: ContactIntegration,
    pub scheme: TimeScheme,
    pub path: SolverPath,
    /// Steps of the reference run for `time_l2_final` (midpoint scheme, same mesh).
    pub time_reference_steps: Option<usize>,
    references: Mutex<BTreeMap<usize, Reference>>,
}

impl PlaneStudy {
    /// A study of `exact`.
    pub fn new(
        exact: PlaneManufactured,
        integration: ContactIntegration,
        scheme: TimeScheme,
        path: SolverPath,
        time_reference_steps: Option<usize>,
    ) -> Self {
        Self {
            exact,
            integration,
            scheme,
            path,
            time_reference_steps,
            references: Mutex::new(BTreeMap::new()),
        }
    }

    fn solver(
        &self,
        divisions: usize,
        steps: usize,
        scheme: TimeScheme,
    ) -> Result<PlaneSolver, String> {
        let problem = self.exact.problem(divisions, self.integration);
        let grid = TimeGrid::uniform(problem.final_time, steps).map_err(|e| e.to_string())?;
        PlaneSolver::new(
            &problem,
            grid,
            scheme,
            PlaneParams {
                path: self.path,
                ..Default::default()
            },
        )
        .map_err(|e| e.to_string())
    }

    /// u_N of the reference run on an n × n mesh (computed once per mesh, shared by parallel
    /// levels).
    fn reference(&self, divisions: usize) -> Result<Vec<f64>, String> {
        let steps = self.time_reference_steps.ok_or("no time_reference_steps")?;
        let cell = {
            let mut map = self
                .references
                .lock()
                .map_err(|_| "reference cache poisoned".to_string())?;
            map.entry(divisions)
                .or_insert_with(|| Arc::new(OnceLock::new()))
                .clone()
        };
        cell.get_or_init(|| {
            let mut s = self.solver(divisions, steps, TimeScheme::Midpoint)?;
            let mut last = Vec::new();
            s.run(
                &mut |st: &contactlab::model::quasistatic::plane_solver::PlaneStep<'_>| {
                    if st.n == steps {
                        last = st.u.to_vec();
                    }
                },
            )
            .map_err(|e| e.to_string())?;
            Ok(last)
        })
        .clone()
    }

    /// Runs (n, N, scheme) and measures the errors (with `time_error`, also the time error
    /// against the reference run on the same mesh).
    pub fn run_level(
        &self,
        divisions: usize,
        steps: usize,
        scheme: TimeScheme,
        time_error: bool,
    ) -> Result<LevelResult, String> {
        let mut solver = self.solver(divisions, steps, scheme)?;
        let mesh = solver.problem().mesh.clone();
        let start = Instant::now();
        let mut obs = PlaneErrorObserver::new(&self.exact, mesh.nodes(), mesh.triangles(), steps);
        let stats = solver.run(&mut obs).map_err(|e| e.to_string())?;
        let cpu_seconds = start.elapsed().as_secs_f64();
        let mut errors = obs.errors();
        if time_error {
            let r = self.reference(divisions)?;
            errors.insert(
                "time_l2_final".into(),
                l2_difference(mesh.nodes(), mesh.triangles(), &obs.final_u, &r),
            );
        }
        let u_end = obs.final_u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        Ok(LevelResult {
            elements: divisions,
            steps,
            h: mesh.h_max(),
            k: solver.grid().k_max(),
            scheme,
            errors,
            u_end,
            cpu_seconds,
            stats: serde_json::to_value(&stats).unwrap_or(serde_json::Value::Null),
        })
    }
}
