//! The rod of Fernández & Sofonea (2004) §4.1, run in code: the paper's two oil pressures with the
//! three time treatments of the elastic term, printing the end displacement u_h(1, T) against the
//! exact (4.6) and (4.7).
//!
//! `cargo run --release --example rod_paper`

use contactlab::error::Error;
use contactlab::mesh::interval::IntervalMesh;
use contactlab::model::quasistatic::rod::RodProblem;
use contactlab::model::quasistatic::rod_output::RodOutputRequest;
use contactlab::model::quasistatic::rod_solver::{RodParams, RodSolver};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::time::grid::TimeGrid;

fn main() -> Result<(), Error> {
    let exact_end = |p0: f64, t: f64| {
        if p0 == 6.0 {
            -(1.0 - (-t).exp())
        } else {
            3.0 * (1.0 - (-t / 2.0).exp())
        }
    };
    println!(
        "{:>4} {:>9} {:>18} {:>18} {:>10}",
        "p0", "scheme", "u_h(1, T)", "u(1, T)", "error"
    );
    for p0 in [6.0, 2.0] {
        let problem = RodProblem::fernandez_sofonea(p0);
        for scheme in TimeScheme::ALL {
            let solver = RodSolver::new(
                &problem,
                IntervalMesh::uniform(1.0, 100)?,
                TimeGrid::uniform(0.5, 50)?,
                scheme,
                RodParams::default(),
            )?;
            let sol = solver.solve(&RodOutputRequest::default())?;
            let u = sol.end_displacement[50];
            let e = exact_end(p0, 0.5);
            println!(
                "{p0:>4} {:>9} {u:>18.12} {e:>18.12} {:>10.2e}",
                scheme.name(),
                (u - e).abs()
            );
        }
    }
    Ok(())
}
