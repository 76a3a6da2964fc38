//! Error functionals of a plane run against a manufactured solution, accumulated step by step.
//!
//! - `paper_E` = max_n (‖ε(u_n − u(t_n))‖ + ‖ε(w_n − u̇(t_n))‖), the norms |v|_V = ‖ε(v)‖_{L²(Ω)} of
//!   Fernández & Sofonea (2004), Corollary 3.2 (degree-2 rule per triangle: the P1 strain is
//!   constant, so the integrand is smooth to second order).
//! - `energy_final` = ‖ε(u_N − u(T))‖; `l2_final` = ‖u_N − u(T)‖_{L²} (degree-5 rule);
//!   `nodal_max` = max_n max_i |u_n(x_i) − u(x_i, t_n)|.
//! - `time_l2_final` = ‖u_N − u_N^ref‖_{L²}: the time error alone, against a run on the same mesh
//!   with a much smaller step (set by the study, not by this observer).

use std::collections::BTreeMap;

use contactlab::fem::triangle_p1::{contract, P1Triangle, Sym2};
use contactlab::fem::triangle_quadrature::TriangleRule;
use contactlab::model::quasistatic::plane_solver::{PlaneObserver, PlaneStep};

use crate::manufactured::plane::PlaneManufactured;

/// Names of the plane error functionals.
pub const PLANE_ERRORS: [&str; 5] = [
    "paper_E",
    "energy_final",
    "l2_final",
    "nodal_max",
    "time_l2_final",
];

/// Accumulates the plane error functionals.
pub struct PlaneErrorObserver<'a> {
    exact: &'a PlaneManufactured,
    nodes: Vec<[f64; 2]>,
    triangles: Vec<[usize; 3]>,
    elements: Vec<P1Triangle>,
    rule2: TriangleRule,
    rule5: TriangleRule,
    final_step: usize,
    paper_e: f64,
    nodal: f64,
    energy_final: f64,
    l2_final: f64,
    /// u_N (for time errors against a reference).
    pub final_u: Vec<f64>,
}

impl<'a> PlaneErrorObserver<'a> {
    /// An observer for the mesh (nodes, triangles) of a run ending at step `final_step`.
    pub fn new(
        exact: &'a PlaneManufactured,
        nodes: &[[f64; 2]],
        triangles: &[[usize; 3]],
        final_step: usize,
    ) -> Self {
        let elements = triangles
            .iter()
            .map(|t| P1Triangle::new([nodes[t[0]], nodes[t[1]], nodes[t[2]]]))
            .collect();
        Self {
            exact,
            nodes: nodes.to_vec(),
            triangles: triangles.to_vec(),
            elements,
            rule2: TriangleRule::of_degree(2).expect("degree 2 exists"),
            rule5: TriangleRule::of_degree(5).expect("degree 5 exists"),
            final_step,
            paper_e: 0.0,
            nodal: 0.0,
            energy_final: 0.0,
            l2_final: 0.0,
            final_u: Vec::new(),
        }
    }

    /// The error functionals by name (without the time error, which the study adds).
    pub fn errors(&self) -> BTreeMap<String, f64> {
        let mut m = BTreeMap::new();
        m.insert("paper_E".into(), self.paper_e);
        m.insert("energy_final".into(), self.energy_final);
        m.insert("l2_final".into(), self.l2_final);
        m.insert("nodal_max".into(), self.nodal);
        m
    }

    fn local(v: &[f64], t: &[usize; 3]) -> [f64; 6] {
        std::array::from_fn(|p| v[2 * t[p / 2] + p % 2])
    }

    /// (‖ε(u_h − u)‖, ‖ε(w_h − u̇)‖) at time t.
    fn strain_errors(&self, u: &[f64], w: &[f64], t: f64) -> (f64, f64) {
        let (mut eu, mut ew) = (0.0, 0.0);
        for (tri, el) in self.triangles.iter().zip(&self.elements) {
            let p = [self.nodes[tri[0]], self.nodes[tri[1]], self.nodes[tri[2]]];
            let (su, sw) = (
                el.strain(&Self::local(u, tri)),
                el.strain(&Self::local(w, tri)),
            );
            for (l, wq) in self.rule2.points.iter().zip(&self.rule2.weights) {
                let x = P1Triangle::point(&p, l);
                let j = self.exact.jet(x[0], x[1], t);
                let du: Sym2 = sub(&su, &j.strain());
                let dw: Sym2 = sub(&sw, &j.strain_rate());
                eu += wq * el.area * contract(&du, &du);
                ew += wq * el.area * contract(&dw, &dw);
            }
        }
        (eu.sqrt(), ew.sqrt())
    }

    fn l2(&self, u: &[f64], t: f64) -> f64 {
        let mut s = 0.0;
        for (tri, el) in self.triangles.iter().zip(&self.elements) {
            let p = [self.nodes[tri[0]], self.nodes[tri[1]], self.nodes[tri[2]]];
            for (l, wq) in self.rule5.points.iter().zip(&self.rule5.weights) {
                let x = P1Triangle::point(&p, l);
                let j = self.exact.jet(x[0], x[1], t);
                for c in 0..2 {
                    let uh = l[0] * u[2 * tri[0] + c]
                        + l[1] * u[2 * tri[1] + c]
                        + l[2] * u[2 * tri[2] + c];
                    s += wq * el.area * (uh - j.u[c]).powi(2);
                }
            }
        }
        s.sqrt()
    }
}

fn sub(a: &Sym2, b: &Sym2) -> Sym2 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

impl PlaneObserver for PlaneErrorObserver<'_> {
    fn observe(&mut self, step: &PlaneStep<'_>) {
        for (i, x) in self.nodes.iter().enumerate() {
            let j = self.exact.jet(x[0], x[1], step.t);
            let e =
                ((step.u[2 * i] - j.u[0]).powi(2) + (step.u[2 * i + 1] - j.u[1]).powi(2)).sqrt();
            self.nodal = self.nodal.max(e);
        }
        if let Some(w) = step.w {
            let (eu, ew) = self.strain_errors(step.u, w, step.t);
            self.paper_e = self.paper_e.max(eu + ew);
            if step.n == self.final_step {
                self.energy_final = eu;
                self.l2_final = self.l2(step.u, step.t);
                self.final_u = step.u.to_vec();
            }
        }
    }
}

/// ‖a − b‖_{L²} for two P1 fields on the same mesh (degree-2 rule: exact for the quadratic
/// integrand).
pub fn l2_difference(nodes: &[[f64; 2]], triangles: &[[usize; 3]], a: &[f64], b: &[f64]) -> f64 {
    let mut s = 0.0;
    for tri in triangles {
        let p = [nodes[tri[0]], nodes[tri[1]], nodes[tri[2]]];
        let area = 0.5
            * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]));
        // edge-midpoint rule, exact for quadratics
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
