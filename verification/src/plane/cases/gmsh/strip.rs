//! Part 3 of `plane_gmsh`: the two-material strip. A plane scene on the Gmsh file `[strip] mesh`
//! (the strip (0, 2L) × (0, H), 2D groups for the two materials, boundary groups `left`,
//! `bottom`, `right`), written here from the closed form's constants and validated by the solver
//! crate as a user's scene: `shape = "gmsh"`, the first material as the scene's `[viscosity]` and
//! `[elasticity]`, the second as a `[[region]]` on the group `second_region`, `fix_x` on
//! `left`, `fix_y` on `bottom`, the traction (t0, 0) on `right`, the implicit scheme. Every
//! snapshot against u_n = (1 − r^n) u_s of [`crate::exact::bimaterial_strip`], which lies in the
//! P1 space (the interface is a mesh line) and solves the implicit steps exactly.
//!
//! **Bound.** Only round-off separates the two: each implicit step solves
//! (τ/k + 1) K_B u_n = …, which errs by c ε κ ‖u‖ (κ = κ₂((τ + k) K_B), computed,
//! [`super::conditioning`]); the recursion u_n − u_s = r (u_{n−1} − u_s) carries earlier errors
//! with the factor r < 1, so after n steps
//!
//!   max_i |u_n − (1 − r^n) u_s| ≤ c ε κ n max|u_s|,
//!
//! c = `round_off_factor`. A triangle with the wrong material (a wrong element → region map), a
//! support or traction on the wrong group, or a wrong law gives an error of the order of the
//! solution.

use serde::Deserialize;

use contactlab::scene::plane::{PlaneScene, PlaneSceneFile};

use crate::core::format::{invalid, positive, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::exact::bimaterial_strip::{BimaterialStrip, IsotropicConstants};
use crate::plane::cases::gmsh::conditioning::step_condition_number;
use crate::plane::cases::gmsh::files::repository_root;

/// (a1, a2) of an isotropic law in the case file.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Constants {
    pub a1: f64,
    pub a2: f64,
}

/// `[strip]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StripSpec {
    /// The mesh file (relative to the repository root).
    pub mesh: String,
    /// L: the interface x = L, a mesh line.
    pub interface: f64,
    /// B on x < L (the scene's default law).
    pub first: Constants,
    /// B on x > L (a `[[region]]`).
    pub second: Constants,
    /// The 2D group of the second material.
    pub second_region: String,
    /// τ: A = τ B in both materials.
    pub relaxation_time: f64,
    /// t0 of the end traction (t0, 0).
    pub traction: f64,
    pub final_time: f64,
    pub steps: usize,
    /// c of the bound c ε κ n max|u_s|.
    pub round_off_factor: f64,
}

impl StripSpec {
    /// The closed form of these constants.
    fn exact(&self) -> Result<BimaterialStrip, String> {
        let c = |k: Constants| IsotropicConstants { a1: k.a1, a2: k.a2 };
        BimaterialStrip::new(
            self.interface,
            c(self.first),
            c(self.second),
            self.traction,
            self.relaxation_time,
        )
    }

    /// Checks the numbers and the materials' compatibility.
    pub fn check(&self, path: &std::path::Path) -> Result<(), CaseError> {
        for (field, v) in [
            ("strip.interface", self.interface),
            ("strip.first.a2", self.first.a2),
            ("strip.second.a2", self.second.a2),
            ("strip.relaxation_time", self.relaxation_time),
            ("strip.final_time", self.final_time),
            ("strip.round_off_factor", self.round_off_factor),
        ] {
            positive(path, field, v)?;
        }
        if self.steps == 0 {
            return Err(invalid(path, "strip.steps", 0, "≥ 1"));
        }
        self.exact()
            .map(|_| ())
            .map_err(|e| invalid(path, "strip.second", "(a1, a2)", &e))
    }

    /// The scene, as a user would write it.
    fn scene(&self) -> Result<PlaneScene, String> {
        let law = |c: Constants, scale: f64| {
            let mut t = toml::Table::new();
            t.insert("law".into(), "isotropic".into());
            t.insert("a1".into(), (scale * c.a1).into());
            t.insert("a2".into(), (scale * c.a2).into());
            toml::Value::Table(t)
        };
        let tau = self.relaxation_time;
        let part = |group: &str, key: &str, value: toml::Value| {
            let mut t = toml::Table::new();
            t.insert("group".into(), group.into());
            t.insert(key.into(), value);
            toml::Value::Table(t)
        };
        let mut scene = toml::Table::new();
        scene.insert("model".into(), "plane".into());
        let mut geometry = toml::Table::new();
        geometry.insert("shape".into(), "gmsh".into());
        geometry.insert("file".into(), self.mesh.clone().into());
        scene.insert("geometry".into(), geometry.into());
        let mut time = toml::Table::new();
        time.insert("final_time".into(), self.final_time.into());
        time.insert("steps".into(), (self.steps as i64).into());
        time.insert("scheme".into(), "implicit".into());
        scene.insert("time".into(), time.into());
        scene.insert("viscosity".into(), law(self.first, tau));
        scene.insert("elasticity".into(), law(self.first, 1.0));
        let mut region = toml::Table::new();
        region.insert("group".into(), self.second_region.clone().into());
        region.insert("viscosity".into(), law(self.second, tau));
        region.insert("elasticity".into(), law(self.second, 1.0));
        scene.insert("region".into(), vec![toml::Value::Table(region)].into());
        scene.insert(
            "dirichlet".into(),
            vec![
                part("left", "support", "fix_x".into()),
                part("bottom", "support", "fix_y".into()),
            ]
            .into(),
        );
        scene.insert(
            "traction".into(),
            vec![part(
                "right",
                "value",
                vec![toml::Value::from(self.traction), 0.0.into()].into(),
            )]
            .into(),
        );
        let times: Vec<toml::Value> = (1..=self.steps)
            .map(|n| (self.final_time * n as f64 / self.steps as f64).into())
            .collect();
        let mut output = toml::Table::new();
        output.insert("times".into(), times.into());
        scene.insert("output".into(), output.into());
        let mut file: PlaneSceneFile = scene
            .try_into()
            .map_err(|e: toml::de::Error| format!("[strip] scene: {e}"))?;
        file.base_dir = Some(repository_root());
        PlaneScene::from_file(file).map_err(|e| e.to_string())
    }
}

/// Runs part 3 and adds its gate.
pub fn run(spec: &StripSpec, report: &mut CaseReport) -> Result<(), String> {
    let exact = spec.exact()?;
    let scene = spec.scene()?;
    let solution = scene.solve().map_err(|e| e.to_string())?;
    let step = spec.final_time / spec.steps as f64;
    let kappa = step_condition_number(&scene.problem, step)?;
    let nodes = scene.problem.mesh.nodes();
    let scale = nodes.iter().fold(0.0f64, |m, p| {
        let u = exact.static_displacement(p[0], p[1]);
        m.max(u[0].abs()).max(u[1].abs())
    });
    let mut checks = Vec::new();
    let mut rows = Vec::new();
    for snap in &solution.snapshots {
        let mut worst = 0.0f64;
        for (i, p) in nodes.iter().enumerate() {
            let u = exact.implicit_step(snap.n, step, p[0], p[1]);
            for (c, v) in u.into_iter().enumerate() {
                worst = worst.max((snap.u[2 * i + c] - v).abs());
            }
        }
        let limit = spec.round_off_factor * f64::EPSILON * kappa * snap.n as f64 * scale;
        checks.push(Check::at_most(
            &format!("n = {}: max nodal |u_n − (1 − r^n) u_s|", snap.n),
            worst,
            limit,
        ));
        rows.push(vec![
            snap.n.to_string(),
            format!("{}", snap.t),
            format!("{:.6}", 1.0 - exact.ratio(step).powi(snap.n as i32)),
            format!("{worst:e}"),
            format!("{limit:e}"),
        ]);
    }
    report.gates.push(GateVerdict::from_checks(
        format!("two-material strip ({}): u_n = (1 − r^n) u_s", spec.mesh),
        "exact",
        checks,
        &format!(
            "the closed form of exact/bimaterial_strip.rs lies in the P1 space and solves the \
             implicit steps: only round-off remains, ≤ c ε κ n max|u_s| with c = {}, κ = \
             κ₂((τ + k) K_B) = {kappa:.1} computed on the mesh ({} nodes), max|u_s| = {scale}; \
             a triangle with the other material's law gives an error of the order of u",
            spec.round_off_factor,
            nodes.len()
        ),
    ));
    report.tables.push(Table {
        title: format!(
            "Two-material strip: r = τ/(τ + k) = {}, regions {:?}",
            exact.ratio(step),
            scene
                .problem
                .regions
                .iter()
                .map(|r| format!("{} ({} triangles)", r.name, r.triangles.len()))
                .collect::<Vec<_>>()
        ),
        header: vec![
            "n".into(),
            "t_n".into(),
            "1 − r^n".into(),
            "max |error|".into(),
            "bound".into(),
        ],
        rows,
    });
    Ok(())
}
