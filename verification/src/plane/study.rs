//! A plane study: a manufactured solution with the case's discretization options, and one run of
//! it at (n × n squares, N steps, scheme) with its errors — including, where asked, the time error
//! against a run on the same mesh with a much smaller step.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex, OnceLock};

use serde::Deserialize;

use contactlab::model::quasistatic::plane::{ContactIntegration, PlaneProblem};
use contactlab::model::quasistatic::plane_solver::{PlaneParams, PlaneSolver, SolverPath};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::time::grid::TimeGrid;

use crate::core::study::Study;
use crate::core::sweep::{Level, Measured};
use crate::manufactured::plane::PlaneManufactured;
use contactlab::fem::norms::l2_difference;

use crate::plane::errors::PlaneErrorObserver;

/// `[exact]`: the manufactured solution of a plane case (`plane_manufactured_linear`,
/// `plane_manufactured_nonlinear`, `plane_manufactured_strain`), on n × n squares of the unit
/// square.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExactSpec {
    pub solution: String,
}

impl ExactSpec {
    /// The manufactured solution it names.
    pub fn manufactured(&self) -> Result<PlaneManufactured, String> {
        PlaneManufactured::by_name(&self.solution).ok_or_else(|| {
            format!(
                "exact solution `{}`: unknown; known: plane_manufactured_linear, \
                 plane_manufactured_nonlinear, plane_manufactured_strain",
                self.solution
            )
        })
    }
}

/// `[discretization]`: options of every run of a plane case.
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Discretization {
    pub scheme: Option<TimeScheme>,
    /// `gauss2` or `nodal`.
    pub contact_integration: Option<ContactIntegration>,
    /// `auto`, `condensed` or `newton`.
    pub solver_path: Option<SolverPath>,
    /// Steps of the reference run on the same mesh for the time error `time_l2_final`.
    pub time_reference_steps: Option<usize>,
}

/// The solver of `problem` with N = `steps` uniform steps, `scheme` and the solver `path`.
pub fn plane_solver(
    problem: &PlaneProblem,
    steps: usize,
    scheme: TimeScheme,
    path: SolverPath,
) -> Result<PlaneSolver, String> {
    let grid = TimeGrid::uniform(problem.final_time, steps).map_err(|e| e.to_string())?;
    PlaneSolver::new(
        problem,
        grid,
        scheme,
        PlaneParams {
            path,
            ..Default::default()
        },
    )
    .map_err(|e| e.to_string())
}

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
    /// The study of a case: its manufactured solution and options.
    pub fn from_case(exact: &ExactSpec, d: &Discretization) -> Result<Self, String> {
        Ok(Self::new(
            exact.manufactured()?,
            d.contact_integration.unwrap_or(ContactIntegration::Gauss2),
            d.scheme.unwrap_or_default(),
            d.solver_path.unwrap_or(SolverPath::Auto),
            d.time_reference_steps,
        ))
    }

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
        plane_solver(&problem, steps, scheme, self.path)
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
}

impl Study for PlaneStudy {
    type Scheme = TimeScheme;

    fn default_scheme(&self) -> TimeScheme {
        self.scheme
    }

    /// Runs (n × n squares, N steps, scheme) and measures the errors against the manufactured
    /// solution (with `time_error`, also the time error `time_l2_final` against the reference
    /// run on the same mesh).
    fn run_level(
        &self,
        divisions: usize,
        steps: usize,
        scheme: TimeScheme,
        time_error: bool,
    ) -> Result<Level, String> {
        let mut solver = self.solver(divisions, steps, scheme)?;
        let mesh = solver.problem().mesh.clone();
        let mut final_u = Vec::new();
        let mut level = Level::timed(divisions, steps, scheme, || {
            let mut obs =
                PlaneErrorObserver::new(&self.exact, mesh.nodes(), mesh.triangles(), steps);
            let stats = solver.run(&mut obs).map_err(|e| e.to_string())?;
            final_u = std::mem::take(&mut obs.final_u);
            Ok::<_, String>(Measured {
                h: mesh.h_max(),
                k: solver.grid().k_max(),
                errors: obs.errors(),
                u_end: final_u.iter().fold(0.0f64, |m, v| m.max(v.abs())),
                stats,
            })
        })?;
        if time_error {
            let r = self.reference(divisions)?;
            level.errors.insert(
                "time_l2_final".into(),
                l2_difference(mesh.nodes(), mesh.triangles(), &final_u, &r),
            );
        }
        Ok(level)
    }
}
