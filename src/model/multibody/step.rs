//! One step of the multibody system: the semismooth Newton method on the increment d and the
//! candidates' multipliers, with segment switching (docs/multibody.md §5).
//!
//! Each iteration assembles R = (R_u, C_N, C_T) and the Newton matrix ([`StepSystem`]), updates
//! the candidates' active and stick/slip states from their complementarity functions
//! ([`Candidate::contribute`]) and takes the full Newton step (cut back only where a body would be
//! inverted, det F ≤ 0). A slave node whose projection leaves its segment (ξ < 0 or ξ > 1) moves
//! to the neighbouring segment of the master surface, or is released at the master's free end;
//! the system is then laid out anew. After the first iteration an inactive candidate activates
//! only when it penetrates beyond the round-off of c g (a band that keeps a released redundant
//! constraint — two-pass where the meshes share a node — from cycling on round-off gaps;
//! [`RowScale::hysteresis`]).
//!
//! Convergence: the states did not change in the iteration and every row is within its tolerance
//! — ‖R_u‖_∞ ≤ tol · s (s the largest sum of magnitudes of a row's terms, its round-off scale) and
//! |C| ≤ tol · s + 16 ε c |x| (c |x| the round-off of c g). A run at its round-off floor (states
//! unchanged, ‖R‖ not halved over three iterations, within 100 × the tolerance) is accepted and
//! counted. A run out of iterations whose states repeated is an [`SolveError::ActiveSetCycle`],
//! otherwise [`SolveError::NewtonNotConverged`].

use crate::error::SolveError;
use crate::model::dynamic::body::ElasticBody;
use crate::model::dynamic::newton::NewtonParams;
use crate::model::multibody::bodies::BodySet;
use crate::model::multibody::constraint::{Candidate, PairLaw, RowScale, Tangent};
use crate::model::multibody::invariants::{
    value_and_gradient, Evaluation, Gap, InvariantForms, Local6,
};
use crate::model::multibody::scheme::MultibodyScheme;
use crate::model::multibody::surface::ContactSurface;
use crate::model::multibody::system::{PatchDofs, StepSystem};

/// How far past a segment's end (in ξ) a projection goes before the node switches segment.
pub const SWITCH_TOLERANCE: f64 = 1e-9;

/// How far past a master's free end (in ξ) a converged node goes before it is released: half the
/// end segment, the point where the master's free end leaves the part of the slave surface the
/// node stands for (its tributary half-segment, on matching meshes). Inside that band the node is
/// held on the end segment's line extended: the single pass's stand-in for the master's corner
/// pressing on the slave face, which a second pass would carry.
///
/// Why not a few per cent. Two bars meeting face to face on P1 meshes that are not mirror images
/// of each other (both `Diagonal::Up`) shear their end columns in opposite senses: the consistent
/// mass couples a node's x-row to its neighbours differently at the top and the bottom of a
/// column, and the contact force, which alternates from step to step under the midpoint-type
/// rules, drives that coupling at every step. The corners then slide past each other
/// transversally at 0.13–0.4 v (v/c = 0.1), a slide of 2–20 % of h that does not shrink with h
/// (measured: `tests/multibody_bars_energy.rs`). With a release at 2 % (the value before issue
/// 31) the corner node was released under load, crossed the extended master line unconstrained,
/// came back inside the segment penetrated and was re-activated from inside: the constraint then
/// pushed it out with the positive work −λ g₀ > 0 (the energy of the head-on bars rose by 10 %
/// to 3×) or the step missed it (`no_equilibrium`). A node that slides off the end (a block
/// leaving its support) is released half a segment later than at 2 %, still in the step the
/// kinematics give (`multibody_sliding` computes it from this constant).
pub const RELEASE_TOLERANCE: f64 = 0.5;

/// The step's time integrator, or a static equilibrium.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepKind {
    Dynamic(MultibodyScheme),
    Static,
}

impl StepKind {
    fn evaluation(self) -> Evaluation {
        match self {
            StepKind::Dynamic(s) => s.evaluation(),
            StepKind::Static => Evaluation::End,
        }
    }
}

/// Where the step is (for errors).
#[derive(Debug, Clone, Copy)]
pub struct StepAt {
    pub step: usize,
    pub time: f64,
}

/// The master of a pair as the step sees it: a surface (with its body) or the foundation.
#[derive(Debug, Clone, Copy)]
pub enum MasterRef<'a> {
    Surface(&'a ContactSurface),
    Foundation,
}

/// What a step's Newton method reports.
#[derive(Debug, Clone, Copy, Default)]
pub struct StepReport {
    pub iterations: usize,
    pub switches: usize,
    pub releases: usize,
    pub analyses: usize,
    pub floor_stop: bool,
    /// Halvings of the line search.
    pub backtracks: usize,
    /// ‖R_u‖_∞ at convergence and the bound ‖d‖₁ ‖R_u‖_∞ + Σ |λ| |C| / c.
    pub residual: f64,
    pub newton_bound: f64,
    /// ‖R_u‖₁ and Σ |x_{n+1/2}| |R_u| over the nodes at convergence: the momentum and angular
    /// momentum a step's residual can move (k times these, [`super::audit`]).
    pub residual_sum: f64,
    pub residual_moment: f64,
    /// Σ_i s_i |d_i| (s_i the sum of the magnitudes of row i's terms): the round-off scale of the
    /// step's work d·R, and Σ_i s_i, Σ_i |x| s_i: those of its momentum and angular momentum.
    pub work_scale: f64,
    pub force_scale: f64,
    pub moment_scale: f64,
}

/// C of the round-off floor C ε s_i of a momentum row (s_i = Σ |terms| of the row): a few
/// roundings of each term (the products and the sums that form it), each within ε/2.
pub const FLOOR_ROUNDINGS: f64 = 8.0;

/// The row of an iterate furthest from its threshold: |R_i| / max(tol · s, floor_i) (a constraint
/// row's floor is 16 ε c |x|), the row's |R_i| and threshold, and whether some row meets its
/// threshold only through its floor (|R_i| > tol · s): the stop at the round-off floor.
#[derive(Debug, Clone, Copy, Default)]
struct WorstRow {
    ratio: f64,
    residual: f64,
    threshold: f64,
    at_floor: bool,
}

impl WorstRow {
    /// Takes a row with residual `r`, threshold `threshold` (≥ `tol`, the relative tolerance's).
    fn take(&mut self, r: f64, threshold: f64, tol: f64) {
        let threshold = threshold.max(f64::MIN_POSITIVE);
        let ratio = r / threshold;
        if ratio > self.ratio || !ratio.is_finite() {
            self.ratio = ratio;
            self.residual = r;
            self.threshold = threshold;
        }
        if r > tol && ratio <= 1.0 {
            self.at_floor = true;
        }
    }
}

/// The last Newton update, for the line search: the point it started from, the direction (already
/// cut back for admissibility), and the merit ‖D⁻¹ R‖₂ there.
struct LineState {
    d: Vec<f64>,
    delta: Vec<f64>,
    lambda: Vec<(f64, f64)>,
    dlambda: Vec<(f64, f64)>,
    merit: f64,
    /// The scaled residual (in tolerances) where the update started: the search acts only far
    /// from the round-off floor (above 100 tolerances), where ‖D⁻¹ R‖₂ measures progress; at the
    /// floor it cannot decrease and halving would only spend iterations.
    worst: f64,
    /// The candidates' states where the update started: the merit is compared only when they did
    /// not change (a change of the active set or of stick/slip changes the rows' definitions).
    states: Vec<(bool, i8, usize)>,
    /// The fraction of the direction taken, and how often it was halved.
    step: f64,
    halvings: usize,
}

/// Buffers of the step, allocated once per run.
#[derive(Debug)]
pub struct StepWorkspace {
    /// Per body: the constant block α M + θ K of a linear body (values on its pattern).
    linear_blocks: Vec<Option<Vec<f64>>>,
    sym: Vec<Vec<f64>>,
    skew: Vec<Vec<f64>>,
    r: Vec<f64>,
    scale: Vec<f64>,
    force: Vec<f64>,
    md: Vec<f64>,
    u1: Vec<f64>,
    um: Vec<f64>,
    trial: Vec<f64>,
    /// Per body and component: the local dofs of that component at every node (None when a node
    /// holds it), along which a linear body's stiffness is translated out ([`translated_out`]).
    translation_dofs: Vec<[Option<Vec<usize>>; 2]>,
    /// u − ū of a linear body (its range of the system vector), and K (d − d̄).
    shifted: Vec<f64>,
    force_increment: Vec<f64>,
    /// Per linear body: |K| (the magnitudes of its stiffness values); and |u₀ − ū₀| + θ |d − d̄|
    /// and |K| times it, the round-off scale of its force rows (the sum of the magnitudes of the
    /// terms that K u adds up: |K u| alone misses the cancellation of a smooth deformation).
    abs_stiffness: Vec<Option<Vec<f64>>>,
    abs_state: Vec<f64>,
    force_round_off: Vec<f64>,
    /// The constant part b of R_u = α M d + F − b.
    pub b: Vec<f64>,
    pub system: Option<StepSystem>,
    pub forms: InvariantForms,
}

impl StepWorkspace {
    /// Buffers for `bodies` and the step kind (k: the step size; unused for a static step).
    pub fn new(bodies: &BodySet, kind: StepKind, k: f64) -> Self {
        let (alpha, theta) = match kind {
            StepKind::Dynamic(s) => (s.alpha(k), if s.is_midpoint_type() { 0.5 } else { 1.0 }),
            StepKind::Static => (0.0, 1.0),
        };
        let linear_blocks = bodies
            .bodies()
            .iter()
            .map(|b| {
                b.linear_stiffness().map(|kk| {
                    kk.iter()
                        .zip(b.mass())
                        .map(|(k, m)| alpha * m + theta * k)
                        .collect()
                })
            })
            .collect();
        let n = bodies.dofs();
        Self {
            linear_blocks,
            sym: bodies
                .bodies()
                .iter()
                .map(|b| vec![0.0; b.pattern().nnz()])
                .collect(),
            skew: bodies
                .bodies()
                .iter()
                .map(|b| {
                    if matches!(kind, StepKind::Dynamic(MultibodyScheme::EnergyMomentum))
                        && !b.is_linear()
                    {
                        vec![0.0; b.pattern().nnz()]
                    } else {
                        Vec::new()
                    }
                })
                .collect(),
            r: Vec::new(),
            scale: vec![0.0; n],
            force: vec![0.0; n],
            md: vec![0.0; n],
            u1: vec![0.0; n],
            um: vec![0.0; n],
            trial: vec![0.0; n],
            translation_dofs: (0..bodies.len())
                .map(|b| {
                    let nodes = bodies.body(b).data().mesh.nodes().len();
                    let start = bodies.range(b).start;
                    [0, 1].map(|c| {
                        (0..nodes)
                            .map(|node| bodies.dof(b, node, c).map(|d| d - start))
                            .collect::<Option<Vec<usize>>>()
                    })
                })
                .collect(),
            shifted: vec![0.0; n],
            force_increment: vec![0.0; n],
            abs_stiffness: bodies
                .bodies()
                .iter()
                .map(|b| {
                    b.linear_stiffness()
                        .map(|kk| kk.iter().map(|v| v.abs()).collect())
                })
                .collect(),
            abs_state: vec![0.0; n],
            force_round_off: vec![0.0; n],
            b: vec![0.0; n],
            system: None,
            forms: InvariantForms::new(),
        }
    }
}

/// The data of one step.
#[derive(Debug, Clone, Copy)]
pub struct StepData<'a> {
    pub bodies: &'a BodySet,
    pub laws: &'a [PairLaw],
    pub masters: &'a [MasterRef<'a>],
    pub kind: StepKind,
    pub k: f64,
    pub u0: &'a [f64],
    pub at: StepAt,
}

/// The body part of the residual and the Newton matrix at u₁ = u₀ + d: R_u = α M d + F − b into
/// `ws.r[..n]` (and its row scales into `ws.scale`), the blocks into `ws.sym` / `ws.skew`. `false`
/// for an inadmissible state (det F ≤ 0 somewhere).
fn assemble_bodies(data: &StepData<'_>, d: &[f64], ws: &mut StepWorkspace, matrix: bool) -> bool {
    let bodies = data.bodies;
    let n = bodies.dofs();
    let alpha = match data.kind {
        StepKind::Dynamic(s) => s.alpha(data.k),
        StepKind::Static => 0.0,
    };
    for i in 0..n {
        ws.u1[i] = data.u0[i] + d[i];
        ws.um[i] = 0.5 * (data.u0[i] + ws.u1[i]);
    }
    bodies.mass_mul(d, &mut ws.md);
    for (bi, body) in bodies.bodies().iter().enumerate() {
        let rg = bodies.range(bi);
        let (u0, u1, um) = (&data.u0[rg.clone()], &ws.u1[rg.clone()], &ws.um[rg.clone()]);
        let f = &mut ws.force[rg.clone()];
        let scheme = match data.kind {
            StepKind::Dynamic(s) => Some(s),
            StepKind::Static => None,
        };
        let midpoint_state = matches!(
            scheme,
            Some(MultibodyScheme::Midpoint | MultibodyScheme::EnergyMomentum)
        );
        if let (Some(kk), Some(block)) = (body.linear_stiffness(), &ws.linear_blocks[bi]) {
            // a linear body: F = K u at the scheme's state u₀ + θ d (the discrete gradient is
            // K u_{1/2}), evaluated as K (u₀ − ū₀) + θ K (d − d̄) ([`translated_out`])
            let theta = if midpoint_state { 0.5 } else { 1.0 };
            let shifted = &mut ws.shifted[rg.clone()];
            let dofs = &ws.translation_dofs[bi];
            let abs_state = &mut ws.abs_state[rg.clone()];
            translated_out(u0, dofs, shifted);
            body.pattern().symmetric_mul(kk, shifted, f);
            for (a, x) in abs_state.iter_mut().zip(shifted.iter()) {
                *a = x.abs();
            }
            translated_out(&d[rg.clone()], dofs, shifted);
            let fd = &mut ws.force_increment[rg.clone()];
            body.pattern().symmetric_mul(kk, shifted, fd);
            for (a, b) in f.iter_mut().zip(fd.iter()) {
                *a += theta * b;
            }
            for (a, x) in abs_state.iter_mut().zip(shifted.iter()) {
                *a += theta * x.abs();
            }
            if let Some(abs_k) = &ws.abs_stiffness[bi] {
                body.pattern()
                    .symmetric_mul(abs_k, abs_state, &mut ws.force_round_off[rg.clone()]);
            }
            if matrix {
                ws.sym[bi].copy_from_slice(block);
            }
        } else {
            ws.force_round_off[rg.clone()]
                .iter_mut()
                .for_each(|v| *v = 0.0);
            let ok = match scheme {
                Some(MultibodyScheme::EnergyMomentum) => body.discrete_gradient_force(u0, u1, f),
                Some(MultibodyScheme::Midpoint) => body.internal_force(um, f),
                _ => body.internal_force(u1, f),
            };
            if !ok {
                return false;
            }
            if matrix {
                let sym = &mut ws.sym[bi];
                for (s, m) in sym.iter_mut().zip(body.mass()) {
                    *s = alpha * m;
                }
                match scheme {
                    Some(MultibodyScheme::EnergyMomentum) => {
                        let skew = &mut ws.skew[bi];
                        skew.iter_mut().for_each(|v| *v = 0.0);
                        body.add_discrete_gradient_tangent_split(u0, u1, 1.0, sym, skew);
                    }
                    Some(MultibodyScheme::Midpoint) => body.add_tangent(um, 0.5, sym),
                    _ => body.add_tangent(u1, 1.0, sym),
                }
            }
        }
    }
    for i in 0..n {
        let inertia = alpha * ws.md[i];
        ws.r[i] = inertia + ws.force[i] - ws.b[i];
        ws.scale[i] = inertia.abs() + ws.force[i].abs().max(ws.force_round_off[i]) + ws.b[i].abs();
    }
    true
}

/// `out` = u − ū: u with its mean ū over the nodes subtracted in each component that every node
/// carries (`dofs[c]`; a component held somewhere is left as it is).
///
/// A linear body's force K u at u₀ + θ d is evaluated as K (u₀ − ū₀) + θ K (d − d̄): K
/// annihilates translations, so the value is the same, but the round-off is ε |K| (|u₀ − ū₀| +
/// |d − d̄|) — the deformation — instead of ε |K| |u₀ + θ d|: a stiff body that has slid far
/// from its reference position carries the absolute rounding ε |u| of its total displacement
/// into every iterate, and K maps it to forces ε |K| |u| (E = 1e8, |u| ≈ 0.1: ≈ 1e−9, above the
/// Newton tolerance 1e−12 s of a step whose forces are of order 1, and above the floor band
/// 100 × that). The two blocks of `verification/cases/multibody_friction.toml` did not converge
/// in their second to twelfth step; with the split form the rounding of u₀ is a constant of the
/// step and the increment's is relative to the step's own deformation.
fn translated_out(u: &[f64], dofs: &[Option<Vec<usize>>; 2], out: &mut [f64]) {
    out.copy_from_slice(u);
    for d in dofs.iter().flatten() {
        if d.is_empty() {
            continue;
        }
        let mean = d.iter().map(|&i| u[i]).sum::<f64>() / d.len() as f64;
        for &i in d {
            out[i] = u[i] - mean;
        }
    }
}

/// A hash of the candidates' states (active, stick/slip, segment): what must not change in the
/// converged iteration, and what repeats when the active set cycles.
/// A penalty candidate's contact flag is left out: its force is C¹ across g = 0 (the residual's
/// formula does not change), so Newton and the line search may cross it.
fn signature(candidates: &[Candidate], laws: &[PairLaw]) -> Vec<(bool, i8, usize)> {
    candidates
        .iter()
        .map(|c| {
            let active = c.active && laws[c.pair].has_normal_multiplier();
            let t = match c.tangent {
                Tangent::Free => 0,
                Tangent::Stick => 1,
                Tangent::Slip(d) => {
                    if d > 0.0 {
                        2
                    } else {
                        3
                    }
                }
            };
            (active, t, c.segment.unwrap_or(usize::MAX))
        })
        .collect()
}

/// The fraction of the Newton step δ to take when a penalty contact open at the iterate
/// (g > 0 where the scheme evaluates its force: x₁, or x_{1/2} for the midpoint rule) would close
/// along it. The linearized model on the open side has no penalty stiffness, so the full step
/// lands as deep as the free motion (ε/M times the penalized penetration): the step stops at
/// t* (g = 0 on the linearized path) plus 1 % of the rest, and Newton continues with the
/// penalty's stiffness. 1 when no penalty contact closes.
fn penalty_entry_step(
    candidates: &[Candidate],
    data: &StepData<'_>,
    forms: &InvariantForms,
    u1: &[f64],
    delta: &[f64],
) -> f64 {
    let midpoint = data.kind.evaluation() == Evaluation::Midpoint;
    let mut step = 1.0f64;
    for c in candidates {
        if data.laws[c.pair].has_normal_multiplier() {
            continue;
        }
        let mut dx = Local6::zeros();
        for (i, dof) in c.dofs.iter().enumerate() {
            if let Some(dof) = dof {
                dx[i] = delta[*dof];
            }
        }
        let x1 = c.positions(u1);
        let (x, dx) = if midpoint {
            (0.5 * (c.x0 + x1), 0.5 * dx)
        } else {
            (x1, dx)
        };
        let (g, dg) = value_and_gradient(forms, &Gap, &x);
        let g_full = g + dg.dot(&dx);
        if g > 0.0 && g_full < 0.0 {
            let t = g / (g - g_full);
            step = step.min(t + 0.01 * (1.0 - t));
        }
    }
    step
}

/// Re-pairs candidate `c` with segment `segment` of its master surface, at the start positions
/// u₀ (g₀, τ₀ and ℓ of the new pairing).
pub fn pair_with_segment(
    c: &mut Candidate,
    bodies: &BodySet,
    slave_body: usize,
    master: &ContactSurface,
    segment: usize,
    u0: &[f64],
    forms: &InvariantForms,
) {
    let [n1, n2] = master.segments[segment];
    let mb = master.body;
    let xs = bodies.reference(slave_body, c.slave);
    let (x1, x2) = (bodies.reference(mb, n1), bodies.reference(mb, n2));
    c.segment = Some(segment);
    c.dofs = [
        bodies.dof(slave_body, c.slave, 0),
        bodies.dof(slave_body, c.slave, 1),
        bodies.dof(mb, n1, 0),
        bodies.dof(mb, n1, 1),
        bodies.dof(mb, n2, 0),
        bodies.dof(mb, n2, 1),
    ];
    c.reference = Local6::from_column_slice(&[xs[0], xs[1], x1[0], x1[1], x2[0], x2[1]]);
    c.x0 = c.positions(u0);
    let a = [c.x0[4] - c.x0[2], c.x0[5] - c.x0[3]];
    c.ell = (a[0] * a[0] + a[1] * a[1]).sqrt();
    let (g0, tau0) = c.gap_and_tangential(forms, &c.x0);
    c.g0 = g0;
    c.tau0 = tau0;
}

/// The coordinates of a candidate's patch: its slave node, then the nodes of its master segment
/// and of the segments before and after it (the foundation: the slave node only).
fn patch_dofs(c: &Candidate, data: &StepData<'_>, slave_body: usize) -> PatchDofs {
    let b = data.bodies;
    let mut patch = [None; 10];
    patch[0] = b.dof(slave_body, c.slave, 0);
    patch[1] = b.dof(slave_body, c.slave, 1);
    let (Some(seg), MasterRef::Surface(m)) = (c.segment, data.masters[c.pair]) else {
        return patch;
    };
    let mut nodes = Vec::with_capacity(4);
    if let Some(p) = m.previous[seg] {
        nodes.push(m.segments[p][0]);
    }
    nodes.extend_from_slice(&m.segments[seg]);
    if let Some(n) = m.next[seg] {
        nodes.push(m.segments[n][1]);
    }
    nodes.dedup();
    for (i, &node) in nodes.iter().take(4).enumerate() {
        patch[2 + 2 * i] = b.dof(m.body, node, 0);
        patch[3 + 2 * i] = b.dof(m.body, node, 1);
    }
    patch
}

/// Solves one step: on return `d` holds the increment and the candidates their multipliers,
/// states and g₁, τ₁. `slave_bodies[pair]` is the body of each pair's slave surface.
pub fn solve_step(
    data: &StepData<'_>,
    slave_bodies: &[usize],
    candidates: &mut Vec<Candidate>,
    d: &mut [f64],
    params: &NewtonParams,
    max_switches: usize,
    ws: &mut StepWorkspace,
) -> Result<StepReport, SolveError> {
    let n = data.bodies.dofs();
    let at = data.kind.evaluation();
    let mut report = StepReport::default();
    let mut switch_count = vec![0usize; candidates.len()];
    let mut visited: Vec<Vec<usize>> = vec![Vec::new(); candidates.len()];
    let mut prev_sig: Option<Vec<(bool, i8, usize)>> = None;
    let mut history: Vec<Vec<(bool, i8, usize)>> = Vec::new();
    let mut residuals: Vec<f64> = Vec::new();
    let mut unchanged = 0usize;
    let mut last = f64::INFINITY;
    // the worst row's residual and threshold relative to the largest row scale s (the error's
    // like-for-like comparison)
    let mut last_relative = (f64::INFINITY, params.tolerance);
    // the monotone line search on ‖D⁻¹ R‖₂: the point and the Newton direction of the last update
    let mut line: Option<LineState> = None;
    let mut merit_scales: Option<(f64, f64)> = None;
    // the predictor (k v_n for a dynamic step) cut back towards u_n while it would invert a body:
    // at a large step the velocities of a vibrating body carry elements through det F = 0
    for _ in 0..=params.max_backtracks {
        for i in 0..n {
            ws.um[i] = data.u0[i] + d[i];
        }
        let ok = data
            .bodies
            .bodies()
            .iter()
            .enumerate()
            .all(|(b, body)| body.is_linear() || body.admissible(&ws.um[data.bodies.range(b)]));
        if ok {
            break;
        }
        d.iter_mut().for_each(|x| *x *= 0.5);
    }
    for iteration in 1..=params.max_iterations {
        crate::run_control::check(|| {
            format!(
                "step {} (t = {}), Newton iteration {iteration}",
                data.at.step, data.at.time
            )
        })?;
        report.iterations = iteration;
        // the layout of the system (anew after a switch or a release)
        let relayout = match &ws.system {
            Some(s) => !s.serves(candidates),
            None => true,
        };
        if relayout {
            let patches: Vec<PatchDofs> = candidates
                .iter()
                .map(|c| patch_dofs(c, data, slave_bodies[c.pair]))
                .collect();
            let sys = StepSystem::new(data.bodies, candidates, &patches, data.laws)?;
            report.analyses += 1;
            ws.system = Some(sys);
        } else if let Some(s) = &ws.system {
            s.number(candidates);
        }
        let Some(mut sys) = ws.system.take() else {
            unreachable!("laid out above")
        };
        let total = sys.order();
        ws.r.resize(total, 0.0);
        if !assemble_bodies(data, d, ws, true) {
            ws.system = Some(sys);
            return Err(SolveError::NonFinite {
                step: data.at.step,
                time: data.at.time,
                quantity: "stored energy (an element inverted, det F ≤ 0)".into(),
                value: f64::INFINITY,
                hint: " — try a smaller step".into(),
            });
        }
        sys.clear();
        for b in 0..data.bodies.len() {
            sys.add_body(b, &ws.sym[b], &ws.skew[b]);
        }
        let s_u = ws
            .scale
            .iter()
            .fold(0.0f64, |m, v| m.max(*v))
            .max(f64::MIN_POSITIVE);
        // the row scale c: the largest diagonal of the bodies' blocks
        let c = {
            let mut m = 0.0f64;
            for b in 0..data.bodies.len() {
                let p = data.bodies.body(b).pattern();
                for i in 0..p.order() {
                    if let Some(slot) = p.diagonal_slot(i) {
                        m = m.max(ws.sym[b][slot].abs());
                    }
                }
            }
            m.max(f64::MIN_POSITIVE)
        };
        let scale = RowScale {
            c,
            regularization: 1e-12,
            hysteresis: iteration > 1,
        };
        let mut worst_row = WorstRow::default();
        let mut bound_c = 0.0;
        let mut rc2 = 0.0;
        let mut x_all = 0.0f64;
        for (ci, cand) in candidates.iter_mut().enumerate() {
            let x1 = cand.positions(&ws.u1);
            let law = &data.laws[cand.pair];
            let out = cand.contribute(&ws.forms, law, at, &x1, scale);
            for (i, dof) in cand.dofs.iter().enumerate() {
                if let Some(dof) = dof {
                    ws.r[*dof] += out.r_u[i];
                    ws.scale[*dof] += out.r_u[i].abs();
                }
            }
            let xmax = x1.amax();
            // a constraint row's threshold: the relative tolerance, plus its round-off floor
            // 16 ε c |x| (c g₁ is computed from coordinates of size |x|)
            let tol_c = params.tolerance * s_u + 16.0 * f64::EPSILON * c * xmax;
            x_all = x_all.max(xmax);
            if let Some(ln) = cand.ln {
                ws.r[ln] = out.r_n;
                worst_row.take(out.r_n.abs(), tol_c, params.tolerance * s_u);
                rc2 += out.r_n * out.r_n;
                bound_c += cand.lambda_n.abs() * out.r_n.abs() / c;
            }
            if let Some(lt) = cand.lt {
                ws.r[lt] = out.r_t;
                worst_row.take(out.r_t.abs(), tol_c, params.tolerance * s_u);
                rc2 += out.r_t * out.r_t;
                bound_c += cand.lambda_t.abs() * out.r_t.abs() / c;
            }
            sys.add_candidate(ci, &cand.dofs, &out.jac);
        }
        let s_u = ws
            .scale
            .iter()
            .fold(0.0f64, |m, v| m.max(*v))
            .max(f64::MIN_POSITIVE);
        let r_u = ws.r[..n].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        // each momentum row against the larger of the relative tolerance tol · s and its own
        // computed round-off floor C ε s_i (s_i = Σ |terms| of row i)
        for i in 0..n {
            let floor = FLOOR_ROUNDINGS * f64::EPSILON * ws.scale[i];
            let tol = params.tolerance * s_u;
            worst_row.take(ws.r[i].abs(), tol.max(floor), tol);
        }
        let worst = worst_row.ratio;
        if !r_u.is_finite() || !worst.is_finite() {
            ws.system = Some(sys);
            return Err(SolveError::NonFinite {
                step: data.at.step,
                time: data.at.time,
                quantity: format!("step residual at Newton iteration {iteration}"),
                value: r_u,
                hint: " — the step's data overflow, or the scheme lost stability (try \
                       energy_momentum or a smaller step)"
                    .into(),
            });
        }
        // the line search: a full Newton step that did not decrease the scaled ‖D⁻¹ R‖₂ is
        // halved (D: the rows' tolerances at the step's first iteration, fixed in the step, so that every row's round-off weighs alike — the
        // plain ‖R‖₂ of stiff bodies sits on the noise of their force rows while the other rows
        // still converge; the Newton direction descends on any fixed row scaling). Compared
        // only between iterations without a switch or a change of states (they change R).
        let (w_u, w_c) = *merit_scales.get_or_insert_with(|| {
            let w_u = params.tolerance * s_u;
            (w_u, w_u + 16.0 * f64::EPSILON * c * x_all)
        });
        let merit = {
            let ru2 = ws.r[..n].iter().map(|v| v * v).sum::<f64>();
            (ru2 / (w_u * w_u) + rc2 / (w_c * w_c)).sqrt()
        };
        if let Some(l) = &mut line {
            if l.worst > 100.0
                && l.states == signature(candidates, data.laws)
                && merit > (1.0 - 1e-4 * l.step) * l.merit
                && l.halvings < params.max_backtracks
            {
                l.step *= 0.5;
                l.halvings += 1;
                report.backtracks += 1;
                for i in 0..n {
                    d[i] = l.d[i] + l.step * l.delta[i];
                }
                for (cand, (lam, dlam)) in
                    candidates.iter_mut().zip(l.lambda.iter().zip(&l.dlambda))
                {
                    cand.lambda_n = lam.0 + l.step * dlam.0;
                    cand.lambda_t = lam.1 + l.step * dlam.1;
                }
                ws.system = Some(sys);
                continue;
            }
        }
        let sig = signature(candidates, data.laws);
        let same = prev_sig.as_ref() == Some(&sig);
        unchanged = if same { unchanged + 1 } else { 0 };
        residuals.push(worst);
        let floor = unchanged >= 3
            && worst <= 100.0
            && residuals.len() >= 4
            && worst > 0.5 * residuals[residuals.len() - 4];
        if same && (worst <= 1.0 || floor) {
            // a node past the free end of its master (no neighbouring segment) leaves it: drop
            // it and iterate again if it carried a force (a node in the dead zone of a convex
            // master vertex, beyond both segments' ends, stays on the extended segment)
            let beyond: Vec<bool> = candidates
                .iter()
                .map(|c| {
                    let (Some(seg), MasterRef::Surface(m)) = (c.segment, data.masters[c.pair])
                    else {
                        return false;
                    };
                    let xi = c.xi(&ws.forms, &c.positions(&ws.u1));
                    (xi > 1.0 + RELEASE_TOLERANCE && m.next[seg].is_none())
                        || (xi < -RELEASE_TOLERANCE && m.previous[seg].is_none())
                })
                .collect();
            if beyond.iter().any(|b| *b) {
                let forced = candidates
                    .iter()
                    .zip(&beyond)
                    .any(|(c, b)| *b && (c.active || c.lambda_t != 0.0));
                report.releases += beyond.iter().filter(|b| **b).count();
                let mut i = 0;
                candidates.retain(|_| {
                    i += 1;
                    !beyond[i - 1]
                });
                let mut j = 0;
                switch_count.retain(|_| {
                    j += 1;
                    !beyond[j - 1]
                });
                let mut v = 0;
                visited.retain(|_| {
                    v += 1;
                    !beyond[v - 1]
                });
                if forced {
                    ws.system = Some(sys);
                    prev_sig = None;
                    line = None;
                    continue;
                }
            }
            report.floor_stop = worst > 1.0 || worst_row.at_floor;
            report.residual = r_u;
            report.residual_sum = ws.r[..n].iter().map(|v| v.abs()).sum();
            // the lever arm of the moments: √2 · max |x| over the nodes, bounded by 2 max |X| + |u|
            let lever = {
                let xmax = data
                    .bodies
                    .bodies()
                    .iter()
                    .flat_map(|b| b.data().mesh.nodes().iter())
                    .fold(0.0f64, |m, x| m.max(x[0].abs()).max(x[1].abs()));
                let umax = ws
                    .u1
                    .iter()
                    .chain(data.u0.iter())
                    .fold(0.0f64, |m, v| m.max(v.abs()));
                2.0 * (xmax + umax)
            };
            report.residual_moment = lever * report.residual_sum;
            report.work_scale = ws.scale[..n]
                .iter()
                .zip(d.iter())
                .map(|(a, b)| a * b.abs())
                .sum();
            report.force_scale = ws.scale[..n].iter().sum();
            report.moment_scale = lever * report.force_scale;
            report.newton_bound = d.iter().map(|x| x.abs()).sum::<f64>() * r_u + bound_c;
            for cand in candidates.iter_mut() {
                let x1 = cand.positions(&ws.u1);
                let (g1, tau1) = cand.gap_and_tangential(&ws.forms, &x1);
                cand.g1 = g1;
                cand.tau1 = tau1;
            }
            ws.system = Some(sys);
            return Ok(report);
        }
        history.push(sig.clone());
        prev_sig = Some(sig);
        // the Newton step
        let mut delta: Vec<f64> = ws.r.iter().map(|v| -v).collect();
        let solved = sys.solve(&mut delta);
        ws.system = Some(sys);
        solved?;
        // a penalty contact about to close: stop just past g = 0 (penalty_entry_step), then
        // Newton continues on the stiff side; cut back further only where a body would be
        // inverted
        let mut step = penalty_entry_step(candidates, data, &ws.forms, &ws.u1, &delta);
        for _ in 0..=params.max_backtracks {
            for i in 0..n {
                ws.trial[i] = d[i] + step * delta[i];
            }
            for i in 0..n {
                ws.um[i] = data.u0[i] + ws.trial[i];
            }
            let ok =
                data.bodies.bodies().iter().enumerate().all(|(b, body)| {
                    body.is_linear() || body.admissible(&ws.um[data.bodies.range(b)])
                });
            if ok {
                break;
            }
            step *= 0.5;
        }
        let mut state = LineState {
            d: d.to_vec(),
            delta: delta[..n].iter().map(|v| step * v).collect(),
            lambda: candidates
                .iter()
                .map(|c| (c.lambda_n, c.lambda_t))
                .collect(),
            dlambda: candidates
                .iter()
                .map(|c| {
                    (
                        c.ln.map_or(0.0, |i| step * delta[i]),
                        c.lt.map_or(0.0, |i| step * delta[i]),
                    )
                })
                .collect(),
            merit,
            worst,
            states: prev_sig.clone().unwrap_or_default(),
            step: 1.0,
            halvings: 0,
        };
        d.copy_from_slice(&ws.trial[..n]);
        for (cand, dl) in candidates.iter_mut().zip(&state.dlambda) {
            cand.lambda_n += dl.0;
            cand.lambda_t += dl.1;
        }
        last = worst;
        last_relative = (worst_row.residual / s_u, worst_row.threshold / s_u);
        // segment switching (a node past a segment's end moves to the neighbour there)
        for i in 0..n {
            ws.u1[i] = data.u0[i] + d[i];
        }
        for (ci, cand) in candidates.iter_mut().enumerate() {
            let (Some(seg), MasterRef::Surface(master)) = (cand.segment, data.masters[cand.pair])
            else {
                continue;
            };
            let xi = cand.xi(&ws.forms, &cand.positions(&ws.u1));
            let target = if xi > 1.0 + SWITCH_TOLERANCE {
                master.next[seg]
            } else if xi < -SWITCH_TOLERANCE {
                master.previous[seg]
            } else {
                None
            };
            if let Some(next) = target {
                // only onto a segment the node projects onto: a node in the dead zone of a convex
                // master vertex (beyond both segments' ends) stays on the extended segment
                let [n1, n2] = master.segments[next];
                let xs = data
                    .bodies
                    .position(slave_bodies[cand.pair], cand.slave, &ws.u1);
                let (x1, x2) = (
                    data.bodies.position(master.body, n1, &ws.u1),
                    data.bodies.position(master.body, n2, &ws.u1),
                );
                let onto = crate::model::multibody::search::project(xs, x1, x2, next).xi;
                let projects = (-SWITCH_TOLERANCE..=1.0 + SWITCH_TOLERANCE).contains(&onto);
                // and never back to a segment it left in this step: a node at a convex master
                // vertex, held on one segment's line, lands just past its end where the next
                // segment claims it, and back (the vertex's non-smoothness); it stays on the
                // second segment, within the distance the two lines differ there
                let revisit = visited[ci].contains(&next);
                if projects && !revisit && switch_count[ci] < max_switches {
                    visited[ci].push(seg);
                    switch_count[ci] += 1;
                    report.switches += 1;
                    pair_with_segment(
                        cand,
                        data.bodies,
                        slave_bodies[cand.pair],
                        master,
                        next,
                        data.u0,
                        &ws.forms,
                    );
                    cand.switched = true;
                    cand.was_active = false;
                    cand.tangent = Tangent::Free;
                    state.halvings = usize::MAX;
                }
            }
        }
        // no line search across a switch (the residual changed its definition)
        line = (state.halvings == 0).then_some(state);
    }
    // out of iterations: a cycle if a state repeated
    let period = history
        .iter()
        .rev()
        .skip(1)
        .position(|s| Some(s) == history.last());
    if let Some(p) = period {
        let last_sig = &history[history.len() - 1];
        let cycle = &history[history.len() - 2 - p..];
        let changing: Vec<String> = candidates
            .iter()
            .enumerate()
            .filter(|(i, _)| {
                i < &last_sig.len() && cycle.iter().any(|s| s.get(*i) != last_sig.get(*i))
            })
            .take(6)
            .map(|(_, c)| match c.segment {
                Some(s) => format!("pair {} slave node {} on segment {s}", c.pair, c.slave),
                None => format!("pair {} slave node {} on the foundation", c.pair, c.slave),
            })
            .collect();
        if !changing.is_empty() {
            return Err(SolveError::ActiveSetCycle {
                step: data.at.step,
                time: data.at.time,
                iterations: params.max_iterations,
                residual: last,
                period: p + 1,
                constraints: changing.join(", "),
            });
        }
    }
    Err(SolveError::NewtonNotConverged {
        step: data.at.step,
        time: data.at.time,
        iterations: params.max_iterations,
        residual: last_relative.0,
        // the worst row's relative threshold max(tol, floor_i / s): its floor where above tol
        tolerance: last_relative.1,
    })
}

#[cfg(test)]
mod tests {
    //! A stiff linear body far from its reference position: the split evaluation of K u keeps the
    //! round-off of the deformation, not of the total displacement.
    use std::sync::Arc;

    use super::*;
    use crate::field::Field;
    use crate::material::hyperelastic::LinearElastic;
    use crate::mesh::triangle::{Diagonal, TriangleMesh};
    use crate::model::dynamic::bar::MassMatrix;
    use crate::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};

    #[test]
    fn linear_force_far_from_the_reference_has_the_round_off_of_the_deformation() {
        let body = PlaneBody::new(PlaneBodyData {
            mesh: TriangleMesh::rectangle([0.0, 0.0], [1.0, 0.5], [5, 3], Diagonal::Up).unwrap(),
            density: 1.0,
            law: Arc::new(LinearElastic::from_young_poisson(1e8, 0.0).unwrap()),
            dirichlet: vec![],
            traction: vec![],
            body_force: [Field::Constant(0.0), Field::Constant(0.0)],
            mass: MassMatrix::Consistent,
            regions: vec![],
        })
        .unwrap();
        let bodies = BodySet::new(vec![Arc::new(body)]).unwrap();
        let n = bodies.dofs();
        // a deformation of 1e−9 on a translation of order 1, and a step that translates by 1e−2
        let deform = |i: usize, s: f64| s * 1e-9 * ((i * 7 % 11) as f64 - 5.0);
        let translate = |i: usize, t: [f64; 2]| t[i % 2];
        let u0: Vec<f64> = (0..n)
            .map(|i| translate(i, [0.7, -0.3]) + deform(i, 1.0))
            .collect();
        let d: Vec<f64> = (0..n)
            .map(|i| translate(i, [1e-2, 3e-3]) + deform(i, 0.5))
            .collect();
        let scheme = MultibodyScheme::Midpoint;
        let k = 0.01;
        let mut ws = StepWorkspace::new(&bodies, StepKind::Dynamic(scheme), k);
        let data = StepData {
            bodies: &bodies,
            laws: &[],
            masters: &[],
            kind: StepKind::Dynamic(scheme),
            k,
            u0: &u0,
            at: StepAt { step: 1, time: k },
        };
        ws.r.resize(n, 0.0);
        assert!(assemble_bodies(&data, &d, &mut ws, false));
        // the reference: K applied to the stored state's deformation at the midpoint alone (u₀ −
        // t₀ and d − t_d are exact: Sterbenz)
        let kk = bodies.body(0).linear_stiffness().unwrap();
        let um: Vec<f64> = (0..n)
            .map(|i| {
                (u0[i] - translate(i, [0.7, -0.3])) + 0.5 * (d[i] - translate(i, [1e-2, 3e-3]))
            })
            .collect();
        let mut reference = vec![0.0; n];
        bodies
            .body(0)
            .pattern()
            .symmetric_mul(kk, &um, &mut reference);
        let scale = reference.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let error = ws
            .force
            .iter()
            .zip(&reference)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        // K u of the total displacement rounds at ε |K| |u| ≈ 1e−8 here
        let mut naive = vec![0.0; n];
        let total: Vec<f64> = (0..n).map(|i| u0[i] + 0.5 * d[i]).collect();
        bodies
            .body(0)
            .pattern()
            .symmetric_mul(kk, &total, &mut naive);
        let naive_error = naive
            .iter()
            .zip(&reference)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(error < 1e-6 * scale, "split: {error:e} (scale {scale:e})");
        assert!(
            naive_error > 100.0 * error,
            "naive {naive_error:e} vs split {error:e}"
        );
    }
}
