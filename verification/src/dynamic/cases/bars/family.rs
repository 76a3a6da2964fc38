//! The run families of the 1D kinds: a contact treatment with a scheme and a mass matrix, the
//! penalty stiffness and the IPM depth scaled with the mesh, and the bar they run on.
//!
//! Scaling with the mesh (`stiffness_scaling = "element"`, the default): r = r̂ E / h. The bar's
//! end carries the contact weight A (its section), so the contact force is A r p and the penalty
//! spring A r = r̂ E A / h is r̂ times as stiff as one element; the penetration p ≈ σ / r =
//! σ h / (r̂ E) is O(h) like the discretization error and the step operator's conditioning does not
//! depend on h; `depth_scaling = "element"`: g = ĝ h, the IPM limits the penetration to a fixed
//! fraction of an element. `"absolute"` takes the values as they are.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use contactlab::field::Field;
use contactlab::material::hyperelastic::{Hyperelastic1d, LinearElastic1d, StVenantKirchhoff1d};
use contactlab::mesh::interval::IntervalMesh;
use contactlab::model::dynamic::audit::AuditSummary;
use contactlab::model::dynamic::bar::{BarBody, BarData, BarSupports, MassMatrix};
use contactlab::model::dynamic::contact_model::NormalTreatment;
use contactlab::model::dynamic::scheme::DynamicScheme;

use crate::core::gate::Check;
use contactlab::model::dynamic::record::Conserving;

use crate::dynamic::study::audit_checks;

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
    /// The bar's law (default linear; the closed forms of the 1D kinds are the linear law's).
    #[serde(default, skip_serializing_if = "BarLaw::is_linear")]
    pub law: BarLaw,
    /// The full semismooth Newton path even for the linear law (the scene's `solver.path =
    /// "full"`): no condensation onto the contact dofs, Newton on every dof.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub full_path: bool,
}

/// The law of a bar family.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BarLaw {
    #[default]
    Linear,
    /// W = E/8 (F² − 1)².
    StVenantKirchhoff,
}

impl BarLaw {
    fn is_linear(&self) -> bool {
        *self == BarLaw::Linear
    }

    /// The law with modulus E.
    pub fn law(self, young: f64) -> Arc<dyn Hyperelastic1d> {
        match self {
            BarLaw::Linear => Arc::new(LinearElastic1d { young }),
            BarLaw::StVenantKirchhoff => Arc::new(StVenantKirchhoff1d { young }),
        }
    }
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
    /// run (midpoint type, and Newmark with the trapezoidal mean of the forces); HLT 3.7 and
    /// (1.49) for an energy-consistent compliance force (Signorini has none: its (3.7) residual
    /// is identically zero and its (1.49) is (1.48)).
    pub fn conserving(&self) -> Conserving {
        let compliance = self.treatment.has_stiffness();
        Conserving {
            balance: true,
            contact: !compliance || self.treatment.is_energy_consistent(),
            compliance,
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
        } else if self.scheme == DynamicScheme::Gonzalez {
            "Gonzalez: the balance (1.48) holds at round-off for either law (the stored energy \
             from the law's W(F), the force from its discrete gradient)"
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

    /// The P1 bar on M equal elements with the law `law`.
    pub fn body(&self, elements: usize, mass: MassMatrix, law: BarLaw) -> Result<BarBody, String> {
        let mesh = IntervalMesh::uniform(self.length, elements).map_err(|e| e.to_string())?;
        BarBody::new(BarData {
            mesh,
            density: self.density,
            area: self.area,
            law: law.law(self.young),
            supports: self.supports,
            mass,
            body_force: Field::Constant(0.0),
        })
        .map_err(|e| e.to_string())
    }
}
