//! The dynamic scene (`model = "dynamic"`): an elastic body thrown at (or resting on) a rigid
//! foundation — body shape and mesh, hyperelastic material, scheme, contact treatment, friction,
//! initial state and outputs (Barboteu–Danan–Sofonea (1.14)–(1.20)).
//!
//! ```toml
//! model = "dynamic"
//! title = "neo-Hookean ring thrown obliquely at the foundation"
//!
//! [body]
//! shape = "annulus"            # "bar" | "rectangle" | "disk" | "annulus"
//! center = [0.0, 0.52]         # disk, annulus
//! inner = 0.3                  # annulus
//! outer = 0.5                  # annulus; disk: radius = 0.5, rings = 12
//! radial = 4                   # annulus
//! around = 64                  # annulus
//! # rectangle: origin = [0, 0], size = [1, 1], divisions = [8, 8], diagonal = "up"
//! # bar: length = 1.0, elements = 100, area = 1.0, supports = ["right"]
//! density = 1000.0
//! mass = "consistent"          # "consistent" | "lumped"
//!
//! [material]                   # "linear" | "st_venant_kirchhoff" | "neo_hooke" (plane strain)
//! law = "neo_hooke"            # bar: "linear" | "st_venant_kirchhoff", young only
//! young = 1e6
//! poisson = 0.3
//!
//! [time]
//! final_time = 0.06
//! steps = 600
//! scheme = "gonzalez"          # "newmark" | "midpoint" | "gonzalez"
//!
//! [initial]
//! velocity = [4.0, -8.0]       # numbers or expressions of x, y (bar: one value, e.g. -1.0)
//! displacement = [0.0, 0.0]
//!
//! [body_force]
//! value = [0.0, 0.0]           # numbers or expressions of x, y, t (bar: one value)
//!
//! [[dirichlet]]                # 2D: sides (rectangle) or where = "expression > 0 on the part"
//! where = "y - 0.999"
//! support = "clamped"
//!
//! [[traction]]
//! sides = ["top"]
//! value = [0.0, "-100*t"]
//!
//! [contact]
//! level = 0.0                  # 2D: the foundation {x2 ≤ level}
//! where = "0.52 - y"           # 2D: the candidate contact boundary (default: all of it)
//! # bar: end = "left", wall = 0.0
//! treatment = "limited_penetration"   # "penalty" | "energy_consistent" (= "hauret_le_tallec")
//!                                      # | "hauret_le_tallec_tilted" | "limited_penetration" | "signorini"
//! stiffness = 1e9              # r (all but signorini)
//! depth = 5e-4                 # g (limited_penetration)
//!
//! [contact.friction]           # optional (2D): "constant" | "growing" (μ1 of (1.13)) | "decreasing" (μ2)
//! law = "growing"
//! mu0 = 0.3
//! depth = 5e-4                 # g of (1.13); default: contact.depth
//!
//! [output]
//! times = [0.01, 0.02]         # snapshots of the displacement
//!
//! [solver]
//! tolerance = 1e-12
//! max_iterations = 60
//! path = "auto"                # "auto" (the model decides) | "full" (for comparisons)
//! ```

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::contact::friction::FrictionCoefficient;
use crate::error::{Error, InputError};
use crate::field::Field;
use crate::material::hyperelastic::{
    Hyperelastic1d, Hyperelastic2d, LinearElastic, LinearElastic1d, NeoHooke, StVenantKirchhoff,
    StVenantKirchhoff1d,
};
use crate::mesh::generators::{annulus, disk};
use crate::mesh::interval::IntervalMesh;
use crate::mesh::triangle::{Diagonal, Grading, RectangleSide, TriangleMesh};
use crate::model::dynamic::bar::{BarBody, BarData, BarSupports, MassMatrix};
use crate::model::dynamic::body::ElasticBody;
use crate::model::dynamic::contact_model::{BarEnd, ContactModel, NormalTreatment};
use crate::model::dynamic::newton::NewtonParams;
use crate::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};
use crate::model::dynamic::scheme::DynamicScheme;
use crate::model::dynamic::solver::{
    DynamicParams, DynamicProblem, DynamicSolution, DynamicSolver,
};
use crate::model::quasistatic::plane::{BoundarySelector, DirichletPart, TractionPart};
use crate::scene::field_spec::FieldSpec;
use crate::scene::plane::{selector, vector, DirichletSection, TractionSection};

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
    pub origin: Option<[f64; 2]>,
    pub size: Option<[f64; 2]>,
    pub divisions: Option<[usize; 2]>,
    pub diagonal: Option<Diagonal>,
    // disk, annulus
    pub center: Option<[f64; 2]>,
    pub radius: Option<f64>,
    pub rings: Option<usize>,
    pub inner: Option<f64>,
    pub outer: Option<f64>,
    pub radial: Option<usize>,
    pub around: Option<usize>,
}

/// `[material]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicMaterialSection {
    pub law: String,
    pub young: f64,
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
    Vector([FieldSpec; 2]),
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
}

/// `[solver]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct DynamicSolverSection {
    pub tolerance: Option<f64>,
    pub max_iterations: Option<usize>,
    pub path: Option<String>,
}

/// The body of a validated scene (the concrete type, for outputs and plots).
#[derive(Debug, Clone)]
pub enum SceneBody {
    Bar(Arc<BarBody>),
    Plane(Arc<PlaneBody>),
}

/// A validated dynamic scene.
#[derive(Debug, Clone)]
pub struct DynamicScene {
    pub title: String,
    pub body: SceneBody,
    pub problem: DynamicProblem,
    pub params: DynamicParams,
    pub file: DynamicSceneFile,
}

fn missing(field: &str, what: &str) -> InputError {
    InputError::new(field, "(missing)", what)
}

/// Rejects keys that belong to other shapes.
fn only(shape: &str, given: &[(&str, bool)], allowed: &[&str]) -> Result<(), InputError> {
    for (k, present) in given {
        if *present && !allowed.contains(k) {
            return Err(InputError::new(
                format!("body.{k}"),
                "(given)",
                format!("no such key for shape = \"{shape}\""),
            ));
        }
    }
    Ok(())
}

fn treatment(c: &DynamicContactSection) -> Result<NormalTreatment, InputError> {
    let r = || {
        c.stiffness
            .ok_or_else(|| missing("contact.stiffness", "the penalty stiffness r > 0"))
    };
    let t = match c.treatment.as_str() {
        "penalty" => NormalTreatment::Penalty { stiffness: r()? },
        "energy_consistent" | "hauret_le_tallec" => {
            NormalTreatment::EnergyConsistent { stiffness: r()? }
        }
        "hauret_le_tallec_tilted" => NormalTreatment::HauretLeTallecTilted { stiffness: r()? },
        "limited_penetration" => NormalTreatment::LimitedPenetration {
            stiffness: r()?,
            depth: c
                .depth
                .ok_or_else(|| missing("contact.depth", "the depth g > 0 of the asperity layer"))?,
        },
        "signorini" => {
            if c.stiffness.is_some() {
                return Err(InputError::new(
                    "contact.stiffness",
                    "(given)",
                    "no stiffness for treatment = \"signorini\" (exact non-penetration)",
                ));
            }
            NormalTreatment::Signorini
        }
        other => {
            return Err(InputError::new(
                "contact.treatment",
                format!("\"{other}\""),
                "\"penalty\", \"energy_consistent\", \"hauret_le_tallec\", \
                 \"hauret_le_tallec_tilted\", \"limited_penetration\" or \"signorini\"",
            ))
        }
    };
    t.validate("contact")?;
    Ok(t)
}

fn friction(c: &DynamicContactSection) -> Result<Option<FrictionCoefficient>, InputError> {
    let Some(f) = &c.friction else {
        return Ok(None);
    };
    let depth = || {
        f.depth.or(c.depth).ok_or_else(|| {
            missing(
                "contact.friction.depth",
                "the depth g of (1.13) (or contact.depth)",
            )
        })
    };
    let coef = match f.law.as_str() {
        "constant" => FrictionCoefficient::Constant { mu0: f.mu0 },
        "growing" | "mu1" => FrictionCoefficient::Growing {
            mu0: f.mu0,
            depth: depth()?,
        },
        "decreasing" | "mu2" => FrictionCoefficient::Decreasing {
            mu0: f.mu0,
            depth: depth()?,
        },
        other => {
            return Err(InputError::new(
                "contact.friction.law",
                format!("\"{other}\""),
                "\"constant\", \"growing\" (μ1) or \"decreasing\" (μ2)",
            ))
        }
    };
    coef.validate("contact.friction")?;
    Ok(Some(coef))
}

fn scalar(field: &str, v: &Option<ValueSpec>) -> Result<Field, InputError> {
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

fn pair(field: &str, v: &Option<ValueSpec>) -> Result<[Field; 2], InputError> {
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

impl DynamicScene {
    /// Parses and validates a scene from TOML text; `source_name` labels errors.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Self, Error> {
        let file: DynamicSceneFile = toml::from_str(text).map_err(|e| Error::Scene {
            source_name: source_name.to_string(),
            message: e.to_string(),
        })?;
        Self::from_file(file)
    }

    /// Validates a parsed scene file.
    pub fn from_file(file: DynamicSceneFile) -> Result<Self, Error> {
        if file.model != "dynamic" {
            return Err(InputError::new("model", &file.model, "\"dynamic\"").into());
        }
        let b = &file.body;
        let given = [
            ("length", b.length.is_some()),
            ("elements", b.elements.is_some()),
            ("area", b.area.is_some()),
            ("supports", b.supports.is_some()),
            ("origin", b.origin.is_some()),
            ("size", b.size.is_some()),
            ("divisions", b.divisions.is_some()),
            ("diagonal", b.diagonal.is_some()),
            ("center", b.center.is_some()),
            ("radius", b.radius.is_some()),
            ("rings", b.rings.is_some()),
            ("inner", b.inner.is_some()),
            ("outer", b.outer.is_some()),
            ("radial", b.radial.is_some()),
            ("around", b.around.is_some()),
        ];
        let (body, contact, u0, v0) = if b.shape == "bar" {
            only("bar", &given, &["length", "elements", "area", "supports"])?;
            Self::bar(&file)?
        } else {
            let mesh = match b.shape.as_str() {
                "rectangle" => {
                    only(
                        "rectangle",
                        &given,
                        &["origin", "size", "divisions", "diagonal"],
                    )?;
                    TriangleMesh::graded_rectangle(
                        b.origin.unwrap_or([0.0, 0.0]),
                        b.size
                            .ok_or_else(|| missing("body.size", "[width, height]"))?,
                        b.divisions
                            .ok_or_else(|| missing("body.divisions", "[n_x, n_y]"))?,
                        b.diagonal.unwrap_or_default(),
                        [Grading::UNIFORM; 2],
                    )?
                }
                "disk" => {
                    only("disk", &given, &["center", "radius", "rings"])?;
                    disk(
                        b.center.ok_or_else(|| missing("body.center", "[x, y]"))?,
                        b.radius
                            .ok_or_else(|| missing("body.radius", "a radius > 0"))?,
                        b.rings
                            .ok_or_else(|| missing("body.rings", "a number of rings ≥ 1"))?,
                    )?
                }
                "annulus" => {
                    only(
                        "annulus",
                        &given,
                        &["center", "inner", "outer", "radial", "around"],
                    )?;
                    annulus(
                        b.center.ok_or_else(|| missing("body.center", "[x, y]"))?,
                        b.inner
                            .ok_or_else(|| missing("body.inner", "a radius > 0"))?,
                        b.outer
                            .ok_or_else(|| missing("body.outer", "a radius > inner"))?,
                        b.radial
                            .ok_or_else(|| missing("body.radial", "layers ≥ 1"))?,
                        b.around
                            .ok_or_else(|| missing("body.around", "cells around ≥ 3"))?,
                    )?
                }
                other => {
                    return Err(InputError::new(
                        "body.shape",
                        format!("\"{other}\""),
                        "\"bar\", \"rectangle\", \"disk\" or \"annulus\"",
                    )
                    .into())
                }
            };
            Self::plane(&file, mesh)?
        };
        let dyn_body: Arc<dyn ElasticBody> = match &body {
            SceneBody::Bar(b) => b.clone(),
            SceneBody::Plane(p) => p.clone(),
        };
        let mut newton = NewtonParams::default();
        if let Some(t) = file.solver.tolerance {
            newton.tolerance = t;
        }
        if let Some(m) = file.solver.max_iterations {
            newton.max_iterations = m;
        }
        let force_full_path = match file.solver.path.as_deref() {
            None | Some("auto") => false,
            Some("full") => true,
            Some(other) => {
                return Err(InputError::new(
                    "solver.path",
                    format!("\"{other}\""),
                    "\"auto\" or \"full\"",
                )
                .into())
            }
        };
        for (i, t) in file.output.times.iter().enumerate() {
            if !(t.is_finite() && *t >= 0.0 && *t <= file.time.final_time) {
                return Err(InputError::new(
                    format!("output.times[{i}]"),
                    t,
                    format!("a time in [0, final_time = {}]", file.time.final_time),
                )
                .into());
            }
        }
        let params = DynamicParams {
            newton,
            force_full_path,
            snapshot_times: file.output.times.clone(),
        };
        let problem = DynamicProblem {
            body: dyn_body,
            contact,
            scheme: file.time.scheme,
            final_time: file.time.final_time,
            steps: file.time.steps,
            initial_displacement: u0,
            initial_velocity: v0,
        };
        // validate everything the solver checks, now
        DynamicSolver::new(problem.clone(), params.clone())?;
        Ok(Self {
            title: file.title.clone(),
            body,
            problem,
            params,
            file,
        })
    }

    #[allow(clippy::type_complexity)]
    fn bar(
        file: &DynamicSceneFile,
    ) -> Result<(SceneBody, Option<ContactModel>, Vec<f64>, Vec<f64>), Error> {
        let b = &file.body;
        let m = &file.material;
        if m.poisson.is_some() {
            return Err(InputError::new(
                "material.poisson",
                "(given)",
                "no Poisson ratio for a bar (young only)",
            )
            .into());
        }
        let law: Arc<dyn Hyperelastic1d> = match m.law.as_str() {
            "linear" => Arc::new(LinearElastic1d { young: m.young }),
            "st_venant_kirchhoff" => Arc::new(StVenantKirchhoff1d { young: m.young }),
            other => {
                return Err(InputError::new(
                    "material.law",
                    format!("\"{other}\""),
                    "\"linear\" or \"st_venant_kirchhoff\" for a bar",
                )
                .into())
            }
        };
        let supports = b.supports.clone().unwrap_or_default();
        let mesh = IntervalMesh::uniform(
            b.length
                .ok_or_else(|| missing("body.length", "a length > 0"))?,
            b.elements
                .ok_or_else(|| missing("body.elements", "a number of elements ≥ 1"))?,
        )?;
        let nodes = mesh.nodes().to_vec();
        let body_force = match &file.body_force {
            Some(s) => scalar("body_force.value", &Some(s.value.clone()))?,
            None => Field::Constant(0.0),
        };
        let body = Arc::new(BarBody::new(BarData {
            mesh,
            density: b.density,
            area: b.area.unwrap_or(1.0),
            law,
            supports: BarSupports {
                left: supports.contains(&BarEnd::Left),
                right: supports.contains(&BarEnd::Right),
            },
            mass: b.mass,
            body_force,
        })?);
        if !file.dirichlet.is_empty() || !file.traction.is_empty() {
            return Err(InputError::new(
                "dirichlet",
                "(given)",
                "body.supports for a bar (no [[dirichlet]] or [[traction]])",
            )
            .into());
        }
        let contact = match &file.contact {
            None => None,
            Some(c) => {
                if c.level.is_some() || !c.sides.is_empty() || c.where_.is_some() {
                    return Err(InputError::new(
                        "contact.level",
                        "(given)",
                        "end and wall for a bar (level, sides, where are for plane bodies)",
                    )
                    .into());
                }
                if c.friction.is_some() {
                    return Err(InputError::new(
                        "contact.friction",
                        "(given)",
                        "no friction for a bar (no tangential direction)",
                    )
                    .into());
                }
                Some(ContactModel::bar_wall(
                    &body,
                    c.end
                        .ok_or_else(|| missing("contact.end", "\"left\" or \"right\""))?,
                    c.wall
                        .ok_or_else(|| missing("contact.wall", "the wall position x"))?,
                    treatment(c)?,
                )?)
            }
        };
        let u0f = scalar("initial.displacement", &file.initial.displacement)?;
        let v0f = scalar("initial.velocity", &file.initial.velocity)?;
        let u0: Vec<f64> = nodes.iter().map(|&x| u0f.eval(x, 0.0, 0.0)).collect();
        let v0: Vec<f64> = nodes.iter().map(|&x| v0f.eval(x, 0.0, 0.0)).collect();
        let (u0, v0) = (body.from_nodal(&u0), body.from_nodal(&v0));
        Ok((SceneBody::Bar(body), contact, u0, v0))
    }

    #[allow(clippy::type_complexity)]
    fn plane(
        file: &DynamicSceneFile,
        mesh: TriangleMesh,
    ) -> Result<(SceneBody, Option<ContactModel>, Vec<f64>, Vec<f64>), Error> {
        let m = &file.material;
        let poisson = m
            .poisson
            .ok_or_else(|| missing("material.poisson", "a Poisson ratio in (−1, 1/2)"))?;
        let law: Arc<dyn Hyperelastic2d> = match m.law.as_str() {
            "linear" => Arc::new(
                LinearElastic::from_young_poisson(m.young, poisson)
                    .map_err(|e| e.within("material"))?,
            ),
            "st_venant_kirchhoff" => Arc::new(
                StVenantKirchhoff::from_young_poisson(m.young, poisson)
                    .map_err(|e| e.within("material"))?,
            ),
            "neo_hooke" => Arc::new(
                NeoHooke::from_young_poisson(m.young, poisson).map_err(|e| e.within("material"))?,
            ),
            other => {
                return Err(InputError::new(
                    "material.law",
                    format!("\"{other}\""),
                    "\"linear\", \"st_venant_kirchhoff\" or \"neo_hooke\"",
                )
                .into())
            }
        };
        let dirichlet = file
            .dirichlet
            .iter()
            .enumerate()
            .map(|(i, d)| {
                Ok(DirichletPart {
                    boundary: selector(&format!("dirichlet[{i}]"), &d.sides, d.where_.as_ref())?,
                    support: d.support,
                })
            })
            .collect::<Result<Vec<_>, InputError>>()?;
        let traction = file
            .traction
            .iter()
            .enumerate()
            .map(|(i, t)| {
                Ok(TractionPart {
                    boundary: selector(&format!("traction[{i}]"), &t.sides, t.where_.as_ref())?,
                    traction: vector(&format!("traction[{i}].value"), &t.value)?,
                })
            })
            .collect::<Result<Vec<_>, InputError>>()?;
        let body_force = match &file.body_force {
            Some(s) => pair("body_force.value", &Some(s.value.clone()))?,
            None => [Field::Constant(0.0), Field::Constant(0.0)],
        };
        let nodes = mesh.nodes().to_vec();
        let body = Arc::new(PlaneBody::new(PlaneBodyData {
            mesh,
            density: file.body.density,
            law,
            dirichlet,
            traction,
            body_force,
            mass: file.body.mass,
        })?);
        let contact = match &file.contact {
            None => None,
            Some(c) => {
                if c.end.is_some() || c.wall.is_some() {
                    return Err(InputError::new(
                        "contact.end",
                        "(given)",
                        "level (and sides or where) for a plane body (end and wall are for bars)",
                    )
                    .into());
                }
                let boundary = if c.sides.is_empty() && c.where_.is_none() {
                    BoundarySelector::Predicate(Arc::new(|_| true))
                } else {
                    selector("contact", &c.sides, c.where_.as_ref())?
                };
                Some(ContactModel::plane_half_space(
                    &body,
                    &boundary,
                    c.level
                        .ok_or_else(|| missing("contact.level", "the foundation level y"))?,
                    treatment(c)?,
                    friction(c)?,
                )?)
            }
        };
        let u0f = pair("initial.displacement", &file.initial.displacement)?;
        let v0f = pair("initial.velocity", &file.initial.velocity)?;
        let interleave = |f: &[Field; 2]| -> Vec<f64> {
            nodes
                .iter()
                .flat_map(|p| [f[0].eval(p[0], p[1], 0.0), f[1].eval(p[0], p[1], 0.0)])
                .collect()
        };
        let (u0, v0) = (
            body.from_nodal(&interleave(&u0f)),
            body.from_nodal(&interleave(&v0f)),
        );
        Ok((SceneBody::Plane(body), contact, u0, v0))
    }

    /// The solver of the scene.
    pub fn solver(&self) -> Result<DynamicSolver, Error> {
        DynamicSolver::new(self.problem.clone(), self.params.clone())
    }

    /// Runs the scene.
    pub fn solve(&self) -> Result<DynamicSolution, Error> {
        self.solver()?.solve()
    }
}

#[cfg(test)]
mod tests {
    //! Dynamic scenes: the documented example parses and runs; misplaced and missing keys are
    //! named in the errors.
    use super::*;

    const RING: &str = r#"
model = "dynamic"
title = "ring"
[body]
shape = "annulus"
center = [0.0, 0.502]
inner = 0.3
outer = 0.5
radial = 2
around = 24
density = 1000.0
[material]
law = "neo_hooke"
young = 1e6
poisson = 0.3
[time]
final_time = 0.004
steps = 8
scheme = "gonzalez"
[initial]
velocity = [4.0, -8.0]
[contact]
level = 0.0
where = "0.502 - y"
treatment = "limited_penetration"
stiffness = 1e9
depth = 5e-4
[contact.friction]
law = "growing"
mu0 = 0.3
"#;

    #[test]
    fn ring_scene_parses_and_runs() {
        let scene = DynamicScene::from_toml_str(RING, "ring").expect("valid scene");
        let sol = scene.solve().expect("runs");
        assert_eq!(sol.audit.records.len(), 9);
        assert!(matches!(scene.body, SceneBody::Plane(_)));
    }

    #[test]
    fn key_of_another_shape_is_named() {
        let text = RING.replace("radial = 2", "radial = 2\nradius = 0.5");
        let err = DynamicScene::from_toml_str(&text, "ring").unwrap_err();
        assert!(err.to_string().contains("body.radius"), "{err}");
    }

    #[test]
    fn missing_stiffness_is_named() {
        let text = RING.replace("stiffness = 1e9\n", "");
        let err = DynamicScene::from_toml_str(&text, "ring").unwrap_err();
        assert!(err.to_string().contains("contact.stiffness"), "{err}");
    }

    #[test]
    fn newmark_with_energy_consistent_force_is_rejected() {
        let text = RING.replace("scheme = \"gonzalez\"", "scheme = \"newmark\"");
        let err = DynamicScene::from_toml_str(&text, "ring").unwrap_err();
        assert!(err.to_string().contains("scheme"), "{err}");
    }

    #[test]
    fn bar_scene_parses() {
        let text = r#"
model = "dynamic"
[body]
shape = "bar"
length = 1.0
elements = 20
supports = ["right"]
density = 1.0
[material]
law = "linear"
young = 1.0
[time]
final_time = 1.0
steps = 20
scheme = "midpoint"
[initial]
displacement = "(1 - x)/2"
[contact]
end = "left"
wall = 0.0
treatment = "signorini"
"#;
        let scene = DynamicScene::from_toml_str(text, "bar").expect("valid bar scene");
        assert!(matches!(scene.body, SceneBody::Bar(_)));
        scene.solve().expect("runs");
    }
}
