//! Finite-element Ritz bases of the string on [0, 1] with w(0) = w(1) = 0: P1 (hat functions) and
//! C¹ Hermite cubics, the second discretization of the moving string (the first is the sine basis).
//!
//! The Gram matrices of [`super::basis::StringOperators`] are assembled element by element with
//! 4-point Gauss–Legendre quadrature (exact for the products of cubics and their derivatives).
//! The curvature operator uses ⟨Φ_i, Φ''_j⟩ = [Φ_i Φ'_j]₀¹ − ⟨Φ'_i, Φ'_j⟩ = −⟨Φ'_i, Φ'_j⟩ (the
//! functions vanish at both guides), which is exact for C¹ Hermite functions and the weak
//! definition for C⁰ hat functions (Hetzler 2009, (61)–(64) with R_Q = 0).
//!
//! Expected eigenvalue errors for smooth eigenfunctions: O(h²) for P1 and O(h⁶)…O(h⁴) for Hermite
//! (the verification suite measures them).

use faer::Mat;

use crate::error::InputError;
use crate::fem::quadrature::GaussLegendre;
use crate::mesh::interval::IntervalMesh;
use crate::model::moving::basis::{RitzBasis, StringOperators};

/// The element family.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ElementKind {
    /// Continuous piecewise-linear hat functions at the interior nodes.
    P1,
    /// C¹ piecewise-cubic Hermite functions: value and slope at every node (no value at the ends).
    Hermite,
}

/// A finite-element basis on a mesh of [0, 1].
#[derive(Debug, Clone, PartialEq)]
pub struct FiniteElementBasis {
    kind: ElementKind,
    mesh: IntervalMesh,
}

/// Local shape functions on an element of length h at local t ∈ [0, 1]: (value, d/dξ) of each.
fn local_shapes(kind: ElementKind, h: f64, t: f64) -> ([f64; 4], [f64; 4]) {
    match kind {
        ElementKind::P1 => ([1.0 - t, t, 0.0, 0.0], [-1.0 / h, 1.0 / h, 0.0, 0.0]),
        ElementKind::Hermite => {
            let [value, slope, _] = crate::fem::hermite::hermite_shapes(h, t);
            (value, slope)
        }
    }
}

impl FiniteElementBasis {
    /// A basis of `kind` on `elements` equal elements of [0, 1].
    pub fn uniform(kind: ElementKind, elements: usize) -> Result<Self, InputError> {
        let min = match kind {
            ElementKind::P1 => 2,
            ElementKind::Hermite => 1,
        };
        if elements < min {
            return Err(InputError::new(
                "discretization.elements",
                elements,
                format!("at least {min} elements for {kind:?}"),
            ));
        }
        Ok(Self {
            kind,
            mesh: IntervalMesh::uniform(1.0, elements)?,
        })
    }

    /// A basis of `kind` on a given mesh of [0, 1].
    pub fn on_mesh(kind: ElementKind, mesh: IntervalMesh) -> Result<Self, InputError> {
        if (mesh.length() - 1.0).abs() > 1e-14 {
            return Err(InputError::new(
                "discretization.mesh",
                mesh.length(),
                "a mesh of [0, 1]",
            ));
        }
        let b = Self::uniform(kind, mesh.elements())?;
        Ok(Self { mesh, ..b })
    }

    /// The element family.
    pub fn kind(&self) -> ElementKind {
        self.kind
    }

    /// The largest element length h.
    pub fn h(&self) -> f64 {
        self.mesh.h_max()
    }

    /// Global dof of local shape `a` of element `e` (`None`: constrained by w = 0 at a guide).
    fn dof(&self, e: usize, a: usize) -> Option<usize> {
        let ne = self.mesh.elements();
        match self.kind {
            ElementKind::P1 => {
                let node = e + a;
                (a < 2 && node > 0 && node < ne).then(|| node - 1)
            }
            ElementKind::Hermite => {
                let node = e + a / 2;
                if a % 2 == 0 {
                    self.value_dof(node)
                } else {
                    Some(self.slope_dof(node))
                }
            }
        }
    }

    /// Hermite: the value dof of a node (none at the guides); dofs are numbered node by node,
    /// value before slope: θ0, w1, θ1, …, w_{M−1}, θ_{M−1}, θ_M.
    fn value_dof(&self, node: usize) -> Option<usize> {
        (node > 0 && node < self.mesh.elements()).then(|| 2 * node - 1)
    }

    /// Hermite: the slope dof of a node.
    fn slope_dof(&self, node: usize) -> usize {
        (2 * node).min(2 * self.mesh.elements() - 1)
    }
}

impl RitzBasis for FiniteElementBasis {
    fn len(&self) -> usize {
        let ne = self.mesh.elements();
        match self.kind {
            ElementKind::P1 => ne - 1,
            ElementKind::Hermite => 2 * ne,
        }
    }

    fn operators(&self) -> StringOperators {
        let n = self.len();
        let mut mass = Mat::<f64>::zeros(n, n);
        let mut transport = Mat::<f64>::zeros(n, n);
        let mut stiffness = Mat::<f64>::zeros(n, n);
        let rule = GaussLegendre::new(4).unwrap_or_else(|_| unreachable!("4 points is valid"));
        let locals = match self.kind {
            ElementKind::P1 => 2,
            ElementKind::Hermite => 4,
        };
        for e in 0..self.mesh.elements() {
            let (x0, x1) = self.mesh.element(e);
            let h = x1 - x0;
            for (&p, &w) in rule.points().iter().zip(rule.weights()) {
                let t = 0.5 * (p + 1.0);
                let wt = 0.5 * w * h;
                let (v, d) = local_shapes(self.kind, h, t);
                for a in 0..locals {
                    let Some(i) = self.dof(e, a) else { continue };
                    for b in 0..locals {
                        let Some(j) = self.dof(e, b) else { continue };
                        mass[(i, j)] += wt * v[a] * v[b];
                        transport[(i, j)] += wt * v[a] * d[b];
                        stiffness[(i, j)] += wt * d[a] * d[b];
                    }
                }
            }
        }
        let curvature = Mat::from_fn(n, n, |i, j| -stiffness[(i, j)]);
        StringOperators {
            mass,
            transport,
            stiffness,
            curvature,
        }
    }

    fn point_values_into(&self, xi: f64, values: &mut [f64], slopes: &mut [f64]) {
        values.iter_mut().for_each(|v| *v = 0.0);
        slopes.iter_mut().for_each(|v| *v = 0.0);
        let nodes = self.mesh.nodes();
        let ne = self.mesh.elements();
        let Some(e) = self.mesh.locate(xi.clamp(0.0, 1.0)) else {
            return;
        };
        // At an interior node, average the two elements' slopes (P1 slopes jump there).
        let at_node = (1..ne).find(|&i| (nodes[i] - xi).abs() <= 1e-14);
        let elements: Vec<(usize, f64)> = match at_node {
            Some(i) => vec![(i - 1, 0.5), (i, 0.5)],
            None => vec![(e, 1.0)],
        };
        for (e, weight) in elements {
            let (x0, x1) = self.mesh.element(e);
            let h = x1 - x0;
            let t = ((xi - x0) / h).clamp(0.0, 1.0);
            let (v, d) = local_shapes(self.kind, h, t);
            for a in 0..4 {
                if let Some(i) = self.dof(e, a) {
                    values[i] += weight * v[a];
                    slopes[i] += weight * d[a];
                }
            }
        }
    }

    /// Means by three-point Gauss–Legendre on each element's share of [a, b] (exact for the cubic
    /// Hermite functions, and for P1); mean slopes from the (continuous) values at a and b.
    fn patch_means_into(&self, a: f64, b: f64, means: &mut [f64], mean_slopes: &mut [f64]) {
        means.iter_mut().for_each(|v| *v = 0.0);
        let width = b - a;
        let gauss = [
            (-(0.6f64).sqrt(), 5.0 / 9.0),
            (0.0, 8.0 / 9.0),
            ((0.6f64).sqrt(), 5.0 / 9.0),
        ];
        for e in 0..self.mesh.elements() {
            let (x0, x1) = self.mesh.element(e);
            let (lo, hi) = (x0.max(a), x1.min(b));
            if hi <= lo {
                continue;
            }
            let h = x1 - x0;
            for (g, w) in gauss {
                let x = 0.5 * (lo + hi) + 0.5 * (hi - lo) * g;
                let (v, _) = local_shapes(self.kind, h, (x - x0) / h);
                for (i, vi) in v.iter().enumerate() {
                    if let Some(dof) = self.dof(e, i) {
                        means[dof] += 0.5 * (hi - lo) * w * vi / width;
                    }
                }
            }
        }
        let n = means.len();
        let (mut va, mut vb, mut scratch) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        self.point_values_into(a, &mut va, &mut scratch);
        self.point_values_into(b, &mut vb, &mut scratch);
        for k in 0..n {
            mean_slopes[k] = (vb[k] - va[k]) / width;
        }
    }

    fn label(&self) -> String {
        let kind = match self.kind {
            ElementKind::P1 => "P1",
            ElementKind::Hermite => "Hermite",
        };
        format!("{kind}, {} elements", self.mesh.elements())
    }
}

#[cfg(test)]
mod tests {
    //! Setting: P1 and Hermite bases on uniform meshes. Goal: the textbook element matrices, exact
    //! skew-symmetry of the transport operator, and exact interpolation of w = ξ(1 − ξ) by
    //! Hermite cubics.
    use super::*;

    #[test]
    fn p1_matrices_are_the_textbook_tridiagonals() {
        let b = FiniteElementBasis::uniform(ElementKind::P1, 4).unwrap();
        let ops = b.operators();
        let h = 0.25;
        assert_eq!(b.len(), 3);
        assert!((ops.mass[(1, 1)] - 4.0 * h / 6.0).abs() < 1e-15);
        assert!((ops.mass[(1, 2)] - h / 6.0).abs() < 1e-15);
        assert!((ops.stiffness[(1, 1)] - 2.0 / h).abs() < 1e-13);
        assert!((ops.stiffness[(0, 1)] + 1.0 / h).abs() < 1e-13);
        assert!((ops.transport[(0, 1)] - 0.5).abs() < 1e-15);
        assert!((ops.transport[(1, 0)] + 0.5).abs() < 1e-15);
        assert!(ops.transport[(1, 1)].abs() < 1e-15);
    }

    /// The Hermite coefficients (nodal values and slopes) of w = ξ(1 − ξ) on `elements` equal
    /// elements, which the basis reproduces exactly.
    fn quadratic_coefficients(b: &FiniteElementBasis, elements: usize) -> Vec<f64> {
        let mut q = vec![0.0; b.len()];
        for node in 0..=elements {
            let x = node as f64 / elements as f64;
            if let Some(i) = b.value_dof(node) {
                q[i] = x * (1.0 - x);
            }
            q[b.slope_dof(node)] = 1.0 - 2.0 * x;
        }
        q
    }

    #[test]
    fn hermite_transport_is_skew_and_values_interpolate_cubics() {
        let b = FiniteElementBasis::uniform(ElementKind::Hermite, 5).unwrap();
        let n = b.len();
        assert_eq!(n, 10);
        let ops = b.operators();
        for i in 0..n {
            for j in 0..n {
                assert!((ops.transport[(i, j)] + ops.transport[(j, i)]).abs() < 1e-14);
                assert!((ops.mass[(i, j)] - ops.mass[(j, i)]).abs() < 1e-15);
            }
        }
        // w = ξ(1 − ξ): nodal values and slopes as coefficients reproduce it exactly.
        let q = quadratic_coefficients(&b, 5);
        let (mut v, mut s) = (vec![0.0; n], vec![0.0; n]);
        for xi in [0.0, 0.13, 0.4, 0.77, 1.0] {
            b.point_values_into(xi, &mut v, &mut s);
            let w: f64 = v.iter().zip(&q).map(|(a, b)| a * b).sum();
            let dw: f64 = s.iter().zip(&q).map(|(a, b)| a * b).sum();
            assert!((w - xi * (1.0 - xi)).abs() < 1e-14, "{xi}: {w}");
            assert!((dw - (1.0 - 2.0 * xi)).abs() < 1e-13, "{xi}: {dw}");
        }
    }

    #[test]
    fn patch_means_of_an_interpolated_quadratic_are_exact() {
        // w = ξ(1 − ξ), exact in the Hermite basis: its patch mean over [a, b] is
        // (b² − a²)/2 − (b³ − a³)/3 over (b − a), its mean slope 1 − (a + b); patches across
        // element ends and inside one element.
        let b = FiniteElementBasis::uniform(ElementKind::Hermite, 5).unwrap();
        let n = b.len();
        let q = quadratic_coefficients(&b, 5);
        let (mut m, mut s) = (vec![0.0; n], vec![0.0; n]);
        for (lo, hi) in [(0.13, 0.77), (0.41, 0.45), (0.2, 0.4), (0.05, 0.95)] {
            b.patch_means_into(lo, hi, &mut m, &mut s);
            let mean: f64 = m.iter().zip(&q).map(|(a, b)| a * b).sum();
            let slope: f64 = s.iter().zip(&q).map(|(a, b)| a * b).sum();
            let exact = ((hi * hi - lo * lo) / 2.0 - (hi.powi(3) - lo.powi(3)) / 3.0) / (hi - lo);
            assert!(
                (mean - exact).abs() < 1e-14,
                "[{lo}, {hi}]: {mean} vs {exact}"
            );
            assert!(
                (slope - (1.0 - lo - hi)).abs() < 1e-13,
                "[{lo}, {hi}]: {slope}"
            );
        }
    }

    #[test]
    fn too_few_elements_is_an_input_error() {
        let e = FiniteElementBasis::uniform(ElementKind::P1, 1).unwrap_err();
        assert_eq!(e.field, "discretization.elements");
    }
}
