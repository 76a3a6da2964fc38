//! A manufactured solution of plane-strain elastodynamics with persistent normal-compliance
//! contact (Barboteu–Danan–Sofonea, "BDS", (1.14)–(1.18) with the compliance (1.8) and no
//! friction), for the time and space rates of the dynamic solver.
//!
//! Ω = (0, 1)², Γ1 = the top side (clamped), Γ2 = the left and right sides (tractions), Γ3 = the
//! bottom side, above the foundation {x2 ≤ 0}. One closure u(x, y, t) (generic over dual
//! numbers), with
//!
//!   u_x = 0.04 (1 − y) [sin(πx) cos(2πt) + x y sin(2πt)],
//!   u_y = −(1 − y) a(x, t) + 0.02 (1 − y) y sin(2πx) cos(πt),
//!   a(x, t) = 0.06 + 0.03 sin(2πt + 0.5) + 0.015 cos(πx) sin(3πt),
//!
//! vanishes on Γ1 (the factor 1 − y) and keeps Γ3 in persistent contact: the penetration
//! p(x, t) = 0 − u_y(x, 0, t) = a(x, t) ≥ 0.015 > 0 for all x and t. The data that make u exact
//! are derived by automatic differentiation (num-dual):
//!
//!   f0 = ρ ü − Div Π(F)                     in Ω          (BDS (1.15)),
//!   f2 = Π ν                                 on Γ2         (BDS (1.17)),
//!   g  = Π ν − r p(u) e_y,  ν = (0, −1)      on Γ3,
//!
//! so that Π ν = g + r p e_y on Γ3: the traction g (added to the Γ3 edges as a load) plus the
//! normal-compliance force r p_+ (BDS (1.8)) of the foundation, whose outward normal is e_y. The
//! solver applies the compliance nodally (weights w_i = half the adjacent Γ3 edge lengths): the
//! trapezoidal rule for ∫_Γ3 r p_h φ_i, a quadrature whose consistency error is O(h²) (it does not
//! limit the P1 rates), while g is integrated by Gauss on the edges.
//!
//! Div Π_i = Σ_k ∂_k Π_ik(F(x)) = Σ_k [∂Π/∂F : ∂_k F]_ik is obtained by evaluating Π on dual
//! numbers F + ε ∂_k F, where F and ∂_k F come from hyper-dual evaluations of u in the directions
//! (x, x), (x, y), (y, y); ü from a hyper-dual evaluation in (t, t). Π is written here a second
//! time, independently of the solver's laws, for each plane-strain law:
//!
//! - linear: Π = λ tr ε I + 2μ ε, ε = sym(F − I);
//! - St Venant–Kirchhoff: Π = F (λ tr E I + 2μ E), E = (FᵀF − I)/2;
//! - neo-Hooke: Π = μ (F − F⁻ᵀ) + λ ln J F⁻ᵀ, J = det F.

use std::cell::RefCell;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::sync::Arc;

use num_dual::{Dual64, DualNum, HyperDual64, HyperHyperDual64};
use serde::{Deserialize, Serialize};

use contactlab::field::{Dependence, Field};
use contactlab::material::hyperelastic::{
    Hyperelastic2d, LinearElastic, NeoHooke, StVenantKirchhoff,
};
use contactlab::mesh::triangle::{Diagonal, RectangleSide, TriangleMesh};
use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};
use contactlab::model::quasistatic::plane::{
    BoundarySelector, DirichletPart, Support, TractionPart,
};

/// A 2 × 2 matrix as rows.
pub type Mat2<D> = [[D; 2]; 2];

/// The plane-strain law of the manufactured solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ManufacturedLaw {
    Linear,
    StVenantKirchhoff,
    NeoHooke,
}

impl ManufacturedLaw {
    /// The law's name as written in case files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Linear => "linear",
            Self::StVenantKirchhoff => "st_venant_kirchhoff",
            Self::NeoHooke => "neo_hooke",
        }
    }

    /// Π(F) on any (dual) number type, written independently of the solver's laws.
    pub fn piola<D: DualNum<Primitive = f64> + Copy>(
        self,
        lambda: f64,
        mu: f64,
        f: Mat2<D>,
    ) -> Mat2<D> {
        match self {
            Self::Linear => {
                let e = [
                    [f[0][0] - 1.0, (f[0][1] + f[1][0]) * 0.5],
                    [(f[0][1] + f[1][0]) * 0.5, f[1][1] - 1.0],
                ];
                let tr = (e[0][0] + e[1][1]) * lambda;
                [
                    [tr + e[0][0] * (2.0 * mu), e[0][1] * (2.0 * mu)],
                    [e[1][0] * (2.0 * mu), tr + e[1][1] * (2.0 * mu)],
                ]
            }
            Self::StVenantKirchhoff => {
                // E = (FᵀF − I)/2, S = λ tr E I + 2μ E, Π = F S
                let c = |i: usize, j: usize| f[0][i] * f[0][j] + f[1][i] * f[1][j];
                let e = [
                    [(c(0, 0) - 1.0) * 0.5, c(0, 1) * 0.5],
                    [c(1, 0) * 0.5, (c(1, 1) - 1.0) * 0.5],
                ];
                let tr = (e[0][0] + e[1][1]) * lambda;
                let s = [
                    [tr + e[0][0] * (2.0 * mu), e[0][1] * (2.0 * mu)],
                    [e[1][0] * (2.0 * mu), tr + e[1][1] * (2.0 * mu)],
                ];
                let mut p = [[D::from(0.0); 2]; 2];
                for (i, row) in p.iter_mut().enumerate() {
                    for (j, v) in row.iter_mut().enumerate() {
                        *v = f[i][0] * s[0][j] + f[i][1] * s[1][j];
                    }
                }
                p
            }
            Self::NeoHooke => {
                let j = f[0][0] * f[1][1] - f[0][1] * f[1][0];
                // F⁻ᵀ = cof F / J
                let inv_t = [[f[1][1] / j, -f[1][0] / j], [-f[0][1] / j, f[0][0] / j]];
                let ln_j = j.ln() * lambda;
                let mut p = [[D::from(0.0); 2]; 2];
                for (a, row) in p.iter_mut().enumerate() {
                    for (b, v) in row.iter_mut().enumerate() {
                        *v = (f[a][b] - inv_t[a][b]) * mu + inv_t[a][b] * ln_j;
                    }
                }
                p
            }
        }
    }

    /// The solver's law with the same Lamé constants.
    pub fn solver_law(self, lambda: f64, mu: f64) -> Result<Arc<dyn Hyperelastic2d>, String> {
        let e = |e: contactlab::error::InputError| e.to_string();
        Ok(match self {
            Self::Linear => Arc::new(LinearElastic::from_lame(lambda, mu).map_err(e)?),
            Self::StVenantKirchhoff => {
                Arc::new(StVenantKirchhoff::from_lame(lambda, mu).map_err(e)?)
            }
            Self::NeoHooke => Arc::new(NeoHooke::from_lame(lambda, mu).map_err(e)?),
        })
    }
}

/// Which exact displacement: the smooth field of the module documentation, or the affine one of
/// the time study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ManufacturedField {
    /// u of the module documentation: P1 does not represent it (space error O(h) / O(h²)).
    #[default]
    Smooth,
    /// u = (1 − y) (b(t), −a(t)), b = 0.04 sin(2πt), a = 0.06 + 0.03 sin(2πt + 0.5) +
    /// 0.015 sin(3πt): affine in space, so F is uniform, Div Π = 0 for every law and f0 = ρ ü is
    /// affine; the consistent mass, the degree-2 load quadrature and the nodal compliance (p = a(t)
    /// is uniform along Γ3, so w_i r p = ∫ r p φ_i) make the nodal interpolant of u the exact
    /// solution of the semi-discrete equations. A run's error against u(T) is then its time error
    /// alone (docs/dynamic.md §3).
    Affine,
}

impl ManufacturedField {
    /// The name as written in case files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Smooth => "smooth",
            Self::Affine => "affine",
        }
    }

    /// u(x, y, t) of this field, on any (dual) number type.
    pub fn displacement<D: DualNum<Primitive = f64> + Copy>(self, x: D, y: D, t: D) -> [D; 2] {
        match self {
            Self::Smooth => displacement(x, y, t),
            Self::Affine => affine_displacement(y, t),
        }
    }
}

/// The affine exact displacement of [`ManufacturedField::Affine`].
pub fn affine_displacement<D: DualNum<Primitive = f64> + Copy>(y: D, t: D) -> [D; 2] {
    let s = -y + 1.0;
    let b = (t * (2.0 * PI)).sin() * 0.04;
    let a = (t * (2.0 * PI) + 0.5).sin() * 0.03 + (t * (3.0 * PI)).sin() * 0.015 + 0.06;
    [s * b, -(s * a)]
}

/// The exact displacement (see the module documentation), on any (dual) number type.
pub fn displacement<D: DualNum<Primitive = f64> + Copy>(x: D, y: D, t: D) -> [D; 2] {
    let s = -y + 1.0;
    let a = (t * (2.0 * PI) + 0.5).sin() * 0.03
        + (x * PI).cos() * (t * (3.0 * PI)).sin() * 0.015
        + 0.06;
    let ux = s * ((x * PI).sin() * (t * (2.0 * PI)).cos() + x * y * (t * (2.0 * PI)).sin()) * 0.04;
    let uy = -(s * a) + s * y * (x * (2.0 * PI)).sin() * (t * PI).cos() * 0.02;
    [ux, uy]
}

/// The smallest exact penetration on Γ3 over all x and t (both fields): a ≥ 0.06 − 0.03 − 0.015.
pub const MIN_EXACT_PENETRATION: f64 = 0.015;

/// u, ∇u (rows: components) and u̇ at a point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Jet {
    pub u: [f64; 2],
    pub grad: Mat2<f64>,
    pub velocity: [f64; 2],
}

impl Jet {
    /// ε(u) as (ε11, ε22, ε12).
    pub fn strain(&self) -> [f64; 3] {
        [
            self.grad[0][0],
            self.grad[1][1],
            0.5 * (self.grad[0][1] + self.grad[1][0]),
        ]
    }
}

/// u, ∇u and u̇ of the smooth field (see [`jet_of`]).
pub fn jet(x: f64, y: f64, t: f64) -> Jet {
    jet_of(ManufacturedField::Smooth, x, y, t)
}

/// u, ∇u and u̇ from one hyper-hyper-dual evaluation (x → ε1, y → ε2, t → ε3).
pub fn jet_of(field: ManufacturedField, x: f64, y: f64, t: f64) -> Jet {
    type H = HyperHyperDual64;
    let r = field.displacement(
        H::from_re(x).derivative1(),
        H::from_re(y).derivative2(),
        H::from_re(t).derivative3(),
    );
    Jet {
        u: [r[0].re, r[1].re],
        grad: [[r[0].eps1, r[0].eps2], [r[1].eps1, r[1].eps2]],
        velocity: [r[0].eps3, r[1].eps3],
    }
}

/// F, ∂_x F, ∂_y F and ü at a point (four hyper-dual evaluations).
fn second_derivatives(
    field: ManufacturedField,
    x: f64,
    y: f64,
    t: f64,
) -> (Mat2<f64>, [Mat2<f64>; 2], [f64; 2]) {
    type H = HyperDual64;
    let both = |v: f64| H::new(v, 1.0, 1.0, 0.0);
    let u = |x: H, y: H, t: H| field.displacement(x, y, t);
    let xx = u(both(x), H::from_re(y), H::from_re(t));
    let yy = u(H::from_re(x), both(y), H::from_re(t));
    let xy = u(
        H::from_re(x).derivative1(),
        H::from_re(y).derivative2(),
        H::from_re(t),
    );
    let tt = u(H::from_re(x), H::from_re(y), both(t));
    let mut f = [[0.0; 2]; 2];
    let mut df = [[[0.0; 2]; 2]; 2];
    for i in 0..2 {
        f[i] = [xy[i].eps1, xy[i].eps2];
        f[i][i] += 1.0;
        // ∂_x F_i· = (u_i,xx, u_i,xy), ∂_y F_i· = (u_i,xy, u_i,yy)
        df[0][i] = [xx[i].eps1eps2, xy[i].eps1eps2];
        df[1][i] = [xy[i].eps1eps2, yy[i].eps1eps2];
    }
    (f, df, [tt[0].eps1eps2, tt[1].eps1eps2])
}

/// Which side of the square a traction is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    Left,
    Right,
    Bottom,
}

impl Side {
    fn normal(self) -> [f64; 2] {
        match self {
            Side::Left => [-1.0, 0.0],
            Side::Right => [1.0, 0.0],
            Side::Bottom => [0.0, -1.0],
        }
    }
}

/// (Π, f0) of the points evaluated on this thread at one (solution, time): the solver's load
/// assembly asks for both components of a vector field at each point, and every interior edge
/// midpoint twice (once per triangle); each point costs four hyper-dual evaluations of u and
/// three of Π. The map is emptied when the solution or the time changes.
#[derive(Default)]
struct PointCache {
    key: (u64, u64),
    points: HashMap<(u64, u64), (Mat2<f64>, [f64; 2])>,
}

thread_local! {
    static CACHE: RefCell<PointCache> = RefCell::new(PointCache::default());
}

/// The manufactured problem: law, constants and the compliance of the foundation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DynamicManufactured {
    pub law: ManufacturedLaw,
    pub lambda: f64,
    pub mu: f64,
    pub density: f64,
    /// r of the normal compliance r p_+ (BDS (1.8)).
    pub stiffness: f64,
    pub final_time: f64,
    /// The exact displacement.
    pub field: ManufacturedField,
}

impl DynamicManufactured {
    /// E = 10, ν = 0.3 (plane strain: λ = 5.769…, μ = 3.846…), ρ = 1, r = 20, T = 1: the inertia
    /// ρ ü (~2.4), the stresses (~1) and the contact pressure r p (0.3 … 2.1) are of one size,
    /// and the strains (up to ~0.11) make the neo-Hookean and St Venant–Kirchhoff laws visibly
    /// nonlinear.
    pub fn standard(law: ManufacturedLaw) -> Self {
        let (young, poisson): (f64, f64) = (10.0, 0.3);
        Self {
            law,
            lambda: young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)),
            mu: young / (2.0 * (1.0 + poisson)),
            density: 1.0,
            stiffness: 20.0,
            final_time: 1.0,
            field: ManufacturedField::Smooth,
        }
    }

    /// The same problem with the exact displacement `field`.
    pub fn with_field(self, field: ManufacturedField) -> Self {
        Self { field, ..self }
    }

    fn id(&self) -> u64 {
        let law = match self.law {
            ManufacturedLaw::Linear => 1,
            ManufacturedLaw::StVenantKirchhoff => 2,
            ManufacturedLaw::NeoHooke => 3,
        };
        match self.field {
            ManufacturedField::Smooth => law,
            ManufacturedField::Affine => 10 + law,
        }
    }

    /// Π(F(x, y, t)).
    pub fn piola(&self, x: f64, y: f64, t: f64) -> Mat2<f64> {
        self.point(x, y, t).0
    }

    /// f0 = ρ ü − Div Π at (x, y, t).
    pub fn body_force(&self, x: f64, y: f64, t: f64) -> [f64; 2] {
        self.point(x, y, t).1
    }

    /// (Π, f0), cached per thread for the last point.
    fn point(&self, x: f64, y: f64, t: f64) -> (Mat2<f64>, [f64; 2]) {
        let key = (self.id(), t.to_bits());
        let point = (x.to_bits(), y.to_bits());
        let hit = CACHE.with(|c| {
            let mut c = c.borrow_mut();
            if c.key != key {
                c.key = key;
                c.points.clear();
            }
            c.points.get(&point).copied()
        });
        if let Some(v) = hit {
            return v;
        }
        let (f, df, acc) = second_derivatives(self.field, x, y, t);
        let p = self.law.piola(self.lambda, self.mu, f);
        // ∂_k Π from Π(F + ε ∂_k F)
        let dp: [Mat2<f64>; 2] = std::array::from_fn(|k| {
            let fd: Mat2<Dual64> =
                std::array::from_fn(|i| std::array::from_fn(|j| Dual64::new(f[i][j], df[k][i][j])));
            let pd = self.law.piola(self.lambda, self.mu, fd);
            std::array::from_fn(|i| std::array::from_fn(|j| pd[i][j].eps))
        });
        let div = [dp[0][0][0] + dp[1][0][1], dp[0][1][0] + dp[1][1][1]];
        let f0 = [
            self.density * acc[0] - div[0],
            self.density * acc[1] - div[1],
        ];
        CACHE.with(|c| c.borrow_mut().points.insert(point, (p, f0)));
        (p, f0)
    }

    /// The penetration p = 0 − u_y(x, 0, t) on Γ3.
    pub fn penetration(&self, x: f64, t: f64) -> f64 {
        -self.field.displacement(x, 0.0, t)[1]
    }

    /// The load on `side`: Π ν on Γ2; Π ν − r p_+ e_y on Γ3.
    pub fn traction(&self, side: Side, x: f64, y: f64, t: f64) -> [f64; 2] {
        let p = self.piola(x, y, t);
        let n = side.normal();
        let mut g = [
            p[0][0] * n[0] + p[0][1] * n[1],
            p[1][0] * n[0] + p[1][1] * n[1],
        ];
        if side == Side::Bottom {
            g[1] -= self.stiffness * self.penetration(x, t).max(0.0);
        }
        g
    }

    fn vector_field(
        &self,
        value: impl Fn(&Self, f64, f64, f64, usize) -> f64 + Copy + Send + Sync + 'static,
    ) -> [Field; 2] {
        let all = Dependence {
            x: true,
            y: true,
            t: true,
        };
        let me = *self;
        [0, 1].map(|c| Field::function(all, move |x, y, t| value(&me, x, y, t, c)))
    }

    /// The plane body on n × n squares of the unit square (diagonals up), with the body force,
    /// the Γ2 tractions, the Γ3 source g and the clamped top.
    pub fn body(&self, divisions: usize, mass: MassMatrix) -> Result<PlaneBody, String> {
        let mesh = TriangleMesh::rectangle([0.0, 0.0], [1.0, 1.0], [divisions; 2], Diagonal::Up)
            .map_err(|e| e.to_string())?;
        let traction = [
            (RectangleSide::Left, Side::Left),
            (RectangleSide::Right, Side::Right),
            (RectangleSide::Bottom, Side::Bottom),
        ]
        .into_iter()
        .map(|(rs, side)| TractionPart {
            boundary: BoundarySelector::side(rs),
            traction: self.vector_field(move |m, x, y, t, c| m.traction(side, x, y, t)[c]),
        })
        .collect();
        PlaneBody::new(PlaneBodyData {
            mesh,
            density: self.density,
            law: self.law.solver_law(self.lambda, self.mu)?,
            dirichlet: vec![DirichletPart {
                boundary: BoundarySelector::side(RectangleSide::Top),
                support: Support::Clamped,
            }],
            traction,
            body_force: self.vector_field(|m, x, y, t, c| m.body_force(x, y, t)[c]),
            mass,
            regions: Vec::new(),
        })
        .map_err(|e| e.to_string())
    }

    /// Interleaved nodal values (u_x, u_y per node) of u(·, t) (`velocity`: of u̇(·, t)).
    pub fn nodal(&self, nodes: &[[f64; 2]], t: f64, velocity: bool) -> Vec<f64> {
        nodes
            .iter()
            .flat_map(|p| {
                let j = jet_of(self.field, p[0], p[1], t);
                if velocity {
                    j.velocity
                } else {
                    j.u
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    //! The dynamic manufactured solution: u vanishes on Γ1 and keeps Γ3 penetrated; the AD source
    //! terms (ü, Div Π, f0, the tractions) agree with central finite differences of u and Π; the
    //! independent Π of each law agrees with the solver's law.
    use super::*;
    use nalgebra::Matrix2;

    const LAWS: [ManufacturedLaw; 3] = [
        ManufacturedLaw::Linear,
        ManufacturedLaw::StVenantKirchhoff,
        ManufacturedLaw::NeoHooke,
    ];

    #[test]
    fn closure_vanishes_on_the_clamped_top_and_gamma3_stays_penetrated() {
        let m = DynamicManufactured::standard(ManufacturedLaw::Linear);
        for i in 0..=20 {
            let x = i as f64 / 20.0;
            assert_eq!(displacement(x, 1.0, 0.37), [0.0, 0.0]);
            for n in 0..=200 {
                let t = n as f64 / 200.0;
                assert!(m.penetration(x, t) >= MIN_EXACT_PENETRATION - 1e-15);
            }
        }
    }

    #[test]
    fn acceleration_and_divergence_match_central_differences() {
        let h = 1e-4;
        for law in LAWS {
            let m = DynamicManufactured::standard(law);
            for &(x, y, t) in &[(0.3, 0.6, 0.2), (0.8, 0.1, 0.7), (0.05, 0.95, 0.99)] {
                let u = |t: f64| displacement(x, y, t);
                let acc: Vec<f64> = (0..2)
                    .map(|c| (u(t + h)[c] - 2.0 * u(t)[c] + u(t - h)[c]) / (h * h))
                    .collect();
                let px = |d: f64| m.piola(x + d, y, t);
                let py = |d: f64| m.piola(x, y + d, t);
                let div: Vec<f64> = (0..2)
                    .map(|i| {
                        (px(h)[i][0] - px(-h)[i][0]) / (2.0 * h)
                            + (py(h)[i][1] - py(-h)[i][1]) / (2.0 * h)
                    })
                    .collect();
                let f0 = m.body_force(x, y, t);
                for c in 0..2 {
                    let fd = m.density * acc[c] - div[c];
                    assert!(
                        (fd - f0[c]).abs() < 2e-5 * (1.0 + f0[c].abs()),
                        "{law:?} f0[{c}] = {} vs FD {fd}",
                        f0[c]
                    );
                }
            }
        }
    }

    #[test]
    fn jet_matches_central_differences() {
        let (x, y, t, h) = (0.41, 0.27, 0.63, 1e-6);
        let j = jet(x, y, t);
        for c in 0..2 {
            let dx = (displacement(x + h, y, t)[c] - displacement(x - h, y, t)[c]) / (2.0 * h);
            let dy = (displacement(x, y + h, t)[c] - displacement(x, y - h, t)[c]) / (2.0 * h);
            let dt = (displacement(x, y, t + h)[c] - displacement(x, y, t - h)[c]) / (2.0 * h);
            assert!((dx - j.grad[c][0]).abs() < 1e-8);
            assert!((dy - j.grad[c][1]).abs() < 1e-8);
            assert!((dt - j.velocity[c]).abs() < 1e-8);
        }
    }

    #[test]
    fn independent_piola_agrees_with_the_solver_laws() {
        let m = DynamicManufactured::standard(ManufacturedLaw::Linear);
        let f = [[1.07, -0.04], [0.09, 0.93]];
        for law in LAWS {
            let ours = law.piola(m.lambda, m.mu, f);
            let theirs = law
                .solver_law(m.lambda, m.mu)
                .unwrap()
                .piola(&Matrix2::new(f[0][0], f[0][1], f[1][0], f[1][1]));
            for i in 0..2 {
                for j in 0..2 {
                    assert!((ours[i][j] - theirs[(i, j)]).abs() < 1e-12, "{law:?}");
                }
            }
        }
    }

    #[test]
    fn gamma3_source_plus_compliance_is_the_exact_traction() {
        let m = DynamicManufactured::standard(ManufacturedLaw::NeoHooke);
        let (x, t) = (0.37, 0.61);
        let g = m.traction(Side::Bottom, x, 0.0, t);
        let p = m.piola(x, 0.0, t);
        // Π ν with ν = (0, −1) = g + r p e_y
        assert!((-p[0][1] - g[0]).abs() < 1e-14);
        assert!((-p[1][1] - (g[1] + m.stiffness * m.penetration(x, t))).abs() < 1e-13);
    }
}
