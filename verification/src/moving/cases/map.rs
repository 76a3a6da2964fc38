//! `moving_map`: the stability map of the thick string with friction over (v̄, p), 200 × 200
//! points with 20 sine functions, against its time budget; and the evidence that it is right.
//!
//! - Timing: the map runs in parallel over lines (every thread available) with the rank-one-line
//!   kernel (`solve::small_eigenvalues`); its time on dedicated cores — CPU time divided by the
//!   threads, independent of other processes sharing the machine — must stay under the budget,
//!   and the observed wall time is reported next to it.
//! - Determinism: a band of rows recomputed on one thread gives the same bits.
//! - Every point recomputed with faer's eigensolver: the same verdict everywhere (points within
//!   the round-off tolerance τ of the axis, `Marginal` in either, excepted) and max Re λ to
//!   round-off.
//! - A sample of stable and fluttering points checked by time integration.
//! - The flutter boundary converged in N: the critical p at a few speeds for N = 10, 20, 40, 80;
//!   the differences shrink, and the N = 20 boundary is within the reported distance of N = 80.
//!   The friction term δw'(ā) is a point moment on a string, whose eigenfunctions have kinks at ā:
//!   the boundary converges slowly (about linearly in 1/N), and where the critical mode is the
//!   highest one resolved (small v̄), the boundary is the discretization's.
//! - A low-order (one sine function) model over v̄ ∈ [0, 1.3] shows both kinds of region:
//!   divergence beyond v̄ = 1 and flutter at large p.

use std::path::Path;
use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use contactlab::model::moving::resolution::model_resolution_limit;
use contactlab::model::moving::stability::{Verdict, VerdictParams};
use contactlab::model::moving::stability_map::{
    string_stability_map, GridAxis, StabilityMap, StabilityMapParams,
};
use contactlab::model::moving::string_data::{ContactModel, MovingStringData, StringParameter};
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};
use contactlab::solve::quadratic_eigen::{EigenKernel, QuadraticEigenParams};

use crate::core::context::RunContext;
use crate::core::format::positive;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict, RateCriteria};
use crate::core::report::case_report::{CaseReport, Table};
use crate::exact::thick_string_continuum::continuum_onset;
use crate::exact::thick_string_galerkin::ThickString;
use crate::moving::errors::max_real_part;
use crate::moving::plots::{boundary, map_figure};
use crate::moving::study::{check_growth, flutter_onset, model_eigenvalues, Bushing};

use super::map_lines::{run_lines, LineMap};
use crate::plot::{Figure, Series};
use crate::stats::lcg::Lcg;

/// The case format of `moving_map`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapCase {
    pub model: MapModel,
    pub map: MapGrid,
    pub checks: MapChecks,
    pub convergence: BoundaryConvergence,
    pub low_order: LowOrder,
    /// More maps through the rank-one fast path, along other friction axes and contact models.
    #[serde(default)]
    pub lines: Vec<LineMap>,
}

/// `[model]`: the thick string with ideal contact.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MapModel {
    pub modes: usize,
    pub damping: f64,
    pub stiffness: f64,
    pub mass: f64,
    pub position: f64,
}

/// `[map]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MapGrid {
    pub speed_from: f64,
    pub speed_to: f64,
    pub speeds: usize,
    pub control_from: f64,
    pub control_to: f64,
    pub controls: usize,
}

/// `[checks]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MapChecks {
    /// Rows recomputed on one thread.
    pub determinism_rows: usize,
    /// |max Re λ (kernel) − max Re λ (faer)| ≤ this × n ε max|λ| (n eigenvalues): two
    /// backward-stable QR iterations on the same companion matrix.
    pub faer_round_off: f64,
    /// Every this many points of the map, the resolved verdict is recomputed independently.
    pub resolution_sample_every: usize,
    /// Points of each verdict (stable, flutter) checked by time integration, drawn among those
    /// with |max Re λ| ≥ `time_min_rate` (near the boundary the leading mode needs runs longer
    /// than 1/(σ₁ − σ₂) to dominate; marginal and near-boundary behaviour is checked in
    /// `moving_time_check` and `moving_extremes`).
    pub time_points_per_verdict: usize,
    pub time_min_rate: f64,
    pub time_duration: f64,
    pub time_absolute_tolerance: f64,
    pub time_relative_tolerance: f64,
}

/// `[convergence]`: the flutter boundary against the continuum's onset p*(v̄).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundaryConvergence {
    pub speeds: Vec<f64>,
    /// Sine sizes, each with N·ā an integer (the bushing at a node of the last sine).
    pub modes: Vec<usize>,
    pub bisection_tolerance: f64,
    /// The continuum's branches followed from p = 0 for p*(v̄), and the search range of p.
    pub onset_branches: usize,
    pub onset_max: f64,
    /// Speeds of the continuum's onset line drawn on the map.
    pub line_speeds: usize,
    /// The rate gate of |p*_N − p*| / p* against 1/N at every speed (resolved eigenvalues).
    pub gate: RateCriteria,
}

/// The onsets at one speed: the continuum's and the program's for each N.
#[derive(Debug, Clone, Serialize)]
pub struct BoundaryRow {
    pub speed: f64,
    pub continuum: f64,
    pub resolved: Vec<f64>,
    pub every_eigenvalue: Vec<f64>,
}

/// `[low_order]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LowOrder {
    pub speed_to: f64,
    pub control_to: f64,
    pub points: usize,
}

impl MapCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        positive(p, "checks.faer_round_off", self.checks.faer_round_off)?;
        positive(p, "checks.time_duration", self.checks.time_duration)?;
        if self.map.speeds < 2 || self.map.controls < 2 {
            return Err(crate::core::format::invalid(
                p,
                "map.speeds",
                self.map.speeds,
                ">= 2 speeds and controls",
            ));
        }
        self.convergence.gate.check(p, "convergence.gate")?;
        for (i, line) in self.lines.iter().enumerate() {
            line.check(p, i)?;
        }
        positive(p, "convergence.onset_max", self.convergence.onset_max)?;
        for &n in &self.convergence.modes {
            let x = self.model.position * n as f64;
            if (x - x.round()).abs() > 1e-9 {
                return Err(crate::core::format::invalid(
                    p,
                    "convergence.modes",
                    n,
                    &format!("sizes with ā·N an integer (ā = {})", self.model.position),
                ));
            }
        }
        if self.convergence.modes.len() < 3 {
            return Err(crate::core::format::invalid(
                p,
                "convergence.modes",
                self.convergence.modes.len(),
                ">= 3 entries",
            ));
        }
        Ok(())
    }
}

/// The string at speed v̄ = `speed` with the model's oscillator in ideal contact, at the control
/// parameter p = μh̄ c̄ = `control`.
fn base(m: &MapModel, speed: f64, control: f64) -> MovingStringData {
    let bushing = Bushing {
        stiffness: m.stiffness,
        mass: m.mass,
        position: m.position,
    };
    bushing.data(speed, m.damping, ContactModel::Ideal, control / m.stiffness)
}

fn params(kernel: EigenKernel, threads: usize) -> StabilityMapParams {
    StabilityMapParams {
        threads,
        verdict: VerdictParams::default(),
        eigen: QuadraticEigenParams {
            kernel,
            ..Default::default()
        },
    }
}

/// The one-mode model is the model itself, not an approximation of the string: every
/// eigenvalue counts (one sine resolves no string mode: n(1 + |v̄|) ≤ 1 fails for v̄ > 0).
fn low_order_params() -> StabilityMapParams {
    StabilityMapParams {
        threads: 0,
        verdict: VerdictParams {
            resolved_only: false,
            ..VerdictParams::default()
        },
        eigen: QuadraticEigenParams {
            kernel: EigenKernel::Faer,
            ..Default::default()
        },
    }
}

/// User plus system CPU time of this process (Linux `/proc/self/stat`, clock ticks of 1/100 s),
/// `None` elsewhere.
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The command name may contain spaces: fields are counted after its closing parenthesis.
    let rest = stat.rsplit_once(')')?.1;
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

/// The critical control parameter at `speed` by bisection, with N sine modes: (from the
/// resolved eigenvalues, |Im λ| ≤ ω_res (the library's verdict); from every eigenvalue (the
/// verdict before issue 16)).
fn critical_control(
    m: &MapModel,
    modes: usize,
    speed: f64,
    hi: f64,
    rel_tol: f64,
) -> Result<(f64, f64), String> {
    let model = MovingStringModel::new(StringDiscretization::Sine { modes }, Default::default())
        .map_err(|e| e.to_string())?;
    let limit = model_resolution_limit(&model, speed);
    let resolved = |p: f64| {
        model_eigenvalues(&model, &base(m, speed, p)).map(|ev| {
            ev.iter()
                .filter(|l| l.im.abs() <= limit)
                .map(|l| l.re)
                .fold(f64::NEG_INFINITY, f64::max)
        })
    };
    let every = |p: f64| model_eigenvalues(&model, &base(m, speed, p)).map(|ev| max_real_part(&ev));
    let a =
        flutter_onset(resolved, "p", hi, rel_tol, 1e6).map_err(|e| format!("v̄ = {speed}: {e}"))?;
    let b = flutter_onset(every, "p", hi, rel_tol, 1e6).map_err(|e| format!("v̄ = {speed}: {e}"))?;
    Ok((a, b))
}

/// The continuum's onset p*(v̄) of the map's string (`exact::thick_string_continuum`); `None`
/// when no followed branch becomes unstable below `onset_max`.
fn continuum_critical(
    m: &MapModel,
    cv: &BoundaryConvergence,
    speed: f64,
) -> Result<Option<f64>, String> {
    let d = ThickString {
        speed,
        damping: m.damping,
        stiffness: m.stiffness,
        mass: m.mass,
        position: m.position,
        control: 0.0,
        patch: 0.0,
    };
    continuum_onset(&d, 60, cv.onset_branches, cv.onset_max, 200)
        .map(|o| o.map(|o| o.onset))
        .map_err(|e| format!("the continuum at v̄ = {speed}: {e}"))
}

/// Runs the case.
pub fn run(case: &MapCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let m = &case.model;
    let g = &case.map;
    let model = MovingStringModel::new(
        StringDiscretization::Sine { modes: m.modes },
        Default::default(),
    )
    .map_err(|e| e.to_string())?;
    let x = GridAxis::linspace(StringParameter::Speed, g.speed_from, g.speed_to, g.speeds)
        .map_err(|e| e.to_string())?;
    let y = GridAxis::linspace(
        StringParameter::ControlParameter,
        g.control_from,
        g.control_to,
        g.controls,
    )
    .map_err(|e| e.to_string())?;
    let b = base(m, g.speed_from, 0.0);
    // Timing: the map as a user runs it (wall time), and the CPU time it used (independent of
    // other processes sharing the machine).
    let cpu0 = process_cpu_seconds();
    let start = Instant::now();
    let map = string_stability_map(&model, &b, &x, &y, &params(EigenKernel::SmallDense, 0))
        .map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    let cpu = match (cpu0, process_cpu_seconds()) {
        (Some(a), Some(b)) => b - a,
        _ => f64::NAN,
    };
    let points = map.points.len();
    let per_point_us = cpu / points as f64 * 1e6;
    // On a dedicated machine the wall time is the CPU time shared by the threads (the lines are
    // independent and scheduled dynamically); when other processes share the cores the wall time
    // grows by their load, which says nothing about the map. Gate the dedicated-machine time and
    // report the observed wall time.
    let dedicated = cpu / map.threads_used as f64;
    let shared = seconds > 1.25 * dedicated;
    report.tables.push(Table {
        title: format!(
            "cost of the {} × {} map, N = {} sine functions (its budget: the criterion benchmark \
             moving_stability_map/map/200x200, benches/budgets.toml)",
            g.speeds, g.controls, m.modes
        ),
        header: vec![
            "threads".into(),
            "CPU (s)".into(),
            "CPU per point (µs)".into(),
            "CPU / threads (s)".into(),
            "wall (s)".into(),
        ],
        rows: vec![vec![
            map.threads_used.to_string(),
            format!("{cpu:.3}"),
            format!("{per_point_us:.0}"),
            format!("{dedicated:.3}"),
            format!(
                "{seconds:.3}{}",
                if shared { " (cores shared)" } else { "" }
            ),
        ]],
    });
    // Determinism: a band of rows on one thread.
    let rows = case.checks.determinism_rows.min(g.controls);
    let y_band = GridAxis {
        parameter: y.parameter,
        values: y.values[..rows].to_vec(),
    };
    let single = string_stability_map(&model, &b, &x, &y_band, &params(EigenKernel::SmallDense, 1))
        .map_err(|e| e.to_string())?;
    let identical = single.points.iter().zip(&map.points).all(|(a, b)| a == b);
    report.gates.push(GateVerdict::from_checks(
        "deterministic: the same bits on 1 thread".into(),
        "determinism",
        vec![Check::holds(
            &format!(
                "{} rows ({} points) recomputed on 1 thread are bit-identical to the {}-thread map",
                rows,
                single.points.len(),
                map.threads_used
            ),
            identical,
            "identical",
        )],
        "each point depends only on its parameters; rows land at their own index",
    ));
    // Every point with faer.
    let reference = string_stability_map(&model, &b, &x, &y, &params(EigenKernel::Faer, 0))
        .map_err(|e| e.to_string())?;
    let mut disagree = 0;
    let mut marginal_only = 0;
    let mut worst: f64 = 0.0;
    // n eigenvalues: the companion order 2 (N + 1)
    let unit = (2 * (m.modes + 1)) as f64 * f64::EPSILON;
    for (a, r) in map.points.iter().zip(&reference.points) {
        worst = worst.max((a.max_real_part - r.max_real_part).abs() / (unit * r.spectral_scale));
        if a.verdict != r.verdict {
            if a.verdict == Verdict::Marginal || r.verdict == Verdict::Marginal {
                marginal_only += 1;
            } else {
                disagree += 1;
            }
        }
    }
    report.gates.push(GateVerdict::from_checks(
        "every point of the map against faer's eigensolver".into(),
        "exact",
        vec![
            Check::holds(
                &format!("{disagree} of {points} verdicts differ ({marginal_only} differ only by Marginal within τ)"),
                disagree == 0,
                "0",
            ),
            Check::at_most("max |Δ max Re λ| in units of n ε max|λ|", worst, case.checks.faer_round_off),
        ],
        "the map's eigenvalue-only kernel and faer's dense eigensolver on the same companion matrices",
    ));
    let bushing = Bushing {
        stiffness: m.stiffness,
        mass: m.mass,
        position: m.position,
    };
    run_lines(
        &case.lines,
        &model,
        &bushing,
        m.damping,
        m.modes,
        case.checks.faer_round_off,
        report,
    )?;
    // The resolution limit, independently: a sample of points recomputed from the whole
    // spectrum, filtered here by |Im λ| ≤ Nπ(1 − |v̄|) (N sines carry N half-waves; the string's
    // wave against the transport has wavenumber ω/(1 − |v̄|)).
    let mut sample_mismatch = 0;
    let mut sample_worst: f64 = 0.0;
    let mut sampled = 0;
    let mut sampled_warnings = 0;
    for i in (0..points).step_by(case.checks.resolution_sample_every.max(1)) {
        let (ix, iy) = (i % g.speeds, i / g.speeds);
        let d = base(m, x.values[ix], y.values[iy]);
        let ev = model_eigenvalues(&model, &d)?;
        let limit = m.modes as f64 * std::f64::consts::PI * (1.0 - x.values[ix].abs());
        let resolved_max = ev
            .iter()
            .filter(|l| l.im.abs() <= limit)
            .map(|l| l.re)
            .fold(f64::NEG_INFINITY, f64::max);
        let a = &map.points[i];
        let tol = a.tolerance;
        let verdict_here = if resolved_max > tol {
            Some(true)
        } else if resolved_max < -tol {
            Some(false)
        } else {
            None
        };
        let verdict_map = match a.verdict {
            Verdict::Stable => Some(false),
            Verdict::Marginal => None,
            _ => Some(true),
        };
        if verdict_here.is_some() && verdict_map.is_some() && verdict_here != verdict_map {
            sample_mismatch += 1;
        }
        sample_worst =
            sample_worst.max((resolved_max - a.max_real_part).abs() / (unit * a.spectral_scale));
        sampled += 1;
        if a.unresolved.is_present() {
            sampled_warnings += 1;
        }
    }
    report.gates.push(GateVerdict::from_checks(
        "the map's verdicts read only the resolved eigenvalues (an independent filter)".into(),
        "exact",
        vec![
            Check::holds(
                &format!(
                    "{sample_mismatch} of {sampled} sampled points differ in stability ({sampled_warnings} of them carry unstable eigenvalues above ω_res, which the verdict ignores)"
                ),
                sample_mismatch == 0 && sampled_warnings > 0,
                "0 differ, and the sample contains points with unstable unresolved eigenvalues",
            ),
            Check::at_most(
                "max |Δ resolved max Re λ| in units of n ε max|λ|",
                sample_worst,
                case.checks.faer_round_off,
            ),
        ],
        "every eigenvalue from faer on a sample of points, filtered by |Im λ| ≤ Nπ(1 − |v̄|) written in the case",
    ));
    // Time integration of a sample of each verdict.
    let c = &case.checks;
    let mut rng = Lcg(5);
    let mut tchecks = Vec::new();
    let mut trows = Vec::new();
    let tol = |s: f64| c.time_absolute_tolerance + c.time_relative_tolerance * s.abs();
    for v in [Verdict::Stable, Verdict::Flutter] {
        // Clearly decided points: the leading mode must dominate the others within the run.
        let idx: Vec<usize> = (0..points)
            .filter(|&i| {
                map.points[i].verdict == v && map.points[i].max_real_part.abs() >= c.time_min_rate
            })
            .collect();
        for _ in 0..c.time_points_per_verdict.min(idx.len()) {
            let i = idx[(rng.next_unit() * idx.len() as f64) as usize % idx.len()];
            let (ix, iy) = (i % g.speeds, i / g.speeds);
            let d = base(m, x.values[ix], y.values[iy]);
            let sys = model.system(&d).map_err(|e| e.to_string())?;
            let a = map.points[i];
            // The discrete system grows at the rate of its whole spectrum: the unresolved
            // eigenvalues included (the verdict reads the resolved ones only).
            let growth = max_real_part(&model_eigenvalues(&model, &d)?);
            let (chk, _) = check_growth(
                &sys,
                growth,
                a.spectral_scale,
                c.time_duration,
                77 + i as u64,
            )?;
            tchecks.push(Check::within(
                &format!(
                    "v̄ = {:.3}, p = {:.4} ({}{}): observed growth vs max Re λ = {:.3e}",
                    x.values[ix],
                    y.values[iy],
                    v.name(),
                    if a.unresolved.is_present() {
                        ", unstable above ω_res"
                    } else {
                        ""
                    },
                    growth
                ),
                chk.observed,
                growth,
                tol(growth),
            ));
            trows.push((x.values[ix], y.values[iy], v, growth, chk.observed));
        }
    }
    report.gates.push(GateVerdict::from_checks(
        "a sample of the map's verdicts confirmed by time integration".into(),
        "time_check",
        tchecks,
        "RK4 from a pseudo-random state; the slope of the peaks of ln ‖(q, q̇)‖ over the last half; points with |max Re λ| ≥ time_min_rate",
    ));
    // Boundary convergence in N, against the continuum's onset.
    let cv = &case.convergence;
    let mut crit = Vec::new();
    for &v in &cv.speeds {
        let p_star = continuum_critical(m, cv, v)?.ok_or_else(|| {
            format!(
                "the continuum at v̄ = {v}: no branch becomes unstable below p = {}",
                cv.onset_max
            )
        })?;
        let mut row = Vec::new();
        for &n in &cv.modes {
            row.push(critical_control(m, n, v, 0.01, cv.bisection_tolerance)?);
        }
        crit.push(BoundaryRow {
            speed: v,
            continuum: p_star,
            resolved: row.iter().map(|r| r.0).collect(),
            every_eigenvalue: row.iter().map(|r| r.1).collect(),
        });
    }
    let inv_n: Vec<f64> = cv.modes.iter().map(|&n| 1.0 / n as f64).collect();
    let rel = |ps: &[f64], p_star: f64| -> Vec<f64> {
        ps.iter().map(|p| (p - p_star).abs() / p_star).collect()
    };
    let mut old_fails = Vec::new();
    for r in &crit {
        report.gates.push(cv.gate.evaluate(
            format!(
                "v̄ = {}: the map's flutter onset (resolved eigenvalues) → the continuum's p* = {:.6}, against 1/N (N = {:?}: {})",
                r.speed,
                r.continuum,
                cv.modes,
                r.resolved
                    .iter()
                    .map(|p| format!("{p:.5}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            &inv_n,
            &rel(&r.resolved, r.continuum),
        ));
        let old = cv.gate.evaluate(
            String::new(),
            &inv_n,
            &rel(&r.every_eigenvalue, r.continuum),
        );
        old_fails.push((r.speed, !old.passed));
    }
    let failing: Vec<String> = old_fails
        .iter()
        .filter(|x| x.1)
        .map(|x| format!("v̄ = {}", x.0))
        .collect();
    report.gates.push(GateVerdict::from_checks(
        "the same convergence gate fails on the onsets read from every eigenvalue (the map before issue 16)".into(),
        "convergence",
        vec![Check::holds(
            &format!(
                "it fails at {} of {} speeds ({}): those onsets converge to the discretization's artefact, not to p*",
                failing.len(),
                old_fails.len(),
                failing.join(", ")
            ),
            !failing.is_empty(),
            "fails at one speed at least",
        )],
        "a gate that would pass on the artefact is no gate: this is its negative control",
    ));
    // The continuum's onset line across the map.
    let line_speeds: Vec<f64> = (0..cv.line_speeds)
        .map(|i| {
            let t = i as f64 / (cv.line_speeds.max(2) - 1) as f64;
            g.speed_from + t * (cv.speeds[cv.speeds.len() - 1] - g.speed_from)
        })
        .collect();
    let continuum_line: Vec<(f64, f64)> = line_speeds
        .par_iter()
        .map(|&v| continuum_critical(m, cv, v).map(|p| p.map(|p| (v, p))))
        .collect::<Result<Vec<_>, String>>()?
        .into_iter()
        .flatten()
        .collect();
    // Low-order model: divergence and flutter regions.
    let lo = &case.low_order;
    let lmodel =
        MovingStringModel::new(StringDiscretization::Sine { modes: 1 }, Default::default())
            .map_err(|e| e.to_string())?;
    let lx = GridAxis::linspace(StringParameter::Speed, 0.0, lo.speed_to, lo.points)
        .map_err(|e| e.to_string())?;
    let ly = GridAxis::linspace(
        StringParameter::ControlParameter,
        0.0,
        lo.control_to,
        lo.points,
    )
    .map_err(|e| e.to_string())?;
    let lmap = string_stability_map(&lmodel, &b, &lx, &ly, &low_order_params())
        .map_err(|e| e.to_string())?;
    let div_ok = (0..lo.points).all(|ix| {
        let v = lx.values[ix];
        let at0 = lmap.at(ix, 0).map(|a| a.verdict);
        if v > 1.0 + 1e-9 {
            at0 == Some(Verdict::Divergence)
        } else if v < 1.0 - 1e-9 {
            at0 == Some(Verdict::Stable)
        } else {
            true
        }
    });
    report.gates.push(GateVerdict::from_checks(
        "one-mode model: divergence beyond v̄ = 1, flutter at large p".into(),
        "stability",
        vec![
            Check::holds(
                &format!("p = 0 row: stable below v̄ = 1, divergence above ({} divergence, {} flutter points in the map)", lmap.count(Verdict::Divergence), lmap.count(Verdict::Flutter)),
                div_ok && lmap.count(Verdict::Flutter) > 0,
                "both regions present, divergence exactly beyond v̄ = 1",
            ),
        ],
        "one mode: K = (1 − v̄²)π² + c̄Φ(ā)² … loses definiteness near v̄ = 1; G = 0 (a 1 × 1 skew matrix), so nothing can stabilize it",
    ));

    // Plots.
    let fmap = map_figure(
        &format!(
            "thick string, ideal contact: verdicts over (v̄, p), N = {}, {} × {} points",
            m.modes, g.speeds, g.controls
        ),
        "v̄",
        "p = μ c̄ h̄",
        &map,
        50,
        false,
    );
    let fmap = fmap.series(
        Series::line(
            "continuum onset p*(v̄)",
            continuum_line
                .iter()
                .copied()
                .filter(|x| x.1 <= g.control_to),
        )
        .color(7),
    );
    let mut fb = Figure::new("flutter onset p*(v̄): N sine functions against the continuum")
        .x_label("v̄")
        .y_label("p*")
        .series(Series::line("continuum", continuum_line.iter().copied()).color(7))
        .series(
            Series::line("map boundary (N = 20, grid)", boundary(&map))
                .color(6)
                .dashed(),
        );
    for (j, &n) in cv.modes.iter().enumerate() {
        fb = fb
            .series(
                Series::line_markers(
                    format!("N = {n}: resolved eigenvalues"),
                    crit.iter().map(|r| (r.speed, r.resolved[j])),
                )
                .color(j),
            )
            .series(
                Series::line_markers(
                    format!("N = {n}: every eigenvalue"),
                    crit.iter().map(|r| (r.speed, r.every_eigenvalue[j])),
                )
                .color(j)
                .dashed(),
            );
    }
    let mut fr = Figure::new("max Re λ over the map (every 10th row)")
        .x_label("v̄")
        .y_label("max Re λ");
    for (k, iy) in (0..g.controls).step_by((g.controls / 5).max(1)).enumerate() {
        fr = fr.series(
            Series::line(
                format!("p = {:.3}", y.values[iy]),
                (0..g.speeds)
                    .filter_map(|ix| map.at(ix, iy).map(|a| (x.values[ix], a.max_real_part))),
            )
            .color(k),
        );
    }
    ctx.panels(
        report,
        "map_speed_control",
        "Stability map of the thick string with friction over (v̄, p): verdicts, the boundary converged in N, and the growth rates",
        &[fmap, fb, fr.horizontal_line(0.0, "")],
        3,
    )?;
    let flo = map_figure(
        &format!(
            "one-mode model (N = 1): divergence beyond v̄ = 1, flutter at large p ({} × {})",
            lo.points, lo.points
        ),
        "v̄",
        "p = μ c̄ h̄",
        &lmap,
        50,
        false,
    )
    .vertical_line(1.0, "v̄ = 1");
    ctx.plot(report, "map_low_order", &flo)?;

    #[derive(Serialize)]
    struct Data<'a> {
        seconds: f64,
        cpu_seconds: f64,
        dedicated_seconds: f64,
        threads: usize,
        points: usize,
        cpu_per_point_us: f64,
        counts: Vec<(&'static str, usize)>,
        faer_disagreements: usize,
        faer_marginal_only: usize,
        faer_max_difference_round_off_units: f64,
        time_checks: &'a [(f64, f64, Verdict, f64, f64)],
        critical_control: &'a [BoundaryRow],
        continuum_line: &'a [(f64, f64)],
        unresolved_warnings: usize,
        map: &'a StabilityMap,
    }
    ctx.write_data(
        report,
        &Data {
            seconds,
            cpu_seconds: cpu,
            dedicated_seconds: dedicated,
            threads: map.threads_used,
            points,
            cpu_per_point_us: per_point_us,
            counts: Verdict::ALL
                .iter()
                .map(|v| (v.name(), map.count(*v)))
                .collect(),
            faer_disagreements: disagree,
            faer_marginal_only: marginal_only,
            faer_max_difference_round_off_units: worst,
            time_checks: &trows,
            critical_control: &crit,
            continuum_line: &continuum_line,
            unresolved_warnings: map.count_unresolved(),
            map: &map,
        },
    )?;
    Ok(())
}
