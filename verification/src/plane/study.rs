//! A plane study: a manufactured solution with the case's discretization options, and one run of
//! it at (n × n squares, N steps, scheme) with its errors against the exact solution — and, where a
//! sweep asks, the diagnostic `time_l2_final` against a run of the same code on the same mesh with a
//! much smaller step (never gated).

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::{Arc, Mutex, OnceLock};

use serde::Deserialize;

use contactlab::model::quasistatic::plane::{ContactIntegration, PlaneProblem};
use contactlab::model::quasistatic::plane_solver::{PlaneParams, PlaneSolver, SolverPath};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::time::grid::TimeGrid;

use crate::core::format::{invalid, CaseError};
use crate::core::study::Study;
use crate::core::sweep::{Level, Measured};
use crate::manufactured::normal_response::NormalResponse;
use crate::manufactured::plane::PlaneManufactured;
use crate::manufactured::plane_fields::PlaneField;
use contactlab::fem::norms::l2_difference;

use crate::plane::errors::PlaneErrorObserver;

/// `[exact]`: the manufactured solution of a plane case on n × n squares of the unit square: its
/// materials and foundation (`plane_manufactured_linear`, `plane_manufactured_nonlinear`,
/// `plane_manufactured_strain`) and its displacement field (`switching`, the default, or
/// `affine` with its `switch_time`; `manufactured/plane_fields.rs`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExactSpec {
    pub solution: String,
    #[serde(default)]
    pub field: FieldKind,
    /// t* of the affine field, in (0, T).
    pub switch_time: Option<f64>,
    /// The foundation law on Γ3: `lubricated` (2.8), the default, or `linear` (2.7).
    #[serde(default)]
    pub law: LawKind,
    /// β of the law (default 5; ≥ 0).
    pub beta: Option<f64>,
}

/// The foundation law of `[exact]`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LawKind {
    /// (2.8) β r_+ + p0 with the solution's p0.
    #[default]
    Lubricated,
    /// (2.7) β r.
    Linear,
}

/// The displacement field of `[exact]`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FieldKind {
    #[default]
    Switching,
    Affine,
}

impl ExactSpec {
    /// The manufactured solution it names, or the field of `[exact]` that is wrong with the value
    /// found and what was expected.
    fn resolve(&self) -> Result<PlaneManufactured, (&'static str, String, String)> {
        let base = PlaneManufactured::by_name(&self.solution).ok_or_else(|| {
            (
                "exact.solution",
                self.solution.clone(),
                "plane_manufactured_linear, plane_manufactured_nonlinear or \
                 plane_manufactured_strain"
                    .to_string(),
            )
        })?;
        let final_time = base.final_time;
        let field = match (self.field, self.switch_time) {
            (FieldKind::Switching, None) => PlaneField::Switching,
            (FieldKind::Switching, Some(t)) => {
                return Err((
                    "exact.switch_time",
                    t.to_string(),
                    "no switch_time for the switching field (only for field = \"affine\")"
                        .to_string(),
                ))
            }
            (FieldKind::Affine, Some(t)) if t.is_finite() && t > 0.0 && t < final_time => {
                PlaneField::Affine { switch_time: t }
            }
            (FieldKind::Affine, t) => {
                return Err((
                    "exact.switch_time",
                    t.map_or("(missing)".to_string(), |t| t.to_string()),
                    format!("a time in (0, {final_time}) for the affine field"),
                ))
            }
        };
        let beta = match (self.beta, base.foundation) {
            (None, NormalResponse::Lubricated { beta, .. }) => beta,
            (Some(b), _) if b.is_finite() && b >= 0.0 => b,
            (b, _) => {
                return Err((
                    "exact.beta",
                    b.map_or("(missing)".to_string(), |b| b.to_string()),
                    "a finite number ≥ 0".to_string(),
                ))
            }
        };
        let p0 = match base.foundation {
            NormalResponse::Lubricated { p0, .. } => p0,
            _ => 0.0,
        };
        let foundation = match self.law {
            LawKind::Lubricated => NormalResponse::Lubricated { beta, p0 },
            LawKind::Linear => NormalResponse::Linear { beta },
        };
        Ok(base.with_field(field).with_foundation(foundation))
    }

    /// The manufactured solution it names.
    pub fn manufactured(&self) -> Result<PlaneManufactured, String> {
        self.resolve()
            .map_err(|(field, value, expected)| format!("{field} = {value}: expected {expected}"))
    }

    /// Checks `[exact]` of the case file at `path`, naming the wrong field.
    pub fn check(&self, path: &Path) -> Result<PlaneManufactured, CaseError> {
        self.resolve()
            .map_err(|(field, value, expected)| invalid(path, field, value, &expected))
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

    /// The solver of the study's problem on n × n squares with N steps.
    pub fn solver(
        &self,
        divisions: usize,
        steps: usize,
        scheme: TimeScheme,
    ) -> Result<PlaneSolver, String> {
        let problem = self.exact.problem(divisions, self.integration)?;
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
