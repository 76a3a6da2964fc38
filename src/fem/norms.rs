//! Error norms of a P1 function against a given function, by Gauss quadrature per element
//! (exact when the integrand is a polynomial of degree ≤ 2n − 1 for an n-point rule).

use crate::fem::quadrature::GaussLegendre;
use crate::mesh::interval::IntervalMesh;

/// ‖u_h − u‖_{L²(0,L)} for P1 nodal values `nodal` and a function `u`.
pub fn l2_error(
    mesh: &IntervalMesh,
    quadrature: &GaussLegendre,
    nodal: &[f64],
    u: impl Fn(f64) -> f64,
) -> f64 {
    let mut sum = 0.0;
    for e in 0..mesh.elements() {
        let (a, b) = mesh.element(e);
        let (ua, ub) = (nodal[e], nodal[e + 1]);
        sum += quadrature.integrate(a, b, |x| {
            let s = (x - a) / (b - a);
            let d = (1.0 - s) * ua + s * ub - u(x);
            d * d
        });
    }
    sum.sqrt()
}

/// |u_h − u|_{H¹(0,L)} = ‖(u_h − u)_x‖_{L²} for P1 nodal values and the derivative `u_x`.
pub fn h1_seminorm_error(
    mesh: &IntervalMesh,
    quadrature: &GaussLegendre,
    nodal: &[f64],
    u_x: impl Fn(f64) -> f64,
) -> f64 {
    let mut sum = 0.0;
    for e in 0..mesh.elements() {
        let (a, b) = mesh.element(e);
        let slope = (nodal[e + 1] - nodal[e]) / (b - a);
        sum += quadrature.integrate(a, b, |x| {
            let d = slope - u_x(x);
            d * d
        });
    }
    sum.sqrt()
}

/// max_i |u_h(x_i) − u(x_i)|.
pub fn max_nodal_error(mesh: &IntervalMesh, nodal: &[f64], u: impl Fn(f64) -> f64) -> f64 {
    mesh.nodes()
        .iter()
        .zip(nodal)
        .map(|(&x, &v)| (v - u(x)).abs())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    //! Norms: the interpolant of x² has the known L² and H¹ interpolation errors.
    use super::*;

    #[test]
    fn interpolation_error_of_x_squared() {
        // On one element of length h the interpolation error of x² is s(h − s): L² squared = h⁵/30,
        // H¹ seminorm squared = h³/3 per element.
        let m = 8;
        let mesh = IntervalMesh::uniform(1.0, m).unwrap();
        let q = GaussLegendre::new(3).unwrap();
        let nodal: Vec<f64> = mesh.nodes().iter().map(|x| x * x).collect();
        let h = 1.0 / m as f64;
        let l2 = l2_error(&mesh, &q, &nodal, |x| x * x);
        assert!((l2 - (m as f64 * h.powi(5) / 30.0).sqrt()).abs() < 1e-14);
        let h1 = h1_seminorm_error(&mesh, &q, &nodal, |x| 2.0 * x);
        assert!((h1 - (m as f64 * h.powi(3) / 3.0).sqrt()).abs() < 1e-14);
        assert!(max_nodal_error(&mesh, &nodal, |x| x * x) < 1e-16);
    }
}
