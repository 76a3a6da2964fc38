//! The plane scene (`model = "plane"`): problem P in 2D — geometry, materials, boundary parts,
//! contact law, scheme and outputs.
//!
//! ```toml
//! model = "plane"
//! title = "Fernández–Sofonea Test 2D, clamped sides, β = 1000"
//!
//! [geometry]                       # a rectangle of n_x × n_y squares, each cut along a diagonal
//! # shape = "gmsh"                 # or a Gmsh mesh: file = "part.msh" (relative to the scene
//! #                                # file's directory), optional scale = 1.0, offset = [0.0, 0.0]
//! #                                # (x ↦ scale x + offset); see crate::mesh::gmsh
//! origin = [0.0, 0.0]
//! size = [6.0, 6.0]
//! divisions = [24, 24]
//! diagonal = "up"                  # "up": (x_i, y_j)–(x_{i+1}, y_{j+1}) (default) | "down"
//! # grading = [1.0, 1.0]           # power-law exponents per direction
//! # graded_towards = ["start", "start"]
//!
//! [time]
//! final_time = 1.0
//! steps = 100                      # or times = [...]; grading = 1.0
//! scheme = "explicit"              # "explicit" (the paper's) | "implicit" | "midpoint"
//!
//! [viscosity]                      # A: "paper" (mu, eta) | "isotropic" (a1, a2) | "saturating" (mu, eta, gamma, tau_c)
//! law = "paper"
//! mu = 30.0
//! eta = 20.0
//!
//! [elasticity]                     # B: "plane_stress" | "plane_strain" (young, poisson) | "isotropic" (a1, a2) | "softening" (lambda, shear, delta, eps_c)
//! law = "plane_stress"
//! young = 100.0
//! poisson = 0.3
//!
//! [body_force]
//! value = [0.0, 0.0]               # numbers or expressions of x, y, t
//!
//! [[dirichlet]]                    # Γ1 parts: by side, by an expression of x, y positive on the
//! sides = ["left", "right"]        # part's edge midpoints (where = "1e-9 - x"), or by a boundary
//!                                  # group of the Gmsh file (group = "clamp"): exactly one of them
//! support = "clamped"              # "clamped" | "fix_x" | "fix_y"
//!
//! [[traction]]                     # Γ2 parts
//! sides = ["top"]
//! value = [0.0, "-10*(6 - x)*t"]
//!
//! [contact]                        # Γ3
//! sides = ["bottom"]
//! law = "lubricated"               # "linear" | "lubricated" | "prescribed" (as for the rod)
//! beta = 1000.0
//! p0 = 2.0
//! integration = "gauss2"           # "gauss2" (default) | "nodal"
//!
//! # [[region]]                     # Gmsh meshes: a 2D physical group with its own A and/or B
//! # group = "insert"               # (the other triangles take [viscosity] and [elasticity])
//! # viscosity = { law = "paper", mu = 60.0, eta = 40.0 }
//! # elasticity = { law = "plane_strain", young = 400.0, poisson = 0.3 }
//!
//! [initial]
//! displacement = [0.0, 0.0]
//!
//! [output]
//! times = [0.5, 1.0]
//! vtk = false                      # `verify scene` also writes ParaView files (.vtu per time, .pvd)
//!
//! [solver]
//! path = "auto"                    # "auto" | "condensed" | "newton"
//! start_at_first_equilibrium = false
//! ```

use std::path::PathBuf;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::error::{Error, InputError};
use crate::material::nonlinear::{SaturatingViscosity, SofteningElasticity};
use crate::material::plane_law::{IsotropicLinear, PlaneLaw};
use crate::mesh::gmsh::{GmshMesh, Placement};
use crate::mesh::triangle::{Diagonal, Grading, RectangleSide, TriangleMesh};
use crate::model::quasistatic::plane::{
    ContactIntegration, ContactPart, MaterialRegion, PlaneProblem,
};
use crate::model::quasistatic::plane_output::{PlaneOutputRequest, PlaneSolution};
use crate::model::quasistatic::plane_solver::{PlaneParams, PlaneSolver, SolverPath};
use crate::model::quasistatic::scheme::TimeScheme;
use crate::scene::boundary::{
    dirichlet_parts, require_parts_selected, selector, traction_parts, vector, Selection,
};
pub use crate::scene::boundary::{DirichletSection, TractionSection};
use crate::scene::common::{check_model, missing, parse_toml, reject_keys};
use crate::scene::field_spec::FieldSpec;
use crate::time::grid::TimeGrid;

/// The file format of a plane scene (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSceneFile {
    /// `"plane"`: the quasistatic Kelvin–Voigt plane body, problem P of Fernández & Sofonea
    /// (docs/quasistatic.md).
    pub model: String,
    /// A title for the reports and plots (default: none).
    #[serde(default)]
    pub title: String,
    /// `[geometry]`: the body, a rectangle of n_x × n_y squares each cut into two P1 triangles, or
    /// a Gmsh mesh (`shape = "gmsh"`).
    pub geometry: GeometrySection,
    /// `[time]`: the time grid of [0, T] and the scheme.
    pub time: PlaneTimeSection,
    /// `[viscosity]`: the viscous law A of σ = A ε(u̇) + B ε(u) (2.1), strongly monotone (2.10).
    pub viscosity: MaterialSection,
    /// `[elasticity]`: the elastic law B of σ = A ε(u̇) + B ε(u) (2.1), Lipschitz (2.11).
    pub elasticity: MaterialSection,
    /// `[body_force]`: the body force f0 of Div σ + f0 = 0 (2.2) (default: none).
    #[serde(default)]
    pub body_force: VectorSection,
    /// `[[dirichlet]]`: the parts of Γ1 (2.3), each held by its `support` (default: none).
    #[serde(default)]
    pub dirichlet: Vec<DirichletSection>,
    /// `[[traction]]`: the parts of Γ2 (2.4), each loaded by a traction f2 = σν (default: none).
    #[serde(default)]
    pub traction: Vec<TractionSection>,
    /// `[contact]`: Γ3 and its foundation law (2.5) (absent: no contact).
    pub contact: Option<ContactSection>,
    /// `[initial]`: the initial displacement u0 (2.6) (default 0).
    #[serde(default)]
    pub initial: InitialSection,
    /// `[output]`: the snapshot times.
    #[serde(default)]
    pub output: PlaneOutputSection,
    /// `[solver]`: the solver path and the start at the first equilibrium.
    #[serde(default)]
    pub solver: PlaneSolverSection,
    /// `[[region]]`: regions of a Gmsh mesh with their own materials.
    #[serde(default)]
    pub region: Vec<RegionSection>,
    /// The directory that a Gmsh `file` is relative to (the scene file's; not a key: set by
    /// [`crate::scene::Scene::load`]; `None`: the working directory).
    #[serde(skip)]
    pub base_dir: Option<PathBuf>,
}

/// `[[region]]`: a 2D physical group of the body's Gmsh file and its own A and/or B (a law left
/// out is the scene's `[viscosity]` or `[elasticity]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSection {
    /// The 2D physical group (a named surface) of the Gmsh file whose triangles take these laws;
    /// regions must not overlap.
    pub group: String,
    /// The viscosity A of the region's triangles, with the keys of `[viscosity]` (absent: the
    /// scene's `[viscosity]`).
    pub viscosity: Option<MaterialSection>,
    /// The elasticity B of the region's triangles, with the keys of `[elasticity]` (absent: the
    /// scene's `[elasticity]`).
    pub elasticity: Option<MaterialSection>,
}

/// `[geometry]`: `shape = "rectangle"` (the default; `size`, `divisions`, `origin`, `diagonal`,
/// `grading`, `graded_towards`) or `shape = "gmsh"` (`file`, `scale`, `offset`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeometrySection {
    /// `"rectangle"` (default) or `"gmsh"`.
    pub shape: Option<String>,
    /// The `.msh` file (format 4.1 ASCII or binary, or 2.2 ASCII), relative to the scene file
    /// (`shape = "gmsh"` only).
    pub file: Option<String>,
    /// x ↦ scale x + offset on the file's coordinates: the scale (default 1; `shape = "gmsh"`).
    pub scale: Option<f64>,
    /// x ↦ scale x + offset on the file's coordinates: the offset [x, y] (default [0, 0];
    /// `shape = "gmsh"`).
    #[serde(default, deserialize_with = "super::fixed_array::exact_option")]
    pub offset: Option<[f64; 2]>,
    /// [x_0, y_0]: the lower-left corner of the rectangle (default [0, 0]).
    #[serde(default, deserialize_with = "super::fixed_array::exact")]
    pub origin: [f64; 2],
    /// [width, height] > 0: the sides of the rectangle (required for `shape = "rectangle"`).
    #[serde(default, deserialize_with = "super::fixed_array::exact_option")]
    pub size: Option<[f64; 2]>,
    /// [n_x, n_y] ≥ 1: the squares along x and y, 2 n_x n_y triangles (required for the
    /// rectangle).
    #[serde(default, deserialize_with = "super::fixed_array::exact_option")]
    pub divisions: Option<[usize; 2]>,
    /// Which diagonal cuts each square (default `"up"`).
    #[serde(default)]
    pub diagonal: Diagonal,
    /// [q_x, q_y] in [1, 10]: power-law grading per direction (absent: uniform).
    #[serde(default, deserialize_with = "super::fixed_array::exact_option")]
    pub grading: Option<[f64; 2]>,
    /// The end each graded direction refines towards, `"start"` (x_0, y_0) or `"end"` (default
    /// [`"start"`, `"start"`]).
    #[serde(default, deserialize_with = "super::fixed_array::exact_option")]
    pub graded_towards: Option<[GradingDirection; 2]>,
}

/// Which end a graded direction refines towards.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GradingDirection {
    /// Refine towards the start, x = x_0 (or y = y_0).
    Start,
    /// Refine towards the end, x = x_0 + width (or y = y_0 + height).
    End,
}

/// `[time]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneTimeSection {
    /// T > 0: the end of the time interval.
    pub final_time: f64,
    /// N ≥ 1: the number of steps (uniform, or graded by `grading`); either this or `times`.
    pub steps: Option<usize>,
    /// q in [1, 10]: power-law graded times t_n = T (n/N)^q (default 1: uniform).
    pub grading: Option<f64>,
    /// Explicit times 0 = t_0 < … < t_N = T instead of `steps`.
    pub times: Option<Vec<f64>>,
    /// The time treatment of the elastic term B ε(u) (docs/quasistatic.md, the fully discrete
    /// scheme; default `"explicit"`, the paper's).
    #[serde(default)]
    pub scheme: TimeScheme,
}

/// `[viscosity]` or `[elasticity]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    /// The law and its keys: `"plane_stress"`, `"plane_strain"` (`young`, `poisson`), `"isotropic"`
    /// (`a1`, `a2`), `"paper"` (`mu`, `eta`), `"saturating"` (`mu`, `eta`, `gamma`, `tau_c`),
    /// `"softening"` (`lambda`, `shear`, `delta`, `eps_c`); other keys are errors.
    pub law: String,
    /// E > 0, laws `"plane_stress"` and `"plane_strain"`: Young's modulus (docs/quasistatic.md,
    /// Test 2D).
    pub young: Option<f64>,
    /// κ, laws `"plane_stress"` (−1 < κ < 1) and `"plane_strain"` (−1 < κ < 1/2): Poisson's ratio.
    pub poisson: Option<f64>,
    /// a1, law `"isotropic"`: (L τ) = a1 tr(τ) I + a2 τ, positive definite (a2 > 0, a2 + 2 a1 > 0).
    pub a1: Option<f64>,
    /// a2 > 0, law `"isotropic"`: the coefficient of τ in a1 tr(τ) I + a2 τ.
    pub a2: Option<f64>,
    /// μ, laws `"paper"` and `"saturating"`: the coefficient of tr(τ) I in μ tr(τ) I + η τ (Test
    /// 2D; η + 2μ > 0).
    pub mu: Option<f64>,
    /// η > 0, laws `"paper"` and `"saturating"`: the coefficient of τ in μ tr(τ) I + η τ.
    pub eta: Option<f64>,
    /// γ ≥ 0, law `"saturating"`: the saturation stress of the term γ tanh(|τ|/τ_c) τ/|τ|.
    pub gamma: Option<f64>,
    /// τ_c > 0, law `"saturating"`: the strain rate at which γ tanh(|τ|/τ_c) saturates.
    pub tau_c: Option<f64>,
    /// λ, law `"softening"`: the coefficient of tr(ε) I in λ tr(ε) I + 2G (1 − δ |ε|²/(|ε|² +
    /// ε_c²)) ε (G + λ > 0).
    pub lambda: Option<f64>,
    /// G > 0, law `"softening"`: the shear modulus at small strain.
    pub shear: Option<f64>,
    /// δ in [0, 1), law `"softening"`: the shear stiffness falls from 2G to 2G(1 − δ) at large
    /// strain.
    pub delta: Option<f64>,
    /// ε_c > 0, law `"softening"`: the strain around which the shear stiffness softens.
    pub eps_c: Option<f64>,
}

/// A vector of two numbers or expressions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VectorSection {
    /// The body force [f0_x, f0_y] of (2.2): numbers or expressions of x, y, t.
    #[serde(deserialize_with = "super::fixed_array::exact")]
    pub value: [FieldSpec; 2],
}

impl Default for VectorSection {
    fn default() -> Self {
        Self {
            value: [FieldSpec::Number(0.0), FieldSpec::Number(0.0)],
        }
    }
}

/// `[contact]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSection {
    /// The sides of the rectangle that form Γ3; either this or `where`.
    #[serde(default)]
    pub sides: Vec<RectangleSide>,
    /// Instead of `sides`: an expression of x, y that is positive at the midpoints of the Γ3 edges.
    #[serde(rename = "where")]
    pub where_: Option<String>,
    /// A boundary group of the body's Gmsh file.
    pub group: Option<String>,
    /// The foundation law p_ν(r) of the normal velocity r (docs/quasistatic.md): `"linear"` (2.7) β
    /// r, `"lubricated"` (2.8) β r_+ + p0, or `"prescribed"` (2.9) S.
    pub law: String,
    /// β ≥ 0, the damper of laws `"linear"` and `"lubricated"` (required there, refused for
    /// `"prescribed"`).
    pub beta: Option<f64>,
    /// p0, the oil pressure of law `"lubricated"` (required there, refused otherwise): a number ≥ 0
    /// or an expression of x, y, t.
    pub p0: Option<FieldSpec>,
    /// S, the prescribed normal stress of law `"prescribed"` (required there, refused otherwise): a
    /// number or an expression of x, y, t.
    pub stress: Option<FieldSpec>,
    /// How the contact integral ∫_Γ3 p_ν(w_ν) v_ν is computed (default `"gauss2"`).
    #[serde(default)]
    pub integration: ContactIntegration,
    /// The boundary source g on Γ3 (manufactured solutions).
    #[serde(default, deserialize_with = "super::fixed_array::exact_option")]
    pub source: Option<[FieldSpec; 2]>,
}

/// `[initial]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct InitialSection {
    /// [u0_x, u0_y]: numbers or expressions of x, y, zero on Γ1 (default [0, 0]).
    #[serde(default, deserialize_with = "super::fixed_array::exact_option")]
    pub displacement: Option<[FieldSpec; 2]>,
}

/// `[output]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneOutputSection {
    /// Snapshot times, each a time of the grid: u and w at the nodes, the stress and its von Mises
    /// norm per triangle (default: none).
    #[serde(default)]
    pub times: Vec<f64>,
    /// `verify scene` also writes one `.vtu` per snapshot and a `.pvd` collection (ParaView):
    /// displacement, velocity, strain, stress, von Mises, the contact quantities, the body id.
    #[serde(default)]
    pub vtk: bool,
}

/// `[solver]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSolverSection {
    /// Which solver runs each step (default `"auto"`).
    #[serde(default)]
    pub path: SolverPath,
    /// When Γ1 leaves a rigid motion free and the first steps have no equilibrium, keep u0 until
    /// the first step that has one (default false: such a step is an error; docs/quasistatic.md,
    /// Test 2D).
    #[serde(default)]
    pub start_at_first_equilibrium: bool,
}

/// A validated plane scene.
#[derive(Debug, Clone)]
pub struct PlaneScene {
    pub title: String,
    pub problem: PlaneProblem,
    pub grid: TimeGrid,
    pub scheme: TimeScheme,
    pub params: PlaneParams,
    pub output: PlaneOutputRequest,
    pub file: PlaneSceneFile,
}

/// The material law of a section.
pub fn material(prefix: &str, m: &MaterialSection) -> Result<Arc<dyn PlaneLaw>, InputError> {
    let get = |k: &str, v: Option<f64>| {
        v.ok_or_else(|| {
            missing(
                format!("{prefix}.{k}"),
                format!("a value for law = \"{}\"", m.law),
            )
        })
    };
    let allowed: &[&str] = match m.law.as_str() {
        "plane_stress" | "plane_strain" => &["young", "poisson"],
        "isotropic" => &["a1", "a2"],
        "paper" => &["mu", "eta"],
        "saturating" => &["mu", "eta", "gamma", "tau_c"],
        "softening" => &["lambda", "shear", "delta", "eps_c"],
        other => {
            return Err(InputError::new(
                format!("{prefix}.law"),
                format!("\"{other}\""),
                "\"plane_stress\", \"plane_strain\", \"isotropic\", \"paper\", \"saturating\" or \"softening\"",
            ))
        }
    };
    let given = [
        ("young", m.young),
        ("poisson", m.poisson),
        ("a1", m.a1),
        ("a2", m.a2),
        ("mu", m.mu),
        ("eta", m.eta),
        ("gamma", m.gamma),
        ("tau_c", m.tau_c),
        ("lambda", m.lambda),
        ("shear", m.shear),
        ("delta", m.delta),
        ("eps_c", m.eps_c),
    ]
    .map(|(k, v)| (k, v.is_some()));
    reject_keys(prefix, ("law", &m.law), &given, allowed)?;
    // Young's modulus and Poisson's ratio in the law's admissible range, named as written (the
    // moduli a1, a2 they give are internal: ν = 1/2 in plane strain would show as a1 = inf).
    if let ("plane_stress" | "plane_strain", Some(nu)) = (m.law.as_str(), m.poisson) {
        let (upper, why) = if m.law == "plane_strain" {
            (0.5, "−1 < ν < 1/2 (plane strain; ν = 1/2 is incompressible, which this law cannot represent)")
        } else {
            (1.0, "−1 < ν < 1 (plane stress)")
        };
        if !(nu > -1.0 && nu < upper) {
            return Err(InputError::new(format!("{prefix}.poisson"), nu, why));
        }
        if let Some(e) = m.young {
            crate::error::require_positive(&format!("{prefix}.young"), e)?;
        }
    }
    match m.law.as_str() {
        "paper" => definite_form(prefix, ("eta", m.eta), ("mu", m.mu))?,
        "isotropic" => definite_form(prefix, ("a2", m.a2), ("a1", m.a1))?,
        _ => {}
    }
    let law: Arc<dyn PlaneLaw> = match m.law.as_str() {
        "plane_stress" => Arc::new(IsotropicLinear::plane_stress(
            get("young", m.young)?,
            get("poisson", m.poisson)?,
        )),
        "plane_strain" => Arc::new(IsotropicLinear::plane_strain(
            get("young", m.young)?,
            get("poisson", m.poisson)?,
        )),
        "isotropic" => Arc::new(IsotropicLinear {
            a1: get("a1", m.a1)?,
            a2: get("a2", m.a2)?,
        }),
        "paper" => Arc::new(IsotropicLinear::viscosity(
            get("mu", m.mu)?,
            get("eta", m.eta)?,
        )),
        "saturating" => Arc::new(SaturatingViscosity {
            mu: get("mu", m.mu)?,
            eta: get("eta", m.eta)?,
            gamma: get("gamma", m.gamma)?,
            tau_c: get("tau_c", m.tau_c)?,
        }),
        _ => Arc::new(SofteningElasticity {
            lambda: get("lambda", m.lambda)?,
            shear: get("shear", m.shear)?,
            delta: get("delta", m.delta)?,
            eps_c: get("eps_c", m.eps_c)?,
        }),
    };
    law.validate(prefix)?;
    Ok(law)
}

/// The form (L τ) = a1 tr τ δ + a2 τ is positive definite iff a2 > 0 and a2 + 2 a1 > 0: checked on
/// the keys as written (`mu`, `eta` for the paper's law; `a1`, `a2`), so the message names the one
/// to change.
fn definite_form(
    prefix: &str,
    (k2, a2): (&str, Option<f64>),
    (k1, a1): (&str, Option<f64>),
) -> Result<(), InputError> {
    let (Some(a2), Some(a1)) = (a2, a1) else {
        return Ok(());
    };
    if a2.is_nan() || a2 <= 0.0 {
        return Err(InputError::new(
            format!("{prefix}.{k2}"),
            a2,
            format!("a number > 0 (with {k1}, the form is positive definite iff {k2} > 0 and {k2} + 2 {k1} > 0)"),
        ));
    }
    if (a2 + 2.0 * a1).is_nan() || a2 + 2.0 * a1 <= 0.0 {
        return Err(InputError::new(
            format!("{prefix}.{k1}"),
            a1,
            format!(
                "{k1} > −{k2}/2 = {} (the form is positive definite iff {k2} + 2 {k1} > 0)",
                -0.5 * a2
            ),
        ));
    }
    Ok(())
}

/// The bytes a plane run holds and writes, from the counts alone (before the mesh is built, for
/// a rectangle), against the memory and disk limits ([`crate::scene::memory::RunSize`]): per dof
/// the operators, the Cholesky factor of a 2D grid (fill ~ n log₂ n) and the work vectors; per
/// distinct output time u and w at the nodes and stress and von Mises per triangle, as doubles
/// and as text (VTK: the same again); per step a few values (8) and their text. `(field,
/// written)` name the key that sets the mesh size.
fn plane_memory(
    file: &PlaneSceneFile,
    nodes: f64,
    triangles: f64,
    (field, written): (&str, String),
) -> Result<(), Error> {
    use crate::scene::memory::{distinct_times, RunSize, TEXT_BYTES};
    let dofs = 2.0 * nodes;
    let steps = match (&file.time.times, file.time.steps) {
        (Some(t), _) => t.len() as f64,
        (None, Some(n)) => n as f64,
        (None, None) => 0.0,
    };
    let per_output = 4.0 * nodes + 4.0 * triangles;
    // the explicit scheme's step bound (`verify scene`, a linear scene up to DENSE_LIMIT dofs):
    // a dense generalized eigenproblem, A and B, the factor and the workspace, 6 n² doubles
    // (50 MiB measured for the 1199 dofs of Test 2D)
    let dense = if file.time.scheme == TimeScheme::Explicit
        && dofs <= crate::model::quasistatic::plane_stability::DENSE_LIMIT as f64
    {
        6.0 * 8.0 * dofs * dofs
    } else {
        0.0
    };
    let vtk = if file.output.vtk { 2.0 } else { 1.0 };
    let run = RunSize {
        mesh_key: (field.to_string(), written),
        outputs: distinct_times(&file.output.times) as f64,
        steps,
        memory: [
            8.0 * dofs * (70.0 + 4.0 * dofs.max(2.0).log2()) + dense,
            vtk * per_output * (8.0 + TEXT_BYTES),
            8.0 * (8.0 + TEXT_BYTES),
        ],
        disk: [
            TEXT_BYTES * (2.0 * nodes + 3.0 * triangles),
            vtk * per_output * TEXT_BYTES,
            8.0 * TEXT_BYTES,
        ],
        memory_how: "16 MiB + 8 B × dofs (70 + 4 log₂ dofs) (explicit: + 6 × 8 B × dofs²) + \
                     output times × (4 nodes + 4 triangles) × 48 B (VTK: twice) + (N + 1) × 8 × \
                     48 B",
        disk_how: "40 B a number: output times × (4 nodes + 4 triangles) (VTK: twice) + (N + 1) \
                   × 8",
    };
    run.require()?;
    Ok(())
}

/// The mesh of `[geometry]` (and the Gmsh file it was read from, for its groups).
fn geometry_mesh(file: &PlaneSceneFile) -> Result<(TriangleMesh, Option<GmshMesh>), Error> {
    let g = &file.geometry;
    let given = [
        ("file", g.file.is_some()),
        ("scale", g.scale.is_some()),
        ("offset", g.offset.is_some()),
        ("origin", g.origin != [0.0, 0.0]),
        ("size", g.size.is_some()),
        ("divisions", g.divisions.is_some()),
        ("diagonal", g.diagonal != Diagonal::default()),
        ("grading", g.grading.is_some()),
        ("graded_towards", g.graded_towards.is_some()),
    ];
    match g.shape.as_deref().unwrap_or("rectangle") {
        "rectangle" => {
            crate::scene::common::reject_keys(
                "geometry",
                ("shape", "rectangle"),
                &given,
                &[
                    "origin",
                    "size",
                    "divisions",
                    "diagonal",
                    "grading",
                    "graded_towards",
                ],
            )?;
            let size = g
                .size
                .ok_or_else(|| missing("geometry.size", "[width, height]"))?;
            let divisions = g
                .divisions
                .ok_or_else(|| missing("geometry.divisions", "[n_x, n_y]"))?;
            let [nx, ny] = divisions.map(|d| d as f64);
            plane_memory(
                file,
                (nx + 1.0) * (ny + 1.0),
                2.0 * nx * ny,
                (
                    "geometry.divisions",
                    format!("[{}, {}]", divisions[0], divisions[1]),
                ),
            )?;
            let grading = match (g.grading, g.graded_towards) {
                (None, _) => [Grading::UNIFORM; 2],
                (Some(q), towards) => {
                    let t = towards.unwrap_or([GradingDirection::Start; 2]);
                    [0, 1].map(|k| Grading {
                        exponent: q[k],
                        towards_start: t[k] == GradingDirection::Start,
                    })
                }
            };
            let mesh =
                TriangleMesh::graded_rectangle(g.origin, size, divisions, g.diagonal, grading)
                    .map_err(crate::scene::common::mesh_field_as_written("geometry"))?;
            Ok((mesh, None))
        }
        "gmsh" => {
            crate::scene::common::reject_keys(
                "geometry",
                ("shape", "gmsh"),
                &given,
                &["file", "scale", "offset"],
            )?;
            let gmsh = read_gmsh(
                "geometry",
                g.file.as_ref(),
                g.scale,
                g.offset,
                file.base_dir.as_deref(),
            )?;
            plane_memory(
                file,
                gmsh.mesh.nodes().len() as f64,
                gmsh.mesh.triangles().len() as f64,
                (
                    "geometry.file",
                    format!("\"{}\"", g.file.as_deref().unwrap_or("")),
                ),
            )?;
            Ok((gmsh.mesh.clone(), Some(gmsh)))
        }
        other => Err(InputError::new(
            "geometry.shape",
            format!("\"{other}\""),
            "\"rectangle\" or \"gmsh\"",
        )
        .into()),
    }
}

/// The Gmsh mesh of a `{section}` with `shape = "gmsh"`: `file` relative to `base_dir`, mapped by
/// x ↦ scale x + offset.
pub(crate) fn read_gmsh(
    section: &str,
    file: Option<&String>,
    scale: Option<f64>,
    offset: Option<[f64; 2]>,
    base_dir: Option<&std::path::Path>,
) -> Result<GmshMesh, Error> {
    let name = file.ok_or_else(|| {
        missing(
            format!("{section}.file"),
            "the .msh file (relative to the scene file)",
        )
    })?;
    let scale = crate::error::require_positive(&format!("{section}.scale"), scale.unwrap_or(1.0))?;
    let offset = offset.unwrap_or([0.0, 0.0]);
    for (k, o) in offset.iter().enumerate() {
        crate::error::require_finite(&format!("{section}.offset[{k}]"), *o)?;
    }
    let path = match base_dir {
        Some(dir) => dir.join(name),
        None => PathBuf::from(name),
    };
    Ok(GmshMesh::read(&path, Placement { scale, offset })?)
}

/// The regions of `[[region]]`, section i named `region[i]`.
fn regions(file: &PlaneSceneFile, gmsh: Option<&GmshMesh>) -> Result<Vec<MaterialRegion>, Error> {
    let mut out = Vec::new();
    for (i, r) in file.region.iter().enumerate() {
        let prefix = format!("region[{i}]");
        let Some(gmsh) = gmsh else {
            return Err(InputError::new(
                format!("{prefix}.group"),
                format!("\"{}\"", r.group),
                "a body read from a Gmsh file (geometry.shape = \"gmsh\") to name its regions",
            )
            .into());
        };
        let triangles = gmsh.region(&format!("{prefix}.group"), &r.group)?.to_vec();
        let law =
            |key: &str, section: &Option<MaterialSection>, default: &MaterialSection| match section
            {
                Some(m) => material(&format!("{prefix}.{key}"), m),
                None => material(key, default),
            };
        out.push(MaterialRegion {
            name: r.group.clone(),
            triangles,
            viscosity: law("viscosity", &r.viscosity, &file.viscosity)?,
            elasticity: law("elasticity", &r.elasticity, &file.elasticity)?,
        });
    }
    Ok(out)
}

impl PlaneScene {
    /// Parses and validates a scene from TOML text; `source_name` labels errors.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Self, Error> {
        Self::from_file(parse_toml(text, source_name)?)
    }

    /// Validates a parsed scene file.
    pub fn from_file(file: PlaneSceneFile) -> Result<Self, Error> {
        check_model(&file.model, "plane")?;
        let (mesh, gmsh) = geometry_mesh(&file)?;
        let contact = match &file.contact {
            Some(c) => Some(ContactPart {
                boundary: selector(
                    "contact",
                    Selection {
                        sides: &c.sides,
                        where_: c.where_.as_ref(),
                        group: c.group.as_ref(),
                    },
                    gmsh.as_ref(),
                )?,
                law: Arc::new(crate::scene::foundation::foundation_law(
                    "contact",
                    &c.law,
                    c.beta,
                    c.p0.as_ref(),
                    c.stress.as_ref(),
                )?),
                integration: c.integration,
                source: c
                    .source
                    .as_ref()
                    .map(|s| vector("contact.source", s))
                    .transpose()?,
            }),
            None => None,
        };
        let dirichlet = dirichlet_parts(&file.dirichlet, gmsh.as_ref())?;
        let traction = traction_parts(&file.traction, gmsh.as_ref())?;
        let regions = regions(&file, gmsh.as_ref())?;
        require_parts_selected(
            &mesh,
            &dirichlet,
            &traction,
            contact.as_ref().map(|c| &c.boundary),
        )?;
        let problem = PlaneProblem {
            mesh,
            final_time: file.time.final_time,
            viscosity: material("viscosity", &file.viscosity)?,
            elasticity: material("elasticity", &file.elasticity)?,
            regions,
            body_force: vector("body_force.value", &file.body_force.value)?,
            dirichlet,
            traction,
            contact,
            initial_displacement: match &file.initial.displacement {
                Some(v) => vector("initial.displacement", v)?,
                None => [
                    crate::field::Field::Constant(0.0),
                    crate::field::Field::Constant(0.0),
                ],
            },
        };
        let t = &file.time;
        let grid = match (&t.times, t.steps) {
            (Some(times), None) => {
                let grid = TimeGrid::from_times(times.clone())?;
                // Checked here, where the user's key is known (the solver checks it again).
                if (grid.final_time() - t.final_time).abs() > 1e-12 * t.final_time {
                    return Err(InputError::new(
                        format!("time.times[{}]", times.len() - 1),
                        grid.final_time(),
                        format!(
                            "time.final_time = {} (the last time ends the run)",
                            t.final_time
                        ),
                    )
                    .into());
                }
                grid
            }
            (None, Some(steps)) => match t.grading {
                Some(q) if q != 1.0 => TimeGrid::graded(t.final_time, steps, q)?,
                _ => TimeGrid::uniform(t.final_time, steps)?,
            },
            _ => {
                return Err(InputError::new(
                    "time.steps",
                    "(missing or given with time.times)",
                    "either time.steps or time.times",
                )
                .into())
            }
        };
        Ok(Self {
            title: file.title.clone(),
            problem,
            grid,
            scheme: t.scheme,
            params: PlaneParams {
                path: file.solver.path,
                start_at_first_equilibrium: file.solver.start_at_first_equilibrium,
                ..Default::default()
            },
            output: PlaneOutputRequest {
                snapshot_times: file.output.times.clone(),
            },
            file,
        })
    }

    /// The solver of this scene.
    pub fn solver(&self) -> Result<PlaneSolver, Error> {
        PlaneSolver::new(&self.problem, self.grid.clone(), self.scheme, self.params)
    }

    /// Solves the scene and records its outputs.
    pub fn solve(&self) -> Result<PlaneSolution, Error> {
        self.solver()?.solve(&self.output)
    }
}

#[cfg(test)]
mod tests {
    //! Plane scenes: the documented example parses and runs; a misspelt key, a key of another
    //! law and a rollers scene without a way to start give errors that name the field.
    use super::*;

    const PAPER: &str = r#"
model = "plane"
[geometry]
size = [6.0, 6.0]
divisions = [6, 6]
[time]
final_time = 1.0
steps = 10
[viscosity]
law = "paper"
mu = 30.0
eta = 20.0
[elasticity]
law = "plane_stress"
young = 100.0
poisson = 0.3
[[dirichlet]]
sides = ["left", "right"]
support = "clamped"
[[traction]]
sides = ["top"]
value = [0.0, "-10*(6 - x)*t"]
[contact]
sides = ["bottom"]
law = "lubricated"
beta = 1000.0
p0 = 2.0
[output]
times = [1.0]
"#;

    #[test]
    fn paper_scene_runs_with_the_condensed_path() {
        let sol = PlaneScene::from_toml_str(PAPER, "x")
            .unwrap()
            .solve()
            .unwrap();
        assert_eq!(sol.stats.path, "condensed");
        assert_eq!(sol.snapshots.len(), 1);
        assert!(sol.snapshots[0].von_mises.iter().all(|v| v.is_finite()));
    }

    #[test]
    fn boundary_parts_by_expression_select_the_same_edges_as_by_side() {
        let by_where = PAPER.replace(
            "sides = [\"left\", \"right\"]",
            "where = \"abs(x - 3) - 2.999\"",
        );
        let a = PlaneScene::from_toml_str(PAPER, "x")
            .unwrap()
            .solve()
            .unwrap();
        let b = PlaneScene::from_toml_str(&by_where, "x")
            .unwrap()
            .solve()
            .unwrap();
        assert_eq!(a.snapshots[0].u, b.snapshots[0].u);
    }

    #[test]
    fn an_indefinite_form_names_the_key_as_written() {
        for (from, to, key) in [
            (
                "mu = 30.0\neta = 20.0",
                "mu = 0.0\neta = 0.0",
                "viscosity.eta = 0",
            ),
            ("mu = 30.0", "mu = -10.0", "viscosity.mu = -10"),
        ] {
            let err = PlaneScene::from_toml_str(&PAPER.replace(from, to), "x").unwrap_err();
            assert!(err.to_string().contains(key), "{err}");
        }
    }

    #[test]
    fn times_ending_before_the_final_time_name_the_last_time() {
        let text = PAPER.replace("steps = 10", "times = [0.0, 2.0]");
        let err = PlaneScene::from_toml_str(&text, "x")
            .unwrap_err()
            .to_string();
        assert!(err.contains("time.times[1] = 2"), "{err}");
        assert!(err.contains("time.final_time = 1"), "{err}");
    }

    #[test]
    fn key_of_another_law_is_named() {
        let text = PAPER.replace("mu = 30.0", "mu = 30.0\nyoung = 3.0");
        let err = PlaneScene::from_toml_str(&text, "x").unwrap_err();
        assert!(err.to_string().contains("viscosity.young"), "{err}");
    }

    #[test]
    fn rollers_without_start_variant_fail_with_no_equilibrium_at_step_1() {
        let text = PAPER
            .replace("support = \"clamped\"", "support = \"fix_x\"")
            .replace("steps = 10", "steps = 100");
        let err = PlaneScene::from_toml_str(&text, "x")
            .unwrap()
            .solve()
            .unwrap_err();
        match err {
            Error::Solve(crate::error::SolveError::NoEquilibrium { step, .. }) => {
                assert_eq!(step, 1)
            }
            other => panic!("{other}"),
        }
        let text = text.replace(
            "[output]",
            "[solver]\nstart_at_first_equilibrium = true\n[output]",
        );
        let sol = PlaneScene::from_toml_str(&text, "x")
            .unwrap()
            .solve()
            .unwrap();
        // 180 t < 12 N for t ≤ 0.06: the first six steps have no equilibrium.
        assert_eq!(sol.stats.skipped_steps, vec![1, 2, 3, 4, 5, 6]);
    }
}
