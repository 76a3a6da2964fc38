//! A plane-strain body in elastodynamics with P1 triangles (Barboteu–Danan–Sofonea, "BDS",
//! (1.14)–(1.17)): ρ ü − Div Π(F) = f0 in Ω, u = 0 on Γ1, Π ν = f2 on Γ2.
//!
//! On a triangle with shape gradients ∇φ_a the deformation gradient is constant,
//! F = I + Σ_a u_a ⊗ ∇φ_a; the internal force of node a is |e| Π(F) ∇φ_a and the tangent
//! stiffness |e| ∇φ_a · (∂Π/∂F) ∇φ_b. Consistent mass (ρ|e|/12)(1 + δ_ab) per component, or
//! lumped ρ|e|/3. Regions of the mesh may carry their own ρ and law ([`plane_material`]): each
//! element's terms use its own.
//!
//! [`plane_material`]: crate::model::dynamic::plane_material

use std::sync::Arc;

use nalgebra::{Matrix2, SMatrix};

use crate::error::InputError;
use crate::fem::sparse::SymmetricPattern;
use crate::fem::triangle_p1::P1Triangle;
use crate::field::Field;
use crate::material::hyperelastic::Hyperelastic2d;
use crate::mesh::triangle::TriangleMesh;
use crate::model::dynamic::bar::MassMatrix;
use crate::model::dynamic::body::{stiffness_at_rest, ElasticBody, FreeDofs, Operators};
pub use crate::model::dynamic::plane_material::BodyRegion;
use crate::model::dynamic::plane_material::ElementMaterials;
use crate::model::quasistatic::plane::{DirichletPart, TractionPart};

/// The data of a plane-strain body.
#[derive(Debug, Clone)]
pub struct PlaneBodyData {
    pub mesh: TriangleMesh,
    pub density: f64,
    pub law: Arc<dyn Hyperelastic2d>,
    pub dirichlet: Vec<DirichletPart>,
    pub traction: Vec<TractionPart>,
    /// f0(x, y, t).
    pub body_force: [Field; 2],
    pub mass: MassMatrix,
    /// Regions with their own density and law (disjoint); the triangles of no region take
    /// `density` and `law`. Empty for a one-material body.
    pub regions: Vec<BodyRegion>,
}

/// The space-discretized plane body.
#[derive(Debug)]
pub struct PlaneBody {
    data: PlaneBodyData,
    elements: Vec<P1Triangle>,
    /// The density and law of each element (built once).
    materials: ElementMaterials,
    element_dofs: Vec<[Option<usize>; 6]>,
    /// The free dofs (global dof 2 i + c of node i, component c) and the operators.
    ops: Operators,
    /// Traction edges: (node a, node b, part index).
    traction_edges: Vec<([usize; 2], usize)>,
    h_min: f64,
}

impl PlaneBody {
    /// Validates the data, numbers the free dofs and assembles the mass (and, for a small-strain
    /// law, the stiffness).
    pub fn new(data: PlaneBodyData) -> Result<Self, InputError> {
        for (c, f) in data.body_force.iter().enumerate() {
            f.validate(&format!("body.body_force[{c}]"))?;
        }
        let mesh = &data.mesh;
        let nn = mesh.nodes().len();
        let mut fixed = vec![false; 2 * nn];
        let mut traction_edges = Vec::new();
        for (e, edge) in mesh.boundary().iter().enumerate() {
            for part in &data.dirichlet {
                if part.boundary.contains(mesh, e) {
                    for &node in &edge.nodes {
                        for c in 0..2 {
                            if part.support.fixes(c) {
                                fixed[2 * node + c] = true;
                            }
                        }
                    }
                }
            }
            if let Some(i) = data
                .traction
                .iter()
                .position(|p| p.boundary.contains(mesh, e))
            {
                traction_edges.push((edge.nodes, i));
            }
        }
        let dofs = FreeDofs::number(fixed);
        let n = dofs.count();
        let elements: Vec<P1Triangle> = mesh
            .triangles()
            .iter()
            .map(|t| P1Triangle::new([mesh.nodes()[t[0]], mesh.nodes()[t[1]], mesh.nodes()[t[2]]]))
            .collect();
        if let Some(i) = elements
            .iter()
            .position(|e| !(e.area.is_finite() && e.area > 0.0))
        {
            return Err(InputError::new(
                format!("mesh.triangles[{i}]"),
                format!("area {}", elements[i].area),
                "counter-clockwise triangles of positive area",
            ));
        }
        let materials = ElementMaterials::new(
            data.density,
            &data.law,
            &data.regions,
            mesh.triangles().len(),
        )?;
        let element_dofs: Vec<[Option<usize>; 6]> = mesh
            .triangles()
            .iter()
            .map(|t| std::array::from_fn(|p| dofs.of(2 * t[p / 2] + p % 2)))
            .collect();
        let pattern = SymmetricPattern::new(n, &element_dofs);
        let mut mass = vec![0.0; pattern.nnz()];
        for (e, el) in elements.iter().enumerate() {
            let m = materials.density(e) * el.area;
            let mut local = [0.0; 36];
            for a in 0..3 {
                for b in 0..3 {
                    let v = match data.mass {
                        MassMatrix::Consistent => m / 12.0 * if a == b { 2.0 } else { 1.0 },
                        MassMatrix::Lumped => {
                            if a == b {
                                m / 3.0
                            } else {
                                0.0
                            }
                        }
                    };
                    for c in 0..2 {
                        local[(2 * a + c) * 6 + 2 * b + c] = v;
                    }
                }
            }
            pattern.add_element(&mut mass, e, &local);
        }
        let h_min = mesh
            .triangles()
            .iter()
            .flat_map(|t| {
                (0..3).map(move |i| {
                    let (a, b) = (mesh.nodes()[t[i]], mesh.nodes()[t[(i + 1) % 3]]);
                    ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
                })
            })
            .fold(f64::INFINITY, f64::min);
        let mut body = Self {
            data,
            elements,
            materials,
            element_dofs,
            ops: Operators {
                dofs,
                pattern,
                mass,
                stiffness: None,
            },
            traction_edges,
            h_min,
        };
        if body.materials.all_small_strain() {
            body.ops.stiffness = Some(stiffness_at_rest(&body));
        }
        Ok(body)
    }

    /// The data.
    pub fn data(&self) -> &PlaneBodyData {
        &self.data
    }

    /// The free-dof index of global dof 2 i + c (None where Γ1 holds it).
    pub fn dof(&self, node: usize, component: usize) -> Option<usize> {
        self.ops.dofs.of(2 * node + component)
    }

    /// Interleaved nodal values (u_x, u_y per node) of a free-dof vector.
    pub fn nodal(&self, u: &[f64]) -> Vec<f64> {
        self.ops.dofs.nodal(u)
    }

    /// A free-dof vector from interleaved nodal values.
    pub fn from_nodal(&self, values: &[f64]) -> Vec<f64> {
        self.ops.dofs.from_nodal(values)
    }

    /// W_e, the law of element `e` (the body's or its region's).
    #[inline]
    pub fn law_of(&self, e: usize) -> &dyn Hyperelastic2d {
        self.materials.law(e)
    }

    /// ρ_e, the density of element `e`.
    #[inline]
    pub fn density_of(&self, e: usize) -> f64 {
        self.materials.density(e)
    }

    /// The region of element `e` (an index into `data().regions`), `None` where the body's own
    /// material applies.
    #[inline]
    pub fn region_of(&self, e: usize) -> Option<usize> {
        self.materials.index(e).checked_sub(1)
    }

    /// Whether every element of u is admissible for its law (det F > 0 for neo-Hooke): the check
    /// of a Newton update, without evaluating the energy.
    pub fn admissible(&self, u: &[f64]) -> bool {
        (0..self.elements.len()).all(|e| {
            self.materials
                .law(e)
                .admissible(&self.deformation_gradient(u, e))
        })
    }

    /// Adds `scale` · ∂F^algo/∂u1 (u0, u1) split into its symmetric part (into `sym`) and its skew
    /// part (upper triangle, into `skew`) in one pass over the elements: the sum of
    /// [`ElasticBody::add_discrete_gradient_tangent`] and [`ElasticBody::add_discrete_gradient_skew`]
    /// with the law's discrete-gradient tangent evaluated once per element.
    pub fn add_discrete_gradient_tangent_split(
        &self,
        u0: &[f64],
        u1: &[f64],
        scale: f64,
        sym: &mut [f64],
        skew: &mut [f64],
    ) {
        for e in 0..self.elements.len() {
            let f0 = self.deformation_gradient(u0, e);
            let f1 = self.deformation_gradient(u1, e);
            let law = self.materials.law(e);
            let k = self.element_matrix(e, scale, false, |df| {
                law.discrete_gradient_tangent(&f0, &f1, df)
            });
            let mut s = [0.0; 36];
            let mut w = [0.0; 36];
            for p in 0..6 {
                for q in 0..6 {
                    s[p * 6 + q] = 0.5 * (k[p * 6 + q] + k[q * 6 + p]);
                    w[p * 6 + q] = 0.5 * (k[p * 6 + q] - k[q * 6 + p]);
                }
            }
            self.ops.pattern.add_element(sym, e, &s);
            self.ops.pattern.add_element(skew, e, &w);
        }
    }

    /// The element geometries.
    pub fn elements(&self) -> &[P1Triangle] {
        &self.elements
    }

    /// F_e = I + Σ_a u_a ⊗ ∇φ_a.
    #[inline]
    #[allow(non_snake_case)]
    pub fn deformation_gradient(&self, u: &[f64], e: usize) -> Matrix2<f64> {
        let g = &self.elements[e].grad;
        let d = &self.element_dofs[e];
        let mut F = Matrix2::identity();
        for a in 0..3 {
            let ux = d[2 * a].map_or(0.0, |i| u[i]);
            let uy = d[2 * a + 1].map_or(0.0, |i| u[i]);
            for j in 0..2 {
                F[(0, j)] += ux * g[a][j];
                F[(1, j)] += uy * g[a][j];
            }
        }
        F
    }

    /// Adds |e| Π ∇φ_a to the element's free dofs.
    #[inline]
    fn scatter_stress(&self, e: usize, p: &Matrix2<f64>, out: &mut [f64]) {
        let el = &self.elements[e];
        for a in 0..3 {
            for c in 0..2 {
                if let Some(i) = self.element_dofs[e][2 * a + c] {
                    out[i] += el.area * (p[(c, 0)] * el.grad[a][0] + p[(c, 1)] * el.grad[a][1]);
                }
            }
        }
    }

    /// The element matrix |e| ∇φ_a · T(dF_b) ∇φ_b for a linear map T of dF (row-major 6 × 6),
    /// symmetrized when `symmetrize`. T is applied to the four unit matrices E_cJ only (a local
    /// dof's dF = e_c ⊗ ∇φ_b = Σ_J ∂_Jφ_b E_cJ), so a law's tangent is evaluated four times per
    /// element instead of six.
    fn element_matrix(
        &self,
        e: usize,
        scale: f64,
        symmetrize: bool,
        t: impl Fn(&Matrix2<f64>) -> Matrix2<f64>,
    ) -> [f64; 36] {
        let el = &self.elements[e];
        let mut unit = [[Matrix2::zeros(); 2]; 2];
        for (c, row) in unit.iter_mut().enumerate() {
            for (j, slot) in row.iter_mut().enumerate() {
                let mut df = Matrix2::zeros();
                df[(c, j)] = 1.0;
                *slot = t(&df);
            }
        }
        let mut k = SMatrix::<f64, 6, 6>::zeros();
        for b in 0..3 {
            for c in 0..2 {
                let dp = unit[c][0] * el.grad[b][0] + unit[c][1] * el.grad[b][1];
                for a in 0..3 {
                    for i in 0..2 {
                        k[(2 * a + i, 2 * b + c)] = scale
                            * el.area
                            * (dp[(i, 0)] * el.grad[a][0] + dp[(i, 1)] * el.grad[a][1]);
                    }
                }
            }
        }
        if symmetrize {
            k = 0.5 * (k + k.transpose());
        }
        let mut out = [0.0; 36];
        for p in 0..6 {
            for q in 0..6 {
                out[p * 6 + q] = k[(p, q)];
            }
        }
        out
    }
}

impl ElasticBody for PlaneBody {
    fn operators(&self) -> &Operators {
        &self.ops
    }

    fn stored_energy(&self, u: &[f64]) -> f64 {
        let mut w = 0.0;
        for (e, el) in self.elements.iter().enumerate() {
            let f = self.deformation_gradient(u, e);
            let law = self.materials.law(e);
            if !law.admissible(&f) {
                return f64::INFINITY;
            }
            w += el.area * law.energy(&f);
        }
        w
    }

    fn internal_force(&self, u: &[f64], out: &mut [f64]) -> bool {
        out.iter_mut().for_each(|v| *v = 0.0);
        for e in 0..self.elements.len() {
            let f = self.deformation_gradient(u, e);
            let law = self.materials.law(e);
            if !law.admissible(&f) {
                return false;
            }
            let p = law.piola(&f);
            self.scatter_stress(e, &p, out);
        }
        true
    }

    fn internal_force_terms(&self, u0: &[f64], u1: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = 0.0);
        for (e, el) in self.elements.iter().enumerate() {
            let rho = self.materials.density(e);
            let c = self.materials.law(e).wave_speed(rho);
            let scale = |u: &[f64]| {
                let f = self.deformation_gradient(u, e);
                let (n, j) = (f.norm(), f.determinant());
                // |F|³ (C − I) and, for a law with F⁻ᵀ in its stress (neo-Hooke), |F| (1 + |ln J|)/J
                let inverse = if j > 0.0 {
                    n * (1.0 + j.ln().abs()) / j
                } else {
                    0.0
                };
                n.powi(3) + inverse
            };
            let m = el.area * rho * c * c * scale(u0).max(scale(u1));
            for a in 0..3 {
                let g = el.grad[a][0].abs() + el.grad[a][1].abs();
                for comp in 0..2 {
                    if let Some(i) = self.element_dofs[e][2 * a + comp] {
                        out[i] += m * g;
                    }
                }
            }
        }
    }

    fn add_tangent(&self, u: &[f64], scale: f64, values: &mut [f64]) {
        for e in 0..self.elements.len() {
            let f = self.deformation_gradient(u, e);
            let law = self.materials.law(e);
            let k = self.element_matrix(e, scale, false, |df| law.tangent(&f, df));
            self.ops.pattern.add_element(values, e, &k);
        }
    }

    fn discrete_gradient_force(&self, u0: &[f64], u1: &[f64], out: &mut [f64]) -> bool {
        out.iter_mut().for_each(|v| *v = 0.0);
        for e in 0..self.elements.len() {
            let f0 = self.deformation_gradient(u0, e);
            let f1 = self.deformation_gradient(u1, e);
            let law = self.materials.law(e);
            if !law.admissible(&f1) {
                return false;
            }
            let p = law.discrete_gradient(&f0, &f1);
            self.scatter_stress(e, &p, out);
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
        for e in 0..self.elements.len() {
            let f0 = self.deformation_gradient(u0, e);
            let f1 = self.deformation_gradient(u1, e);
            let law = self.materials.law(e);
            let k = self.element_matrix(e, scale, true, |df| {
                law.discrete_gradient_tangent(&f0, &f1, df)
            });
            self.ops.pattern.add_element(values, e, &k);
        }
    }

    fn add_discrete_gradient_skew(&self, u0: &[f64], u1: &[f64], scale: f64, values: &mut [f64]) {
        for e in 0..self.elements.len() {
            let f0 = self.deformation_gradient(u0, e);
            let f1 = self.deformation_gradient(u1, e);
            let law = self.materials.law(e);
            let k = self.element_matrix(e, scale, false, |df| {
                law.discrete_gradient_tangent(&f0, &f1, df)
            });
            let mut w = [0.0; 36];
            for p in 0..6 {
                for q in 0..6 {
                    w[p * 6 + q] = 0.5 * (k[p * 6 + q] - k[q * 6 + p]);
                }
            }
            self.ops.pattern.add_element(values, e, &w);
        }
    }

    fn load_into(&self, t: f64, out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = 0.0);
        let mesh = &self.data.mesh;
        let [fx, fy] = &self.data.body_force;
        let zero = |f: &Field| f.as_constant() == Some(0.0);
        if !(zero(fx) && zero(fy)) {
            // degree-2 rule: the edge midpoints with weights |e|/3 (φ = 1/2 at both ends)
            for (e, tri) in mesh.triangles().iter().enumerate() {
                let w = self.elements[e].area / 3.0;
                for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                    let (a, b) = (mesh.nodes()[tri[i]], mesh.nodes()[tri[j]]);
                    let x = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
                    let f = [fx.eval(x[0], x[1], t), fy.eval(x[0], x[1], t)];
                    for p in [i, j] {
                        for c in 0..2 {
                            if let Some(d) = self.element_dofs[e][2 * p + c] {
                                out[d] += 0.5 * w * f[c];
                            }
                        }
                    }
                }
            }
        }
        let gauss3 = [
            (0.5 - 0.5 * (0.6f64).sqrt(), 5.0 / 18.0),
            (0.5, 8.0 / 18.0),
            (0.5 + 0.5 * (0.6f64).sqrt(), 5.0 / 18.0),
        ];
        for &([na, nb], part) in &self.traction_edges {
            let [gx, gy] = &self.data.traction[part].traction;
            let (a, b) = (mesh.nodes()[na], mesh.nodes()[nb]);
            let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            for &(s, w) in &gauss3 {
                let x = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
                let f = [gx.eval(x[0], x[1], t), gy.eval(x[0], x[1], t)];
                for (node, phi) in [(na, 1.0 - s), (nb, s)] {
                    for c in 0..2 {
                        if let Some(d) = self.ops.dofs.of(2 * node + c) {
                            out[d] += w * len * phi * f[c];
                        }
                    }
                }
            }
        }
    }

    fn load_depends_on_time(&self) -> bool {
        self.data.body_force.iter().any(|f| f.dependence().t)
            || self
                .data
                .traction
                .iter()
                .any(|p| p.traction.iter().any(|f| f.dependence().t))
    }

    fn load_is_zero(&self) -> bool {
        let zero = |f: &Field| f.as_constant() == Some(0.0);
        self.data.body_force.iter().all(zero) && self.traction_edges.is_empty()
    }

    fn wave_speed(&self) -> f64 {
        self.materials.wave_speed()
    }

    fn h_min(&self) -> f64 {
        self.h_min
    }

    fn describe(&self) -> String {
        let mut text = format!(
            "plane-strain body: {} nodes, {} P1 triangles, {} free dofs, {}, ρ = {}, {:?} mass",
            self.data.mesh.nodes().len(),
            self.elements.len(),
            self.ops.dofs.count(),
            self.data.law.describe(),
            self.data.density,
            self.data.mass
        );
        for r in &self.data.regions {
            text.push_str(&format!(
                "; region \"{}\" ({} triangles): {}, ρ = {}",
                r.name,
                r.triangles.len(),
                r.law.describe(),
                r.density
            ));
        }
        text
    }
}
