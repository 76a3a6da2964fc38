//! The case format of `dynamic_manufactured` and its checks: the law, the mass matrix, the
//! time and space studies (scheme × contact force), and the rate gates on their series.

use crate::stats::levels::MIN_LEVELS;
use std::path::Path;

use serde::{Deserialize, Serialize};

use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::contact_model::NormalTreatment;
use contactlab::model::dynamic::scheme::DynamicScheme;

use crate::core::format::CaseError;
use contactlab::model::dynamic::record::Conserving;

use crate::core::format::{at_least, invalid};
use crate::core::gate::RateGate;
use crate::manufactured::dynamic_plane::ManufacturedLaw;

/// The contact force of a run (the compliance r of the solution).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactForce {
    /// r (p_n)_+ at t_n (BDS (1.8)).
    Penalty,
    /// r [(p_n)_+² − (p_{n−1})_+²] / (2 (p_n − p_{n−1})) (BDS (1.46), HLT (3.68)).
    EnergyConsistent,
}

impl ContactForce {
    pub(crate) fn name(self) -> &'static str {
        match self {
            Self::Penalty => "penalty",
            Self::EnergyConsistent => "energy_consistent",
        }
    }

    pub(crate) fn treatment(self, stiffness: f64) -> NormalTreatment {
        match self {
            Self::Penalty => NormalTreatment::Penalty { stiffness },
            Self::EnergyConsistent => NormalTreatment::EnergyConsistent { stiffness },
        }
    }
}

/// A scheme with a contact force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Combination {
    pub scheme: DynamicScheme,
    pub treatment: ContactForce,
    /// The full semismooth Newton path even for the linear law (the scene's `solver.path =
    /// "full"`): no condensation onto the contact dofs, Newton on every dof with the assembled
    /// operator.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub full_path: bool,
}

impl Combination {
    pub(crate) fn label(&self) -> String {
        let path = if self.full_path { " (full path)" } else { "" };
        format!("{} + {}{path}", self.scheme.name(), self.treatment.name())
    }

    /// The identities this combination satisfies at round-off (see the module docs).
    pub(crate) fn conserving(&self, law: ManufacturedLaw) -> Conserving {
        let conserving_scheme = self.scheme == DynamicScheme::Gonzalez
            || (self.scheme == DynamicScheme::Midpoint && law == ManufacturedLaw::Linear);
        Conserving {
            balance: conserving_scheme,
            contact: self.treatment == ContactForce::EnergyConsistent,
            compliance: true,
        }
    }
}

/// `[time_study]`: runs on the affine field of
/// [`crate::manufactured::dynamic_plane::ManufacturedField::Affine`], whose nodal interpolant
/// solves the semi-discrete equations exactly (consistent mass): the error against u(T) is the
/// time error alone, measured against the exact solution, not against another run.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TimeStudy {
    /// The mesh: n × n squares.
    pub divisions: usize,
    pub steps: Vec<usize>,
    pub runs: Vec<Combination>,
}

/// `[space_study]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpaceStudy {
    pub divisions: Vec<usize>,
    /// N = steps_per_division · n (k ∝ h).
    pub steps_per_division: usize,
    pub scheme: DynamicScheme,
    pub treatment: ContactForce,
}

/// Which study a gate reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Study {
    Time,
    Space,
}

/// The error a gate fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorName {
    /// ‖u_N − u(T)‖_{L²} (time: on the affine field, the time error alone).
    L2,
    /// space: ‖ε(u_N − u(T))‖_{L²}.
    Energy,
}

/// What a `[[gate]]` measures: one error of one study (and, in time, one run).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeriesSelect {
    pub study: Study,
    /// The run of the time study (required there).
    pub scheme: Option<DynamicScheme>,
    pub treatment: Option<ContactForce>,
    /// The run on the full path (see [`Combination::full_path`]).
    #[serde(default)]
    pub full_path: bool,
    pub error: ErrorName,
}

/// `[[gate]]`: a rate gate on one series.
pub type ManufacturedGate = RateGate<SeriesSelect>;

/// The case format of `dynamic_manufactured`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManufacturedCase {
    pub law: ManufacturedLaw,
    #[serde(default)]
    pub mass: MassMatrix,
    pub time_study: Option<TimeStudy>,
    pub space_study: Option<SpaceStudy>,
    #[serde(default)]
    pub gate: Vec<ManufacturedGate>,
}

pub(crate) fn check_combination(p: &Path, field: &str, c: &Combination) -> Result<(), CaseError> {
    if c.scheme == DynamicScheme::Newmark && c.treatment == ContactForce::EnergyConsistent {
        return Err(invalid(
            p,
            field,
            c.label(),
            "a midpoint-type scheme for the energy-consistent force (the solver rejects newmark)",
        ));
    }
    Ok(())
}

impl ManufacturedCase {
    /// Checks the numbers and the references between gates and studies.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        if self.time_study.is_none() && self.space_study.is_none() {
            return Err(invalid(
                p,
                "time_study",
                "(missing)",
                "a [time_study] or a [space_study]",
            ));
        }
        if let Some(t) = &self.time_study {
            at_least(p, "time_study.steps", &t.steps, 2)?;
            at_least(p, "time_study.runs", &t.runs, 1)?;
            if t.divisions == 0 {
                return Err(invalid(p, "time_study.divisions", 0, "at least 1"));
            }
            if self.mass != MassMatrix::Consistent {
                return Err(invalid(
                    p,
                    "mass",
                    "lumped",
                    "the consistent mass with a [time_study] (with a lumped mass the affine \
                     field is no longer the semi-discrete solution, and the time error would \
                     not be separated from the space error)",
                ));
            }
            for (i, c) in t.runs.iter().enumerate() {
                check_combination(p, &format!("time_study.runs[{i}]"), c)?;
            }
        }
        if let Some(s) = &self.space_study {
            at_least(p, "space_study.divisions", &s.divisions, 2)?;
            if s.steps_per_division == 0 || s.divisions.contains(&0) {
                return Err(invalid(
                    p,
                    "space_study.steps_per_division",
                    s.steps_per_division,
                    "≥ 1, with divisions ≥ 1",
                ));
            }
            check_combination(
                p,
                "space_study",
                &Combination {
                    scheme: s.scheme,
                    treatment: s.treatment,
                    full_path: false,
                },
            )?;
        }
        for (i, g) in self.gate.iter().enumerate() {
            self.check_gate(p, i, g)?;
        }
        Ok(())
    }

    pub(crate) fn check_gate(
        &self,
        p: &Path,
        i: usize,
        gate: &ManufacturedGate,
    ) -> Result<(), CaseError> {
        let field = format!("gate[{i}]");
        gate.criteria.check(p, &field)?;
        let g = &gate.select;
        let levels = match g.study {
            Study::Time => {
                let t = self.time_study.as_ref().ok_or_else(|| {
                    invalid(p, &format!("{field}.study"), "time", "a [time_study]")
                })?;
                let c = match (g.scheme, g.treatment) {
                    (Some(scheme), Some(treatment)) => Combination {
                        scheme,
                        treatment,
                        full_path: g.full_path,
                    },
                    _ => {
                        return Err(invalid(
                            p,
                            &format!("{field}.scheme"),
                            "(missing)",
                            "scheme and treatment of a time_study run",
                        ))
                    }
                };
                if !t.runs.contains(&c) {
                    return Err(invalid(
                        p,
                        &format!("{field}.scheme"),
                        c.label(),
                        "a run of [time_study]",
                    ));
                }
                if g.error != ErrorName::L2 {
                    return Err(invalid(
                        p,
                        &format!("{field}.error"),
                        "energy",
                        "l2 (the time error ‖u_N − u_N^ref‖_L²)",
                    ));
                }
                t.steps.len()
            }
            Study::Space => {
                let s = self.space_study.as_ref().ok_or_else(|| {
                    invalid(p, &format!("{field}.study"), "space", "a [space_study]")
                })?;
                if g.scheme.is_some() || g.treatment.is_some() {
                    return Err(invalid(
                        p,
                        &format!("{field}.scheme"),
                        "(given)",
                        "no scheme or treatment (the space study has one)",
                    ));
                }
                s.divisions.len()
            }
        };
        if levels < MIN_LEVELS {
            return Err(invalid(
                p,
                &format!("{field}.study"),
                levels,
                &format!("a study of at least {MIN_LEVELS} levels (the rate fit needs them)"),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! The format: unknown keys, newmark with the energy-consistent force, and gates naming runs
    //! the case does not have are errors; a coarse run of the linear solution conserves energy to
    //! round-off and stays in persistent contact.
    use super::*;
    use crate::core::case::Case;
    use crate::dynamic::cases::manufactured::runs::solve;
    use crate::manufactured::dynamic_plane::DynamicManufactured;
    use std::path::PathBuf;

    const CASE: &str = r#"
id = "t"
title = "t"
kind = "dynamic_manufactured"
explanation = "x"
law = "linear"
[time_study]
divisions = 4
steps = [4, 8, 16]
runs = [{ scheme = "midpoint", treatment = "energy_consistent" }]
[[gate]]
study = "time"
scheme = "midpoint"
treatment = "energy_consistent"
error = "l2"
expected_rate = 2.0
tolerance = 0.1
ci_width = 1.0
"#;

    fn load(text: &str) -> Result<ManufacturedCase, CaseError> {
        let path = PathBuf::from("t.toml");
        let case = Case::from_text(Path::new("t"), text)?;
        let c: ManufacturedCase = case.body()?;
        c.check(&path)?;
        Ok(c)
    }

    #[test]
    fn valid_case_parses() {
        load(CASE).unwrap();
    }

    #[test]
    fn unknown_key_is_an_error() {
        assert!(load(&CASE.replace("law = \"linear\"", "law = \"linear\"\nfoo = 1")).is_err());
    }

    #[test]
    fn newmark_with_energy_consistent_force_is_an_error() {
        let text = CASE.replace(
            "runs = [{ scheme = \"midpoint\"",
            "runs = [{ scheme = \"newmark\"",
        );
        let err = load(&text).unwrap_err().to_string();
        assert!(err.contains("time_study.runs[0]"), "{err}");
    }

    #[test]
    fn gate_on_a_missing_run_is_an_error() {
        let text = CASE.replace(
            "scheme = \"midpoint\"\ntreatment",
            "scheme = \"gonzalez\"\ntreatment",
        );
        assert!(load(&text).is_err());
    }

    #[test]
    fn coarse_linear_run_conserves_and_stays_in_contact() {
        let m = DynamicManufactured::standard(ManufacturedLaw::Linear);
        let c = Combination {
            scheme: DynamicScheme::Midpoint,
            treatment: ContactForce::EnergyConsistent,
            full_path: false,
        };
        let r = solve(&m, MassMatrix::Consistent, 4, 16, c).unwrap();
        let s = r.audit.summary();
        assert!(
            s.max_drift_1_48 <= s.tolerance() && s.max_drift_1_49 <= s.tolerance(),
            "{s:?}"
        );
        assert!(r.min_penetration > 0.0);
        assert!(r.errors.l2 < 0.05, "{:?}", r.errors);
    }
}
