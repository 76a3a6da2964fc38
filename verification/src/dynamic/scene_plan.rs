//! The planner on a dynamic scene (`core::plan`, self-convergence; docs/planner.md §5): the
//! scene at M (its body's primary mesh count, [`BodyCounts`]), N uniform steps and a scheme,
//! its output functionals at T measured on each run.
//!
//! | functional | body | value at T |
//! |---|---|---|
//! | `rebound_velocity_y`, `rebound_velocity_x` | plane, free | the centre-of-mass velocity (1_cᵀ M v_N)/(1_cᵀ M 1_c), once the body has left the foundation |
//! | `rebound_velocity` | bar, free | the same along the bar |
//! | `contact_force` | with contact | Σ w_i N_i, the normal force the foundation (the wall) carries |
//! | `max_von_mises` | any | the largest von Mises stress of an element (a bar: max \|P\|) |
//! | `max_displacement` | plane | the largest nodal \|u_N\| |
//! | `end_displacement` | bar | u_N at the contact end (without contact: the right end) |
//!
//! The default is the rebound velocity for a free body with contact, else the largest
//! displacement (plane) or the end displacement (bar). The velocity v_N is the scheme's own:
//! Newmark's v_n, the midpoint-type schemes' δu_n. A rebound is defined once the body has left:
//! a run still in contact at T is an error that says so (the pilot's scheme is then not
//! planned).
//!
//! The schemes are those the scene's contact treatment allows: Newmark only with a treatment
//! that is not energy-consistent (the scene refuses the other combinations, BDS §1.6); for a
//! linear law the midpoint rule and Gonzalez's scheme coincide (docs/dynamic.md), and only the
//! midpoint rule is planned. All are implicit: no step bound. No order is declared: an impact's
//! regularity is the scene's (the observed orders are reported, the model's misfit is checked).
//! The work is nodes × N.

use std::fmt;

use serde::{Deserialize, Serialize};

use contactlab::material::stress_state::hyperelastic_state;
use contactlab::model::dynamic::body::ElasticBody;
use contactlab::model::dynamic::contact_model::BarEnd;
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::DynamicSolution;
use contactlab::scene::dynamic::{DynamicScene, DynamicSceneFile, SceneBody};

use crate::core::cpu_clock::min_thread_cpu_seconds;
use crate::core::plan::impact::ImpactScenePlan;
use crate::core::plan::refine::{BodyCounts, RefinedScene};
use crate::core::study::Study;
use crate::core::sweep::{Level, Measured};

/// A dynamic scheme as the planner names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct PlanScheme(pub DynamicScheme);

impl Default for PlanScheme {
    fn default() -> Self {
        Self(DynamicScheme::Midpoint)
    }
}

impl fmt::Display for PlanScheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0.name())
    }
}

/// The functionals of a dynamic scene's plan, by body (module docs).
pub const PLANE_FUNCTIONALS: [&str; 5] = [
    "rebound_velocity_y",
    "rebound_velocity_x",
    "contact_force",
    "max_von_mises",
    "max_displacement",
];
/// The functionals of a bar's plan (module docs).
pub const BAR_FUNCTIONALS: [&str; 4] = [
    "rebound_velocity",
    "contact_force",
    "max_von_mises",
    "end_displacement",
];

/// A dynamic scene as a planner's study.
pub struct DynamicScenePlan {
    /// The scene, its body's counts scaled with M.
    scene: RefinedScene,
    base: (usize, usize),
    final_time: f64,
    schemes: Vec<PlanScheme>,
    functional: String,
    /// No supports: the body's rebound is defined.
    free: bool,
    contact: bool,
    /// The bar's end whose displacement `end_displacement` is.
    end: BarEnd,
}

impl DynamicScenePlan {
    /// From a scene's table (`source` names it in errors) and the functional to plan (empty:
    /// the default of the module docs).
    ///
    /// # Errors
    /// A body the planner cannot refine (Gmsh), an invalid scene, a functional the body does not
    /// have.
    pub fn from_table(table: toml::Table, source: &str, functional: &str) -> Result<Self, String> {
        let body = table
            .get("body")
            .and_then(|b| b.as_table())
            .ok_or_else(|| format!("{source}: [body]: missing (a multibody scene's [[body]] sections are planned by the multibody family)"))?;
        // the shape first: a Gmsh scene is refused without reading its mesh
        let counts = BodyCounts::read(body, "body").map_err(|e| format!("{source}: {e}"))?;
        let refined = RefinedScene::new(table, source, vec![counts]);
        let scene = parse(&refined.table, source)?;
        let file = &scene.file;
        let bar = matches!(scene.body, SceneBody::Bar(_));
        let free = if bar {
            file.body.supports.as_ref().is_none_or(|s| s.is_empty())
        } else {
            file.dirichlet.is_empty()
        };
        let contact = scene.problem.contact.is_some();
        let energy_consistent = scene
            .problem
            .contact
            .as_ref()
            .is_some_and(|c| c.treatment.is_energy_consistent());
        let linear = scene.problem.body.is_linear();
        let mut schemes = Vec::new();
        if !energy_consistent {
            schemes.push(PlanScheme(DynamicScheme::Newmark));
        }
        schemes.push(PlanScheme(DynamicScheme::Midpoint));
        if !linear {
            schemes.push(PlanScheme(DynamicScheme::Gonzalez));
        }
        let known: &[&str] = if bar {
            &BAR_FUNCTIONALS
        } else {
            &PLANE_FUNCTIONALS
        };
        let functional = if functional.is_empty() {
            match (free && contact, bar) {
                (true, true) => "rebound_velocity",
                (true, false) => "rebound_velocity_y",
                (false, true) => "end_displacement",
                (false, false) => "max_displacement",
            }
            .to_string()
        } else {
            functional.to_string()
        };
        let available = |name: &str| match name {
            "rebound_velocity" | "rebound_velocity_x" | "rebound_velocity_y" => free && contact,
            "contact_force" => contact,
            _ => true,
        };
        if !known.contains(&functional.as_str()) || !available(&functional) {
            let have: Vec<&str> = known.iter().copied().filter(|f| available(f)).collect();
            return Err(format!(
                "{source}: --functional {functional}: expected one of {} for this {} (a rebound \
                 needs a free body with contact, a contact force a [contact] section)",
                have.join(", "),
                if bar { "bar" } else { "plane body" }
            ));
        }
        let end = file
            .contact
            .as_ref()
            .and_then(|c| c.end)
            .unwrap_or(BarEnd::Right);
        Ok(Self {
            base: (refined.m0(), file.time.steps),
            final_time: file.time.final_time,
            scene: refined,
            schemes,
            functional,
            free,
            contact,
            end,
        })
    }

    /// The functional the plan measures (the request's, or the default).
    pub fn functional(&self) -> &str {
        &self.functional
    }

    /// The same scene with the first round's finest pilot at `base` (M, N).
    pub fn with_base(self, base: (usize, usize)) -> Self {
        Self { base, ..self }
    }

    /// The scene at (M = `elements`, N = `steps`, `scheme`).
    fn scene(
        &self,
        elements: usize,
        steps: usize,
        scheme: PlanScheme,
    ) -> Result<DynamicScene, String> {
        let table = self.scene.table_at(elements, steps, scheme.0.name())?;
        parse(&table, &self.scene.source)
    }

    /// The functionals of a run at T (module docs); `where_` names the run in errors.
    fn values(
        &self,
        scene: &DynamicScene,
        sol: &DynamicSolution,
        where_: &str,
    ) -> Result<std::collections::BTreeMap<String, f64>, String> {
        let mut values = std::collections::BTreeMap::new();
        let last = sol.audit.records.last().ok_or("no step recorded")?;
        let (u, v) = (&sol.final_displacement, &sol.final_velocity);
        if self.contact {
            values.insert("contact_force".to_string(), last.contact_force);
        }
        let in_contact = last.contact_force > 0.0 || last.max_penetration > 0.0;
        let rebound = self.functional.starts_with("rebound_velocity");
        if rebound && in_contact {
            return Err(format!(
                "{}: the body is still in contact at T = {} ({where_}: Σ w N = {:.4e}, largest \
                 penetration {:.4e}); a rebound is defined once it has left — a later \
                 time.final_time, or another functional",
                self.functional, self.final_time, last.contact_force, last.max_penetration
            ));
        }
        match &scene.body {
            SceneBody::Bar(b) => {
                let (un, x) = (b.nodal(u), b.data().mesh.nodes());
                let stress = (0..un.len() - 1)
                    .map(|e| {
                        b.data()
                            .law
                            .piola(1.0 + (un[e + 1] - un[e]) / (x[e + 1] - x[e]))
                            .abs()
                    })
                    .fold(0.0, f64::max);
                values.insert("max_von_mises".into(), stress);
                let end = match self.end {
                    BarEnd::Left => un[0],
                    BarEnd::Right => un[un.len() - 1],
                };
                values.insert("end_displacement".into(), end);
                if self.free && !in_contact {
                    let ones: Vec<f64> = (0..un.len()).map(|_| 1.0).collect();
                    values.insert(
                        "rebound_velocity".into(),
                        centre_of_mass_velocity(
                            scene.problem.body.as_ref(),
                            v,
                            &b.from_nodal(&ones),
                        ),
                    );
                }
            }
            SceneBody::Plane(p) => {
                let mesh = &p.data().mesh;
                let vm = (0..mesh.triangles().len())
                    .map(|e| {
                        hyperelastic_state(p.law_of(e), &p.deformation_gradient(u, e)).von_mises()
                    })
                    .fold(0.0, f64::max);
                values.insert("max_von_mises".into(), vm);
                let un = p.nodal(u);
                values.insert(
                    "max_displacement".into(),
                    un.chunks(2).map(|c| c[0].hypot(c[1])).fold(0.0, f64::max),
                );
                if self.free && !in_contact {
                    for (c, name) in [(0, "rebound_velocity_x"), (1, "rebound_velocity_y")] {
                        let ones: Vec<f64> = (0..mesh.nodes().len())
                            .flat_map(|_| if c == 0 { [1.0, 0.0] } else { [0.0, 1.0] })
                            .collect();
                        values.insert(
                            name.into(),
                            centre_of_mass_velocity(
                                scene.problem.body.as_ref(),
                                v,
                                &p.from_nodal(&ones),
                            ),
                        );
                    }
                }
            }
        }
        if let Some((name, x)) = values.iter().find(|(_, x)| !x.is_finite()) {
            return Err(format!("{name} = {x} ({where_})"));
        }
        Ok(values)
    }
}

/// (1ᵀ M v)/(1ᵀ M 1) for the translation 1 (free dofs): the centre-of-mass velocity along it.
fn centre_of_mass_velocity(body: &dyn ElasticBody, v: &[f64], one: &[f64]) -> f64 {
    let mut m1 = vec![0.0; one.len()];
    body.pattern().symmetric_mul(body.mass(), one, &mut m1);
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    dot(&m1, v) / dot(&m1, one)
}

fn parse(table: &toml::Table, source: &str) -> Result<DynamicScene, String> {
    let file: DynamicSceneFile = table
        .clone()
        .try_into()
        .map_err(|e: toml::de::Error| format!("{source}: {e}"))?;
    DynamicScene::from_file(file).map_err(|e| format!("{source}: {e}"))
}

impl Study for DynamicScenePlan {
    type Scheme = PlanScheme;

    fn default_scheme(&self) -> PlanScheme {
        PlanScheme::default()
    }

    fn run_level(
        &self,
        elements: usize,
        steps: usize,
        scheme: PlanScheme,
        _time_error: bool,
    ) -> Result<Level, String> {
        let scene = self.scene(elements, steps, scheme)?;
        let solver = scene.solver().map_err(|e| e.to_string())?;
        let h = self.scene.h(elements);
        let k = self.final_time / steps as f64;
        let mut values = Default::default();
        let mut level = Level::timed(elements, steps, scheme, || {
            let sol = solver.solve().map_err(|e| e.to_string())?;
            values = self.values(&scene, &sol, &format!("M = {elements}, N = {steps}"))?;
            Ok::<_, String>(Measured {
                h,
                k,
                errors: Default::default(),
                u_end: values.get(&self.functional).copied().unwrap_or(0.0),
                stats: sol.stats,
            })
        })?;
        level.values = values;
        Ok(level)
    }
}

impl ImpactScenePlan for DynamicScenePlan {
    fn base(&self) -> (usize, usize) {
        self.base
    }

    fn final_time(&self) -> f64 {
        self.final_time
    }

    fn schemes(&self) -> Vec<PlanScheme> {
        self.schemes.clone()
    }

    fn refined(&self) -> &RefinedScene {
        &self.scene
    }

    fn time_loop_seconds(
        &self,
        elements: usize,
        steps: usize,
        scheme: PlanScheme,
    ) -> Result<f64, String> {
        let scene = self.scene(elements, steps, scheme)?;
        let solver = scene.solver().map_err(|e| e.to_string())?;
        min_thread_cpu_seconds(1, || solver.solve().map(|_| ()).map_err(|e| e.to_string()))
    }
}
