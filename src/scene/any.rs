//! Any scene: a file read once, its `model` key deciding which model the rest describes, and one
//! call that runs it.
//!
//! ```no_run
//! use contactlab::scene::Scene;
//! let scene = Scene::load(std::path::Path::new("examples/scenes/rod_paper_p0_6.toml"))?;
//! let solution = scene.run()?;
//! println!("{}", solution.summary());
//! # Ok::<(), contactlab::error::Error>(())
//! ```

use std::path::Path;

use serde::Serialize;

use crate::error::{Error, InputError};
use crate::model::dynamic::solver::DynamicSolution;
use crate::model::multibody::solver::MultibodySolution;
use crate::model::quasistatic::plane_output::PlaneSolution;
use crate::model::quasistatic::rod_output::RodSolution;
use crate::scene::common::scene_error;
use crate::scene::dynamic::{DynamicScene, DynamicSceneFile};
use crate::scene::moving::{DiscSceneResult, MovingScene, PlateSceneResult, StringSceneResult};
use crate::scene::multibody::{MultibodyScene, MultibodySceneFile};
use crate::scene::plane::{PlaneScene, PlaneSceneFile};
use crate::scene::rod::{RodScene, RodSceneFile};

/// The models a scene may name.
pub const MODELS: [&str; 6] = [
    "rod",
    "plane",
    "dynamic",
    "moving_string",
    "disc_particle",
    "rotating_plate",
];

/// A validated scene of any model.
#[derive(Debug)]
pub enum Scene {
    /// `model = "rod"`: the quasistatic Kelvin–Voigt rod.
    Rod(Box<RodScene>),
    /// `model = "plane"`: the quasistatic Kelvin–Voigt plane body.
    Plane(Box<PlaneScene>),
    /// `model = "dynamic"`: an elastic body against a rigid foundation.
    Dynamic(Box<DynamicScene>),
    /// `model = "dynamic"` with `[[body]]` sections: several bodies in contact
    /// ([`Scene::model`] says `"multibody"`).
    Multibody(Box<MultibodyScene>),
    /// `model = "moving_string"`, `"disc_particle"` or `"rotating_plate"`: a moving continuum.
    Moving(MovingScene),
}

/// What running a scene gives: the model's own solution type.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum Solution {
    Rod(RodSolution),
    Plane(PlaneSolution),
    Dynamic(DynamicSolution),
    Multibody(Box<MultibodySolution>),
    MovingString(StringSceneResult),
    DiscParticle(DiscSceneResult),
    RotatingPlate(Box<PlateSceneResult>),
}

impl Scene {
    /// Reads and validates the scene file at `path` (a Gmsh `file` it names is relative to the
    /// directory of `path`).
    pub fn load(path: &Path) -> Result<Self, Error> {
        let source = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| scene_error(&source, e))?;
        Self::from_toml_str(&text, &source)
    }

    /// Parses and validates a scene from TOML text; `source_name` (a file name) labels errors.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Self, Error> {
        let table: toml::Table = text.parse().map_err(|e| scene_error(source_name, e))?;
        check_magnitudes(&toml::Value::Table(table.clone()), &mut String::new())?;
        check_sections(&table)?;
        Self::from_table(table, source_name)
    }

    /// Validates a parsed scene table (read once: the `model` key chooses the format the table is
    /// deserialized into; unknown keys are errors).
    pub fn from_table(table: toml::Table, source_name: &str) -> Result<Self, Error> {
        let model = match table.get("model") {
            Some(toml::Value::String(s)) => s.clone(),
            Some(other) => {
                return Err(InputError::new(
                    "model",
                    other,
                    "a string naming the model, e.g. \"rod\"",
                )
                .into())
            }
            None => {
                return Err(InputError::new(
                    "model",
                    "(missing)",
                    "a string naming the model, e.g. model = \"rod\"",
                )
                .into())
            }
        };
        let parse = |e: toml::de::Error| scene_error(source_name, e);
        Ok(match model.as_str() {
            "rod" => {
                let file: RodSceneFile = table.try_into().map_err(parse)?;
                Scene::Rod(Box::new(RodScene::from_file(file)?))
            }
            "plane" => {
                let mut file: PlaneSceneFile = table.try_into().map_err(parse)?;
                file.base_dir = scene_dir(source_name);
                Scene::Plane(Box::new(PlaneScene::from_file(file)?))
            }
            // several bodies: `[[body]]`, an array of tables
            "dynamic" if table.get("body").is_some_and(toml::Value::is_array) => {
                let mut file: MultibodySceneFile = table.try_into().map_err(parse)?;
                file.base_dir = scene_dir(source_name);
                Scene::Multibody(Box::new(MultibodyScene::from_file(file)?))
            }
            "dynamic" => {
                let mut file: DynamicSceneFile = table.try_into().map_err(parse)?;
                file.base_dir = scene_dir(source_name);
                Scene::Dynamic(Box::new(DynamicScene::from_file(file)?))
            }
            "multibody" => {
                return Err(InputError::new(
                    "model",
                    "\"multibody\"",
                    "\"dynamic\" (a dynamic scene whose bodies are [[body]] sections is a \
                     multibody scene)",
                )
                .into())
            }
            "moving_string" | "disc_particle" | "rotating_plate" => {
                Scene::Moving(MovingScene::from_table(table, source_name)?)
            }
            other => {
                return Err(InputError::new(
                    "model",
                    format!("\"{other}\""),
                    format!("one of {}", MODELS.map(|m| format!("\"{m}\"")).join(", ")),
                )
                .into())
            }
        })
    }

    /// The scene's model, as its file names it — except a dynamic scene of `[[body]]` sections,
    /// which is `"multibody"` (the family that writes its results).
    pub fn model(&self) -> &'static str {
        match self {
            Scene::Rod(_) => "rod",
            Scene::Plane(_) => "plane",
            Scene::Dynamic(_) => "dynamic",
            Scene::Multibody(_) => "multibody",
            Scene::Moving(MovingScene::String(_)) => "moving_string",
            Scene::Moving(MovingScene::Disc(_)) => "disc_particle",
            Scene::Moving(MovingScene::Plate(_)) => "rotating_plate",
        }
    }

    /// The scene's title (empty when it has none).
    pub fn title(&self) -> &str {
        match self {
            Scene::Rod(s) => &s.title,
            Scene::Plane(s) => &s.title,
            Scene::Dynamic(s) => &s.title,
            Scene::Multibody(s) => &s.title,
            Scene::Moving(MovingScene::String(s)) => &s.title,
            Scene::Moving(MovingScene::Disc(s)) => &s.title,
            Scene::Moving(MovingScene::Plate(s)) => &s.title,
        }
    }

    /// Runs the scene: the whole time loop (with the scene's outputs) or the eigenvalue analysis.
    pub fn run(&self) -> Result<Solution, Error> {
        Ok(match self {
            Scene::Rod(s) => Solution::Rod(s.solver()?.solve(&s.output)?),
            Scene::Plane(s) => Solution::Plane(s.solver()?.solve(&s.output)?),
            Scene::Dynamic(s) => Solution::Dynamic(s.solve()?),
            Scene::Multibody(s) => Solution::Multibody(Box::new(s.solve()?)),
            Scene::Moving(MovingScene::String(s)) => Solution::MovingString(s.run()?),
            Scene::Moving(MovingScene::Disc(s)) => Solution::DiscParticle(s.run()?),
            Scene::Moving(MovingScene::Plate(s)) => Solution::RotatingPlate(Box::new(s.run()?)),
        })
    }
}

impl Solution {
    /// The model of the scene that gave it.
    pub fn model(&self) -> &'static str {
        match self {
            Solution::Rod(_) => "rod",
            Solution::Plane(_) => "plane",
            Solution::Dynamic(_) => "dynamic",
            Solution::Multibody(_) => "multibody",
            Solution::MovingString(_) => "moving_string",
            Solution::DiscParticle(_) => "disc_particle",
            Solution::RotatingPlate(_) => "rotating_plate",
        }
    }

    /// A one-line summary of what was computed.
    pub fn summary(&self) -> String {
        match self {
            Solution::Rod(s) => format!(
                "rod, {} scheme, M = {}, N = {}: u_h(L, T) = {:.12e}, {} Newton iterations",
                s.scheme,
                s.nodes.len().saturating_sub(1),
                s.times.len().saturating_sub(1),
                s.end_displacement.last().copied().unwrap_or(f64::NAN),
                s.stats.newton_iterations
            ),
            Solution::Plane(s) => format!(
                "plane body, {} path, {} dofs, {} steps, {} Newton iterations",
                s.stats.path, s.stats.dofs, s.stats.steps, s.stats.newton_iterations
            ),
            Solution::Dynamic(s) => format!(
                "dynamic body, {} steps, {} Newton iterations",
                s.stats.steps, s.stats.newton_iterations
            ),
            Solution::Multibody(s) => {
                let a = s.summary();
                format!(
                    "multibody, {} steps, {} unknowns, {} Newton iterations: energy drift {:.3e}, \
                     activation work {:.3e}, friction work {:.3e}",
                    s.stats.steps,
                    s.stats.unknowns,
                    s.stats.newton_iterations,
                    a.energy_drift,
                    a.activation_work,
                    a.friction_work
                )
            }
            Solution::MovingString(r) => format!(
                "moving string, {} eigenvalues: {:?} (max Re λ = {:.6e})",
                r.eigenvalues.len(),
                r.assessment.verdict,
                r.assessment.max_real_part
            ),
            Solution::DiscParticle(r) => format!(
                "disc particle: {:?} (max Re λ = {:.6e})",
                r.point.assessment.verdict, r.point.assessment.max_real_part
            ),
            Solution::RotatingPlate(r) => format!(
                "rotating plate, {} eigenvalues at Ω = {}: {:?} (max Re λ = {:.6e}), lowest \
                 critical speed {}",
                r.eigenvalues.len(),
                r.angular_speed,
                r.assessment.verdict,
                r.assessment.max_real_part,
                r.harmonics
                    .iter()
                    .flat_map(|h| h.critical_speeds.first().copied())
                    .min_by(f64::total_cmp)
                    .map_or("(none: N = 0)".to_string(), |w| format!("{w:.6}"))
            ),
        }
    }
}

/// The keys of the scene formats that hold a table (a `[section]` or an inline `{ … }`), or for
/// the repeated ones an array of tables.
const TABLE_KEYS: [&str; 26] = [
    "body",
    "body_force",
    "contact",
    "contact.friction",
    "discretization",
    "elasticity",
    "exact",
    "foundation",
    "geometry",
    "initial",
    "map",
    "map.x",
    "map.y",
    "material",
    "mesh",
    "oscillator",
    "output",
    "pad",
    "particle",
    "plate",
    "rod",
    "solver",
    "stability",
    "string",
    "time",
    "viscosity",
];

/// Keys whose arrays of tables are the repeated sections (`[[sweep]]`).
const REPEATED_KEYS: [&str; 4] = ["dirichlet", "traction", "sweep", "contact_pair"];

/// Keys that are a table in one format and an array of tables in another: `body` (the one-body
/// dynamic scene's `[body]`, the multibody scene's `[[body]]`).
const TABLE_OR_REPEATED_KEYS: [&str; 1] = ["body"];

/// In each table of the arrays `[[body]]` and `[[contact_pair]]`: the keys that hold a table
/// (`body[0].material`) and those that hold an array of tables (`[[body.dirichlet]]`).
const NESTED_TABLE_KEYS: [&str; 4] = ["material", "slave", "master", "foundation"];
const NESTED_REPEATED_KEYS: [&str; 2] = ["dirichlet", "traction"];

/// The directory of the scene file `source_name`, which the Gmsh files it names are relative to
/// (`None` for a name without a directory: the working directory).
fn scene_dir(source_name: &str) -> Option<std::path::PathBuf> {
    Path::new(source_name)
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .map(Path::to_path_buf)
}

/// What a section key must hold.
#[derive(Clone, Copy, PartialEq)]
enum SectionKind {
    Table,
    Tables,
    TableOrTables,
}

/// Checks that the section `path` (as written: `body[0].material`) holds what `kind` says.
fn section(path: &str, kind: SectionKind, v: &toml::Value) -> Result<(), Error> {
    let tables =
        |v: &toml::Value| matches!(v, toml::Value::Array(a) if a.iter().all(toml::Value::is_table));
    let ok = match kind {
        SectionKind::Table => v.is_table(),
        SectionKind::Tables => tables(v),
        SectionKind::TableOrTables => v.is_table() || tables(v),
    };
    if ok {
        return Ok(());
    }
    let header = path.replace(|c: char| c == '[' || c.is_ascii_digit() || c == ']', "");
    let expected = match kind {
        SectionKind::Tables => format!("tables: [[{header}]] sections"),
        SectionKind::Table => {
            format!("a table: a [{header}] section or {path} = {{ key = value, … }}")
        }
        SectionKind::TableOrTables => format!(
            "a table (a [{header}] section: one body) or tables ([[{header}]] sections: several \
             bodies)"
        ),
    };
    Err(InputError::new(path, v, expected).into())
}

/// A section written as something else is refused: serde would read `string = [0.5, 0.05]` as
/// the fields of `[string]` in order, silently.
fn check_sections(table: &toml::Table) -> Result<(), Error> {
    for (k, v) in table {
        let key = k.as_str();
        if TABLE_OR_REPEATED_KEYS.contains(&key) {
            section(k, SectionKind::TableOrTables, v)?;
        } else if REPEATED_KEYS.contains(&key) {
            section(k, SectionKind::Tables, v)?;
        } else if TABLE_KEYS.contains(&key) {
            section(k, SectionKind::Table, v)?;
        }
        match v {
            toml::Value::Table(inner) => {
                for (k2, v2) in inner {
                    let path = format!("{k}.{k2}");
                    if TABLE_KEYS.contains(&path.as_str()) {
                        section(&path, SectionKind::Table, v2)?;
                    }
                }
            }
            // the tables of [[body]] and [[contact_pair]]
            toml::Value::Array(a) if matches!(key, "body" | "contact_pair") => {
                for (i, t) in a.iter().enumerate() {
                    let Some(t) = t.as_table() else { continue };
                    for (k2, v2) in t {
                        let path = format!("{k}[{i}].{k2}");
                        if NESTED_TABLE_KEYS.contains(&k2.as_str()) {
                            section(&path, SectionKind::Table, v2)?;
                        } else if NESTED_REPEATED_KEYS.contains(&k2.as_str()) {
                            section(&path, SectionKind::Tables, v2)?;
                        }
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// The largest magnitude a number of a scene file may have, and (besides 0) the smallest.
///
/// A scene's numbers meet in products — moduli times lengths, loads times lengths squared over
/// moduli, masses times speeds squared — and a product of three factors beyond 1e150 (or below
/// 1e-150) leaves the double range, so the run would fill with ∞ or 0 long after the input was
/// read. Such inputs are refused up front, the key named; the solvers still stop at the first
/// non-finite value of what a scene within these bounds computes.
pub const MAX_MAGNITUDE: f64 = 1e150;

/// Every float of a scene file is finite and, unless 0, of magnitude within
/// [1/[`MAX_MAGNITUDE`], [`MAX_MAGNITUDE`]]; `path` is the key as written (`body.density`).
fn check_magnitudes(v: &toml::Value, path: &mut String) -> Result<(), Error> {
    match v {
        toml::Value::Float(x) => {
            let m = x.abs();
            if !x.is_finite() || m > MAX_MAGNITUDE || (m > 0.0 && m < 1.0 / MAX_MAGNITUDE) {
                return Err(InputError::new(
                    path.as_str(),
                    x,
                    "a finite number of magnitude between 1e-150 and 1e150 (or 0): beyond, the \
                     products of moduli, lengths and loads leave the range of doubles",
                )
                .into());
            }
            Ok(())
        }
        toml::Value::Table(t) => {
            for (k, x) in t {
                let len = path.len();
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(k);
                check_magnitudes(x, path)?;
                path.truncate(len);
            }
            Ok(())
        }
        toml::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                let len = path.len();
                path.push_str(&format!("[{i}]"));
                check_magnitudes(x, path)?;
                path.truncate(len);
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    //! Every example scene loads under its model; an unknown or missing model is a typed error
    //! naming the field; a small rod scene runs to the paper's pinned end displacement.
    use super::*;

    fn examples() -> Vec<std::path::PathBuf> {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
        let mut v: Vec<_> = std::fs::read_dir(dir)
            .expect("examples/scenes")
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .collect();
        v.sort();
        v
    }

    #[test]
    fn every_example_scene_loads_under_the_model_it_names() {
        let files = examples();
        assert!(files.len() >= 10);
        for f in files {
            let text = std::fs::read_to_string(&f).expect("readable");
            let table: toml::Table = text.parse().expect("TOML");
            let mut named = table["model"].as_str().expect("model").to_string();
            // a dynamic scene of [[body]] sections is the multibody model
            if named == "dynamic" && table.get("body").is_some_and(toml::Value::is_array) {
                named = "multibody".into();
            }
            let scene = Scene::load(&f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
            assert_eq!(scene.model(), named, "{}", f.display());
        }
    }

    #[test]
    fn an_unknown_or_missing_model_is_an_error_naming_the_field() {
        let e = Scene::from_toml_str("model = \"gel\"\n", "x.toml").expect_err("unknown");
        let s = e.to_string();
        assert!(
            s.contains("model") && s.contains("gel") && s.contains("\"rod\""),
            "{s}"
        );
        let e = Scene::from_toml_str("title = \"t\"\n", "x.toml").expect_err("missing");
        assert!(e.to_string().contains("model"), "{e}");
        let e = Scene::from_toml_str("model = 3\n", "x.toml").expect_err("not a string");
        assert!(e.to_string().contains("model"), "{e}");
    }

    #[test]
    fn a_rod_scene_runs_and_its_solution_serializes_with_its_model() {
        let scene = Scene::from_toml_str(
            "model = \"rod\"\n[rod]\nlength = 1.0\nfinal_time = 0.1\nviscosity = 1.0\n\
             elasticity = 1.0\nload = 10.0\n[foundation]\nlaw = \"linear\"\nbeta = 1.0\n\
             [mesh]\nelements = 10\n[time]\nsteps = 5\n",
            "small.toml",
        )
        .expect("valid");
        let solution = scene.run().expect("runs");
        assert_eq!(solution.model(), "rod");
        let json = serde_json::to_value(&solution).expect("serializes");
        assert_eq!(json["model"], "rod");
        assert!(
            solution.summary().contains("M = 10, N = 5"),
            "{}",
            solution.summary()
        );
    }
}
