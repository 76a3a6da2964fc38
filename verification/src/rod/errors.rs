//! Error functionals of a rod run against an exact solution, accumulated step by step.
//!
//! - `paper_E` = max_n ( |u_n − u(t_n)|_V + |w_n − u̇(t_n)|_V ), |v|_V = ‖v_x‖_{L²(0,L)}
//!   (Fernández & Sofonea 2004, Corollary 3.2 and §4.1), by Gauss quadrature per element (exact for
//!   the polynomial-in-x solutions of the constant-data family).
//! - `u_nodal_max` = max_n max_i |u_n(x_i) − u(x_i, t_n)|: in 1D the P1 Galerkin solution of this
//!   constant-coefficient operator is nodally exact in space, so this is the time error alone.
//! - `w_nodal_max` = max_n max_i |w_n(x_i) − u̇(x_i, τ_n)| with τ_n the scheme's data time (t_n, or
//!   t_{n−1/2} for the midpoint scheme, whose w_n approximates the midpoint velocity).
//! - `v_nodal_max` = max_n max_i |v_n(x_i) − u̇(x_i, t_n)| for the post-processed velocity v_n.
//! - `u_final_l2` = ‖u_N − u(T)‖_{L²}; `u_final_h1` = |u_N − u(T)|_V.
//! - `end_displacement` = |u_N(L) − u(L, T)|; `contact_stress_max` = max_n |σ_h(L, t_n) − σ(L, t_n)|.

use std::collections::BTreeMap;

use contactlab::fem::quadrature::GaussLegendre;
use contactlab::model::quasistatic::rod_solver::{RodObserver, RodStep};

use crate::exact::{RodExactSolution, RodJet};

/// Names of the rod error functionals, in report order.
pub const ROD_ERRORS: [&str; 8] = [
    "paper_E",
    "u_nodal_max",
    "w_nodal_max",
    "v_nodal_max",
    "u_final_l2",
    "u_final_h1",
    "end_displacement",
    "contact_stress_max",
];

/// Accumulates the error functionals while a rod solver runs.
pub struct RodErrorObserver<'a> {
    exact: &'a dyn RodExactSolution,
    viscosity: f64,
    elasticity: f64,
    quadrature: GaussLegendre,
    paper_e: f64,
    u_nodal: f64,
    w_nodal: f64,
    v_nodal: Option<f64>,
    u_final_l2: f64,
    u_final_h1: f64,
    end_displacement: f64,
    contact_stress: f64,
    final_step: usize,
    /// Quadrature points of the mesh (element-major) and the jet tables of the current step.
    quad_x: Vec<f64>,
    quad_w: Vec<f64>,
    jets_quad: Vec<RodJet>,
    jets_nodes: Vec<RodJet>,
    jets_nodes_tau: Vec<RodJet>,
    /// Per-step (t_n, |u_n − u|_V + |w_n − u̇|_V) when `record_history` is set.
    pub history: Option<Vec<(f64, f64)>>,
    /// The first point where the exact solution was not finite (`f64::max` would drop its NaN
    /// and report a perfect agreement).
    non_finite: Option<String>,
}

impl<'a> RodErrorObserver<'a> {
    /// An observer for a rod with viscosity a and elasticity b (for the exact contact stress), whose
    /// run ends at step `final_step` = N (where the final-time errors are taken).
    pub fn new(
        exact: &'a dyn RodExactSolution,
        viscosity: f64,
        elasticity: f64,
        final_step: usize,
    ) -> Self {
        Self {
            exact,
            viscosity,
            elasticity,
            // 4 points: exact for integrands of degree ≤ 7 in x.
            quadrature: GaussLegendre::new(4).expect("4 Gauss points are valid"),
            paper_e: 0.0,
            u_nodal: 0.0,
            w_nodal: 0.0,
            v_nodal: None,
            u_final_l2: 0.0,
            u_final_h1: 0.0,
            end_displacement: 0.0,
            contact_stress: 0.0,
            final_step,
            quad_x: Vec::new(),
            quad_w: Vec::new(),
            jets_quad: Vec::new(),
            jets_nodes: Vec::new(),
            jets_nodes_tau: Vec::new(),
            history: None,
            non_finite: None,
        }
    }

    /// Also keep the per-step paper error.
    pub fn with_history(mut self) -> Self {
        self.history = Some(Vec::new());
        self
    }

    /// The error functionals, or why they mean nothing: the exact solution not finite somewhere
    /// the run was compared with it, or a functional not finite.
    pub fn checked_errors(&self) -> Result<BTreeMap<String, f64>, String> {
        if let Some(why) = &self.non_finite {
            return Err(why.clone());
        }
        let errors = self.errors();
        match errors.iter().find(|(_, v)| !v.is_finite()) {
            Some((k, v)) => Err(format!(
                "the error functional {k} = {v} against the exact solution {} is not finite",
                self.exact.name()
            )),
            None => Ok(errors),
        }
    }

    /// Records the first jet in `jets` (at the points `xs`, time t) with a non-finite value.
    fn check_jets(&mut self, xs: &[f64], jets: &[RodJet], t: f64) {
        if self.non_finite.is_some() {
            return;
        }
        let finite = |j: &RodJet| {
            [j.u, j.u_x, j.u_t, j.u_xt, j.u_xx, j.u_xxt]
                .iter()
                .all(|v| v.is_finite())
        };
        if let Some((x, j)) = xs.iter().zip(jets).find(|(_, j)| !finite(j)) {
            self.non_finite = Some(format!(
                "the exact solution {} is not finite at t = {t}, x = {x} (u = {}, u_x = {}, u_t = {}): \
                 its formula does not hold for these data, and no error can be measured against it",
                self.exact.name(),
                j.u,
                j.u_x,
                j.u_t
            ));
        }
    }

    /// The error functionals by name (`v_nodal_max` only where v was computed).
    pub fn errors(&self) -> BTreeMap<String, f64> {
        let mut m = BTreeMap::new();
        m.insert("paper_E".to_string(), self.paper_e);
        m.insert("u_nodal_max".to_string(), self.u_nodal);
        m.insert("w_nodal_max".to_string(), self.w_nodal);
        if let Some(v) = self.v_nodal {
            m.insert("v_nodal_max".to_string(), v);
        }
        m.insert("u_final_l2".to_string(), self.u_final_l2);
        m.insert("u_final_h1".to_string(), self.u_final_h1);
        m.insert("end_displacement".to_string(), self.end_displacement);
        m.insert("contact_stress_max".to_string(), self.contact_stress);
        m
    }

    /// Builds the quadrature tables of the mesh on the first step.
    fn prepare(&mut self, nodes: &[f64]) {
        if self.jets_nodes.len() == nodes.len() {
            return;
        }
        let q = self.quadrature.points().len();
        self.quad_x.clear();
        self.quad_w.clear();
        for e in 0..nodes.len() - 1 {
            let (a, b) = (nodes[e], nodes[e + 1]);
            let half = 0.5 * (b - a);
            for (&s, &w) in self
                .quadrature
                .points()
                .iter()
                .zip(self.quadrature.weights())
            {
                self.quad_x.push(0.5 * (a + b) + half * s);
                self.quad_w.push(w * half);
            }
        }
        let zero = RodJet {
            u: 0.0,
            u_x: 0.0,
            u_t: 0.0,
            u_xt: 0.0,
            u_xx: 0.0,
            u_xxt: 0.0,
        };
        self.jets_quad = vec![zero; self.quad_x.len()];
        self.jets_nodes = vec![zero; nodes.len()];
        self.jets_nodes_tau = vec![zero; nodes.len()];
        debug_assert_eq!(self.quad_x.len(), q * (nodes.len() - 1));
    }

    /// (Σ_e ∫ (slope_e − g)² dx)^{1/2} for nodal values `v` and the exact derivative g selected by
    /// `pick` from the quadrature jets of the current step.
    fn seminorm(&self, nodes: &[f64], v: &[f64], pick: fn(&RodJet) -> f64) -> f64 {
        let q = self.quadrature.points().len();
        let mut sum = 0.0;
        for e in 0..nodes.len() - 1 {
            let slope = (v[e + 1] - v[e]) / (nodes[e + 1] - nodes[e]);
            for j in e * q..(e + 1) * q {
                let d = slope - pick(&self.jets_quad[j]);
                sum += self.quad_w[j] * d * d;
            }
        }
        sum.sqrt()
    }

    /// ‖v_h − u‖_{L²} from the quadrature jets of the current step.
    fn l2(&self, nodes: &[f64], v: &[f64]) -> f64 {
        let q = self.quadrature.points().len();
        let mut sum = 0.0;
        for e in 0..nodes.len() - 1 {
            let (a, b) = (nodes[e], nodes[e + 1]);
            for j in e * q..(e + 1) * q {
                let s = (self.quad_x[j] - a) / (b - a);
                let d = (1.0 - s) * v[e] + s * v[e + 1] - self.jets_quad[j].u;
                sum += self.quad_w[j] * d * d;
            }
        }
        sum.sqrt()
    }
}

impl RodObserver for RodErrorObserver<'_> {
    fn observe(&mut self, step: &RodStep<'_>) {
        let nodes = step.nodes;
        let m = nodes.len() - 1;
        let t = step.t;
        self.prepare(nodes);
        self.exact.jets_at_time(nodes, t, &mut self.jets_nodes);
        let jets = std::mem::take(&mut self.jets_nodes);
        self.check_jets(nodes, &jets, t);
        self.jets_nodes = jets;
        let jl = self.jets_nodes[m];
        let sigma = self.viscosity * jl.u_xt + self.elasticity * jl.u_x;
        self.contact_stress = self.contact_stress.max((step.contact_stress - sigma).abs());
        for (u, j) in step.u.iter().zip(&self.jets_nodes) {
            self.u_nodal = self.u_nodal.max((u - j.u).abs());
        }
        if let (Some(v), true) = (step.v, step.n > 0) {
            let mut worst = self.v_nodal.unwrap_or(0.0);
            for (v, j) in v.iter().zip(&self.jets_nodes) {
                worst = worst.max((v - j.u_t).abs());
            }
            self.v_nodal = Some(worst);
        }
        let Some(w) = step.w else {
            return;
        };
        let tau = step.data_time;
        let at_tau = if tau == t {
            &self.jets_nodes
        } else {
            self.exact
                .jets_at_time(nodes, tau, &mut self.jets_nodes_tau);
            &self.jets_nodes_tau
        };
        for (w, j) in w.iter().zip(at_tau) {
            self.w_nodal = self.w_nodal.max((w - j.u_t).abs());
        }
        self.exact
            .jets_at_time(&self.quad_x, t, &mut self.jets_quad);
        let (xs, jets) = (
            std::mem::take(&mut self.quad_x),
            std::mem::take(&mut self.jets_quad),
        );
        self.check_jets(&xs, &jets, t);
        (self.quad_x, self.jets_quad) = (xs, jets);
        let eu = self.seminorm(nodes, step.u, |j| j.u_x);
        let ew = self.seminorm(nodes, w, |j| j.u_xt);
        self.paper_e = self.paper_e.max(eu + ew);
        if let Some(h) = &mut self.history {
            h.push((t, eu + ew));
        }
        if step.n == self.final_step {
            self.u_final_h1 = eu;
            self.u_final_l2 = self.l2(nodes, step.u);
            self.end_displacement = (step.u[m] - jl.u).abs();
        }
    }
}
