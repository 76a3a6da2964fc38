//! The energy audit (`model::dynamic::audit`) on whole runs: every identity a conserving run
//! claims holds within its round-off tolerance C ε Σ s_j, and each one fails, far beyond it, when
//! one ingredient of the run is deliberately wrong — so none of them holds by construction.
//!
//! The setting is the periodic Signorini bar of docs/dynamic.md §5 (ρ = E = A = 1 on (0, 1), held
//! at x = 1, a wall at x = 0, u0 = (1 − x)/2): through the impact at t = 1, the held phase and the
//! release at t = 2, with the midpoint rule (conserving for this linear bar) and each contact
//! treatment.

use std::sync::Arc;

use contactlab::field::Field;
use contactlab::material::hyperelastic::LinearElastic1d;
use contactlab::mesh::interval::IntervalMesh;
use contactlab::model::dynamic::audit::AuditSummary;
use contactlab::model::dynamic::bar::{BarBody, BarData, BarSupports, MassMatrix};
use contactlab::model::dynamic::body::{ElasticBody, Operators};
use contactlab::model::dynamic::contact_model::{BarEnd, ContactModel, NormalTreatment};
use contactlab::model::dynamic::record::conserving;
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::{DynamicParams, DynamicProblem, DynamicSolver};

const ELEMENTS: usize = 40;
const STEPS: usize = 100;

fn bar() -> BarBody {
    BarBody::new(BarData {
        mesh: IntervalMesh::uniform(1.0, ELEMENTS).expect("mesh"),
        density: 1.0,
        area: 1.0,
        law: Arc::new(LinearElastic1d { young: 1.0 }),
        supports: BarSupports {
            left: false,
            right: true,
        },
        mass: MassMatrix::Consistent,
        body_force: Field::Constant(0.0),
    })
    .expect("bar")
}

/// The audit summary of the bar run with `body` (the bar or a wrapper of it), `treatment` and
/// `scheme` up to T = 2.5, and whether the run claims the identities.
fn audited(
    body: Arc<dyn ElasticBody>,
    treatment: NormalTreatment,
    scheme: DynamicScheme,
) -> (AuditSummary, contactlab::model::dynamic::record::Conserving) {
    let shape = bar();
    let contact = ContactModel::bar_wall(&shape, BarEnd::Left, 0.0, treatment).expect("contact");
    let nodes: Vec<f64> = shape.data().mesh.nodes().to_vec();
    let u0 = shape.from_nodal(&nodes.iter().map(|x| 0.5 * (1.0 - x)).collect::<Vec<_>>());
    let n = shape.dofs();
    let problem = DynamicProblem {
        body,
        contact: Some(contact),
        scheme,
        final_time: 2.5,
        steps: STEPS,
        initial_displacement: u0,
        initial_velocity: vec![0.0; n],
    };
    let claims = conserving(&problem);
    let solution = DynamicSolver::new(problem, DynamicParams::default())
        .expect("valid")
        .solve()
        .expect("run");
    (solution.audit.summary(), claims)
}

/// The bar with its internal force (and stiffness) scaled by `factor` while its stored energy is
/// the bar's: an internal force that is not the gradient of the energy the audit evaluates, as a
/// wrong factor in an element force (or a halved Gonzalez correction) would be.
#[derive(Debug)]
struct ScaledForce {
    inner: BarBody,
    ops: Operators,
    factor: f64,
}

impl ScaledForce {
    fn new(factor: f64) -> Self {
        let inner = bar();
        let mut ops = inner.operators().clone();
        if let Some(k) = ops.stiffness.as_mut() {
            k.iter_mut().for_each(|v| *v *= factor);
        }
        Self { inner, ops, factor }
    }
}

impl ElasticBody for ScaledForce {
    fn operators(&self) -> &Operators {
        &self.ops
    }
    fn stored_energy(&self, u: &[f64]) -> f64 {
        self.inner.stored_energy(u)
    }
    fn internal_force(&self, u: &[f64], f: &mut [f64]) -> bool {
        let ok = self.inner.internal_force(u, f);
        f.iter_mut().for_each(|v| *v *= self.factor);
        ok
    }
    fn internal_force_terms(&self, u0: &[f64], u1: &[f64], out: &mut [f64]) {
        self.inner.internal_force_terms(u0, u1, out);
        out.iter_mut().for_each(|v| *v *= self.factor);
    }
    fn add_tangent(&self, u: &[f64], scale: f64, values: &mut [f64]) {
        self.inner.add_tangent(u, scale * self.factor, values)
    }
    fn discrete_gradient_force(&self, u0: &[f64], u1: &[f64], f: &mut [f64]) -> bool {
        let ok = self.inner.discrete_gradient_force(u0, u1, f);
        f.iter_mut().for_each(|v| *v *= self.factor);
        ok
    }
    fn add_discrete_gradient_tangent(&self, u0: &[f64], u1: &[f64], scale: f64, v: &mut [f64]) {
        self.inner
            .add_discrete_gradient_tangent(u0, u1, scale * self.factor, v)
    }
    fn add_discrete_gradient_skew(&self, u0: &[f64], u1: &[f64], scale: f64, v: &mut [f64]) {
        self.inner
            .add_discrete_gradient_skew(u0, u1, scale * self.factor, v)
    }
    fn load_into(&self, t: f64, out: &mut [f64]) {
        self.inner.load_into(t, out)
    }
    fn load_depends_on_time(&self) -> bool {
        self.inner.load_depends_on_time()
    }
    fn load_is_zero(&self) -> bool {
        self.inner.load_is_zero()
    }
    fn wave_speed(&self) -> f64 {
        self.inner.wave_speed()
    }
    fn h_min(&self) -> f64 {
        self.inner.h_min()
    }
    fn describe(&self) -> String {
        format!("{} with its force × {}", self.inner.describe(), self.factor)
    }
}

const ENERGY_CONSISTENT: NormalTreatment = NormalTreatment::EnergyConsistent { stiffness: 400.0 };

#[test]
fn a_conserving_run_keeps_every_identity_it_claims_within_round_off() {
    for treatment in [
        ENERGY_CONSISTENT,
        NormalTreatment::HauretLeTallecTilted { stiffness: 400.0 },
        NormalTreatment::LimitedPenetration {
            stiffness: 400.0,
            depth: 1e-3,
        },
    ] {
        let (s, claims) = audited(Arc::new(bar()), treatment, DynamicScheme::Midpoint);
        assert!(claims.balance && claims.claims_3_7() && claims.claims_1_49());
        for ratio in [s.drift_ratio_1_48, s.drift_ratio_3_7, s.drift_ratio_1_49] {
            assert!(ratio <= 1.0, "{treatment:?}: {s:?}");
        }
        assert!(s.constraint_work_ratio <= 1.0, "{treatment:?}: {s:?}");
    }
}

#[test]
fn an_internal_force_that_is_not_the_energy_gradient_fails_1_48_and_1_49_not_3_7() {
    // a relative error of 1e-6 in the internal force: far below any rate's resolution, far
    // above round-off
    let (s, _) = audited(
        Arc::new(ScaledForce::new(1.0 + 1e-6)),
        ENERGY_CONSISTENT,
        DynamicScheme::Midpoint,
    );
    assert!(s.drift_ratio_1_48 > 1e3, "{s:?}");
    assert!(s.drift_ratio_1_49 > 1e3, "{s:?}");
    assert!(s.drift_ratio_3_7 <= 1.0, "{s:?}");
    let (exact, _) = audited(
        Arc::new(ScaledForce::new(1.0)),
        ENERGY_CONSISTENT,
        DynamicScheme::Midpoint,
    );
    assert!(exact.drift_ratio_1_48 <= 1.0, "{exact:?}");
}

#[test]
fn a_compliance_force_without_exact_work_fails_3_7_and_1_49_not_1_48() {
    // the penalty r (p_n)_+ at t_n is the energy-consistent force with the wrong secant
    let (s, claims) = audited(
        Arc::new(bar()),
        NormalTreatment::Penalty { stiffness: 400.0 },
        DynamicScheme::Midpoint,
    );
    assert!(claims.balance && !claims.claims_3_7());
    assert!(s.drift_ratio_1_48 <= 1.0, "{s:?}");
    assert!(s.drift_ratio_3_7 > 1e6, "{s:?}");
    assert!(s.drift_ratio_1_49 > 1e6, "{s:?}");
}

#[test]
fn constraint_work_is_the_multipliers_and_has_no_sign_under_newmark() {
    // the midpoint rule's Signorini multiplier at t_n only dissipates; Newmark's trapezoidal
    // mean of the multipliers still pushes the end in the step it leaves the wall: D_b > 0,
    // computed from λ̄ and the penetrations, fails the sign check
    let (mid, claims) = audited(
        Arc::new(bar()),
        NormalTreatment::Signorini,
        DynamicScheme::Midpoint,
    );
    assert!(claims.balance && !claims.compliance && !claims.claims_1_49());
    assert!(mid.constraint_work_ratio <= 1.0, "{mid:?}");
    let (newmark, _) = audited(
        Arc::new(bar()),
        NormalTreatment::Signorini,
        DynamicScheme::Newmark,
    );
    assert!(newmark.constraint_work_ratio > 1e6, "{newmark:?}");
    // the balance (1.48) itself holds for Newmark on the linear bar (trapezoidal mean of the
    // forces)
    assert!(newmark.drift_ratio_1_48 <= 1.0, "{newmark:?}");
}

#[test]
#[ignore]
fn scratch_dump() {
    use contactlab::model::dynamic::audit::round_off_tolerance;
    use contactlab::scene::dynamic::DynamicScene;
    let path = std::env::var("SCENE").unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let scene = DynamicScene::from_toml_str(&text, &path).unwrap();
    let sol = DynamicSolver::new(scene.problem.clone(), scene.params.clone())
        .unwrap()
        .solve()
        .unwrap();
    let a = &sol.audit;
    let s = a.summary();
    println!("{s:?}");
    let sums = a.roundoff_scales();
    let e = a.energy_scale();
    for (r, sum) in a.records.iter().zip(&sums).take(12) {
        println!(
            "n={} t={:.4e} R48/E={:+.2e} ratio={:.3} stiffw/E={:.2e} it={} res48/E={:+.2e} E={:.6e} pen={:.3e}",
            r.step, r.time, r.drift_1_48 / e, r.drift_1_48.abs() / round_off_tolerance(*sum).max(1e-300), r.stiffness_work / e, r.newton_iterations, r.residual_1_48 / e, r.energy(), r.penalty
        );
    }
}
