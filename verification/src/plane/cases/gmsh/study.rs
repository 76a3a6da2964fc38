//! Part 2 of `plane_gmsh`: convergence on Gmsh meshes. A [`Study`] whose level n runs the
//! manufactured solution (data from the formulas of `manufactured/plane.rs`) on the mesh of the
//! file `[convergence] mesh` with `{n}` replaced by n, its Γ1, Γ2 and Γ3 the file's boundary
//! groups `left`, `top` and `right`, `bottom` (`SquareSides`), and measures the plane error
//! functionals. h is the mesh's longest edge, measured, not n.

use std::sync::Arc;

use serde::Deserialize;

use contactlab::model::quasistatic::plane::{BoundarySelector, ContactIntegration, PlaneProblem};
use contactlab::model::quasistatic::plane_solver::{PlaneStep, SolverPath};
use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::study::Study;
use crate::core::sweep::{Level, Measured};
use crate::manufactured::plane::{PlaneManufactured, SquareSides};
use crate::plane::cases::gmsh::files::read_mesh;
use crate::plane::errors::PlaneErrorObserver;
use crate::plane::study::{plane_solver, Discretization, ExactSpec};

/// `[convergence]`: the meshes of the sweeps.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSeries {
    /// A path relative to the repository root with `{n}`, replaced by a level's elements
    /// (`examples/meshes/unit_square_{n}.msh`).
    pub mesh: String,
}

impl MeshSeries {
    /// The file of level n.
    pub fn file(&self, n: usize) -> String {
        self.mesh.replace("{n}", &n.to_string())
    }
}

/// The boundary group `name` of a file's mesh as a boundary part.
fn group(g: &contactlab::mesh::gmsh::GmshMesh, name: &str) -> Result<BoundarySelector, String> {
    let edges = g
        .boundary_group(&format!("group {name}"), name)
        .map_err(|e| e.to_string())?;
    Ok(BoundarySelector::Edges {
        group: name.to_string(),
        edges: Arc::new(edges.to_vec()),
    })
}

/// The manufactured problem on the unit-square mesh of `file`, its sides the file's groups
/// `left`, `top`, `right`, `bottom`.
pub fn square_problem(
    exact: &PlaneManufactured,
    file: &str,
    integration: ContactIntegration,
) -> Result<PlaneProblem, String> {
    let g = read_mesh(file)?;
    let sides = SquareSides {
        left: group(&g, "left")?,
        top: group(&g, "top")?,
        right: group(&g, "right")?,
        bottom: group(&g, "bottom")?,
    };
    Ok(exact.problem_on(g.mesh.clone(), sides, integration))
}

/// u_N of `problem` with N = `steps` steps of `scheme`.
pub fn final_displacement(
    problem: &PlaneProblem,
    steps: usize,
    scheme: TimeScheme,
    path: SolverPath,
) -> Result<Vec<f64>, String> {
    let mut solver = plane_solver(problem, steps, scheme, path)?;
    let mut last = Vec::new();
    solver
        .run(&mut |st: &PlaneStep<'_>| {
            if st.n == steps {
                last = st.u.to_vec();
            }
        })
        .map_err(|e| e.to_string())?;
    Ok(last)
}

/// The manufactured solution on a series of Gmsh meshes.
pub struct GmshStudy {
    pub exact: PlaneManufactured,
    pub integration: ContactIntegration,
    pub scheme: TimeScheme,
    pub path: SolverPath,
    pub meshes: MeshSeries,
}

impl GmshStudy {
    /// The study of a case.
    pub fn from_case(
        exact: &ExactSpec,
        d: &Discretization,
        meshes: &MeshSeries,
    ) -> Result<Self, String> {
        Ok(Self {
            exact: exact.manufactured()?,
            integration: d.contact_integration.unwrap_or(ContactIntegration::Gauss2),
            scheme: d.scheme.unwrap_or_default(),
            path: d.solver_path.unwrap_or(SolverPath::Auto),
            meshes: meshes.clone(),
        })
    }
}

impl Study for GmshStudy {
    type Scheme = TimeScheme;

    fn default_scheme(&self) -> TimeScheme {
        self.scheme
    }

    /// Runs the mesh of level n with N steps and measures the errors against the manufactured
    /// solution (no same-mesh time reference: `time_error` is refused).
    fn run_level(
        &self,
        n: usize,
        steps: usize,
        scheme: TimeScheme,
        time_error: bool,
    ) -> Result<Level, String> {
        if time_error {
            return Err("plane_gmsh has no same-mesh time reference (time_error)".into());
        }
        let problem = square_problem(&self.exact, &self.meshes.file(n), self.integration)?;
        let mesh = problem.mesh.clone();
        let mut solver = plane_solver(&problem, steps, scheme, self.path)?;
        Level::timed(n, steps, scheme, || {
            let mut obs =
                PlaneErrorObserver::new(&self.exact, mesh.nodes(), mesh.triangles(), steps);
            let stats = solver.run(&mut obs).map_err(|e| e.to_string())?;
            Ok::<_, String>(Measured {
                h: mesh.h_max(),
                k: solver.grid().k_max(),
                errors: obs.errors(),
                u_end: obs.final_u.iter().fold(0.0f64, |m, v| m.max(v.abs())),
                stats,
            })
        })
    }
}
