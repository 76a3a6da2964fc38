//! The run of a `rotating_plate` scene: the analysed point (eigenvalues and verdict), the
//! non-rotating frequencies ω_{n,m} of the discretization with the spatial-frame waves they
//! predict, every sweep and the map.
//!
//! Without a pad the plate's spectrum is known harmonic by harmonic (Hetzler 2009, (72)–(74);
//! `model::moving::plate::model`): λ = i(±ω_{n,m} − nΩ), i.e. in the spatial frame a forward wave
//! of frequency ω_{n,m} + n|Ω| and a backward wave of frequency |ω_{n,m} − n|Ω||, which stands
//! still at the critical speed Ω = ω_{n,m}/n (n ≥ 1). The scene reports them next to the computed
//! eigenvalues (the Campbell diagram's reference lines).

use serde::Serialize;

use faer::c64;

use crate::error::{Error, InputError, SolveError};
use crate::model::moving::linearized::LinearizedModel;
use crate::model::moving::plate::modes::harmonic_frequencies;
use crate::model::moving::plate::{PadData, PlateParameter};
use crate::model::moving::stability::{assess_resolved, StabilityAssessment};
use crate::model::moving::stability_map::{
    stability_map, AxisParameter, StabilityMap, StabilityMapParams,
};
use crate::model::moving::sweep::{sweep, Sweep};
use crate::scene::moving::plate::RotatingPlateScene;
use crate::solve::quadratic_eigen::{QuadraticEigenParams, QuadraticEigenStats};

/// The non-rotating frequencies of harmonic n and the spatial-frame waves they predict at the
/// scene's Ω (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HarmonicWaves {
    /// n (nodal diameters).
    pub n: usize,
    /// ω_{n,0} < ω_{n,1} < … (the lowest two, or `radial_modes`).
    pub frequencies: Vec<f64>,
    /// ω_{n,m} + n|Ω|.
    pub forward: Vec<f64>,
    /// |ω_{n,m} − n|Ω||.
    pub backward: Vec<f64>,
    /// ω_{n,m}/n (empty for n = 0, which has none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub critical_speeds: Vec<f64>,
}

impl HarmonicWaves {
    /// The waves of harmonic `n` with frequencies `frequencies` at angular speed `omega`.
    pub fn new(n: usize, frequencies: Vec<f64>, omega: f64) -> Self {
        let shift = n as f64 * omega.abs();
        Self {
            n,
            forward: frequencies.iter().map(|w| w + shift).collect(),
            backward: frequencies.iter().map(|w| (w - shift).abs()).collect(),
            critical_speeds: if n == 0 {
                Vec::new()
            } else {
                frequencies.iter().map(|w| w / n as f64).collect()
            },
            frequencies,
        }
    }
}

/// What a plate scene computes.
#[derive(Debug, Clone, Serialize)]
pub struct PlateSceneResult {
    /// Ω and α of the analysed point.
    pub angular_speed: f64,
    pub damping: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pad: Option<PadData>,
    pub coordinates: Vec<String>,
    /// [Re λ, Im λ].
    pub eigenvalues: Vec<[f64; 2]>,
    /// Per eigenvalue, the eigenvector x as [Re, Im] per coordinate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub eigenvectors: Option<Vec<Vec<[f64; 2]>>>,
    pub assessment: StabilityAssessment,
    pub stats: QuadraticEigenStats,
    /// Per harmonic n = 0 … N, the non-rotating frequencies and the predicted waves.
    pub harmonics: Vec<HarmonicWaves>,
    pub sweeps: Vec<Sweep<PlateParameter>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub map: Option<StabilityMap<PlateParameter>>,
}

/// The keys that set the scales of a plate's eigenproblem (named when its numbers leave the
/// range of doubles).
const SCALES: &str = "the scales of plate.angular_speed, plate.bending_stiffness, \
     plate.mass_per_area, plate.outer_radius, plate.thickness, pad.stiffness and pad.friction \
     within the range of doubles";

/// An error naming `field` when an eigenvalue is not finite: the eigensolver met numbers beyond
/// the range of doubles (e.g. Ω² ρh b⁴ of the transport stiffness), which the file's magnitude
/// bounds (each number within 1e±150) do not exclude for products of four factors.
fn require_finite(field: &str, at: impl std::fmt::Display, ev: &[c64]) -> Result<(), Error> {
    if ev.iter().all(|l| l.re.is_finite() && l.im.is_finite()) {
        return Ok(());
    }
    Err(InputError::new(
        field,
        at,
        format!("finite eigenvalues (some are NaN or ∞ there): {SCALES}"),
    )
    .into())
}

impl RotatingPlateScene {
    /// The non-rotating frequencies ω_{n,m} of the scene's discretization for n = 0 … N: the
    /// retained modes' in the modal basis, else the lowest two of each harmonic.
    pub fn harmonic_frequencies(&self) -> Result<Vec<Vec<f64>>, Error> {
        let d = self.model.discretization();
        let harmonics = (d.angular.len() - 1) / 2;
        (0..=harmonics)
            .map(|n| match d.radial_modes {
                // the cosine function of harmonic n is angular function 2n − 1 (0 for n = 0)
                Some(_) => Ok(self
                    .model
                    .modal_frequencies((2 * n).saturating_sub(1))
                    .to_vec()),
                None => harmonic_frequencies(self.model.properties(), d.elements, n, 2),
            })
            .collect()
    }

    /// Runs the scene: the analysed point, the harmonic frequencies, every sweep and the map.
    pub fn run(&self) -> Result<PlateSceneResult, Error> {
        let system = self.model.system(&self.data)?;
        let eigen = system
            .eigen(QuadraticEigenParams {
                compute_eigenvectors: self.eigenvectors,
                ..Default::default()
            })
            .map_err(|source| SolveError::Eigenproblem {
                at: format!("the scene's point ({})", self.model.describe(&self.data)),
                source,
            })?;
        require_finite("plate", self.model.describe(&self.data), &eigen.eigenvalues)?;
        let assessment = assess_resolved(
            &eigen.eigenvalues,
            &self.verdict,
            self.model.resolution_limit(&self.data),
        );
        let harmonics: Vec<HarmonicWaves> = self
            .harmonic_frequencies()?
            .into_iter()
            .enumerate()
            .map(|(n, w)| HarmonicWaves::new(n, w, self.data.angular_speed))
            .collect();
        let mut sweeps = Vec::new();
        for (i, axis) in self.sweeps.iter().enumerate() {
            let sw = sweep(
                &self.model,
                &self.data,
                axis,
                QuadraticEigenParams::default(),
                &self.verdict,
                self.threads,
            )?;
            for (v, ev) in axis.values.iter().zip(&sw.spectra) {
                require_finite(
                    &format!("sweep[{i}].from/to"),
                    format!("{} = {v}", axis.parameter.key()),
                    ev,
                )?;
            }
            sweeps.push(sw);
        }
        let map = match &self.map {
            None => None,
            Some((x, y)) => Some(stability_map(
                &self.model,
                &self.data,
                x,
                y,
                &StabilityMapParams {
                    threads: self.threads,
                    verdict: self.verdict,
                    eigen: QuadraticEigenParams {
                        kernel: self.map_kernel,
                        ..QuadraticEigenParams::default()
                    },
                },
            )?),
        };
        if let Some(m) = &map {
            let nx = m.x.values.len();
            for (k, a) in m.points.iter().enumerate() {
                let numbers = [a.max_real_part, a.critical_re, a.critical_im, a.tolerance];
                if !numbers.iter().all(|v| v.is_finite()) {
                    let (x, y) = (m.x.values[k % nx], m.y.values[k / nx]);
                    return Err(InputError::new(
                        "map.x/map.y",
                        format!(
                            "({} = {x}, {} = {y})",
                            m.x.parameter.key(),
                            m.y.parameter.key()
                        ),
                        format!("finite eigenvalues (some are NaN or ∞ there): {SCALES}"),
                    )
                    .into());
                }
            }
        }
        Ok(PlateSceneResult {
            angular_speed: self.data.angular_speed,
            damping: self.data.damping,
            pad: self.data.pad,
            coordinates: system.coordinates.clone(),
            eigenvalues: eigen.eigenvalues.iter().map(|l| [l.re, l.im]).collect(),
            eigenvectors: eigen.eigenvectors.as_ref().map(|x| {
                (0..x.ncols())
                    .map(|j| {
                        (0..x.nrows())
                            .map(|i| [x[(i, j)].re, x[(i, j)].im])
                            .collect()
                    })
                    .collect()
            }),
            assessment,
            stats: eigen.stats,
            harmonics,
            sweeps,
            map,
        })
    }
}
