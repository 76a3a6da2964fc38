//! The study of a convergence case: the rod (scene or manufactured) or a plane manufactured
//! solution, run level by level.

use contactlab::model::quasistatic::plane::ContactIntegration;
use contactlab::model::quasistatic::plane_solver::SolverPath;
use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::case::CaseFile;
use crate::manufactured::plane::PlaneManufactured;
use crate::plane_study::PlaneStudy;
use crate::rod_study::{LevelResult, RodStudy};

/// A study of either model.
pub enum Study {
    Rod(RodStudy),
    Plane(PlaneStudy),
}

impl Study {
    /// The study a case describes: a plane manufactured solution when `[exact] solution` names
    /// one, the rod otherwise.
    pub fn from_case(case: &CaseFile) -> Result<Self, String> {
        let plane = case
            .exact
            .as_ref()
            .and_then(|e| PlaneManufactured::by_name(&e.solution));
        match plane {
            Some(exact) => {
                let d = &case.discretization;
                Ok(Study::Plane(PlaneStudy::new(
                    exact,
                    d.contact_integration.unwrap_or(ContactIntegration::Gauss2),
                    d.scheme.unwrap_or_default(),
                    d.solver_path.unwrap_or(SolverPath::Auto),
                    d.time_reference_steps,
                )))
            }
            None => RodStudy::from_case(case)
                .map(Study::Rod)
                .map_err(|e| e.to_string()),
        }
    }

    /// The default scheme.
    pub fn scheme(&self) -> TimeScheme {
        match self {
            Study::Rod(r) => r.scheme,
            Study::Plane(p) => p.scheme,
        }
    }

    /// One level (`time_error`: also the plane time error against the same-mesh reference).
    pub fn run_level(
        &self,
        elements: usize,
        steps: usize,
        scheme: TimeScheme,
        time_error: bool,
    ) -> Result<LevelResult, String> {
        match self {
            Study::Rod(r) => r
                .run_level(elements, steps, scheme)
                .map_err(|e| e.to_string()),
            Study::Plane(p) => p.run_level(elements, steps, scheme, time_error),
        }
    }
}
