//! Manufactured solutions of the plane problem P (Fernández & Sofonea 2004, (2.1)–(2.6)).
//!
//! One closure u(x, y, t) per solution (`plane_fields`, generic over dual numbers). On
//! Ω = (0, 1)² with Γ1 the left side (clamped, u = 0 there), Γ2 the top and right sides and Γ3 the
//! bottom (ν = (0, −1)), the data that make u exact are
//!
//!   f0 = −Div σ,   f2 = σν on Γ2,   g = σν + p_ν(u̇_ν) ν on Γ3,   σ = A(ε(u̇)) + B(ε(u)),
//!
//! so that −σ_ν = p_ν(u̇_ν) − g_ν and σ_τ = g_τ on Γ3 (docs/quasistatic.md, §Manufactured
//! solutions). A, B and p_ν are the laws written in this crate (`plane_laws`, `normal_response`),
//! never the solver's law objects, which only go into the problem handed to the solver: a wrong
//! stress or contact law in the solver cannot hide in the data.
//!
//! Div σ is the automatic derivative of σ(x, y, t) itself: σ is evaluated at
//! (x + ε1, y + ε2, t) on hyper-dual numbers, ∂_x σ = the ε1 part, ∂_y σ = the ε2 part. Inside,
//! ε(u) and ε(u̇) come from two evaluations of u on hyper-dual numbers over those, in the
//! directions (x, t) and (y, t): u_{i,x} = ε1, u_{i,t} = ε2, u_{i,xt} = ε1ε2.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use num_dual::{DualNum, HyperDual, HyperDual64, HyperHyperDual64};

use contactlab::fem::triangle_p1::Sym2;
use contactlab::field::{Dependence, Field};
use contactlab::mesh::triangle::{Diagonal, RectangleSide, TriangleMesh};
use contactlab::model::quasistatic::plane::{
    BoundarySelector, ContactIntegration, ContactPart, DirichletPart, PlaneProblem, Support,
    TractionPart,
};

use crate::manufactured::normal_response::NormalResponse;
use crate::manufactured::plane_fields::PlaneField;
use crate::manufactured::plane_laws::{MaterialLaw, Sym};

type Hhd = HyperHyperDual64;

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
pub fn plane_jet(u: &PlaneField, x: f64, y: f64, t: f64) -> PlaneJet {
    let r = u.eval(
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

/// (ε(u), ε(u̇), u̇) at (x, y, t) on the number type D: u on hyper-dual numbers over D in the
/// directions (x, t) and (y, t).
fn kinematics<D: DualNum<Primitive = f64> + Copy>(
    u: &PlaneField,
    x: D,
    y: D,
    t: D,
) -> (Sym<D>, Sym<D>, [D; 2]) {
    let (zero, one) = (D::zero(), D::one());
    let tt = HyperDual::new(t, zero, one, zero);
    let rx = u.eval(
        HyperDual::new(x, one, zero, zero),
        HyperDual::from_re(y),
        tt,
    );
    let ry = u.eval(
        HyperDual::from_re(x),
        HyperDual::new(y, one, zero, zero),
        tt,
    );
    // u_{i,x} = rx[i].eps1, u_{i,y} = ry[i].eps1, u_{i,t} = rx[i].eps2, u_{i,jt} = ·.eps1eps2
    let strain = [rx[0].eps1, ry[1].eps1, (ry[0].eps1 + rx[1].eps1) * 0.5];
    let rate = [
        rx[0].eps1eps2,
        ry[1].eps1eps2,
        (ry[0].eps1eps2 + rx[1].eps1eps2) * 0.5,
    ];
    (strain, rate, [rx[0].eps2, rx[1].eps2])
}

/// (key, σ, Div σ, u̇_ν) of the last point evaluated.
type PointCache = Option<([u64; 4], Sym2, [f64; 2], f64)>;

thread_local! {
    /// The last (solution, x, y, t) → (σ, Div σ, u̇_ν) evaluated on this thread: the load assembly
    /// asks for both components of a vector field at the same point one after the other, and
    /// each evaluation costs several nested dual passes.
    static LAST: std::cell::Cell<PointCache> = const { std::cell::Cell::new(None) };
}

/// Distinguishes solutions in the per-thread evaluation cache.
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// The four sides of the unit square as boundary parts of a mesh.
#[derive(Debug)]
pub struct SquareSides {
    pub left: BoundarySelector,
    pub top: BoundarySelector,
    pub right: BoundarySelector,
    pub bottom: BoundarySelector,
}

impl SquareSides {
    /// The sides of a generated rectangle mesh (its side tags).
    pub fn rectangle() -> Self {
        Self {
            left: BoundarySelector::side(RectangleSide::Left),
            top: BoundarySelector::side(RectangleSide::Top),
            right: BoundarySelector::side(RectangleSide::Right),
            bottom: BoundarySelector::side(RectangleSide::Bottom),
        }
    }
}

/// A manufactured plane solution: its field, its materials and its foundation (the laws of this
/// crate).
#[derive(Debug, Clone)]
pub struct PlaneManufactured {
    name: String,
    id: u64,
    pub final_time: f64,
    pub field: PlaneField,
    pub viscosity: MaterialLaw,
    pub elasticity: MaterialLaw,
    pub foundation: NormalResponse,
}

impl PlaneManufactured {
    fn with(name: &str, viscosity: MaterialLaw, elasticity: MaterialLaw) -> Self {
        Self {
            name: name.to_string(),
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            final_time: 1.0,
            field: PlaneField::Switching,
            viscosity,
            elasticity,
            foundation: NormalResponse::Lubricated { beta: 5.0, p0: 1.0 },
        }
    }

    /// Linear Kelvin–Voigt in plane stress (A: μ = 3, η = 2; B: E = 10, κ = 0.3), damper (2.8)
    /// with β = 5, p0 = 1.
    pub fn linear_switching() -> Self {
        Self::with(
            "plane manufactured, linear",
            MaterialLaw::Viscosity { mu: 3.0, eta: 2.0 },
            MaterialLaw::PlaneStress {
                young: 10.0,
                poisson: 0.3,
            },
        )
    }

    /// Nonlinear A (saturating viscosity μ = 3, η = 2, γ = 1, τ_c = 0.1) and B (softening
    /// elasticity λ = 5, G = 4, δ = 0.5, ε_c = 0.05), the same foundation.
    pub fn nonlinear() -> Self {
        Self::with(
            "plane manufactured, nonlinear A and B",
            MaterialLaw::Saturating {
                mu: 3.0,
                eta: 2.0,
                gamma: 1.0,
                tau_c: 0.1,
            },
            MaterialLaw::Softening {
                lambda: 5.0,
                shear: 4.0,
                delta: 0.5,
                eps_c: 0.05,
            },
        )
    }

    /// Plane strain (B: E = 10, κ = 0.3), the same A and foundation.
    pub fn plane_strain() -> Self {
        Self::with(
            "plane manufactured, plane strain",
            MaterialLaw::Viscosity { mu: 3.0, eta: 2.0 },
            MaterialLaw::PlaneStrain {
                young: 10.0,
                poisson: 0.3,
            },
        )
    }

    /// By name (`plane_manufactured_linear`, `_nonlinear`, `_strain`), with the switching field.
    pub fn by_name(name: &str) -> Option<Self> {
        match name {
            "plane_manufactured_linear" => Some(Self::linear_switching()),
            "plane_manufactured_nonlinear" => Some(Self::nonlinear()),
            "plane_manufactured_strain" => Some(Self::plane_strain()),
            _ => None,
        }
    }

    /// The same materials and foundation with another displacement field.
    pub fn with_field(mut self, field: PlaneField) -> Self {
        if field != PlaneField::Switching {
            self.name = format!("{}, {}", self.name, field.describe());
        }
        self.field = field;
        self.id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
        self
    }

    /// The same solution on another foundation.
    pub fn with_foundation(mut self, foundation: NormalResponse) -> Self {
        if foundation != self.foundation {
            self.name = format!("{}, p_ν = {foundation:?}", self.name);
        }
        self.foundation = foundation;
        self.id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
        self
    }

    /// The name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// u and its first derivatives.
    pub fn jet(&self, x: f64, y: f64, t: f64) -> PlaneJet {
        plane_jet(&self.field, x, y, t)
    }

    /// σ = A(ε(u̇)) + B(ε(u)) and u̇ at (x, y, t) on the number type D (the laws of this crate).
    fn stress_on<D: DualNum<Primitive = f64> + Copy>(&self, x: D, y: D, t: D) -> (Sym<D>, [D; 2]) {
        let (e, er, ut) = kinematics(&self.field, x, y, t);
        let a = self.viscosity.stress(&er);
        let b = self.elasticity.stress(&e);
        ([a[0] + b[0], a[1] + b[1], a[2] + b[2]], ut)
    }

    /// σ(x, y, t).
    pub fn stress(&self, x: f64, y: f64, t: f64) -> Sym2 {
        self.stress_on(x, y, t).0
    }

    /// (σ, Div σ, u̇_ν on the bottom side) at (x, y, t): σ on (x + ε1, y + ε2), cached per thread
    /// for the last point.
    fn point_data(&self, x: f64, y: f64, t: f64) -> (Sym2, [f64; 2], f64) {
        let key = [self.id, x.to_bits(), y.to_bits(), t.to_bits()];
        if let Some((k, s, d, un)) = LAST.with(|c| c.get()) {
            if k == key {
                return (s, d, un);
            }
        }
        let (sd, ut) = self.stress_on(
            HyperDual64::from_re(x).derivative1(),
            HyperDual64::from_re(y).derivative2(),
            HyperDual64::from_re(t),
        );
        let s = [sd[0].re, sd[1].re, sd[2].re];
        // Div σ_1 = ∂x σ11 + ∂y σ12, Div σ_2 = ∂x σ12 + ∂y σ22
        let d = [sd[0].eps1 + sd[2].eps2, sd[2].eps1 + sd[1].eps2];
        let un = -ut[1].re;
        LAST.with(|c| c.set(Some((key, s, d, un))));
        (s, d, un)
    }

    /// Div σ at (x, y, t).
    pub fn div_stress(&self, x: f64, y: f64, t: f64) -> [f64; 2] {
        self.point_data(x, y, t).1
    }

    /// The Γ3 source g = σν + p_ν(u̇_ν) ν at (x, 0, t), ν = (0, −1), u̇_ν = −u̇2.
    pub fn contact_source(&self, x: f64, y: f64, t: f64) -> [f64; 2] {
        let (s, _, un) = self.point_data(x, y, t);
        let p = self.foundation.value(un);
        [-s[2], -s[1] - p]
    }

    /// The problem on an n × n mesh of the unit square whose exact solution is u (n ≥ 1).
    pub fn problem(
        &self,
        divisions: usize,
        integration: ContactIntegration,
    ) -> Result<PlaneProblem, String> {
        let mesh =
            TriangleMesh::rectangle([0.0, 0.0], [1.0, 1.0], [divisions, divisions], Diagonal::Up)
                .map_err(|e| format!("{divisions} × {divisions} squares: {e}"))?;
        Ok(self.problem_on(mesh, SquareSides::rectangle(), integration))
    }

    /// The problem on any triangulation `mesh` of the unit square whose exact solution is u, with
    /// its four sides selected by `sides` (Γ1 = left, Γ2 = top and right, Γ3 = bottom). The data
    /// are evaluated where the mesh puts its nodes and quadrature points, so a side selected
    /// wrongly, or a mesh that is not the unit square, shows as an error that does not converge.
    pub fn problem_on(
        &self,
        mesh: TriangleMesh,
        sides: SquareSides,
        integration: ContactIntegration,
    ) -> PlaneProblem {
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
        // Γ2: top (ν = (0, 1): σν = (σ12, σ22)) and right (ν = (1, 0): σν = (σ11, σ12)).
        let side = |components: [usize; 2]| {
            [0, 1].map(|c| {
                let m = me.clone();
                Field::function(xyt, move |x, y, t| m.point_data(x, y, t).0[components[c]])
            })
        };
        let (top, right) = (side([2, 1]), side([0, 2]));
        let source = [0, 1].map(|c| {
            let m = me.clone();
            Field::function(xyt, move |x, y, t| m.contact_source(x, y, t)[c])
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
            mesh,
            final_time: self.final_time,
            viscosity: self.viscosity.solver_law(),
            elasticity: self.elasticity.solver_law(),
            regions: Vec::new(),
            body_force: body,
            dirichlet: vec![DirichletPart {
                boundary: sides.left,
                support: Support::Clamped,
            }],
            traction: vec![
                TractionPart {
                    boundary: sides.top,
                    traction: top,
                },
                TractionPart {
                    boundary: sides.right,
                    traction: right,
                },
            ],
            contact: Some(ContactPart {
                boundary: sides.bottom,
                law: Arc::new(self.foundation.solver_law()),
                integration,
                source: Some(source),
            }),
            initial_displacement: u0,
        }
    }
}

#[cfg(test)]
mod tests {
    //! Manufactured plane solutions: Div σ by automatic differentiation agrees with central
    //! differences of σ; the source makes the contact condition hold with the independent law;
    //! the affine field's stress is constant in space (f0 = 0), which puts it in V^h.
    use super::*;

    fn all() -> Vec<PlaneManufactured> {
        let affine = PlaneField::Affine { switch_time: 0.5 };
        vec![
            PlaneManufactured::linear_switching(),
            PlaneManufactured::nonlinear(),
            PlaneManufactured::plane_strain(),
            PlaneManufactured::linear_switching().with_field(affine),
            PlaneManufactured::nonlinear().with_field(affine),
        ]
    }

    #[test]
    fn div_stress_matches_finite_differences_for_every_solution() {
        for m in all() {
            for &(x, y, t) in &[(0.3, 0.6, 0.2), (0.8, 0.1, 0.7)] {
                let h = 1e-5;
                let sx = |dx: f64| m.stress(x + dx, y, t);
                let sy = |dy: f64| m.stress(x, y + dy, t);
                let ds_dx: Vec<f64> = (0..3).map(|c| (sx(h)[c] - sx(-h)[c]) / (2.0 * h)).collect();
                let ds_dy: Vec<f64> = (0..3).map(|c| (sy(h)[c] - sy(-h)[c]) / (2.0 * h)).collect();
                let fd = [ds_dx[0] + ds_dy[2], ds_dx[2] + ds_dy[1]];
                let d = m.div_stress(x, y, t);
                for c in 0..2 {
                    // central differences: O(h²) truncation, O(ε/h) round-off
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
    fn stress_is_the_laws_of_this_crate_applied_to_the_jet() {
        for m in all() {
            let (x, y, t) = (0.37, 0.52, 0.61);
            let j = m.jet(x, y, t);
            let a = m.viscosity.stress(&j.strain_rate());
            let b = m.elasticity.stress(&j.strain());
            let s = m.stress(x, y, t);
            for c in 0..3 {
                assert!((s[c] - (a[c] + b[c])).abs() < 1e-14, "{}", m.name());
            }
        }
    }

    #[test]
    fn contact_condition_holds_with_the_source() {
        for m in all() {
            let (x, t) = (0.37, 0.61);
            let s = m.stress(x, 0.0, t);
            let un = -m.jet(x, 0.0, t).ut[1];
            let g = m.contact_source(x, 0.0, t);
            // −σ_ν = p_ν(u̇_ν) − g_ν with σ_ν = σ22 (ν = (0, −1)), g_ν = −g_2
            assert!((-s[1] - (m.foundation.value(un) + g[1])).abs() < 1e-12);
            // σ_τ = g_τ: the tangential component of σν is −σ12
            assert!((-s[2] - g[0]).abs() < 1e-12);
        }
    }

    #[test]
    fn the_affine_field_has_no_body_force() {
        let m = PlaneManufactured::nonlinear().with_field(PlaneField::Affine { switch_time: 0.3 });
        for &(x, y, t) in &[(0.1, 0.9, 0.05), (0.7, 0.2, 0.3), (1.0, 0.0, 0.95)] {
            let d = m.div_stress(x, y, t);
            assert!(d[0].abs() < 1e-13 && d[1].abs() < 1e-13, "{d:?}");
        }
    }

    #[test]
    fn a_mesh_without_squares_is_an_error() {
        assert!(PlaneManufactured::linear_switching()
            .problem(0, ContactIntegration::Gauss2)
            .is_err());
    }
}
