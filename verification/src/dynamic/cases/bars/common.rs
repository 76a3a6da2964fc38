//! What the two 1D dynamic-contact case kinds share (`dynamic_signorini_bar`, `dynamic_bar_wall`):
//! run families (contact treatment × scheme × mass matrix, with the penalty stiffness and the
//! IPM depth scaled with the mesh), sweeps of (M, N) levels, rate gates, convergence plots and
//! the cost table.
//!
//! Scaling with the mesh (`stiffness_scaling = "element"`, the default): r = r̂ E / h. The bar's
//! end carries the contact weight A (its section), so the contact force is A r p and the penalty
//! spring A r = r̂ E A / h is r̂ times as stiff as one element; the penetration p ≈ σ / r =
//! σ h / (r̂ E) is O(h) like the discretization error and the step operator's conditioning does not depend on
//! h; `depth_scaling = "element"`: g = ĝ h, the IPM limits the penetration to a fixed fraction of
//! an element. `"absolute"` takes the values as they are.

use std::collections::BTreeMap;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use contactlab::field::Field;
use contactlab::material::hyperelastic::LinearElastic1d;
use contactlab::mesh::interval::IntervalMesh;
use contactlab::model::dynamic::audit::AuditSummary;
use contactlab::model::dynamic::bar::{BarBody, BarData, BarSupports, MassMatrix};
use contactlab::model::dynamic::contact_model::NormalTreatment;
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::DynamicStats;

use std::path::Path;

use crate::core::case::Case;
use crate::core::format::{invalid, CaseError};
use crate::core::gate::{Check, GateVerdict, RateGate as CoreRateGate};
use crate::core::report::case_report::Table;
use crate::core::sweep::Against;
use contactlab::model::dynamic::record::Conserving;

use crate::dynamic::study::audit_checks;
use crate::plot::{Figure, Series};

/// The contact treatment of a family (the names of [`NormalTreatment`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TreatmentKind {
    Signorini,
    Penalty,
    EnergyConsistent,
    HauretLeTallecTilted,
    LimitedPenetration,
}

impl TreatmentKind {
    /// Whether the treatment has a penalty stiffness.
    pub fn has_stiffness(self) -> bool {
        self != Self::Signorini
    }

    /// Whether the compliance force's discrete work is exact (midpoint-type schemes only).
    pub fn is_energy_consistent(self) -> bool {
        matches!(
            self,
            Self::EnergyConsistent | Self::HauretLeTallecTilted | Self::LimitedPenetration
        )
    }
}

/// How a stiffness or depth of the case file becomes the solver's value on a mesh of size h.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Scaling {
    /// r = value · E A / h, g = value · h.
    #[default]
    Element,
    /// The value as it is.
    Absolute,
}

/// `[[family]]`: one contact treatment with one scheme and one mass matrix.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FamilySpec {
    pub name: String,
    pub treatment: TreatmentKind,
    pub scheme: DynamicScheme,
    #[serde(default)]
    pub mass: MassMatrix,
    /// r̂ (element scaling) or r (absolute); required for every treatment but Signorini.
    pub stiffness: Option<f64>,
    #[serde(default)]
    pub stiffness_scaling: Scaling,
    /// ĝ or g of `limited_penetration`.
    pub depth: Option<f64>,
    #[serde(default)]
    pub depth_scaling: Scaling,
}

impl FamilySpec {
    /// Checks the combination; `field` names the family in errors.
    pub fn check(&self, field: &str) -> Result<(), (String, String, String)> {
        let bad = |f: &str, v: String, e: &str| Err((format!("{field}.{f}"), v, e.to_string()));
        match (self.treatment.has_stiffness(), self.stiffness) {
            (true, None) => return bad("stiffness", "(missing)".into(), "a stiffness > 0"),
            (false, Some(r)) => {
                return bad("stiffness", r.to_string(), "no stiffness for signorini")
            }
            (true, Some(r)) if !(r.is_finite() && r > 0.0) => {
                return bad("stiffness", r.to_string(), "a finite number > 0")
            }
            _ => {}
        }
        let limited = self.treatment == TreatmentKind::LimitedPenetration;
        match (limited, self.depth) {
            (true, None) => return bad("depth", "(missing)".into(), "a depth > 0"),
            (false, Some(g)) => {
                return bad(
                    "depth",
                    g.to_string(),
                    "a depth only for limited_penetration",
                )
            }
            (true, Some(g)) if !(g.is_finite() && g > 0.0) => {
                return bad("depth", g.to_string(), "a finite number > 0")
            }
            _ => {}
        }
        if self.scheme == DynamicScheme::Newmark && self.treatment.is_energy_consistent() {
            return bad(
                "scheme",
                "newmark".into(),
                "midpoint or gonzalez: the energy-consistent force is defined for the midpoint \
                 relation (BDS (1.31))",
            );
        }
        Ok(())
    }

    /// The solver's treatment on a mesh of size h (bar of modulus E; its section A is the contact
    /// weight, so r is a stiffness per unit area).
    pub fn normal_treatment(&self, h: f64, young: f64) -> NormalTreatment {
        let r = self
            .stiffness
            .map_or(0.0, |r| match self.stiffness_scaling {
                Scaling::Element => r * young / h,
                Scaling::Absolute => r,
            });
        let g = self.depth.map_or(0.0, |g| match self.depth_scaling {
            Scaling::Element => g * h,
            Scaling::Absolute => g,
        });
        match self.treatment {
            TreatmentKind::Signorini => NormalTreatment::Signorini,
            TreatmentKind::Penalty => NormalTreatment::Penalty { stiffness: r },
            TreatmentKind::EnergyConsistent => NormalTreatment::EnergyConsistent { stiffness: r },
            TreatmentKind::HauretLeTallecTilted => {
                NormalTreatment::HauretLeTallecTilted { stiffness: r }
            }
            TreatmentKind::LimitedPenetration => NormalTreatment::LimitedPenetration {
                stiffness: r,
                depth: g,
            },
        }
    }

    /// The identities the audit gates at round-off: the balance (1.48) holds for every linear
    /// run (midpoint type, and Newmark with the trapezoidal mean of the forces); the contact
    /// identities (1.49) and HLT 3.7 only for an energy-consistent force.
    pub fn conserving(&self) -> Conserving {
        Conserving {
            balance: true,
            contact: self.treatment.is_energy_consistent(),
        }
    }

    /// The audit checks of the family: those of [`audit_checks`], without the dissipative sign
    /// of the constraint work for Newmark (the trapezoidal mean of the Signorini multipliers
    /// does work of either sign: its drift is reported, not gated).
    pub fn audit_checks(&self, summary: &AuditSummary) -> Vec<Check> {
        let checks = audit_checks(&self.name, summary, self.conserving());
        if self.scheme == DynamicScheme::Newmark {
            checks
                .into_iter()
                .filter(|c| !c.name.contains("constraint work"))
                .collect()
        } else {
            checks
        }
    }

    /// Why the audit gate of the family checks what it checks.
    pub fn audit_note(&self) -> String {
        use TreatmentKind as T;
        let scheme = if self.scheme == DynamicScheme::Newmark {
            "Newmark: the balance (1.48) with the trapezoidal mean of the forces holds at \
             round-off (linear body); the constraint work of the averaged multipliers has no \
             sign (reported, not gated)"
        } else {
            "midpoint rule, linear body: the balance (1.48) holds at round-off"
        };
        let contact = match self.treatment {
            T::Signorini => {
                "; Signorini: the constraint work D_b ≤ 0 per step (BDS (1.49) with g = 0)"
            }
            T::Penalty => {
                "; penalty r (p_n)_+: its work over a step is not the change of (r/2) p_+², so \
                 (1.49) drifts (reported in the tables, not gated)"
            }
            T::EnergyConsistent | T::HauretLeTallecTilted => {
                "; energy-consistent force: (1.49) and HLT Prop. 3.7 at round-off"
            }
            T::LimitedPenetration => {
                "; IPM: stage (a) energy-consistent — (1.49), HLT 3.7 at round-off; stage (b) \
                 only dissipates (D_b ≤ 0)"
            }
        };
        format!("worst over every run of the family. {scheme}{contact}.")
    }

    /// A one-line description of the family for reports.
    pub fn describe(&self) -> String {
        let mut s = format!(
            "{} / {} / {} mass",
            treatment_name(self.treatment),
            self.scheme.name(),
            mass_name(self.mass)
        );
        if let Some(r) = self.stiffness {
            s += &match self.stiffness_scaling {
                Scaling::Element => format!(", r = {r} E / h"),
                Scaling::Absolute => format!(", r = {r}"),
            };
        }
        if let Some(g) = self.depth {
            s += &match self.depth_scaling {
                Scaling::Element => format!(", g = {g} h"),
                Scaling::Absolute => format!(", g = {g}"),
            };
        }
        s
    }
}

/// The TOML name of a treatment.
pub fn treatment_name(t: TreatmentKind) -> &'static str {
    match t {
        TreatmentKind::Signorini => "signorini",
        TreatmentKind::Penalty => "penalty",
        TreatmentKind::EnergyConsistent => "energy_consistent",
        TreatmentKind::HauretLeTallecTilted => "hauret_le_tallec_tilted",
        TreatmentKind::LimitedPenetration => "limited_penetration",
    }
}

/// The TOML name of a mass matrix.
pub fn mass_name(m: MassMatrix) -> &'static str {
    match m {
        MassMatrix::Consistent => "consistent",
        MassMatrix::Lumped => "lumped",
    }
}

/// The data of a uniform linear elastic bar.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarSetup {
    pub length: f64,
    pub density: f64,
    pub young: f64,
    pub area: f64,
    pub supports: BarSupports,
}

impl BarSetup {
    /// c = √(E/ρ).
    pub fn wave_speed(&self) -> f64 {
        (self.young / self.density).sqrt()
    }

    /// The P1 bar on M equal elements.
    pub fn body(&self, elements: usize, mass: MassMatrix) -> Result<BarBody, String> {
        let mesh = IntervalMesh::uniform(self.length, elements).map_err(|e| e.to_string())?;
        BarBody::new(BarData {
            mesh,
            density: self.density,
            area: self.area,
            law: Arc::new(LinearElastic1d { young: self.young }),
            supports: self.supports,
            mass,
            body_force: Field::Constant(0.0),
        })
        .map_err(|e| e.to_string())
    }
}

/// `[[sweep]]`: levels (M, N) run with each of its families.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    pub name: String,
    /// The families run (default: every family of the case).
    #[serde(default)]
    pub families: Vec<String>,
    /// M per level (or one value for every level).
    pub elements: Vec<usize>,
    /// N per level (or one value for every level); exclusive with `courant`.
    pub steps: Option<Vec<usize>>,
    /// k = courant · h / c for every level (N = T / k, rounded).
    pub courant: Option<f64>,
    /// T of this sweep's runs (default: the case's).
    pub final_time: Option<f64>,
    /// Errors plotted against h for this sweep besides the gated ones (every family of the
    /// sweep).
    #[serde(default)]
    pub plot: Vec<String>,
}

impl SweepSpec {
    /// Checks the levels; `field` names the sweep in errors.
    pub fn check(&self, field: &str) -> Result<(), (String, String, String)> {
        let bad = |f: &str, v: String, e: &str| Err((format!("{field}.{f}"), v, e.to_string()));
        if let Some(t) = self.final_time {
            if !(t.is_finite() && t > 0.0) {
                return bad("final_time", t.to_string(), "a finite T > 0");
            }
        }
        if self.elements.is_empty() || self.elements.contains(&0) {
            return bad(
                "elements",
                format!("{:?}", self.elements),
                "M ≥ 1 per level",
            );
        }
        match (&self.steps, self.courant) {
            (Some(_), Some(_)) | (None, None) => bad(
                "steps",
                "(steps and courant)".into(),
                "exactly one of steps and courant",
            ),
            (Some(s), None) => {
                if s.is_empty() || s.contains(&0) {
                    return bad("steps", format!("{s:?}"), "N ≥ 1 per level");
                }
                let (m, n) = (self.elements.len(), s.len());
                if m != n && m != 1 && n != 1 {
                    return bad(
                        "steps",
                        format!("{n} entries"),
                        &format!("one per level ({m}) or a single entry"),
                    );
                }
                Ok(())
            }
            (None, Some(c)) if !(c.is_finite() && c > 0.0) => {
                bad("courant", c.to_string(), "a finite number > 0")
            }
            _ => Ok(()),
        }
    }

    /// T of the sweep's runs, given the case's T.
    pub fn time(&self, case_final_time: f64) -> f64 {
        self.final_time.unwrap_or(case_final_time)
    }

    /// The (M, N) levels for a bar of length L, wave speed c and final time T.
    pub fn levels(&self, length: f64, wave_speed: f64, final_time: f64) -> Vec<(usize, usize)> {
        let count = self
            .elements
            .len()
            .max(self.steps.as_ref().map_or(1, Vec::len));
        (0..count)
            .map(|i| {
                let m = *self.elements.get(i).unwrap_or(&self.elements[0]);
                let n = match (&self.steps, self.courant) {
                    (Some(s), _) => *s.get(i).unwrap_or(&s[0]),
                    (None, Some(c)) => {
                        let k = c * length / m as f64 / wave_speed;
                        ((final_time / k).round() as usize).max(1)
                    }
                    (None, None) => 1,
                };
                (m, n)
            })
            .collect()
    }

    /// A one-level sweep (M, k = courant · h / c) of every family.
    pub fn single(elements: usize, courant: f64) -> Self {
        Self {
            name: String::new(),
            families: Vec::new(),
            elements: vec![elements],
            steps: None,
            courant: Some(courant),
            final_time: None,
            plot: Vec::new(),
        }
    }

    /// Whether the sweep runs the family.
    pub fn runs(&self, family: &str) -> bool {
        self.families.is_empty() || self.families.iter().any(|f| f == family)
    }
}

/// Checks the names a rate or ceiling gate refers to: a `[[sweep]]`, a `[[family]]` the sweep
/// runs and a measured error; `field` names the gate in errors. The sweep on success.
fn check_gate_names<'a>(
    field: &str,
    (sweep, family, error): (&str, &str, &str),
    sweeps: &'a [SweepSpec],
    families: &[FamilySpec],
    errors: &[&str],
) -> Result<&'a SweepSpec, (String, String, String)> {
    let bad = |f: &str, v: String, e: String| Err((format!("{field}.{f}"), v, e));
    let Some(found) = sweeps.iter().find(|s| s.name == sweep) else {
        return bad("sweep", sweep.into(), "the name of a [[sweep]]".into());
    };
    if !families.iter().any(|f| f.name == family) || !found.runs(family) {
        return bad(
            "family",
            family.into(),
            format!("a [[family]] run by sweep `{}`", found.name),
        );
    }
    if !errors.contains(&error) {
        return bad(
            "error",
            error.into(),
            format!("one of {}", errors.join(", ")),
        );
    }
    Ok(found)
}

/// What a bar `[[gate]]` measures: one error of one family along one sweep, against h or k.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarSelect {
    pub sweep: String,
    pub family: String,
    pub error: String,
    pub against: Against,
}

/// `[[gate]]`: a rate gate of a bar case.
pub type RateGate = CoreRateGate<BarSelect>;

/// Checks a bar rate gate: the names it refers to, its parameter, then the core's criteria.
fn check_rate_gate(
    path: &Path,
    field: &str,
    g: &RateGate,
    sweeps: &[SweepSpec],
    families: &[FamilySpec],
    errors: &[&str],
) -> Result<(), CaseError> {
    let sel = &g.select;
    let names = check_gate_names(
        field,
        (&sel.sweep, &sel.family, &sel.error),
        sweeps,
        families,
        errors,
    );
    if let Err((f, v, e)) = names {
        return Err(invalid(path, &f, v, &e));
    }
    if sel.against == Against::HPlusK {
        return Err(invalid(
            path,
            &format!("{field}.against"),
            "h_plus_k",
            "h or k",
        ));
    }
    g.criteria.check(path, field)
}

/// `[[ceiling]]`: an error of one family on one level (M, N) of a sweep must stay below a value
/// (for quantities that converge without a clean rate, or must vanish to round-off).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CeilingGate {
    pub sweep: String,
    pub family: String,
    pub error: String,
    /// M of the level (default: the finest level of the sweep).
    pub elements: Option<usize>,
    pub ceiling: f64,
    #[serde(default)]
    pub note: String,
}

impl CeilingGate {
    /// Checks the names and the number.
    pub fn check(
        &self,
        field: &str,
        sweeps: &[SweepSpec],
        families: &[FamilySpec],
        errors: &[&str],
    ) -> Result<(), (String, String, String)> {
        let bad = |f: &str, v: String, e: String| Err((format!("{field}.{f}"), v, e));
        let sweep = check_gate_names(
            field,
            (&self.sweep, &self.family, &self.error),
            sweeps,
            families,
            errors,
        )?;
        if let Some(m) = self.elements {
            if !sweep.elements.contains(&m) {
                return bad(
                    "elements",
                    m.to_string(),
                    "the M of a level of the sweep".into(),
                );
            }
        }
        if !(self.ceiling.is_finite() && self.ceiling > 0.0) {
            return bad(
                "ceiling",
                self.ceiling.to_string(),
                "a finite number > 0".into(),
            );
        }
        Ok(())
    }
}

/// The checks common to the case formats: unique family and sweep names, each family, sweep and
/// gate valid.
pub fn check_common(
    case: &Case,
    families: &[FamilySpec],
    sweeps: &[SweepSpec],
    gates: &[RateGate],
    ceilings: &[CeilingGate],
    errors: &[&str],
) -> Result<(), CaseError> {
    let path = case.path.display().to_string();
    let invalid = |(field, value, expected): (String, String, String)| CaseError::Invalid {
        path: path.clone(),
        field,
        value,
        expected,
    };
    if families.is_empty() {
        return Err(invalid((
            "family".into(),
            "(none)".into(),
            "at least one [[family]]".into(),
        )));
    }
    for (i, f) in families.iter().enumerate() {
        f.check(&format!("family[{i}]")).map_err(invalid)?;
        if families[..i].iter().any(|g| g.name == f.name) {
            return Err(invalid((
                format!("family[{i}].name"),
                f.name.clone(),
                "a unique name".into(),
            )));
        }
    }
    for (i, s) in sweeps.iter().enumerate() {
        s.check(&format!("sweep[{i}]")).map_err(invalid)?;
        if let Some(e) = s.plot.iter().find(|e| !errors.contains(&e.as_str())) {
            return Err(invalid((
                format!("sweep[{i}].plot"),
                e.clone(),
                format!("names among {}", errors.join(", ")),
            )));
        }
        if sweeps[..i].iter().any(|g| g.name == s.name) {
            return Err(invalid((
                format!("sweep[{i}].name"),
                s.name.clone(),
                "a unique name".into(),
            )));
        }
        for f in &s.families {
            if !families.iter().any(|g| &g.name == f) {
                return Err(invalid((
                    format!("sweep[{i}].families"),
                    f.clone(),
                    "names of [[family]]s".into(),
                )));
            }
        }
    }
    for (i, g) in gates.iter().enumerate() {
        check_rate_gate(
            case.path(),
            &format!("gate[{i}]"),
            g,
            sweeps,
            families,
            errors,
        )?;
    }
    for (i, g) in ceilings.iter().enumerate() {
        g.check(&format!("ceiling[{i}]"), sweeps, families, errors)
            .map_err(invalid)?;
    }
    Ok(())
}

/// The measured quantities of one run (by error name), its audit summary and statistics.
#[derive(Debug, Clone)]
pub struct LevelOutcome {
    pub elements: usize,
    pub steps: usize,
    pub h: f64,
    pub k: f64,
    pub errors: BTreeMap<String, f64>,
    pub summary: AuditSummary,
    pub stats: DynamicStats,
    /// The time loop's wall time without the observer's (error evaluation) time (s).
    pub solver_seconds: f64,
}

impl LevelOutcome {
    /// The solver's cost per step (µs), the observer excluded.
    pub fn micros_per_step(&self) -> f64 {
        1e6 * self.solver_seconds / self.steps.max(1) as f64
    }
}

/// The runs of one sweep with one family, levels in the case file's order.
#[derive(Debug, Clone)]
pub struct SweepOutcome {
    pub sweep: String,
    pub family: String,
    pub levels: Vec<LevelOutcome>,
}

/// One run of a case: a level of a sweep with a family, or the shown level of a family
/// (`sweep = None`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Job {
    pub sweep: Option<usize>,
    pub family: usize,
    pub elements: usize,
    pub steps: usize,
    pub final_time: f64,
}

impl Job {
    /// The runs of a case in a fixed order (sweeps in file order, family-major, levels in file
    /// order; then the shown level of every family `shows` accepts), so that the results, collected
    /// in this order, do not depend on the thread count.
    pub fn list(
        sweeps: &[SweepSpec],
        families: &[FamilySpec],
        bar: &BarSetup,
        final_time: f64,
        show: (usize, f64),
        shows: impl Fn(&str) -> bool,
    ) -> Vec<Job> {
        let mut jobs = Vec::new();
        for (s, sweep) in sweeps.iter().enumerate() {
            let t = sweep.time(final_time);
            for (f, family) in families.iter().enumerate() {
                if !sweep.runs(&family.name) {
                    continue;
                }
                for (elements, steps) in sweep.levels(bar.length, bar.wave_speed(), t) {
                    jobs.push(Job {
                        sweep: Some(s),
                        family: f,
                        elements,
                        steps,
                        final_time: t,
                    });
                }
            }
        }
        let (elements, steps) =
            SweepSpec::single(show.0, show.1).levels(bar.length, bar.wave_speed(), final_time)[0];
        for (f, family) in families.iter().enumerate() {
            if shows(&family.name) {
                jobs.push(Job {
                    sweep: None,
                    family: f,
                    elements,
                    steps,
                    final_time,
                });
            }
        }
        jobs
    }
}

/// Groups the sweep runs' outcomes (aligned with `jobs`; shown runs are skipped) by (sweep,
/// family), levels in job order.
pub fn group_outcomes(
    jobs: &[Job],
    levels: Vec<LevelOutcome>,
    sweeps: &[SweepSpec],
    families: &[FamilySpec],
) -> Vec<SweepOutcome> {
    let mut outcomes: Vec<SweepOutcome> = Vec::new();
    for (job, level) in jobs.iter().zip(levels) {
        let Some(s) = job.sweep else { continue };
        let (sweep, family) = (&sweeps[s].name, &families[job.family].name);
        match outcomes
            .iter_mut()
            .find(|o| &o.sweep == sweep && &o.family == family)
        {
            Some(o) => o.levels.push(level),
            None => outcomes.push(SweepOutcome {
                sweep: sweep.clone(),
                family: family.clone(),
                levels: vec![level],
            }),
        }
    }
    outcomes
}

/// The gate name of a rate gate.
fn gate_name(g: &RateGate) -> String {
    let s = &g.select;
    format!(
        "{}/{}: {} vs {}",
        s.sweep,
        s.family,
        s.error,
        s.against.label()
    )
}

/// Evaluates the rate gates on the outcomes.
pub fn rate_gates(gates: &[RateGate], outcomes: &[SweepOutcome]) -> Vec<GateVerdict> {
    gates
        .iter()
        .map(|g| {
            let Some(o) = outcomes
                .iter()
                .find(|o| o.sweep == g.select.sweep && o.family == g.select.family)
            else {
                return GateVerdict::from_checks(
                    gate_name(g),
                    "rate",
                    vec![Check::holds(
                        "runs of the sweep and family",
                        false,
                        "present",
                    )],
                    &g.criteria.note,
                );
            };
            let param: Vec<f64> = o
                .levels
                .iter()
                .map(|l| {
                    if g.select.against == Against::K {
                        l.k
                    } else {
                        l.h
                    }
                })
                .collect();
            let error: Vec<f64> = o
                .levels
                .iter()
                .map(|l| l.errors.get(&g.select.error).copied().unwrap_or(f64::NAN))
                .collect();
            g.criteria.evaluate(gate_name(g), &param, &error)
        })
        .collect()
}

/// Evaluates the ceiling gates on the outcomes.
pub fn ceiling_gates(ceilings: &[CeilingGate], outcomes: &[SweepOutcome]) -> Vec<GateVerdict> {
    ceilings
        .iter()
        .map(|c| {
            let level = outcomes
                .iter()
                .find(|o| o.sweep == c.sweep && o.family == c.family)
                .and_then(|o| match c.elements {
                    Some(m) => o.levels.iter().find(|l| l.elements == m),
                    None => o.levels.iter().min_by(|a, b| a.h.total_cmp(&b.h)),
                });
            let (name, observed) = match level {
                Some(l) => (
                    format!("{} at M = {}, N = {}", c.error, l.elements, l.steps),
                    l.errors.get(&c.error).copied().unwrap_or(f64::NAN),
                ),
                None => (format!("{} (no such run)", c.error), f64::NAN),
            };
            let mut check = Check::at_most(&name, observed, c.ceiling);
            check.passed &= observed.is_finite();
            GateVerdict::from_checks(
                format!("{}/{}: {} ceiling", c.sweep, c.family, c.error),
                "ceiling",
                vec![check],
                &c.note,
            )
        })
        .collect()
}

/// The audit gate of each family over every run of every sweep: the worst residuals and step
/// works of its runs (each relative to its own run's energy scale).
pub fn worst_summary(outcomes: &[SweepOutcome], family: &str) -> Option<AuditSummary> {
    let mut worst: Option<AuditSummary> = None;
    for l in outcomes
        .iter()
        .filter(|o| o.family == family)
        .flat_map(|o| &o.levels)
    {
        let s = l.summary;
        worst = Some(match worst {
            None => s,
            Some(w) => AuditSummary {
                energy_scale: w.energy_scale.min(s.energy_scale),
                max_residual_1_48: w.max_residual_1_48.max(s.max_residual_1_48),
                max_residual_1_49: w.max_residual_1_49.max(s.max_residual_1_49),
                max_residual_3_7: w.max_residual_3_7.max(s.max_residual_3_7),
                max_step_friction_work: w.max_step_friction_work.max(s.max_step_friction_work),
                max_step_constraint_work: w
                    .max_step_constraint_work
                    .max(s.max_step_constraint_work),
                drift_1_49: if s.drift_1_49.abs() > w.drift_1_49.abs() {
                    s.drift_1_49
                } else {
                    w.drift_1_49
                },
                steps: w.steps.max(s.steps),
            },
        });
    }
    worst
}

/// One log–log figure per (sweep, gated or `plot`-listed error, parameter): every family the
/// sweep runs (the gated ones with markers, the others dashed, for comparison), with the gates'
/// expected slopes.
pub fn convergence_figures(
    case_id: &str,
    sweeps: &[SweepSpec],
    gates: &[RateGate],
    outcomes: &[SweepOutcome],
) -> Vec<(String, Figure)> {
    let mut keys: Vec<(String, String, Against)> = Vec::new();
    let listed = sweeps.iter().flat_map(|s| {
        s.plot
            .iter()
            .map(|e| (s.name.clone(), e.clone(), Against::H))
    });
    let gated = gates.iter().map(|g| {
        (
            g.select.sweep.clone(),
            g.select.error.clone(),
            g.select.against,
        )
    });
    for key in gated.chain(listed) {
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys.into_iter()
        .map(|(sweep, error, against)| {
            let mut fig = Figure::new(format!(
                "{case_id}: sweep `{sweep}`, {error} against {}",
                against.label()
            ))
            .x_label(against.label())
            .y_label(error.as_str())
            .log_log();
            let gated: Vec<&RateGate> = gates
                .iter()
                .filter(|g| {
                    let s = &g.select;
                    s.sweep == sweep && s.error == error && s.against == against
                })
                .collect();
            for (i, o) in outcomes.iter().filter(|o| o.sweep == sweep).enumerate() {
                let pts: Vec<(f64, f64)> = o
                    .levels
                    .iter()
                    .filter_map(|l| {
                        let p = if against == Against::K { l.k } else { l.h };
                        l.errors.get(&error).map(|e| (p, *e))
                    })
                    .collect();
                let series = if gated.iter().any(|g| g.select.family == o.family) {
                    Series::line_markers(format!("{} (gated)", o.family), pts)
                } else {
                    Series::line(o.family.clone(), pts).dashed()
                };
                fig = fig.series(series.color(i));
            }
            let mut slopes: Vec<f64> = Vec::new();
            for g in &gated {
                let rate = g.criteria.expected_rate;
                if !slopes.iter().any(|s| (s - rate).abs() < 1e-12) {
                    slopes.push(rate);
                }
            }
            for s in slopes {
                fig = fig.reference_slope(s, format!("slope {s:.3}"));
            }
            let suffix = if against == Against::K { "k" } else { "h" };
            (format!("convergence_{sweep}_{error}_{suffix}"), fig)
        })
        .collect()
}

/// The table of every run's measured quantities, one row per (sweep, family, level).
pub fn errors_table(title: &str, names: &[&str], outcomes: &[SweepOutcome]) -> Table {
    let mut header: Vec<String> = ["sweep", "family", "M", "N", "h", "k"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    header.extend(names.iter().map(|s| s.to_string()));
    header.extend(
        [
            "max |r(1.48)|/E_ref",
            "max |r(1.49)|/E_ref",
            "drift (1.49)",
            "Newton it./step",
        ]
        .iter()
        .map(|s| s.to_string()),
    );
    let rows = outcomes
        .iter()
        .flat_map(|o| {
            o.levels.iter().map(move |l| {
                let mut row = vec![
                    o.sweep.clone(),
                    o.family.clone(),
                    l.elements.to_string(),
                    l.steps.to_string(),
                    format!("{:.4e}", l.h),
                    format!("{:.4e}", l.k),
                ];
                row.extend(names.iter().map(|n| {
                    l.errors
                        .get(*n)
                        .map_or("–".to_string(), |v| format!("{v:.4e}"))
                }));
                row.push(format!("{:.2e}", l.summary.max_residual_1_48));
                row.push(format!("{:.2e}", l.summary.max_residual_1_49));
                row.push(format!("{:.2e}", l.summary.drift_1_49));
                row.push(format!(
                    "{:.3}",
                    l.stats.newton_iterations as f64 / l.steps as f64
                ));
                row
            })
        })
        .collect();
    Table {
        title: title.to_string(),
        header,
        rows,
    }
}

/// Per family: the cost per step and the Newton iterations per step (mean over all its runs,
/// max over all steps), and the audit's worst residuals and drift.
pub fn cost_and_audit_table(families: &[FamilySpec], outcomes: &[SweepOutcome]) -> Table {
    let rows = families
        .iter()
        .filter_map(|f| {
            let levels: Vec<&LevelOutcome> = outcomes
                .iter()
                .filter(|o| o.family == f.name)
                .flat_map(|o| &o.levels)
                .collect();
            let finest = levels
                .iter()
                .min_by(|a, b| a.h.total_cmp(&b.h).then(a.k.total_cmp(&b.k)))?;
            let steps: usize = levels.iter().map(|l| l.steps).sum();
            let iterations: usize = levels.iter().map(|l| l.stats.newton_iterations).sum();
            let max_it = levels
                .iter()
                .map(|l| l.stats.max_newton_iterations)
                .max()
                .unwrap_or(0);
            let w = worst_summary(outcomes, &f.name)?;
            Some(vec![
                f.name.clone(),
                f.describe(),
                levels.len().to_string(),
                format!(
                    "{:.2} (M = {}, N = {})",
                    finest.micros_per_step(),
                    finest.elements,
                    finest.steps
                ),
                format!(
                    "{} ({} unknowns)",
                    finest.stats.factor_nnz, finest.stats.unknowns
                ),
                format!("{:.3}", iterations as f64 / steps as f64),
                max_it.to_string(),
                format!("{:.1e}", w.max_residual_1_48),
                format!("{:.1e}", w.max_residual_1_49),
                format!("{:.1e}", w.drift_1_49),
                format!("{:.1e}", w.max_step_constraint_work),
            ])
        })
        .collect();
    Table {
        title: "per family: solver cost per step (µs, the finest run, error evaluation excluded; \
                a shared machine: indicative), Newton iterations per step (mean over all runs, max \
                over all steps), worst audit over all runs"
            .into(),
        header: [
            "family",
            "treatment / scheme / mass",
            "runs",
            "µs per step",
            "factor nnz (finest)",
            "Newton it./step (mean)",
            "max it./step",
            "max |r(1.48)|/E_ref",
            "max |r(1.49)|/E_ref",
            "largest drift of (1.49)",
            "max step constraint work",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    }
}
