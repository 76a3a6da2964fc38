//! `dynamic_performance`: the cost of the dynamic contact solver against problem size.
//!
//! Each `[[series]]` runs one impact scene on meshes of growing size and records, per level, the
//! setup and time-loop seconds (best of `repeats`), the Newton iterations per step, the time per
//! step and per Newton iteration, the factor's nonzeros, and the cost of the sparse linear algebra
//! the step is built on, measured on the same matrix through the public API:
//!
//! - condensed path (a linear body: A = α M + θ K factored once with the contact dofs last, the
//!   step condensed onto them — see `step_operator::CondensedStep`): one forward and one
//!   backward pass over the factor, the least a step can cost;
//! - full path (a hyperelastic body: per Newton iteration the scheme's force, its tangent, a
//!   numeric refactorization with the symbolic analysis reused, one solve): the numeric
//!   factorization and the solve, next to the element kernels (force, tangent assembly).
//!
//! Times are the thread's CPU time ([`crate::core::cpu_clock`]): the loop from the observer's call
//! on the initial state to its call after the last step, the references best of several calls; a
//! ratio of CPU times does not drift when other processes share the cores (the setup column is
//! the solver's wall clock).
//!
//! "The cost of a step must grow no faster than the sparse solve's": the ratio (time per step) /
//! (forward + backward pass) on the condensed path, and (time per Newton iteration) /
//! (factorization + solve) on the full path, may not grow across the levels by more than the
//! stated factor (a timing gate: it is a ratio of times, kept out of the deterministic report).
//! `[[timed]]` entries time one whole run (setup + loop) and report it; no absolute time is
//! gated here — the budgets (the ring impact at the report's resolution in under a minute) live
//! with the criterion benchmarks (`benches/budgets.toml`, `verify benches`).

mod format;

pub use format::{check, PerformanceCase, SeriesSpec, TimedSpec};

use std::time::Instant;

use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::{DynamicPath, DynamicSolution, DynamicSolver};
use contactlab::scene::dynamic::DynamicScene;
use contactlab::solve::sparse_cholesky::SparseCholesky;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::cpu_clock::thread_cpu_seconds;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::dynamic::scene::scene_from_table;
use crate::plot::{Figure, Series};

/// Best thread CPU time of `f` (s) over at least `min_reps` calls and about 50 ms of wall time.
fn best_of(min_reps: usize, mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    let start = Instant::now();
    let mut reps = 0;
    while reps < min_reps || (start.elapsed().as_secs_f64() < 0.05 && reps < 1000) {
        let t = thread_cpu_seconds();
        f();
        best = best.min(thread_cpu_seconds() - t);
        reps += 1;
    }
    best
}

/// One run of `solver`, with the thread CPU time of its time loop: from the observer's call on
/// the initial state (the end of the setup) to its call after the last step.
fn timed_run(solver: &DynamicSolver) -> Result<(DynamicSolution, f64), contactlab::error::Error> {
    let (mut first, mut last) = (f64::NAN, f64::NAN);
    let sol = solver.solve_with(&mut |v| {
        let now = thread_cpu_seconds();
        if v.step == 0 {
            first = now;
        }
        last = now;
    })?;
    Ok((sol, last - first))
}

/// One measured level.
#[derive(Debug, Clone)]
struct Level {
    label: String,
    dofs: usize,
    contact_dofs: usize,
    path: DynamicPath,
    steps: usize,
    iterations: usize,
    max_iterations: usize,
    factorizations: usize,
    backtracks: usize,
    setup: f64,
    looped: f64,
    factor_nnz: usize,
    /// Sparse references: numeric factorization and one solve (full path) or one forward +
    /// backward pass (condensed path).
    t_factor: f64,
    t_solve: f64,
    /// Element kernels (full path): the scheme's force and its tangent assembly.
    t_force: f64,
    t_tangent: f64,
}

impl Level {
    fn per_step(&self) -> f64 {
        self.looped / self.steps as f64
    }

    fn per_iteration(&self) -> f64 {
        self.looped / self.iterations.max(1) as f64
    }

    /// The cost relative to the sparse linear algebra it is built on.
    fn ratio(&self) -> f64 {
        match self.path {
            DynamicPath::Condensed => self.per_step() / self.t_solve,
            DynamicPath::Full => self.per_iteration() / (self.t_factor + self.t_solve),
        }
    }

    /// The sparse reference cost per step (condensed) or per Newton iteration (full).
    fn reference(&self) -> f64 {
        match self.path {
            DynamicPath::Condensed => self.t_solve,
            DynamicPath::Full => self.t_factor + self.t_solve,
        }
    }
}

fn measure(label: &str, scene: &DynamicScene, repeats: usize) -> Result<Level, String> {
    let solver = scene.solver().map_err(|e| format!("{label}: {e}"))?;
    let mut best: Option<DynamicSolution> = None;
    let (mut setup, mut looped) = (f64::INFINITY, f64::INFINITY);
    // a first run warms caches and page tables; the timed runs follow
    for _ in 0..repeats + 1 {
        let (sol, loop_cpu) = timed_run(&solver).map_err(|e| format!("{label}: {e}"))?;
        setup = setup.min(sol.stats.setup_seconds);
        looped = looped.min(loop_cpu);
        best = Some(sol);
    }
    let sol = best.ok_or("no run")?;
    let pb = &scene.problem;
    let body = pb.body.clone();
    let n = body.dofs();
    let k = pb.final_time / pb.steps as f64;
    let alpha = pb.scheme.alpha(k);
    let theta = if pb.scheme == DynamicScheme::Newmark {
        1.0
    } else {
        0.5
    };
    let pattern = body.pattern().clone();
    let gamma = pb.contact.as_ref().map(|c| c.dofs()).unwrap_or_default();
    let path = sol.stats.path.unwrap_or(DynamicPath::Full);
    // the step matrix: α M + θ K (K at u = 0 for a hyperelastic body: the same pattern and cost)
    let mut values: Vec<f64> = body.mass().iter().map(|m| alpha * m).collect();
    match body.linear_stiffness() {
        Some(kv) => values
            .iter_mut()
            .zip(kv)
            .for_each(|(v, kk)| *v += theta * kk),
        None => body.add_tangent(&vec![0.0; n], theta, &mut values),
    }
    let mut level = Level {
        label: label.to_string(),
        dofs: n,
        contact_dofs: gamma.len(),
        path,
        steps: sol.stats.steps,
        iterations: sol.stats.newton_iterations,
        max_iterations: sol.stats.max_newton_iterations,
        factorizations: sol.stats.factorizations,
        backtracks: sol.stats.backtracks,
        setup,
        looped,
        factor_nnz: sol.stats.factor_nnz,
        t_factor: f64::NAN,
        t_solve: f64::NAN,
        t_force: f64::NAN,
        t_tangent: f64::NAN,
    };
    match path {
        DynamicPath::Condensed => {
            let mut chol =
                SparseCholesky::analyze(&pattern, &gamma, label).map_err(|e| e.to_string())?;
            level.t_factor = best_of(1, || {
                let _ = chol.factor(&pattern, &values);
            });
            chol.factor(&pattern, &values).map_err(|e| e.to_string())?;
            let mut ws = chol.workspace(1);
            let b = vec![1.0; n];
            let (mut y, mut x) = (vec![0.0; n], vec![0.0; n]);
            level.t_solve = best_of(5, || {
                chol.forward(&b, &mut y, &mut ws);
                chol.backward(&mut y, &mut x, &mut ws);
            });
        }
        DynamicPath::Full => {
            let mut chol =
                SparseCholesky::analyze(&pattern, &[], label).map_err(|e| e.to_string())?;
            chol.factor(&pattern, &values).map_err(|e| e.to_string())?;
            level.t_factor = best_of(3, || {
                let _ = chol.factor(&pattern, &values);
            });
            let mut ws = chol.workspace(1);
            let mut x = vec![1.0; n];
            level.t_solve = best_of(5, || chol.solve_in_place(&mut x, &mut ws));
            // the kernels at the final state and the state one step before (u − k v)
            let u1 = sol.final_displacement.clone();
            let u0: Vec<f64> = u1
                .iter()
                .zip(&sol.final_velocity)
                .map(|(u, v)| u - k * v)
                .collect();
            let mut f = vec![0.0; n];
            let mut tangent = values.clone();
            match pb.scheme {
                DynamicScheme::Gonzalez => {
                    level.t_force = best_of(3, || {
                        body.discrete_gradient_force(&u0, &u1, &mut f);
                    });
                    level.t_tangent = best_of(3, || {
                        body.add_discrete_gradient_tangent(&u0, &u1, 1.0, &mut tangent)
                    });
                }
                _ => {
                    level.t_force = best_of(3, || {
                        body.internal_force(&u1, &mut f);
                    });
                    level.t_tangent = best_of(3, || body.add_tangent(&u1, theta, &mut tangent));
                }
            }
        }
    }
    Ok(level)
}

fn ms(s: f64) -> String {
    format!("{:.4}", s * 1e3)
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c: PerformanceCase = case.body().map_err(|e| e.to_string())?;
    let mut cost = Figure::new("time per step against dofs (dashed: the sparse reference)")
        .x_label("free dofs")
        .y_label("seconds")
        .log_log();
    let mut breakdowns = Vec::new();
    for (si, spec) in c.series.iter().enumerate() {
        let mut levels = Vec::new();
        for (li, set) in spec.levels.iter().enumerate() {
            let label = format!("{} [{}]", spec.name, level_label(set));
            let scene = scene_from_table(&spec.scene, set, &format!("series[{si}].levels[{li}]"))?;
            levels.push(measure(&label, &scene, spec.repeats)?);
        }
        let first = levels[0].ratio();
        let last = levels.last().ok_or("no levels")?;
        let growth = levels.iter().map(|l| l.ratio() / first).fold(0.0, f64::max);
        let what = match last.path {
            DynamicPath::Condensed => "(time per step) / (forward + backward pass)",
            DynamicPath::Full => "(time per Newton iteration) / (numeric factorization + solve)",
        };
        report.gates.push(GateVerdict::from_timing_checks(
            format!("performance: {}", spec.name),
            vec![Check::at_most(
                &format!(
                    "largest growth of {what} over the first level (time loop at {} dofs, {} \
                     steps: {:.3} s, not gated)",
                    last.dofs, last.steps, last.looped
                ),
                growth,
                spec.max_ratio_growth,
            )],
            &spec.note,
        ));
        let full = last.path == DynamicPath::Full;
        let mut head = vec![
            "level",
            "dofs",
            "contact dofs",
            "steps",
            "Newton its (per step / max)",
            "factorizations",
            "backtracks",
            "setup (s)",
            "loop, CPU (s)",
            "per step (ms)",
            "per Newton it (ms)",
            "factor nnz",
            "numeric factorization (ms)",
        ];
        head.push(if full {
            "sparse solve (ms)"
        } else {
            "forward + backward (ms)"
        });
        if full {
            head.extend(["force (ms)", "tangent assembly (ms)"]);
        }
        head.push("ratio (timing)");
        let rows = levels
            .iter()
            .map(|l| {
                let mut row = vec![
                    l.label.clone(),
                    l.dofs.to_string(),
                    l.contact_dofs.to_string(),
                    l.steps.to_string(),
                    format!(
                        "{:.2} / {}",
                        l.iterations as f64 / l.steps as f64,
                        l.max_iterations
                    ),
                    l.factorizations.to_string(),
                    l.backtracks.to_string(),
                    format!("{:.4}", l.setup),
                    format!("{:.4}", l.looped),
                    ms(l.per_step()),
                    ms(l.per_iteration()),
                    l.factor_nnz.to_string(),
                    ms(l.t_factor),
                    ms(l.t_solve),
                ];
                if full {
                    row.push(ms(l.t_force));
                    row.push(ms(l.t_tangent));
                }
                row.push(format!("{:.2}", l.ratio()));
                row
            })
            .collect();
        report.tables.push(Table {
            title: format!("{} ({:?} path)", spec.name, last.path).to_lowercase(),
            header: head.iter().map(|s| s.to_string()).collect(),
            rows,
        });
        cost = cost
            .series(
                Series::line_markers(
                    format!("{}: per step", spec.name),
                    levels.iter().map(|l| (l.dofs as f64, l.per_step())),
                )
                .color(si),
            )
            .series(
                Series::line_markers(
                    match last.path {
                        DynamicPath::Condensed => format!("{}: forward + backward", spec.name),
                        DynamicPath::Full => format!("{}: factorization + solve", spec.name),
                    },
                    levels.iter().map(|l| (l.dofs as f64, l.reference())),
                )
                .color(si)
                .dashed(),
            );
        if full {
            let fig = Figure::new(format!("{}: one Newton iteration and its parts", spec.name))
                .x_label("free dofs")
                .y_label("seconds")
                .log_log()
                .series(
                    Series::line_markers(
                        "measured per iteration",
                        levels.iter().map(|l| (l.dofs as f64, l.per_iteration())),
                    )
                    .color(0),
                )
                .series(
                    Series::line_markers(
                        "tangent assembly",
                        levels.iter().map(|l| (l.dofs as f64, l.t_tangent)),
                    )
                    .color(1),
                )
                .series(
                    Series::line_markers(
                        "numeric factorization",
                        levels.iter().map(|l| (l.dofs as f64, l.t_factor)),
                    )
                    .color(2),
                )
                .series(
                    Series::line_markers(
                        "force (one evaluation)",
                        levels.iter().map(|l| (l.dofs as f64, l.t_force)),
                    )
                    .color(3),
                )
                .series(
                    Series::line_markers(
                        "sparse solve",
                        levels.iter().map(|l| (l.dofs as f64, l.t_solve)),
                    )
                    .color(4),
                )
                .reference_slope(1.0, "slope 1");
            breakdowns.push(fig);
        }
    }
    if !c.series.is_empty() {
        cost = cost.reference_slope(1.0, "slope 1");
        let mut figs = vec![cost];
        figs.extend(breakdowns);
        let n = figs.len();
        ctx.panels(
            report,
            "cost_per_step",
            "cost per step against problem size",
            &figs,
            n.min(2),
        )?;
    }
    let mut rows = Vec::new();
    for (bi, spec) in c.timed.iter().enumerate() {
        let mut best = f64::INFINITY;
        let mut last = None;
        // timed from the scene file to the last step: what a user waits for
        for _ in 0..spec.repeats.max(1) {
            let start = Instant::now();
            let scene = spec.load(case.path(), bi)?;
            let solver = scene.solver().map_err(|e| format!("{}: {e}", spec.name))?;
            let sol = solver.solve().map_err(|e| format!("{}: {e}", spec.name))?;
            best = best.min(start.elapsed().as_secs_f64());
            last = Some((scene, sol));
        }
        let (scene, sol) = last.ok_or("no run")?;
        let s = &sol.stats;
        rows.push(vec![
            spec.name.clone(),
            scene.problem.body.describe(),
            format!("{:?}", s.path.unwrap_or(DynamicPath::Full)).to_lowercase(),
            s.steps.to_string(),
            format!(
                "{:.2} / {}",
                s.newton_iterations as f64 / s.steps as f64,
                s.max_newton_iterations
            ),
            s.stage_b_steps.to_string(),
            format!("{:.4}", s.setup_seconds),
            format!("{:.4}", s.loop_seconds),
            format!("{best:.4}"),
        ]);
    }
    if !rows.is_empty() {
        report.tables.push(Table {
            title: "timed whole runs (their budgets: benches/budgets.toml)".into(),
            header: [
                "run",
                "body",
                "path",
                "steps",
                "Newton its (per step / max)",
                "stage (b) steps",
                "setup (s)",
                "loop (s)",
                "whole run, best (s)",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect(),
            rows,
        });
    }
    Ok(())
}

fn level_label(set: &toml::Table) -> String {
    set.iter()
        .map(|(k, v)| format!("{} = {v}", k.rsplit('.').next().unwrap_or(k)))
        .collect::<Vec<_>>()
        .join(", ")
}
