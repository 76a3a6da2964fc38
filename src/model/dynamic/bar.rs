//! A bar (0, L) in 1D elastodynamics: ρ A ü − (A P(1 + u_x))_x = A f, P = W′(F), with P1
//! elements (the 1D case of Barboteu–Danan–Sofonea (1.15)).
//!
//! On an element of length h_e with end values u_a, u_b: F_e = 1 + (u_b − u_a)/h_e, internal
//! forces A P(F_e) (−1, 1), tangent (A W″(F_e)/h_e) [1 −1; −1 1], consistent mass
//! (ρ A h_e/6) [2 1; 1 2] or lumped (ρ A h_e/2) I.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::error::{require_positive, InputError};
use crate::fem::sparse::SymmetricPattern;
use crate::field::Field;
use crate::material::hyperelastic::Hyperelastic1d;
use crate::mesh::interval::IntervalMesh;
use crate::model::dynamic::body::{stiffness_at_rest, ElasticBody, FreeDofs, Operators};

/// Consistent or lumped (row-sum) mass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MassMatrix {
    /// The consistent P1 mass matrix (the default).
    #[default]
    Consistent,
    /// The row-sum lumped, diagonal mass matrix.
    Lumped,
}

/// Which ends of the bar are held at u = 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct BarSupports {
    pub left: bool,
    pub right: bool,
}

/// The data of a bar.
#[derive(Debug, Clone)]
pub struct BarData {
    pub mesh: IntervalMesh,
    pub density: f64,
    /// Cross-section A (the bar's energies and forces scale with it).
    pub area: f64,
    pub law: Arc<dyn Hyperelastic1d>,
    pub supports: BarSupports,
    pub mass: MassMatrix,
    /// Body force f(x, t) per unit volume.
    pub body_force: Field,
}

/// The space-discretized bar.
#[derive(Debug)]
pub struct BarBody {
    data: BarData,
    element_dofs: Vec<[Option<usize>; 2]>,
    /// The free dofs (one per node) and the operators.
    ops: Operators,
}

impl BarBody {
    /// Validates the data and assembles the mass (and, for a small-strain law, the stiffness).
    pub fn new(data: BarData) -> Result<Self, InputError> {
        require_positive("bar.density", data.density)?;
        require_positive("bar.area", data.area)?;
        data.law.validate("bar.material")?;
        data.body_force.validate("bar.body_force")?;
        let nodes = data.mesh.nodes().len();
        let dofs =
            FreeDofs::number((0..nodes).map(|i| {
                (i == 0 && data.supports.left) || (i + 1 == nodes && data.supports.right)
            }));
        let n = dofs.count();
        let element_dofs: Vec<[Option<usize>; 2]> = (0..data.mesh.elements())
            .map(|e| [dofs.of(e), dofs.of(e + 1)])
            .collect();
        let pattern = SymmetricPattern::new(n, &element_dofs);
        let mut mass = vec![0.0; pattern.nnz()];
        for e in 0..data.mesh.elements() {
            let (a, b) = data.mesh.element(e);
            let m = data.density * data.area * (b - a);
            let local = match data.mass {
                MassMatrix::Consistent => [m / 3.0, m / 6.0, m / 6.0, m / 3.0],
                MassMatrix::Lumped => [m / 2.0, 0.0, 0.0, m / 2.0],
            };
            pattern.add_element(&mut mass, e, &local);
        }
        let mut body = Self {
            data,
            element_dofs,
            ops: Operators {
                dofs,
                pattern,
                mass,
                stiffness: None,
            },
        };
        if body.data.law.is_small_strain() {
            body.ops.stiffness = Some(stiffness_at_rest(&body));
        }
        Ok(body)
    }

    /// The data.
    pub fn data(&self) -> &BarData {
        &self.data
    }

    /// The free-dof index of node i (None at a held end).
    pub fn node_dof(&self, i: usize) -> Option<usize> {
        self.ops.dofs.of(i)
    }

    /// Nodal values of a free-dof vector (0 at held ends).
    pub fn nodal(&self, u: &[f64]) -> Vec<f64> {
        self.ops.dofs.nodal(u)
    }

    /// A free-dof vector from nodal values.
    pub fn from_nodal(&self, values: &[f64]) -> Vec<f64> {
        self.ops.dofs.from_nodal(values)
    }

    #[inline]
    fn value(&self, u: &[f64], d: Option<usize>) -> f64 {
        d.map_or(0.0, |d| u[d])
    }

    /// F_e = 1 + (u_b − u_a)/h_e.
    #[inline]
    fn deformation(&self, u: &[f64], e: usize) -> (f64, f64) {
        let (a, b) = self.data.mesh.element(e);
        let h = b - a;
        let [da, db] = self.element_dofs[e];
        (1.0 + (self.value(u, db) - self.value(u, da)) / h, h)
    }
}

impl ElasticBody for BarBody {
    fn operators(&self) -> &Operators {
        &self.ops
    }

    fn stored_energy(&self, u: &[f64]) -> f64 {
        let mut w = 0.0;
        for e in 0..self.element_dofs.len() {
            let (f, h) = self.deformation(u, e);
            if !self.data.law.admissible(f) {
                return f64::INFINITY;
            }
            w += self.data.area * h * self.data.law.energy(f);
        }
        w
    }

    fn internal_force(&self, u: &[f64], out: &mut [f64]) -> bool {
        out.iter_mut().for_each(|v| *v = 0.0);
        for (e, [da, db]) in self.element_dofs.iter().enumerate() {
            let (f, _) = self.deformation(u, e);
            if !self.data.law.admissible(f) {
                return false;
            }
            let p = self.data.area * self.data.law.piola(f);
            if let Some(a) = da {
                out[*a] -= p;
            }
            if let Some(b) = db {
                out[*b] += p;
            }
        }
        true
    }

    fn internal_force_terms(&self, u0: &[f64], u1: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = 0.0);
        let rho = self.data.density;
        let c = self.data.law.wave_speed(rho);
        for (e, [da, db]) in self.element_dofs.iter().enumerate() {
            let scale = |f: f64| {
                let inverse = if f > 0.0 {
                    (1.0 + f.ln().abs()) / f
                } else {
                    0.0
                };
                f.abs().powi(3) + inverse
            };
            let (f0, _) = self.deformation(u0, e);
            let (f1, _) = self.deformation(u1, e);
            let m = self.data.area * rho * c * c * scale(f0).max(scale(f1));
            for i in [da, db].into_iter().flatten() {
                out[*i] += m;
            }
        }
    }

    fn add_tangent(&self, u: &[f64], scale: f64, values: &mut [f64]) {
        for e in 0..self.element_dofs.len() {
            let (f, h) = self.deformation(u, e);
            let k = scale * self.data.area * self.data.law.tangent(f) / h;
            self.ops.pattern.add_element(values, e, &[k, -k, -k, k]);
        }
    }

    fn discrete_gradient_force(&self, u0: &[f64], u1: &[f64], out: &mut [f64]) -> bool {
        out.iter_mut().for_each(|v| *v = 0.0);
        for (e, [da, db]) in self.element_dofs.iter().enumerate() {
            let (f0, _) = self.deformation(u0, e);
            let (f1, _) = self.deformation(u1, e);
            if !self.data.law.admissible(f1) {
                return false;
            }
            let p = self.data.area * self.data.law.discrete_gradient(f0, f1);
            if let Some(a) = da {
                out[*a] -= p;
            }
            if let Some(b) = db {
                out[*b] += p;
            }
        }
        true
    }

    fn add_discrete_gradient_tangent(
        &self,
        u0: &[f64],
        u1: &[f64],
        scale: f64,
        values: &mut [f64],
    ) {
        for e in 0..self.element_dofs.len() {
            let (f0, h) = self.deformation(u0, e);
            let (f1, _) = self.deformation(u1, e);
            let k = scale * self.data.area * self.data.law.discrete_gradient_tangent(f0, f1) / h;
            self.ops.pattern.add_element(values, e, &[k, -k, -k, k]);
        }
    }

    /// The bar's element tangent [k, −k; −k, k] is symmetric: no skew part.
    fn add_discrete_gradient_skew(
        &self,
        _u0: &[f64],
        _u1: &[f64],
        _scale: f64,
        _values: &mut [f64],
    ) {
    }

    fn load_into(&self, t: f64, out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = 0.0);
        if self.load_is_zero() {
            return;
        }
        // 3-point Gauss per element (exact for quadratic data times P1)
        let g = (0.6f64).sqrt();
        let rule = [(-g, 5.0 / 9.0), (0.0, 8.0 / 9.0), (g, 5.0 / 9.0)];
        for (e, [da, db]) in self.element_dofs.iter().enumerate() {
            let (a, b) = self.data.mesh.element(e);
            let h = b - a;
            for &(s, w) in &rule {
                let x = a + 0.5 * h * (1.0 + s);
                let fx = self.data.area * self.data.body_force.eval(x, 0.0, t) * 0.5 * h * w;
                let phi_b = 0.5 * (1.0 + s);
                if let Some(i) = da {
                    out[*i] += fx * (1.0 - phi_b);
                }
                if let Some(i) = db {
                    out[*i] += fx * phi_b;
                }
            }
        }
    }

    fn load_depends_on_time(&self) -> bool {
        self.data.body_force.dependence().t
    }

    fn load_is_zero(&self) -> bool {
        self.data.body_force.as_constant() == Some(0.0)
    }

    fn wave_speed(&self) -> f64 {
        self.data.law.wave_speed(self.data.density)
    }

    fn h_min(&self) -> f64 {
        self.data.mesh.h_min()
    }

    fn describe(&self) -> String {
        format!(
            "bar of length {} on {} P1 elements, {}, ρ = {}, {:?} mass",
            self.data.mesh.length(),
            self.data.mesh.elements(),
            self.data.law.describe(),
            self.data.density,
            self.data.mass
        )
    }
}
