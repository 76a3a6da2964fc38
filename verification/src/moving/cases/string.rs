//! `moving_string`: the axially moving string between fixed guides against its exact
//! eigenvalues λ_n = i n π (1 − v̄²) (`exact.rs`).
//!
//! - Convergence: the relative error of the first modes' frequencies against the number of sine
//!   functions N (parameter h = 1/N) and the element size h of P1 and Hermite elements, with
//!   rate gates; at v̄ = 0 the sine basis is exact (its functions are the modes).
//! - Real parts: the undamped system is conservative gyroscopic; every Re λ must vanish to
//!   round-off relative to the spectral scale.
//! - The critical speed: as v̄ → 1 every frequency goes to zero like 1 − v̄² (the relative error
//!   stays at its discretization level), at v̄ = 1 the N eigenvalues of K = 0 are zero — the
//!   divergence boundary, for every mode at once — and beyond, with damping, every mode is
//!   unstable: the Kelvin–Tait–Chetaev theorem counts one unstable eigenvalue per negative
//!   eigenvalue of K(v̄) = (1 − v̄²)⟨Φ'ᵀ, Φ'⟩, i.e. N.
//! - Loci and Campbell diagram over v̄ ∈ [0, 1.2] with tracked branches against the exact lines.

use std::path::Path;

use serde::{Deserialize, Serialize};

use contactlab::model::moving::stability::{assess, VerdictParams};
use contactlab::model::moving::string_data::MovingStringData;
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};

use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::format::{invalid, positive};
use crate::core::gate::RateGate;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::exact::moving_string::{damped_string_eigenvalue, string_eigenvalue};
use crate::moving::bounds::{ceiling_factor as factor, predicted_error};
use crate::moving::convergence::{rate_gates, Convergence, Level};
use crate::moving::errors::frequencies;
use crate::moving::plots::{loci_figures, root_locus, upper_branches};
use crate::moving::study::{speed_axis, speed_sweep, string_eigenvalues, SeriesSelect};
use crate::plot::Series;

/// The case format of `moving_string`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StringCase {
    pub convergence: Convergence,
    #[serde(default)]
    pub gate: Vec<RateGate<SeriesSelect>>,
    pub exactness: Exactness,
    pub critical: Critical,
    pub loci: Loci,
}

/// `[exactness]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Exactness {
    /// v̄ = 0 with this many sine modes: every frequency exact to round-off.
    pub at_rest_modes: usize,
    /// The round-off bound C of |λ − λ_exact| (at rest) and |Re λ| (undamped runs) in units of
    /// n ε max |λ|, n the number of eigenvalues: the backward error of the Hessenberg QR is of
    /// order n ε ‖A‖, and the eigenvalues of a conservative gyroscopic system are well
    /// conditioned.
    pub round_off: f64,
}

/// `[critical]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Critical {
    pub modes: usize,
    /// δ = 1 − v̄ approaching the critical speed.
    pub approach: Vec<f64>,
    /// The relative error of ω1..ω3 at every δ at most this (≤ 3) times its value at the first
    /// δ: the error stays bounded as v̄ → 1 (the scaled problem has a limit).
    pub frequency_factor: f64,
    /// At v̄ = 1: eigenvalues with |λ| ≤ this × n ε max |λ| count as zero (K = 0: exact zeros,
    /// moved by round-off only).
    pub zero_round_off: f64,
    pub supercritical_speeds: Vec<f64>,
    pub damping: f64,
}

/// `[loci]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Loci {
    pub modes: usize,
    pub from: f64,
    pub to: f64,
    pub points: usize,
    /// Tracked branches compared with the exact lines.
    pub branches: usize,
    /// Compare for v̄ ≤ this.
    pub compare_up_to: f64,
    /// The error model's coarse level: the same sweeps with this many sine functions.
    pub coarse_modes: usize,
    /// The largest error at `modes` at most this (≤ 3) times the prediction
    /// E(coarse) · (coarse/modes)³ of the sine basis's rate 3.
    pub ceiling_factor: f64,
}

impl StringCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        let c = &self.convergence;
        c.check(p)?;
        if c.modes_checked == 0 {
            return Err(invalid(p, "convergence.modes_checked", 0, ">= 1"));
        }
        for (i, g) in self.gate.iter().enumerate() {
            g.criteria.check(p, &format!("gate[{i}]"))?;
            let ok = g
                .select
                .series
                .split_once('/')
                .and_then(|(b, v)| {
                    let v: f64 = v.parse().ok()?;
                    (["sine", "p1", "hermite"].contains(&b) && c.speeds.contains(&v)).then_some(())
                })
                .is_some();
            if !ok {
                return Err(invalid(
                    p,
                    &format!("gate[{i}].series"),
                    &g.select.series,
                    "basis/speed with basis sine, p1 or hermite and a speed of [convergence]",
                ));
            }
        }
        positive(p, "exactness.round_off", self.exactness.round_off)?;
        factor(
            p,
            "critical.frequency_factor",
            self.critical.frequency_factor,
        )?;
        positive(p, "critical.zero_round_off", self.critical.zero_round_off)?;
        factor(p, "loci.ceiling_factor", self.loci.ceiling_factor)?;
        if !(1..self.loci.modes).contains(&self.loci.coarse_modes) {
            return Err(invalid(
                p,
                "loci.coarse_modes",
                self.loci.coarse_modes,
                "between 1 and loci.modes − 1",
            ));
        }
        positive(p, "critical.damping", self.critical.damping)?;
        if self.loci.points < 3 || self.loci.branches == 0 {
            return Err(invalid(
                p,
                "loci.points",
                self.loci.points,
                ">= 3 points and >= 1 branch",
            ));
        }
        Ok(())
    }
}

/// Runs the case.
pub fn run(case: &StringCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = &case.convergence;
    let mut levels = Vec::new();
    for &v in &c.speeds {
        let exact: Vec<f64> = (1..=c.modes_checked)
            .map(|k| string_eigenvalue(k, v))
            .collect();
        levels.extend(c.levels(v, &MovingStringData::string(v, 0.0), &exact, true)?);
    }
    rate_gates(&case.gate, &levels, "frequency error", report)?;
    let worst_re = levels
        .iter()
        .filter_map(|l| l.real_part_round_off)
        .fold(0.0, f64::max);
    // v̄ = 0: the sine functions are the modes.
    let at_rest = string_eigenvalues(
        StringDiscretization::Sine {
            modes: case.exactness.at_rest_modes,
        },
        &MovingStringData::string(0.0, 0.0),
    )?;
    let f0 = frequencies(&at_rest);
    let unit =
        at_rest.len() as f64 * f64::EPSILON * at_rest.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let rest_err = f0
        .iter()
        .enumerate()
        .map(|(k, &w)| (w - string_eigenvalue(k + 1, 0.0)).abs() / unit)
        .fold(0.0, f64::max);
    let rest_re = at_rest.iter().map(|l| l.re.abs()).fold(0.0, f64::max) / unit;
    report.gates.push(GateVerdict::from_checks(
        "exact values: v̄ = 0 exact, real parts zero".into(),
        "exact",
        vec![
            Check::at_most(
                &format!(
                    "v̄ = 0, N = {}: max |ω_k − kπ| in units of n ε max|λ| (n = {})",
                    case.exactness.at_rest_modes,
                    at_rest.len()
                ),
                rest_err,
                case.exactness.round_off,
            ),
            Check::at_most(
                "undamped runs (every level, and v̄ = 0): max |Re λ| in units of n ε max|λ|",
                worst_re.max(rest_re),
                case.exactness.round_off,
            ),
        ],
        "the sine functions are the modes at rest; a conservative gyroscopic system has its spectrum on the imaginary axis; both to the backward error of the eigensolver, n ε ‖A‖",
    ));

    // The critical speed.
    let cr = &case.critical;
    let disc = StringDiscretization::Sine { modes: cr.modes };
    let mut approach = Vec::new();
    let mut first: Option<Vec<f64>> = None;
    let mut worst_ratio: f64 = 0.0;
    for &d in &cr.approach {
        let v = 1.0 - d;
        let ev = string_eigenvalues(disc, &MovingStringData::string(v, 0.0))?;
        let f = frequencies(&ev);
        let errs: Vec<f64> = (1..=3)
            .map(|k| (f[k - 1] - string_eigenvalue(k, v)).abs() / string_eigenvalue(k, v))
            .collect();
        let base = first.get_or_insert_with(|| errs.clone());
        for (e, b) in errs.iter().zip(base.iter()) {
            worst_ratio = worst_ratio.max(e / b);
        }
        approach.push((d, f[0], string_eigenvalue(1, v), errs));
    }
    let ev1 = string_eigenvalues(disc, &MovingStringData::string(1.0, 0.0))?;
    let rho1 = ev1.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let zero_unit = ev1.len() as f64 * f64::EPSILON * rho1;
    let zeros = ev1
        .iter()
        .filter(|l| l.norm() <= cr.zero_round_off * zero_unit)
        .count();
    let mut checks = vec![
        Check::at_most(
            &format!(
                "v̄ = 1 − δ, δ = {:e} … {:e}: relative error of ω1..ω3 against nπ(1 − v̄²), largest ratio to its value at δ = {:e} (first δ: {:.3e}, {:.3e}, {:.3e})",
                cr.approach[0],
                cr.approach[cr.approach.len() - 1],
                cr.approach[0],
                approach[0].3[0],
                approach[0].3[1],
                approach[0].3[2]
            ),
            worst_ratio,
            cr.frequency_factor,
        ),
        Check::holds(
            &format!(
                "v̄ = 1: {zeros} of {} eigenvalues are zero (|λ| ≤ {} n ε max|λ| = {:.2e} max|λ|); expected ≥ N = {}",
                ev1.len(),
                cr.zero_round_off,
                cr.zero_round_off * zero_unit / rho1,
                cr.modes
            ),
            zeros >= cr.modes,
            "every mode reaches zero frequency at v̄ = 1 (divergence boundary)",
        ),
    ];
    let mut super_runs = Vec::new();
    for &v in &cr.supercritical_speeds {
        let ev = string_eigenvalues(disc, &MovingStringData::string(v, cr.damping))?;
        let a = assess(&ev, &VerdictParams::default());
        super_runs.push((v, a));
        checks.push(Check::holds(
            &format!(
                "v̄ = {v}, ᾱ = {}: {} unstable eigenvalues ({:?}), expected N = {} (Kelvin–Tait–Chetaev)",
                cr.damping, a.unstable_eigenvalues, a.verdict, cr.modes
            ),
            a.unstable_eigenvalues == cr.modes,
            "one unstable eigenvalue per negative eigenvalue of K",
        ));
    }
    let ev_sub = string_eigenvalues(disc, &MovingStringData::string(0.99, cr.damping))?;
    let sub = assess(&ev_sub, &VerdictParams::default());
    checks.push(Check::holds(
        &format!("v̄ = 0.99, ᾱ = {}: {:?}", cr.damping, sub.verdict),
        sub.unstable_eigenvalues == 0,
        "stable below the critical speed",
    ));
    report.gates.push(GateVerdict::from_checks(
        "divergence at v̄ = 1 for every mode".into(),
        "stability",
        checks,
        "K(v̄) = (1 − v̄²)⟨Φ'ᵀ,Φ'⟩ is positive definite below 1, zero at 1, negative definite above",
    ));

    // Loci and Campbell diagram: the tracked branches at N = `modes` against the exact lines,
    // with the ceiling of the sine basis's error model E ∝ N⁻³ from the same sweeps at
    // N = `coarse_modes`.
    let l = &case.loci;
    let axis = speed_axis(l.from, l.to, l.points)?;
    let undamped = |m: usize| loci_errors(m, 0.0, &axis, l, cr.damping);
    let damped_run = |m: usize| loci_errors(m, cr.damping, &axis, l, cr.damping);
    let (sweep, chosen, worst_branch) = undamped(l.modes)?;
    let (_, _, coarse_branch) = undamped(l.coarse_modes)?;
    let (damped, chosen_d, worst_damped) = damped_run(l.modes)?;
    let (_, _, coarse_damped) = damped_run(l.coarse_modes)?;
    let (nf, nc) = (l.modes as f64, l.coarse_modes as f64);
    let pred_branch = predicted_error(coarse_branch, nc, nf, 3.0);
    let pred_damped = predicted_error(coarse_damped, nc, nf, 3.0);
    report.gates.push(GateVerdict::from_checks(
        "tracked branches follow nπ(1 − v̄²)".into(),
        "exact",
        vec![Check::at_most(
            &format!(
                "first {} tracked branches (N = {}), v̄ ≤ {}: max |λ − i nπ(1 − v̄²)| / nπ(1 − v̄²) vs {} × the prediction {pred_branch:.3e} of E ∝ N⁻³ from N = {} ({coarse_branch:.3e})",
                l.branches, l.modes, l.compare_up_to, l.ceiling_factor, l.coarse_modes
            ),
            worst_branch,
            l.ceiling_factor * pred_branch,
        )],
        "the branch tracker (secant predictor + optimal assignment) keeps each mode on its branch; a swapped branch would be off by the gap between modes, ≥ 1/(branches) relative",
    ));
    let exact_lines: Vec<Series> = (1..=l.branches)
        .map(|n| {
            let pts: Vec<(f64, f64)> = axis
                .values
                .iter()
                .map(|&v| (v, string_eigenvalue(n, v)))
                .collect();
            Series::line(if n == 1 { "exact nπ(1 − v̄²)" } else { "" }, pts)
                .color(6)
                .dashed()
        })
        .collect();
    let (_, im_fig) = loci_figures(
        "moving string, ᾱ = 0",
        "v̄",
        &sweep.branches,
        &chosen,
        &exact_lines,
    );
    report.gates.push(GateVerdict::from_checks(
        format!("damped loci: λ_n = (1 − v̄²)(−ᾱ/2 + i sqrt(n²π² − ᾱ²/4)), ᾱ = {}", cr.damping),
        "exact",
        vec![Check::at_most(
            &format!(
                "first {} tracked branches, v̄ ∈ [{}, {}] with |1 − v̄| ≥ 0.02: max |λ − λ_n| / |λ_n| vs {} × the prediction {pred_damped:.3e} of E ∝ N⁻³ from N = {} ({coarse_damped:.3e})",
                l.branches, l.from, l.to, l.ceiling_factor, l.coarse_modes
            ),
            worst_damped,
            l.ceiling_factor * pred_damped,
        )],
        "every branch passes through λ = 0 at v̄ = 1 and its real part −ᾱ(1 − v̄²)/2 turns positive beyond",
    ));
    let (re_fig, _) = loci_figures(
        &format!("ᾱ = {}", cr.damping),
        "v̄",
        &damped.branches,
        &chosen_d,
        &[],
    );
    let re_fig = re_fig.series(
        Series::line(
            "exact −ᾱ(1 − v̄²)/2",
            axis.values
                .iter()
                .map(|&v| (v, damped_string_eigenvalue(1, v, cr.damping).re))
                .collect::<Vec<_>>(),
        )
        .color(6)
        .dashed(),
    );
    ctx.panels(
        report,
        "loci",
        "Loci of the moving string (N = 32, tracked branches): Campbell diagram against the exact nπ(1 − v̄²) — every frequency reaches 0 at v̄ = 1 — and, with damping, the growth rates, which all cross zero there",
        &[im_fig.vertical_line(1.0, "v̄ = 1"), re_fig.vertical_line(1.0, "v̄ = 1")],
        2,
    )?;
    ctx.plot(
        report,
        "root_locus",
        &root_locus(
            &format!(
                "moving string, ᾱ = {}, v̄ ∈ [{}, {}]",
                cr.damping, l.from, l.to
            ),
            &damped.branches,
            &chosen_d,
        ),
    )?;
    // Convergence plots.
    let figs = c.figures(&levels, "relative frequency error", [3.0, 2.0, 6.0]);
    ctx.panels(
        report,
        "convergence",
        "Convergence of the frequencies: sine basis (rate 3 in 1/N), P1 (rate 2), Hermite (rate 6)",
        &figs,
        3,
    )?;

    #[derive(Serialize)]
    struct Data<'a> {
        max_branch_error_coarse: f64,
        max_damped_branch_error_coarse: f64,
        levels: &'a [Level],
        at_rest_max_error: f64,
        approach: Vec<(f64, f64, f64, Vec<f64>)>,
        zeros_at_critical: usize,
        supercritical: Vec<(
            f64,
            contactlab::model::moving::stability::StabilityAssessment,
        )>,
        max_branch_error: f64,
        max_damped_branch_error: f64,
    }
    ctx.write_data(
        report,
        &Data {
            levels: &levels,
            at_rest_max_error: rest_err,
            approach,
            zeros_at_critical: zeros,
            supercritical: super_runs,
            max_branch_error: worst_branch,
            max_branch_error_coarse: coarse_branch,
            max_damped_branch_error_coarse: coarse_damped,
            max_damped_branch_error: worst_damped,
        },
    )
}

/// The tracked loci of N = `modes` sine functions over `axis` with damping `damping`, and the
/// largest relative distance of the first `l.branches` branches from the exact eigenvalues:
/// undamped (ᾱ = 0) for v̄ ≤ `compare_up_to` against i nπ(1 − v̄²), damped wherever
/// |1 − v̄| ≥ 0.02 against (1 − v̄²)(−ᾱ/2 + i sqrt(n²π² − ᾱ²/4)).
fn loci_errors(
    modes: usize,
    damping: f64,
    axis: &contactlab::model::moving::stability_map::GridAxis,
    l: &Loci,
    damped_alpha: f64,
) -> Result<(contactlab::model::moving::sweep::Sweep, Vec<usize>, f64), String> {
    let model = MovingStringModel::new(StringDiscretization::Sine { modes }, Default::default())
        .map_err(|e| e.to_string())?;
    let sweep = speed_sweep(&model, &MovingStringData::string(l.from, damping), axis)?;
    let chosen = upper_branches(&sweep.branches, l.branches);
    let mut worst: f64 = 0.0;
    for (k, &b) in chosen.iter().enumerate() {
        for (i, &v) in axis.values.iter().enumerate() {
            let x = sweep.branches.branches[b][i];
            if damping == 0.0 {
                if v <= l.compare_up_to {
                    let e = string_eigenvalue(k + 1, v);
                    worst = worst.max(((x.im - e).abs() + x.re.abs()) / e);
                }
            } else if (1.0 - v).abs() >= 0.02 {
                let e = damped_string_eigenvalue(k + 1, v, damped_alpha);
                worst = worst.max(((x.re - e.re).abs() + (x.im - e.im).abs()) / e.norm());
            }
        }
    }
    Ok((sweep, chosen, worst))
}
