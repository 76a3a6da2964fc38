//! P1 (piecewise-linear) elements on an interval mesh: stiffness, load vectors, evaluation.
//!
//! Unknowns are the nodal values at x_1, …, x_M (x_0 = 0 is clamped), so vectors passed here
//! hold all M + 1 nodal values and index 0 is the clamped node.

use crate::fem::quadrature::GaussLegendre;
use crate::mesh::interval::IntervalMesh;

/// The stiffness matrix K_ij = ∫_0^L φ_i' φ_j' dx on the free nodes 1..M, as a symmetric
/// tridiagonal (diagonal, off-diagonal): K_ii = 1/h_i + 1/h_{i+1} (1/h_M at x_M),
/// K_{i,i+1} = −1/h_{i+1}. Index j of the output is node j + 1.
pub fn stiffness_tridiagonal(mesh: &IntervalMesh) -> (Vec<f64>, Vec<f64>) {
    let m = mesh.elements();
    let mut diag = vec![0.0; m];
    let mut off = vec![0.0; m.saturating_sub(1)];
    for e in 0..m {
        let (a, b) = mesh.element(e);
        let s = 1.0 / (b - a);
        // element e joins nodes e and e + 1, i.e. unknowns e − 1 and e
        if e >= 1 {
            diag[e - 1] += s;
            off[e - 1] -= s;
        }
        diag[e] += s;
    }
    (diag, off)
}

/// F_i = ∫_0^L f φ_i dx for all nodes 0..M, written into `out` (length M + 1).
pub fn load_vector_into(
    mesh: &IntervalMesh,
    quadrature: &GaussLegendre,
    f: impl Fn(f64) -> f64,
    out: &mut [f64],
) {
    out.iter_mut().for_each(|v| *v = 0.0);
    for e in 0..mesh.elements() {
        let (a, b) = mesh.element(e);
        let h = b - a;
        let mut left = 0.0;
        let mut right = 0.0;
        let half = 0.5 * h;
        for (&s, &w) in quadrature.points().iter().zip(quadrature.weights()) {
            let lambda = 0.5 * (1.0 + s);
            let fx = f(a + h * lambda) * w * half;
            left += fx * (1.0 - lambda);
            right += fx * lambda;
        }
        out[e] += left;
        out[e + 1] += right;
    }
}

/// The load vector of a constant f: F_i = f (h_i + h_{i+1}) / 2, exact.
pub fn constant_load_vector_into(mesh: &IntervalMesh, f: f64, out: &mut [f64]) {
    out.iter_mut().for_each(|v| *v = 0.0);
    for e in 0..mesh.elements() {
        let (a, b) = mesh.element(e);
        let half = 0.5 * f * (b - a);
        out[e] += half;
        out[e + 1] += half;
    }
}

/// The P1 function with nodal values `nodal` evaluated at x ∈ [0, L] (`None` outside).
pub fn evaluate(mesh: &IntervalMesh, nodal: &[f64], x: f64) -> Option<f64> {
    let e = mesh.locate(x)?;
    let (a, b) = mesh.element(e);
    let s = (x - a) / (b - a);
    Some((1.0 - s) * nodal[e] + s * nodal[e + 1])
}

#[cfg(test)]
mod tests {
    //! P1 on intervals: the stiffness reproduces −v'' for v(x) = x (K z = e_M), loads are exact for
    //! polynomials up to the rule's degree, and evaluation interpolates.
    use super::*;

    #[test]
    fn stiffness_times_identity_function_is_unit_flux_at_the_end() {
        let mesh =
            IntervalMesh::graded(1.0, 7, 1.7, crate::mesh::interval::GradingEnd::End).unwrap();
        let (d, o) = stiffness_tridiagonal(&mesh);
        let x = &mesh.nodes()[1..];
        let m = x.len();
        for i in 0..m {
            let mut kx = d[i] * x[i];
            if i > 0 {
                kx += o[i - 1] * x[i - 1];
            }
            if i + 1 < m {
                kx += o[i] * x[i + 1];
            }
            let expected = if i + 1 == m { 1.0 } else { 0.0 };
            assert!((kx - expected).abs() < 1e-12, "row {i}: {kx}");
        }
    }

    #[test]
    fn load_of_quadratic_is_exact_with_two_points() {
        let mesh = IntervalMesh::uniform(1.0, 4).unwrap();
        let q = GaussLegendre::new(2).unwrap();
        let mut out = vec![0.0; 5];
        load_vector_into(&mesh, &q, |x| x * x, &mut out);
        // sum of F_i = ∫ f = 1/3 ; sum x_i F_i = ∫ x f = 1/4 (P1 reproduces 1 and x)
        assert!((out.iter().sum::<f64>() - 1.0 / 3.0).abs() < 1e-15);
        let first: f64 = out.iter().zip(mesh.nodes()).map(|(f, x)| f * x).sum();
        assert!((first - 0.25).abs() < 1e-15);
    }

    #[test]
    fn constant_load_matches_quadrature() {
        let mesh =
            IntervalMesh::graded(2.0, 5, 2.0, crate::mesh::interval::GradingEnd::Start).unwrap();
        let q = GaussLegendre::new(1).unwrap();
        let mut a = vec![0.0; 6];
        let mut b = vec![0.0; 6];
        load_vector_into(&mesh, &q, |_| 3.0, &mut a);
        constant_load_vector_into(&mesh, 3.0, &mut b);
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-14);
        }
    }

    #[test]
    fn evaluate_interpolates_linearly() {
        let mesh = IntervalMesh::uniform(1.0, 2).unwrap();
        assert_eq!(evaluate(&mesh, &[0.0, 1.0, 3.0], 0.75), Some(2.0));
        assert_eq!(evaluate(&mesh, &[0.0, 1.0, 3.0], 1.0), Some(3.0));
        assert_eq!(evaluate(&mesh, &[0.0, 1.0, 3.0], -0.1), None);
    }
}
