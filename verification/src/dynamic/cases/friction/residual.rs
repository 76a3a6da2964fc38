//! The check of each step's equations with the contact laws written in the verification crate:
//! the residual of BDS (1.36) with the normal force of (1.8)/(1.46) and the Coulomb force of
//! (1.38) with μ of (1.13) ([`crate::exact::coulomb_friction`]), at the solver's states, for a
//! small-strain (linear) body.
//!
//! For a midpoint-type scheme (docs/dynamic.md §2; the midpoint rule and Gonzalez's scheme
//! coincide on a linear body), with d = u_n − u_{n−1} = k (δu_n + δu_{n−1})/2,
//!
//!   R = M (δu_n − δu_{n−1})/k + K (u_{n−1} + d/2) − f(t_{n−1/2}) − ξ_ν − ξ_τ;
//!
//! on contact node i (weight w_i, penetrations q = p_{n−1}, p = p_n) ξ_ν = w_i N(q, p) along the
//! foundation's normal and, if the node slips (d_τ ≠ 0), ξ_τ = −w_i μ(p) N(q, p) sign(d_τ) — the
//! friction at t_n with the backward-difference slip rate. A node that sticks has d_τ = 0 (the
//! solver prescribes it, up to the round-off of the elimination: |d_τ| ≤ 64 ε |u_τ| counts as
//! stuck) and an unknown reaction T = (R without ξ_τ)/w_i, which must lie within the bound
//! μ(p) N. (A node that slides less than that would be taken as stuck, and its friction, at
//! the bound, passes the bound check: the classification cannot hide a wrong force.)
//!
//! **What the check may demand.** The semismooth Newton method stops when ‖R‖_∞ ≤ τ s over the
//! rows it does not eliminate (`src/model/dynamic/newton.rs`), s the largest term of the step
//! equation; on the full solver path (the runs force it) for a linear body
//!
//!   s = max(‖(αM + θK) d‖_∞, ‖α k M δu_{n−1} + f − K u_{n−1}‖_∞, max_i w_i N_i)
//!
//! (α = 2/k², θ = 1/2), which this module computes the same way. The solver evaluates R in
//! floating point and so does this module: each row is a sum whose rounding is at most a small
//! multiple of ε times the sum of the magnitudes of its terms,
//!
//!   A_i = Σ_j |K_ij| (|u_{n−1,j}| + |d_j|) + α Σ_j |M_ij| (|d_j| + k |δu_{n−1,j}|) + |f_i| + w_i N_i,
//!
//! which can far exceed s: K applied to the block's sliding (a rigid translation, which K maps to
//! zero) cancels only up to ε Σ |K_ij| |u_j|. The bound per row is |R_i| ≤ τ s + 64 ε A_i (64
//! covers the dozen-odd terms per row in both evaluations), and a sticking node's reaction may
//! exceed its bound by 64 ε A_i / w_i. With the laws right the check passes at every step; a wrong
//! coefficient, direction, time level or factor of the friction leaves a residual of the size of
//! the friction force.

use contactlab::model::dynamic::body::{stiffness_at_rest, ElasticBody};
use contactlab::model::dynamic::contact_model::ContactModel;
use contactlab::model::dynamic::plane_body::PlaneBody;

use crate::exact::coulomb_friction::{Compliance, Coulomb};

/// The round-off allowance of a row, in units of ε A_i.
pub const ROUND_OFF_TERMS: f64 = 64.0;

/// The check of one step.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StepCheck {
    /// max over the rows the solver does not eliminate of |R_i| / (τ s + 64 ε A_i) (≤ 1).
    pub residual: f64,
    /// max over sticking nodes of (|T_i| − μ N_i) w_i / (64 ε A_i) (≤ 1); None when no node
    /// sticks.
    pub stick_excess: Option<f64>,
    /// τ s + 64 ε A_i per row: what each row may leave.
    pub allowance: Vec<f64>,
    /// Whether every contact node is penetrated and slips forward (d_τ > 0).
    pub all_slide_forward: bool,
}

/// The step equations of a run with the reference laws.
pub struct StepEquations<'a> {
    body: &'a PlaneBody,
    contact: &'a ContactModel,
    coulomb: Coulomb,
    compliance: Compliance,
    k: f64,
    tolerance: f64,
    /// K and |K| on the body's pattern.
    stiffness: Vec<f64>,
    stiffness_abs: Vec<f64>,
    mass_abs: Vec<f64>,
}

/// y = A x on `body`'s pattern.
fn mul(body: &PlaneBody, a: &[f64], x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; x.len()];
    body.pattern().symmetric_mul(a, x, &mut y);
    y
}

fn abs(v: &[f64]) -> Vec<f64> {
    v.iter().map(|x| x.abs()).collect()
}

impl<'a> StepEquations<'a> {
    /// The equations of the linear `body` with `contact`, step k, Newton tolerance τ and the
    /// reference laws; None for a body that is not linear.
    pub fn new(
        body: &'a PlaneBody,
        contact: &'a ContactModel,
        (coulomb, compliance): (Coulomb, Compliance),
        k: f64,
        tolerance: f64,
    ) -> Option<Self> {
        if !body.is_linear() {
            return None;
        }
        let stiffness = stiffness_at_rest(body);
        Some(Self {
            body,
            contact,
            coulomb,
            compliance,
            k,
            tolerance,
            stiffness_abs: abs(&stiffness),
            stiffness,
            mass_abs: abs(body.mass()),
        })
    }

    /// Checks step n from (u_{n−1}, δu_{n−1}) to δu_n at time t_n.
    pub fn check(&self, t: f64, (u0, v0): (&[f64], &[f64]), v1: &[f64]) -> StepCheck {
        let (k, body) = (self.k, self.body);
        let n = body.dofs();
        let alpha = 2.0 / (k * k);
        let d: Vec<f64> = (0..n).map(|i| 0.5 * k * (v1[i] + v0[i])).collect();
        let dv: Vec<f64> = (0..n).map(|i| (v1[i] - v0[i]) / k).collect();
        let mid: Vec<f64> = (0..n).map(|i| u0[i] + 0.5 * d[i]).collect();
        let mut f = vec![0.0; n];
        body.load_into(t - 0.5 * k, &mut f);
        let inertia = mul(body, body.mass(), &dv);
        let internal = mul(body, &self.stiffness, &mid);
        let mut r: Vec<f64> = (0..n).map(|i| inertia[i] + internal[i] - f[i]).collect();
        // the solver's scale s
        let (md, kd, ku, mv) = (
            mul(body, body.mass(), &d),
            mul(body, &self.stiffness, &d),
            mul(body, &self.stiffness, u0),
            mul(body, body.mass(), v0),
        );
        let mut scale = (0..n).fold(0.0f64, |s, i| {
            s.max((alpha * md[i] + 0.5 * kd[i]).abs())
                .max((alpha * k * mv[i] + f[i] - ku[i]).abs())
        });
        // the magnitudes of the terms of each row
        let (u_abs, d_abs) = (abs(u0), abs(&d));
        let kterms = mul(
            body,
            &self.stiffness_abs,
            &(0..n).map(|i| u_abs[i] + d_abs[i]).collect::<Vec<_>>(),
        );
        let mterms = mul(
            body,
            &self.mass_abs,
            &(0..n)
                .map(|i| d_abs[i] + k * v0[i].abs())
                .collect::<Vec<_>>(),
        );
        let mut terms: Vec<f64> = (0..n)
            .map(|i| kterms[i] + alpha * mterms[i] + f[i].abs())
            .collect();
        // contact forces with the reference laws
        let u1: Vec<f64> = (0..n).map(|i| u0[i] + d[i]).collect();
        let mut eliminated = vec![false; n];
        let mut sticking = Vec::new();
        let mut all_forward = true;
        for nd in &self.contact.nodes {
            let penetration = |u: &[f64]| nd.offset + nd.sign * u[nd.normal_dof];
            let (q, p) = (penetration(u0), penetration(&u1));
            let normal = self.compliance.force(q, p);
            let w = nd.weight;
            scale = scale.max((w * normal).abs());
            r[nd.normal_dof] += nd.sign * w * normal;
            terms[nd.normal_dof] += (w * normal).abs();
            let Some(td) = nd.tangent_dof else {
                continue;
            };
            let bound = self.coulomb.mu(p) * normal;
            terms[td] += w * bound;
            let slip = d[td];
            // a sticking node's increment is the round-off of the prescribed d_τ = 0
            let stuck = slip.abs() <= ROUND_OFF_TERMS * f64::EPSILON * u0[td].abs();
            all_forward &= p > 0.0 && slip > 0.0 && !stuck;
            if stuck {
                eliminated[td] = true;
                sticking.push((td, w, bound));
            } else {
                r[td] += w * bound * slip.signum();
            }
        }
        let allowance: Vec<f64> = terms
            .iter()
            .map(|a| self.tolerance * scale + ROUND_OFF_TERMS * f64::EPSILON * a)
            .collect();
        let residual = (0..n)
            .filter(|&i| !eliminated[i])
            .map(|i| r[i].abs() / allowance[i])
            .fold(0.0, f64::max);
        let stick_excess = sticking
            .iter()
            .map(|&(td, w, bound)| {
                ((r[td] / w).abs() - bound) * w / (ROUND_OFF_TERMS * f64::EPSILON * terms[td])
            })
            .reduce(f64::max);
        StepCheck {
            residual,
            stick_excess,
            allowance,
            all_slide_forward: all_forward,
        }
    }
}
