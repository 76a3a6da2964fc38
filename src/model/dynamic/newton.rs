//! One semismooth Newton method for every contact treatment (Barboteu–Danan–Sofonea, "BDS",
//! §1.6.2: a Newton method per stage of the step).
//!
//! The unknown is the step increment d. The residual is R(d) = R_b(d) − ξ(d) with R_b the body
//! part ([`StepOperator`]) and ξ the nodal contact forces. Compliance forces enter with their
//! (generalized) slopes. Constraints — Signorini p ≤ g with multiplier λ ≥ 0, and Coulomb stick
//! — are handled as a primal–dual active set method, which is semismooth Newton applied to the
//! complementarity functions
//!
//!   C_ν = λ − max(0, λ + c_ν (p − g)),   C_τ = T − proj_[−b, b](T − c_τ Δτ),
//!
//! with b = μ(p) N the friction bound and c_ν, c_τ the Jacobian's diagonal per weight: a node is
//! active (p = g prescribed) when λ + c_ν (p − g) > 0, sticks (Δτ = 0 prescribed) when
//! |T − c_τ Δτ| ≤ b, and otherwise slides with T = b sign(T − c_τ Δτ). Prescribed increments are
//! eliminated symmetrically; multipliers are the reactions of the eliminated rows. The slide
//! force's dependence on p through b is not differentiated (it would make the Jacobian
//! unsymmetric), so with friction Newton converges linearly near the solution — the statistics
//! show it.
//!
//! A sliding node whose update would reverse its slide (T = −b → +b or back) is put in stick
//! instead: the solution then lies between the two slide states, and c_τ, the Jacobian's
//! diagonal, includes the body's stiffness, which for a stiff body far exceeds the stiffness of
//! its rigid sliding motion (α times its mass), so the plain update jumps over the stick state
//! and cycles between ±b — at the stop of a sliding block the method did not converge in 60
//! iterations whatever the mesh (`verification/cases/dynamic_friction*.toml`). From stick the
//! reaction decides: within the bound the node stays, beyond it the node slides in the direction
//! the reaction points.
//!
//! Convergence: the active sets did not change and either ‖R‖_∞ ≤ tol · s, s the largest term of
//! R, or every free row is within its computed round-off floor, |R_i| ≤ [`FLOOR_FACTOR`] ε a_i,
//! a_i the sum of the absolute values of the terms of row i (inertia, internal force with its
//! stress's round-off scale, step data, contact and friction forces with the round-off of the
//! penetration they are computed from), and ‖R‖_∞ no longer halves. A stop at the floor is
//! convergence — the requested tolerance lies below what the residual can resolve — and is
//! counted ([`NewtonStats::at_floor`]). Without constraints a backtracking line search on ‖R‖₂ globalizes the
//! iteration; an inadmissible state (det F ≤ 0) is also cut back. Failures are typed errors with
//! the step, time, iteration and residual.

use crate::contact::compliance::{energy_consistent, penalty, tilted_correction};
use crate::contact::friction::FrictionCoefficient;
use crate::error::SolveError;
use crate::model::dynamic::step_operator::StepOperator;

/// Parameters of the Newton method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonParams {
    /// Relative tolerance on ‖R‖_∞ / s.
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Halvings of a step allowed by the line search.
    pub max_backtracks: usize,
}

impl Default for NewtonParams {
    fn default() -> Self {
        Self {
            tolerance: 1e-12,
            max_iterations: 60,
            max_backtracks: 40,
        }
    }
}

impl NewtonParams {
    /// Checks the values; errors name `newton.*`.
    pub fn validate(&self) -> Result<(), crate::error::InputError> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(crate::error::InputError::new(
                "newton.tolerance",
                self.tolerance,
                "a number in (0, 1)",
            ));
        }
        if self.max_iterations == 0 {
            return Err(crate::error::InputError::new(
                "newton.max_iterations",
                self.max_iterations,
                "at least 1",
            ));
        }
        Ok(())
    }
}

/// What the normal force of a node is in this stage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NodeLaw {
    /// N = r p_+.
    Penalty { r: f64 },
    /// BDS (1.46) with its exact slope.
    EnergyConsistent { r: f64 },
    /// HLT (3.69).
    Tilted { r: f64 },
    /// p ≤ gap with N = N_ec(p) + λ, λ ≥ 0, λ (gap − p) = 0, where N_ec is the
    /// energy-consistent compliance force (BDS (1.46)) of `stiffness` (0: none, Signorini): at
    /// p = gap it is the stage-(b) compliance r (p_{n−1} + g)/2, and a node whose constraint is
    /// inactive keeps the exact discrete work of stage (a), so stage (b) only dissipates.
    Constrained { gap: f64, stiffness: f64 },
}

/// A contact node as the Newton method sees it (indices are the operator's unknowns).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StageNode {
    pub nd: usize,
    pub td: Option<usize>,
    pub sign: f64,
    pub weight: f64,
    /// p_{n−1}.
    pub q: f64,
    pub law: NodeLaw,
    /// The friction coefficient, and whether it is frozen at μ0 (stage (b)).
    pub friction: Option<(FrictionCoefficient, bool)>,
}

/// Active-set state of a node, carried across iterations, stages and steps (warm start).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NodeState {
    /// Constraint active (p = gap).
    pub active: bool,
    /// Multiplier λ per weight.
    pub lambda: f64,
    /// Sticking (Δτ = 0).
    pub stick: bool,
    /// Slide direction of the friction force (±1).
    pub dir: f64,
}

/// The forces of a node at the solution.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NodeForces {
    /// p_n.
    pub p: f64,
    /// N per weight (compliance + multiplier).
    pub normal: f64,
    /// T per weight (friction).
    pub tangential: f64,
    /// Generalized contact forces on the normal and tangential unknowns (the tilt of (3.69)
    /// included), friction excluded: the compliance force plus the multiplier's −s w λ e_ν.
    pub force_nd: f64,
    pub force_td: f64,
    /// The compliance force alone on the normal and tangential unknowns (the tilt of (3.69)
    /// included; 0 for Signorini).
    pub compliance_nd: f64,
    pub compliance_td: f64,
    /// λ per weight: the multiplier of the unilateral constraint (Signorini, stage (b) of the
    /// IPM), the reaction of its eliminated row; 0 where no constraint acts.
    pub multiplier: f64,
    /// Generalized friction force on the tangential unknown.
    pub friction_td: f64,
}

/// Statistics of one Newton solve.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NewtonStats {
    pub iterations: usize,
    pub backtracks: usize,
    /// Final ‖R‖_∞ / s.
    pub residual: f64,
    /// Final ‖R‖_∞ (absolute; the rows of prescribed increments excluded).
    pub residual_norm: f64,
    pub active: usize,
    pub sticking: usize,
    pub sliding: usize,
    /// Whether the solve stopped at its round-off floor (see [`FLOOR_FACTOR`]) rather than at
    /// the tolerance.
    pub at_floor: bool,
    /// The largest floor of a free row relative to s, max_i [`FLOOR_FACTOR`] ε a_i / s, at the
    /// last iteration.
    pub floor: f64,
}

/// The round-off floor of row i of R is `FLOOR_FACTOR` · ε · a_i, a_i the sum of the absolute
/// values of the row's terms.
///
/// Why 32 = 16 × 2: the row is a sum of terms each computed with a few roundings. A P1 row sums
/// at most about 14 matrix entries (a node with 7 neighbours, 2 components) plus the step data
/// and a contact force, and the sum of n terms is in error by at most (n − 1) ε Σ|t| (Higham,
/// Accuracy and Stability, §4.2), typically √n ε Σ|t| with rounding errors of random sign: 16
/// is the worst case of a 17-term row and 4 times the typical error of a 256-term (condensed)
/// one, whose a_i already includes the rounding of forming C = L Lᵀ and L y. Each term is itself
/// a product of rounded factors (a stress of a finite-strain law passes C, J, ln J, F⁻ᵀ and F S),
/// in error by about 2 ε of its size: hence × 2. Measured: the O-ring of
/// `examples/scenes/dynamic_gmsh_o_ring.toml` thrown at 20 m/s stagnates at 32 ε a_i in a contact
/// node's row (2.0 × the 16 ε a_i first used). A residual within the floor cannot be reduced
/// further by Newton: the update it computes is round-off. A residual above it keeps iterating.
pub const FLOOR_FACTOR: f64 = 32.0;

/// Scratch vectors of the Newton method (allocated once per run).
#[derive(Debug, Default)]
pub struct NewtonWorkspace {
    r: Vec<f64>,
    /// a_i: the sum of |terms| of each row of R.
    terms: Vec<f64>,
    rhs: Vec<f64>,
    d_old: Vec<f64>,
    delta: Vec<f64>,
    fixed: Vec<(usize, f64)>,
    marker: Vec<bool>,
    new_state: Vec<NodeState>,
    bound: Vec<f64>,
}

/// Where the step is (for errors).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepAt {
    pub step: usize,
    pub time: f64,
}

/// The compliance force per weight and its slope; None for a constrained node.
#[inline]
fn compliance(law: NodeLaw, q: f64, p: f64) -> Option<(f64, f64)> {
    match law {
        NodeLaw::Penalty { r } => {
            let f = penalty(r, p);
            Some((f.value, f.slope))
        }
        NodeLaw::EnergyConsistent { r } => {
            let f = energy_consistent(r, q, p);
            Some((f.value, f.slope))
        }
        NodeLaw::Constrained { stiffness, .. } => {
            let f = energy_consistent(stiffness, q, p);
            Some((f.value, f.slope))
        }
        NodeLaw::Tilted { .. } => None,
    }
}

/// The generalized forces (on the normal and tangential unknowns) of the HLT variant (3.69) at
/// increments (d_ν, d_τ): F = λ_{n+1/2} ν + c δφ/|δφ|² (see [`tilted_correction`]).
#[inline]
fn tilted_forces(r: f64, node: &StageNode, dn: f64, dt: f64) -> (f64, f64, f64) {
    let p = node.q + node.sign * dn;
    // ν·δφ = −s d_ν, |δφ|² = d_ν² + d_τ²
    let (lam, c) = tilted_correction(r, node.q, p, -node.sign * dn, dn * dn + dt * dt);
    let w = node.weight;
    (w * (-node.sign * lam + c * dn), w * c * dt, lam)
}

/// The diagonal of the (unsymmetric) derivative of the (3.69) forces, by central differences
/// (a symmetric approximation of the tangent, clipped at 0).
fn tilted_slopes(r: f64, node: &StageNode, dn: f64, dt: f64) -> (f64, f64) {
    let h = 1e-7 * dn.abs().max(dt.abs()).max(node.q.abs()).max(1e-12);
    let jn =
        -(tilted_forces(r, node, dn + h, dt).0 - tilted_forces(r, node, dn - h, dt).0) / (2.0 * h);
    let jt =
        -(tilted_forces(r, node, dn, dt + h).1 - tilted_forces(r, node, dn, dt - h).1) / (2.0 * h);
    (jn.max(0.0), jt.max(0.0))
}

/// The stiffness r of a node's normal law (0 for Signorini).
fn law_stiffness(law: NodeLaw) -> f64 {
    match law {
        NodeLaw::Penalty { r } | NodeLaw::EnergyConsistent { r } | NodeLaw::Tilted { r } => r,
        NodeLaw::Constrained { stiffness, .. } => stiffness,
    }
}

/// The round-off scale of a node's normal force: w (|N| + r |d_ν| / [`FLOOR_FACTOR`] · 2). The
/// force is evaluated to ε |N| (p = q + s d_ν is one rounded addition); but Newton can move d_ν
/// only by its ulp ≤ 2 ε |d_ν|, and a stiff wall turns that into a jump w r 2 ε |d_ν| of the
/// residual (p the small difference of two numbers of size |d_ν|): the second term makes the
/// floor hold that jump. It is a bound: Newton often lands nearer, so a residual still halving
/// below it keeps iterating (see [`solve_stage`]).
#[inline]
fn contact_terms(node: &StageNode, d: &[f64], normal: f64) -> f64 {
    let granularity = 2.0 / FLOOR_FACTOR * law_stiffness(node.law) * d[node.nd].abs();
    node.weight * (normal.abs() + granularity)
}

/// Adds the compliance (and constant constrained) forces of every node to r = R_b, i.e.
/// r ← r − ξ, and their round-off scales to `terms`; returns the largest force term.
fn add_normal_forces(nodes: &[StageNode], d: &[f64], r: &mut [f64], terms: &mut [f64]) -> f64 {
    let mut s: f64 = 0.0;
    for node in nodes {
        let p = node.q + node.sign * d[node.nd];
        let w = node.weight;
        match node.law {
            NodeLaw::Tilted { r: stiffness } => {
                let dt = node.td.map_or(0.0, |t| d[t]);
                let (fn_, ft, _) = tilted_forces(stiffness, node, d[node.nd], dt);
                r[node.nd] -= fn_;
                s = s.max(fn_.abs());
                terms[node.nd] += contact_terms(node, d, fn_ / w);
                if let Some(t) = node.td {
                    r[t] -= ft;
                    s = s.max(ft.abs());
                    terms[t] += ft.abs() + w * 2.0 / FLOOR_FACTOR * stiffness * dt.abs();
                }
            }
            law => {
                let (n, _) = compliance(law, node.q, p).unwrap_or((0.0, 0.0));
                r[node.nd] += node.sign * w * n;
                s = s.max((w * n).abs());
                terms[node.nd] += contact_terms(node, d, n);
            }
        }
    }
    s
}

/// Solves one stage: R(d) = 0 with the nodes' laws; `d` holds the initial guess and receives
/// the solution, `state` the warm-started active sets; `forces` receives each node's forces.
#[allow(clippy::too_many_arguments)]
pub fn solve_stage(
    op: &mut dyn StepOperator,
    nodes: &[StageNode],
    state: &mut [NodeState],
    d: &mut [f64],
    forces: &mut [NodeForces],
    params: &NewtonParams,
    ws: &mut NewtonWorkspace,
    at: StepAt,
) -> Result<NewtonStats, SolveError> {
    let n = op.len();
    ws.r.resize(n, 0.0);
    ws.terms.resize(n, 0.0);
    ws.rhs.resize(n, 0.0);
    ws.d_old.resize(n, 0.0);
    ws.delta.resize(n, 0.0);
    ws.new_state.clear();
    ws.new_state.extend_from_slice(state);
    ws.bound.resize(nodes.len(), 0.0);
    let has_sets = nodes
        .iter()
        .any(|nd| matches!(nd.law, NodeLaw::Constrained { .. }) || nd.friction.is_some());
    let mut stats = NewtonStats::default();
    let mut merit_old = f64::INFINITY;
    let mut step_length = 1.0;
    let mut halvings = 0;
    let mut iteration = 0;
    let mut previous_norm = f64::INFINITY;
    loop {
        // a large body's iterations and backtracks can take long: a stop request ends them
        crate::run_control::check(|| {
            format!(
                "step {} (t = {}), Newton iteration {iteration}",
                at.step, at.time
            )
        })?;
        // 1. the residual with the current sets
        let body_scale = op.body_residual(d, &mut ws.r, &mut ws.terms);
        let Some(body_scale) = body_scale else {
            // inadmissible state: cut the last step back; an inadmissible initial guess (the
            // predictor d = k v of a large step) is pulled back towards d = 0, i.e. towards
            // u_n = u_{n−1}, which is admissible
            if halvings < params.max_backtracks {
                stats.backtracks += 1;
                halvings += 1;
                if iteration > 0 {
                    step_length *= 0.5;
                    for i in 0..n {
                        d[i] = ws.d_old[i] + step_length * ws.delta[i];
                    }
                } else {
                    d.iter_mut().for_each(|x| *x *= 0.5);
                }
                continue;
            }
            return Err(SolveError::NonFinite {
                step: at.step,
                time: at.time,
                quantity: "deformation (det F ≤ 0 in some element)".into(),
                value: f64::NAN,
                hint: " — the step inverted an element; reduce the time step".into(),
            });
        };
        let force_scale = add_normal_forces(nodes, d, &mut ws.r, &mut ws.terms);
        let scale = body_scale.max(force_scale).max(f64::MIN_POSITIVE);
        // 2. multipliers and new sets
        let mut changed = false;
        for (i, node) in nodes.iter().enumerate() {
            let w = node.weight;
            let p = node.q + node.sign * d[node.nd];
            let mut normal = match node.law {
                NodeLaw::Constrained { gap, .. } => {
                    let force = compliance(node.law, node.q, p).map_or(0.0, |(v, _)| v);
                    let lam = if state[i].active {
                        -ws.r[node.nd] / (node.sign * w)
                    } else {
                        0.0
                    };
                    let c = op.diagonal(node.nd) / w;
                    let active = lam + c * (p - gap) > 0.0;
                    changed |= active != state[i].active;
                    ws.new_state[i].active = active;
                    ws.new_state[i].lambda = if state[i].active { lam } else { 0.0 };
                    force + ws.new_state[i].lambda
                }
                NodeLaw::Tilted { r } => {
                    crate::contact::compliance::energy_consistent(r, node.q, p).value
                }
                law => compliance(law, node.q, p).map_or(0.0, |(v, _)| v),
            };
            normal = normal.max(0.0);
            if let (Some((mu, frozen)), Some(t)) = (node.friction, node.td) {
                let coef = if frozen { mu.mu0() } else { mu.value(p) };
                let bound = coef * normal;
                ws.bound[i] = bound;
                let tang = if state[i].stick {
                    ws.r[t] / w
                } else {
                    state[i].dir * bound
                };
                let c = op.diagonal(t) / w;
                let z = tang - c * d[t];
                let dir = if z >= 0.0 { 1.0 } else { -1.0 };
                // a sliding node whose slide would reverse is put in stick first: the solution
                // lies between the two slide states (see the module docs)
                let reverses = !state[i].stick && state[i].dir != 0.0 && dir != state[i].dir;
                let stick = bound > 0.0 && (z.abs() <= bound || reverses);
                changed |= stick != state[i].stick || (!stick && dir != state[i].dir);
                ws.new_state[i].stick = stick;
                ws.new_state[i].dir = dir;
            }
        }
        // 3. the residual of the current sets (friction of sliding nodes added, eliminated rows
        //    skipped)
        ws.marker.clear();
        ws.marker.resize(n, false);
        for (i, node) in nodes.iter().enumerate() {
            if matches!(node.law, NodeLaw::Constrained { .. }) && state[i].active {
                ws.marker[node.nd] = true;
            }
            if let (Some(_), Some(t)) = (node.friction, node.td) {
                if state[i].stick {
                    ws.marker[t] = true;
                }
            }
        }
        let any_eliminated = ws.marker.iter().any(|&m| m);
        let mut norm: f64 = 0.0;
        let mut merit = 0.0;
        let slide = |i: usize, node: &StageNode, dir: f64, bound: &[f64]| {
            if node.friction.is_some() && node.td.is_some() {
                node.weight * dir * bound[i]
            } else {
                0.0
            }
        };
        for (i, node) in nodes.iter().enumerate() {
            if let Some(t) = node.td {
                if !state[i].stick {
                    let f = slide(i, node, state[i].dir, &ws.bound);
                    ws.r[t] -= f;
                    // the bound μ N inherits the normal force's round-off scale
                    if f != 0.0 {
                        ws.terms[t] += f.abs() + contact_terms(node, d, 0.0);
                    }
                }
            }
        }
        let eps_floor = FLOOR_FACTOR * f64::EPSILON;
        let mut floor: f64 = 0.0;
        let mut excess: f64 = 0.0;
        let mut worst_row = 0;
        for i in 0..n {
            let v = ws.r[i];
            if !v.is_finite() {
                return Err(SolveError::NonFinite {
                    step: at.step,
                    time: at.time,
                    quantity: format!("step residual (unknown {i})"),
                    value: v,
                    hint: String::new(),
                });
            }
            if !ws.marker[i] {
                norm = norm.max(v.abs());
                merit += v * v;
                let row_floor = eps_floor * ws.terms[i];
                floor = floor.max(row_floor);
                let ratio = v.abs() / row_floor.max(f64::MIN_POSITIVE);
                if ratio > excess {
                    excess = ratio;
                    worst_row = i;
                }
            }
        }
        // back to R_b − ξ_ν (the friction of the sets chosen below is added in step 4)
        for (i, node) in nodes.iter().enumerate() {
            if let Some(t) = node.td {
                if !state[i].stick {
                    ws.r[t] += slide(i, node, state[i].dir, &ws.bound);
                }
            }
        }
        let relative = norm / scale;
        stats.residual = relative;
        stats.residual_norm = norm;
        stats.floor = floor / scale;
        // every free row within its round-off floor: nothing left that Newton can resolve
        let at_floor = excess <= 1.0;
        // line search (no sets): insist on decrease of ‖R‖₂
        if !has_sets
            && iteration > 0
            && merit.sqrt() > (1.0 - 1e-4 * step_length) * merit_old
            && relative > params.tolerance
            && !at_floor
            && halvings < params.max_backtracks
        {
            stats.backtracks += 1;
            halvings += 1;
            step_length *= 0.5;
            for i in 0..n {
                d[i] = ws.d_old[i] + step_length * ws.delta[i];
            }
            continue;
        }
        // prescribed increments hold only after a solve with them eliminated; a residual at its
        // round-off floor is converged whatever the requested tolerance (counted)
        if !changed && (iteration > 0 || !any_eliminated) {
            if relative <= params.tolerance {
                break;
            }
            // at the floor and no longer halving: a residual still falling below its bound
            // (Newton often lands on a better representable increment than the bound assumes)
            // keeps iterating, which costs at most one iteration
            if at_floor && norm > 0.5 * previous_norm {
                stats.at_floor = true;
                break;
            }
        }
        previous_norm = norm;
        if iteration >= params.max_iterations {
            if at_floor && !changed {
                // within the floor at the cap (still halving, but nothing left to resolve)
                stats.at_floor = true;
                break;
            }
            return Err(SolveError::DynamicNewtonNotConverged {
                step: at.step,
                time: at.time,
                iterations: iteration,
                residual: relative,
                tolerance: params.tolerance,
                floor: floor / scale,
                row: worst_row,
                excess,
            });
        }
        // 4. the Newton step with the new sets
        state.copy_from_slice(&ws.new_state);
        merit_old = merit.sqrt();
        ws.fixed.clear();
        for (i, node) in nodes.iter().enumerate() {
            if let NodeLaw::Constrained { gap, .. } = node.law {
                if state[i].active {
                    let p = node.q + node.sign * d[node.nd];
                    ws.fixed.push((node.nd, (gap - p) / node.sign));
                }
            }
            if let (Some(_), Some(t)) = (node.friction, node.td) {
                if state[i].stick {
                    ws.fixed.push((t, -d[t]));
                } else {
                    ws.r[t] -= node.weight * state[i].dir * ws.bound[i];
                }
            }
        }
        op.begin_jacobian(d);
        for node in nodes {
            let p = node.q + node.sign * d[node.nd];
            if let Some((_, slope)) = compliance(node.law, node.q, p) {
                op.add_diagonal(node.nd, node.weight * slope);
            }
            if let NodeLaw::Tilted { r } = node.law {
                let dt = node.td.map_or(0.0, |t| d[t]);
                let (jn, jt) = tilted_slopes(r, node, d[node.nd], dt);
                op.add_diagonal(node.nd, jn);
                if let Some(t) = node.td {
                    op.add_diagonal(t, jt);
                }
            }
        }
        for i in 0..n {
            ws.rhs[i] = -ws.r[i];
        }
        op.solve(&ws.fixed, &mut ws.rhs)
            .map_err(|e| with_step(e, at))?;
        ws.d_old.copy_from_slice(d);
        ws.delta.copy_from_slice(&ws.rhs);
        step_length = 1.0;
        halvings = 0;
        for i in 0..n {
            d[i] += ws.delta[i];
        }
        iteration += 1;
        stats.iterations = iteration;
    }
    // forces at the solution; ws.r = R_b − ξ_ν (friction excluded): the reactions of the
    // eliminated rows follow from it
    for (i, node) in nodes.iter().enumerate() {
        let w = node.weight;
        let p = node.q + node.sign * d[node.nd];
        let mut f = NodeForces {
            p,
            ..Default::default()
        };
        match node.law {
            NodeLaw::Constrained { .. } => {
                let force = compliance(node.law, node.q, p).map_or(0.0, |(v, _)| v);
                let lam = if state[i].active {
                    // reaction: everything but the multiplier balances it
                    (-ws.r[node.nd] / (node.sign * w)).max(0.0)
                } else {
                    0.0
                };
                state[i].lambda = lam;
                f.normal = force + lam;
                f.multiplier = lam;
                f.compliance_nd = -node.sign * w * force;
                f.force_nd = -node.sign * w * f.normal;
            }
            NodeLaw::Tilted { r } => {
                let dt = node.td.map_or(0.0, |t| d[t]);
                let (fn_, ft, lam) = tilted_forces(r, node, d[node.nd], dt);
                f.normal = lam;
                f.force_nd = fn_;
                f.force_td = ft;
                f.compliance_nd = fn_;
                f.compliance_td = ft;
            }
            law => {
                let (v, _) = compliance(law, node.q, p).unwrap_or((0.0, 0.0));
                f.normal = v;
                f.force_nd = -node.sign * w * v;
                f.compliance_nd = f.force_nd;
            }
        }
        if let (Some(_), Some(t)) = (node.friction, node.td) {
            let tang = if state[i].stick {
                // reaction of the stick row: R_b − ξ_ν-part − w T = 0
                ws.r[t] / w
            } else {
                state[i].dir * ws.bound[i]
            };
            f.tangential = tang;
            f.friction_td = w * tang;
        }
        forces[i] = f;
    }
    for (s, node) in state.iter().zip(nodes) {
        if s.active && matches!(node.law, NodeLaw::Constrained { .. }) {
            stats.active += 1;
        }
        if node.friction.is_some() && node.td.is_some() {
            if s.stick {
                stats.sticking += 1;
            } else {
                stats.sliding += 1;
            }
        }
    }
    Ok(stats)
}

/// Attaches the step and time to a linear-solver failure.
fn with_step(e: SolveError, at: StepAt) -> SolveError {
    match e {
        SolveError::Singular {
            operator,
            row,
            pivot,
        } => SolveError::Singular {
            operator: format!("{operator} at step {} (t = {})", at.step, at.time),
            row,
            pivot,
        },
        other => other,
    }
}
