//! Kind `rod_stability`: the explicit scheme's step bound (docs/quasistatic.md, "Stability of the
//! explicit scheme").
//!
//! With linear a, b and the law p_ν(r) = β r the rod's step is a linear iteration
//! u_n = R u_{n−1} + c. R has two eigenvalues: on every mode that vanishes at x = L,
//!
//!   μ1 = 1 − k b / α,          α = a + θ b k,
//!
//! and on the contact mode z = K⁻¹e_M (z(x) = x: the Green's function of −d²/dx² with v(0) = 0 and a
//! unit flux at L, which P1 reproduces exactly),
//!
//!   μ2 = 1 − k b / (α + β L).
//!
//! For the explicit scheme (θ = 0) |μ1| < 1 iff k < 2a/b, independent of h: the predicted boundary.
//! Implicit (θ = 1) and midpoint (θ = 1/2) give |μ| < 1 for every k. Observation: the increments
//! d_n = u_n − u_{n−1} = k w_n obey d_{n+1} = R d_n; splitting d_n = α_n z + r_n with r_n(L) = 0
//! gives each mode's observed factor, α_{n+1}/α_n and ⟨r_{n+1}, r_n⟩/‖r_n‖², measured on the first
//! steps (well above round-off). Instability itself is observed as growth of ‖d_n‖ over the run.

use std::fmt::Write;

use serde::{Deserialize, Serialize};

use contactlab::contact::normal_law::FoundationLaw;
use contactlab::model::quasistatic::rod_solver::{RodSolver, RodStep};
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::time::grid::TimeGrid;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Section};
use crate::core::report::markdown::sci;
use crate::plot::{Figure, Series};
use crate::rod::study::{Discretization, RodStudy};

/// The case body of `rod_stability`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StabilityCase {
    /// The rod (linear law (2.7): the step is a linear iteration).
    pub scene: toml::Table,
    pub stability: StabilitySpec,
}

/// `[stability]`: runs across the explicit bound k = 2a/b.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StabilitySpec {
    /// Meshes (M) to run, showing the bound does not depend on h.
    pub elements: Vec<usize>,
    /// Steps per run (T = N k is set per run).
    pub steps: usize,
    /// k / (2a/b) for the explicit runs.
    pub fractions: Vec<f64>,
    /// k / (2a/b) for the implicit and midpoint runs (far beyond the explicit bound).
    pub unconditional_fractions: Vec<f64>,
    /// Largest |μ_observed − μ_predicted| of each mode's amplification factor.
    pub mu_tolerance: f64,
    /// The observed onset must be bracketed within this relative distance of the prediction.
    pub onset_bracket: f64,
}

impl StabilityCase {
    /// Parses the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        case.body()
    }
}

/// One run of a stability case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StabilityRun {
    pub scheme: TimeScheme,
    pub elements: usize,
    /// k / (2a/b).
    pub fraction: f64,
    pub k: f64,
    /// μ1 = 1 − k b/α on the modes vanishing at x = L: predicted and observed.
    pub mu_interior_predicted: f64,
    pub mu_interior_observed: f64,
    /// μ2 = 1 − k b/(α + β L) on the contact mode: predicted and observed.
    pub mu_contact_predicted: f64,
    pub mu_contact_observed: f64,
    /// The predicted spectral radius max(|μ1|, |μ2|).
    pub rho_predicted: f64,
    /// (‖d_N‖/‖d_1‖)^{1/(N−1)}: the observed mean growth of the increments over the run.
    pub mean_growth: f64,
}

/// The stability case's data (the report's `stability` field).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StabilityReport {
    /// 2a/b.
    pub predicted_bound: f64,
    /// Largest explicit fraction observed stable and smallest observed unstable.
    pub observed_onset: (f64, f64),
    pub runs: Vec<StabilityRun>,
}

impl StabilityReport {
    /// The report's Markdown section: the bound and a table of the runs.
    fn section(&self) -> Section {
        let mut body = format!(
            "Predicted bound 2a/b = {}; observed onset between k = {} and k = {}.\n\n",
            self.predicted_bound, self.observed_onset.0, self.observed_onset.1
        );
        body.push_str(
            "| scheme | M | k/(2a/b) | k | μ1 predicted | μ1 observed | μ2 predicted | μ2 observed | mean growth |\n",
        );
        body.push_str("|---|---|---|---|---|---|---|---|---|\n");
        for run in &self.runs {
            let _ = writeln!(
                body,
                "| {} | {} | {} | {} | {:.9} | {:.9} | {:.9} | {:.9} | {:.6} |",
                run.scheme,
                run.elements,
                run.fraction,
                sci(run.k),
                run.mu_interior_predicted,
                run.mu_interior_observed,
                run.mu_contact_predicted,
                run.mu_contact_observed,
                run.mean_growth
            );
        }
        Section {
            title: "Stability runs".into(),
            body,
        }
    }
}

/// The predicted eigenvalues (μ1, μ2) of the step's iteration matrix: interior modes and contact
/// mode.
pub fn predicted_modes(scheme: TimeScheme, k: f64, a: f64, b: f64, beta_l: f64) -> (f64, f64) {
    let alpha = a + scheme.theta() * b * k;
    (1.0 - k * b / alpha, 1.0 - k * b / (alpha + beta_l))
}

/// The observed factors of the interior and contact modes from the first two increments whose
/// components are resolved: (μ1, μ2), NaN where a mode has decayed below round-off or is absent.
fn observed_modes(increments: &[Vec<f64>], nodes: &[f64]) -> (f64, f64) {
    let m = nodes.len() - 1;
    let l = nodes[m];
    let split = |d: &[f64]| -> (f64, Vec<f64>) {
        let alpha = d[m] / l;
        let r: Vec<f64> = d.iter().zip(nodes).map(|(v, x)| v - alpha * x).collect();
        (alpha, r)
    };
    let (a1, r1) = split(&increments[0]);
    let (a2, r2) = split(&increments[1]);
    let scale = increments[0].iter().map(|v| v * v).sum::<f64>().sqrt();
    let rr: f64 = r1.iter().map(|v| v * v).sum();
    let mu1 = if m >= 2 && rr.sqrt() > 1e-8 * scale {
        r2.iter().zip(&r1).map(|(p, q)| p * q).sum::<f64>() / rr
    } else {
        f64::NAN
    };
    let mu2 = if a1.abs() * l > 1e-8 * scale {
        a2 / a1
    } else {
        f64::NAN
    };
    (mu1, mu2)
}

/// Runs the stability case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = StabilityCase::parse(case).map_err(|e| e.to_string())?;
    let spec = &c.stability;
    let mut study = RodStudy::new(Some(&c.scene), None, &Discretization::default())
        .map_err(|e| e.to_string())?;
    let (a, b) = (study.problem.viscosity, study.problem.elasticity);
    let law = study
        .problem
        .foundation
        .as_foundation_law()
        .ok_or("the stability case needs one of the laws (2.7)-(2.9)")?;
    let beta_l = match law {
        FoundationLaw::Linear { beta } => beta * study.problem.length,
        _ => {
            return Err(
                "the stability case needs the linear law (2.7), whose step is linear".into(),
            )
        }
    };
    let bound = 2.0 * a / b;
    let mut runs = Vec::new();
    let mut plans: Vec<(TimeScheme, usize, f64)> = Vec::new();
    for &m in &spec.elements {
        for &f in &spec.fractions {
            plans.push((TimeScheme::Explicit, m, f));
        }
        for scheme in [TimeScheme::Implicit, TimeScheme::Midpoint] {
            for &f in spec.fractions.iter().chain(&spec.unconditional_fractions) {
                plans.push((scheme, m, f));
            }
        }
    }
    let bar = ctx.progress_bar(plans.len() as u64, &case.header.id);
    for (scheme, m, fraction) in plans {
        let k = fraction * bound;
        let (mu1_pred, mu2_pred) = predicted_modes(scheme, k, a, b, beta_l);
        let steps = spec.steps;
        study.problem.final_time = k * steps as f64;
        let grid = TimeGrid::uniform(study.problem.final_time, steps).map_err(|e| e.to_string())?;
        let mesh = study.mesh(m).map_err(|e| e.to_string())?;
        let nodes = mesh.nodes().to_vec();
        let solver = RodSolver::new(&study.problem, mesh, grid, scheme, study.params)
            .map_err(|e| format!("stability run ({scheme}, k = {k}): {e}"))?;
        let mut first: Vec<Vec<f64>> = Vec::with_capacity(2);
        let mut norms: Vec<f64> = Vec::with_capacity(steps);
        solver
            .run(&mut |s: &RodStep<'_>| {
                if let Some(w) = s.w {
                    if first.len() < 2 {
                        first.push(w.iter().map(|v| v * s.k).collect());
                    }
                    norms.push(w.iter().map(|v| v * v).sum::<f64>().sqrt());
                }
            })
            .map_err(|e| format!("stability run ({scheme}, k = {k}): {e}"))?;
        let (mu1_obs, mu2_obs) = observed_modes(&first, &nodes);
        let n = norms.len();
        let mean_growth = (norms[n - 1] / norms[0]).powf(1.0 / (n - 1) as f64);
        let rho_pred = if m >= 2 {
            mu1_pred.abs().max(mu2_pred.abs())
        } else {
            mu2_pred.abs()
        };
        runs.push(StabilityRun {
            scheme,
            elements: m,
            fraction,
            k,
            mu_interior_predicted: mu1_pred,
            mu_interior_observed: mu1_obs,
            mu_contact_predicted: mu2_pred,
            mu_contact_observed: mu2_obs,
            rho_predicted: rho_pred,
            mean_growth,
        });
        bar.inc(1);
    }
    bar.finish_and_clear();

    // Gates.
    let explicit: Vec<&StabilityRun> = runs
        .iter()
        .filter(|r| r.scheme == TimeScheme::Explicit)
        .collect();
    let stable_max = explicit
        .iter()
        .filter(|r| r.mean_growth < 1.0)
        .map(|r| r.fraction)
        .fold(f64::NEG_INFINITY, f64::max);
    let unstable_min = explicit
        .iter()
        .filter(|r| r.mean_growth > 1.0)
        .map(|r| r.fraction)
        .fold(f64::INFINITY, f64::min);
    let consistent = explicit
        .iter()
        .all(|r| (r.mean_growth > 1.0) == (r.fraction > 1.0));
    let onset = vec![
        Check::holds(
            &format!(
                "observed onset bracket [{stable_max}, {unstable_min}] (units of 2a/b) contains the prediction 1, on every mesh"
            ),
            stable_max < 1.0 && unstable_min > 1.0 && consistent,
            "growth exactly for k > 2a/b",
        ),
        Check::at_most("1 − largest stable fraction", 1.0 - stable_max, spec.onset_bracket),
        Check::at_most("smallest unstable fraction − 1", unstable_min - 1.0, spec.onset_bracket),
    ];
    let mut gates = vec![GateVerdict::from_checks(
        "explicit onset of instability at k = 2a/b".into(),
        "stability",
        onset,
        "observed as growth of the increments over 200 steps; the prediction is h-independent",
    )];
    let mut agree = Vec::new();
    for r in &runs {
        for (what, pred, obs) in [
            (
                "interior mode",
                r.mu_interior_predicted,
                r.mu_interior_observed,
            ),
            (
                "contact mode",
                r.mu_contact_predicted,
                r.mu_contact_observed,
            ),
        ] {
            if r.elements < 2 && what == "interior mode" {
                continue;
            }
            let mut c = Check::at_most(
                &format!(
                    "{} M = {} k/(2a/b) = {:e}, {what}: |μ_obs − μ_pred| (μ_pred = {pred:.9})",
                    r.scheme, r.elements, r.fraction
                ),
                (obs - pred).abs(),
                spec.mu_tolerance,
            );
            c.passed &= obs.is_finite();
            agree.push(c);
        }
    }
    gates.push(GateVerdict::from_checks(
        "observed modal amplification = predicted eigenvalues".into(),
        "stability",
        agree,
        "each mode's factor from the first two increments",
    ));
    let mut bounded = Vec::new();
    for r in runs.iter().filter(|r| r.scheme != TimeScheme::Explicit) {
        bounded.push(Check::at_most(
            &format!(
                "{} M = {} k/(2a/b) = {:e}: mean growth per step",
                r.scheme, r.elements, r.fraction
            ),
            r.mean_growth,
            1.0,
        ));
    }
    gates.push(GateVerdict::from_checks(
        "implicit and midpoint stay stable for every k".into(),
        "stability",
        bounded,
        "unconditional stability of θ ≥ 1/2",
    ));
    report.gates = gates;

    // Plot: predicted and observed |μ| of both modes against k/(2a/b).
    let mut fig = Figure::new(format!(
        "{}: amplification factors against k/(2a/b) (M = {})",
        case.header.id, spec.elements[0]
    ))
    .x_label("k / (2a/b)")
    .y_label("|μ| per step")
    .log_log()
    .vertical_line(1.0, "predicted bound k = 2a/b")
    .horizontal_line(1.0, "|μ| = 1");
    for (i, scheme) in TimeScheme::ALL.iter().enumerate() {
        let mine: Vec<&StabilityRun> = runs
            .iter()
            .filter(|r| r.scheme == *scheme && r.elements == spec.elements[0])
            .collect();
        let mut pred: Vec<(f64, f64)> = mine
            .iter()
            .map(|r| (r.fraction, r.mu_interior_predicted.abs()))
            .collect();
        pred.sort_by(|x, y| x.0.total_cmp(&y.0));
        let obs: Vec<(f64, f64)> = mine
            .iter()
            .map(|r| (r.fraction, r.mu_interior_observed.abs()))
            .collect();
        let growth: Vec<(f64, f64)> = mine.iter().map(|r| (r.fraction, r.mean_growth)).collect();
        fig = fig
            .series(
                Series::line(format!("{scheme}: |μ1| predicted"), pred)
                    .dashed()
                    .color(i),
            )
            .series(Series::markers(format!("{scheme}: |μ1| observed"), obs).color(i))
            .series(
                Series::markers(format!("{scheme}: mean growth of ‖d_n‖"), growth).color(i + 3),
            );
    }
    let mut zoom = Figure::new("explicit scheme near the bound (all meshes)")
        .x_label("k / (2a/b)")
        .y_label("per step")
        .vertical_line(1.0, "k = 2a/b")
        .horizontal_line(1.0, "1");
    for (i, &m) in spec.elements.iter().enumerate() {
        let mine: Vec<&StabilityRun> = runs
            .iter()
            .filter(|r| r.scheme == TimeScheme::Explicit && r.elements == m)
            .collect();
        zoom = zoom
            .series(
                Series::line_markers(
                    format!("|μ1| observed, M = {m}"),
                    mine.iter()
                        .map(|r| (r.fraction, r.mu_interior_observed.abs())),
                )
                .color(i),
            )
            .series(
                Series::markers(
                    format!("mean growth of ‖d_n‖, M = {m}"),
                    mine.iter().map(|r| (r.fraction, r.mean_growth)),
                )
                .color(i + 4),
            );
    }
    ctx.panels(
        report,
        "amplification",
        "amplification factors: all schemes (log–log) and the explicit scheme near its bound",
        &[fig, zoom],
        2,
    )?;
    let data = StabilityReport {
        predicted_bound: bound,
        observed_onset: (stable_max * bound, unstable_min * bound),
        runs,
    };
    report.sections.push(data.section());
    report.stability = Some(serde_json::to_value(&data).map_err(|e| e.to_string())?);
    Ok(())
}
