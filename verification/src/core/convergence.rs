//! Convergence studies of any model with a [`Study`]: sweeps in h and k, rate gates with
//! confidence intervals, joint error-model gates, pinned reference values, and one log–log plot
//! per (sweep, parameter) with the expected slopes.
//!
//! A family's convergence kind reads its case body as a [`ConvergenceCase`] (its own keys — the
//! scene, the exact solution, its options — and the generic part, a [`ConvergenceSpec`]) and
//! hands the generic part to [`run`] with its study.

use std::path::Path;

use serde::de::DeserializeOwned;
use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::{invalid, CaseError};
use crate::core::gate::{ModelCriteria, RateGate};
use crate::core::report::case_report::CaseReport;
use crate::core::study::{run_sweeps, Study};
use crate::core::sweep::{Against, SweepReport, SweepSpec};
use crate::plot::{Figure, Series};
use crate::stats::error_model::Combination;

/// What a convergence `[[gate]]` measures: one error of one sweep (and scheme) against h, k or
/// h + k.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSelect<S> {
    pub sweep: String,
    /// Required when the sweep runs several schemes.
    pub scheme: Option<S>,
    pub error: String,
    pub against: Against,
}

/// `[[model_gate]]`: E(h, k) fitted over all runs of the named sweeps.
#[derive(Debug, Clone)]
pub struct ModelGate<S> {
    pub sweeps: Vec<String>,
    pub scheme: Option<S>,
    pub error: String,
    pub criteria: ModelCriteria,
}

impl<'de, S: serde::de::DeserializeOwned> Deserialize<'de> for ModelGate<S> {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Select<S> {
            sweeps: Vec<String>,
            scheme: Option<S>,
            error: String,
        }
        let mut rest = toml::Table::deserialize(deserializer)?;
        let mut criteria = toml::Table::new();
        for key in [
            "expected_p",
            "expected_q",
            "tolerance",
            "ci_width",
            "combination",
            "note",
        ] {
            if let Some(v) = rest.remove(key) {
                criteria.insert(key.to_string(), v);
            }
        }
        let criteria: ModelCriteria = criteria.try_into().map_err(serde::de::Error::custom)?;
        let s: Select<S> = rest.try_into().map_err(serde::de::Error::custom)?;
        Ok(Self {
            sweeps: s.sweeps,
            scheme: s.scheme,
            error: s.error,
            criteria,
        })
    }
}

/// The generic part of a convergence case.
#[derive(Debug, Clone)]
pub struct ConvergenceSpec<S: Default> {
    pub sweeps: Vec<SweepSpec<S>>,
    pub gates: Vec<RateGate<SweepSelect<S>>>,
    pub model_gates: Vec<ModelGate<S>>,
}

/// The sections of a convergence case body that the core reads.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, bound = "S: DeserializeOwned + Default")]
struct Sections<S: Default> {
    #[serde(default)]
    sweep: Vec<SweepSpec<S>>,
    #[serde(default)]
    gate: Vec<RateGate<SweepSelect<S>>>,
    #[serde(default)]
    model_gate: Vec<ModelGate<S>>,
}

/// A convergence case body: the family's keys, read into its format `F` (which denies unknown
/// keys: the scene, the exact solution, the discretization options), and the core's sections
/// `[[sweep]]`, `[[gate]]` and `[[model_gate]]`. (No pinned values: a gate compares with an exact
/// solution, a manufactured one or a second implementation, never with a previous run's output.)
#[derive(Debug, Clone)]
pub struct ConvergenceCase<F, S: Default> {
    pub family: F,
    pub spec: ConvergenceSpec<S>,
}

impl<F: DeserializeOwned, S: DeserializeOwned + Copy + Default> ConvergenceCase<F, S> {
    /// Reads the body of `case` and checks the core's sections against the study's error
    /// names `errors` (the family checks its own keys).
    pub fn parse(case: &Case, errors: &[&str]) -> Result<Self, CaseError> {
        let (sections, family): (Sections<S>, F) =
            case.body_split(&["sweep", "gate", "model_gate"])?;
        let spec = ConvergenceSpec {
            sweeps: sections.sweep,
            gates: sections.gate,
            model_gates: sections.model_gate,
        };
        spec.check(case.path(), errors)?;
        Ok(Self { family, spec })
    }
}

impl<S: Copy + Default> ConvergenceSpec<S> {
    /// Checks sweeps and gates against the study's error names (`errors`).
    pub fn check(&self, path: &Path, errors: &[&str]) -> Result<(), CaseError> {
        for (i, s) in self.sweeps.iter().enumerate() {
            s.check(path, &format!("sweep[{i}]"))?;
        }
        let expected_error = format!("one of {}", errors.join(", "));
        for (i, g) in self.gates.iter().enumerate() {
            let field = format!("gate[{i}]");
            if !self.sweeps.iter().any(|s| s.name == g.select.sweep) {
                return Err(invalid(
                    path,
                    &format!("{field}.sweep"),
                    &g.select.sweep,
                    "the name of a [[sweep]]",
                ));
            }
            if !errors.contains(&g.select.error.as_str()) {
                return Err(invalid(
                    path,
                    &format!("{field}.error"),
                    &g.select.error,
                    &expected_error,
                ));
            }
            g.criteria.check(path, &field)?;
        }
        for (i, g) in self.model_gates.iter().enumerate() {
            for s in &g.sweeps {
                if !self.sweeps.iter().any(|x| &x.name == s) {
                    return Err(invalid(
                        path,
                        &format!("model_gate[{i}].sweeps"),
                        s,
                        "names of [[sweep]]s",
                    ));
                }
            }
            if !errors.contains(&g.error.as_str()) {
                return Err(invalid(
                    path,
                    &format!("model_gate[{i}].error"),
                    &g.error,
                    &expected_error,
                ));
            }
        }
        if self.sweeps.is_empty() {
            return Err(invalid(
                path,
                "sweep",
                "(missing)",
                "a section for this kind of case",
            ));
        }
        Ok(())
    }
}

/// The sweep `name` run with `scheme` (or its only scheme).
fn find<'a>(
    sweeps: &'a [SweepReport],
    name: &str,
    scheme: Option<String>,
) -> Result<&'a SweepReport, String> {
    let candidates: Vec<&SweepReport> = sweeps.iter().filter(|s| s.name == name).collect();
    match scheme {
        Some(s) => candidates
            .into_iter()
            .find(|r| r.scheme == s)
            .ok_or_else(|| format!("sweep `{name}` has no runs with scheme {s}")),
        None if candidates.len() == 1 => Ok(candidates[0]),
        None => Err(format!(
            "sweep `{name}` runs several schemes: the gate must name one"
        )),
    }
}

/// Runs the sweeps, evaluates the rate and model gates, and plots the gated
/// errors.
pub fn run<T: Study>(
    spec: &ConvergenceSpec<T::Scheme>,
    study: &T,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    report.sweeps = run_sweeps(study, &spec.sweeps, ctx, &report.id)?;
    let mut gates = Vec::new();
    for g in &spec.gates {
        let sel = &g.select;
        let sweep = find(
            &report.sweeps,
            &sel.sweep,
            sel.scheme.map(|s| s.to_string()),
        )?;
        let param: Vec<f64> = sweep.levels.iter().map(|l| sel.against.of(l)).collect();
        let error: Vec<f64> = sweep
            .levels
            .iter()
            .map(|l| l.errors.get(&sel.error).copied().unwrap_or(f64::NAN))
            .collect();
        let name = format!(
            "{}/{}: {} vs {}",
            sel.sweep,
            sweep.scheme,
            sel.error,
            sel.against.label()
        );
        gates.push(g.criteria.evaluate(name, &param, &error));
    }
    for g in &spec.model_gates {
        let (mut h, mut k, mut e) = (Vec::new(), Vec::new(), Vec::new());
        for name in &g.sweeps {
            let sweep = find(&report.sweeps, name, g.scheme.map(|s| s.to_string()))?;
            for l in &sweep.levels {
                h.push(l.h);
                k.push(l.k);
                e.push(l.errors.get(&g.error).copied().unwrap_or(f64::NAN));
            }
        }
        let form = match g.criteria.combination {
            Combination::Sum => "C_h h^p + C_k k^q",
            Combination::Quadrature => "((C_h h^p)² + (C_k k^q)²)^½",
        };
        let name = format!("{}: {} ≈ {form}", g.sweeps.join(" + "), g.error);
        gates.push(g.criteria.evaluate(name, &h, &k, &e));
    }
    report.gates = gates;
    convergence_plots(spec, ctx, report)
}

/// One log–log plot per (sweep, parameter) of the gated errors, with the expected slopes.
fn convergence_plots<S: Copy + Default>(
    spec: &ConvergenceSpec<S>,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let mut figures = Vec::new();
    for sweep in &spec.sweeps {
        let mut againsts: Vec<Against> = Vec::new();
        for g in spec.gates.iter().filter(|g| g.select.sweep == sweep.name) {
            if !againsts.contains(&g.select.against) {
                againsts.push(g.select.against);
            }
        }
        for against in againsts {
            let mut errors: Vec<&str> = Vec::new();
            let mut slopes: Vec<f64> = Vec::new();
            for g in spec
                .gates
                .iter()
                .filter(|g| g.select.sweep == sweep.name && g.select.against == against)
            {
                if !errors.contains(&g.select.error.as_str()) {
                    errors.push(&g.select.error);
                }
                let rate = g.criteria.expected_rate;
                if !slopes.iter().any(|s| (s - rate).abs() < 1e-12) {
                    slopes.push(rate);
                }
            }
            let mut fig = Figure::new(format!(
                "{}: sweep `{}`, errors against {}",
                report.id,
                sweep.name,
                against.label()
            ))
            .x_label(against.label())
            .y_label("error")
            .log_log();
            for s in report.sweeps.iter().filter(|s| s.name == sweep.name) {
                for e in &errors {
                    let pts: Vec<(f64, f64)> = s
                        .levels
                        .iter()
                        .filter_map(|l| l.errors.get(*e).map(|v| (against.of(l), *v)))
                        .collect();
                    if !pts.is_empty() {
                        fig = fig.series(Series::line_markers(format!("{e} ({})", s.scheme), pts));
                    }
                }
            }
            for s in slopes {
                fig = fig.reference_slope(s, format!("slope {s}"));
            }
            figures.push((format!("{}_{}", sweep.name, against.file_label()), fig));
        }
    }
    for (name, fig) in figures {
        ctx.plot(report, &name, &fig)?;
    }
    Ok(())
}
