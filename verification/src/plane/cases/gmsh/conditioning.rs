//! The scale of the round-off and perturbation bounds of `plane_gmsh`: the spectral condition
//! number of a step's operator, and the sensitivity of P1 stiffness entries to moved nodes.
//!
//! One step of the plane scheme solves (K_A + θ k K_B) u_n = … on the free dofs (θ = 0, 1, ½ for
//! the explicit, implicit and midpoint schemes; the foundation adds k β times a boundary mass, a
//! relative O(k β h) change of the spectrum, left out). A backward-stable solve of K u = f
//! errs by at most c ε κ(K) ‖u‖ (Higham, *Accuracy and Stability of Numerical Algorithms*, §7.1);
//! a relative perturbation η of K and f moves u by at most 2 κ η / (1 − κ η) ≈ 2 κ η ‖u‖. Errors
//! made in step n are carried to the end by the scheme, which is contractive in the energy norm:
//! over N steps they add at most N times.
//!
//! **Moved nodes.** With every node moved by at most δ, a triangle's area changes by at most
//! 3 δ ℓ_max/2 and its shape-function gradients (edges rotated, over twice the area) by at most
//! 2 δ/ℓ_min relative plus the area's change; for the right isosceles triangles of a square grid
//! (legs h, A = h²/2, ℓ_max = √2 h) the entries A ∇φ_a ∇φ_b of the element stiffness change by at
//! most (4.3 + 2 × 6.3) δ/h ≤ [`GEOMETRY_SENSITIVITY`] δ/h relative.
//!
//! κ is computed here, not estimated: the elements' stiffness with the problem's linear laws
//! assembled into a dense matrix on the free dofs (those the Dirichlet parts leave free),
//! eigenvalues by nalgebra's symmetric eigensolver. It is only the scale of a bound; the
//! evidence is the comparison the bound gates.

use nalgebra::{DMatrix, SymmetricEigen};

use contactlab::fem::triangle_p1::P1Triangle;
use contactlab::model::quasistatic::plane::PlaneProblem;

/// The relative change of a P1 stiffness entry per δ/h of moved nodes on a square grid (module
/// docs: 4.3 + 2 × 6.3 = 16.9).
pub const GEOMETRY_SENSITIVITY: f64 = 17.0;

/// The dense limit: larger problems are refused (the case's meshes have a few hundred dofs).
const DENSE_LIMIT: usize = 3000;

/// Per dof (2i, 2i + 1 for node i): whether a Dirichlet part of `problem` fixes it.
pub fn fixed_dofs(problem: &PlaneProblem) -> Vec<bool> {
    let mesh = &problem.mesh;
    let mut fixed = vec![false; 2 * mesh.nodes().len()];
    for part in &problem.dirichlet {
        for (e, edge) in mesh.boundary().iter().enumerate() {
            if part.boundary.contains(mesh, e) {
                for node in edge.nodes {
                    for c in 0..2 {
                        if part.support.fixes(c) {
                            fixed[2 * node + c] = true;
                        }
                    }
                }
            }
        }
    }
    fixed
}

/// κ₂(K_A + θ k K_B) on the free dofs of a problem with linear A and B.
pub fn step_condition_number(problem: &PlaneProblem, theta_k: f64) -> Result<f64, String> {
    let mesh = &problem.mesh;
    let fixed = fixed_dofs(problem);
    let mut index = vec![usize::MAX; fixed.len()];
    let mut n = 0;
    for (d, &f) in fixed.iter().enumerate() {
        if !f {
            index[d] = n;
            n += 1;
        }
    }
    if n == 0 || n > DENSE_LIMIT {
        return Err(format!("{n} free dofs: expected 1 to {DENSE_LIMIT}"));
    }
    let mut k = DMatrix::<f64>::zeros(n, n);
    for (e, tri) in mesh.triangles().iter().enumerate() {
        let (Some(a), Some(b)) = (
            problem.viscosity_of(e).as_linear().copied(),
            problem.elasticity_of(e).as_linear().copied(),
        ) else {
            return Err(format!(
                "triangle {e}: a nonlinear law (κ needs linear A and B)"
            ));
        };
        let geometry = P1Triangle::new(tri.map(|v| mesh.nodes()[v]));
        let ke = geometry.stiffness(|s| {
            let (sa, sb) = (a.apply(s), b.apply(s));
            [0, 1, 2].map(|c| sa[c] + theta_k * sb[c])
        });
        for p in 0..6 {
            let gp = index[2 * tri[p / 2] + p % 2];
            if gp == usize::MAX {
                continue;
            }
            for q in 0..6 {
                let gq = index[2 * tri[q / 2] + q % 2];
                if gq != usize::MAX {
                    k[(gp, gq)] += ke[(p, q)];
                }
            }
        }
    }
    let eig = SymmetricEigen::new(k).eigenvalues;
    let (low, high) = eig
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), &v| (l.min(v), h.max(v)));
    if low.is_nan() || low <= 0.0 {
        return Err(format!(
            "the step operator is not positive definite (smallest eigenvalue {low:e})"
        ));
    }
    Ok(high / low)
}

#[cfg(test)]
mod tests {
    //! The condition number on a clamped square grows like n² (the P1 stiffness's κ ~ (L/h)²):
    //! halving h multiplies it by about 4; the fixed dofs are those of the clamped side.
    use super::*;
    use crate::manufactured::plane::PlaneManufactured;
    use contactlab::model::quasistatic::plane::ContactIntegration;

    #[test]
    fn the_condition_number_grows_like_n_squared() {
        let m = PlaneManufactured::linear_switching();
        let kappa = |n: usize| {
            let p = m.problem(n, ContactIntegration::Gauss2).expect("problem");
            assert_eq!(fixed_dofs(&p).iter().filter(|&&f| f).count(), 2 * (n + 1));
            step_condition_number(&p, 0.01).expect("κ")
        };
        let ratio = kappa(8) / kappa(4);
        assert!((3.0..5.0).contains(&ratio), "{ratio}");
    }
}
