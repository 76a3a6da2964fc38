//! `dynamic_extremes`: stability of the dynamic contact solver at the extremes of its data
//! (Barboteu–Danan–Sofonea, "BDS"; Hauret–Le Tallec, "HLT"; `docs/dynamic.md` §§1–3).
//! Every run must give a correct solution or stop with a typed error that carries its data —
//! never a panic, never a NaN in what it recorded. Four studies, each a list in the case file:
//!
//! - `[[blow_up]]` — the midpoint rule against Gonzalez's scheme on a hyperelastic body with a
//!   large step. The midpoint rule evaluates F_int at u_{n−1/2}, whose work over the step is not
//!   𝒲(u_n) − 𝒲(u_{n−1}) for a nonlinear law, so (1.48) fails and the energy can grow without
//!   bound (BDS §1.6; EM paper §4); Gonzalez's discrete gradient (BDS (1.41)–(1.43)) makes
//!   Π^algo : (∇u_n − ∇u_{n−1}) = W̃(C_n) − W̃(C_{n−1}) exact, so the energy is conserved to
//!   round-off without contact and the identities (1.48)/(1.49)/HLT 3.7 hold with an
//!   energy-consistent contact force.
//! - `[[penalty]]` — the penalty stiffness r over many decades on an impact: the condition of
//!   the step Jacobian J = α M + θ K + Σ_i w_i N_i′(p_i) e_i e_iᵀ (full path) and of its Schur
//!   complement on the contact dofs (condensed path) by a dense symmetric eigen-decomposition,
//!   Newton iterations and backtracks, the largest penetration and its asymptotic slope in r,
//!   and the energy identities.
//! - `[[speed]]` — impact speeds over decades: the identities at round-off, and the trends of
//!   penetration and contact time: exact homogeneity (a linear body with zero initial gap: u
//!   scales with v), wave theory for a bar (contact time 2L/c, rebound at v, mean contact force
//!   ρ c A v), Hertz-like stiffening for a curved body (sublinear penetration, non-increasing
//!   contact time).
//! - `[[large_step]]` — time steps from resolved to far above the wave-crossing time h_min/c and
//!   the contact duration: the conserving combinations stay bounded with the identities at
//!   round-off; the others (Newmark, the midpoint rule on a hyperelastic body, the plain
//!   penalty force) are reported.
//!
//! This file holds the case format, its `check` and `run`, which hands each study to its own
//! file (`blow_up`, `penalty`, `speed`, `large_step`); `common` holds the recorded run, its
//! measurements and its gate, shared by the studies.

mod blow_up;
pub(crate) mod common;
mod large_step;
mod penalty;
mod speed;

use serde::{Deserialize, Serialize};

use contactlab::model::dynamic::scheme::DynamicScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::{invalid, positive, CaseError};
use crate::core::report::case_report::CaseReport;
use crate::dynamic::scene::scene_from_table;

/// The case format of `dynamic_extremes` (unknown keys are errors).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ExtremesCase {
    #[serde(default)]
    pub blow_up: Vec<BlowUpSpec>,
    #[serde(default)]
    pub penalty: Vec<PenaltySpec>,
    #[serde(default)]
    pub speed: Vec<SpeedSpec>,
    #[serde(default)]
    pub large_step: Vec<LargeStepSpec>,
}

/// `[[blow_up]]`: one scene run with a scheme that does not conserve energy and one that does.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BlowUpSpec {
    pub name: String,
    /// The dynamic scene (inline; `model = "dynamic"` implied); `time.scheme` is set per run.
    pub scene: toml::Table,
    /// The scheme expected to violate (1.48) (the midpoint rule on a hyperelastic body).
    pub unstable: DynamicScheme,
    /// The conserving scheme (Gonzalez).
    pub stable: DynamicScheme,
    /// The least largest relative energy error max_n |(E + Φ)_n − (E + Φ)_0 − W_n| / (E + Φ)_0
    /// the unstable scheme must show before it stops or ends (the blow-up made visible).
    pub min_energy_error: f64,
    #[serde(default)]
    pub note: String,
}

/// `[[penalty]]`: one impact run with each penalty stiffness r (and each solver path).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PenaltySpec {
    pub name: String,
    pub scene: toml::Table,
    /// The values of `contact.stiffness`.
    pub stiffness: Vec<f64>,
    /// `auto` (the model's path) and/or `full` (the full Newton path, for comparison).
    #[serde(default = "default_paths")]
    pub paths: Vec<String>,
    /// Largest number of dofs for which the condition numbers are computed (dense eigenvalues).
    #[serde(default = "default_condition_dofs")]
    pub condition_max_dofs: usize,
    /// The slope of ln(max penetration) against ln r is fitted on the runs with r ≥ this.
    pub slope_from: f64,
    pub expected_slope: f64,
    pub slope_tolerance: f64,
    /// The slope of ln κ(J) (worst case) against ln r, fitted on the runs with
    /// r ≥ `condition_slope_from` (κ ∝ r once r w_i dominates λ_max(α M + θ K)).
    pub expected_condition_slope: Option<f64>,
    pub condition_slope_from: Option<f64>,
    /// Largest Newton iteration count of one step allowed.
    pub max_newton_iterations: usize,
    /// Largest relative difference of the largest penetration between the paths, checked for
    /// r ≤ `path_agreement_up_to` (the resolved regime; beyond, the chattering contact nodes
    /// amplify round-off and the difference is reported only).
    pub path_agreement: Option<f64>,
    pub path_agreement_up_to: Option<f64>,
    #[serde(default)]
    pub note: String,
}

fn default_paths() -> Vec<String> {
    vec!["auto".into()]
}

fn default_condition_dofs() -> usize {
    1200
}

/// `[[speed]]`: one impact at each speed.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedSpec {
    pub name: String,
    pub scene: toml::Table,
    /// Impact speeds |v| (m/s); the initial velocity is v · direction.
    pub speeds: Vec<f64>,
    /// Unit direction of the throw: one component for a bar, two in 2D.
    pub direction: Vec<f64>,
    /// The problem is positively homogeneous in (u, v) (linear body, zero initial gap, no load):
    /// p_max/v, F_max/v, contact time and rebound coefficient must agree across speeds to this
    /// relative tolerance.
    pub homogeneity_tolerance: Option<f64>,
    /// A bar: contact time against 2L/c, rebound coefficient against 1 and mean contact force
    /// against ρ c A v, each to this relative tolerance (wave theory of the free bar).
    pub wave_theory_tolerance: Option<f64>,
    /// Every pairwise exponent d ln p_max / d ln v must lie in this interval.
    pub penetration_exponent: Option<[f64; 2]>,
    /// The contact time must not increase with the speed (by more than one step).
    #[serde(default)]
    pub contact_time_nonincreasing: bool,
    #[serde(default)]
    pub note: String,
}

/// `[[large_step]]`: variants of one scene run with steps from resolved to far too large.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LargeStepSpec {
    pub name: String,
    pub scene: toml::Table,
    /// Numbers of steps over the scene's final time (k = T / N), finest first.
    pub steps: Vec<usize>,
    pub variant: Vec<VariantSpec>,
    /// The largest step must be at least this many wave-crossing times h_min / c …
    pub min_wave_crossings: f64,
    /// … and at least this fraction of the contact duration (measured on the finest run of the
    /// first conserving variant).
    pub min_contact_fraction: f64,
    #[serde(default)]
    pub note: String,
}

/// `[[large_step.variant]]`: scheme, law and contact treatment of one variant.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct VariantSpec {
    pub label: String,
    /// Dotted scene keys and values (`"time.scheme" = "gonzalez"`).
    #[serde(default)]
    pub set: toml::Table,
}

/// Validates a scene table now (its errors name the case file and the study).
fn check_scene(case: &Case, field: &str, scene: &toml::Table) -> Result<(), CaseError> {
    scene_from_table(scene, &toml::Table::new(), field)
        .map(|_| ())
        .map_err(|e| CaseError::Read {
            path: case.path().display().to_string(),
            message: e,
        })
}

/// Checks the case's format: known keys only, valid scenes, sensible numbers.
pub fn check(case: &Case) -> Result<(), CaseError> {
    let c: ExtremesCase = case.body()?;
    if c.blow_up.is_empty() && c.penalty.is_empty() && c.speed.is_empty() && c.large_step.is_empty()
    {
        return Err(invalid(
            case.path(),
            "blow_up / penalty / speed / large_step",
            "(none)",
            "at least one study",
        ));
    }
    for (i, b) in c.blow_up.iter().enumerate() {
        let f = format!("blow_up[{i}]");
        check_scene(case, &format!("{f}.scene"), &b.scene)?;
        positive(
            case.path(),
            &format!("{f}.min_energy_error"),
            b.min_energy_error,
        )?;
        if b.unstable == b.stable {
            return Err(invalid(
                case.path(),
                &format!("{f}.stable"),
                b.stable.name(),
                "a scheme other than `unstable`",
            ));
        }
    }
    for (i, p) in c.penalty.iter().enumerate() {
        let f = format!("penalty[{i}]");
        check_scene(case, &format!("{f}.scene"), &p.scene)?;
        if p.stiffness.len() < 3 {
            return Err(invalid(
                case.path(),
                &format!("{f}.stiffness"),
                format!("{} values", p.stiffness.len()),
                "at least 3 values",
            ));
        }
        for (j, r) in p.stiffness.iter().enumerate() {
            positive(case.path(), &format!("{f}.stiffness[{j}]"), *r)?;
        }
        if p.stiffness.iter().filter(|&&r| r >= p.slope_from).count() < 2 {
            return Err(invalid(
                case.path(),
                &format!("{f}.slope_from"),
                p.slope_from,
                "a value with at least two stiffnesses at or above it",
            ));
        }
        for path in &p.paths {
            if path != "auto" && path != "full" {
                return Err(invalid(
                    case.path(),
                    &format!("{f}.paths"),
                    path,
                    "\"auto\" or \"full\"",
                ));
            }
        }
        positive(
            case.path(),
            &format!("{f}.slope_tolerance"),
            p.slope_tolerance,
        )?;
    }
    for (i, s) in c.speed.iter().enumerate() {
        let f = format!("speed[{i}]");
        check_scene(case, &format!("{f}.scene"), &s.scene)?;
        if s.speeds.len() < 2 {
            return Err(invalid(
                case.path(),
                &format!("{f}.speeds"),
                format!("{} values", s.speeds.len()),
                "at least 2 speeds",
            ));
        }
        for (j, v) in s.speeds.iter().enumerate() {
            positive(case.path(), &format!("{f}.speeds[{j}]"), *v)?;
        }
        let norm: f64 = s.direction.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(s.direction.len() == 1 || s.direction.len() == 2) || (norm - 1.0).abs() > 1e-12 {
            return Err(invalid(
                case.path(),
                &format!("{f}.direction"),
                format!("{:?}", s.direction),
                "a unit vector of 1 (bar) or 2 components",
            ));
        }
    }
    for (i, l) in c.large_step.iter().enumerate() {
        let f = format!("large_step[{i}]");
        check_scene(case, &format!("{f}.scene"), &l.scene)?;
        if l.steps.len() < 2 || l.steps.contains(&0) {
            return Err(invalid(
                case.path(),
                &format!("{f}.steps"),
                format!("{:?}", l.steps),
                "at least 2 step counts ≥ 1",
            ));
        }
        if l.variant.is_empty() {
            return Err(invalid(
                case.path(),
                &format!("{f}.variant"),
                "(none)",
                "at least one [[large_step.variant]]",
            ));
        }
        for (j, v) in l.variant.iter().enumerate() {
            scene_from_table(&l.scene, &v.set, &format!("{f}.variant[{j}]")).map_err(|e| {
                CaseError::Read {
                    path: case.path().display().to_string(),
                    message: e,
                }
            })?;
        }
    }
    Ok(())
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c: ExtremesCase = case.body().map_err(|e| e.to_string())?;
    for (i, spec) in c.blow_up.iter().enumerate() {
        blow_up::run_blow_up(i, spec, ctx, report)?;
    }
    for (i, spec) in c.penalty.iter().enumerate() {
        penalty::run_penalty(i, spec, ctx, report)?;
    }
    for (i, spec) in c.speed.iter().enumerate() {
        speed::run_speed(i, spec, ctx, report)?;
    }
    for (i, spec) in c.large_step.iter().enumerate() {
        large_step::run_large_step(i, spec, ctx, report)?;
    }
    Ok(())
}
