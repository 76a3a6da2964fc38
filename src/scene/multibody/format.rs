//! The file format of a multibody scene: a dynamic scene whose `body` is an array of tables
//! (`[[body]]`), with `[[contact_pair]]` sections that pair a slave boundary part of one body with
//! a master part of another (or with the rigid foundation).

use serde::{Deserialize, Serialize};

use crate::mesh::triangle::{Diagonal, RectangleSide};
use crate::model::dynamic::bar::MassMatrix;
use crate::model::multibody::scheme::MultibodyScheme;
use crate::scene::boundary::{DirichletSection, TractionSection};
use crate::scene::field_spec::FieldSpec;
use crate::scene::plane_shape::PlaneShape;

/// The file format of a multibody scene (see the module docs of `scene::multibody`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MultibodySceneFile {
    /// `"dynamic"`, with the bodies written as `[[body]]` sections: several plane-strain
    /// hyperelastic bodies in node-to-segment contact with each other and with a rigid
    /// foundation, M φ̈ + ∇V(φ) − Σ (λ_N ∇g + λ_T ∇τ) = f with g ≥ 0, λ_N ≥ 0, λ_N g = 0 and
    /// Coulomb friction |λ_T| ≤ μ λ_N (the energy–momentum paper, "EM", (39)–(57);
    /// docs/multibody.md).
    pub model: String,
    /// A title for the reports and plots (default: none).
    #[serde(default)]
    pub title: String,
    /// `[[body]]`: the bodies, at least one; each its shape, mesh, density, material, loads,
    /// supports and initial rigid motion.
    pub body: Vec<MultibodyBodySection>,
    /// `[[contact_pair]]`: the contact pairs, each slave nodes of one body against the master
    /// segments of another or against the foundation (default: none — the bodies fly freely).
    #[serde(default)]
    pub contact_pair: Vec<ContactPairSection>,
    /// `[time]`: the final time, the steps and the integrator.
    pub time: MultibodyTimeSection,
    /// `[output]`: the snapshot times and the ParaView output.
    #[serde(default)]
    pub output: MultibodyOutputSection,
    /// `[solver]`: the Newton iteration of each step and the contact search.
    #[serde(default)]
    pub solver: MultibodySolverSection,
    /// The directory that a Gmsh `body.file` is relative to (the scene file's; not a key: set by
    /// [`crate::scene::Scene::load`]; `None`: the working directory).
    #[serde(skip)]
    pub base_dir: Option<std::path::PathBuf>,
}

/// `[[body]]`: one plane-strain body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MultibodyBodySection {
    /// The body's name, which `[[contact_pair]]` sections refer to; unique among the bodies
    /// (default: `"body 0"`, `"body 1"`, … by position).
    pub name: Option<String>,
    /// `"rectangle"` (`origin`, `size`, `divisions`, `diagonal`), `"disk"` (`center`, `radius`,
    /// `rings`), `"annulus"` (`center`, `inner`, `outer`, `radial`, `around`) or `"gmsh"` (`file`,
    /// `scale`, `offset`); keys of another shape are errors.
    pub shape: String,
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
    // gmsh
    /// Gmsh: the `.msh` file (format 4.1 ASCII or binary, or 2.2 ASCII), relative to the scene
    /// file; its boundary groups may then be selected by `group = "name"`.
    pub file: Option<String>,
    /// Gmsh: x ↦ scale x + offset on the file's coordinates, the scale > 0 (default 1).
    pub scale: Option<f64>,
    /// Gmsh: x ↦ scale x + offset on the file's coordinates, the offset [x, y] (default [0, 0]).
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub offset: Option<[f64; 2]>,
    /// ρ > 0, the mass density of ρ φ̈ − Div P = f (EM (39)).
    pub density: f64,
    /// The mass matrix (default `"consistent"`).
    #[serde(default)]
    pub mass: MassMatrix,
    /// The stored energy W of P = ∂_F W(F): `{ law, young, poisson }` (plane strain).
    pub material: BodyMaterialSection,
    /// The initial velocity [v_x, v_y] of the body's rigid motion v(X) = v + ω e_z × (X − c)
    /// (default [0, 0]).
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact")]
    pub velocity: [f64; 2],
    /// ω, the initial angular velocity of the rigid motion v(X) = v + ω e_z × (X − c),
    /// counter-clockwise positive (rad per unit time; default 0).
    #[serde(default)]
    pub angular_velocity: f64,
    /// c = [x, y], the centre of the initial spin ω (default: the body's centre of mass in the
    /// reference configuration).
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact_option")]
    pub spin_center: Option<[f64; 2]>,
    /// The body force per unit volume f = [f_x, f_y] (e.g. [0, −ρ g]): numbers or expressions of
    /// x, y, t (default [0, 0]).
    #[serde(default, deserialize_with = "crate::scene::fixed_array::exact")]
    pub body_force: [FieldSpec; 2],
    /// `[[body.dirichlet]]`: the parts of the body's boundary held at u = 0 (EM's Γ_u), as the
    /// dynamic scene's `[[dirichlet]]` (default: none).
    #[serde(default)]
    pub dirichlet: Vec<DirichletSection>,
    /// `[[body.traction]]`: the parts of the body's boundary loaded by a traction (EM's Γ_σ), as
    /// the dynamic scene's `[[traction]]` (default: none).
    #[serde(default)]
    pub traction: Vec<TractionSection>,
}

impl MultibodyBodySection {
    /// The plane-shape keys of the section.
    pub(crate) fn plane_shape(&self) -> PlaneShape<'_> {
        PlaneShape {
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

/// `material` of a `[[body]]`: a plane-strain hyperelastic law.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyMaterialSection {
    /// `"linear"` (small strain: not objective, so a spinning body's angular momentum drifts),
    /// `"st_venant_kirchhoff"` or `"neo_hooke"` (docs/dynamic.md, Laws).
    pub law: String,
    /// E > 0: Young's modulus.
    pub young: f64,
    /// ν in (−1, 1/2): Poisson's ratio (plane strain).
    pub poisson: f64,
}

/// `[[contact_pair]]`: the slave nodes of one body's boundary part against the master segments
/// of another body's (or against the foundation), with the constraint's enforcement and its
/// friction (EM §3).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactPairSection {
    /// The slave side: `{ body = "name", sides | where | group }`; each node of its boundary part
    /// carries the constraint g ≥ 0 against the master, g the gap of EM (16).
    pub slave: PairSideSection,
    /// The master side, another body's boundary part: `{ body = "name", sides | where | group }`
    /// (its edges are the segments the slave nodes are projected on); either this or
    /// `foundation`.
    pub master: Option<PairSideSection>,
    /// Instead of `master`: the rigid foundation {y ≤ level}, `{ level = 0.0 }`.
    pub foundation: Option<PairFoundationSection>,
    /// `"single"` (the default) or `"two"`: the roles exchanged as a second pair (refused with the
    /// foundation).
    #[serde(default)]
    pub pass: Pass,
    /// How g ≥ 0 is enforced (default `"lagrange"`).
    #[serde(default)]
    pub enforcement: EnforcementName,
    /// ε > 0, the penalty stiffness: with `enforcement = "penalty"` each slave node stores the
    /// energy (ε/2) (g₋)², g₋ = max(−g, 0), and carries the force ε g₋; with `"compliant"` the
    /// multiplier satisfies λ_N = ε g₋ at the step's end (force per unit gap; required with
    /// `"penalty"` and `"compliant"`, refused with `"lagrange"`).
    pub stiffness: Option<f64>,
    /// μ ≥ 0, Coulomb's friction coefficient of |λ_T| ≤ μ λ_N, stick or slip against the
    /// motion (EM (22)–(23), the return map (50)–(52)); μ > 0 needs a normal multiplier,
    /// `enforcement = "lagrange"` or `"compliant"`
    /// (default 0: frictionless, no friction code runs).
    #[serde(default)]
    pub friction: f64,
    /// What happens when the pair's bodies overlap at t = 0 (a slave node inside the master body
    /// or below the foundation, or a master-part node inside the slave body, deeper than the
    /// round-off tolerance 1e-12 × the longest segment + 8 ε × the largest coordinate):
    /// `"error"` (the default) refuses the scene, naming the pair, the node and the depth;
    /// `"resolve"` starts with each penetrating slave node moved onto its closest point of the
    /// master's boundary (an initial displacement, whose stored energy is part of E₀).
    #[serde(default)]
    pub initial_overlap: InitialOverlap,
    /// Accept an energy–momentum run whose energy rises through this pair's positive activation
    /// or segment-switch work, a node re-entering the master from inside (default false: the run
    /// stops with a typed energy-gain error naming the step, the node and the work;
    /// docs/multibody.md §8).
    #[serde(default)]
    pub allow_energy_gain: bool,
}

/// One side of a contact pair: a body and a part of its boundary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PairSideSection {
    /// The `name` of a `[[body]]`.
    pub body: String,
    /// The sides of a rectangle body that form the part; at most one of `sides`, `where`, `group`
    /// (none: the whole boundary).
    #[serde(default)]
    pub sides: Vec<RectangleSide>,
    /// Instead of `sides`: an expression of x, y that is positive at the midpoints of the part's
    /// edges (reference configuration).
    #[serde(rename = "where")]
    pub where_: Option<String>,
    /// Instead of `sides` or `where`: a boundary physical group of the body's Gmsh file.
    pub group: Option<String>,
}

/// `foundation` of a `[[contact_pair]]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PairFoundationSection {
    /// The rigid foundation is the half-plane {y ≤ level}; the gap of a slave node is
    /// g = y − level.
    pub level: f64,
}

/// Single- or two-pass contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Pass {
    /// The slave nodes against the master segments only (the default).
    #[default]
    Single,
    /// Also the master's nodes against the slave's segments: exact on flat interfaces (the
    /// contact patch test) but it over-constrains curved ones with Lagrange multipliers (the
    /// active set may cycle).
    Two,
}

/// What a `[[contact_pair]]` does when its bodies overlap at t = 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InitialOverlap {
    /// The scene is refused, naming the pair, the node and the depth (the default).
    #[default]
    Error,
    /// Each penetrating slave node starts on its closest point of the master's boundary (an
    /// initial displacement; the run starts with the stored energy it carries).
    Resolve,
}

/// How a pair's constraint g ≥ 0 is enforced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EnforcementName {
    /// Lagrange multipliers: g ≥ 0, λ_N ≥ 0, λ_N g = 0 exactly at the step's end (EM (19)–(21);
    /// the default).
    #[default]
    Lagrange,
    /// A penalty: the energy (ε/2) (g₋)² per slave node (`stiffness` ε), conserved by the
    /// energy–momentum scheme; at a fixed step it does not tend to the multipliers' solution as
    /// ε → ∞ (the contact mode √(ε/m) is not resolved: docs/multibody.md §3.1).
    Penalty,
    /// A compliant multiplier: λ_N = ε g₋ at the step's end (`stiffness` ε), solved like the
    /// multipliers; a penetration λ_N/ε, and the multipliers' solution plus O(1/ε).
    Compliant,
}

/// `[time]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MultibodyTimeSection {
    /// T > 0: the end of the run.
    pub final_time: f64,
    /// N ≥ 1 equal steps of [0, T] (k = T/N).
    pub steps: usize,
    /// The time integrator (default `"energy_momentum"`: momenta conserved, energy conserved
    /// except where a constraint activates).
    #[serde(default = "energy_momentum")]
    pub scheme: MultibodyScheme,
}

fn energy_momentum() -> MultibodyScheme {
    MultibodyScheme::EnergyMomentum
}

/// `[output]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MultibodyOutputSection {
    /// Snapshot times in [0, T]: every body's displacement and velocity and the contact states at
    /// the step nearest each (default: none).
    #[serde(default)]
    pub times: Vec<f64>,
    /// `verify scene` also writes one `.vtu` per snapshot with all bodies and a `.pvd` collection
    /// (ParaView): displacement, velocity, strain, stress, von Mises, the body id, the contact
    /// pressure, gap and slip.
    #[serde(default)]
    pub vtk: bool,
}

/// `[solver]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct MultibodySolverSection {
    /// The relative tolerance of each step's Newton method on its residual, in (0, 1) (default
    /// 1e-12).
    pub tolerance: Option<f64>,
    /// The most Newton iterations per step, ≥ 1 (default 60).
    pub max_iterations: Option<usize>,
    /// The contact search radius as a multiple of the longest master segment, > 0 (plus twice
    /// the distance the fastest node covers in a step; default 1).
    pub search_margin: Option<f64>,
    /// The master-segment switches allowed per slave node and step (then the node stays on its
    /// segment; default 4).
    pub max_switches: Option<usize>,
}
