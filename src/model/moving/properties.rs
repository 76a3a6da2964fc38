//! Matrix-property checks: is the transport operator gyroscopic (G = −Gᵀ) and is the transport
//! stiffness symmetric (K_T = K_Tᵀ)? The boundary terms decide (Hetzler 2009, §3.3.1).
//!
//! For a prismatic continuum transported along ξ with speed v (dimensionless, cross-section 1),
//! the operators P_T[W] = v W' and Q_T[W] = v² W'' satisfy, by integration by parts,
//!
//! ```text
//!   ⟨V, P_T W⟩ = R_P − ⟨W, P_T V⟩,   R_P = v [V W]₀¹                         (58)–(60), (64)
//!   ⟨V, Q_T W⟩ = R_Q + ⟨W, Q_T V⟩,   R_Q = v² [V W' − V' W]₀¹               (61)–(64)
//! ```
//!
//! so for a basis Φ with P_ij = ⟨Φ_i, v Φ_j'⟩ and Q_ij = ⟨Φ_i, v² Φ_j''⟩ (computed directly,
//! without integrating by parts): P + Pᵀ = R_P(Φ_i, Φ_j) and Q − Qᵀ = R_Q(Φ_i, Φ_j). G = 2P is
//! skew exactly when R_P vanishes on the basis (fixed guides, rigidly coupled or periodic ends,
//! Fig. 10) and K_T = Q symmetric exactly when R_Q vanishes (vanishing displacement or slope at
//! both ends, or periodicity, Fig. 12). Ends whose displacements differ (Fig. 11) make neither.

use faer::{Mat, MatRef};
use serde::{Deserialize, Serialize};

use crate::error::InputError;
use crate::fem::quadrature::GaussLegendre;

/// ‖A − Aᵀ‖_F / ‖A‖_F (0 for A = 0).
pub fn symmetry_defect(a: MatRef<'_, f64>) -> f64 {
    defect(a, -1.0)
}

/// ‖A + Aᵀ‖_F / ‖A‖_F (0 for A = 0).
pub fn skew_defect(a: MatRef<'_, f64>) -> f64 {
    defect(a, 1.0)
}

fn defect(a: MatRef<'_, f64>, sign: f64) -> f64 {
    let (mut d, mut s) = (0.0, 0.0);
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            let t = if j < a.nrows() && i < a.ncols() {
                a[(j, i)]
            } else {
                f64::NAN
            };
            d += (a[(i, j)] + sign * t).powi(2);
            s += a[(i, j)].powi(2);
        }
    }
    if s == 0.0 {
        0.0
    } else {
        (d / s).sqrt()
    }
}

/// The boundary conditions of the transported continuum in Figs 10–12.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TransportBoundary {
    /// W(0) = W(1) = 0: fixed guides (Fig. 10a, Fig. 12a). Basis √2 sin(kπξ).
    FixedGuides,
    /// W(0) = W(1): ends rigidly coupled (Fig. 10b). Basis 1, sin(kπξ).
    RigidlyCoupled,
    /// W and W' periodic (Fig. 10c). Basis 1, cos(2πkξ), sin(2πkξ).
    Periodic,
    /// W'(0) = W'(1) = 0: vanishing slope at both ends (Fig. 12b). Basis cos(kπξ).
    ZeroSlope,
    /// W(0) = 0, the other end free to move (Fig. 11): basis ξ^k, k ≥ 1.
    OneEndFree,
    /// Both ends free to move independently (Fig. 11): basis ξ^k, k ≥ 0.
    BothEndsFree,
}

impl TransportBoundary {
    /// All families.
    pub const ALL: [TransportBoundary; 6] = [
        TransportBoundary::FixedGuides,
        TransportBoundary::RigidlyCoupled,
        TransportBoundary::Periodic,
        TransportBoundary::ZeroSlope,
        TransportBoundary::OneEndFree,
        TransportBoundary::BothEndsFree,
    ];

    /// Does R_P vanish for every pair of admissible functions? (V(1)W(1) = V(0)W(0).)
    pub fn gyroscopic_predicted(self) -> bool {
        matches!(
            self,
            TransportBoundary::FixedGuides
                | TransportBoundary::RigidlyCoupled
                | TransportBoundary::Periodic
        )
    }

    /// Does R_Q vanish for every pair? (V W' − V' W equal at both ends.)
    pub fn symmetric_transport_stiffness_predicted(self) -> bool {
        matches!(
            self,
            TransportBoundary::FixedGuides
                | TransportBoundary::Periodic
                | TransportBoundary::ZeroSlope
        )
    }

    /// The figure of the paper.
    pub fn figure(self) -> &'static str {
        match self {
            TransportBoundary::FixedGuides => "Fig. 10a / 12a",
            TransportBoundary::RigidlyCoupled => "Fig. 10b",
            TransportBoundary::Periodic => "Fig. 10c",
            TransportBoundary::ZeroSlope => "Fig. 12b",
            TransportBoundary::OneEndFree | TransportBoundary::BothEndsFree => "Fig. 11",
        }
    }

    /// Basis function k (0-based) of the family and its first two derivatives at ξ.
    pub fn shape(self, k: usize, xi: f64) -> [f64; 3] {
        let pi = std::f64::consts::PI;
        let sin = |w: f64, s: f64| {
            [
                s * (w * xi).sin(),
                s * w * (w * xi).cos(),
                -s * w * w * (w * xi).sin(),
            ]
        };
        let cos = |w: f64| [(w * xi).cos(), -w * (w * xi).sin(), -w * w * (w * xi).cos()];
        let mono = |p: usize| {
            let pf = p as f64;
            [
                xi.powi(p as i32),
                if p >= 1 {
                    pf * xi.powi(p as i32 - 1)
                } else {
                    0.0
                },
                if p >= 2 {
                    pf * (pf - 1.0) * xi.powi(p as i32 - 2)
                } else {
                    0.0
                },
            ]
        };
        match self {
            TransportBoundary::FixedGuides => sin((k + 1) as f64 * pi, std::f64::consts::SQRT_2),
            TransportBoundary::RigidlyCoupled => {
                if k == 0 {
                    [1.0, 0.0, 0.0]
                } else {
                    sin(k as f64 * pi, 1.0)
                }
            }
            TransportBoundary::Periodic => {
                if k == 0 {
                    [1.0, 0.0, 0.0]
                } else {
                    let w = 2.0 * pi * k.div_ceil(2) as f64;
                    if k % 2 == 1 {
                        cos(w)
                    } else {
                        sin(w, 1.0)
                    }
                }
            }
            TransportBoundary::ZeroSlope => cos(k as f64 * pi),
            TransportBoundary::OneEndFree => mono(k + 1),
            TransportBoundary::BothEndsFree => mono(k),
        }
    }
}

/// The transport operators of a basis and their boundary terms.
#[derive(Debug, Clone, PartialEq)]
pub struct TransportOperators {
    /// P_ij = ⟨Φ_i, v Φ_j'⟩ (G = 2P).
    pub p: Mat<f64>,
    /// Q_ij = ⟨Φ_i, v² Φ_j''⟩ (K_T = Q).
    pub q: Mat<f64>,
    /// R_P(Φ_i, Φ_j) = v [Φ_i Φ_j]₀¹.
    pub r_p: Mat<f64>,
    /// R_Q(Φ_i, Φ_j) = v² [Φ_i Φ_j' − Φ_i' Φ_j]₀¹.
    pub r_q: Mat<f64>,
}

/// The boundary term matrix R_P of (60)/(64) for values at ξ = 0 and ξ = 1.
pub fn boundary_term_rp(speed: f64, at0: &[[f64; 3]], at1: &[[f64; 3]]) -> Mat<f64> {
    let n = at0.len();
    Mat::from_fn(n, n, |i, j| {
        speed * (at1[i][0] * at1[j][0] - at0[i][0] * at0[j][0])
    })
}

/// The boundary term matrix R_Q of (63)/(64) for values and slopes at ξ = 0 and ξ = 1.
pub fn boundary_term_rq(speed: f64, at0: &[[f64; 3]], at1: &[[f64; 3]]) -> Mat<f64> {
    let n = at0.len();
    let w = |a: &[[f64; 3]], i: usize, j: usize| a[i][0] * a[j][1] - a[i][1] * a[j][0];
    Mat::from_fn(n, n, |i, j| speed * speed * (w(at1, i, j) - w(at0, i, j)))
}

/// P, Q (by composite Gauss–Legendre quadrature, 16 panels × 12 points) and R_P, R_Q for the
/// first `functions` members of a boundary family at transport speed `speed`.
pub fn transport_operators(
    family: TransportBoundary,
    functions: usize,
    speed: f64,
) -> Result<TransportOperators, InputError> {
    if !(1..=12).contains(&functions) {
        return Err(InputError::new(
            "properties.functions",
            functions,
            "1 to 12 basis functions",
        ));
    }
    if !speed.is_finite() {
        return Err(InputError::new(
            "properties.speed",
            speed,
            "a finite number",
        ));
    }
    let n = functions;
    let rule = GaussLegendre::new(12)?;
    let panels = 16;
    let mut p = Mat::<f64>::zeros(n, n);
    let mut q = Mat::<f64>::zeros(n, n);
    let mut vals = vec![[0.0; 3]; n];
    for panel in 0..panels {
        let (a, b) = (
            panel as f64 / panels as f64,
            (panel + 1) as f64 / panels as f64,
        );
        for (&x, &w) in rule.points().iter().zip(rule.weights()) {
            let xi = 0.5 * (a + b) + 0.5 * (b - a) * x;
            let wt = 0.5 * (b - a) * w;
            for (k, v) in vals.iter_mut().enumerate() {
                *v = family.shape(k, xi);
            }
            for i in 0..n {
                for j in 0..n {
                    p[(i, j)] += wt * vals[i][0] * speed * vals[j][1];
                    q[(i, j)] += wt * vals[i][0] * speed * speed * vals[j][2];
                }
            }
        }
    }
    let at0: Vec<[f64; 3]> = (0..n).map(|k| family.shape(k, 0.0)).collect();
    let at1: Vec<[f64; 3]> = (0..n).map(|k| family.shape(k, 1.0)).collect();
    Ok(TransportOperators {
        p,
        q,
        r_p: boundary_term_rp(speed, &at0, &at1),
        r_q: boundary_term_rq(speed, &at0, &at1),
    })
}

#[cfg(test)]
mod tests {
    //! Setting: every boundary family of Figs 10–12. Goal: P + Pᵀ = R_P and Q − Qᵀ = R_Q to
    //! round-off, and the predicted (a)symmetry.
    use super::*;

    #[test]
    fn integration_by_parts_identities_hold_for_every_family() {
        for f in TransportBoundary::ALL {
            let t = transport_operators(f, 7, 0.6).unwrap();
            let n = 7;
            let scale_p = t.p.as_ref().norm_max();
            let scale_q = t.q.as_ref().norm_max();
            for i in 0..n {
                for j in 0..n {
                    let e1 = t.p[(i, j)] + t.p[(j, i)] - t.r_p[(i, j)];
                    let e2 = t.q[(i, j)] - t.q[(j, i)] - t.r_q[(i, j)];
                    assert!(e1.abs() < 1e-12 * scale_p, "{f:?} P {i} {j}: {e1}");
                    assert!(e2.abs() < 1e-12 * scale_q, "{f:?} Q {i} {j}: {e2}");
                }
            }
            assert_eq!(
                skew_defect(t.p.as_ref()) < 1e-12,
                f.gyroscopic_predicted(),
                "{f:?}"
            );
            assert_eq!(
                symmetry_defect(t.q.as_ref()) < 1e-12,
                f.symmetric_transport_stiffness_predicted(),
                "{f:?}"
            );
        }
    }

    #[test]
    fn too_many_functions_is_an_input_error() {
        let e = transport_operators(TransportBoundary::Periodic, 40, 1.0).unwrap_err();
        assert_eq!(e.field, "properties.functions");
    }
}
