//! The elastic body of a dynamic problem after space discretization (P1 elements): its free dofs,
//! mass matrix, stored energy, internal forces with their tangents, the Gonzalez discrete-gradient
//! forces, and external loads.
//!
//! Semi-discrete equations (Barboteu–Danan–Sofonea, "BDS", (1.15)–(1.17) in P1 form):
//!
//!   M ü + F_int(u) = f(t) + ξ(u),   F_int(u) = ∇_u 𝒲(u),   𝒲(u) = Σ_e |e| W(F_e(u)),
//!
//! with M the consistent (or lumped) mass, W the stored-energy density, f the body forces and
//! tractions, and ξ the contact forces of the foundation.

use std::fmt::Debug;

use crate::fem::sparse::SymmetricPattern;

/// The free dofs of a body: the index among the free dofs of each nodal value (the value of a
/// node, or one component of it), `None` where a support holds it at zero.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FreeDofs {
    index: Vec<Option<usize>>,
    count: usize,
}

impl FreeDofs {
    /// Numbers the nodal values in order, skipping those that `held` marks as held at zero.
    pub fn number(held: impl IntoIterator<Item = bool>) -> Self {
        let mut count = 0;
        let index = held
            .into_iter()
            .map(|h| {
                (!h).then(|| {
                    count += 1;
                    count - 1
                })
            })
            .collect();
        Self { index, count }
    }

    /// The number of free dofs.
    pub fn count(&self) -> usize {
        self.count
    }

    /// The free dof of nodal value `i` (`None` where held).
    pub fn of(&self, i: usize) -> Option<usize> {
        self.index[i]
    }

    /// The nodal values of the free-dof vector `u` (0 where held).
    pub fn nodal(&self, u: &[f64]) -> Vec<f64> {
        self.index.iter().map(|d| d.map_or(0.0, |d| u[d])).collect()
    }

    /// The free-dof vector of the nodal `values` (the held ones dropped).
    pub fn from_nodal(&self, values: &[f64]) -> Vec<f64> {
        let mut u = vec![0.0; self.count];
        for (i, d) in self.index.iter().enumerate() {
            if let Some(d) = d {
                u[*d] = values[i];
            }
        }
        u
    }
}

/// What every body assembles on its free dofs: the sparsity pattern shared by the mass and the
/// tangent stiffness, the mass values and, for a small-strain law, the constant stiffness.
#[derive(Debug, Clone)]
pub struct Operators {
    pub dofs: FreeDofs,
    pub pattern: SymmetricPattern,
    pub mass: Vec<f64>,
    pub stiffness: Option<Vec<f64>>,
}

/// K_T(0) of `body` (values on its pattern): the constant stiffness when its law is small-strain.
pub fn stiffness_at_rest(body: &dyn ElasticBody) -> Vec<f64> {
    let mut k = vec![0.0; body.pattern().nnz()];
    body.add_tangent(&vec![0.0; body.dofs()], 1.0, &mut k);
    k
}

/// A space-discretized elastic body. Vectors hold the free dofs only (Γ1 dofs are held at zero).
pub trait ElasticBody: Send + Sync + Debug {
    /// The free dofs and the operators assembled on them.
    fn operators(&self) -> &Operators;

    /// Number of free dofs.
    fn dofs(&self) -> usize {
        self.operators().dofs.count()
    }

    /// The sparsity pattern shared by the mass and the tangent stiffness.
    fn pattern(&self) -> &SymmetricPattern {
        &self.operators().pattern
    }

    /// The mass matrix (values on [`ElasticBody::pattern`]).
    fn mass(&self) -> &[f64] {
        &self.operators().mass
    }

    /// Whether F_int is linear (small-strain law): then the stiffness is constant and a step
    /// operator is factored once.
    fn is_linear(&self) -> bool {
        self.operators().stiffness.is_some()
    }

    /// The constant stiffness K (values on the pattern) of a linear body.
    fn linear_stiffness(&self) -> Option<&[f64]> {
        self.operators().stiffness.as_deref()
    }

    /// 𝒲(u) = Σ_e |e| W(F_e); +∞ for an inadmissible state (neo-Hooke with det F ≤ 0).
    fn stored_energy(&self, u: &[f64]) -> f64;

    /// F_int(u) into `f`; `false` (and `f` unspecified) for an inadmissible state.
    fn internal_force(&self, u: &[f64], f: &mut [f64]) -> bool;

    /// The round-off scale of each row of the internal force evaluated at the states `u0` and
    /// `u1` (F_int(u1) when they are equal, F^algo(u0, u1) otherwise), into `out`:
    ///
    ///   a_i = Σ_e |e| m_e Σ_J |∂_J φ_a|,   m_e = ρ_e c_e² max over u0, u1 of
    ///   (|F_e|³ + |F_e| (1 + |ln J_e|)/J_e),
    ///
    /// (|F| the Frobenius norm, J = det F, ρ c² = λ + 2μ the longitudinal modulus at rest). The
    /// stress is computed from C = FᵀF, whose entries are of size |F|², so the strain
    /// E = (C − I)/2 carries an error ε |F|² whatever the load, the stress ε (λ + 2μ) |F|² and
    /// Π = F S one |F| more; a law with F⁻ᵀ in its stress (neo-Hooke: μ (F − F⁻ᵀ) + λ ln J F⁻ᵀ,
    /// |F⁻ᵀ| = |F|/J in 2D) carries ε (λ + 2μ) |F| (1 + |ln J|)/J, large in a strongly compressed
    /// element. m_e also bounds |Π_e| itself, so ε a_i bounds the round-off of row i of the
    /// assembled force up to the number of terms summed.
    fn internal_force_terms(&self, u0: &[f64], u1: &[f64], out: &mut [f64]);

    /// Adds `scale` · K_T(u) to `values` (on the pattern).
    fn add_tangent(&self, u: &[f64], scale: f64, values: &mut [f64]);

    /// The discrete-gradient force F^algo(u0, u1) = Σ_e |e| Π^algo(F_e(u0), F_e(u1)) : ∇φ (BDS
    /// (1.41)–(1.42)), with F^algo(u0, u1)·(u1 − u0) = 𝒲(u1) − 𝒲(u0) (BDS (1.43)); `false` for an
    /// inadmissible state.
    fn discrete_gradient_force(&self, u0: &[f64], u1: &[f64], f: &mut [f64]) -> bool;

    /// Adds `scale` · sym(∂F^algo/∂u1) (u0, u1) to `values`: the symmetric part of the exact
    /// derivative (a symmetric Newton tangent; the skew part is dropped).
    fn add_discrete_gradient_tangent(&self, u0: &[f64], u1: &[f64], scale: f64, values: &mut [f64]);

    /// Adds `scale` · skew(∂F^algo/∂u1) (u0, u1) = `scale` · (∂F^algo/∂u1 − (∂F^algo/∂u1)ᵀ)/2 to
    /// `values` (upper triangle W_ij, i < j, on the pattern; W_ji = −W_ij): with
    /// [`Self::add_discrete_gradient_tangent`] the exact derivative. Adds nothing for a body
    /// whose discrete-gradient tangent is symmetric (the bar: one strain component).
    fn add_discrete_gradient_skew(&self, u0: &[f64], u1: &[f64], scale: f64, values: &mut [f64]);

    /// The external load f(t) (body forces and tractions) into `out`.
    fn load_into(&self, t: f64, out: &mut [f64]);

    /// Whether the load depends on time.
    fn load_depends_on_time(&self) -> bool;

    /// Whether the load is identically zero.
    fn load_is_zero(&self) -> bool;

    /// The longitudinal wave speed c at rest.
    fn wave_speed(&self) -> f64;

    /// The smallest element size (for the wave-crossing time h_min / c).
    fn h_min(&self) -> f64;

    /// A short description of the body for reports.
    fn describe(&self) -> String;
}
