//! The case format of `dynamic_impact` and its checks: the runs (scheme × treatment), the
//! self-convergence studies and their gates, and the scene every run varies.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::scene::dynamic::{DynamicScene, DynamicSceneFile};

use crate::core::format::CaseError;

use super::runs::{Job, RunSummary, SceneSource, Treatment};
use crate::core::format::{at_least, invalid, positive};

/// `[[run]]`: a scheme and a contact treatment on the scene (its resolution, or `steps`).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ImpactRun {
    pub label: Option<String>,
    pub scheme: DynamicScheme,
    pub treatment: Treatment,
    /// Steps instead of the scene's (a larger step for a scheme comparison).
    pub steps: Option<usize>,
    /// The run may stop with a typed error (shown, and not a failure of the case).
    #[serde(default)]
    pub allow_failure: bool,
}

impl ImpactRun {
    pub(crate) fn label(&self) -> String {
        self.label.clone().unwrap_or_else(|| {
            let base = format!("{} + {}", self.scheme.name(), self.treatment.name());
            match self.steps {
                Some(n) => format!("{base} (N = {n})"),
                None => base,
            }
        })
    }
}

/// A quantity of the self-convergence study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Centre-of-mass velocity at T (after separation), x and y.
    ReboundVelocityX,
    ReboundVelocityY,
    /// t_end − t_start of the contact interval.
    ContactDuration,
    /// max over steps and nodes of p_i.
    MaxPenetration,
    /// −((E + Φ)_N − (E + Φ)_0)/(E + Φ)_0: friction and stage-(b) losses.
    EnergyLoss,
}

impl Quantity {
    pub(crate) const ALL: [Quantity; 5] = [
        Self::ReboundVelocityX,
        Self::ReboundVelocityY,
        Self::ContactDuration,
        Self::MaxPenetration,
        Self::EnergyLoss,
    ];

    pub(crate) fn name(self) -> &'static str {
        match self {
            Self::ReboundVelocityX => "rebound v_x (m/s)",
            Self::ReboundVelocityY => "rebound v_y (m/s)",
            Self::ContactDuration => "contact duration (s)",
            Self::MaxPenetration => "max penetration (m)",
            Self::EnergyLoss => "energy loss / E_0",
        }
    }

    pub(crate) fn of(self, s: &RunSummary) -> Option<f64> {
        match self {
            Self::ReboundVelocityX => s.contact.map(|_| s.final_velocity[0]),
            Self::ReboundVelocityY => s.contact.map(|_| s.final_velocity[1]),
            Self::ContactDuration => s.contact_duration,
            Self::MaxPenetration => Some(s.max_penetration),
            Self::EnergyLoss => Some(-s.energy_change),
        }
    }
}

/// `[[gci.gate]]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GciGate {
    pub quantity: Quantity,
    /// The order the quantity should show (the fallback of an unverified observed order).
    pub formal_order: f64,
    /// GCI of the finest pair, in per cent.
    pub max_percent: f64,
    /// |A − 1| (needs four levels or more).
    pub asymptotic_tolerance: Option<f64>,
    #[serde(default)]
    pub note: String,
}

/// `[[gci]]`: a self-convergence study of one run's scheme and treatment.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GciStudy {
    /// The label of a `[[run]]` (its scheme and treatment; the scene's steps).
    pub run: String,
    /// Multiples of the scene's resolution (mesh divisions and steps together), ascending with a
    /// constant ratio.
    pub refinements: Vec<f64>,
    #[serde(default)]
    pub gate: Vec<GciGate>,
}

/// The case format of `dynamic_impact`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ImpactCase {
    /// The scene (`model = "dynamic"`), relative to the case file.
    pub scene: String,
    /// The report's resolution as a multiple of the scene's (mesh divisions and steps; default 1).
    pub resolution: Option<f64>,
    /// Times of the deformed snapshots of the first run.
    #[serde(default)]
    pub snapshot_times: Vec<f64>,
    /// Largest relative change of the centre-of-mass velocity in flight.
    pub momentum_tolerance: f64,
    /// Largest relative energy loss of a frictionless limited-penetration run.
    pub max_stage_b_loss: Option<f64>,
    #[serde(rename = "run")]
    pub runs: Vec<ImpactRun>,
    #[serde(default)]
    pub gci: Vec<GciStudy>,
}

/// The scene file named by a case.
pub(crate) fn scene_file(case_path: &Path, scene: &str) -> Result<(PathBuf, SceneSource), String> {
    let path = case_path
        .parent()
        .unwrap_or_else(|| Path::new("."))
        .join(scene);
    let text =
        std::fs::read_to_string(&path).map_err(|e| format!("scene {}: {e}", path.display()))?;
    let table: toml::Table = text
        .parse()
        .map_err(|e| format!("scene {}: {e}", path.display()))?;
    let file: DynamicSceneFile = table
        .clone()
        .try_into()
        .map_err(|e| format!("scene {}: {e}", path.display()))?;
    Ok((path, SceneSource { table, file }))
}

/// The ratio of consecutive refinements, if constant.
pub(crate) fn refinement_ratio(r: &[f64]) -> Option<f64> {
    let q = r.get(1)? / r.first()?;
    let constant = r.windows(2).all(|w| ((w[1] / w[0]) / q - 1.0).abs() < 1e-9);
    (constant && q > 1.0).then_some(q)
}

impl ImpactCase {
    /// The runs' jobs at the report's resolution.
    pub(crate) fn job(&self, run: &ImpactRun, snapshots: bool) -> Job {
        Job {
            scheme: run.scheme,
            treatment: run.treatment,
            factor: self.resolution.unwrap_or(1.0),
            steps: run.steps,
            snapshots,
        }
    }

    pub(crate) fn run_by_label(&self, label: &str) -> Option<&ImpactRun> {
        self.runs.iter().find(|r| r.label() == label)
    }

    /// Checks the case, its scene and every run and level it asks for.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        let bad = |field: &str, value: &str, expected: &str| invalid(p, field, value, expected);
        positive(p, "momentum_tolerance", self.momentum_tolerance)?;
        if let Some(r) = self.resolution {
            positive(p, "resolution", r)?;
        }
        if let Some(b) = self.max_stage_b_loss {
            positive(p, "max_stage_b_loss", b)?;
        }
        at_least(p, "run", &self.runs, 1)?;
        let (path, source) =
            scene_file(p, &self.scene).map_err(|e| bad("scene", &self.scene, &e))?;
        let file = &source.file;
        if !file.dirichlet.is_empty() {
            return Err(bad(
                "scene",
                &path.display().to_string(),
                "a free body (no [[dirichlet]]): momentum and rebound velocity need one",
            ));
        }
        for (i, t) in self.snapshot_times.iter().enumerate() {
            if !(t.is_finite() && *t >= 0.0 && *t <= file.time.final_time) {
                return Err(invalid(
                    p,
                    &format!("snapshot_times[{i}]"),
                    t,
                    "a time in [0, the scene's final_time]",
                ));
            }
        }
        for (i, r) in self.runs.iter().enumerate() {
            if self.runs[..i].iter().any(|q| q.label() == r.label()) {
                return Err(bad(
                    &format!("run[{i}].label"),
                    &r.label(),
                    "a label no other run has",
                ));
            }
            let f = source
                .variant(&self.job(r, false), &[])
                .map_err(|e| bad(&format!("run[{i}]"), &r.label(), &e))?;
            DynamicScene::from_file(f)
                .map_err(|e| bad(&format!("run[{i}]"), &r.label(), &e.to_string()))?;
        }
        for (i, g) in self.gci.iter().enumerate() {
            self.check_gci(p, i, g, &source)?;
        }
        Ok(())
    }

    pub(crate) fn check_gci(
        &self,
        p: &Path,
        i: usize,
        g: &GciStudy,
        source: &SceneSource,
    ) -> Result<(), CaseError> {
        let field = format!("gci[{i}]");
        let run = self
            .run_by_label(&g.run)
            .ok_or_else(|| invalid(p, &format!("{field}.run"), &g.run, "the label of a [[run]]"))?;
        if run.steps.is_some() {
            return Err(invalid(
                p,
                &format!("{field}.run"),
                &g.run,
                "a run at the scene's steps (the levels refine the scene)",
            ));
        }
        at_least(p, &format!("{field}.refinements"), &g.refinements, 3)?;
        if refinement_ratio(&g.refinements).is_none() {
            return Err(invalid(
                p,
                &format!("{field}.refinements"),
                format!("{:?}", g.refinements),
                "ascending multiples with a constant ratio > 1",
            ));
        }
        for &f in &g.refinements {
            let job = Job {
                factor: f,
                ..self.job(run, false)
            };
            source
                .variant(&job, &[])
                .map_err(|e| invalid(p, &format!("{field}.refinements"), f, &e))?;
        }
        for (j, gate) in g.gate.iter().enumerate() {
            positive(
                p,
                &format!("{field}.gate[{j}].max_percent"),
                gate.max_percent,
            )?;
            positive(
                p,
                &format!("{field}.gate[{j}].formal_order"),
                gate.formal_order,
            )?;
            if let Some(t) = gate.asymptotic_tolerance {
                positive(p, &format!("{field}.gate[{j}].asymptotic_tolerance"), t)?;
                if g.refinements.len() < 4 {
                    return Err(invalid(
                        p,
                        &format!("{field}.gate[{j}].asymptotic_tolerance"),
                        t,
                        "four refinements or more (with three, the ratio is f1/f2 by construction)",
                    ));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! The format: unknown keys, labels that do not exist, refinements without a constant ratio
    //! or not giving whole meshes, and asymptotic checks on three levels are errors.
    use super::*;
    use crate::core::case::Case;

    const CASE: &str = r#"
id = "t"
title = "t"
kind = "dynamic_impact"
explanation = "x"
scene = "../../examples/scenes/dynamic_ball_impact.toml"
momentum_tolerance = 1e-12
[[run]]
scheme = "gonzalez"
treatment = "limited_penetration"
[[gci]]
run = "gonzalez + limited_penetration"
refinements = [0.5, 1.0, 2.0, 4.0]
[[gci.gate]]
quantity = "rebound_velocity_y"
formal_order = 1.0
max_percent = 1.0
asymptotic_tolerance = 0.1
"#;

    fn load(text: &str) -> Result<ImpactCase, CaseError> {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/t.toml");
        let case = Case::from_text(Path::new("t"), text)?;
        let c: ImpactCase = case.body()?;
        c.check(&path)?;
        Ok(c)
    }

    #[test]
    fn valid_case_parses() {
        load(CASE).unwrap();
    }

    #[test]
    fn unknown_key_is_an_error() {
        assert!(
            load(&CASE.replace("explanation = \"x\"", "explanation = \"x\"\nfoo = 1")).is_err()
        );
    }

    #[test]
    fn gci_of_an_unknown_run_is_an_error() {
        let err = load(&CASE.replace("run = \"gonzalez", "run = \"midpoint")).unwrap_err();
        assert!(err.to_string().contains("gci[0].run"), "{err}");
    }

    #[test]
    fn refinements_must_have_a_constant_ratio_and_whole_meshes() {
        assert!(load(&CASE.replace("[0.5, 1.0, 2.0, 4.0]", "[0.5, 1.0, 3.0, 4.0]")).is_err());
        assert!(load(&CASE.replace("[0.5, 1.0, 2.0, 4.0]", "[0.1, 0.2, 0.4, 0.8]")).is_err());
    }

    #[test]
    fn asymptotic_check_needs_four_levels() {
        let err = load(&CASE.replace("[0.5, 1.0, 2.0, 4.0]", "[1.0, 2.0, 4.0]")).unwrap_err();
        assert!(err.to_string().contains("asymptotic_tolerance"), "{err}");
    }

    #[test]
    fn newmark_with_limited_penetration_is_an_error() {
        let text = CASE.replace("scheme = \"gonzalez\"", "scheme = \"newmark\"");
        let err = load(&text).unwrap_err();
        assert!(err.to_string().contains("run[0]"), "{err}");
    }
}
