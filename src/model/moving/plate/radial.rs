//! The radial Ritz basis of the plate: C¹ Hermite cubic elements on [a, b] (value and slope at
//! every node), the inner edge clamped (W(a) = W'(a) = 0; for a = 0 the paper's centre
//! conditions), the outer edge free, clamped or simply supported.
//!
//! With w = Σ R_j(r) ψ_k(φ) q_kj the Kirchhoff bending energy in polar coordinates,
//!
//! ```text
//!   U = D/2 ∫∫ [ (Δw)² − 2(1 − ν) ( w_rr (w_r/r + w_φφ/r²) − (∂_r(w_φ/r))² ) ] r dr dφ,
//! ```
//!
//! splits into products of angular and radial integrals (`model.rs`). This file computes the
//! radial ones (i test, j trial):
//!
//! ```text
//!   m[i,j] = ∫ R_j S_i r dr                                         (mass, transport)
//!   a[i,j] = ∫ [(R_j'' + R_j'/r)(S_i'' + S_i'/r) − (1−ν)(R_j'' S_i' + S_i'' R_j')/r] r dr
//!   c[i,j] = ∫ (ν R_j'' + R_j'/r) S_i / r dr                          (with ∫ψ_k χ_l'')
//!   d[i,j] = ∫ R_j S_i / r³ dr                                         (with ∫ψ_k'' χ_l'')
//!   e[i,j] = 2(1−ν) ∫ (R_j'/r − R_j/r²)(S_i'/r − S_i/r²) r dr           (twist, with ∫ψ_k' χ_l')
//! ```
//!
//! by 8-point Gauss–Legendre quadrature per element (the integrands are rational in r for a > 0;
//! for a = 0 the first element's constrained functions start at r², so its integrands are
//! polynomials and the quadrature never evaluates r = 0).

use faer::Mat;

use crate::error::InputError;
use crate::fem::hermite::hermite_shapes;
use crate::fem::quadrature::GaussLegendre;
use crate::model::moving::plate::data::OuterEdge;

/// The radial matrices of one basis (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct RadialMatrices {
    pub mass: Mat<f64>,
    pub a: Mat<f64>,
    pub c: Mat<f64>,
    pub d: Mat<f64>,
    pub e: Mat<f64>,
}

/// Hermite cubic elements on [a, b].
#[derive(Debug, Clone, PartialEq)]
pub struct RadialBasis {
    nodes: Vec<f64>,
    outer: OuterEdge,
    /// Global dof of (node, 0 = value | 1 = slope), `None` when constrained.
    dofs: Vec<[Option<usize>; 2]>,
    count: usize,
}

impl RadialBasis {
    /// `elements` equal elements on [a, b] (1 to 4000).
    pub fn uniform(a: f64, b: f64, elements: usize, outer: OuterEdge) -> Result<Self, InputError> {
        if !(1..=4000).contains(&elements) {
            return Err(InputError::new(
                "discretization.elements",
                elements,
                "1 to 4000 radial elements",
            ));
        }
        if !(a.is_finite() && b.is_finite() && a >= 0.0 && b > a) {
            return Err(InputError::new(
                "plate.outer_radius",
                b,
                format!("a radius > a = {a}"),
            ));
        }
        let nodes: Vec<f64> = (0..=elements)
            .map(|i| {
                if i == elements {
                    b
                } else {
                    a + (b - a) * i as f64 / elements as f64
                }
            })
            .collect();
        let mut dofs = vec![[None, None]; nodes.len()];
        let mut count = 0;
        for (i, d) in dofs.iter_mut().enumerate() {
            for (k, slot) in d.iter_mut().enumerate() {
                let constrained = i == 0
                    || (i == elements
                        && match outer {
                            OuterEdge::Free => false,
                            OuterEdge::Clamped => true,
                            OuterEdge::SimplySupported => k == 0,
                        });
                if !constrained {
                    *slot = Some(count);
                    count += 1;
                }
            }
        }
        if count == 0 {
            return Err(InputError::new(
                "discretization.elements",
                elements,
                "enough elements to leave a free radial function (≥ 2 for a clamped outer edge)",
            ));
        }
        Ok(Self {
            nodes,
            outer,
            dofs,
            count,
        })
    }

    /// The number of radial functions.
    pub fn len(&self) -> usize {
        self.count
    }

    /// Never empty (checked on construction).
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The element length h.
    pub fn h(&self) -> f64 {
        self.nodes[1] - self.nodes[0]
    }

    /// The outer-edge condition.
    pub fn outer_edge(&self) -> OuterEdge {
        self.outer
    }

    fn local_dofs(&self, e: usize) -> [Option<usize>; 4] {
        [
            self.dofs[e][0],
            self.dofs[e][1],
            self.dofs[e + 1][0],
            self.dofs[e + 1][1],
        ]
    }

    /// The values R_j(r) of every radial function at r ∈ [a, b] (0 outside).
    pub fn values_at(&self, r: f64, out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = 0.0);
        let ne = self.nodes.len() - 1;
        let (a, b) = (self.nodes[0], self.nodes[ne]);
        if !(r >= a && r <= b) {
            return;
        }
        let h = self.h();
        let e = (((r - a) / h).floor() as usize).min(ne - 1);
        let t = ((r - self.nodes[e]) / (self.nodes[e + 1] - self.nodes[e])).clamp(0.0, 1.0);
        let s = hermite_shapes(self.nodes[e + 1] - self.nodes[e], t);
        for (loc, dof) in self.local_dofs(e).into_iter().enumerate() {
            if let Some(g) = dof {
                out[g] += s[0][loc];
            }
        }
    }

    /// The coefficients of the interpolant of W given as r ↦ (W(r), W'(r)) (nodal values and
    /// slopes; constrained dofs dropped).
    pub fn interpolate(&self, w: impl Fn(f64) -> (f64, f64)) -> Vec<f64> {
        let mut q = vec![0.0; self.count];
        for (i, &r) in self.nodes.iter().enumerate() {
            let (v, s) = w(r);
            if let Some(g) = self.dofs[i][0] {
                q[g] = v;
            }
            if let Some(g) = self.dofs[i][1] {
                q[g] = s;
            }
        }
        q
    }

    /// The radial matrices for Poisson's ratio ν.
    pub fn matrices(&self, poisson: f64) -> Result<RadialMatrices, InputError> {
        let n = self.count;
        let z = || Mat::<f64>::zeros(n, n);
        let mut out = RadialMatrices {
            mass: z(),
            a: z(),
            c: z(),
            d: z(),
            e: z(),
        };
        let rule = GaussLegendre::new(8)?;
        let nu = poisson;
        for e in 0..self.nodes.len() - 1 {
            let (r0, r1) = (self.nodes[e], self.nodes[e + 1]);
            let h = r1 - r0;
            let dofs = self.local_dofs(e);
            for (&x, &w) in rule.points().iter().zip(rule.weights()) {
                let t = 0.5 * (1.0 + x);
                let r = r0 + h * t;
                let wt = 0.5 * h * w;
                let s = hermite_shapes(h, t);
                for (li, gi) in dofs.iter().enumerate() {
                    let Some(i) = *gi else { continue };
                    let (si, dsi, ddsi) = (s[0][li], s[1][li], s[2][li]);
                    for (lj, gj) in dofs.iter().enumerate() {
                        let Some(j) = *gj else { continue };
                        let (rj, drj, ddrj) = (s[0][lj], s[1][lj], s[2][lj]);
                        out.mass[(i, j)] += wt * rj * si * r;
                        out.a[(i, j)] += wt
                            * ((ddrj + drj / r) * (ddsi + dsi / r)
                                - (1.0 - nu) * (ddrj * dsi + ddsi * drj) / r)
                            * r;
                        out.c[(i, j)] += wt * (nu * ddrj + drj / r) * si / r;
                        out.d[(i, j)] += wt * rj * si / (r * r * r);
                        out.e[(i, j)] += wt
                            * 2.0
                            * (1.0 - nu)
                            * (drj / r - rj / (r * r))
                            * (dsi / r - si / (r * r))
                            * r;
                    }
                }
            }
        }
        Ok(out)
    }

    /// The rows of a strain factor B of the bending stiffness of harmonic n,
    /// K_n = D [a − n² (c + cᵀ) + n⁴ d + n² e] = Bᵀ B, passed to `row` one at a time as the
    /// element's four global dofs (`None`: constrained, its coefficient not part of B) and the
    /// four coefficients. For W(r) cos nφ the curvatures are
    /// κ_rr = W'', κ_θθ = W'/r − n² W/r², κ_rθ = n (W'/r − W/r²) (up to the angular factor), and
    /// the energy density (per unit ∫ψ²) is
    ///
    /// ```text
    ///   D [κ_rr² + κ_θθ² + 2ν κ_rr κ_θθ + 2(1 − ν) κ_rθ²] r
    ///     = D [(κ_rr + ν κ_θθ)² + (1 − ν²) κ_θθ² + 2(1 − ν) κ_rθ²] r,
    /// ```
    ///
    /// a sum of three squares for −1 < ν < 1; at each Gauss point with weight w_g the three rows
    /// are √(D w_g r) times (κ_rr + ν κ_θθ, √(1 − ν²) κ_θθ, √(2(1 − ν)) κ_rθ) of the shape
    /// functions. Expanding the squares gives back the integrands of a, c, d, e (module docs), so
    /// BᵀB = K_n up to round-off (unit test). The factor is what keeps the low frequencies
    /// accurate on fine meshes (`modes.rs`): it is never squared.
    pub fn strain_rows(
        &self,
        poisson: f64,
        n: usize,
        bending_stiffness: f64,
        mut row: impl FnMut(&[Option<usize>; 4], &[f64; 4]),
    ) -> Result<(), InputError> {
        let rule = GaussLegendre::new(8)?;
        let nu = poisson;
        let n2 = (n * n) as f64;
        let nf = n as f64;
        let (s_tt, s_rt) = ((1.0 - nu * nu).sqrt(), (2.0 * (1.0 - nu)).sqrt());
        for e in 0..self.nodes.len() - 1 {
            let (r0, r1) = (self.nodes[e], self.nodes[e + 1]);
            let h = r1 - r0;
            let dofs = self.local_dofs(e);
            for (&x, &w) in rule.points().iter().zip(rule.weights()) {
                let t = 0.5 * (1.0 + x);
                let r = r0 + h * t;
                let scale = (bending_stiffness * 0.5 * h * w * r).sqrt();
                let s = hermite_shapes(h, t);
                let (mut b1, mut b2, mut b3) = ([0.0; 4], [0.0; 4], [0.0; 4]);
                for l in 0..4 {
                    let (v, d1, d2) = (s[0][l], s[1][l], s[2][l]);
                    let k_tt = d1 / r - n2 * v / (r * r);
                    let k_rt = nf * (d1 / r - v / (r * r));
                    b1[l] = scale * (d2 + nu * k_tt);
                    b2[l] = scale * s_tt * k_tt;
                    b3[l] = scale * s_rt * k_rt;
                }
                row(&dofs, &b1);
                row(&dofs, &b2);
                row(&dofs, &b3);
            }
        }
        Ok(())
    }

    /// ∫ N_r R_j' S_i' r dr and ∫ N_θ R_j S_i / r dr for in-plane stress resultants given as
    /// functions of r (the membrane stiffening, `membrane.rs`).
    pub fn membrane_matrices(
        &self,
        radial_stress: impl Fn(f64) -> f64,
        hoop_stress: impl Fn(f64) -> f64,
    ) -> Result<(Mat<f64>, Mat<f64>), InputError> {
        let n = self.count;
        let (mut kr, mut kt) = (Mat::<f64>::zeros(n, n), Mat::<f64>::zeros(n, n));
        let rule = GaussLegendre::new(8)?;
        for e in 0..self.nodes.len() - 1 {
            let (r0, r1) = (self.nodes[e], self.nodes[e + 1]);
            let h = r1 - r0;
            let dofs = self.local_dofs(e);
            for (&x, &w) in rule.points().iter().zip(rule.weights()) {
                let t = 0.5 * (1.0 + x);
                let r = r0 + h * t;
                let wt = 0.5 * h * w;
                let (nr, nt) = (radial_stress(r), hoop_stress(r));
                let s = hermite_shapes(h, t);
                for (li, gi) in dofs.iter().enumerate() {
                    let Some(i) = *gi else { continue };
                    for (lj, gj) in dofs.iter().enumerate() {
                        let Some(j) = *gj else { continue };
                        kr[(i, j)] += wt * nr * s[1][lj] * s[1][li] * r;
                        kt[(i, j)] += wt * nt * s[0][lj] * s[0][li] / r;
                    }
                }
            }
        }
        Ok((kr, kt))
    }
}

#[cfg(test)]
mod tests {
    //! Setting: the radial basis on [0.2, 1]. Goal: the constraints remove the right dofs, and every
    //! radial integral is exact on W = r², which the space contains.
    use super::*;

    #[test]
    fn outer_edge_conditions_remove_the_right_dofs() {
        let free = RadialBasis::uniform(0.2, 1.0, 4, OuterEdge::Free).unwrap();
        let ss = RadialBasis::uniform(0.2, 1.0, 4, OuterEdge::SimplySupported).unwrap();
        let cl = RadialBasis::uniform(0.2, 1.0, 4, OuterEdge::Clamped).unwrap();
        assert_eq!((free.len(), ss.len(), cl.len()), (8, 7, 6));
        assert!(RadialBasis::uniform(0.2, 1.0, 1, OuterEdge::Clamped).is_err());
        assert!(RadialBasis::uniform(0.2, 1.0, 0, OuterEdge::Free).is_err());
    }

    #[test]
    fn radial_integrals_are_exact_for_r_squared() {
        // W = r² on [0, 1] is in the cubic Hermite space with W(0) = W'(0) = 0, so every
        // radial integral of it is exact: m = ∫ r⁵ = 1/6, a = ∫ (16 − 8(1−ν)) r = 8 − 4(1−ν),
        // c = ∫ (2ν + 2) r = 1 + ν, d = ∫ r = 1/2, e = 2(1−ν) ∫ r = 1 − ν.
        let nu = 0.3;
        let b = RadialBasis::uniform(0.0, 1.0, 5, OuterEdge::Free).unwrap();
        let q = b.interpolate(|r| (r * r, 2.0 * r));
        let m = b.matrices(nu).unwrap();
        let quad = |a: &Mat<f64>| {
            let mut s = 0.0;
            for i in 0..b.len() {
                for j in 0..b.len() {
                    s += q[i] * a[(i, j)] * q[j];
                }
            }
            s
        };
        let close = |x: f64, y: f64| (x - y).abs() < 1e-13 * y.abs().max(1.0);
        assert!(close(quad(&m.mass), 1.0 / 6.0));
        assert!(close(quad(&m.a), 8.0 - 4.0 * (1.0 - nu)));
        assert!(close(quad(&m.c), 1.0 + nu));
        assert!(close(quad(&m.d), 0.5));
        assert!(close(quad(&m.e), 1.0 - nu));
        let mut v = vec![0.0; b.len()];
        b.values_at(0.7, &mut v);
        let w: f64 = v.iter().zip(&q).map(|(a, b)| a * b).sum();
        assert!(close(w, 0.49));
    }
}
