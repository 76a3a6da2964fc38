//! The angular Ritz basis of the plate and its Gram matrices.
//!
//! The full disc is periodic in φ: the basis 1, cos nφ, sin nφ (n = 1 … N) with closed-form
//! integrals. For the symmetry checks of Hetzler (2009) §3.3.1 the plate can also be an annular
//! *sector* 0 ≤ φ ≤ Θ through whose radial edges the material is transported (a spatial window
//! of the spinning disc, as the string between guides): its angular functions are the string's
//! families of Figs 10–12 (`properties::TransportBoundary`) in ξ = φ/Θ, integrated by quadrature.
//!
//! With ψ_k the trial and χ_l the test functions (both from the same basis):
//!
//! ```text
//!   A0[l,k] = ∫ χ_l ψ_k,  A11[l,k] = ∫ χ_l' ψ_k',  A20[l,k] = ∫ χ_l'' ψ_k,  A22[l,k] = ∫ χ_l'' ψ_k''
//!   P[l,k] = ∫ χ_l ψ_k'   (gyroscopic: G = 2Ω ρh P ⊗ m, (72)–(74))
//!   Q[l,k] = ∫ χ_l ψ_k''  (transport stiffness: K_T = Ω² ρh Q ⊗ m)
//! ```
//!
//! P and Q are computed without integrating by parts: P + Pᵀ = [χψ] and Q − Qᵀ = [χψ' − χ'ψ]
//! over the edges, which vanish for the periodic basis (G skew, K_T symmetric) and not for every
//! sector family.

use std::f64::consts::PI;

use faer::Mat;
use serde::Serialize;

use crate::error::InputError;
use crate::fem::quadrature::GaussLegendre;
use crate::model::moving::properties::TransportBoundary;

/// The angular basis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum AngularBasis {
    /// The full disc: 1, cos nφ, sin nφ for n = 1 … `harmonics` (2N + 1 functions).
    Periodic { harmonics: usize },
    /// A sector 0 ≤ φ ≤ `angle` with the first `functions` functions of `edges` in φ/Θ.
    Sector {
        angle: f64,
        edges: TransportBoundary,
        functions: usize,
    },
}

/// The angular Gram matrices (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct AngularMatrices {
    pub a0: Mat<f64>,
    pub a11: Mat<f64>,
    pub a20: Mat<f64>,
    pub a22: Mat<f64>,
    pub p: Mat<f64>,
    pub q: Mat<f64>,
}

impl AngularBasis {
    /// Checks the basis.
    pub fn validate(&self) -> Result<(), InputError> {
        match *self {
            AngularBasis::Periodic { harmonics } => {
                if harmonics > 64 {
                    return Err(InputError::new(
                        "discretization.harmonics",
                        harmonics,
                        "0 to 64 harmonics",
                    ));
                }
            }
            AngularBasis::Sector {
                angle, functions, ..
            } => {
                if !(angle.is_finite() && angle > 0.0 && angle < 2.0 * PI) {
                    return Err(InputError::new(
                        "discretization.sector_angle",
                        angle,
                        "an angle in (0, 2π)",
                    ));
                }
                if !(1..=12).contains(&functions) {
                    return Err(InputError::new(
                        "discretization.functions",
                        functions,
                        "1 to 12 angular functions",
                    ));
                }
            }
        }
        Ok(())
    }

    /// The number of angular functions.
    pub fn len(&self) -> usize {
        match *self {
            AngularBasis::Periodic { harmonics } => 2 * harmonics + 1,
            AngularBasis::Sector { functions, .. } => functions,
        }
    }

    /// Never empty.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// For the periodic basis, the harmonic n of function k and whether it is a sine.
    pub fn harmonic(&self, k: usize) -> Option<(usize, bool)> {
        match self {
            AngularBasis::Periodic { .. } => Some((k.div_ceil(2), k > 0 && k % 2 == 0)),
            AngularBasis::Sector { .. } => None,
        }
    }

    /// (ψ_k, ψ_k', ψ_k'') at φ.
    pub fn shape(&self, k: usize, phi: f64) -> [f64; 3] {
        match *self {
            AngularBasis::Periodic { .. } => {
                let (n, sine) = self.harmonic(k).unwrap_or((0, false));
                let nf = n as f64;
                let (s, c) = (nf * phi).sin_cos();
                if n == 0 {
                    [1.0, 0.0, 0.0]
                } else if sine {
                    [s, nf * c, -nf * nf * s]
                } else {
                    [c, -nf * s, -nf * nf * c]
                }
            }
            AngularBasis::Sector { angle, edges, .. } => {
                let s = edges.shape(k, phi / angle);
                [s[0], s[1] / angle, s[2] / (angle * angle)]
            }
        }
    }

    /// The Gram matrices: closed forms for the periodic basis, quadrature (16 panels × 12
    /// Gauss–Legendre points, as for the string's families) for a sector.
    pub fn matrices(&self) -> Result<AngularMatrices, InputError> {
        self.validate()?;
        let n = self.len();
        let z = || Mat::<f64>::zeros(n, n);
        let mut m = AngularMatrices {
            a0: z(),
            a11: z(),
            a20: z(),
            a22: z(),
            p: z(),
            q: z(),
        };
        match *self {
            AngularBasis::Periodic { .. } => {
                for k in 0..n {
                    let (h, sine) = self.harmonic(k).unwrap_or((0, false));
                    let nf = h as f64;
                    let norm = if h == 0 { 2.0 * PI } else { PI };
                    m.a0[(k, k)] = norm;
                    m.a11[(k, k)] = nf * nf * norm;
                    m.a20[(k, k)] = -nf * nf * norm;
                    m.a22[(k, k)] = nf.powi(4) * norm;
                    m.q[(k, k)] = -nf * nf * norm;
                    if h > 0 && sine {
                        // ∫ cos_n (sin_n)' = nπ, ∫ sin_n (cos_n)' = −nπ
                        m.p[(k - 1, k)] = nf * PI;
                        m.p[(k, k - 1)] = -nf * PI;
                    }
                }
            }
            AngularBasis::Sector { angle, .. } => {
                let rule = GaussLegendre::new(12)?;
                let panels = 16;
                let mut vals = vec![[0.0; 3]; n];
                for panel in 0..panels {
                    let (lo, hi) = (
                        angle * panel as f64 / panels as f64,
                        angle * (panel + 1) as f64 / panels as f64,
                    );
                    for (&x, &w) in rule.points().iter().zip(rule.weights()) {
                        let phi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x;
                        let wt = 0.5 * (hi - lo) * w;
                        for (k, v) in vals.iter_mut().enumerate() {
                            *v = self.shape(k, phi);
                        }
                        for l in 0..n {
                            for k in 0..n {
                                let (c, p) = (vals[l], vals[k]);
                                m.a0[(l, k)] += wt * c[0] * p[0];
                                m.a11[(l, k)] += wt * c[1] * p[1];
                                m.a20[(l, k)] += wt * c[2] * p[0];
                                m.a22[(l, k)] += wt * c[2] * p[2];
                                m.p[(l, k)] += wt * c[0] * p[1];
                                m.q[(l, k)] += wt * c[0] * p[2];
                            }
                        }
                    }
                }
            }
        }
        Ok(m)
    }
}

#[cfg(test)]
mod tests {
    //! Setting: the periodic basis with N = 3. Goal: the closed-form Gram matrices equal the
    //! integrals by quadrature of the shapes (a wrong sign in P or a wrong norm fails), and the
    //! sector basis is validated.
    use super::*;

    #[test]
    fn periodic_closed_forms_equal_quadrature() {
        let basis = AngularBasis::Periodic { harmonics: 3 };
        let m = basis.matrices().unwrap();
        let rule = GaussLegendre::new(12).unwrap();
        let n = basis.len();
        let mut num = AngularMatrices {
            a0: Mat::zeros(n, n),
            a11: Mat::zeros(n, n),
            a20: Mat::zeros(n, n),
            a22: Mat::zeros(n, n),
            p: Mat::zeros(n, n),
            q: Mat::zeros(n, n),
        };
        for panel in 0..32 {
            let (lo, hi) = (
                2.0 * PI * panel as f64 / 32.0,
                2.0 * PI * (panel + 1) as f64 / 32.0,
            );
            for (&x, &w) in rule.points().iter().zip(rule.weights()) {
                let phi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x;
                let wt = 0.5 * (hi - lo) * w;
                for l in 0..n {
                    for k in 0..n {
                        let (c, p) = (basis.shape(l, phi), basis.shape(k, phi));
                        num.a0[(l, k)] += wt * c[0] * p[0];
                        num.a11[(l, k)] += wt * c[1] * p[1];
                        num.a20[(l, k)] += wt * c[2] * p[0];
                        num.a22[(l, k)] += wt * c[2] * p[2];
                        num.p[(l, k)] += wt * c[0] * p[1];
                        num.q[(l, k)] += wt * c[0] * p[2];
                    }
                }
            }
        }
        for (a, b) in [
            (&m.a0, &num.a0),
            (&m.a11, &num.a11),
            (&m.a20, &num.a20),
            (&m.a22, &num.a22),
            (&m.p, &num.p),
            (&m.q, &num.q),
        ] {
            for l in 0..n {
                for k in 0..n {
                    assert!((a[(l, k)] - b[(l, k)]).abs() < 1e-12, "({l}, {k})");
                }
            }
        }
    }

    #[test]
    fn sector_bases_are_validated() {
        let bad = AngularBasis::Sector {
            angle: 7.0,
            edges: TransportBoundary::FixedGuides,
            functions: 4,
        };
        assert_eq!(
            bad.validate().unwrap_err().field,
            "discretization.sector_angle"
        );
        assert!(AngularBasis::Periodic { harmonics: 65 }.validate().is_err());
    }
}
