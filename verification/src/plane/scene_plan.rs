//! The planner on a plane scene without an exact solution (`core::plan`, self-convergence):
//! the scene at (n_x = M, n_y in the scene's aspect, N uniform steps, scheme), its output
//! functionals at T measured on each run:
//!
//! - `contact_force`: Σ_i W_i p_ν(x_i) over the contact points at T (the force the foundation
//!   carries, per unit thickness);
//! - `max_von_mises`: the largest von Mises stress of a triangle at T;
//! - `max_displacement`: the largest nodal |u_N|.
//!
//! The explicit scheme's bound is 2 / the largest constitutive ratio of its regions' linear laws
//! (docs/quasistatic.md, stability note); a nonlinear law has no known bound and the explicit
//! scheme is then not planned.

use contactlab::model::quasistatic::plane_output::PlaneOutputRequest;
use contactlab::model::quasistatic::plane_stability::constitutive_ratio;
use contactlab::model::quasistatic::plane_step::PlaneStep;
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::scene::plane::{PlaneScene, PlaneSceneFile};

use crate::core::cpu_clock::min_thread_cpu_seconds;
use crate::core::overrides;
use crate::core::plan::{value_floor, Plannable};
use crate::core::study::Study;
use crate::core::sweep::{Level, Measured};

/// The functionals a plane scene's plan may name.
pub const PLANE_SCENE_FUNCTIONALS: [&str; 3] =
    ["contact_force", "max_von_mises", "max_displacement"];

/// A plane scene as a planner's study.
pub struct PlaneScenePlan {
    /// The scene's table (every run overrides its divisions, steps and scheme).
    table: toml::Table,
    source: String,
    /// n_y / n_x of the scene.
    aspect: f64,
    base: (usize, usize),
    final_time: f64,
    bound: Option<f64>,
}

impl PlaneScenePlan {
    /// From a scene's text (`source` names it in errors): a rectangle (`geometry.divisions`) on
    /// a uniform grid (`time.steps`).
    pub fn from_text(text: &str, source: &str) -> Result<Self, String> {
        let table: toml::Table = toml::from_str(text).map_err(|e| format!("{source}: {e}"))?;
        Self::from_table(table, source)
    }

    /// From a scene's table ([`Self::from_text`]).
    pub fn from_table(mut table: toml::Table, source: &str) -> Result<Self, String> {
        // the shape first: a Gmsh scene's mesh file is not read for nothing
        let shape = table
            .get("geometry")
            .and_then(|g| g.get("shape"))
            .and_then(|s| s.as_str())
            .unwrap_or("rectangle");
        if shape != "rectangle" {
            return Err(format!(
                "{source}: geometry.shape = \"{shape}\": the planner refines geometry.divisions \
                 of a rectangle; a Gmsh mesh cannot be refined by it"
            ));
        }
        let scene = parse(&table, source)?;
        let g = &scene.file.geometry;
        let [nx, ny] = g
            .divisions
            .ok_or_else(|| format!("{source}: geometry.divisions: missing"))?;
        if scene.file.time.times.is_some() {
            return Err(format!(
                "{source}: time.times: the planner varies a uniform grid (time.steps), not a \
                 list of times"
            ));
        }
        // every run records the state at T only (the scene's snapshot times need not be times
        // of the planner's grids)
        let _ = overrides::remove(&mut table, "output");
        let a = scene.problem.viscosity.as_linear();
        let b = scene.problem.elasticity.as_linear();
        let mut ratio = match (a, b) {
            (Some(a), Some(b)) => Some(constitutive_ratio(a, b)),
            _ => None,
        };
        for r in &scene.problem.regions {
            ratio = match (ratio, r.viscosity.as_linear(), r.elasticity.as_linear()) {
                (Some(x), Some(a), Some(b)) => Some(x.max(constitutive_ratio(a, b))),
                _ => None,
            };
        }
        Ok(Self {
            table,
            source: source.to_string(),
            aspect: ny as f64 / nx as f64,
            base: (nx, scene.grid.steps()),
            final_time: scene.grid.final_time(),
            bound: Some(ratio.map_or(0.0, |r| 2.0 / r)),
        })
    }

    /// The same scene with the first round's finest pilot at `base` (n_x, N).
    pub fn with_base(self, base: (usize, usize)) -> Self {
        Self { base, ..self }
    }

    /// The scene at (n_x = `elements`, N = `steps`, `scheme`).
    fn scene(
        &self,
        elements: usize,
        steps: usize,
        scheme: TimeScheme,
    ) -> Result<PlaneScene, String> {
        let ny = ((elements as f64 * self.aspect).round() as usize).max(1);
        let mut set = toml::Table::new();
        let int = |v: usize| toml::Value::Integer(v as i64);
        set.insert(
            "geometry.divisions".into(),
            toml::Value::Array(vec![int(elements), int(ny)]),
        );
        set.insert("time.steps".into(), int(steps));
        set.insert(
            "time.scheme".into(),
            toml::Value::String(scheme.name().into()),
        );
        let table = overrides::applied(&self.table, &set).map_err(|e| e.to_string())?;
        parse(&table, &self.source)
    }
}

fn parse(table: &toml::Table, source: &str) -> Result<PlaneScene, String> {
    let file: PlaneSceneFile = table
        .clone()
        .try_into()
        .map_err(|e: toml::de::Error| format!("{source}: {e}"))?;
    PlaneScene::from_file(file).map_err(|e| format!("{source}: {e}"))
}

impl Study for PlaneScenePlan {
    type Scheme = TimeScheme;

    fn default_scheme(&self) -> TimeScheme {
        TimeScheme::default()
    }

    fn run_level(
        &self,
        elements: usize,
        steps: usize,
        scheme: TimeScheme,
        _time_error: bool,
    ) -> Result<Level, String> {
        let scene = self.scene(elements, steps, scheme)?;
        let mut solver = scene.solver().map_err(|e| e.to_string())?;
        let request = PlaneOutputRequest {
            snapshot_times: vec![scene.grid.final_time()],
        };
        let h = scene.problem.mesh.h_max();
        let k = scene.grid.k_max();
        let mut values = std::collections::BTreeMap::new();
        let mut level = Level::timed(elements, steps, scheme, || {
            let sol = solver.solve(&request).map_err(|e| e.to_string())?;
            let last = sol.snapshots.last().ok_or("no state at T")?;
            let max_abs = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let u_max = last
                .u
                .chunks(2)
                .map(|c| c[0].hypot(c[1]))
                .fold(0.0f64, f64::max);
            values.insert(
                "contact_force".to_string(),
                sol.contact_force.last().copied().unwrap_or(0.0),
            );
            values.insert("max_von_mises".to_string(), max_abs(&last.von_mises));
            values.insert("max_displacement".to_string(), u_max);
            Ok::<_, String>(Measured {
                h,
                k,
                errors: Default::default(),
                u_end: u_max,
                stats: sol.stats.clone(),
            })
        })?;
        if let Some((name, v)) = values.iter().find(|(_, v)| !v.is_finite()) {
            return Err(format!("{name} = {v} at M = {elements}, N = {steps}"));
        }
        level.values = values;
        Ok(level)
    }
}

impl Plannable for PlaneScenePlan {
    fn base(&self) -> (usize, usize) {
        self.base
    }

    fn final_time(&self) -> f64 {
        self.final_time
    }

    fn schemes(&self) -> Vec<TimeScheme> {
        TimeScheme::ALL.to_vec()
    }

    fn stability_bound(&self, scheme: TimeScheme) -> Option<f64> {
        (scheme == TimeScheme::Explicit)
            .then_some(self.bound)
            .flatten()
    }

    /// In k (the data are smooth in time): the contact force and the von Mises stress at T
    /// carry the velocity w_N (the damper, the viscous stress), first order for every scheme;
    /// the displacement at T is first order for θ = 0, 1 and second order for the midpoint
    /// scheme. In h: the nodal displacement of P1 elements is second order where the solution
    /// is smooth (Test 2D's pilots at n ≤ 24 show 1.23, and runs up to n = 280 show the order
    /// rising through 1.6, 1.8 to 2.1: pre-asymptotic pilots, which the check refuses). The
    /// contact force and the largest von Mises stress depend on the regularity near the ends
    /// of the contact zone and at the corners (Test 2D: p ≈ 0.57 for the von Mises maximum, a
    /// corner singularity): not checked.
    fn expected_orders(&self, scheme: TimeScheme, functional: &str) -> (Option<f64>, Option<f64>) {
        match functional {
            "contact_force" | "max_von_mises" => (None, Some(1.0)),
            "max_displacement" => (
                Some(2.0),
                Some(if scheme == TimeScheme::Midpoint {
                    2.0
                } else {
                    1.0
                }),
            ),
            _ => (None, None),
        }
    }

    fn seconds(&self, elements: usize, steps: usize, scheme: TimeScheme) -> Result<f64, String> {
        let scene = self.scene(elements, steps, scheme)?;
        min_thread_cpu_seconds(3, || {
            let mut solver = scene.solver().map_err(|e| e.to_string())?;
            let mut sink = 0.0;
            solver
                .run(&mut |s: &PlaneStep<'_>| {
                    sink += s.contact_pressure.first().copied().unwrap_or(0.0)
                })
                .map_err(|e| e.to_string())?;
            std::hint::black_box(sink);
            Ok(())
        })
    }

    /// n_x n_y N (the plane's step costs O(dofs) with the factors of the condensed path).
    fn work(&self, elements: usize, steps: usize) -> f64 {
        let ny = ((elements as f64 * self.aspect).round()).max(1.0);
        elements as f64 * ny * steps as f64
    }

    fn work_label(&self) -> &'static str {
        "n_x n_y N"
    }

    /// 100 ε times the largest magnitude of the functional over the pilots.
    fn floor(&self, functional: &str, pilots: &[Level]) -> f64 {
        value_floor(functional, pilots)
    }
}
