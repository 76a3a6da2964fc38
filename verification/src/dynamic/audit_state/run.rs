//! The state-recomputed audit of one dynamic run: an observer of the solver's steps
//! ([`StateAuditor`]) that recomputes every audited quantity from the state (module docs of
//! `super`), compares the step records with it, and gates the sign laws and, where the scheme
//! claims them, the identities ([`state_audit_checks`]).
//!
//! Floors and tolerances (C = 2, N the terms of a sum, S the sum of their magnitudes):
//! - a record against its recomputed value: |rec − state| over C ε (N + 30) S — K, 𝒲 and Φ at
//!   every step; the step works W_τ and D_b; the cumulative works W_ext, W_c, W_τ, D_b over the
//!   sum of the steps' floors plus C ε Σ_j |cumulative_j| (the running sum's own rounding);
//! - a sign law (the step's recomputed D_b, W_τ): over C ε Σ |terms| (with the rounding of the
//!   penetrations and increments computed from u) plus the step's Newton part ν_n + C ε s_n,
//!   s_n = S_n + σ_n (S_n the recomputed energies' magnitudes, ν_n = ‖d‖₁ ‖R‖_∞ and
//!   σ_n = ‖K‖_∞ ‖u_n‖ ‖d‖ the solver's reported Newton bound and stiffness-work scale — the only
//!   solver numbers used, and only as slack: no energy or work of the solver enters);
//! - the recomputed identities (1.48) E_n − E_0 − Σ (W_ext + W_c + W_τ) and (1.49)
//!   (E + Φ)_n − (E + Φ)_0 − Σ (W_ext + W_τ + D_b), and the rise (E + Φ)_n − (E + Φ)_0 − Σ W_ext,
//!   over tol_n = floor(E_n + Φ_n) + floor(E_0 + Φ_0) + Σ_{j≤n} (floor(works_j) + ν_j + C ε s_j).

use crate::core::audit_floor::{floor, max_nan, C};
use serde::Serialize;

use contactlab::model::dynamic::audit::AuditRecord;
use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::dynamic::newton::NodeForces;
use contactlab::model::dynamic::plane_body::PlaneBody;
use contactlab::model::dynamic::record::Conserving;
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::{DynamicProblem, StepView};
use contactlab::scene::dynamic::DynamicSceneFile;

use super::geometry::{gamma3_nodes, penetration, Gamma3, Gamma3Node};
use super::sums::{plane_sums, PlaneSums};
use crate::core::gate::{Check, GateVerdict};
use crate::manufactured::strain_energy::{PlaneLaw, StrainEnergy};

/// A penetration p = level − (y + u_y) rounds by at most this many ε times its operands' size.
const P_ROUNDING: f64 = 4.0;

/// The foundation {y ≤ level} under Γ3 and its compliance, as the case's scene states them.
#[derive(Debug, Clone)]
pub struct Foundation {
    pub level: f64,
    pub gamma3: Gamma3,
    /// r of Φ = Σ w (r/2) p_+² (none: Signorini).
    pub stiffness: Option<f64>,
    /// The HLT tilted force (3.69): its generalized forces on (u_y, u_x) are read from the
    /// view (its tilt is not a per-weight normal force).
    pub tilted: bool,
}

/// What the audit reads of a case's scene: density, mass kind, law and foundation.
#[derive(Debug, Clone)]
pub struct AuditSpec {
    pub density: f64,
    pub lumped: bool,
    pub law: PlaneLaw,
    pub foundation: Option<Foundation>,
}

impl AuditSpec {
    /// The spec of a dynamic scene with a plane body. Errors: a bar, material regions, a law
    /// not written here, Γ3 by Gmsh group.
    pub fn of_scene(file: &DynamicSceneFile) -> Result<Self, String> {
        if file.body.shape == "bar" {
            return Err("state audit: a bar (see docs/dynamic.md)".into());
        }
        if !file.region.is_empty() {
            return Err("state audit: material regions (not recomputed)".into());
        }
        let m = &file.material;
        let law = match m.law.as_str() {
            "linear" => StrainEnergy::Linear,
            "st_venant_kirchhoff" => StrainEnergy::StVenantKirchhoff,
            "neo_hooke" => StrainEnergy::NeoHooke,
            other => return Err(format!("state audit: law \"{other}\" not written here")),
        };
        let poisson = m.poisson.ok_or("state audit: material.poisson missing")?;
        let foundation = match &file.contact {
            None => None,
            Some(c) => Some(Foundation {
                level: c.level.ok_or("state audit: contact.level missing")?,
                gamma3: Gamma3::of(c)?,
                stiffness: if c.treatment == "signorini" {
                    None
                } else {
                    Some(
                        c.stiffness
                            .ok_or("state audit: contact.stiffness missing")?,
                    )
                },
                tilted: c.treatment == "hauret_le_tallec_tilted",
            }),
        };
        Ok(Self {
            density: file.body.density,
            lumped: file.body.mass == MassMatrix::Lumped,
            law: PlaneLaw::from_young_poisson(law, m.young, poisson),
            foundation,
        })
    }
}

/// What the state-recomputed audit of a run shows. The `*_ratio` fields are maxima over the
/// steps of a difference or a sign law's value over its floor (module docs): ≤ 1 passes.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct StateAudit {
    pub steps: usize,
    /// Records against the state: K, 𝒲, Φ.
    pub kinetic_ratio: f64,
    pub stored_ratio: f64,
    pub penalty_ratio: f64,
    /// The records' works (cumulative W_ext, W_c, W_τ, D_b and the step's W_τ, D_b) against
    /// the recomputed ones.
    pub work_record_ratio: f64,
    /// Sign laws on the recomputed step works D_b and W_τ (midpoint-type schemes for W_τ).
    pub constraint_sign_ratio: f64,
    pub friction_sign_ratio: f64,
    pub constraint_steps: usize,
    pub friction_steps: usize,
    /// The recomputed identities' drifts and the energy's rise, over their tolerance.
    pub identity_1_48_ratio: f64,
    pub identity_1_49_ratio: f64,
    pub energy_rise_ratio: f64,
    /// Recomputed (E + Φ)_0, max_n (E + Φ)_n/(E + Φ)_0 and (E + Φ)_N/(E + Φ)_0.
    pub initial_energy: f64,
    pub max_energy_ratio: f64,
    pub final_energy_ratio: f64,
    /// Recomputed Σ D_b and Σ W_τ over (E + Φ)_0.
    pub constraint_work_relative: f64,
    pub friction_work_relative: f64,
}

/// The previous step's state.
struct Previous {
    u: Vec<f64>,
    forces: Vec<NodeForces>,
    p: Vec<f64>,
    energy: f64,
    total: f64,
    load: Vec<f64>,
}

/// Running sums: the recomputed cumulative works, their floors, and the identities' terms.
#[derive(Default)]
struct Running {
    external: f64,
    contact: f64,
    friction: f64,
    constraint: f64,
    /// Σ_j floor_j of each cumulative work plus C ε Σ_j |cumulative_j|.
    floors: [f64; 4],
    /// Σ_j (floor(works_j) + ν_j + C ε s_j).
    slack: f64,
    drift_48: f64,
    drift_49: f64,
}

/// The auditor: feed it every step's view ([`Self::observe`]), then [`Self::finish`].
pub struct StateAuditor<'a> {
    body: &'a PlaneBody,
    spec: AuditSpec,
    scheme: DynamicScheme,
    k: f64,
    /// Γ3 and, per node, its index in the view's forces.
    nodes: Vec<(Gamma3Node, usize)>,
    initial_floor: f64,
    previous: Option<Previous>,
    run: Running,
    audit: StateAudit,
    error: Option<String>,
}

impl<'a> StateAuditor<'a> {
    /// The auditor of `problem`'s run on `body` (the problem's body), by `spec`. The view's
    /// forces are paired with Γ3 by mesh node (the solver's contact nodes, in order): the set of
    /// nodes must be Γ3's, else the audit fails.
    pub fn new(
        body: &'a PlaneBody,
        problem: &DynamicProblem,
        spec: AuditSpec,
    ) -> Result<Self, String> {
        let solver_nodes: Vec<usize> = problem
            .contact
            .as_ref()
            .map(|c| c.nodes.iter().map(|n| n.node).collect())
            .unwrap_or_default();
        let mut nodes = Vec::new();
        if let Some(f) = &spec.foundation {
            for g in gamma3_nodes(body, &f.gamma3) {
                let i = solver_nodes
                    .iter()
                    .position(|&n| n == g.node)
                    .ok_or_else(|| {
                        format!(
                            "state audit: Γ3 node {} is not among the solver's contact nodes",
                            g.node
                        )
                    })?;
                nodes.push((g, i));
            }
        }
        if nodes.len() != solver_nodes.len() {
            return Err(format!(
                "state audit: {} Γ3 nodes recomputed, the solver has {} contact nodes",
                nodes.len(),
                solver_nodes.len()
            ));
        }
        Ok(Self {
            body,
            spec,
            scheme: problem.scheme,
            k: problem.final_time / problem.steps as f64,
            nodes,
            initial_floor: 0.0,
            previous: None,
            run: Running::default(),
            audit: StateAudit {
                // the sign laws and the rise report their largest value (negative: how far
                // below 0 in floors)
                constraint_sign_ratio: f64::NEG_INFINITY,
                friction_sign_ratio: f64::NEG_INFINITY,
                energy_rise_ratio: f64::NEG_INFINITY,
                ..Default::default()
            },
            error: None,
        })
    }

    /// Takes one step's view (the initial state first).
    pub fn observe(&mut self, view: &StepView<'_>) {
        if self.error.is_none() {
            if let Err(e) = self.step(view) {
                self.error = Some(format!("state audit, step {}: {e}", view.step));
            }
        }
    }

    /// The audit of the steps observed.
    pub fn finish(self) -> Result<StateAudit, String> {
        match self.error {
            Some(e) => Err(e),
            None if self.previous.is_none() => Err("state audit: no step observed".into()),
            None => {
                let mut a = self.audit;
                for x in [
                    &mut a.constraint_sign_ratio,
                    &mut a.friction_sign_ratio,
                    &mut a.energy_rise_ratio,
                ] {
                    if *x == f64::NEG_INFINITY {
                        *x = 0.0;
                    }
                }
                Ok(a)
            }
        }
    }

    fn load(&self, t: f64) -> Vec<f64> {
        let mut f = vec![0.0; self.body.dofs()];
        self.body.load_into(t, &mut f);
        f
    }

    /// Φ = Σ w (r/2) p_+², the magnitude of its terms, its floor, and the penetrations.
    fn penalty(&self, u: &[f64]) -> (f64, f64, f64, Vec<f64>) {
        let level = self.spec.foundation.as_ref().map_or(0.0, |f| f.level);
        let r = self
            .spec
            .foundation
            .as_ref()
            .and_then(|f| f.stiffness)
            .unwrap_or(0.0);
        let (mut phi, mut size) = (0.0, 0.0);
        let p: Vec<f64> = self
            .nodes
            .iter()
            .map(|(g, _)| {
                let (p, sz) = penetration(level, g, u);
                let q = p.max(0.0);
                let e = 0.5 * g.weight * r * q * q;
                phi += e;
                size += e + g.weight * r * q * P_ROUNDING * sz;
                p
            })
            .collect();
        (phi, size, floor(self.nodes.len(), size), p)
    }

    fn step(&mut self, view: &StepView<'_>) -> Result<(), String> {
        let (u, v, rec) = (view.displacement, view.velocity, view.record);
        let s = plane_sums(
            self.body,
            self.spec.density,
            self.spec.lumped,
            &self.spec.law,
            u,
            v,
        )?;
        let (phi, phi_size, phi_floor, p) = self.penalty(u);
        let energy = s.kinetic + s.stored;
        let total = energy + phi;
        let total_floor = self.compare_state(&s, phi, phi_floor, rec);
        let t_load = if self.scheme.is_midpoint_type() {
            view.time + 0.5 * self.k
        } else {
            view.time
        };
        let load = self.load(t_load);
        let Some(prev) = self.previous.take() else {
            self.audit.initial_energy = total;
            self.initial_floor = total_floor;
            self.audit.max_energy_ratio = 1.0;
            self.audit.final_energy_ratio = 1.0;
            self.previous = Some(Previous {
                u: u.to_vec(),
                forces: view.forces.to_vec(),
                p,
                energy,
                total,
                load,
            });
            return Ok(());
        };
        let scale = s.kinetic_size + s.stored_size + phi_size;
        let newton = rec.newton_work + C * f64::EPSILON * (scale + rec.stiffness_work);
        let w = self.works(&prev, view, &p, u);
        self.compare_works(&w, rec);
        self.sign_laws(&w, newton);
        // the identities
        let r = &mut self.run;
        r.slack += w.floor + newton;
        r.drift_48 += energy - prev.energy - (w.external + w.contact + w.friction);
        r.drift_49 += total - prev.total - (w.external + w.friction + w.constraint);
        let tol = (r.slack + total_floor + self.initial_floor).max(f64::MIN_POSITIVE);
        let e0 = self.audit.initial_energy;
        let rise = total - e0 - r.external;
        let a = &mut self.audit;
        a.identity_1_48_ratio = max_nan(a.identity_1_48_ratio, r.drift_48.abs() / tol);
        a.identity_1_49_ratio = max_nan(a.identity_1_49_ratio, r.drift_49.abs() / tol);
        a.energy_rise_ratio = max_nan(a.energy_rise_ratio, rise / tol);
        let e0 = e0.abs().max(f64::MIN_POSITIVE);
        a.max_energy_ratio = max_nan(a.max_energy_ratio, total / e0);
        a.final_energy_ratio = total / e0;
        a.constraint_work_relative = r.constraint / e0;
        a.friction_work_relative = r.friction / e0;
        a.steps += 1;
        self.previous = Some(Previous {
            u: u.to_vec(),
            forces: view.forces.to_vec(),
            p,
            energy,
            total,
            load,
        });
        Ok(())
    }

    /// K, 𝒲, Φ of the record against the state; returns the floor of E + Φ.
    fn compare_state(&mut self, s: &PlaneSums, phi: f64, phi_floor: f64, rec: &AuditRecord) -> f64 {
        let n = 3 * s.terms;
        let (fk, fv) = (floor(n, s.kinetic_size), floor(n, s.stored_size));
        let a = &mut self.audit;
        a.kinetic_ratio = max_nan(a.kinetic_ratio, (rec.kinetic - s.kinetic).abs() / fk);
        a.stored_ratio = max_nan(a.stored_ratio, (rec.elastic - s.stored).abs() / fv);
        a.penalty_ratio = max_nan(a.penalty_ratio, (rec.penalty - phi).abs() / phi_floor);
        fk + fv + phi_floor
    }
}

/// The recomputed works of one step, their magnitudes and floors.
#[derive(Debug, Default)]
struct StepWorks {
    external: f64,
    contact: f64,
    friction: f64,
    constraint: f64,
    /// floor of each work: W_ext, W_c, W_τ, D_b.
    floors: [f64; 4],
    /// Σ of the four floors.
    floor: f64,
    /// The sign laws' own floors (C ε Σ|terms|, without the Newton part).
    friction_sign_floor: f64,
    constraint_sign_floor: f64,
    frictional: bool,
    constrained: bool,
}

impl StateAuditor<'_> {
    /// The works of the step n − 1 → n (module docs of `super`).
    fn works(&self, prev: &Previous, view: &StepView<'_>, p: &[f64], u: &[f64]) -> StepWorks {
        let newmark = self.scheme == DynamicScheme::Newmark;
        let eps = C * f64::EPSILON;
        let mut w = StepWorks::default();
        // W_ext = f̄·d: f at t_{n−½} (midpoint types) or the mean of t_{n−1} and t_n (Newmark)
        let f_end = newmark.then(|| self.load(view.time));
        let mut magnitude = 0.0;
        for (i, (u1, u0)) in u.iter().zip(&prev.u).enumerate() {
            let f = match &f_end {
                Some(f1) => 0.5 * (prev.load[i] + f1[i]),
                None => prev.load[i],
            };
            let d = u1 - u0;
            w.external += f * d;
            magnitude += (f * d).abs() + f.abs() * (u0.abs() + u1.abs());
        }
        w.floors[0] = floor(u.len(), magnitude);
        // the contact forces applied over the step: at t_n (midpoint types) or the mean
        let applied = |now: f64, before: f64| if newmark { 0.5 * (now + before) } else { now };
        let tilted = self.spec.foundation.as_ref().is_some_and(|f| f.tilted);
        let (mut m_c, mut m_t, mut m_b) = (0.0, 0.0, 0.0);
        let mut rounding_b = 0.0;
        let level = self.spec.foundation.as_ref().map_or(0.0, |f| f.level);
        for (j, (g, i)) in self.nodes.iter().enumerate() {
            let (f1, f0) = (&view.forces[*i], &prev.forces[*i]);
            let dy = u[g.y_dof] - prev.u[g.y_dof];
            let dx = g.x_dof.map_or(0.0, |x| u[x] - prev.u[x]);
            let uy = prev.u[g.y_dof].abs() + u[g.y_dof].abs();
            let ux = g.x_dof.map_or(0.0, |x| prev.u[x].abs() + u[x].abs());
            // W_c: w N̄ d_y (the force on u_y is w N along the foundation's normal +y), or the
            // tilted force's generalized components
            let (fy, fx) = if tilted {
                (
                    applied(f1.force_nd, f0.force_nd),
                    applied(f1.force_td, f0.force_td),
                )
            } else {
                (g.weight * applied(f1.normal, f0.normal), 0.0)
            };
            let wc = fy * dy + fx * dx;
            w.contact += wc;
            m_c += wc.abs() + fy.abs() * uy + fx.abs() * ux;
            // W_τ = w T̄ d_x
            let t = g.weight * applied(f1.tangential, f0.tangential);
            if t != 0.0 {
                w.frictional = true;
            }
            let wt = t * dx;
            w.friction += wt;
            m_t += wt.abs() + t.abs() * ux;
            // D_b = −w λ̄ (p_n − p_{n−1}), p from the displacements
            let lam = applied(f1.multiplier, f0.multiplier);
            if lam != 0.0 {
                w.constrained = true;
            }
            let wb = -g.weight * lam * (p[j] - prev.p[j]);
            w.constraint += wb;
            let (_, s1) = penetration(level, g, u);
            let (_, s0) = penetration(level, g, &prev.u);
            m_b += wb.abs();
            rounding_b += g.weight * lam.abs() * P_ROUNDING * (s0 + s1);
        }
        let n = self.nodes.len();
        w.floors[1] = floor(n, m_c);
        w.floors[2] = floor(n, m_t);
        w.floors[3] = floor(n, m_b + rounding_b);
        w.floor = w.floors.iter().sum();
        w.friction_sign_floor = eps * m_t;
        w.constraint_sign_floor = eps * (m_b + rounding_b);
        w
    }

    /// The records' works against the recomputed ones (cumulative and step).
    fn compare_works(&mut self, w: &StepWorks, rec: &AuditRecord) {
        let r = &mut self.run;
        r.external += w.external;
        r.contact += w.contact;
        r.friction += w.friction;
        r.constraint += w.constraint;
        let cum = [r.external, r.contact, r.friction, r.constraint];
        for (f, (step, c)) in r.floors.iter_mut().zip(w.floors.iter().zip(cum)) {
            *f += step + C * f64::EPSILON * c.abs();
        }
        let ratios = [
            (rec.external_work - r.external).abs() / r.floors[0],
            (rec.contact_work - r.contact).abs() / r.floors[1],
            (rec.friction_work - r.friction).abs() / r.floors[2],
            (rec.constraint_work - r.constraint).abs() / r.floors[3],
            (rec.step_friction_work - w.friction).abs() / w.floors[2],
            (rec.step_constraint_work - w.constraint).abs() / w.floors[3],
        ];
        let a = &mut self.audit;
        a.work_record_ratio = ratios.into_iter().fold(a.work_record_ratio, max_nan);
    }

    /// D_b ≤ 0 and (midpoint types) W_τ ≤ 0 on the recomputed step works.
    fn sign_laws(&mut self, w: &StepWorks, newton: f64) {
        let a = &mut self.audit;
        if w.constrained {
            a.constraint_steps += 1;
            let f = (w.constraint_sign_floor + newton).max(f64::MIN_POSITIVE);
            a.constraint_sign_ratio = max_nan(a.constraint_sign_ratio, w.constraint / f);
        }
        if w.frictional && self.scheme != DynamicScheme::Newmark {
            a.friction_steps += 1;
            let f = (w.friction_sign_floor + newton).max(f64::MIN_POSITIVE);
            a.friction_sign_ratio = max_nan(a.friction_sign_ratio, w.friction / f);
        }
    }
}

/// The state-recomputed audit's checks of a run (each ≤ 1): the records against the state
/// always; the sign laws where the run had a multiplier or (midpoint types) friction; the
/// recomputed (1.48) where the scheme claims it (`claims.balance`), (1.49) and the energy's rise
/// where it claims the total balance (`claims.total()`, `model/dynamic/record.rs::conserving`).
pub fn state_audit_checks(label: &str, a: &StateAudit, claims: Conserving) -> Vec<Check> {
    let mut checks = vec![
        Check::at_most(
            &format!("{label}: max_n |K (record) − ½ vᵀMv recomputed| / round-off floor"),
            a.kinetic_ratio,
            1.0,
        ),
        Check::at_most(
            &format!("{label}: max_n |𝒲 (record) − Σ A W(∇u) recomputed| / round-off floor"),
            a.stored_ratio,
            1.0,
        ),
        Check::at_most(
            &format!("{label}: max_n |Φ (record) − Σ w (r/2) p₊² recomputed| / round-off floor"),
            a.penalty_ratio,
            1.0,
        ),
        Check::at_most(
            &format!(
                "{label}: max_n |W_ext, W_c, W_τ, D_b (record) − recomputed from f, N, T, λ, d| / \
                 round-off floor"
            ),
            a.work_record_ratio,
            1.0,
        ),
    ];
    if a.constraint_steps > 0 {
        checks.push(Check::at_most(
            &format!("{label}: max_n recomputed D_b = −Σ w λ (p_n − p_{{n−1}}) / floor (≤ 0)"),
            a.constraint_sign_ratio,
            1.0,
        ));
    }
    if a.friction_steps > 0 {
        checks.push(Check::at_most(
            &format!("{label}: max_n recomputed W_τ = Σ w T d_x / floor (≤ 0)"),
            a.friction_sign_ratio,
            1.0,
        ));
    }
    if claims.balance {
        checks.push(Check::at_most(
            &format!(
                "{label}: max_n |E_n − E_0 − Σ (W_ext + W_c + W_τ)| recomputed (1.48) / tolerance"
            ),
            a.identity_1_48_ratio,
            1.0,
        ));
    }
    if claims.total() {
        checks.push(Check::at_most(
            &format!(
                "{label}: max_n |(E + Φ)_n − (E + Φ)_0 − Σ (W_ext + W_τ + D_b)| recomputed (1.49) / \
                 tolerance"
            ),
            a.identity_1_49_ratio,
            1.0,
        ));
        checks.push(Check::at_most(
            &format!(
                "{label}: max_n ((E + Φ)_n − (E + Φ)_0 − Σ W_ext) recomputed / tolerance \
                 ((E + Φ)_N/(E + Φ)_0 = {:.6})",
                a.final_energy_ratio
            ),
            a.energy_rise_ratio,
            1.0,
        ));
    }
    checks
}

/// What the state-recomputed audit gate recomputes (its reason).
pub const STATE_AUDIT_NOTE: &str = "the audit recomputed from the state: K = ½ vᵀMv from a P1 \
    mass (consistent or lumped, as the scene says) assembled in the verification crate, the \
    stored energy by the linear, St Venant–Kirchhoff and neo-Hooke laws written there, \
    Φ = Σ w (r/2) p₊² with Γ3's weights and the penetrations p = level − (y + u_y) of its own \
    reading of the scene's foundation, W_ext = f̄·d, the contact works from the nodal forces and \
    multipliers times the increments (W_c = Σ w N d_y, W_τ = Σ w T d_x, D_b = −Σ w λ Δp) — from \
    the displacements, velocities and forces only; the solver's records must agree with them \
    within C ε (N + 30) Σ|terms|, D_b and (midpoint types) W_τ must be ≤ 0, and where the scheme \
    claims them (1.48), (1.49) and E + Φ never above E₀ + Φ₀ + W_ext hold to the recomputed \
    tolerance (docs/dynamic.md, \"The audit recomputed from the state\")";

/// The gate of a case's state-recomputed audit checks.
pub fn state_audit_gate(name: &str, checks: Vec<Check>) -> GateVerdict {
    GateVerdict::from_checks(name.to_string(), "energy audit", checks, STATE_AUDIT_NOTE)
}
