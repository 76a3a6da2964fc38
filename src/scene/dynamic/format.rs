//! The file format of a dynamic scene: its sections, and the values (one for a bar, two for a
//! plane body) given as numbers or expressions.

use serde::{Deserialize, Serialize};

use crate::error::InputError;
use crate::field::Field;
use crate::mesh::triangle::{Diagonal, RectangleSide};
use crate::model::dynamic::bar::MassMatrix;
use crate::model::dynamic::contact_model::BarEnd;
use crate::model::dynamic::scheme::DynamicScheme;
use crate::scene::boundary::{vector, DirichletSection, TractionSection};
use crate::scene::field_spec::FieldSpec;

/// The file format of a dynamic scene (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicSceneFile {
    pub model: String,
    #[serde(default)]
    pub title: String,
    pub body: BodySection,
    pub material: DynamicMaterialSection,
    pub time: DynamicTimeSection,
    #[serde(default)]
    pub initial: DynamicInitialSection,
    pub body_force: Option<ValueSection>,
    #[serde(default)]
    pub dirichlet: Vec<DirichletSection>,
    #[serde(default)]
    pub traction: Vec<TractionSection>,
    pub contact: Option<DynamicContactSection>,
    #[serde(default)]
    pub output: DynamicOutputSection,
    #[serde(default)]
    pub solver: DynamicSolverSection,
    /// `[[region]]`: regions of a Gmsh body (`body.shape = "gmsh"`) with their own density and/or
    /// material.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub region: Vec<DynamicRegionSection>,
    /// The directory that a Gmsh `body.file` is relative to (the scene file's; not a key: set by
    /// [`crate::scene::Scene::load`]; `None`: the working directory).
    #[serde(skip)]
    pub base_dir: Option<std::path::PathBuf>,
}

/// `[body]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySection {
    pub shape: String,
    pub density: f64,
    #[serde(default)]
    pub mass: MassMatrix,
    // bar
    pub length: Option<f64>,
    pub elements: Option<usize>,
    pub area: Option<f64>,
    pub supports: Option<Vec<BarEnd>>,
    // rectangle
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub origin: Option<[f64; 2]>,
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub size: Option<[f64; 2]>,
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub divisions: Option<[usize; 2]>,
    pub diagonal: Option<Diagonal>,
    // disk, annulus
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub center: Option<[f64; 2]>,
    pub radius: Option<f64>,
    pub rings: Option<usize>,
    pub inner: Option<f64>,
    pub outer: Option<f64>,
    pub radial: Option<usize>,
    pub around: Option<usize>,
    // gmsh: the .msh file (relative to the scene file), x ↦ scale x + offset
    pub file: Option<String>,
    pub scale: Option<f64>,
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub offset: Option<[f64; 2]>,
}

/// `[material]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicMaterialSection {
    /// Plane body: `"linear"`, `"st_venant_kirchhoff"` or `"neo_hooke"` (plane strain); bar:
    /// `"linear"` or `"st_venant_kirchhoff"`.
    pub law: String,
    /// Young's modulus E > 0.
    pub young: f64,
    /// Poisson's ratio ν in (−1, 1/2) (plane body only).
    pub poisson: Option<f64>,
}

/// `[[region]]`: a 2D physical group of the body's Gmsh file with its own density and/or
/// material; a key left out is the body's (`body.density`, the keys of `[material]`). Regions
/// must not overlap.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicRegionSection {
    /// The name of a 2D physical group of the body's `.msh` file.
    pub group: String,
    /// ρ of the region's triangles (default: `body.density`).
    pub density: Option<f64>,
    /// The region's law and constants, as in `[material]` (an inline table, e.g.
    /// `material = { law = "neo_hooke", young = 5e6 }`); each key left out is `[material]`'s.
    pub material: Option<RegionMaterialSection>,
}

/// `material` of a `[[region]]`: the keys of `[material]`, each optional (default: `[material]`'s).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionMaterialSection {
    /// `"linear"`, `"st_venant_kirchhoff"` or `"neo_hooke"` (plane strain).
    pub law: Option<String>,
    /// Young's modulus E > 0.
    pub young: Option<f64>,
    /// Poisson's ratio ν in (−1, 1/2).
    pub poisson: Option<f64>,
}

/// `[time]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicTimeSection {
    pub final_time: f64,
    pub steps: usize,
    pub scheme: DynamicScheme,
}

/// One value (bar) or two (plane), numbers or expressions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ValueSpec {
    Scalar(FieldSpec),
    Vector(#[serde(deserialize_with = "crate::scene::fixed_array::exact")] [FieldSpec; 2]),
}

/// `[body_force]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ValueSection {
    pub value: ValueSpec,
}

/// `[initial]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct DynamicInitialSection {
    pub displacement: Option<ValueSpec>,
    pub velocity: Option<ValueSpec>,
}

/// `[contact]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicContactSection {
    pub treatment: String,
    pub stiffness: Option<f64>,
    pub depth: Option<f64>,
    // 2D
    pub level: Option<f64>,
    #[serde(default)]
    pub sides: Vec<RectangleSide>,
    #[serde(rename = "where")]
    pub where_: Option<String>,
    /// A boundary group of the body's Gmsh file (`shape = "gmsh"`).
    pub group: Option<String>,
    // bar
    pub end: Option<BarEnd>,
    pub wall: Option<f64>,
    pub friction: Option<FrictionSection>,
}

/// `[contact.friction]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSection {
    pub law: String,
    pub mu0: f64,
    pub depth: Option<f64>,
}

/// `[output]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicOutputSection {
    #[serde(default)]
    pub times: Vec<f64>,
    /// `verify scene` also writes one `.vtu` per snapshot and a `.pvd` collection (ParaView):
    /// displacement, velocity, strain, stress, von Mises, the contact quantities, the body id.
    #[serde(default)]
    pub vtk: bool,
}

/// `[solver]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct DynamicSolverSection {
    pub tolerance: Option<f64>,
    pub max_iterations: Option<usize>,
    pub path: Option<String>,
}

/// The one field of the value `v` of a bar (zero when absent); `field` names it in errors.
pub(super) fn scalar(field: &str, v: &Option<ValueSpec>) -> Result<Field, InputError> {
    match v {
        None => Ok(Field::Constant(0.0)),
        Some(ValueSpec::Scalar(s)) => s.to_field(field),
        Some(ValueSpec::Vector(_)) => Err(InputError::new(
            field,
            "(two values)",
            "one value for a bar",
        )),
    }
}

/// The two fields of the value `v` of a plane body (zero when absent); `field` names it in
/// errors.
pub(super) fn pair(field: &str, v: &Option<ValueSpec>) -> Result<[Field; 2], InputError> {
    match v {
        None => Ok([Field::Constant(0.0), Field::Constant(0.0)]),
        Some(ValueSpec::Vector(p)) => vector(field, p),
        Some(ValueSpec::Scalar(_)) => Err(InputError::new(
            field,
            "(one value)",
            "two values [x, y] for a plane body",
        )),
    }
}
