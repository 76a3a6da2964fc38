//! Error norms of P1 functions against given functions, by quadrature per element.
//!
//! - On an interval mesh: ‖u_h − u‖_{L²}, |u_h − u|_{H¹} and the nodal maximum, by an n-point
//!   Gauss rule (exact when the integrand is a polynomial of degree ≤ 2n − 1).
//! - On a triangle mesh, for P1 vector fields stored as interleaved nodal values (u_x, u_y per
//!   node): the energy-type norm ‖ε(u_h) − ε‖_{L²(Ω)} = (Σ_T ∫_T (ε_h − ε) : (ε_h − ε))^{1/2}
//!   with ε(v) = ½(∇v + ∇vᵀ) ([`strain_errors`]), ‖u_h − u‖_{L²(Ω)} ([`l2_errors`]), both for
//!   several fields in one pass (one evaluation of the exact solution per quadrature point), and
//!   ‖a_h − b_h‖_{L²(Ω)} of two P1 fields, exactly ([`l2_difference`]).

use crate::fem::quadrature::GaussLegendre;
use crate::fem::triangle_p1::{contract, P1Triangle, Sym2};
use crate::fem::triangle_quadrature::TriangleRule;
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

/// The six local values (u_x, u_y at the three vertices) of an interleaved P1 vector field.
fn local(v: &[f64], t: &[usize; 3]) -> [f64; 6] {
    std::array::from_fn(|p| v[2 * t[p / 2] + p % 2])
}

/// ‖ε(u_h^{(i)}) − ε_i‖_{L²(Ω)} for K P1 vector fields `fields[i]` on the mesh (nodes, triangles)
/// against exact strains: `exact(x)` returns [ε_1(x), …, ε_K(x)] (Voigt: xx, yy, xy). The P1
/// strain is constant per triangle; `rule` integrates the square of the difference.
pub fn strain_errors<const K: usize>(
    nodes: &[[f64; 2]],
    triangles: &[[usize; 3]],
    rule: &TriangleRule,
    fields: [&[f64]; K],
    mut exact: impl FnMut([f64; 2]) -> [Sym2; K],
) -> [f64; K] {
    let mut sums = [0.0; K];
    for tri in triangles {
        let p = [nodes[tri[0]], nodes[tri[1]], nodes[tri[2]]];
        let el = P1Triangle::new(p);
        let strains: [Sym2; K] = std::array::from_fn(|i| el.strain(&local(fields[i], tri)));
        for (l, wq) in rule.points.iter().zip(&rule.weights) {
            let e = exact(P1Triangle::point(&p, l));
            for i in 0..K {
                let d: Sym2 = [
                    strains[i][0] - e[i][0],
                    strains[i][1] - e[i][1],
                    strains[i][2] - e[i][2],
                ];
                sums[i] += wq * el.area * contract(&d, &d);
            }
        }
    }
    sums.map(f64::sqrt)
}

/// ‖u_h^{(i)} − u_i‖_{L²(Ω)} for K P1 vector fields against exact fields: `exact(x)` returns
/// [u_1(x), …, u_K(x)]; `rule` integrates the square of the difference.
pub fn l2_errors<const K: usize>(
    nodes: &[[f64; 2]],
    triangles: &[[usize; 3]],
    rule: &TriangleRule,
    fields: [&[f64]; K],
    mut exact: impl FnMut([f64; 2]) -> [[f64; 2]; K],
) -> [f64; K] {
    let mut sums = [0.0; K];
    for tri in triangles {
        let p = [nodes[tri[0]], nodes[tri[1]], nodes[tri[2]]];
        let area = P1Triangle::new(p).area;
        for (l, wq) in rule.points.iter().zip(&rule.weights) {
            let e = exact(P1Triangle::point(&p, l));
            for i in 0..K {
                let u = fields[i];
                for c in 0..2 {
                    let uh = l[0] * u[2 * tri[0] + c]
                        + l[1] * u[2 * tri[1] + c]
                        + l[2] * u[2 * tri[2] + c];
                    sums[i] += wq * area * (uh - e[i][c]).powi(2);
                }
            }
        }
    }
    sums.map(f64::sqrt)
}

/// ‖a_h − b_h‖_{L²(Ω)} for two P1 vector fields on the same mesh, exactly: the integrand is
/// quadratic on each triangle, and the edge-midpoint rule (weights |T|/3) is exact for quadratics.
pub fn l2_difference(nodes: &[[f64; 2]], triangles: &[[usize; 3]], a: &[f64], b: &[f64]) -> f64 {
    let mut s = 0.0;
    for tri in triangles {
        let p = [nodes[tri[0]], nodes[tri[1]], nodes[tri[2]]];
        let area = 0.5
            * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]));
        for (i, j) in [(0, 1), (1, 2), (2, 0)] {
            for c in 0..2 {
                let d = 0.5
                    * ((a[2 * tri[i] + c] - b[2 * tri[i] + c])
                        + (a[2 * tri[j] + c] - b[2 * tri[j] + c]));
                s += area / 3.0 * d * d;
            }
        }
    }
    s.sqrt()
}

#[cfg(test)]
mod tests {
    //! Norms against closed-form integrals: the interpolant of x² on an interval (known L² and H¹
    //! interpolation errors); on the unit square, a linear field (exact strain, zero error), the
    //! field (x², 0) whose interpolation errors are known integrals, and the difference of two P1
    //! fields against its exact value.
    use super::*;
    use crate::mesh::triangle::{Diagonal, TriangleMesh};

    fn unit_square(n: usize) -> TriangleMesh {
        TriangleMesh::rectangle([0.0, 0.0], [1.0, 1.0], [n, n], Diagonal::Up).expect("mesh")
    }

    fn interleaved(mesh: &TriangleMesh, f: impl Fn([f64; 2]) -> [f64; 2]) -> Vec<f64> {
        mesh.nodes().iter().flat_map(|&x| f(x)).collect()
    }

    #[test]
    fn a_linear_field_has_no_strain_or_l2_error() {
        let mesh = unit_square(4);
        let rule = TriangleRule::of_degree(2).expect("rule");
        let f = |x: [f64; 2]| [1.0 + 2.0 * x[0] - x[1], 0.5 * x[0] + 3.0 * x[1]];
        let u = interleaved(&mesh, f);
        // ε = [∂x u_x, ∂y u_y, ½(∂y u_x + ∂x u_y)] = [2, 3, −0.25]
        let [e] = strain_errors(mesh.nodes(), mesh.triangles(), &rule, [&u], |_| {
            [[2.0, 3.0, -0.25]]
        });
        let [l] = l2_errors(mesh.nodes(), mesh.triangles(), &rule, [&u], |x| [f(x)]);
        assert!(e < 1e-13 && l < 1e-14, "{e} {l}");
    }

    #[test]
    fn the_strain_error_of_the_interpolant_of_x_squared_is_the_known_integral() {
        // u = (x², 0): ε_xx = 2x; the P1 interpolant on the uniform grid with spacing h has on each
        // triangle a constant ε_xx equal to the difference quotient (x_{i+1}² − x_i²)/h = 2x̄ over the
        // column [x_i, x_{i+1}], so ‖ε_h − ε‖² = Σ_columns ∫ (2x − 2x̄)² = 4 · h²/12 (area 1).
        let n = 8;
        let mesh = unit_square(n);
        let rule = TriangleRule::of_degree(2).expect("rule");
        let u = interleaved(&mesh, |x| [x[0] * x[0], 0.0]);
        let [e] = strain_errors(mesh.nodes(), mesh.triangles(), &rule, [&u], |x| {
            [[2.0 * x[0], 0.0, 0.0]]
        });
        let h = 1.0 / n as f64;
        assert!((e - (4.0 * h * h / 12.0f64).sqrt()).abs() < 1e-14, "{e}");
    }

    #[test]
    fn two_fields_at_once_equal_one_at_a_time_and_the_difference_is_exact() {
        let mesh = unit_square(6);
        let rule = TriangleRule::of_degree(5).expect("rule");
        let a = interleaved(&mesh, |x| [x[0] * x[1], x[0].sin()]);
        let b = interleaved(&mesh, |x| [x[1], 0.0]);
        let exact = |x: [f64; 2]| [x[0] * x[1], x[0].sin()];
        let both = l2_errors(mesh.nodes(), mesh.triangles(), &rule, [&a, &b], |x| {
            [exact(x), exact(x)]
        });
        let [one] = l2_errors(mesh.nodes(), mesh.triangles(), &rule, [&a], |x| [exact(x)]);
        assert_eq!(both[0].to_bits(), one.to_bits());
        // a − b with b = (y, 0) and a = I_h(x y, sin x): the difference of two P1 fields equals
        // the degree-5 quadrature of the same P1 difference (both exact for the quadratic integrand).
        let d = l2_difference(mesh.nodes(), mesh.triangles(), &a, &b);
        let zero = vec![0.0; a.len()];
        let diff: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x - y).collect();
        let q = l2_difference(mesh.nodes(), mesh.triangles(), &diff, &zero);
        assert!((d - q).abs() < 1e-15 * d.max(1.0));
        let [r] = l2_errors(mesh.nodes(), mesh.triangles(), &rule, [&diff], |_| {
            [[0.0, 0.0]]
        });
        assert!((d - r).abs() < 1e-14 * d.max(1.0), "{d} {r}");
    }

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
