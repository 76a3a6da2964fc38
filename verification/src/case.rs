//! The case catalogue: one TOML file per verification case in `verification/cases/`.
//!
//! A case names its kind, its tier, the physics (an inline scene or a manufactured solution), what
//! to run (sweeps, stability runs, extremes, work–precision levels) and its gates. The format is
//! documented in `verification/cases/README.md`; unknown keys are errors.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use contactlab::mesh::interval::GradingEnd;
use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::plane_errors::PLANE_ERRORS;
use crate::rod_errors::ROD_ERRORS;

/// What a case does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CaseKind {
    /// Sweeps in h and k against an exact solution; rate gates, model gates, pinned references.
    Convergence,
    /// The explicit scheme's step bound: prediction against observed amplification.
    Stability,
    /// Data at the edge of the admissible range: each gives correct numbers or a clear error.
    Extremes,
    /// Error against cost for each scheme.
    WorkPrecision,
    /// Timing of the physical-limit run, with a budget.
    Performance,
    /// The paper's Test 2D, both readings of Γ1.
    PaperTest2d,
    /// The 2D explicit step bound.
    PlaneStability,
    /// Condensed and Newton paths: agreement and error against cost.
    PlanePaths,
    /// The 2D time loop against its budget.
    PlanePerformance,
}

/// Which runs include the case: `quick` cases run in `--quick` (CI) and in the default tier.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Tier {
    Quick,
    #[default]
    Default,
}

/// The parameter a rate is measured against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Against {
    H,
    K,
    HPlusK,
}

impl Against {
    /// The label used in reports.
    pub fn label(self) -> &'static str {
        match self {
            Against::H => "h",
            Against::K => "k",
            Against::HPlusK => "h + k",
        }
    }
}

/// The keys every case file has, whatever its kind; the rest of the file belongs to the kind (each
/// family of kinds parses the whole file into its own format, with unknown keys as errors).
#[derive(Debug, Clone, Deserialize, Serialize)]
pub struct CaseHeader {
    pub id: String,
    pub title: String,
    /// The case kind; it selects the runner (see `run::run_case`).
    pub kind: String,
    #[serde(default)]
    pub tier: Tier,
    /// Why the gates expect what they expect.
    pub explanation: String,
}

/// The case format of the quasistatic models (kinds `convergence`, `stability`, `extremes`,
/// `work_precision`, `performance`).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    pub id: String,
    pub title: String,
    pub kind: CaseKind,
    #[serde(default)]
    pub tier: Tier,
    /// Why the gates expect what they expect (regularity, floors, superconvergence).
    pub explanation: String,
    /// An inline rod scene (`model = "rod"`); mesh and time entries are overridden per run.
    pub scene: Option<toml::Table>,
    pub exact: Option<ExactSpec>,
    #[serde(default)]
    pub discretization: DiscretizationSpec,
    #[serde(default)]
    pub sweep: Vec<SweepSpec>,
    #[serde(default)]
    pub gate: Vec<RateGateSpec>,
    #[serde(default)]
    pub model_gate: Vec<ModelGateSpec>,
    #[serde(default)]
    pub reference: Vec<ReferenceSpec>,
    pub figures: Option<FiguresSpec>,
    pub stability: Option<StabilitySpec>,
    #[serde(default)]
    pub extreme: Vec<ExtremeSpec>,
    pub work_precision: Option<WorkPrecisionSpec>,
    pub performance: Option<PerformanceSpec>,
    pub paper_test: Option<PaperTestSpec>,
    pub plane_stability: Option<PlaneStabilitySpec>,
    pub plane_paths: Option<PlanePathsSpec>,
    pub plane_performance: Option<PlanePerformanceSpec>,
}

/// `[paper_test]`: the paper's Test 2D (Fernández & Sofonea 2004, §4.2) under both readings of
/// Γ1, compared with its Figs 11–15.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PaperTestSpec {
    /// Squares per side of the meshes compared.
    pub meshes: Vec<usize>,
    /// The mesh of the figures.
    pub figure_mesh: usize,
    pub betas: Vec<f64>,
    /// The β of the von Mises comparison (the paper's Fig 14: β = 1000).
    pub von_mises_beta: f64,
    /// The paper's von Mises range at T (Fig 14).
    pub paper_von_mises: [f64; 2],
    /// The paper's lowest contact line value at T (Fig 15) and the β whose line reaches it here.
    pub paper_contact_min: f64,
    pub contact_min_beta: f64,
    /// Relative tolerance of the reproduction gates.
    pub reproduction_tolerance: f64,
    /// Largest ratio of successive mesh differences for the self-convergence gate.
    pub convergence_ratio: f64,
}

/// `[plane_stability]`: the explicit bound k λ_max(A⁻¹B) < 2 in 2D.
#[derive(Debug, Clone, Deserialize, Serialize)]
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
}

/// `[plane_paths]`: the condensed and Newton paths on a linear problem, error against cost.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PlanePathsSpec {
    pub elements: Vec<usize>,
    pub steps: Vec<usize>,
    pub error: String,
    pub repeats: usize,
    /// Largest relative difference of the two paths' errors (and solutions).
    pub agreement: f64,
}

/// `[plane_performance]`: the paper's Test 2D time loop against a budget.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PlanePerformanceSpec {
    /// Meshes (squares per side); the last is budgeted.
    pub meshes: Vec<usize>,
    pub steps: usize,
    pub repeats: usize,
    pub budget_seconds: f64,
    /// Largest growth of (step cost / sparse solve cost) across meshes (max/min).
    pub max_cost_ratio_spread: f64,
}

/// `[exact]`: the solution the errors are measured against.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ExactSpec {
    /// `rod_constant_data` (the family, data from the scene), `paper_4_6`, `paper_4_7`,
    /// `rod_manufactured_switching`, `rod_manufactured_receding` (these bring their own data).
    pub solution: String,
}

/// `[discretization]`: options of every run of the case (defaults: the scene's).
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DiscretizationSpec {
    pub mesh_grading: Option<f64>,
    pub graded_towards: Option<GradingEnd>,
    pub time_grading: Option<f64>,
    pub post_process_velocity: Option<bool>,
    /// The scheme of a case without a scene (plane manufactured solutions).
    pub scheme: Option<TimeScheme>,
    /// Plane: `gauss2` or `nodal`.
    pub contact_integration: Option<contactlab::model::quasistatic::plane::ContactIntegration>,
    /// Plane: `auto`, `condensed` or `newton`.
    pub solver_path: Option<contactlab::model::quasistatic::plane_solver::SolverPath>,
    /// Plane: steps of the reference run on the same mesh for the time error `time_l2_final`.
    pub time_reference_steps: Option<usize>,
}

/// `[[sweep]]`: a list of levels (M elements, N steps), each run with each scheme.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    pub name: String,
    pub elements: Vec<usize>,
    /// One entry per level, or a single entry used for every level.
    pub steps: Vec<usize>,
    #[serde(default)]
    pub schemes: Vec<TimeScheme>,
    /// Plane: also measure the time error against the reference run on the same mesh (needs
    /// `[discretization] time_reference_steps`; meant for sweeps in k at a fixed mesh).
    #[serde(default)]
    pub time_error: bool,
}

impl SweepSpec {
    /// The (M, N) levels.
    pub fn levels(&self) -> Vec<(usize, usize)> {
        let n = self.elements.len().max(self.steps.len());
        (0..n)
            .map(|i| {
                let m = *self.elements.get(i).unwrap_or(&self.elements[0]);
                let s = *self.steps.get(i).unwrap_or(&self.steps[0]);
                (m, s)
            })
            .collect()
    }
}

/// `[[gate]]`: a rate gate — fitted rate within tolerance, CI narrower than a width, finest error
/// under a ceiling, pairwise rates of the finest levels consistent with the fit.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RateGateSpec {
    pub sweep: String,
    pub scheme: Option<TimeScheme>,
    pub error: String,
    pub against: Against,
    pub expected_rate: f64,
    pub tolerance: f64,
    pub finest_levels: usize,
    pub ci_width: f64,
    pub ceiling: f64,
    /// Pairwise rates of the finest pairs must lie within this of the fit (default: `tolerance`).
    pub asymptotic_tolerance: Option<f64>,
    /// For rates with an explained scatter: instead of |fit − expected| ≤ tolerance, require the
    /// expected rate to lie inside the 95% confidence interval (the data do not reject it), with
    /// the interval no wider than `ci_width`.
    #[serde(default)]
    pub expected_in_ci: bool,
    #[serde(default)]
    pub note: String,
}

/// `[[model_gate]]`: E(h, k) ≈ C_h h^p + C_k k^q fitted over all runs of the named sweeps.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ModelGateSpec {
    pub sweeps: Vec<String>,
    pub scheme: Option<TimeScheme>,
    pub error: String,
    pub expected_p: f64,
    pub expected_q: f64,
    pub tolerance: f64,
    pub ci_width: f64,
    /// `sum` (E = C_h h^p + C_k k^q) or `quadrature` (E² = (C_h h^p)² + (C_k k^q)², for errors
    /// whose spatial and temporal parts are orthogonal).
    #[serde(default)]
    pub combination: crate::stats::error_model::Combination,
    #[serde(default)]
    pub note: String,
}

/// `[[reference]]`: a pinned value of one run.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceSpec {
    pub name: String,
    /// An error functional (`paper_E`, …) or `u_end` (the computed u_h(L, T)).
    pub quantity: String,
    pub elements: usize,
    pub steps: usize,
    #[serde(default)]
    pub scheme: TimeScheme,
    pub value: f64,
    pub relative_tolerance: f64,
}

/// `[figures]`: the paper's figures (snapshots, node histories, contact stress) for one run.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FiguresSpec {
    pub elements: usize,
    pub steps: usize,
    #[serde(default)]
    pub scheme: TimeScheme,
    pub snapshot_times: Vec<f64>,
    pub probes: Vec<f64>,
    /// Label of the paper figures reproduced, e.g. "Figs 2–4".
    #[serde(default)]
    pub paper_figures: String,
}

/// `[stability]`: runs across the explicit bound k = 2a/b.
#[derive(Debug, Clone, Deserialize, Serialize)]
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

/// `[[extreme]]`: one run at the edge of the admissible data.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ExtremeSpec {
    pub name: String,
    /// Dotted scene keys and values overriding the case's scene (`"foundation.p0" = 5.000000001`).
    #[serde(default)]
    pub set: toml::Table,
    pub elements: usize,
    pub steps: usize,
    #[serde(default)]
    pub scheme: TimeScheme,
    /// `solution` (must run and meet the checks below) or `non_finite_error` (must stop with a
    /// non-finite error naming the step).
    pub expect: String,
    /// Ceiling of the paper error E against the constant-data exact solution.
    pub paper_e_ceiling: Option<f64>,
    /// Largest Newton iteration count allowed in one step.
    pub max_newton_iterations: Option<usize>,
    /// Compare a single step with its independent closed form to this relative tolerance.
    pub one_step_tolerance: Option<f64>,
    /// Also run (2M, 2N) and (4M, 4N): the pairwise rates of the paper error E must lie within
    /// `refinement_tolerance` of this rate (the data still converge at the theory's order).
    pub refinement_rate: Option<f64>,
    pub refinement_tolerance: Option<f64>,
    #[serde(default)]
    pub note: String,
}

/// `[work_precision]`: error against cost for every scheme.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WorkPrecisionSpec {
    pub error: String,
    /// Levels (M, N) along which every scheme is run.
    pub elements: Vec<usize>,
    pub steps: Vec<usize>,
    pub schemes: Vec<TimeScheme>,
    /// Timing repeats per run (the minimum is reported).
    pub repeats: usize,
    /// Gate: the `cheaper` scheme reaches the finest error of `baseline` with at most this
    /// fraction of its work (counted in dof-steps, which is deterministic).
    pub baseline: TimeScheme,
    pub cheaper: TimeScheme,
    pub max_work_ratio: f64,
}

/// `[performance]`: the time loop of one large run against a budget.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PerformanceSpec {
    /// Sizes (M, N) timed; the last is the budgeted one.
    pub elements: Vec<usize>,
    pub steps: Vec<usize>,
    pub repeats: usize,
    pub budget_seconds: f64,
    /// Largest allowed spread of the per-dof-step cost across sizes (max/min): linear growth.
    pub max_cost_spread: f64,
}

/// A case read from disk: its header and the whole file as a table for its kind's runner.
#[derive(Debug, Clone)]
pub struct Case {
    pub path: PathBuf,
    pub header: CaseHeader,
    pub table: toml::Table,
}

/// Why a case file is unusable.
#[derive(Debug, thiserror::Error)]
pub enum CaseError {
    #[error("{path}: {message}")]
    Read { path: String, message: String },
    #[error("{path}: invalid {field} = {value}: expected {expected}")]
    Invalid {
        path: String,
        field: String,
        value: String,
        expected: String,
    },
}

fn invalid(path: &Path, field: &str, value: impl std::fmt::Display, expected: &str) -> CaseError {
    CaseError::Invalid {
        path: path.display().to_string(),
        field: field.to_string(),
        value: value.to_string(),
        expected: expected.to_string(),
    }
}

impl Case {
    /// Reads one case file and checks it with its kind's format.
    pub fn load(path: &Path) -> Result<Self, CaseError> {
        let read_error = |message: String| CaseError::Read {
            path: path.display().to_string(),
            message,
        };
        let text = std::fs::read_to_string(path).map_err(|e| read_error(e.to_string()))?;
        Self::from_text(path, &text)
    }

    /// A case from TOML text (`path` labels errors).
    pub fn from_text(path: &Path, text: &str) -> Result<Self, CaseError> {
        let read_error = |message: String| CaseError::Read {
            path: path.display().to_string(),
            message,
        };
        let table: toml::Table = text
            .parse()
            .map_err(|e: toml::de::Error| read_error(e.to_string()))?;
        let header: CaseHeader = table
            .clone()
            .try_into()
            .map_err(|e: toml::de::Error| read_error(e.to_string()))?;
        let case = Self {
            path: path.to_path_buf(),
            header,
            table,
        };
        crate::run::check_case(&case)?;
        Ok(case)
    }

    /// Reads every `*.toml` of a directory, sorted by file name.
    pub fn load_all(dir: &Path) -> Result<Vec<Self>, CaseError> {
        let entries = std::fs::read_dir(dir).map_err(|e| CaseError::Read {
            path: dir.display().to_string(),
            message: e.to_string(),
        })?;
        let mut paths: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .collect();
        paths.sort();
        let cases: Vec<Self> = paths
            .iter()
            .map(|p| Self::load(p))
            .collect::<Result<_, _>>()?;
        for (i, c) in cases.iter().enumerate() {
            if cases[..i].iter().any(|d| d.header.id == c.header.id) {
                return Err(invalid(
                    &c.path,
                    "id",
                    &c.header.id,
                    "an id no other case uses",
                ));
            }
        }
        Ok(cases)
    }
}

impl CaseFile {
    /// The quasistatic case format of a case, checked.
    pub fn from_case(case: &Case) -> Result<Self, CaseError> {
        let file: CaseFile = case
            .table
            .clone()
            .try_into()
            .map_err(|e: toml::de::Error| CaseError::Read {
                path: case.path.display().to_string(),
                message: e.to_string(),
            })?;
        file.check(&case.path)?;
        Ok(file)
    }

    fn check(&self, p: &Path) -> Result<(), CaseError> {
        let f = self;
        let error_names: Vec<&str> = ROD_ERRORS
            .iter()
            .chain(PLANE_ERRORS.iter())
            .copied()
            .collect();
        for (i, s) in f.sweep.iter().enumerate() {
            if s.elements.is_empty() || s.steps.is_empty() {
                return Err(invalid(
                    p,
                    &format!("sweep[{i}]"),
                    "(empty)",
                    "non-empty elements and steps",
                ));
            }
            if s.elements.len() != s.steps.len() && s.elements.len() != 1 && s.steps.len() != 1 {
                return Err(invalid(
                    p,
                    &format!("sweep[{i}].steps"),
                    format!("{} entries", s.steps.len()),
                    "one entry per level, or a single entry",
                ));
            }
        }
        for (i, g) in f.gate.iter().enumerate() {
            let field = format!("gate[{i}]");
            if !f.sweep.iter().any(|s| s.name == g.sweep) {
                return Err(invalid(
                    p,
                    &format!("{field}.sweep"),
                    &g.sweep,
                    "the name of a [[sweep]]",
                ));
            }
            if !error_names.contains(&g.error.as_str()) {
                return Err(invalid(
                    p,
                    &format!("{field}.error"),
                    &g.error,
                    "a rod error functional",
                ));
            }
            if g.finest_levels < 2 {
                return Err(invalid(
                    p,
                    &format!("{field}.finest_levels"),
                    g.finest_levels,
                    ">= 2",
                ));
            }
            for (name, v) in [
                ("tolerance", g.tolerance),
                ("ci_width", g.ci_width),
                ("ceiling", g.ceiling),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(invalid(
                        p,
                        &format!("{field}.{name}"),
                        v,
                        "a finite number > 0",
                    ));
                }
            }
        }
        for (i, g) in f.model_gate.iter().enumerate() {
            for s in &g.sweeps {
                if !f.sweep.iter().any(|x| &x.name == s) {
                    return Err(invalid(
                        p,
                        &format!("model_gate[{i}].sweeps"),
                        s,
                        "names of [[sweep]]s",
                    ));
                }
            }
            if !error_names.contains(&g.error.as_str()) {
                return Err(invalid(
                    p,
                    &format!("model_gate[{i}].error"),
                    &g.error,
                    "a rod error functional",
                ));
            }
        }
        for (i, r) in f.reference.iter().enumerate() {
            if r.quantity != "u_end" && !error_names.contains(&r.quantity.as_str()) {
                return Err(invalid(
                    p,
                    &format!("reference[{i}].quantity"),
                    &r.quantity,
                    "u_end or a rod error functional",
                ));
            }
        }
        let needs = |what: bool, field: &str| -> Result<(), CaseError> {
            if what {
                Ok(())
            } else {
                Err(invalid(
                    p,
                    field,
                    "(missing)",
                    "a section for this kind of case",
                ))
            }
        };
        match f.kind {
            CaseKind::Convergence => {
                needs(!f.sweep.is_empty() || !f.reference.is_empty(), "sweep")?
            }
            CaseKind::Stability => needs(f.stability.is_some(), "stability")?,
            CaseKind::Extremes => needs(!f.extreme.is_empty(), "extreme")?,
            CaseKind::WorkPrecision => needs(f.work_precision.is_some(), "work_precision")?,
            CaseKind::Performance => needs(f.performance.is_some(), "performance")?,
            CaseKind::PaperTest2d => needs(f.paper_test.is_some(), "paper_test")?,
            CaseKind::PlaneStability => needs(f.plane_stability.is_some(), "plane_stability")?,
            CaseKind::PlanePaths => needs(f.plane_paths.is_some(), "plane_paths")?,
            CaseKind::PlanePerformance => {
                needs(f.plane_performance.is_some(), "plane_performance")?
            }
        }
        if f.scene.is_none() && f.exact.is_none() {
            return Err(invalid(
                p,
                "scene",
                "(missing)",
                "a [scene] or an [exact] manufactured solution",
            ));
        }
        Ok(())
    }
}
