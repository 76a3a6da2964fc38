//! The time loop of a multibody contact problem: contact search at the start of every step, the
//! step's Newton method ([`super::step`]), the velocity update, the audit ([`super::audit`]) and
//! the outputs; and the static equilibrium of the same system (the contact patch test).

use std::time::Instant;

use serde::Serialize;

use crate::error::{require_positive, Error, InputError, SolveError};
use crate::model::dynamic::body::ElasticBody;
use crate::model::dynamic::newton::NewtonParams;
use crate::model::multibody::audit::{
    step_tolerance, summarize, EnergyGuard, MultibodyRecord, MultibodySummary, PositiveWork,
};
use crate::model::multibody::bodies::BodySet;
use crate::model::multibody::constraint::{Candidate, Enforcement, PairLaw, Tangent};
use crate::model::multibody::invariants::{InvariantForms, Local6};
use crate::model::multibody::scheme::MultibodyScheme;
use crate::model::multibody::search::SegmentTree;
use crate::model::multibody::step::{
    pair_with_segment, solve_step, MasterRef, StepAt, StepData, StepKind, StepReport, StepWorkspace,
};
use crate::model::multibody::surface::{ContactSurface, Foundation};

/// The master side of a pair.
#[derive(Debug, Clone)]
pub enum PairMaster {
    /// The segments of a body's boundary part.
    Surface(ContactSurface),
    /// The rigid foundation.
    Foundation(Foundation),
}

/// One contact pair: slave nodes against a master, with its enforcement and friction. A two-pass
/// contact is two pairs with the roles exchanged.
#[derive(Debug, Clone)]
pub struct ContactPair {
    pub slave: ContactSurface,
    pub master: PairMaster,
    pub law: PairLaw,
}

/// A multibody problem: bodies, contact pairs, scheme, time interval and initial state (the
/// system's free dofs).
#[derive(Debug, Clone)]
pub struct MultibodyProblem {
    pub bodies: BodySet,
    pub pairs: Vec<ContactPair>,
    pub scheme: MultibodyScheme,
    pub final_time: f64,
    pub steps: usize,
    pub initial_displacement: Vec<f64>,
    pub initial_velocity: Vec<f64>,
}

/// Parameters of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct MultibodyParams {
    pub newton: NewtonParams,
    /// Segment switches allowed per candidate and step (then the node stays where it is).
    pub max_switches: usize,
    /// Times at which to keep the state (nearest step).
    pub snapshot_times: Vec<f64>,
    /// The search margin as a multiple of the longest master segment (plus twice the distance the
    /// fastest node covers in a step).
    pub search_margin: f64,
    /// Per solver pair: accept an energy–momentum run whose energy rose through this pair's
    /// positive activation or switch work (otherwise [`SolveError::EnergyGain`]); empty: none.
    pub allow_energy_gain: Vec<bool>,
}

impl Default for MultibodyParams {
    fn default() -> Self {
        Self {
            newton: NewtonParams::default(),
            max_switches: 4,
            snapshot_times: Vec::new(),
            search_margin: 1.0,
            allow_energy_gain: Vec::new(),
        }
    }
}

/// Statistics of a run.
#[derive(Debug, Clone, Default, Serialize)]
pub struct MultibodyStats {
    pub steps: usize,
    pub unknowns: usize,
    pub max_candidates: usize,
    pub newton_iterations: usize,
    pub max_newton_iterations: usize,
    /// Symbolic analyses of the step matrix (one per change of the candidates' layout).
    pub analyses: usize,
    pub switches: usize,
    pub releases: usize,
    pub floor_stops: usize,
    /// Halvings of the Newton line search.
    pub backtracks: usize,
    /// Steps redone with a larger search margin because a node outside the candidates
    /// penetrated a master.
    pub search_retries: usize,
    pub search_seconds: f64,
    pub loop_seconds: f64,
    pub setup_seconds: f64,
}

/// A candidate's state after a step (what results files and plots show).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactState {
    pub pair: usize,
    /// The slave node (mesh node of the pair's slave body) and its tributary length.
    pub slave: usize,
    pub weight: f64,
    /// The master segment (None: the foundation).
    pub segment: Option<usize>,
    pub lambda_n: f64,
    pub lambda_t: f64,
    pub gap: f64,
    /// τ₁ − τ₀ of the step.
    pub slip: f64,
    pub active: bool,
    pub stick: bool,
}

/// The state at an output time.
#[derive(Debug, Clone, Serialize)]
pub struct MultibodySnapshot {
    pub step: usize,
    pub time: f64,
    pub displacement: Vec<f64>,
    pub velocity: Vec<f64>,
    pub contacts: Vec<ContactState>,
}

/// What an observer sees after each step (and once for the initial state).
#[derive(Debug)]
pub struct MultibodyStepView<'a> {
    pub step: usize,
    pub time: f64,
    pub displacement: &'a [f64],
    pub velocity: &'a [f64],
    pub contacts: &'a [ContactState],
    pub record: &'a MultibodyRecord,
}

/// The result of a run.
#[derive(Debug, Clone, Default, Serialize)]
pub struct MultibodySolution {
    pub records: Vec<MultibodyRecord>,
    pub snapshots: Vec<MultibodySnapshot>,
    pub final_displacement: Vec<f64>,
    pub final_velocity: Vec<f64>,
    pub stats: MultibodyStats,
}

impl MultibodySolution {
    /// The audit summary.
    pub fn summary(&self) -> MultibodySummary {
        summarize(&self.records)
    }
}

/// The result of a static solve.
#[derive(Debug, Clone, Serialize)]
pub struct StaticSolution {
    pub displacement: Vec<f64>,
    pub contacts: Vec<ContactState>,
    pub iterations: usize,
}

/// The solver of a multibody problem.
#[derive(Debug)]
pub struct MultibodySolver {
    problem: MultibodyProblem,
    params: MultibodyParams,
}

/// The carried state of a slave node between steps.
#[derive(Debug, Clone, Copy)]
struct Carried {
    segment: Option<usize>,
    lambda_n: f64,
    lambda_t: f64,
    active: bool,
    tangent: Tangent,
}

impl MultibodySolver {
    /// Validates the problem.
    pub fn new(problem: MultibodyProblem, params: MultibodyParams) -> Result<Self, Error> {
        let n = problem.bodies.dofs();
        require_positive("time.final_time", problem.final_time)?;
        if problem.steps == 0 {
            return Err(InputError::new("time.steps", 0, "at least 1 step").into());
        }
        params.newton.validate()?;
        require_positive("solver.search_margin", params.search_margin)?;
        for (name, v) in [
            ("initial.displacement", &problem.initial_displacement),
            ("initial.velocity", &problem.initial_velocity),
        ] {
            if v.len() != n {
                return Err(InputError::new(
                    name,
                    format!("{} values", v.len()),
                    format!("{n} values (one per free dof of the bodies)"),
                )
                .into());
            }
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Err(
                    InputError::new(format!("{name}[{i}]"), v[i], "a finite number").into(),
                );
            }
        }
        for (p, pair) in problem.pairs.iter().enumerate() {
            let field = format!("contact_pair[{p}]");
            if let Enforcement::Penalty { stiffness } | Enforcement::Compliant { stiffness } =
                pair.law.enforcement
            {
                require_positive(&format!("{field}.enforcement.stiffness"), stiffness)?;
            }
            if !(pair.law.friction.is_finite() && pair.law.friction >= 0.0) {
                return Err(InputError::new(
                    format!("{field}.friction"),
                    pair.law.friction,
                    "μ ≥ 0",
                )
                .into());
            }
            if pair.law.friction > 0.0 && !pair.law.has_normal_multiplier() {
                return Err(InputError::new(
                    format!("{field}.friction"),
                    pair.law.friction,
                    "0 with penalty enforcement (friction needs a normal multiplier: enforcement = \
                     \"lagrange\" or \"compliant\")",
                )
                .into());
            }
            if pair.slave.body >= problem.bodies.len() {
                return Err(InputError::new(
                    format!("{field}.slave"),
                    pair.slave.body,
                    "a body index",
                )
                .into());
            }
            if let PairMaster::Surface(m) = &pair.master {
                if m.body >= problem.bodies.len() {
                    return Err(
                        InputError::new(format!("{field}.master"), m.body, "a body index").into(),
                    );
                }
                if m.body == pair.slave.body {
                    return Err(InputError::new(
                        format!("{field}.master"),
                        m.body,
                        "a body other than the slave's (self-contact is not modelled)",
                    )
                    .into());
                }
            }
        }
        Ok(Self { problem, params })
    }

    /// The problem.
    pub fn problem(&self) -> &MultibodyProblem {
        &self.problem
    }

    /// The step size k = T / N.
    pub fn step_size(&self) -> f64 {
        self.problem.final_time / self.problem.steps as f64
    }

    fn laws(&self) -> Vec<PairLaw> {
        self.problem.pairs.iter().map(|p| p.law).collect()
    }

    fn masters(&self) -> Vec<MasterRef<'_>> {
        self.problem
            .pairs
            .iter()
            .map(|p| match &p.master {
                PairMaster::Surface(s) => MasterRef::Surface(s),
                PairMaster::Foundation(_) => MasterRef::Foundation,
            })
            .collect()
    }

    /// The candidates at positions u (the search), carrying multipliers and states of the
    /// previous step where a slave node keeps its master segment.
    fn search(
        &self,
        u: &[f64],
        margin_extra: f64,
        carried: &[Vec<Option<Carried>>],
        forms: &InvariantForms,
    ) -> Vec<Candidate> {
        let bodies = &self.problem.bodies;
        let mut out = Vec::new();
        for (p, pair) in self.problem.pairs.iter().enumerate() {
            let sb = pair.slave.body;
            let make = |index: usize, node: usize| Candidate {
                pair: p,
                slave: node,
                slave_index: index,
                segment: None,
                dofs: [None; 6],
                reference: Local6::zeros(),
                x0: Local6::zeros(),
                ell: 1.0,
                g0: 0.0,
                tau0: 0.0,
                g1: 0.0,
                tau1: 0.0,
                lambda_n: 0.0,
                lambda_t: 0.0,
                ln: None,
                lt: None,
                active: false,
                was_active: false,
                tangent: Tangent::Free,
                switched: false,
                held: false,
            };
            let carry = |c: &mut Candidate| {
                if let Some(Some(prev)) = carried.get(p).and_then(|v| v.get(c.slave_index)) {
                    c.held = prev.active;
                    c.lambda_n = prev.lambda_n;
                    c.lambda_t = prev.lambda_t;
                    if prev.segment == c.segment {
                        c.was_active = prev.active;
                        c.active = prev.active;
                        c.tangent = prev.tangent;
                    } else if !pair.law.has_normal_multiplier() && prev.segment.is_some() {
                        // a penalty node the search moved to another segment: its P is now
                        // measured from another line (the works' redefinition jump)
                        c.switched = true;
                    }
                }
            };
            match &pair.master {
                PairMaster::Foundation(f) => {
                    let [x1, x2] = f.segment();
                    let margin = self.params.search_margin
                        * pair.slave.longest_segment(bodies.body(sb))
                        + margin_extra;
                    for (i, &node) in pair.slave.nodes.iter().enumerate() {
                        let xs = bodies.position(sb, node, u);
                        let gap = f.normal[0] * xs[0] + f.normal[1] * xs[1] - f.level;
                        if gap > margin {
                            continue;
                        }
                        let mut c = make(i, node);
                        c.dofs[0] = bodies.dof(sb, node, 0);
                        c.dofs[1] = bodies.dof(sb, node, 1);
                        let r = bodies.reference(sb, node);
                        c.reference =
                            Local6::from_column_slice(&[r[0], r[1], x1[0], x1[1], x2[0], x2[1]]);
                        c.x0 = c.positions(u);
                        let (g0, tau0) = c.gap_and_tangential(forms, &c.x0);
                        c.g0 = g0;
                        c.tau0 = tau0;
                        carry(&mut c);
                        out.push(c);
                    }
                }
                PairMaster::Surface(master) => {
                    let mb = master.body;
                    let ends: Vec<[[f64; 2]; 2]> = master
                        .segments
                        .iter()
                        .map(|s| [bodies.position(mb, s[0], u), bodies.position(mb, s[1], u)])
                        .collect();
                    let longest = ends
                        .iter()
                        .map(|e| ((e[1][0] - e[0][0]).powi(2) + (e[1][1] - e[0][1]).powi(2)).sqrt())
                        .fold(0.0, f64::max);
                    let margin = self.params.search_margin * longest + margin_extra;
                    let tree = SegmentTree::new(ends);
                    for (i, &node) in pair.slave.nodes.iter().enumerate() {
                        let xs = bodies.position(sb, node, u);
                        let Some(pr) = tree.closest(xs, margin) else {
                            continue;
                        };
                        let mut c = make(i, node);
                        pair_with_segment(&mut c, bodies, sb, master, pr.segment, u, forms);
                        carry(&mut c);
                        out.push(c);
                    }
                }
            }
        }
        out
    }

    /// Slave nodes outside `candidates` that penetrate a master at positions u by more than
    /// `tolerance` (the step missed their contact).
    fn missed(&self, u: &[f64], candidates: &[Candidate], tolerance: f64) -> usize {
        let bodies = &self.problem.bodies;
        let mut missed = 0;
        for (p, pair) in self.problem.pairs.iter().enumerate() {
            let mut listed = vec![false; pair.slave.nodes.len()];
            for c in candidates.iter().filter(|c| c.pair == p) {
                listed[c.slave_index] = true;
            }
            let sb = pair.slave.body;
            match &pair.master {
                PairMaster::Foundation(f) => {
                    for (i, &node) in pair.slave.nodes.iter().enumerate() {
                        let xs = bodies.position(sb, node, u);
                        if !listed[i]
                            && f.normal[0] * xs[0] + f.normal[1] * xs[1] - f.level < -tolerance
                        {
                            missed += 1;
                        }
                    }
                }
                PairMaster::Surface(master) => {
                    let mb = master.body;
                    let ends: Vec<[[f64; 2]; 2]> = master
                        .segments
                        .iter()
                        .map(|s| [bodies.position(mb, s[0], u), bodies.position(mb, s[1], u)])
                        .collect();
                    let longest = ends
                        .iter()
                        .map(|e| ((e[1][0] - e[0][0]).powi(2) + (e[1][1] - e[0][1]).powi(2)).sqrt())
                        .fold(0.0, f64::max);
                    let tree = SegmentTree::new(ends);
                    for (i, &node) in pair.slave.nodes.iter().enumerate() {
                        if listed[i] {
                            continue;
                        }
                        let xs = bodies.position(sb, node, u);
                        if let Some(pr) = tree.closest(xs, 0.5 * longest) {
                            if pr.gap < -tolerance && (0.0..=1.0).contains(&pr.xi) {
                                missed += 1;
                            }
                        }
                    }
                }
            }
        }
        missed
    }

    /// The states of the candidates (for observers and snapshots).
    fn states(&self, candidates: &[Candidate]) -> Vec<ContactState> {
        candidates
            .iter()
            .map(|c| ContactState {
                pair: c.pair,
                slave: c.slave,
                weight: self.problem.pairs[c.pair].slave.weights[c.slave_index],
                segment: c.segment,
                lambda_n: c.lambda_n,
                lambda_t: c.lambda_t,
                gap: c.g1,
                slip: c.tau1 - c.tau0,
                active: c.active,
                stick: matches!(c.tangent, Tangent::Stick),
            })
            .collect()
    }

    /// The loads of every body at time t into `f`.
    fn loads(&self, t: f64, f: &mut [f64]) {
        let bodies = &self.problem.bodies;
        for (b, body) in bodies.bodies().iter().enumerate() {
            body.load_into(t, &mut f[bodies.range(b)]);
        }
    }

    /// Runs the time loop.
    pub fn solve(&self) -> Result<MultibodySolution, Error> {
        self.solve_with(&mut |_| {})
    }

    /// Runs the time loop, calling `observer` after every step and once for the initial state.
    pub fn solve_with(
        &self,
        observer: &mut dyn FnMut(&MultibodyStepView<'_>),
    ) -> Result<MultibodySolution, Error> {
        let setup = Instant::now();
        let pb = &self.problem;
        let bodies = &pb.bodies;
        let n = bodies.dofs();
        let k = self.step_size();
        let scheme = pb.scheme;
        let laws = self.laws();
        let masters = self.masters();
        let slave_bodies: Vec<usize> = pb.pairs.iter().map(|p| p.slave.body).collect();
        let mut ws = StepWorkspace::new(bodies, StepKind::Dynamic(scheme), k);
        let forms = InvariantForms::new();
        let mut u = pb.initial_displacement.clone();
        let mut v = pb.initial_velocity.clone();
        let mut a = vec![0.0; n];
        let mut f_prev = vec![0.0; n];
        let mut f_now = vec![0.0; n];
        let mut mv = vec![0.0; n];
        let mut d = vec![0.0; n];
        self.loads(0.0, &mut f_prev);
        if scheme == MultibodyScheme::Newmark {
            // a₀ = M⁻¹ (f(0) − F_int(u₀)) body by body (contact forces at rest are zero)
            for (b, body) in bodies.bodies().iter().enumerate() {
                let r = bodies.range(b);
                let mut fi = vec![0.0; r.len()];
                if !body.internal_force(&u[r.clone()], &mut fi) {
                    return Err(InputError::new(
                        "initial.displacement",
                        "(inadmissible)",
                        "a displacement with det F > 0 in every element",
                    )
                    .into());
                }
                let mut rhs: Vec<f64> = f_prev[r.clone()]
                    .iter()
                    .zip(&fi)
                    .map(|(f, g)| f - g)
                    .collect();
                let mut chol = crate::solve::sparse_cholesky::SparseCholesky::analyze(
                    body.pattern(),
                    &[],
                    "mass matrix M",
                )?;
                chol.factor(body.pattern(), body.mass())?;
                let mut cws = chol.workspace(1);
                chol.solve_in_place(&mut rhs, &mut cws);
                a[r].copy_from_slice(&rhs);
            }
        }
        let mut stats = MultibodyStats {
            unknowns: n,
            ..Default::default()
        };
        let mut carried: Vec<Vec<Option<Carried>>> = pb
            .pairs
            .iter()
            .map(|p| vec![None; p.slave.nodes.len()])
            .collect();
        let first = self.record(0, 0.0, &u, &v, &[], &mut mv, &forms);
        let mut guard = EnergyGuard::new(&first);
        let mut positive: Option<(usize, PositiveWork)> = None;
        let mut records = vec![first];
        if let Some((q, value)) = records[0].first_non_finite() {
            return Err(
                InputError::new("initial", value, format!("a state with finite {q}")).into(),
            );
        }
        let mut snapshots: Vec<MultibodySnapshot> = Vec::new();
        let mut times = self.params.snapshot_times.clone();
        times.sort_by(f64::total_cmp);
        let mut next_snapshot = 0;
        let mut take =
            |step: usize, t: f64, u: &[f64], v: &[f64], c: &[ContactState], next: &mut usize| {
                while *next < times.len() && times[*next] <= t + 0.5 * k {
                    // a time written twice (or two times of one step) is recorded once
                    let fresh = snapshots.last().is_none_or(|s| s.step != step);
                    if (times[*next] > t - 0.5 * k || step == 0) && fresh {
                        snapshots.push(MultibodySnapshot {
                            step,
                            time: t,
                            displacement: u.to_vec(),
                            velocity: v.to_vec(),
                            contacts: c.to_vec(),
                        });
                    }
                    *next += 1;
                }
            };
        take(0, 0.0, &u, &v, &[], &mut next_snapshot);
        observer(&MultibodyStepView {
            step: 0,
            time: 0.0,
            displacement: &u,
            velocity: &v,
            contacts: &[],
            record: &records[0],
        });
        stats.setup_seconds = setup.elapsed().as_secs_f64();
        let loop_start = Instant::now();
        let alpha = scheme.alpha(k);
        let size = bodies
            .bodies()
            .iter()
            .flat_map(|b| b.data().mesh.nodes().iter())
            .fold(0.0f64, |m, x| m.max(x[0].abs()).max(x[1].abs()))
            .max(f64::MIN_POSITIVE);
        for step in 1..=pb.steps {
            crate::run_control::check(|| {
                format!("step {step} of {} (t = {})", pb.steps, k * step as f64)
            })?;
            crate::run_control::report_progress("steps", step as u64, pb.steps as u64);
            let t = k * step as f64;
            let at = StepAt { step, time: t };
            self.loads(
                if scheme.is_midpoint_type() {
                    t - 0.5 * k
                } else {
                    t
                },
                &mut f_now,
            );
            // b = α k M v_n (+ M a_n) + f
            bodies.mass_mul(&v, &mut mv);
            for i in 0..n {
                ws.b[i] = alpha * k * mv[i] + f_now[i];
            }
            if scheme == MultibodyScheme::Newmark {
                bodies.mass_mul(&a, &mut mv);
                for i in 0..n {
                    ws.b[i] += mv[i];
                }
            }
            let vmax = v
                .chunks(2)
                .map(|w| w.iter().map(|x| x * x).sum::<f64>().sqrt())
                .fold(0.0, f64::max);
            let mut margin_extra = 2.0 * k * vmax;
            let mut attempt = 0;
            let (candidates, report) = loop {
                let search_start = Instant::now();
                let mut candidates = self.search(&u, margin_extra, &carried, &forms);
                stats.search_seconds += search_start.elapsed().as_secs_f64();
                stats.max_candidates = stats.max_candidates.max(candidates.len());
                for i in 0..n {
                    d[i] = k * v[i];
                }
                let data = StepData {
                    bodies,
                    laws: &laws,
                    masters: &masters,
                    kind: StepKind::Dynamic(scheme),
                    k,
                    u0: &u,
                    at,
                };
                let report = solve_step(
                    &data,
                    &slave_bodies,
                    &mut candidates,
                    &mut d,
                    &self.params.newton,
                    self.params.max_switches,
                    &mut ws,
                )?;
                let check_start = Instant::now();
                let u1: Vec<f64> = u.iter().zip(&d).map(|(a, b)| a + b).collect();
                let missed = self.missed(&u1, &candidates, 1e-9 * size);
                stats.search_seconds += check_start.elapsed().as_secs_f64();
                if missed == 0 {
                    break (candidates, report);
                }
                attempt += 1;
                stats.search_retries += 1;
                if attempt > 3 {
                    // when nodes were released past a free master end in this step, the
                    // missed ones are usually those, back inside the segment and penetrating:
                    // a larger search finds the same candidates
                    let reason = if report.releases > 0 {
                        format!(
                            "{missed} slave node(s) penetrate a master after {} node(s) were \
                             released past its free end in this step (a corner against a corner \
                             whose end moves by more than the release tolerance) — a smaller \
                             step, two-pass contact, or a master surface that extends beyond the \
                             slave's",
                            report.releases
                        )
                    } else {
                        format!(
                            "{missed} slave node(s) penetrate a master outside the contact \
                             search even with a margin of {margin_extra:e} — the step is too \
                             large for the bodies' speeds"
                        )
                    };
                    return Err(SolveError::NoEquilibrium {
                        step,
                        time: t,
                        reason,
                    }
                    .into());
                }
                margin_extra = 4.0 * margin_extra.max(size * 1e-3);
            };
            self.account(&report, &mut stats);
            if let Some(i) = d.iter().position(|x| !x.is_finite()) {
                return Err(SolveError::NonFinite {
                    step,
                    time: t,
                    quantity: format!("displacement increment (dof {i})"),
                    value: d[i],
                    hint: String::new(),
                }
                .into());
            }
            // the velocity update
            if scheme == MultibodyScheme::Newmark {
                for i in 0..n {
                    let a_new = alpha * (d[i] - k * v[i]) - a[i];
                    v[i] += 0.5 * k * (a[i] + a_new);
                    a[i] = a_new;
                }
            } else {
                for i in 0..n {
                    v[i] = 2.0 / k * d[i] - v[i];
                }
            }
            let prev = records[records.len() - 1];
            for i in 0..n {
                u[i] += d[i];
            }
            let w_ext = if scheme == MultibodyScheme::Newmark {
                d.iter()
                    .zip(f_prev.iter().zip(&f_now))
                    .map(|(x, (a, b))| x * 0.5 * (a + b))
                    .sum()
            } else {
                d.iter().zip(&f_now).map(|(x, y)| x * y).sum::<f64>()
            };
            let mut rec = self.record(step, t, &u, &v, &candidates, &mut mv, &forms);
            self.works(&mut rec, &prev, &candidates, w_ext, &report, &forms);
            if let Some((quantity, value)) = rec.first_non_finite() {
                return Err(SolveError::NonFinite {
                    step,
                    time: t,
                    quantity: format!("{quantity} in the audit"),
                    value,
                    hint: if scheme == MultibodyScheme::EnergyMomentum {
                        " — the energy–momentum scheme conserves energy, so the growth comes from the data or a step too large for its Newton method".into()
                    } else {
                        " — the scheme lost stability (try energy_momentum or a smaller step)".into()
                    },
                }
                .into());
            }
            self.guard_energy(&rec, &mut guard, &mut positive)?;
            records.push(rec);
            for row in carried.iter_mut() {
                row.iter_mut().for_each(|c| *c = None);
            }
            for c in &candidates {
                carried[c.pair][c.slave_index] = Some(Carried {
                    segment: c.segment,
                    lambda_n: if c.active { c.lambda_n } else { 0.0 },
                    lambda_t: if c.active { c.lambda_t } else { 0.0 },
                    active: c.active,
                    tangent: c.tangent,
                });
            }
            let states = self.states(&candidates);
            take(step, t, &u, &v, &states, &mut next_snapshot);
            observer(&MultibodyStepView {
                step,
                time: t,
                displacement: &u,
                velocity: &v,
                contacts: &states,
                record: &records[records.len() - 1],
            });
            std::mem::swap(&mut f_prev, &mut f_now);
        }
        stats.steps = pb.steps;
        stats.loop_seconds = loop_start.elapsed().as_secs_f64();
        Ok(MultibodySolution {
            records,
            snapshots,
            final_displacement: u,
            final_velocity: v,
            stats,
        })
    }

    /// The energy guard of an energy–momentum run ([`EnergyGuard`]): the energy rose beyond the
    /// identity's tolerance over the work supplied, after a multiplier constraint of a node not
    /// held before did positive activation or switch work beyond its step's round-off (it
    /// entered the master from inside) — a typed
    /// [`SolveError::EnergyGain`] naming the constraint with the largest such work, unless its
    /// pair allows the gain. `positive` keeps that constraint and its step over the run.
    fn guard_energy(
        &self,
        rec: &MultibodyRecord,
        guard: &mut EnergyGuard,
        positive: &mut Option<(usize, PositiveWork)>,
    ) -> Result<(), SolveError> {
        let (rise, tolerance) = guard.step(rec);
        if let Some(worst) = rec.positive_worst {
            if rec.positive_entry_work > step_tolerance(rec)
                && positive.is_none_or(|(_, p)| worst.4 > p.4)
            {
                *positive = Some((rec.step, worst));
            }
        }
        if self.problem.scheme != MultibodyScheme::EnergyMomentum || rise <= tolerance {
            return Ok(());
        }
        let Some((at, (pair, slave, segment, switched, work))) = *positive else {
            return Ok(());
        };
        if self
            .params
            .allow_energy_gain
            .get(pair)
            .copied()
            .unwrap_or(false)
        {
            return Ok(());
        }
        let e0 = guard.initial();
        let master = match segment {
            Some(s) => format!("segment {s}"),
            None => "the foundation".to_string(),
        };
        Err(SolveError::EnergyGain {
            step: rec.step,
            time: rec.time,
            energy: rec.energy,
            initial: e0,
            ratio: rec.energy / e0,
            rise,
            tolerance,
            constraint: format!("pair {pair} slave node {slave} on {master} (in step {at})"),
            kind: if switched {
                "segment-switch"
            } else {
                "activation"
            }
            .to_string(),
            work,
        })
    }

    fn account(&self, report: &StepReport, stats: &mut MultibodyStats) {
        stats.newton_iterations += report.iterations;
        stats.max_newton_iterations = stats.max_newton_iterations.max(report.iterations);
        stats.analyses += report.analyses;
        stats.switches += report.switches;
        stats.releases += report.releases;
        stats.floor_stops += usize::from(report.floor_stop);
        stats.backtracks += report.backtracks;
    }

    /// The energies and momenta of a state, and the candidates' counts and forces.
    #[allow(clippy::too_many_arguments)]
    fn record(
        &self,
        step: usize,
        time: f64,
        u: &[f64],
        v: &[f64],
        candidates: &[Candidate],
        scratch: &mut [f64],
        forms: &InvariantForms,
    ) -> MultibodyRecord {
        let bodies = &self.problem.bodies;
        let kinetic: f64 = bodies.kinetic_energies(v, scratch).iter().sum();
        let stored: f64 = bodies.stored_energies(u).iter().sum();
        let penalty: f64 = candidates
            .iter()
            .map(|c| c.penalty_energy(forms, &self.problem.pairs[c.pair].law, &c.positions(u)))
            .sum();
        let mut momentum = [0.0; 2];
        let mut angular = 0.0;
        let (mut pscale, mut jscale) = (0.0, 0.0);
        for (x, p) in bodies.nodal_momenta(u, v, scratch) {
            momentum[0] += p[0];
            momentum[1] += p[1];
            angular += x[0] * p[1] - x[1] * p[0];
            pscale += p[0].abs() + p[1].abs();
            jscale += (x[0] * p[1]).abs() + (x[1] * p[0]).abs();
        }
        MultibodyRecord {
            step,
            time,
            kinetic,
            stored,
            penalty,
            energy: kinetic + stored + penalty,
            momentum,
            angular_momentum: angular,
            momentum_scale: pscale,
            angular_scale: jscale,
            candidates: candidates.len(),
            active: candidates.iter().filter(|c| c.active).count(),
            sticking: candidates
                .iter()
                .filter(|c| c.active && matches!(c.tangent, Tangent::Stick))
                .count(),
            slipping: candidates
                .iter()
                .filter(|c| c.active && matches!(c.tangent, Tangent::Slip(_)))
                .count(),
            normal_force: candidates.iter().map(|c| c.lambda_n).sum(),
            friction_force: candidates.iter().map(|c| c.lambda_t).sum(),
            min_gap: candidates
                .iter()
                .map(|c| c.g1)
                .fold(f64::INFINITY, f64::min),
            ..Default::default()
        }
    }

    /// The works of a step and the energy identity's residual.
    fn works(
        &self,
        rec: &mut MultibodyRecord,
        prev: &MultibodyRecord,
        candidates: &[Candidate],
        external_work: f64,
        report: &StepReport,
        forms: &InvariantForms,
    ) {
        let mut scale = rec.kinetic.abs() + rec.stored.abs() + rec.penalty.abs();
        scale += prev.kinetic.abs() + prev.stored.abs() + prev.penalty.abs() + external_work.abs();
        // the penalty's redefinition: a node whose master segment changed (at the search or in
        // the step) has its P measured from the new segment's line, and the NTS gap is not
        // continuous across a master vertex — P_new(x₀) − P_old(x₀) enters the energy without a
        // force doing it (the step's secant force conserves K + U + P_new exactly); it is the
        // step's switch work, Σ_c P_c(x₀) − (the last record's P) (docs/multibody.md §3.1)
        let penalty_switches = candidates
            .iter()
            .filter(|c| c.switched && !self.problem.pairs[c.pair].law.has_normal_multiplier())
            .count();
        if penalty_switches > 0 {
            let start: f64 = candidates
                .iter()
                .map(|c| c.penalty_energy(forms, &self.problem.pairs[c.pair].law, &c.x0))
                .sum();
            let w = start - prev.penalty;
            rec.normal_work += w;
            rec.switch_work += w;
            // a switch that moves no P (the node outside both lines) changes nothing
            if w != 0.0 {
                rec.switches += penalty_switches;
            }
            scale += start.abs();
        }
        for c in candidates {
            if self.problem.pairs[c.pair].law.has_normal_multiplier() {
                let w = c.lambda_n * (c.g1 - c.g0);
                rec.normal_work += w;
                // g is computed from coordinates of size |x| (π₂ = b × a): its round-off is ε |x|,
                // whatever the gap, so λ's work carries λ ε |x| (at low speeds, more than the
                // energy's own round-off)
                let size = c.x0.amax().max(c.reference.amax());
                scale += (c.lambda_n * c.g1).abs()
                    + (c.lambda_n * c.g0).abs()
                    + 2.0 * c.lambda_n.abs() * size;
                if c.active && c.was_active && !c.switched {
                    rec.holding_gap_work += c.lambda_n.abs() * (c.g0.abs() + c.g1.abs());
                }
                let set_change = c.switched || (c.active && !c.was_active);
                if c.switched {
                    rec.switch_work += w;
                    rec.switches += 1;
                } else if c.active && !c.was_active {
                    rec.activation_work += w;
                }
                if set_change && w > 0.0 {
                    rec.positive_set_work += w;
                    // a held node's switch or re-pairing is the master vertex's non-smoothness
                    // (a concave kink: λ |g₀| with |g₀| ≤ its distance past the vertex times the
                    // kink's angle): flagged only; a node not held entered from inside
                    if !c.held {
                        rec.positive_entry_work += w;
                        if rec.positive_worst.is_none_or(|p| w > p.4) {
                            rec.positive_worst = Some((c.pair, c.slave, c.segment, c.switched, w));
                        }
                    }
                }
            }
            if c.active && !c.was_active && !c.switched {
                rec.activated += 1;
            }
            if !c.active && c.was_active {
                rec.released += 1;
            }
            if c.lt.is_some() {
                let w = c.lambda_t * (c.tau1 - c.tau0);
                rec.friction_work += w;
                scale += (c.lambda_t * c.tau1).abs() + (c.lambda_t * c.tau0).abs();
                scale += 2.0 * c.lambda_t.abs() * c.x0.amax().max(c.reference.amax());
            }
        }
        rec.released += report.releases;
        rec.external_work = external_work;
        rec.identity_residual =
            rec.energy - prev.energy - (rec.normal_work + rec.friction_work + external_work);
        rec.identity_scale = scale;
        rec.newton_bound = report.newton_bound;
        let k = self.step_size();
        rec.momentum_bound = k * report.residual_sum;
        rec.angular_bound = k * report.residual_moment;
        rec.momentum_round_off = k * report.force_scale;
        rec.angular_round_off = k * report.moment_scale;
        rec.identity_scale += report.work_scale;
        rec.newton_iterations = report.iterations;
    }

    /// The static equilibrium F_int(u) = f(t) + contact forces, from the initial displacement
    /// (the velocities are ignored): the contact patch test's solve.
    pub fn solve_static(&self, time: f64) -> Result<StaticSolution, Error> {
        let pb = &self.problem;
        let bodies = &pb.bodies;
        let n = bodies.dofs();
        let laws = self.laws();
        let masters = self.masters();
        let slave_bodies: Vec<usize> = pb.pairs.iter().map(|p| p.slave.body).collect();
        let forms = InvariantForms::new();
        let mut ws = StepWorkspace::new(bodies, StepKind::Static, 1.0);
        let u0 = pb.initial_displacement.clone();
        self.loads(time, &mut ws.b);
        let carried: Vec<Vec<Option<Carried>>> = Vec::new();
        let mut candidates = self.search(&u0, 0.0, &carried, &forms);
        let mut d = vec![0.0; n];
        let data = StepData {
            bodies,
            laws: &laws,
            masters: &masters,
            kind: StepKind::Static,
            k: 1.0,
            u0: &u0,
            at: StepAt { step: 1, time },
        };
        let report = solve_step(
            &data,
            &slave_bodies,
            &mut candidates,
            &mut d,
            &self.params.newton,
            self.params.max_switches,
            &mut ws,
        )?;
        let displacement: Vec<f64> = u0.iter().zip(&d).map(|(a, b)| a + b).collect();
        Ok(StaticSolution {
            displacement,
            contacts: self.states(&candidates),
            iterations: report.iterations,
        })
    }
}
