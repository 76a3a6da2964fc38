//! The errors of the moving-continuum models: invalid input, or an eigenproblem that failed at a
//! named parameter point.

use crate::error::InputError;
use crate::solve::quadratic_eigen::QuadraticEigenError;

/// Any error of `model::moving`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MovingError {
    /// Invalid data, parameters or discretization.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The eigenproblem failed at a parameter point (`v̄ = 0.5, p = 2`).
    #[error("at {at}: {source}")]
    Eigen {
        at: String,
        #[source]
        source: QuadraticEigenError,
    },
}
