//! What the plate cases share: the `[plate]` and `[pad]` sections, the model builder, the
//! spectrum helpers.

use std::path::Path;

use serde::{Deserialize, Serialize};

use contactlab::model::moving::linearized::LinearizedModel;
use contactlab::model::moving::plate::angular::AngularBasis;
use contactlab::model::moving::plate::modes::harmonic_frequencies;
use contactlab::model::moving::plate::{
    OuterEdge, PadData, PlateData, PlateDiscretization, PlateProperties, RotatingPlateModel,
};
use contactlab::model::moving::Mat;
use contactlab::solve::quadratic_eigen::{QuadraticEigen, QuadraticEigenParams};

use crate::core::format::{invalid, CaseError};

/// `[plate]`.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PlateSection {
    pub inner_radius: f64,
    pub outer_radius: f64,
    pub bending_stiffness: f64,
    pub mass_per_area: f64,
    pub poisson: f64,
    pub thickness: f64,
    pub outer_edge: OuterEdge,
}

impl PlateSection {
    /// The plate's properties (no membrane stiffening: the paper's example).
    pub fn properties(&self) -> PlateProperties {
        PlateProperties {
            inner_radius: self.inner_radius,
            outer_radius: self.outer_radius,
            bending_stiffness: self.bending_stiffness,
            mass_per_area: self.mass_per_area,
            poisson: self.poisson,
            thickness: self.thickness,
            outer_edge: self.outer_edge,
            membrane_stiffening: false,
        }
    }

    /// Checks the plate (errors name `plate.<key>`).
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        self.properties()
            .validate()
            .map_err(|e| invalid(p, &e.field, &e.value, &e.expected))
    }
}

/// `[pad]`: the pad's position and stiffness.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PadSection {
    pub radius: f64,
    pub angle: f64,
    pub stiffness: f64,
}

impl PadSection {
    /// The pad with friction μ.
    pub fn with_friction(&self, friction: f64) -> PadData {
        PadData {
            radius: self.radius,
            angle: self.angle,
            stiffness: self.stiffness,
            friction,
        }
    }
}

/// The periodic model with `harmonics`, `elements` and optional `radial_modes`.
pub fn plate_model(
    plate: PlateProperties,
    harmonics: usize,
    elements: usize,
    radial_modes: Option<usize>,
) -> Result<RotatingPlateModel, String> {
    RotatingPlateModel::new(
        plate,
        PlateDiscretization {
            angular: AngularBasis::Periodic { harmonics },
            elements,
            radial_modes,
        },
    )
    .map_err(|e| e.to_string())
}

/// The eigenvalues (and with `vectors` the eigenvectors) of the model at `data` (faer).
pub fn spectrum(
    model: &RotatingPlateModel,
    data: &PlateData,
    vectors: bool,
) -> Result<QuadraticEigen, String> {
    model
        .system(data)
        .map_err(|e| e.to_string())?
        .eigen(QuadraticEigenParams {
            compute_eigenvectors: vectors,
            ..Default::default()
        })
        .map_err(|e| format!("{}: {e}", model.describe(data)))
}

/// The lowest critical speed min_{n ≥ 1} ω_{n,0}/n over n = 1 … N of the model's radial
/// discretization, with the harmonic that attains it.
pub fn lowest_critical_speed(
    plate: &PlateProperties,
    elements: usize,
    harmonics: usize,
) -> Result<(f64, usize), String> {
    let mut best = (f64::INFINITY, 0);
    for n in 1..=harmonics {
        let w = harmonic_frequencies(plate, elements, n, 1).map_err(|e| e.to_string())?;
        let c = w[0] / n as f64;
        if c < best.0 {
            best = (c, n);
        }
    }
    Ok(best)
}

/// The smallest eigenvalue of the symmetric matrix `a` relative to its largest magnitude, by
/// Cholesky of a − s I bisection-free: whether `a` is positive definite (Cholesky succeeds).
pub fn positive_definite(a: &Mat<f64>) -> bool {
    contactlab::solve::dense_cholesky::cholesky_factor(a.as_ref()).is_ok()
}
