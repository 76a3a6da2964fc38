//! The planner on a multibody scene (`core::plan`, self-convergence; docs/planner.md §5): the
//! `[[body]]` sections refined together — M is the first body's primary mesh count and every
//! body's counts scale with it ([`BodyCounts`]) — with N uniform steps and a scheme; the output
//! functionals at T measured on each run:
//!
//! | functional | value at T |
//! |---|---|
//! | `velocity_x.NAME`, `velocity_y.NAME` | body NAME's centre-of-mass velocity Σ_I (M v)_I / m (its rebound once the bodies have separated) |
//! | `contact_force` | Σ λ_N over every pair's candidates (with penalty enforcement Σ ε g₋) |
//! | `max_von_mises` | the largest von Mises stress of a triangle of any body |
//! | `max_displacement` | the largest nodal \|u_N\| of any body |
//!
//! The default is the first body's `velocity_x`. The schemes are those the scene validates with
//! (Newmark, the midpoint rule, the energy–momentum scheme), all implicit; no order is declared
//! (an impact's regularity is the scene's). The work is the total node count × N.

use std::fmt;

use serde::{Deserialize, Serialize};

use contactlab::material::stress_state::hyperelastic_state;
use contactlab::model::multibody::scheme::MultibodyScheme;
use contactlab::model::multibody::solver::{MultibodySolution, MultibodyStepView};
use contactlab::scene::multibody::{MultibodyScene, MultibodySceneFile};

use crate::core::cpu_clock::min_thread_cpu_seconds;
use crate::core::overrides;
use crate::core::plan::impact::ImpactScenePlan;
use crate::core::plan::refine::{BodyCounts, RefinedScene};
use crate::core::study::Study;
use crate::core::sweep::{Level, Measured};
use crate::multibody::errors::centre_velocity;
use crate::multibody::scene::normal_force;

/// A multibody scheme as the planner names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct PlanScheme(pub MultibodyScheme);

impl Default for PlanScheme {
    fn default() -> Self {
        Self(MultibodyScheme::EnergyMomentum)
    }
}

impl fmt::Display for PlanScheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0.name())
    }
}

/// A multibody scene as a planner's study.
pub struct MultibodyScenePlan {
    /// The scene, every body's counts scaled with M.
    scene: RefinedScene,
    names: Vec<String>,
    base: (usize, usize),
    final_time: f64,
    schemes: Vec<PlanScheme>,
    functional: String,
}

impl MultibodyScenePlan {
    /// From a scene's table (`source` names it in errors) and the functional to plan (empty:
    /// the first body's `velocity_x`).
    ///
    /// # Errors
    /// A body the planner cannot refine (Gmsh), an invalid scene, an unknown functional.
    pub fn from_table(table: toml::Table, source: &str, functional: &str) -> Result<Self, String> {
        let sections = table
            .get("body")
            .and_then(|b| b.as_array())
            .ok_or_else(|| format!("{source}: [[body]]: missing"))?;
        let counts = sections
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let prefix = format!("body[{i}]");
                b.as_table()
                    .ok_or_else(|| format!("{prefix}: expected a table"))
                    .and_then(|t| BodyCounts::read(t, &prefix))
            })
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| format!("{source}: {e}"))?;
        let refined = RefinedScene::new(table, source, counts);
        let scene = parse(&refined.table, source)?;
        let file = &scene.file;
        // the schemes the scene's pairs allow: each validated at the scene's resolution
        let mut schemes = Vec::new();
        for s in MultibodyScheme::ALL {
            let mut set = toml::Table::new();
            set.insert("time.scheme".into(), toml::Value::String(s.name().into()));
            let t = overrides::applied(&refined.table, &set).map_err(|e| e.to_string())?;
            if parse(&t, source).is_ok() {
                schemes.push(PlanScheme(s));
            }
        }
        let names = scene.names.clone();
        let mut known: Vec<String> = names
            .iter()
            .flat_map(|n| [format!("velocity_x.{n}"), format!("velocity_y.{n}")])
            .collect();
        known.extend(
            ["contact_force", "max_von_mises", "max_displacement"]
                .iter()
                .map(|s| s.to_string()),
        );
        let functional = if functional.is_empty() {
            known[0].clone()
        } else {
            functional.to_string()
        };
        if !known.contains(&functional) {
            return Err(format!(
                "{source}: --functional {functional}: expected one of {}",
                known.join(", ")
            ));
        }
        Ok(Self {
            base: (refined.m0(), file.time.steps),
            final_time: file.time.final_time,
            scene: refined,
            names,
            schemes,
            functional,
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
    ) -> Result<MultibodyScene, String> {
        let table = self.scene.table_at(elements, steps, scheme.0.name())?;
        parse(&table, &self.scene.source)
    }

    /// The functionals at T (module docs) of a run whose last contacts gave `contact_force`.
    fn values(
        &self,
        scene: &MultibodyScene,
        sol: &MultibodySolution,
        contact_force: f64,
        where_: &str,
    ) -> Result<std::collections::BTreeMap<String, f64>, String> {
        let bodies = &scene.problem.bodies;
        let (u, v) = (&sol.final_displacement, &sol.final_velocity);
        let mut scratch = vec![0.0; bodies.dofs()];
        let mut values = std::collections::BTreeMap::new();
        for (b, name) in self.names.iter().enumerate() {
            let c = centre_velocity(bodies, b, v, &mut scratch);
            values.insert(format!("velocity_x.{name}"), c[0]);
            values.insert(format!("velocity_y.{name}"), c[1]);
        }
        values.insert("contact_force".into(), contact_force);
        let (mut vm, mut um) = (0.0f64, 0.0f64);
        for (b, body) in bodies.bodies().iter().enumerate() {
            let ub = &u[bodies.range(b)];
            for e in 0..body.elements().len() {
                let f = body.deformation_gradient(ub, e);
                vm = vm.max(hyperelastic_state(body.law_of(e), &f).von_mises());
            }
            let un = body.nodal(ub);
            um = un.chunks(2).map(|c| c[0].hypot(c[1])).fold(um, f64::max);
        }
        values.insert("max_von_mises".into(), vm);
        values.insert("max_displacement".into(), um);
        if let Some((name, x)) = values.iter().find(|(_, x)| !x.is_finite()) {
            return Err(format!("{name} = {x} ({where_})"));
        }
        Ok(values)
    }
}

fn parse(table: &toml::Table, source: &str) -> Result<MultibodyScene, String> {
    let file: MultibodySceneFile = table
        .clone()
        .try_into()
        .map_err(|e: toml::de::Error| format!("{source}: {e}"))?;
    MultibodyScene::from_file(file).map_err(|e| format!("{source}: {e}"))
}

impl Study for MultibodyScenePlan {
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
            let mut force = 0.0;
            let sol = solver
                .solve_with(&mut |view: &MultibodyStepView<'_>| {
                    force = view.contacts.iter().map(|c| normal_force(&scene, c)).sum();
                })
                .map_err(|e| e.to_string())?;
            values = self.values(&scene, &sol, force, &format!("M = {elements}, N = {steps}"))?;
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

impl ImpactScenePlan for MultibodyScenePlan {
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
