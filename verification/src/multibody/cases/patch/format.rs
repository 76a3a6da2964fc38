//! The case format of kind `multibody_patch` (unknown keys are errors) and its checks.

use serde::{Deserialize, Serialize};

use crate::core::case::Case;
use crate::core::format::{invalid, positive, CaseError};
use crate::core::gate::{RateCriteria, RateGate};
use crate::exact::contact_patch::{ContactPatch, Hooke};
use crate::multibody::cases::patch::setup::PatchMesh;

/// A block's linear material.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialKeys {
    pub young: f64,
    pub poisson: f64,
}

impl MaterialKeys {
    fn hooke(self) -> Hooke {
        Hooke {
            young: self.young,
            poisson: self.poisson,
        }
    }
}

/// `[[mesh]]`: one pair of non-matching meshes, cells (n_x, n_y) of each block.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshKeys {
    pub lower: [usize; 2],
    pub upper: [usize; 2],
}

impl MeshKeys {
    pub fn mesh(&self) -> PatchMesh {
        PatchMesh {
            lower: self.lower,
            upper: self.upper,
        }
    }
}

/// `[roundoff]`: the two-pass errors must be at most `factor` × ε × L/h_min (case explanation).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoundoffKeys {
    pub factor: f64,
    #[serde(default)]
    pub note: String,
}

/// `[single_pass]`: what single-pass must show on every `[[mesh]]`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SinglePassKeys {
    /// Its stress error must be at least this (it fails the patch test: not round-off).
    pub min_stress_error: f64,
    #[serde(default)]
    pub note: String,
}

/// What a refinement gate measures: one error of single-pass (B slave) against h.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RefinementSelect {
    /// `stress_max`, `stress_l2`, `displacement_max` or `pressure_max`.
    pub error: String,
}

/// `[[refinement.gate]]`: a rate gate in h.
pub type RefinementGate = RateGate<RefinementSelect>;

/// `[refinement]`: single-pass (B slave) on `mesh` refined by each factor at a fixed ratio.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RefinementKeys {
    pub mesh: MeshKeys,
    pub factors: Vec<usize>,
    #[serde(rename = "gate", default)]
    pub gates: Vec<RefinementGate>,
}

/// `[materials]`: two-pass with different materials, against p.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialsKeys {
    pub mesh: MeshKeys,
    pub lower: MaterialKeys,
    pub upper: MaterialKeys,
    /// E of an upper material with the lower one's lateral strain: its ν solves
    /// ν (1 + ν)/E = ν_A (1 + ν_A)/E_A ([`MaterialsKeys::equal_lateral_strain`]).
    pub equal_strain_young: f64,
    pub pressures: Vec<f64>,
    /// The rate of stress_max (relative to p) in p.
    pub gate: RateCriteria,
}

impl MaterialsKeys {
    /// The upper material of E = `equal_strain_young` and the lower one's lateral strain:
    /// ν = (−1 + √(1 + 4 c))/2, c = E ν_A (1 + ν_A)/E_A.
    pub fn equal_lateral_strain(&self) -> MaterialKeys {
        let a = self.lower;
        let c = self.equal_strain_young * a.poisson * (1.0 + a.poisson) / a.young;
        MaterialKeys {
            young: self.equal_strain_young,
            poisson: 0.5 * (-1.0 + (1.0 + 4.0 * c).sqrt()),
        }
    }
}

/// The case format of kind `multibody_patch`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PatchCase {
    pub length: f64,
    pub lower_height: f64,
    pub upper_height: f64,
    pub pressure: f64,
    /// Both blocks' material (the patch test proper).
    pub material: MaterialKeys,
    #[serde(rename = "mesh")]
    pub meshes: Vec<MeshKeys>,
    pub roundoff: RoundoffKeys,
    pub single_pass: SinglePassKeys,
    pub refinement: Option<RefinementKeys>,
    pub materials: Option<MaterialsKeys>,
}

/// The errors a refinement gate may name.
pub const REFINEMENT_ERRORS: [&str; 4] = [
    "stress_max",
    "stress_l2",
    "displacement_max",
    "pressure_max",
];

impl PatchCase {
    /// Parses and checks a case.
    pub fn from_case(case: &Case) -> Result<Self, CaseError> {
        let path = case.path();
        let file: Self = case.body()?;
        for (name, v) in [
            ("length", file.length),
            ("lower_height", file.lower_height),
            ("upper_height", file.upper_height),
            ("pressure", file.pressure),
            ("roundoff.factor", file.roundoff.factor),
            (
                "single_pass.min_stress_error",
                file.single_pass.min_stress_error,
            ),
        ] {
            positive(path, name, v)?;
        }
        check_material(path, "material", file.material)?;
        if file.meshes.is_empty() {
            return Err(invalid(path, "mesh", "(none)", "at least one [[mesh]]"));
        }
        for (i, m) in file.meshes.iter().enumerate() {
            check_mesh(path, &format!("mesh[{i}]"), m)?;
        }
        if let Some(r) = &file.refinement {
            check_mesh(path, "refinement.mesh", &r.mesh)?;
            if r.factors.len() < 3
                || r.factors.windows(2).any(|w| w[1] <= w[0])
                || r.factors[0] == 0
            {
                return Err(invalid(
                    path,
                    "refinement.factors",
                    format!("{:?}", r.factors),
                    "at least three increasing factors ≥ 1",
                ));
            }
            if r.factors.iter().any(|&f| f > 64) {
                return Err(invalid(
                    path,
                    "refinement.factors",
                    format!("{:?}", r.factors),
                    "factors ≤ 64",
                ));
            }
            for (i, g) in r.gates.iter().enumerate() {
                let field = format!("refinement.gate[{i}]");
                if !REFINEMENT_ERRORS.contains(&g.select.error.as_str()) {
                    return Err(invalid(
                        path,
                        &format!("{field}.error"),
                        &g.select.error,
                        &format!("one of {REFINEMENT_ERRORS:?}"),
                    ));
                }
                g.criteria.check(path, &field)?;
            }
        }
        if let Some(m) = &file.materials {
            check_mesh(path, "materials.mesh", &m.mesh)?;
            check_material(path, "materials.lower", m.lower)?;
            check_material(path, "materials.upper", m.upper)?;
            positive(path, "materials.equal_strain_young", m.equal_strain_young)?;
            let nu = m.equal_lateral_strain().poisson;
            if !(0.0..0.5).contains(&nu) {
                return Err(invalid(
                    path,
                    "materials.equal_strain_young",
                    m.equal_strain_young,
                    &format!(
                        "an E for which ν (1 + ν)/E = ν_A (1 + ν_A)/E_A has a root ν in [0, 0.5) (here ν = {nu})"
                    ),
                ));
            }
            if m.pressures.len() < 3
                || m.pressures.iter().any(|p| !(p.is_finite() && *p > 0.0))
                || m.pressures.windows(2).any(|w| w[1] <= w[0])
            {
                return Err(invalid(
                    path,
                    "materials.pressures",
                    format!("{:?}", m.pressures),
                    "at least three increasing pressures > 0",
                ));
            }
            m.gate.check(path, "materials.gate")?;
        }
        Ok(file)
    }

    /// The exact problem with both blocks of `lower`/`upper` at pressure `p`.
    pub fn patch(&self, lower: MaterialKeys, upper: MaterialKeys, p: f64) -> ContactPatch {
        ContactPatch {
            length: self.length,
            lower_height: self.lower_height,
            upper_height: self.upper_height,
            pressure: p,
            lower: lower.hooke(),
            upper: upper.hooke(),
        }
    }

    /// The patch test proper (one material).
    pub fn same_material(&self) -> ContactPatch {
        self.patch(self.material, self.material, self.pressure)
    }
}

fn check_material(path: &std::path::Path, field: &str, m: MaterialKeys) -> Result<(), CaseError> {
    positive(path, &format!("{field}.young"), m.young)?;
    if !(m.poisson.is_finite() && (0.0..0.5).contains(&m.poisson)) {
        return Err(invalid(
            path,
            &format!("{field}.poisson"),
            m.poisson,
            "ν in [0, 0.5)",
        ));
    }
    Ok(())
}

fn check_mesh(path: &std::path::Path, field: &str, m: &MeshKeys) -> Result<(), CaseError> {
    for (name, v) in [("lower", m.lower), ("upper", m.upper)] {
        if v[0] == 0 || v[1] == 0 || v[0] > 512 || v[1] > 512 {
            return Err(invalid(
                path,
                &format!("{field}.{name}"),
                format!("{v:?}"),
                "cells [n_x, n_y], each in 1..=512",
            ));
        }
    }
    Ok(())
}
