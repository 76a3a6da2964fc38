//! The rotating annular Kirchhoff plate in the spatial description (Hetzler 2009, §4.1):
//!
//! ```text
//!   ∫∫ δw (ẅ + 2Ω ∂ẇ/∂φ + Ω² ∂²w/∂φ²) ρh r dr dφ + δU_K[w] = 0                  (72)–(73)
//!   ⇒  M q̈ + (α M + Ω G) q̇ + (K_b + Ω² (K_T + K_σ) + K_pad) q = 0,   G = −Gᵀ, K_T = K_Tᵀ  (74)
//! ```
//!
//! for the Ritz functions w = Σ R_j(r) ψ_k(φ) q_kj (`radial.rs`, `angular.rs`). Every matrix is a
//! sum of Kronecker products of an angular and a radial Gram matrix,
//!
//! ```text
//!   M = ρh A0⊗m,  K_b = D [A0⊗a + A20⊗c + A20ᵀ⊗cᵀ + A22⊗d + A11⊗e],
//!   G = 2ρh P⊗m,  K_T = ρh Q⊗m,  K_σ = ρh [A0⊗k_r + A11⊗k_θ]  (membrane.rs, optional),
//! ```
//!
//! (row index (l, i): test χ_l S_i; column (k, j): trial ψ_k R_j). With `radial_modes = Some(m)`
//! (periodic basis only) each angular function keeps the lowest m radial modes Φ_n of its
//! harmonic (`modes.rs`), scaled so that the reduced mass is the identity; the reduced matrices
//! are the blocks A_t[l,k] Φ_lᵀ R_t Φ_k, never the full ones. Without a pad the reduction is
//! exact for the retained modes (the angular matrices are diagonal but for P, which only couples
//! cos nφ with sin nφ of the same harmonic).
//!
//! The stationary pad at (r_p, φ_p) (`data.rs`): a normal spring k_p on w(r_p, φ_p), and Coulomb
//! friction μ N on the upper surface z = h/2 opposing the surface's motion (+φ for Ω ≥ 0, the
//! limit Ω → 0⁺ at Ω = 0). A Kirchhoff surface point moves in-plane by u_φ = −z (1/r) ∂w/∂φ, so the
//! friction's virtual work at N = N₀ + k_p w is δW = μ N (h/2)(1/r_p) δw_φ: linearized,
//!
//! ```text
//!   K_pad = k_p v vᵀ − s μ k_p h/(2 r_p) w vᵀ,   v = Φ(r_p, φ_p),  w = ∂_φΦ(r_p, φ_p),  s = sign Ω
//! ```
//!
//! — the thick string's friction term (99)–(103) transferred: rank one, split into a symmetric
//! part and a circulatory (skew) part.

use faer::Mat;

use crate::error::{Error, InputError};
use crate::model::moving::linearized::LinearizedModel;
use crate::model::moving::plate::angular::{AngularBasis, AngularMatrices};
use crate::model::moving::plate::data::{PlateData, PlateParameter, PlateProperties};
use crate::model::moving::plate::membrane::SpinningDiscStress;
use crate::model::moving::plate::modes::harmonic_modes;
use crate::model::moving::plate::radial::{RadialBasis, RadialMatrices};
use crate::model::moving::system::{split_symmetric_skew, MovingSystem};

/// The largest number of coordinates of a plate model (dense matrices of this order).
pub const MAX_COORDINATES: usize = 2400;

/// How the plate is discretized.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PlateDiscretization {
    pub angular: AngularBasis,
    /// Radial Hermite elements.
    pub elements: usize,
    /// Radial modes kept per angular function (periodic basis only); `None`: the full basis.
    pub radial_modes: Option<usize>,
}

/// The assembled operators of a rotating plate (module docs).
#[derive(Debug, Clone)]
pub struct RotatingPlateModel {
    plate: PlateProperties,
    discretization: PlateDiscretization,
    radial: RadialBasis,
    /// Per angular function: the radial functions (identity: `None`) and, in the modal basis,
    /// the retained ω of its harmonic.
    modes: Vec<Option<Mat<f64>>>,
    frequencies: Vec<Vec<f64>>,
    block: usize,
    mass: Mat<f64>,
    bending: Mat<f64>,
    gyroscopic: Mat<f64>,
    transport: Mat<f64>,
    membrane: Mat<f64>,
    coordinates: Vec<String>,
}

/// out[(l·b + a, k·b + c)] += s · A[l,k] · (Φ_lᵀ R Φ_k)[a, c] for every non-zero A[l,k].
fn add_kron(
    out: &mut Mat<f64>,
    angular: &Mat<f64>,
    radial: &Mat<f64>,
    scale: f64,
    modes: &[Option<Mat<f64>>],
    block: usize,
) {
    let n = angular.nrows();
    for l in 0..n {
        for k in 0..n {
            let s = scale * angular[(l, k)];
            if s == 0.0 {
                continue;
            }
            let projected;
            let r = match (&modes[l], &modes[k]) {
                (Some(pl), Some(pk)) => {
                    projected = pl.transpose() * radial * pk;
                    &projected
                }
                _ => radial,
            };
            for a in 0..block {
                for c in 0..block {
                    out[(l * block + a, k * block + c)] += s * r[(a, c)];
                }
            }
        }
    }
}

fn angular_label(basis: &AngularBasis, k: usize) -> String {
    match basis.harmonic(k) {
        Some((0, _)) => "1".to_string(),
        Some((n, true)) => format!("sin{n}φ"),
        Some((n, false)) => format!("cos{n}φ"),
        None => format!("ψ{k}"),
    }
}

impl RotatingPlateModel {
    /// Assembles the operators of `plate` on `discretization`.
    pub fn new(plate: PlateProperties, discretization: PlateDiscretization) -> Result<Self, Error> {
        plate.validate()?;
        discretization.angular.validate()?;
        let radial = RadialBasis::uniform(
            plate.inner_radius,
            plate.outer_radius,
            discretization.elements,
            plate.outer_edge,
        )?;
        let nang = discretization.angular.len();
        let block = match discretization.radial_modes {
            None => radial.len(),
            Some(m) => {
                if !matches!(discretization.angular, AngularBasis::Periodic { .. }) {
                    return Err(InputError::new(
                        "discretization.radial_modes",
                        m,
                        "no modal reduction on a sector (the full radial basis)",
                    )
                    .into());
                }
                if !(1..=radial.len()).contains(&m) {
                    return Err(InputError::new(
                        "discretization.radial_modes",
                        m,
                        format!("1 to {} (the radial functions)", radial.len()),
                    )
                    .into());
                }
                m
            }
        };
        let dim = nang * block;
        if dim > MAX_COORDINATES {
            return Err(InputError::new(
                "discretization",
                format!("{nang} angular × {block} radial = {dim} coordinates"),
                format!(
                    "at most {MAX_COORDINATES} coordinates (fewer harmonics or elements, or \
                     radial_modes)"
                ),
            )
            .into());
        }
        let r = radial.matrices(plate.poisson)?;
        let ang = discretization.angular.matrices()?;
        let (modes, frequencies) = Self::modal_basis(
            &plate,
            &discretization.angular,
            &radial,
            &r,
            &ang,
            discretization.radial_modes,
        )?;
        let z = || Mat::<f64>::zeros(dim, dim);
        let (mut mass, mut bending, mut gyroscopic, mut transport, mut membrane) =
            (z(), z(), z(), z(), z());
        let (rho_h, d) = (plate.mass_per_area, plate.bending_stiffness);
        add_kron(&mut mass, &ang.a0, &r.mass, rho_h, &modes, block);
        add_kron(&mut bending, &ang.a0, &r.a, d, &modes, block);
        add_kron(&mut bending, &ang.a20, &r.c, d, &modes, block);
        let (a20t, ct) = (ang.a20.transpose().to_owned(), r.c.transpose().to_owned());
        add_kron(&mut bending, &a20t, &ct, d, &modes, block);
        add_kron(&mut bending, &ang.a22, &r.d, d, &modes, block);
        add_kron(&mut bending, &ang.a11, &r.e, d, &modes, block);
        add_kron(&mut gyroscopic, &ang.p, &r.mass, 2.0 * rho_h, &modes, block);
        add_kron(&mut transport, &ang.q, &r.mass, rho_h, &modes, block);
        if plate.membrane_stiffening {
            let stress =
                SpinningDiscStress::new(plate.inner_radius, plate.outer_radius, plate.poisson);
            let (kr, kt) = radial.membrane_matrices(|x| stress.radial(x), |x| stress.hoop(x))?;
            add_kron(&mut membrane, &ang.a0, &kr, rho_h, &modes, block);
            add_kron(&mut membrane, &ang.a11, &kt, rho_h, &modes, block);
        }
        let basis = &discretization.angular;
        let coordinates = (0..nang)
            .flat_map(|k| {
                let label = angular_label(basis, k);
                let modal = discretization.radial_modes.is_some();
                (0..block).map(move |j| {
                    if modal {
                        format!("{label}·mode{j}")
                    } else {
                        format!("{label}·R{j}")
                    }
                })
            })
            .collect();
        Ok(Self {
            plate,
            discretization,
            radial,
            modes,
            frequencies,
            block,
            mass,
            bending,
            gyroscopic,
            transport,
            membrane,
            coordinates,
        })
    }

    /// Per angular function the retained radial modes (scaled to a unit reduced mass) and
    /// their frequencies; `None` and empty lists for the full basis.
    #[allow(clippy::type_complexity)]
    fn modal_basis(
        plate: &PlateProperties,
        angular: &AngularBasis,
        radial: &RadialBasis,
        r: &RadialMatrices,
        ang: &AngularMatrices,
        radial_modes: Option<usize>,
    ) -> Result<(Vec<Option<Mat<f64>>>, Vec<Vec<f64>>), Error> {
        let nang = angular.len();
        let Some(m) = radial_modes else {
            return Ok((vec![None; nang], vec![Vec::new(); nang]));
        };
        let mut per_harmonic: Vec<Option<(Vec<f64>, Mat<f64>)>> = Vec::new();
        let mut modes = Vec::with_capacity(nang);
        let mut freqs = Vec::with_capacity(nang);
        for k in 0..nang {
            let (n, _) = angular.harmonic(k).unwrap_or((0, false));
            if per_harmonic.len() <= n {
                per_harmonic.resize(n + 1, None);
            }
            if per_harmonic[n].is_none() {
                // a stop request is honoured between two radial eigenproblems (each a dense
                // solve of the radial basis' order: seconds for 1000 elements)
                crate::run_control::check(|| {
                    format!("the radial modes of harmonic n = {n} (angular function {k} of {nang})")
                })?;
                let (lambda, phi) = harmonic_modes(
                    radial,
                    r,
                    plate,
                    n,
                    m,
                    &format!("the radial modes of harmonic n = {n}"),
                )?;
                per_harmonic[n] = Some((lambda, phi));
            }
            let Some((lambda, phi)) = &per_harmonic[n] else {
                unreachable!("computed above")
            };
            let scale = 1.0 / ang.a0[(k, k)].sqrt();
            modes.push(Some(Mat::from_fn(phi.nrows(), phi.ncols(), |i, j| {
                scale * phi[(i, j)]
            })));
            freqs.push(lambda.iter().map(|l| l.max(0.0).sqrt()).collect());
        }
        Ok((modes, freqs))
    }

    /// The plate.
    pub fn properties(&self) -> &PlateProperties {
        &self.plate
    }

    /// The discretization.
    pub fn discretization(&self) -> &PlateDiscretization {
        &self.discretization
    }

    /// The number of coordinates.
    pub fn dimension(&self) -> usize {
        self.coordinates.len()
    }

    /// In the modal basis, the retained non-rotating ω of angular function k (empty otherwise).
    pub fn modal_frequencies(&self, k: usize) -> &[f64] {
        self.frequencies.get(k).map_or(&[], |v| v.as_slice())
    }

    /// M.
    pub fn mass(&self) -> &Mat<f64> {
        &self.mass
    }

    /// K_b (symmetric).
    pub fn bending(&self) -> &Mat<f64> {
        &self.bending
    }

    /// G per unit Ω (skew for the periodic basis).
    pub fn gyroscopic_unit(&self) -> &Mat<f64> {
        &self.gyroscopic
    }

    /// K_T per unit Ω² (symmetric for the periodic basis).
    pub fn transport_unit(&self) -> &Mat<f64> {
        &self.transport
    }

    /// K_σ per unit Ω² (zero without membrane stiffening).
    pub fn membrane_unit(&self) -> &Mat<f64> {
        &self.membrane
    }

    /// (v, w) = (Φ, ∂_φΦ) at (r, φ) in the model's coordinates.
    pub fn point_values(&self, r: f64, phi: f64) -> (Vec<f64>, Vec<f64>) {
        let mut rv = vec![0.0; self.radial.len()];
        self.radial.values_at(r, &mut rv);
        let nang = self.discretization.angular.len();
        let (mut v, mut w) = (vec![0.0; self.dimension()], vec![0.0; self.dimension()]);
        for k in 0..nang {
            let s = self.discretization.angular.shape(k, phi);
            let radial: Vec<f64> = match &self.modes[k] {
                Some(p) => (0..p.ncols())
                    .map(|c| (0..p.nrows()).map(|i| p[(i, c)] * rv[i]).sum())
                    .collect(),
                None => rv.clone(),
            };
            for (a, x) in radial.iter().enumerate() {
                v[k * self.block + a] = s[0] * x;
                w[k * self.block + a] = s[1] * x;
            }
        }
        (v, w)
    }

    /// The friction's lever s μ h/(2 r_p) per unit μ (module docs).
    fn friction_lever(&self, data: &PlateData, radius: f64) -> f64 {
        let s = if data.angular_speed < 0.0 { -1.0 } else { 1.0 };
        s * self.plate.thickness / (2.0 * radius)
    }
}

impl LinearizedModel for RotatingPlateModel {
    type Data = PlateData;
    type Parameter = PlateParameter;

    fn validate_data(&self, data: &PlateData) -> Result<(), Error> {
        Ok(data.validate(&self.plate)?)
    }

    fn set(
        &self,
        parameter: PlateParameter,
        data: &mut PlateData,
        value: f64,
    ) -> Result<(), Error> {
        parameter.set(data, value)?;
        Ok(data.validate(&self.plate)?)
    }

    fn coordinates(&self, _data: &PlateData) -> Vec<String> {
        self.coordinates.clone()
    }

    fn assemble_into(&self, data: &PlateData, out: &mut MovingSystem) -> Result<(), Error> {
        data.validate(&self.plate)?;
        let n = self.dimension();
        if out.dimension() != n {
            return Err(InputError::new(
                "system.dimension",
                out.dimension(),
                format!("{n} coordinates"),
            )
            .into());
        }
        let (om, alpha) = (data.angular_speed, data.damping);
        let mut k = Mat::<f64>::zeros(n, n);
        for j in 0..n {
            for i in 0..n {
                out.mass[(i, j)] = self.mass[(i, j)];
                out.damping[(i, j)] = alpha * self.mass[(i, j)];
                out.gyroscopic[(i, j)] = om * self.gyroscopic[(i, j)];
                k[(i, j)] = self.bending[(i, j)]
                    + om * om * (self.transport[(i, j)] + self.membrane[(i, j)]);
            }
        }
        if let Some(p) = &data.pad {
            let (v, w) = self.point_values(p.radius, p.angle);
            let c = p.friction * p.stiffness * self.friction_lever(data, p.radius);
            for j in 0..n {
                for i in 0..n {
                    k[(i, j)] += p.stiffness * v[i] * v[j] - c * w[i] * v[j];
                }
            }
        }
        split_symmetric_skew(k.as_ref(), &mut out.stiffness, &mut out.circulatory);
        Ok(())
    }

    fn mass_key(&self, _data: &PlateData) -> f64 {
        0.0
    }

    fn rank_one(
        &self,
        data: &PlateData,
        parameter: PlateParameter,
    ) -> Option<(Vec<f64>, Vec<f64>, f64)> {
        let p = data.pad.as_ref()?;
        let (v, w) = self.point_values(p.radius, p.angle);
        let lever = self.friction_lever(data, p.radius);
        match parameter {
            PlateParameter::Friction => Some((w, v, -p.stiffness * lever)),
            PlateParameter::PadStiffness => {
                let r = v
                    .iter()
                    .zip(&w)
                    .map(|(a, b)| a - p.friction * lever * b)
                    .collect();
                Some((r, v, 1.0))
            }
            PlateParameter::AngularSpeed | PlateParameter::Damping => None,
        }
    }

    fn resolution_limit(&self, _data: &PlateData) -> f64 {
        f64::INFINITY
    }

    fn describe(&self, data: &PlateData) -> String {
        let mut s = format!("Ω = {}, α = {}", data.angular_speed, data.damping);
        if let Some(p) = &data.pad {
            s.push_str(&format!(
                ", pad at (r, φ) = ({}, {}), k_p = {}, μ = {}",
                p.radius, p.angle, p.stiffness, p.friction
            ));
        }
        s
    }
}

#[cfg(test)]
mod tests {
    //! Setting: a small clamped–free annulus (a = 0.2, b = 1, ν = 0.3), N = 2 harmonics, 6 radial
    //! elements. Goal: the structure (74) on the assembled matrices, the rotating spectrum
    //! ±iω_{n,m} − inΩ of the full model against the harmonic frequencies, the modal model equal
    //! to it on the retained modes, and the pad's rank-one friction.
    use super::*;
    use crate::model::moving::plate::data::PadData;
    use crate::model::moving::plate::modes::harmonic_frequencies;
    use crate::model::moving::properties::{skew_defect, symmetry_defect};
    use crate::solve::quadratic_eigen::QuadraticEigenParams;

    fn model(modes: Option<usize>) -> RotatingPlateModel {
        RotatingPlateModel::new(
            PlateProperties::default(),
            PlateDiscretization {
                angular: AngularBasis::Periodic { harmonics: 2 },
                elements: 6,
                radial_modes: modes,
            },
        )
        .unwrap()
    }

    #[test]
    fn periodic_plate_has_skew_gyroscopic_and_symmetric_stiffness() {
        let m = model(None);
        assert!(skew_defect(m.gyroscopic_unit().as_ref()) < 1e-15);
        assert!(symmetry_defect(m.transport_unit().as_ref()) < 1e-15);
        assert!(symmetry_defect(m.bending().as_ref()) < 1e-14);
        assert!(symmetry_defect(m.mass().as_ref()) < 1e-15);
    }

    #[test]
    fn rotating_spectrum_is_the_harmonic_frequencies_shifted_by_n_omega() {
        let omega = 1.7;
        for modes in [None, Some(3)] {
            let m = model(modes);
            let data = PlateData {
                angular_speed: omega,
                damping: 0.0,
                pad: None,
            };
            let ev = m
                .system(&data)
                .unwrap()
                .eigen(QuadraticEigenParams::default())
                .unwrap();
            let mut expected = Vec::new();
            for n in 0..=2usize {
                let w = harmonic_frequencies(&PlateProperties::default(), 6, n, 3).unwrap();
                for wm in w {
                    let copies = if n == 0 { 1 } else { 2 };
                    for c in 0..copies {
                        // the two waves of harmonic n: −nΩ ± ω (cos and sin pair up into both)
                        let _ = c;
                        expected.push(wm - n as f64 * omega);
                        expected.push(-wm - n as f64 * omega);
                    }
                }
            }
            // every expected imaginary part is matched by an eigenvalue (±conjugates)
            for e in &expected {
                let hit = ev.eigenvalues.iter().any(|l| {
                    (l.im.abs() - e.abs()).abs() < 1e-9 * (1.0 + e.abs()) && l.re.abs() < 1e-8
                });
                assert!(hit, "modes {modes:?}: no eigenvalue at ±{e}");
            }
        }
    }

    #[test]
    fn pad_friction_is_rank_one_along_mu() {
        let m = model(Some(2));
        let mut data = PlateData {
            angular_speed: 0.5,
            damping: 0.0,
            pad: Some(PadData {
                radius: 0.9,
                angle: 0.3,
                stiffness: 40.0,
                friction: 0.0,
            }),
        };
        let k0 = m.system(&data).unwrap().stiffness_matrix();
        data.pad.as_mut().unwrap().friction = 0.7;
        let k1 = m.system(&data).unwrap().stiffness_matrix();
        let (r, s, coef) = m.rank_one(&data, PlateParameter::Friction).unwrap();
        for i in 0..m.dimension() {
            for j in 0..m.dimension() {
                let d = k1[(i, j)] - k0[(i, j)] - 0.7 * coef * r[i] * s[j];
                assert!(d.abs() < 1e-12 * (1.0 + k1[(i, j)].abs()));
            }
        }
    }

    #[test]
    fn pad_map_is_identical_for_any_thread_count_and_either_kernel_path() {
        use crate::model::moving::stability_map::{stability_map, GridAxis, StabilityMapParams};
        use crate::solve::quadratic_eigen::EigenKernel;
        let m = model(Some(2));
        let base = PlateData {
            angular_speed: 0.0,
            damping: 0.05,
            pad: Some(PadData {
                radius: 0.95,
                angle: 0.2,
                stiffness: 50.0,
                friction: 0.0,
            }),
        };
        let x = GridAxis::linspace(PlateParameter::AngularSpeed, 0.0, 3.0, 7).unwrap();
        let y = GridAxis::linspace(PlateParameter::Friction, 0.0, 0.8, 6).unwrap();
        let run = |threads, kernel| {
            stability_map(
                &m,
                &base,
                &x,
                &y,
                &StabilityMapParams {
                    threads,
                    eigen: QuadraticEigenParams {
                        kernel,
                        ..Default::default()
                    },
                    ..Default::default()
                },
            )
            .unwrap()
        };
        let (a, b) = (
            run(1, EigenKernel::SmallDense),
            run(3, EigenKernel::SmallDense),
        );
        assert_eq!(a.points, b.points);
        let f = run(2, EigenKernel::Faer);
        for (p, q) in a.points.iter().zip(&f.points) {
            assert_eq!(p.verdict, q.verdict);
        }
        assert!(a.points.iter().any(|p| p.verdict.is_unstable()));
    }
}
