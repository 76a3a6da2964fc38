//! Error functionals of a plane run against a manufactured solution, accumulated step by step.
//!
//! - `paper_E` = max_n (‖ε(u_n − u(t_n))‖ + ‖ε(w_n − u̇(t_n))‖), the norms |v|_V = ‖ε(v)‖_{L²(Ω)} of
//!   Fernández & Sofonea (2004), Corollary 3.2 (degree-2 rule per triangle: the P1 strain is
//!   constant, so the integrand is smooth to second order).
//! - `energy_final` = ‖ε(u_N − u(T))‖; `l2_final` = ‖u_N − u(T)‖_{L²} (degree-5 rule);
//!   `nodal_max` = max_n max_i |u_n(x_i) − u(x_i, t_n)|.
//! - `time_l2_final` = ‖u_N − u_N^ref‖_{L²} against a midpoint run of the same code on the same mesh
//!   with a much smaller step (set by the study, not by this observer): a diagnostic of the
//!   semi-discrete problem's time error, never gated (the convergence kind refuses gates on it).

use std::collections::BTreeMap;

use contactlab::fem::norms::{l2_errors, strain_errors};
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
        Self {
            exact,
            nodes: nodes.to_vec(),
            triangles: triangles.to_vec(),
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

    /// (‖ε(u_h − u)‖, ‖ε(w_h − u̇)‖) at time t (degree-2 rule).
    fn strain_errors(&self, u: &[f64], w: &[f64], t: f64) -> (f64, f64) {
        let [eu, ew] = strain_errors(&self.nodes, &self.triangles, &self.rule2, [u, w], |x| {
            let j = self.exact.jet(x[0], x[1], t);
            [j.strain(), j.strain_rate()]
        });
        (eu, ew)
    }

    /// ‖u_h − u‖_{L²} at time t (degree-5 rule).
    fn l2(&self, u: &[f64], t: f64) -> f64 {
        let [e] = l2_errors(&self.nodes, &self.triangles, &self.rule5, [u], |x| {
            [self.exact.jet(x[0], x[1], t).u]
        });
        e
    }
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
