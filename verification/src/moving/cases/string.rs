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
use crate::moving::convergence::{rate_gates, Convergence, Level};
use crate::moving::errors::{frequencies, relative_real_part};
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
    /// v̄ = 0 with this many sine modes: every frequency exact to `at_rest_tolerance`.
    pub at_rest_modes: usize,
    pub at_rest_tolerance: f64,
    /// Undamped runs: max |Re λ| / max |λ| at most this.
    pub real_part_tolerance: f64,
}

/// `[critical]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Critical {
    pub modes: usize,
    /// δ = 1 − v̄ approaching the critical speed.
    pub approach: Vec<f64>,
    /// Largest relative error of the first three frequencies along the approach.
    pub frequency_tolerance: f64,
    /// At v̄ = 1: eigenvalues with |λ| ≤ this × max |λ| count as zero.
    pub zero_tolerance: f64,
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
    pub exact_tolerance: f64,
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
        positive(
            p,
            "exactness.at_rest_tolerance",
            self.exactness.at_rest_tolerance,
        )?;
        positive(
            p,
            "exactness.real_part_tolerance",
            self.exactness.real_part_tolerance,
        )?;
        positive(
            p,
            "critical.frequency_tolerance",
            self.critical.frequency_tolerance,
        )?;
        positive(p, "critical.zero_tolerance", self.critical.zero_tolerance)?;
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
        .filter_map(|l| l.max_relative_real_part)
        .fold(0.0, f64::max);
    // v̄ = 0: the sine functions are the modes.
    let at_rest = string_eigenvalues(
        StringDiscretization::Sine {
            modes: case.exactness.at_rest_modes,
        },
        &MovingStringData::string(0.0, 0.0),
    )?;
    let f0 = frequencies(&at_rest);
    let rest_err = f0
        .iter()
        .enumerate()
        .map(|(k, &w)| (w - string_eigenvalue(k + 1, 0.0)).abs() / string_eigenvalue(k + 1, 0.0))
        .fold(0.0, f64::max);
    report.gates.push(GateVerdict::from_checks(
        "exact values: v̄ = 0 exact, real parts zero".into(),
        "exact",
        vec![
            Check::at_most(
                &format!("v̄ = 0, N = {}: max relative error of all frequencies", case.exactness.at_rest_modes),
                rest_err,
                case.exactness.at_rest_tolerance,
            ),
            Check::at_most(
                "undamped runs: max |Re λ| / max |λ| over every level",
                worst_re.max(relative_real_part(&at_rest)),
                case.exactness.real_part_tolerance,
            ),
        ],
        "the sine functions are the modes at rest; a conservative gyroscopic system has its spectrum on the imaginary axis",
    ));

    // The critical speed.
    let cr = &case.critical;
    let disc = StringDiscretization::Sine { modes: cr.modes };
    let mut approach = Vec::new();
    let mut worst_approach: f64 = 0.0;
    for &d in &cr.approach {
        let v = 1.0 - d;
        let ev = string_eigenvalues(disc, &MovingStringData::string(v, 0.0))?;
        let f = frequencies(&ev);
        let errs: Vec<f64> = (1..=3)
            .map(|k| (f[k - 1] - string_eigenvalue(k, v)).abs() / string_eigenvalue(k, v))
            .collect();
        worst_approach = errs.iter().copied().fold(worst_approach, f64::max);
        approach.push((d, f[0], string_eigenvalue(1, v), errs));
    }
    let ev1 = string_eigenvalues(disc, &MovingStringData::string(1.0, 0.0))?;
    let rho1 = ev1.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let zeros = ev1
        .iter()
        .filter(|l| l.norm() <= cr.zero_tolerance * rho1)
        .count();
    let mut checks = vec![
        Check::at_most(
            "v̄ = 1 − δ, δ = 1e-1 … 1e-8: max relative error of ω1..ω3 against nπ(1 − v̄²)",
            worst_approach,
            cr.frequency_tolerance,
        ),
        Check::holds(
            &format!(
                "v̄ = 1: {zeros} of {} eigenvalues are zero (|λ| ≤ {:.0e} ρ); expected ≥ N = {}",
                ev1.len(),
                cr.zero_tolerance,
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

    // Loci and Campbell diagram.
    let l = &case.loci;
    let model = MovingStringModel::new(
        StringDiscretization::Sine { modes: l.modes },
        Default::default(),
    )
    .map_err(|e| e.to_string())?;
    let axis = speed_axis(l.from, l.to, l.points)?;
    let sweep = speed_sweep(&model, &MovingStringData::string(l.from, 0.0), &axis)?;
    let chosen = upper_branches(&sweep.branches, l.branches);
    let mut worst_branch: f64 = 0.0;
    for (k, &b) in chosen.iter().enumerate() {
        for (i, &v) in axis.values.iter().enumerate() {
            if v <= l.compare_up_to {
                let e = string_eigenvalue(k + 1, v);
                let x = sweep.branches.branches[b][i];
                worst_branch = worst_branch.max(((x.im - e).abs() + x.re.abs()) / e);
            }
        }
    }
    report.gates.push(GateVerdict::from_checks(
        "tracked branches follow nπ(1 − v̄²)".into(),
        "exact",
        vec![Check::at_most(
            &format!(
                "first {} tracked branches (N = {}), v̄ ≤ {}: max |λ − i nπ(1 − v̄²)| / nπ(1 − v̄²)",
                l.branches, l.modes, l.compare_up_to
            ),
            worst_branch,
            l.exact_tolerance,
        )],
        "the branch tracker (secant predictor + optimal assignment) keeps each mode on its branch",
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
    // The same sweep with damping: every branch crosses Re λ = 0 at v̄ = 1.
    let damped = speed_sweep(&model, &MovingStringData::string(l.from, cr.damping), &axis)?;
    let chosen_d = upper_branches(&damped.branches, l.branches);
    let mut worst_damped: f64 = 0.0;
    for (k, &b) in chosen_d.iter().enumerate() {
        for (i, &v) in axis.values.iter().enumerate() {
            if (1.0 - v).abs() >= 0.02 {
                let e = damped_string_eigenvalue(k + 1, v, cr.damping);
                let x = damped.branches.branches[b][i];
                worst_damped =
                    worst_damped.max(((x.re - e.re).abs() + (x.im - e.im).abs()) / e.norm());
            }
        }
    }
    report.gates.push(GateVerdict::from_checks(
        format!("damped loci: λ_n = (1 − v̄²)(−ᾱ/2 + i sqrt(n²π² − ᾱ²/4)), ᾱ = {}", cr.damping),
        "exact",
        vec![Check::at_most(
            &format!(
                "first {} tracked branches, v̄ ∈ [{}, {}] with |1 − v̄| ≥ 0.02: max |λ − λ_n| / |λ_n|",
                l.branches, l.from, l.to
            ),
            worst_damped,
            l.exact_tolerance,
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
            max_damped_branch_error: worst_damped,
        },
    )
}
