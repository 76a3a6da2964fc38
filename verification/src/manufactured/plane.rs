//! Manufactured solutions of the plane problem P (Fernández & Sofonea 2004, (2.1)–(2.6)).
//!
//! One closure u(x, y, t) (two components, on hyper-hyper-dual numbers) per solution. On
//! Ω = (0, 1)² with Γ1 the left side (clamped, u = 0 there), Γ2 the top and right sides and Γ3 the
//! bottom (ν = (0, −1)), the data that make u exact are
//!
//!   f0 = −Div σ,   f2 = σν on Γ2,   g = σν + p_ν(u̇_ν) ν on Γ3,
//!   σ = A(ε(u̇)) + B(ε(u)),   Div σ_i = Σ_k [T_A(ε(u̇)) ∂_k ε(u̇) + T_B(ε(u)) ∂_k ε(u)]_{ik},
//!
//! so that −σ_ν = p_ν(u̇_ν) − g_ν and σ_τ = g_τ on Γ3 (docs/quasistatic.md,
//! §Manufactured solutions). Derivatives come from three hyper-hyper-dual evaluations per point:
//! (x, x, t) gives u_x, u_xx, u_t, u_xt, u_xxt; (y, y, t) the same in y; (x, y, t) gives u_xy,
//! u_xyt. The error norms need only the first derivatives (one evaluation).

use std::sync::Arc;

use num_dual::{DualNum, HyperHyperDual64};

use contactlab::contact::normal_law::{FoundationLaw, NormalLaw, SpaceTime};
use contactlab::fem::triangle_p1::Sym2;
use contactlab::field::{Dependence, Field};
use contactlab::material::nonlinear::{SaturatingViscosity, SofteningElasticity};
use contactlab::material::plane_law::{IsotropicLinear, PlaneLaw};
use contactlab::mesh::triangle::{Diagonal, RectangleSide, TriangleMesh};
use contactlab::model::quasistatic::plane::{
    BoundarySelector, ContactIntegration, ContactPart, DirichletPart, PlaneProblem, Support,
    TractionPart,
};

type Hhd = HyperHyperDual64;

/// u(x, y, t) on hyper-hyper-dual numbers.
pub type PlaneClosure = fn(Hhd, Hhd, Hhd) -> [Hhd; 2];

/// The values and derivatives the errors need: u, ∂_j u_i, u̇, ∂_j u̇_i.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlaneJet {
    pub u: [f64; 2],
    pub du: [[f64; 2]; 2],
    pub ut: [f64; 2],
    pub dut: [[f64; 2]; 2],
}

impl PlaneJet {
    /// ε(u).
    pub fn strain(&self) -> Sym2 {
        [
            self.du[0][0],
            self.du[1][1],
            0.5 * (self.du[0][1] + self.du[1][0]),
        ]
    }
    /// ε(u̇).
    pub fn strain_rate(&self) -> Sym2 {
        [
            self.dut[0][0],
            self.dut[1][1],
            0.5 * (self.dut[0][1] + self.dut[1][0]),
        ]
    }
}

/// First derivatives by one evaluation with x → ε1, y → ε2, t → ε3.
pub fn plane_jet(u: PlaneClosure, x: f64, y: f64, t: f64) -> PlaneJet {
    let r = u(
        Hhd::from_re(x).derivative1(),
        Hhd::from_re(y).derivative2(),
        Hhd::from_re(t).derivative3(),
    );
    let mut j = PlaneJet::default();
    for i in 0..2 {
        j.u[i] = r[i].re;
        j.du[i] = [r[i].eps1, r[i].eps2];
        j.ut[i] = r[i].eps3;
        j.dut[i] = [r[i].eps1eps3, r[i].eps2eps3];
    }
    j
}

/// The jet and ∂_k ε(u), ∂_k ε(u̇) for k = x, y: three evaluations — (x, x, t) and (y, y, t)
/// for the pure second derivatives, (x, y, t) for the jet and the mixed ones.
fn jet_and_strain_gradients(
    u: PlaneClosure,
    x: f64,
    y: f64,
    t: f64,
) -> (PlaneJet, [Sym2; 2], [Sym2; 2]) {
    let xx = u(
        Hhd::new(x, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        Hhd::from_re(y),
        Hhd::from_re(t).derivative3(),
    );
    let yy = u(
        Hhd::from_re(x),
        Hhd::new(y, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        Hhd::from_re(t).derivative3(),
    );
    let xy = u(
        Hhd::from_re(x).derivative1(),
        Hhd::from_re(y).derivative2(),
        Hhd::from_re(t).derivative3(),
    );
    let mut j = PlaneJet::default();
    for i in 0..2 {
        j.u[i] = xy[i].re;
        j.du[i] = [xy[i].eps1, xy[i].eps2];
        j.ut[i] = xy[i].eps3;
        j.dut[i] = [xy[i].eps1eps3, xy[i].eps2eps3];
    }
    // second derivatives u_i,jk and their time derivatives
    let d2 = |i: usize, a: usize, b: usize| -> (f64, f64) {
        match (a, b) {
            (0, 0) => (xx[i].eps1eps2, xx[i].eps1eps2eps3),
            (1, 1) => (yy[i].eps1eps2, yy[i].eps1eps2eps3),
            _ => (xy[i].eps1eps2, xy[i].eps1eps2eps3),
        }
    };
    let mut de = [[0.0; 3]; 2];
    let mut det = [[0.0; 3]; 2];
    for k in 0..2 {
        let (u00, t00) = d2(0, 0, k);
        let (u11, t11) = d2(1, 1, k);
        let (u01, t01) = d2(0, 1, k);
        let (u10, t10) = d2(1, 0, k);
        de[k] = [u00, u11, 0.5 * (u01 + u10)];
        det[k] = [t00, t11, 0.5 * (t01 + t10)];
    }
    (j, de, det)
}

/// (key, σ, Div σ, u̇_ν) of the last point evaluated.
type PointCache = Option<([u64; 4], Sym2, [f64; 2], f64)>;

thread_local! {
    /// The last (solution, x, y, t) → (σ, Div σ, u̇_ν) evaluated on this thread: the load assembly
    /// asks for both components of a vector field at the same point one after the other, and
    /// each evaluation costs several hyper-hyper-dual passes.
    static LAST: std::cell::Cell<PointCache> = const { std::cell::Cell::new(None) };
}

/// A manufactured plane solution with its materials and foundation.
#[derive(Clone)]
pub struct PlaneManufactured {
    name: String,
    /// Distinguishes solutions in the per-thread evaluation cache.
    id: u64,
    pub final_time: f64,
    pub viscosity: Arc<dyn PlaneLaw>,
    pub elasticity: Arc<dyn PlaneLaw>,
    pub beta: f64,
    pub p0: f64,
    u: PlaneClosure,
}

impl std::fmt::Debug for PlaneManufactured {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "PlaneManufactured({})", self.name)
    }
}

/// u1 = x (0.1 sin(πy) + 0.2 t), u2 = x (−0.3 t + 0.1 sin(2πt) cos(πx/2)) − 0.05 x y t: u = 0 on
/// x = 0; on the bottom u̇_ν = −u̇2 = x (0.3 − 0.2π cos(2πt) cos(πx/2)) changes sign in x and t.
fn switching(x: Hhd, y: Hhd, t: Hhd) -> [Hhd; 2] {
    let pi = std::f64::consts::PI;
    let u1 = x * ((y * pi).sin() * 0.1 + t * 0.2);
    let u2 =
        x * (t * (-0.3) + (t * (2.0 * pi)).sin() * (x * (pi / 2.0)).cos() * 0.1) - x * y * t * 0.05;
    [u1, u2]
}

impl PlaneManufactured {
    fn with(
        id: u64,
        name: &str,
        viscosity: Arc<dyn PlaneLaw>,
        elasticity: Arc<dyn PlaneLaw>,
    ) -> Self {
        Self {
            name: name.to_string(),
            id,
            final_time: 1.0,
            viscosity,
            elasticity,
            beta: 5.0,
            p0: 1.0,
            u: switching,
        }
    }

    /// Linear Kelvin–Voigt in plane stress (A: μ = 3, η = 2; B: E = 10, κ = 0.3), damper β = 5,
    /// p0 = 1; u̇_ν changes sign on part of Γ3 during (0, T).
    pub fn linear_switching() -> Self {
        Self::with(
            1,
            "plane manufactured, linear, switching damper",
            Arc::new(IsotropicLinear::viscosity(3.0, 2.0)),
            Arc::new(IsotropicLinear::plane_stress(10.0, 0.3)),
        )
    }

    /// Nonlinear A (saturating viscosity μ = 3, η = 2, γ = 1, τ_c = 0.1) and B (softening
    /// elasticity λ = 5, G = 4, δ = 0.5, ε_c = 0.05), the same u.
    pub fn nonlinear() -> Self {
        Self::with(
            2,
            "plane manufactured, nonlinear A and B",
            Arc::new(SaturatingViscosity {
                mu: 3.0,
                eta: 2.0,
                gamma: 1.0,
                tau_c: 0.1,
            }),
            Arc::new(SofteningElasticity {
                lambda: 5.0,
                shear: 4.0,
                delta: 0.5,
                eps_c: 0.05,
            }),
        )
    }

    /// Plane strain (B: E = 10, κ = 0.3), the same u and A.
    pub fn plane_strain() -> Self {
        Self::with(
            3,
            "plane manufactured, plane strain",
            Arc::new(IsotropicLinear::viscosity(3.0, 2.0)),
            Arc::new(IsotropicLinear::plane_strain(10.0, 0.3)),
        )
    }

    /// By name (`plane_manufactured_linear`, `_nonlinear`, `_strain`).
    pub fn by_name(name: &str) -> Option<Self> {
        match name {
            "plane_manufactured_linear" => Some(Self::linear_switching()),
            "plane_manufactured_nonlinear" => Some(Self::nonlinear()),
            "plane_manufactured_strain" => Some(Self::plane_strain()),
            _ => None,
        }
    }

    /// The name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// u and its first derivatives.
    pub fn jet(&self, x: f64, y: f64, t: f64) -> PlaneJet {
        plane_jet(self.u, x, y, t)
    }

    /// σ(x, y, t).
    pub fn stress(&self, x: f64, y: f64, t: f64) -> Sym2 {
        let j = self.jet(x, y, t);
        let a = self.viscosity.stress(&j.strain_rate());
        let b = self.elasticity.stress(&j.strain());
        [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
    }

    /// (σ, Div σ, u̇_ν on the bottom side) at (x, y, t), cached per thread for the last point.
    fn point_data(&self, x: f64, y: f64, t: f64) -> (Sym2, [f64; 2], f64) {
        let key = [self.id, x.to_bits(), y.to_bits(), t.to_bits()];
        if let Some((k, s, d, un)) = LAST.with(|c| c.get()) {
            if k == key {
                return (s, d, un);
            }
        }
        let (j, de, det) = jet_and_strain_gradients(self.u, x, y, t);
        let (er, e) = (j.strain_rate(), j.strain());
        let a = self.viscosity.stress(&er);
        let b = self.elasticity.stress(&e);
        let s = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
        let ds: [Sym2; 2] = std::array::from_fn(|k| {
            let a = self.viscosity.tangent_apply(&er, &det[k]);
            let b = self.elasticity.tangent_apply(&e, &de[k]);
            [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
        });
        // Div σ_1 = ∂x σ11 + ∂y σ12, Div σ_2 = ∂x σ12 + ∂y σ22
        let d = [ds[0][0] + ds[1][2], ds[0][2] + ds[1][1]];
        let un = -j.ut[1];
        LAST.with(|c| c.set(Some((key, s, d, un))));
        (s, d, un)
    }

    /// Div σ at (x, y, t).
    pub fn div_stress(&self, x: f64, y: f64, t: f64) -> [f64; 2] {
        self.point_data(x, y, t).1
    }

    fn law(&self) -> FoundationLaw {
        FoundationLaw::Lubricated {
            beta: self.beta,
            p0: Field::Constant(self.p0),
        }
    }

    /// The problem on an n × n mesh of the unit square whose exact solution is u.
    pub fn problem(&self, divisions: usize, integration: ContactIntegration) -> PlaneProblem {
        let xyt = Dependence {
            x: true,
            y: true,
            t: true,
        };
        let me = self.clone();
        let body = [0, 1].map(|c| {
            let m = me.clone();
            Field::function(xyt, move |x, y, t| -m.point_data(x, y, t).1[c])
        });
        // Γ2: top (ν = (0, 1)) and right (ν = (1, 0)); one traction field each.
        let top = [0, 1].map(|c| {
            let m = me.clone();
            Field::function(xyt, move |x, y, t| {
                let s = m.point_data(x, y, t).0;
                // σν with ν = (0, 1): (σ12, σ22)
                if c == 0 {
                    s[2]
                } else {
                    s[1]
                }
            })
        });
        let right = [0, 1].map(|c| {
            let m = me.clone();
            Field::function(xyt, move |x, y, t| {
                let s = m.point_data(x, y, t).0;
                // ν = (1, 0): (σ11, σ12)
                if c == 0 {
                    s[0]
                } else {
                    s[2]
                }
            })
        });
        // Γ3 bottom, ν = (0, −1): g = σν + p_ν(u̇_ν) ν, u̇_ν = −u̇2.
        let law = self.law();
        let source = [0, 1].map(|c| {
            let m = me.clone();
            let law = law.clone();
            Field::function(xyt, move |x, y, t| {
                let (s, _, un) = m.point_data(x, y, t);
                let p = law.value(un, SpaceTime { x, y, t });
                if c == 0 {
                    -s[2]
                } else {
                    -s[1] - p
                }
            })
        });
        let u0 = [0, 1].map(|c| {
            let m = me.clone();
            Field::function(
                Dependence {
                    x: true,
                    y: true,
                    t: false,
                },
                move |x, y, _| m.jet(x, y, 0.0).u[c],
            )
        });
        PlaneProblem {
            mesh: TriangleMesh::rectangle(
                [0.0, 0.0],
                [1.0, 1.0],
                [divisions, divisions],
                Diagonal::Up,
            )
            .expect("a positive number of divisions"),
            final_time: self.final_time,
            viscosity: self.viscosity.clone(),
            elasticity: self.elasticity.clone(),
            body_force: body,
            dirichlet: vec![DirichletPart {
                boundary: BoundarySelector::side(RectangleSide::Left),
                support: Support::Clamped,
            }],
            traction: vec![
                TractionPart {
                    boundary: BoundarySelector::side(RectangleSide::Top),
                    traction: top,
                },
                TractionPart {
                    boundary: BoundarySelector::side(RectangleSide::Right),
                    traction: right,
                },
            ],
            contact: Some(ContactPart {
                boundary: BoundarySelector::side(RectangleSide::Bottom),
                law: Arc::new(law),
                integration,
                source: Some(source),
            }),
            initial_displacement: u0,
        }
    }
}

#[cfg(test)]
mod tests {
    //! Manufactured plane solutions: the closure vanishes on Γ1, Div σ from the tangents agrees
    //! with finite differences of σ, the data satisfy the boundary conditions, and u̇_ν changes
    //! sign on Γ3.
    use super::*;

    #[test]
    fn div_stress_matches_finite_differences_for_every_solution() {
        for m in [
            PlaneManufactured::linear_switching(),
            PlaneManufactured::nonlinear(),
            PlaneManufactured::plane_strain(),
        ] {
            for &(x, y, t) in &[(0.3, 0.6, 0.2), (0.8, 0.1, 0.7)] {
                let h = 1e-5;
                let sx = |dx: f64| m.stress(x + dx, y, t);
                let sy = |dy: f64| m.stress(x, y + dy, t);
                let ds_dx: Vec<f64> = (0..3).map(|c| (sx(h)[c] - sx(-h)[c]) / (2.0 * h)).collect();
                let ds_dy: Vec<f64> = (0..3).map(|c| (sy(h)[c] - sy(-h)[c]) / (2.0 * h)).collect();
                let fd = [ds_dx[0] + ds_dy[2], ds_dx[2] + ds_dy[1]];
                let d = m.div_stress(x, y, t);
                for c in 0..2 {
                    assert!(
                        (fd[c] - d[c]).abs() < 1e-6 * (1.0 + d[c].abs()),
                        "{}: {fd:?} vs {d:?}",
                        m.name()
                    );
                }
            }
        }
    }

    #[test]
    fn closure_vanishes_on_the_clamped_side_and_normal_velocity_changes_sign() {
        let m = PlaneManufactured::linear_switching();
        for &y in &[0.0, 0.3, 1.0] {
            let j = m.jet(0.0, y, 0.4);
            assert_eq!(j.u, [0.0, 0.0]);
        }
        let un = |x: f64, t: f64| -m.jet(x, 0.0, t).ut[1];
        assert!(un(0.2, 0.0) < 0.0 && un(0.9, 0.25) > 0.0);
    }

    #[test]
    fn contact_condition_holds_with_the_source() {
        let m = PlaneManufactured::nonlinear();
        let p = m.problem(4, ContactIntegration::Gauss2);
        let c = p.contact.as_ref().unwrap();
        let g = c.source.as_ref().unwrap();
        let (x, t) = (0.37, 0.61);
        let s = m.stress(x, 0.0, t);
        let j = m.jet(x, 0.0, t);
        let pn = c.law.value(-j.ut[1], SpaceTime { x, y: 0.0, t });
        // −σ_ν = p − g_ν with σ_ν = σ22 (ν = (0, −1)), g_ν = −g_2
        let g2 = g[1].eval(x, 0.0, t);
        assert!((-s[1] - (pn + g2)).abs() < 1e-12);
        // σ_τ = g_τ: σ_τ = −σ12 e1 component, g_τ = g_1
        assert!((-s[2] - g[0].eval(x, 0.0, t)).abs() < 1e-12);
    }
}
