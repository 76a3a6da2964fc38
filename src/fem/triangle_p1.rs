//! P1 triangles for plane vector fields: element geometry, strains, and the element stiffness of a
//! linear isotropic operator.
//!
//! Degrees of freedom are interleaved per node: (u_x, u_y) of node i are dofs 2i and 2i + 1. On an
//! element with nodes a = 0, 1, 2 the strain is constant:
//! ε11 = Σ_a ∂_1φ_a u_a,x, ε22 = Σ_a ∂_2φ_a u_a,y, ε12 = ½ Σ_a (∂_2φ_a u_a,x + ∂_1φ_a u_a,y).

use nalgebra::{SMatrix, SVector};

/// A 2D symmetric tensor as (τ11, τ22, τ12).
pub type Sym2 = [f64; 3];

/// The double contraction σ : ε = σ11 ε11 + σ22 ε22 + 2 σ12 ε12.
#[inline]
pub fn contract(s: &Sym2, e: &Sym2) -> f64 {
    s[0] * e[0] + s[1] * e[1] + 2.0 * s[2] * e[2]
}

/// Geometry of one P1 triangle: area and the constant gradients of the three shape functions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct P1Triangle {
    pub area: f64,
    /// ∇φ_a = (grad[a][0], grad[a][1]).
    pub grad: [[f64; 2]; 3],
}

impl P1Triangle {
    /// The geometry of the counter-clockwise triangle with vertices `p`.
    pub fn new(p: [[f64; 2]; 3]) -> Self {
        let det =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        let inv = 1.0 / det;
        let grad = [
            [(p[1][1] - p[2][1]) * inv, (p[2][0] - p[1][0]) * inv],
            [(p[2][1] - p[0][1]) * inv, (p[0][0] - p[2][0]) * inv],
            [(p[0][1] - p[1][1]) * inv, (p[1][0] - p[0][0]) * inv],
        ];
        Self {
            area: 0.5 * det,
            grad,
        }
    }

    /// ε(u) for the element's six nodal values (u_0x, u_0y, u_1x, …).
    #[inline]
    pub fn strain(&self, u: &[f64; 6]) -> Sym2 {
        let g = &self.grad;
        let mut e = [0.0; 3];
        for a in 0..3 {
            let (ux, uy) = (u[2 * a], u[2 * a + 1]);
            e[0] += g[a][0] * ux;
            e[1] += g[a][1] * uy;
            e[2] += 0.5 * (g[a][1] * ux + g[a][0] * uy);
        }
        e
    }

    /// The strain of the element's local dof `p` set to 1 (a column of the strain operator).
    #[inline]
    pub fn unit_strain(&self, p: usize) -> Sym2 {
        let (a, c) = (p / 2, p % 2);
        let g = self.grad[a];
        if c == 0 {
            [g[0], 0.0, 0.5 * g[1]]
        } else {
            [0.0, g[1], 0.5 * g[0]]
        }
    }

    /// The nodal forces ∫ σ : ε(φ_p) = area σ : ε(φ_p) for a constant stress.
    #[inline]
    pub fn internal_forces(&self, s: &Sym2) -> [f64; 6] {
        let mut f = [0.0; 6];
        for (p, fp) in f.iter_mut().enumerate() {
            *fp = self.area * contract(s, &self.unit_strain(p));
        }
        f
    }

    /// The element matrix K_pq = area ε(φ_p) : C ε(φ_q) of a (possibly non-isotropic) linear map
    /// C given as its action on tensors.
    pub fn stiffness(&self, c: impl Fn(&Sym2) -> Sym2) -> SMatrix<f64, 6, 6> {
        let mut k = SMatrix::<f64, 6, 6>::zeros();
        let cols: [Sym2; 6] = std::array::from_fn(|q| c(&self.unit_strain(q)));
        for p in 0..6 {
            let ep = self.unit_strain(p);
            for q in 0..6 {
                k[(p, q)] = self.area * contract(&cols[q], &ep);
            }
        }
        k
    }

    /// The barycentric coordinates of the rule point `l` mapped to the element.
    #[inline]
    pub fn point(p: &[[f64; 2]; 3], l: &[f64; 3]) -> [f64; 2] {
        [
            l[0] * p[0][0] + l[1] * p[1][0] + l[2] * p[2][0],
            l[0] * p[0][1] + l[1] * p[1][1] + l[2] * p[2][1],
        ]
    }
}

/// The local vector as an nalgebra vector (for tests and small algebra).
pub fn local_vector(u: &[f64; 6]) -> SVector<f64, 6> {
    SVector::<f64, 6>::from_column_slice(u)
}

#[cfg(test)]
mod tests {
    //! P1 triangles: gradients reproduce linear fields, rigid motions have zero strain, the element
    //! stiffness is symmetric with the rigid motions in its kernel.
    use super::*;

    const P: [[f64; 2]; 3] = [[0.2, 0.1], [1.3, 0.4], [0.5, 1.2]];

    #[test]
    fn strain_of_a_linear_field_is_exact() {
        let t = P1Triangle::new(P);
        // u = (2x + 3y, −x + 5y): ε11 = 2, ε22 = 5, ε12 = (3 − 1)/2 = 1
        let mut u = [0.0; 6];
        for a in 0..3 {
            u[2 * a] = 2.0 * P[a][0] + 3.0 * P[a][1];
            u[2 * a + 1] = -P[a][0] + 5.0 * P[a][1];
        }
        let e = t.strain(&u);
        assert!(
            (e[0] - 2.0).abs() < 1e-13 && (e[1] - 5.0).abs() < 1e-13 && (e[2] - 1.0).abs() < 1e-13
        );
        assert!(t.area > 0.0);
    }

    #[test]
    fn stiffness_is_symmetric_and_annihilates_rigid_motions() {
        let t = P1Triangle::new(P);
        let k = t.stiffness(|e| {
            [
                30.0 * (e[0] + e[1]) + 20.0 * e[0],
                30.0 * (e[0] + e[1]) + 20.0 * e[1],
                20.0 * e[2],
            ]
        });
        assert!((k - k.transpose()).abs().max() < 1e-12);
        let rigid = [
            [1.0, 0.0, 1.0, 0.0, 1.0, 0.0],
            [0.0, 1.0, 0.0, 1.0, 0.0, 1.0],
            [-P[0][1], P[0][0], -P[1][1], P[1][0], -P[2][1], P[2][0]],
        ];
        for r in rigid {
            assert!((k * local_vector(&r)).abs().max() < 1e-12);
        }
    }

    #[test]
    fn internal_forces_are_the_stiffness_action() {
        let t = P1Triangle::new(P);
        let c = |e: &Sym2| [3.0 * e[0] + e[1], e[0] + 3.0 * e[1], 2.0 * e[2]];
        let u = [0.1, -0.2, 0.3, 0.05, -0.1, 0.2];
        let f = t.internal_forces(&c(&t.strain(&u)));
        let ku = t.stiffness(c) * local_vector(&u);
        for p in 0..6 {
            assert!((f[p] - ku[p]).abs() < 1e-13);
        }
    }
}
