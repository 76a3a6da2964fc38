//! The discrete structure of a plane problem: degrees of freedom (interleaved per node, with Γ1
//! components removed), element geometry, the sparsity pattern, the contact operator on Γ3, the
//! load vector, and the rigid motions that Γ1 leaves free.
//!
//! Contact operator: each contact point g (two Gauss points per Γ3 edge, or the Γ3 nodes) has a
//! weight W_g (edge length × Gauss weight, or half the adjacent edge lengths), an outward normal
//! ν_g, and the row C_g with (C w)_g = w(x_g)·ν_g, so that ∫_Γ3 p_ν(w_ν) v_ν ≈ Σ_g W_g p_ν((Cw)_g)
//! (Cv)_g, i.e. the force vector Cᵀ W p.

use crate::error::InputError;
use crate::fem::sparse::SymmetricPattern;
use crate::fem::triangle_p1::P1Triangle;
use crate::field::Field;
use crate::model::quasistatic::plane::{ContactIntegration, EdgeRole, PlaneProblem};

/// One contact point.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPoint {
    pub position: [f64; 2],
    pub normal: [f64; 2],
    pub weight: f64,
    /// (global dof, coefficient) pairs: (Cw)_g = Σ coefficient · w[dof].
    pub entries: Vec<(usize, f64)>,
}

/// The discrete structure of a plane problem.
#[derive(Debug, Clone)]
pub struct PlaneDofs {
    pub n_nodes: usize,
    /// For each global dof (2·nodes): its index among the solved dofs, or `None` (Γ1 or a fixing
    /// dof of a rigid mode).
    pub solved: Vec<Option<usize>>,
    /// Global dof of each solved dof.
    pub solved_dofs: Vec<usize>,
    /// Global dofs held at zero by Γ1.
    pub fixed: Vec<bool>,
    pub elements: Vec<P1Triangle>,
    /// Solved-dof index of each element's six local dofs.
    pub element_dofs: Vec<[Option<usize>; 6]>,
    pub pattern: SymmetricPattern,
    pub contact_points: Vec<ContactPoint>,
    /// Solved dofs of the Γ3 nodes, in the order the factorization keeps them last.
    pub contact_dofs: Vec<usize>,
    /// Rigid motions that Γ1 leaves free (each a global dof vector: orthogonal unit motions), and the
    /// global dofs removed from the solve to fix them.
    pub rigid_modes: Vec<Vec<f64>>,
    pub fixing_dofs: Vec<usize>,
    pub edge_roles: Vec<EdgeRole>,
}

/// The rigid motions of the plane evaluated at the nodes: translations e_x, e_y and the rotation
/// (−(y − y_c), x − x_c) about the centroid.
fn rigid_motions(nodes: &[[f64; 2]]) -> [Vec<f64>; 3] {
    let n = nodes.len() as f64;
    let (cx, cy) = nodes
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p[0] / n, b + p[1] / n));
    let mut m = [
        vec![0.0; 2 * nodes.len()],
        vec![0.0; 2 * nodes.len()],
        vec![0.0; 2 * nodes.len()],
    ];
    for (i, p) in nodes.iter().enumerate() {
        m[0][2 * i] = 1.0;
        m[1][2 * i + 1] = 1.0;
        m[2][2 * i] = -(p[1] - cy);
        m[2][2 * i + 1] = p[0] - cx;
    }
    m
}

impl PlaneDofs {
    /// Builds the structure. Rigid motions left free by Γ1 are detected and fixed by removing one
    /// Γ3 dof each (their amplitude becomes an unknown of the contact problem).
    pub fn new(problem: &PlaneProblem, roles: Vec<EdgeRole>) -> Result<Self, InputError> {
        let mesh = &problem.mesh;
        let nn = mesh.nodes().len();
        let mut fixed = vec![false; 2 * nn];
        for (e, role) in roles.iter().enumerate() {
            if let EdgeRole::Dirichlet(i) = role {
                let support = problem.dirichlet[*i].support;
                for &node in &mesh.boundary()[e].nodes {
                    for c in 0..2 {
                        if support.fixes(c) {
                            fixed[2 * node + c] = true;
                        }
                    }
                }
            }
        }
        // Contact nodes (Γ3), in boundary order.
        let mut contact_nodes: Vec<usize> = Vec::new();
        for (e, role) in roles.iter().enumerate() {
            if *role == EdgeRole::Contact {
                for &node in &mesh.boundary()[e].nodes {
                    if !contact_nodes.contains(&node) {
                        contact_nodes.push(node);
                    }
                }
            }
        }
        // Rigid motions vanishing on every fixed dof: null space of the fixed rows of [e_x e_y rot].
        let motions = rigid_motions(mesh.nodes());
        let fixed_rows: Vec<[f64; 3]> = (0..2 * nn)
            .filter(|&d| fixed[d])
            .map(|d| [motions[0][d], motions[1][d], motions[2][d]])
            .collect();
        let free_combinations = null_space_3(&fixed_rows);
        let mut rigid_modes: Vec<Vec<f64>> = free_combinations
            .iter()
            .map(|c| {
                (0..2 * nn)
                    .map(|d| c[0] * motions[0][d] + c[1] * motions[1][d] + c[2] * motions[2][d])
                    .collect()
            })
            .collect();
        orthonormalize(&mut rigid_modes);
        let mut fixing_dofs = Vec::new();
        if !rigid_modes.is_empty() {
            if contact_nodes.is_empty() {
                return Err(InputError::new(
                    "dirichlet",
                    format!("{} rigid motion(s) left free", rigid_modes.len()),
                    "a Γ1 that holds the body, or a contact boundary that can carry it",
                ));
            }
            // Greedy choice of well-conditioned fixing dofs among the Γ3 dofs.
            let candidates: Vec<usize> = contact_nodes
                .iter()
                .flat_map(|&n| [2 * n, 2 * n + 1])
                .filter(|&d| !fixed[d])
                .collect();
            let mut residual = rigid_modes.clone();
            for j in 0..residual.len() {
                let best = candidates
                    .iter()
                    .copied()
                    .filter(|d| !fixing_dofs.contains(d))
                    .max_by(|a, b| residual[j][*a].abs().total_cmp(&residual[j][*b].abs()))
                    .filter(|&d| residual[j][d].abs() > 1e-8);
                let Some(d) = best else {
                    return Err(InputError::new(
                        "contact",
                        "(the contact boundary)",
                        "a contact boundary on which every free rigid motion moves",
                    ));
                };
                fixing_dofs.push(d);
                // eliminate this dof from the remaining modes
                let pivot = residual[j][d];
                let row = residual[j].clone();
                for r in residual.iter_mut().skip(j + 1) {
                    let f = r[d] / pivot;
                    for (x, y) in r.iter_mut().zip(&row) {
                        *x -= f * y;
                    }
                }
            }
        }
        // Solved dofs: free, not fixing; Γ3 dofs last (in contact-node order).
        let mut solved = vec![None; 2 * nn];
        let mut solved_dofs = Vec::with_capacity(2 * nn);
        let is_contact_dof = {
            let mut v = vec![false; 2 * nn];
            for &n in &contact_nodes {
                v[2 * n] = true;
                v[2 * n + 1] = true;
            }
            v
        };
        for d in 0..2 * nn {
            if !fixed[d] && !fixing_dofs.contains(&d) {
                solved[d] = Some(solved_dofs.len());
                solved_dofs.push(d);
            }
        }
        let contact_dofs: Vec<usize> = contact_nodes
            .iter()
            .flat_map(|&n| [2 * n, 2 * n + 1])
            .filter_map(|d| if is_contact_dof[d] { solved[d] } else { None })
            .collect();
        let elements: Vec<P1Triangle> = mesh
            .triangles()
            .iter()
            .map(|t| P1Triangle::new([mesh.nodes()[t[0]], mesh.nodes()[t[1]], mesh.nodes()[t[2]]]))
            .collect();
        let element_dofs: Vec<[Option<usize>; 6]> = mesh
            .triangles()
            .iter()
            .map(|t| std::array::from_fn(|p| solved[2 * t[p / 2] + p % 2]))
            .collect();
        let pattern = SymmetricPattern::new(solved_dofs.len(), &element_dofs);
        let contact_points = match &problem.contact {
            Some(c) => contact_points(problem, &roles, c.integration),
            None => Vec::new(),
        };
        Ok(Self {
            n_nodes: nn,
            solved,
            solved_dofs,
            fixed,
            elements,
            element_dofs,
            pattern,
            contact_points,
            contact_dofs,
            rigid_modes,
            fixing_dofs,
            edge_roles: roles,
        })
    }

    /// Number of solved dofs.
    pub fn n_solved(&self) -> usize {
        self.solved_dofs.len()
    }

    /// The load vector over all global dofs at time t: body force (degree-2 rule per triangle),
    /// tractions on Γ2 and the source g on Γ3 (3-point Gauss per edge). Only the parts whose data
    /// satisfy `include` are assembled (to split time-independent from time-dependent parts).
    pub fn load_into(
        &self,
        problem: &PlaneProblem,
        t: f64,
        include: &dyn Fn(&Field) -> bool,
        out: &mut [f64],
    ) {
        out.iter_mut().for_each(|v| *v = 0.0);
        let mesh = &problem.mesh;
        let [fx, fy] = &problem.body_force;
        if (include(fx) || include(fy)) && !(is_zero(fx) && is_zero(fy)) {
            // degree-2 rule: the three edge midpoints with weights 1/3
            for (tri, el) in mesh.triangles().iter().zip(&self.elements) {
                let p = [
                    mesh.nodes()[tri[0]],
                    mesh.nodes()[tri[1]],
                    mesh.nodes()[tri[2]],
                ];
                for (i, j, k) in [(0, 1, 2), (1, 2, 0), (2, 0, 1)] {
                    let x = [0.5 * (p[i][0] + p[j][0]), 0.5 * (p[i][1] + p[j][1])];
                    let w = el.area / 3.0;
                    let f = [
                        if include(fx) {
                            fx.eval(x[0], x[1], t)
                        } else {
                            0.0
                        },
                        if include(fy) {
                            fy.eval(x[0], x[1], t)
                        } else {
                            0.0
                        },
                    ];
                    // φ_i = φ_j = 1/2, φ_k = 0 at the midpoint of edge (i, j)
                    for a in [i, j] {
                        out[2 * tri[a]] += 0.5 * w * f[0];
                        out[2 * tri[a] + 1] += 0.5 * w * f[1];
                    }
                    let _ = k;
                }
            }
        }
        let gauss3 = [
            (0.5 - 0.5 * (0.6f64).sqrt(), 5.0 / 18.0),
            (0.5, 8.0 / 18.0),
            (0.5 + 0.5 * (0.6f64).sqrt(), 5.0 / 18.0),
        ];
        for (e, role) in self.edge_roles.iter().enumerate() {
            let data = match role {
                EdgeRole::Traction(i) => Some(&problem.traction[*i].traction),
                EdgeRole::Contact => problem.contact.as_ref().and_then(|c| c.source.as_ref()),
                _ => None,
            };
            let Some([gx, gy]) = data else { continue };
            if !(include(gx) || include(gy)) {
                continue;
            }
            let edge = &mesh.boundary()[e];
            let (a, b) = (mesh.nodes()[edge.nodes[0]], mesh.nodes()[edge.nodes[1]]);
            let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            for &(s, w) in &gauss3 {
                let x = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
                let f = [
                    if include(gx) {
                        gx.eval(x[0], x[1], t)
                    } else {
                        0.0
                    },
                    if include(gy) {
                        gy.eval(x[0], x[1], t)
                    } else {
                        0.0
                    },
                ];
                for (node, phi) in [(edge.nodes[0], 1.0 - s), (edge.nodes[1], s)] {
                    out[2 * node] += w * len * phi * f[0];
                    out[2 * node + 1] += w * len * phi * f[1];
                }
            }
        }
    }
}

fn is_zero(f: &Field) -> bool {
    f.as_constant() == Some(0.0)
}

fn contact_points(
    problem: &PlaneProblem,
    roles: &[EdgeRole],
    integration: ContactIntegration,
) -> Vec<ContactPoint> {
    let mesh = &problem.mesh;
    let mut points = Vec::new();
    match integration {
        ContactIntegration::Gauss2 => {
            let s = 0.5 / 3f64.sqrt();
            for (e, role) in roles.iter().enumerate() {
                if *role != EdgeRole::Contact {
                    continue;
                }
                let edge = &mesh.boundary()[e];
                let (normal, len) = mesh.edge_normal(edge);
                let (a, b) = (mesh.nodes()[edge.nodes[0]], mesh.nodes()[edge.nodes[1]]);
                for xi in [0.5 - s, 0.5 + s] {
                    let mut entries = Vec::with_capacity(4);
                    for (node, phi) in [(edge.nodes[0], 1.0 - xi), (edge.nodes[1], xi)] {
                        entries.push((2 * node, phi * normal[0]));
                        entries.push((2 * node + 1, phi * normal[1]));
                    }
                    points.push(ContactPoint {
                        position: [a[0] + xi * (b[0] - a[0]), a[1] + xi * (b[1] - a[1])],
                        normal,
                        weight: 0.5 * len,
                        entries,
                    });
                }
            }
        }
        ContactIntegration::Nodal => {
            let mut weight = vec![0.0; mesh.nodes().len()];
            let mut normal = vec![[0.0; 2]; mesh.nodes().len()];
            let mut order = Vec::new();
            for (e, role) in roles.iter().enumerate() {
                if *role != EdgeRole::Contact {
                    continue;
                }
                let edge = &mesh.boundary()[e];
                let (nrm, len) = mesh.edge_normal(edge);
                for &node in &edge.nodes {
                    if weight[node] == 0.0 {
                        order.push(node);
                    }
                    weight[node] += 0.5 * len;
                    normal[node][0] += 0.5 * len * nrm[0];
                    normal[node][1] += 0.5 * len * nrm[1];
                }
            }
            for node in order {
                let n = normal[node];
                let l = (n[0] * n[0] + n[1] * n[1]).sqrt();
                let nu = [n[0] / l, n[1] / l];
                points.push(ContactPoint {
                    position: mesh.nodes()[node],
                    normal: nu,
                    weight: weight[node],
                    entries: vec![(2 * node, nu[0]), (2 * node + 1, nu[1])],
                });
            }
        }
    }
    points
}

/// An orthonormal basis (as rows) of {c ∈ R³ : r·c = 0 for every row r}, by Gram–Schmidt
/// elimination of the rows from the canonical basis.
fn null_space_3(rows: &[[f64; 3]]) -> Vec<[f64; 3]> {
    // Orthonormal basis of the row space.
    let mut basis: Vec<[f64; 3]> = Vec::new();
    let scale = rows
        .iter()
        .map(|r| r.iter().map(|v| v.abs()).fold(0.0, f64::max))
        .fold(1.0, f64::max);
    for r in rows {
        let mut v = *r;
        for b in &basis {
            let d = v[0] * b[0] + v[1] * b[1] + v[2] * b[2];
            for k in 0..3 {
                v[k] -= d * b[k];
            }
        }
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 1e-9 * scale {
            basis.push([v[0] / n, v[1] / n, v[2] / n]);
            if basis.len() == 3 {
                break;
            }
        }
    }
    let mut null = Vec::new();
    for e in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
        let mut v: [f64; 3] = e;
        for b in basis.iter().chain(null.iter()) {
            let d = v[0] * b[0] + v[1] * b[1] + v[2] * b[2];
            for k in 0..3 {
                v[k] -= d * b[k];
            }
        }
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 1e-6 && basis.len() + null.len() < 3 {
            null.push([v[0] / n, v[1] / n, v[2] / n]);
        }
    }
    null
}

/// Makes the modes orthogonal (Gram–Schmidt) and scales each to a largest nodal component of 1, so
/// that a mode is a unit motion (a unit translation, or a rotation whose farthest node moves by 1)
/// and Rᵀ b is the load on it in force units.
fn orthonormalize(modes: &mut [Vec<f64>]) {
    for j in 0..modes.len() {
        for i in 0..j {
            let ii: f64 = modes[i].iter().map(|v| v * v).sum();
            let d: f64 = modes[j]
                .iter()
                .zip(&modes[i])
                .map(|(a, b)| a * b)
                .sum::<f64>()
                / ii;
            let mi = modes[i].clone();
            for (x, y) in modes[j].iter_mut().zip(&mi) {
                *x -= d * y;
            }
        }
        let n = modes[j].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        modes[j].iter_mut().for_each(|v| *v /= n);
    }
}

#[cfg(test)]
mod tests {
    //! Plane dofs: Γ1 readings fix the right components; rollers on the sides leave exactly the
    //! vertical translation free and fix it through one Γ3 dof; contact weights integrate the
    //! boundary length; the load of a constant traction is exact.
    use super::*;
    use crate::model::quasistatic::plane::Support;
    use crate::model::quasistatic::plane::Test2dParams;

    /// Test 2D on 4 × 4 squares with the constant traction f2 = (0, −10) on the top (resultant
    /// −60 over the side of length 6).
    fn problem(support: Support, integration: ContactIntegration) -> PlaneProblem {
        let mut p = PlaneProblem::fernandez_sofonea_test_2d(Test2dParams {
            divisions: 4,
            support,
            integration,
            ..Default::default()
        })
        .unwrap();
        p.traction[0].traction = [Field::Constant(0.0), Field::Constant(-10.0)];
        p
    }

    #[test]
    fn clamped_sides_leave_no_rigid_motion() {
        let p = problem(Support::Clamped, ContactIntegration::Gauss2);
        let d = PlaneDofs::new(&p, p.validate().unwrap()).unwrap();
        assert!(d.rigid_modes.is_empty());
        // 25 nodes, 10 on the sides: 15 free nodes
        assert_eq!(d.n_solved(), 30);
        // bottom nodes without the two corners
        assert_eq!(d.contact_dofs.len(), 6);
    }

    #[test]
    fn rollers_leave_the_vertical_translation_free() {
        let p = problem(Support::FixX, ContactIntegration::Gauss2);
        let d = PlaneDofs::new(&p, p.validate().unwrap()).unwrap();
        assert_eq!(d.rigid_modes.len(), 1);
        let m = &d.rigid_modes[0];
        assert!(m.iter().step_by(2).all(|v| v.abs() < 1e-12));
        assert_eq!(d.fixing_dofs.len(), 1);
        assert_eq!(d.fixing_dofs[0] % 2, 1);
    }

    #[test]
    fn contact_weights_integrate_the_length_for_both_rules() {
        for rule in [ContactIntegration::Gauss2, ContactIntegration::Nodal] {
            let p = problem(Support::Clamped, rule);
            let d = PlaneDofs::new(&p, p.validate().unwrap()).unwrap();
            let total: f64 = d.contact_points.iter().map(|c| c.weight).sum();
            assert!((total - 6.0).abs() < 1e-12);
            assert!(d
                .contact_points
                .iter()
                .all(|c| (c.normal[1] + 1.0).abs() < 1e-12));
        }
    }

    #[test]
    fn constant_traction_load_sums_to_the_resultant() {
        let p = problem(Support::Clamped, ContactIntegration::Gauss2);
        let d = PlaneDofs::new(&p, p.validate().unwrap()).unwrap();
        let mut f = vec![0.0; 2 * d.n_nodes];
        d.load_into(&p, 0.0, &|_| true, &mut f);
        let fy: f64 = f.iter().skip(1).step_by(2).sum();
        assert!((fy + 60.0).abs() < 1e-12);
    }
}
