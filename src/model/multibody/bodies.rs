//! Several plane-strain bodies as one system: their free dofs stacked into one vector
//! U = (U¹, U², …), their reference node positions, and the body-wise operations the step needs.
//!
//! Each body is a [`PlaneBody`] (P1 triangles, its own law, density, supports and loads); the
//! system's mass and stiffness are block diagonal, so the bodies are coupled only by their contact
//! constraints. A node's current position is x = X + u (X the mesh node, which already carries
//! the body's placement).

use std::sync::Arc;

use crate::error::InputError;
use crate::model::dynamic::body::ElasticBody;
use crate::model::dynamic::plane_body::PlaneBody;

/// The bodies and their dof offsets.
#[derive(Debug, Clone)]
pub struct BodySet {
    bodies: Vec<Arc<PlaneBody>>,
    /// offsets[b]: the index of body b's first free dof in U; offsets[len] = the total.
    offsets: Vec<usize>,
}

impl BodySet {
    /// Stacks the bodies (at least one).
    pub fn new(bodies: Vec<Arc<PlaneBody>>) -> Result<Self, InputError> {
        if bodies.is_empty() {
            return Err(InputError::new("body", "(none)", "at least one [[body]]"));
        }
        let mut offsets = vec![0];
        for b in &bodies {
            offsets.push(offsets[offsets.len() - 1] + b.dofs());
        }
        Ok(Self { bodies, offsets })
    }

    /// The number of bodies.
    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    /// Whether there is no body (never: [`Self::new`] refuses it).
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// Body `b`.
    pub fn body(&self, b: usize) -> &Arc<PlaneBody> {
        &self.bodies[b]
    }

    /// All bodies.
    pub fn bodies(&self) -> &[Arc<PlaneBody>] {
        &self.bodies
    }

    /// The number of free dofs of the system.
    pub fn dofs(&self) -> usize {
        self.offsets[self.bodies.len()]
    }

    /// The range of body b's dofs in U.
    pub fn range(&self, b: usize) -> std::ops::Range<usize> {
        self.offsets[b]..self.offsets[b + 1]
    }

    /// The global free dof of component `c` of node `node` of body `b` (None where held).
    pub fn dof(&self, b: usize, node: usize, c: usize) -> Option<usize> {
        self.bodies[b].dof(node, c).map(|d| d + self.offsets[b])
    }

    /// The reference position X of node `node` of body `b`.
    pub fn reference(&self, b: usize, node: usize) -> [f64; 2] {
        self.bodies[b].data().mesh.nodes()[node]
    }

    /// The current position X + u of a node, u read from the system vector `u`.
    pub fn position(&self, b: usize, node: usize, u: &[f64]) -> [f64; 2] {
        let x = self.reference(b, node);
        [
            x[0] + self.dof(b, node, 0).map_or(0.0, |d| u[d]),
            x[1] + self.dof(b, node, 1).map_or(0.0, |d| u[d]),
        ]
    }

    /// y = M x (block diagonal).
    pub fn mass_mul(&self, x: &[f64], y: &mut [f64]) {
        for (b, body) in self.bodies.iter().enumerate() {
            let r = self.range(b);
            body.pattern()
                .symmetric_mul(body.mass(), &x[r.clone()], &mut y[r]);
        }
    }

    /// ½ vᵀ M v per body.
    pub fn kinetic_energies(&self, v: &[f64], scratch: &mut [f64]) -> Vec<f64> {
        self.mass_mul(v, scratch);
        (0..self.len())
            .map(|b| {
                let r = self.range(b);
                0.5 * v[r.clone()]
                    .iter()
                    .zip(&scratch[r])
                    .map(|(a, c)| a * c)
                    .sum::<f64>()
            })
            .collect()
    }

    /// 𝒲(u) per body (+∞ for an inadmissible state).
    pub fn stored_energies(&self, u: &[f64]) -> Vec<f64> {
        self.bodies
            .iter()
            .enumerate()
            .map(|(b, body)| body.stored_energy(&u[self.range(b)]))
            .collect()
    }

    /// The nodal momenta (M v)_I and positions x_I of every node of every body, as
    /// (position, momentum) pairs: the ingredients of the linear momentum Σ (Mv)_I and the angular
    /// momentum Σ x_I × (Mv)_I. Held components carry no momentum.
    pub fn nodal_momenta(
        &self,
        u: &[f64],
        v: &[f64],
        scratch: &mut [f64],
    ) -> Vec<([f64; 2], [f64; 2])> {
        self.mass_mul(v, scratch);
        let mut out = Vec::new();
        for b in 0..self.len() {
            let nodes = self.bodies[b].data().mesh.nodes().len();
            for node in 0..nodes {
                let p = [
                    self.dof(b, node, 0).map_or(0.0, |d| scratch[d]),
                    self.dof(b, node, 1).map_or(0.0, |d| scratch[d]),
                ];
                out.push((self.position(b, node, u), p));
            }
        }
        out
    }

    /// The total node count.
    pub fn nodes(&self) -> usize {
        self.bodies
            .iter()
            .map(|b| b.data().mesh.nodes().len())
            .sum()
    }

    /// The free-dof vector of rigid motion of body `b`: velocity `v` plus angular velocity `omega`
    /// about `center`, v(X) = v + ω e_z × (X − c), written into the body's range of `out` (held dofs
    /// get nothing).
    pub fn rigid_velocity(
        &self,
        b: usize,
        v: [f64; 2],
        omega: f64,
        center: [f64; 2],
        out: &mut [f64],
    ) {
        let nodes = self.bodies[b].data().mesh.nodes();
        for (node, x) in nodes.iter().enumerate() {
            let w = [
                v[0] - omega * (x[1] - center[1]),
                v[1] + omega * (x[0] - center[0]),
            ];
            for c in 0..2 {
                if let Some(d) = self.dof(b, node, c) {
                    out[d] = w[c];
                }
            }
        }
    }

    /// The centre of mass of body `b` in its reference configuration (Σ_e ρ_e |e| x̄_e / Σ ρ_e |e|).
    pub fn centre_of_mass(&self, b: usize) -> [f64; 2] {
        let body = &self.bodies[b];
        let mesh = &body.data().mesh;
        let (mut m, mut s) = (0.0, [0.0, 0.0]);
        for (e, t) in mesh.triangles().iter().enumerate() {
            let w = body.density_of(e) * body.elements()[e].area;
            for &n in t {
                let x = mesh.nodes()[n];
                s[0] += w * x[0] / 3.0;
                s[1] += w * x[1] / 3.0;
            }
            m += w;
        }
        [s[0] / m, s[1] / m]
    }

    /// The mass of body `b`.
    pub fn mass_of(&self, b: usize) -> f64 {
        let body = &self.bodies[b];
        (0..body.elements().len())
            .map(|e| body.density_of(e) * body.elements()[e].area)
            .sum()
    }
}
