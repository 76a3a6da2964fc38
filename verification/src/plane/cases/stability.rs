//! Kind `plane_stability`: the 2D explicit step bound: λ_max(A⁻¹B) computed for the scene on several meshes (generalized
//! eigenvalue; it approaches the constitutive ratio from below and does not grow with refinement),
//! then explicit runs across k = 2/λ_max — growth exactly above it — and implicit and midpoint runs
//! far beyond it. The scene's contact law must make the step linear (a prescribed stress (2.9)), so
//! that the prediction is sharp.

use contactlab::model::quasistatic::plane_solver::PlaneStep;
use contactlab::model::quasistatic::plane_stability::{
    constitutive_ratio, explicit_stability_eigenvalue,
};
use contactlab::model::quasistatic::scheme::TimeScheme;

use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::{at_least, positive, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::plane::scene::{variant, Variant};
use crate::plot::{Figure, Series};

/// The case body of `plane_stability`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StabilityCase {
    /// A linear plane scene (linear A and B, a prescribed contact stress).
    pub scene: toml::Table,
    pub plane_stability: PlaneStabilitySpec,
}

/// `[plane_stability]`: the explicit bound k λ_max(A⁻¹B) < 2 in 2D.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneStabilitySpec {
    /// Meshes (squares per side) on which λ_max is computed.
    pub meshes: Vec<usize>,
    /// The mesh of the time runs.
    pub run_mesh: usize,
    pub steps: usize,
    /// k / (2/λ_max) of the explicit runs.
    pub fractions: Vec<f64>,
    /// k / (2/λ_max) of the implicit and midpoint runs.
    pub unconditional_fractions: Vec<f64>,
    pub onset_bracket: f64,
    /// λ_max may exceed the constitutive ratio by round-off only: relative excess at most this
    /// multiple of ε n, n the free dofs (the Cholesky reduction and the symmetric eigensolver err by
    /// about ε κ(K_A), and κ(K_A) grows like n on these meshes).
    pub round_off_factor: f64,
}

impl StabilityCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: Self = case.body()?;
        let s = &c.plane_stability;
        at_least(case.path(), "plane_stability.meshes", &s.meshes, 2)?;
        positive(
            case.path(),
            "plane_stability.onset_bracket",
            s.onset_bracket,
        )?;
        positive(
            case.path(),
            "plane_stability.round_off_factor",
            s.round_off_factor,
        )?;
        Ok(c)
    }
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = StabilityCase::parse(case).map_err(|e| e.to_string())?;
    let spec = &c.plane_stability;
    let file = &c.scene;
    let base = variant(file, Variant::default())?;
    let (Some(a), Some(b)) = (
        base.problem.viscosity.as_linear(),
        base.problem.elasticity.as_linear(),
    ) else {
        return Err("the stability case needs linear A and B".into());
    };
    let bound = constitutive_ratio(a, b);
    let mut lambdas = Vec::new();
    for &n in &spec.meshes {
        let scene = variant(
            file,
            Variant {
                divisions: Some(n),
                ..Default::default()
            },
        )?;
        let solver = scene.solver().map_err(|e| e.to_string())?;
        let l = explicit_stability_eigenvalue(&solver).map_err(|e| e.to_string())?;
        lambdas.push((n, l, solver.dofs().n_solved()));
    }
    let round_off = |dofs: usize| spec.round_off_factor * f64::EPSILON * dofs as f64;
    let mut checks = Vec::new();
    for &(n, l, dofs) in &lambdas {
        checks.push(Check::at_most(
            &format!(
                "λ_max on {n}×{n} ({dofs} dofs) over the constitutive ratio {bound:.6} \
                 (1 + {} ε n)",
                spec.round_off_factor
            ),
            l / bound,
            1.0 + round_off(dofs),
        ));
    }
    let increasing = lambdas
        .windows(2)
        .all(|w| w[1].1 >= w[0].1 - round_off(w[1].2) * bound);
    checks.push(Check::holds(
        "λ_max does not decrease under refinement (it approaches the ratio from below)",
        increasing,
        "monotone",
    ));
    let mut gates = vec![GateVerdict::from_checks(
        "the step bound 2/λ_max is h-independent".into(),
        "plane_stability",
        checks,
        "λ_max ≤ max(b2/a2, (2b1 + b2)/(2a1 + a2)) for the isotropic forms",
    )];

    // Runs across the bound on run_mesh.
    let scene = variant(
        file,
        Variant {
            divisions: Some(spec.run_mesh),
            ..Default::default()
        },
    )?;
    let lambda = explicit_stability_eigenvalue(&scene.solver().map_err(|e| e.to_string())?)
        .map_err(|e| e.to_string())?;
    let kcrit = 2.0 / lambda;
    let mut runs: Vec<(TimeScheme, f64, f64)> = Vec::new();
    let plans: Vec<(TimeScheme, f64)> = spec
        .fractions
        .iter()
        .map(|&f| (TimeScheme::Explicit, f))
        .chain(
            [TimeScheme::Implicit, TimeScheme::Midpoint]
                .iter()
                .flat_map(|&s| {
                    spec.fractions
                        .iter()
                        .chain(&spec.unconditional_fractions)
                        .map(move |&f| (s, f))
                }),
        )
        .collect();
    for (scheme, f) in plans {
        let k = f * kcrit;
        let scene = variant(
            file,
            Variant {
                divisions: Some(spec.run_mesh),
                scheme: Some(scheme),
                steps: Some(spec.steps),
                final_time: Some(k * spec.steps as f64),
                ..Default::default()
            },
        )?;
        let mut solver = scene.solver().map_err(|e| e.to_string())?;
        let mut norms = Vec::with_capacity(spec.steps);
        let outcome = solver.run(&mut |st: &PlaneStep<'_>| {
            if let Some(w) = st.w {
                norms.push(w.iter().map(|v| v * v).sum::<f64>().sqrt());
            }
        });
        let growth = match outcome {
            Ok(_) if norms.len() >= 2 && norms[0] > 0.0 => {
                (norms[norms.len() - 1] / norms[0]).powf(1.0 / (norms.len() - 1) as f64)
            }
            Ok(_) => f64::NAN,
            // overflow of an unstable explicit run is growth too
            Err(_) => f64::INFINITY,
        };
        runs.push((scheme, f, growth));
    }
    let explicit: Vec<&(TimeScheme, f64, f64)> = runs
        .iter()
        .filter(|r| r.0 == TimeScheme::Explicit)
        .collect();
    let stable_max = explicit
        .iter()
        .filter(|r| r.2 < 1.0)
        .map(|r| r.1)
        .fold(f64::NEG_INFINITY, f64::max);
    let unstable_min = explicit
        .iter()
        .filter(|r| r.2 > 1.0)
        .map(|r| r.1)
        .fold(f64::INFINITY, f64::min);
    let consistent = explicit.iter().all(|r| (r.2 > 1.0) == (r.1 > 1.0));
    gates.push(GateVerdict::from_checks(
        format!("explicit onset at k = 2/λ_max = {kcrit:.6} ({0}×{0})", spec.run_mesh),
        "plane_stability",
        vec![
            Check::holds(
                &format!("growth exactly for k/(2/λ_max) > 1: stable up to {stable_max}, unstable from {unstable_min}"),
                consistent && stable_max < 1.0 && unstable_min > 1.0,
                "onset at the prediction",
            ),
            Check::at_most("1 − largest stable fraction", 1.0 - stable_max, spec.onset_bracket),
            Check::at_most("smallest unstable fraction − 1", unstable_min - 1.0, spec.onset_bracket),
        ],
        "mean growth of ‖w_n‖ per step over the run",
    ));
    let mut bounded = Vec::new();
    for r in runs.iter().filter(|r| r.0 != TimeScheme::Explicit) {
        bounded.push(Check::at_most(
            &format!("{} at k/(2/λ_max) = {}: mean growth per step", r.0, r.1),
            r.2,
            1.0,
        ));
    }
    gates.push(GateVerdict::from_checks(
        "implicit and midpoint stay stable far beyond the bound".into(),
        "plane_stability",
        bounded,
        "",
    ));
    report.gates = gates;
    report.tables.push(Table {
        title: format!("λ_max(A⁻¹B) per mesh (constitutive ratio {bound:.6})"),
        header: vec!["mesh".into(), "λ_max".into(), "2/λ_max".into()],
        rows: lambdas
            .iter()
            .map(|(n, l, _)| {
                vec![
                    format!("{n}×{n}"),
                    format!("{l:.6}"),
                    format!("{:.6}", 2.0 / l),
                ]
            })
            .collect(),
    });
    report.tables.push(Table {
        title: "runs across the bound (mean growth of ‖w_n‖ per step)".into(),
        header: vec![
            "scheme".into(),
            "k/(2/λ_max)".into(),
            "k".into(),
            "mean growth".into(),
        ],
        rows: runs
            .iter()
            .map(|(s, f, g)| {
                vec![
                    s.to_string(),
                    format!("{f}"),
                    format!("{:.6}", f * kcrit),
                    format!("{g:.6}"),
                ]
            })
            .collect(),
    });
    let mut fig = Figure::new(format!(
        "{}: mean growth per step against k/(2/λ_max)",
        case.header.id
    ))
    .x_label("k / (2/λ_max)")
    .y_label("mean growth of ‖w_n‖ per step")
    .log_log()
    .vertical_line(1.0, "predicted bound")
    .horizontal_line(1.0, "1");
    for (i, s) in TimeScheme::ALL.iter().enumerate() {
        let pts: Vec<(f64, f64)> = runs
            .iter()
            .filter(|r| r.0 == *s && r.2.is_finite())
            .map(|r| (r.1, r.2))
            .collect();
        fig = fig.series(Series::line_markers(s.name(), pts).color(i));
    }
    ctx.plot(report, "growth", &fig)?;
    Ok(())
}
