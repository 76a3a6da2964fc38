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
    /// `"dynamic"`: a hyperelastic body, a bar or a plane body, against a rigid foundation
    /// (Barboteu–Danan–Sofonea (1.14)–(1.20), docs/dynamic.md).
    pub model: String,
    /// A title for the reports and plots (default: none).
    #[serde(default)]
    pub title: String,
    /// `[body]`: the shape, its mesh, the density and the mass matrix.
    pub body: BodySection,
    /// `[material]`: the stored energy W of Π = ∂_F W(F) (1.14).
    pub material: DynamicMaterialSection,
    /// `[time]`: the final time, the steps and the integrator.
    pub time: DynamicTimeSection,
    /// `[initial]`: u0 and u1 of (1.20) (default: at rest, undeformed).
    #[serde(default)]
    pub initial: DynamicInitialSection,
    /// `[body_force]`: the body force f0 of (1.15) (absent: none).
    pub body_force: Option<ValueSection>,
    /// `[[dirichlet]]`: the parts of Γ1 (1.16), plane bodies only (a bar uses `body.supports`).
    #[serde(default)]
    pub dirichlet: Vec<DirichletSection>,
    /// `[[traction]]`: the parts of Γ2 (1.17), each loaded by f2 = Πν, plane bodies only.
    #[serde(default)]
    pub traction: Vec<TractionSection>,
    /// `[contact]`: the foundation, the normal treatment and the friction (absent: no contact).
    pub contact: Option<DynamicContactSection>,
    /// `[output]`: the snapshot times.
    #[serde(default)]
    pub output: DynamicOutputSection,
    /// `[solver]`: the Newton iteration of each step and the solver path.
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
    /// `"bar"` (1D: `length`, `elements`, `area`, `supports`), `"rectangle"` (`origin`, `size`,
    /// `divisions`, `diagonal`), `"disk"` (`center`, `radius`, `rings`) or `"annulus"` (`center`,
    /// `inner`, `outer`, `radial`, `around`); keys of another shape are errors.
    pub shape: String,
    /// ρ, the mass density of ρ ü − Div Π = f0 (1.15).
    pub density: f64,
    /// The mass matrix (default `"consistent"`).
    #[serde(default)]
    pub mass: MassMatrix,
    // bar
    /// Bar: the length L > 0 of the bar (0, L).
    pub length: Option<f64>,
    /// Bar: the number of equal elements, ≥ 1.
    pub elements: Option<usize>,
    /// Bar: the cross-section A > 0; energies and forces scale with it (default 1).
    pub area: Option<f64>,
    /// Bar: the ends held at u = 0 (default: none).
    pub supports: Option<Vec<BarEnd>>,
    // rectangle
    /// Rectangle: the lower-left corner [x, y] (default [0, 0]).
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub origin: Option<[f64; 2]>,
    /// Rectangle: [width, height] > 0.
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub size: Option<[f64; 2]>,
    /// Rectangle: [n_x, n_y] ≥ 1 squares, each cut into two triangles.
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub divisions: Option<[usize; 2]>,
    /// Rectangle: which diagonal cuts each square (default `"up"`).
    pub diagonal: Option<Diagonal>,
    // disk, annulus
    /// Disk and annulus: the centre [x, y].
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub center: Option<[f64; 2]>,
    /// Disk: the radius > 0.
    pub radius: Option<f64>,
    /// Disk: the rings of triangles from the centre to the rim, ≥ 1.
    pub rings: Option<usize>,
    /// Annulus: the inner radius > 0.
    pub inner: Option<f64>,
    /// Annulus: the outer radius > `inner`.
    pub outer: Option<f64>,
    /// Annulus: the layers of cells between the radii, ≥ 1.
    pub radial: Option<usize>,
    /// Annulus: the cells around, ≥ 3.
    pub around: Option<usize>,
    /// Gmsh: the `.msh` file (format 4.1 ASCII or binary, or 2.2 ASCII), relative to the scene
    /// file.
    pub file: Option<String>,
    /// Gmsh: x ↦ scale x + offset on the file's coordinates, the scale (default 1).
    pub scale: Option<f64>,
    /// Gmsh: x ↦ scale x + offset on the file's coordinates, the offset [x, y] (default [0, 0]).
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub offset: Option<[f64; 2]>,
}

impl BodySection {
    /// The plane-shape keys of the section.
    pub(crate) fn plane_shape(&self) -> crate::scene::plane_shape::PlaneShape<'_> {
        crate::scene::plane_shape::PlaneShape {
            shape: &self.shape,
            origin: self.origin,
            size: self.size,
            divisions: self.divisions,
            diagonal: self.diagonal,
            center: self.center,
            radius: self.radius,
            rings: self.rings,
            inner: self.inner,
            outer: self.outer,
            radial: self.radial,
            around: self.around,
            file: self.file.as_ref(),
            scale: self.scale,
            offset: self.offset,
        }
    }
}

/// `[material]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicMaterialSection {
    /// Plane body: `"linear"`, `"st_venant_kirchhoff"` or `"neo_hooke"` (plane strain); bar:
    /// `"linear"` or `"st_venant_kirchhoff"` (docs/dynamic.md, Laws).
    pub law: String,
    /// E > 0: Young's modulus.
    pub young: f64,
    /// κ in (−1, 1/2): Poisson's ratio, plane bodies only (required there, refused for a bar).
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
    /// T > 0: the end of the run.
    pub final_time: f64,
    /// N ≥ 1 equal steps of [0, T].
    pub steps: usize,
    /// The time integrator (docs/dynamic.md, Discretization).
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
    /// f0: one number or expression of x, t (bar) or two, [x, y], of x, y, t (plane body).
    pub value: ValueSpec,
}

/// `[initial]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct DynamicInitialSection {
    /// u0 of (1.20): one value (bar) or two, [x, y] (plane body), numbers or expressions of x, y
    /// (default 0).
    pub displacement: Option<ValueSpec>,
    /// u1 = u̇(0) of (1.20): one value (bar) or two (plane body), numbers or expressions of x, y
    /// (default 0).
    pub velocity: Option<ValueSpec>,
}

/// `[contact]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicContactSection {
    /// The normal contact (docs/dynamic.md): `"penalty"` (r), `"energy_consistent"` =
    /// `"hauret_le_tallec"` (r; HLT (3.68)), `"hauret_le_tallec_tilted"` (r; HLT (3.69)),
    /// `"limited_penetration"` (r and `depth`; (1.8), (1.18)) or `"signorini"` (exact
    /// non-penetration, no stiffness).
    pub treatment: String,
    /// r > 0: the penalty or compliance stiffness p(u_ν) = r (u_ν)_+ (1.8); all treatments but
    /// `"signorini"`.
    pub stiffness: Option<f64>,
    /// g > 0: the thickness of the asperity layer of (1.18), `"limited_penetration"`; also the
    /// default of `friction.depth`.
    pub depth: Option<f64>,
    // 2D
    /// Plane body: the foundation is the half-plane {y ≤ level} (required).
    pub level: Option<f64>,
    /// Plane body: the sides (rectangle) of the candidate contact boundary; either this or `where`
    /// (default: all of the boundary).
    #[serde(default)]
    pub sides: Vec<RectangleSide>,
    /// Plane body, instead of `sides`: an expression of x, y positive at the midpoints of the
    /// candidate contact edges.
    #[serde(rename = "where")]
    pub where_: Option<String>,
    /// A boundary group of the body's Gmsh file (`shape = "gmsh"`).
    pub group: Option<String>,
    // bar
    /// Bar: the end that meets the wall (required).
    pub end: Option<BarEnd>,
    /// Bar: the wall position x (required).
    pub wall: Option<f64>,
    /// `[contact.friction]`: Coulomb friction (1.19), plane bodies only (absent: frictionless).
    pub friction: Option<FrictionSection>,
}

/// `[contact.friction]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSection {
    /// The coefficient μ(u_ν) of (1.13): `"constant"` μ0, `"growing"` (or `"mu1"`: 0 → μ0 over the
    /// layer) or `"decreasing"` (or `"mu2"`: 2μ0 → μ0) (docs/dynamic.md).
    pub law: String,
    /// μ0 ≥ 0: the coefficient at full penetration, μ0 = μ(g).
    pub mu0: f64,
    /// g > 0 of (1.13), laws `"growing"` and `"decreasing"` (default: `contact.depth`).
    pub depth: Option<f64>,
}

/// `[output]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicOutputSection {
    /// Snapshot times in [0, T]: the displacement at the step nearest each (default: none).
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
    /// The relative tolerance of Newton on ‖R‖_∞, in (0, 1) (default 1e-12).
    pub tolerance: Option<f64>,
    /// The most Newton iterations per step (default 60).
    pub max_iterations: Option<usize>,
    /// `"auto"` (a linear body takes the linear path) or `"full"` (the full Newton path always, for
    /// comparisons) (default `"auto"`).
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
