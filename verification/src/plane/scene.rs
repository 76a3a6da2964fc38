//! The plane body's scenes: a case's inline `[scene]` varied per run (mesh, damper, Γ1 reading,
//! scheme, steps) by the core's dotted-key overrides, and `verify scene` for plane scenes
//! (`model = "plane"`): it runs the scene and writes `solution.json` (nodes, triangles, snapshots
//! with u, w, stress and von Mises per triangle, the contact force history, solver statistics), a
//! deformed-mesh plot with the von Mises field at the last snapshot, and the contact force
//! history; with `[output] vtk = true` also the ParaView series `solution.pvd` and one
//! `solution_<i>.vtu` per snapshot ([`crate::plane::vtk`]).

use std::path::Path;

use contactlab::model::quasistatic::plane::Support;
use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::scene::plane::{PlaneScene, PlaneSceneFile};

use crate::core::overrides;
use crate::plot::{
    write_svg, write_triangle_svg, Figure, Outline, Series, TriangleField, TriangleMeshPlot,
};

/// One variant of a case's scene: each set field overrides the scene's value.
#[derive(Debug, Clone, Copy, Default)]
pub struct Variant {
    /// Squares per side (`geometry.divisions = [n, n]`).
    pub divisions: Option<usize>,
    /// The damper's β (`contact.beta`, where the scene has a contact).
    pub beta: Option<f64>,
    /// The support of every Γ1 part (`dirichlet[*].support`).
    pub support: Option<Support>,
    pub scheme: Option<TimeScheme>,
    pub steps: Option<usize>,
    pub final_time: Option<f64>,
    pub start_at_first_equilibrium: Option<bool>,
}

impl Variant {
    /// The variant as dotted-key overrides of the scene table.
    fn overrides(&self, scene: &toml::Table) -> toml::Table {
        let mut set = toml::Table::new();
        let mut put = |key: &str, v: toml::Value| {
            set.insert(key.to_string(), v);
        };
        if let Some(n) = self.divisions {
            let n = toml::Value::Integer(n as i64);
            put("geometry.divisions", toml::Value::Array(vec![n.clone(), n]));
        }
        if let (Some(b), true) = (self.beta, scene.contains_key("contact")) {
            put("contact.beta", toml::Value::Float(b));
        }
        if let (Some(s), true) = (self.support, scene.contains_key("dirichlet")) {
            let name = match s {
                Support::Clamped => "clamped",
                Support::FixX => "fix_x",
                Support::FixY => "fix_y",
            };
            put("dirichlet[*].support", toml::Value::String(name.into()));
        }
        if let Some(s) = self.scheme {
            put("time.scheme", toml::Value::String(s.name().into()));
        }
        if let Some(n) = self.steps {
            put("time.steps", toml::Value::Integer(n as i64));
        }
        if let Some(t) = self.final_time {
            put("time.final_time", toml::Value::Float(t));
        }
        if let Some(b) = self.start_at_first_equilibrium {
            put("solver.start_at_first_equilibrium", toml::Value::Boolean(b));
        }
        set
    }
}

/// The validated scene of a case's `[scene]` table changed by `v`.
pub fn variant(scene: &toml::Table, v: Variant) -> Result<PlaneScene, String> {
    if v.steps.is_some() && scene.get("time").and_then(|t| t.get("times")).is_some() {
        return Err(
            "[scene]: a variant with its own steps needs a scene without time.times".into(),
        );
    }
    let table = overrides::applied(scene, &v.overrides(scene)).map_err(|e| e.to_string())?;
    let file: PlaneSceneFile = table
        .try_into()
        .map_err(|e: toml::de::Error| format!("[scene]: {e}"))?;
    PlaneScene::from_file(file).map_err(|e| e.to_string())
}

/// Runs a plane scene and writes its files into `out`; returns a summary.
pub fn write_scene(scene: &PlaneScene, source: &str, out: &Path) -> Result<String, String> {
    let mut solver = scene.solver().map_err(|e| format!("{source}: {e}"))?;
    // The explicit step bound of a linear scene (dense eigenproblem; small and medium meshes).
    let bound = if scene.scheme == TimeScheme::Explicit && scene.problem.is_linear() {
        contactlab::model::quasistatic::plane_stability::explicit_stability_eigenvalue(&solver)
            .ok()
            .map(|l| 2.0 / l)
    } else {
        None
    };
    let sol = solver.solve_or_partial(&scene.output).map_err(|(e, partial)| {
        let message = match bound {
            Some(kmax) if scene.grid.k_max() >= kmax => format!(
                "{source}: {e} (the explicit step bound 2/λ_max(A⁻¹B) of this scene is {kmax:.6}, k = {})",
                scene.grid.k_max()
            ),
            _ => format!("{source}: {e}"),
        } + &likely_inputs(&scene.file, &e);
        // what was computed up to the failure is written, every number finite
        let Some(partial) = partial else {
            return message;
        };
        let written = std::fs::create_dir_all(out)
            .map_err(|e| e.to_string())
            .and_then(|()| crate::core::json_out::finite_json(&*partial, true))
            .and_then(|json| {
                std::fs::write(out.join("partial_solution.json"), json).map_err(|e| e.to_string())
            });
        match written {
            Ok(()) => format!(
                "{message}; the results recorded before are in {}",
                out.join("partial_solution.json").display()
            ),
            Err(w) => format!("{message} (nothing written: {w})"),
        }
    })?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let path = out.join("solution.json");
    std::fs::write(
        &path,
        crate::core::json_out::finite_json(&sol, true)
            .map_err(|e| format!("{source}: solution.json: {e}"))?,
    )
    .map_err(|e| format!("{}: {e}", path.display()))?;
    let title = if scene.title.is_empty() {
        source.to_string()
    } else {
        scene.title.clone()
    };
    if let Some(snap) = sol.snapshots.last() {
        let deformed = sol.deformed(snap);
        let boundary: Vec<[f64; 2]> = scene
            .problem
            .mesh
            .boundary()
            .iter()
            .map(|e| sol.nodes[e.nodes[0]])
            .collect();
        let plot = TriangleMeshPlot::new(
            format!("{title}: von Mises at t = {}", snap.t),
            deformed,
            sol.triangles.clone(),
        )
        .field(TriangleField::per_triangle(
            "|σ|",
            snap.von_mises.iter().copied(),
        ))
        .outline(Outline::new("initial boundary", boundary).closed().dashed());
        write_triangle_svg(&plot, &out.join("von_mises.svg")).map_err(|e| e.to_string())?;
    }
    let fig = Figure::new(format!("{title}: contact force"))
        .x_label("t")
        .y_label("Σ W p_ν")
        .series(Series::line(
            "resultant normal contact force",
            sol.times
                .iter()
                .copied()
                .zip(sol.contact_force.iter().copied()),
        ));
    write_svg(&fig, &out.join("contact_force.svg")).map_err(|e| e.to_string())?;
    let vm_max = sol
        .snapshots
        .last()
        .map(|s| {
            s.von_mises
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .unwrap_or(f64::NAN);
    let bound_text = match bound {
        Some(kmax) => format!(
            "; explicit step bound 2/λ_max(A⁻¹B) = {kmax:.6} (k = {})",
            scene.grid.k_max()
        ),
        None => String::new(),
    };
    let vtk_text = if scene.file.output.vtk {
        let frames =
            crate::plane::vtk::frames(scene, &sol).map_err(|e| format!("{source}: {e}"))?;
        crate::vtk::write_series(out, "solution", &title, &frames)
            .map_err(|e| format!("{source}: {e}"))?;
        format!(
            "; ParaView: {} ({} .vtu)",
            out.join("solution.pvd").display(),
            frames.len()
        )
    } else {
        String::new()
    };
    Ok(format!(
        "{source}: {} path, {} dofs, {} steps ({} skipped for lack of equilibrium), {} sparse factorizations, {} Newton iterations ({} solves stopped at the round-off floor); von Mises max at the last snapshot {vm_max:.4}{bound_text}{vtk_text}{}",
        sol.stats.path,
        sol.stats.dofs,
        sol.stats.steps,
        sol.stats.skipped_steps.len(),
        sol.stats.factorizations,
        sol.stats.newton_iterations,
        sol.stats.floor_stops,
        sol.stats
            .warnings
            .iter()
            .map(|w| format!("\nwarning: {w}"))
            .collect::<String>()
    ))
}

/// For a solver failure (not a stop, not an input refused), the keys that set the step's scales
/// with their values ([`crate::core::likely_inputs`]): the time grid, the moduli, the contact
/// law's constants.
fn likely_inputs(f: &PlaneSceneFile, e: &contactlab::error::Error) -> String {
    use crate::core::likely_inputs::{clause, optional, time_grid};
    use contactlab::error::{Error, SolveError};
    use contactlab::scene::field_spec::FieldSpec;
    if !matches!(e, Error::Solve(s) if !matches!(s, SolveError::Stopped { .. })) {
        return String::new();
    }
    let mut inputs = time_grid(f.time.final_time, f.time.steps);
    for (section, m) in [("elasticity", &f.elasticity), ("viscosity", &f.viscosity)] {
        for (key, v) in [
            ("young", m.young),
            ("mu", m.mu),
            ("eta", m.eta),
            ("a1", m.a1),
            ("a2", m.a2),
            ("lambda", m.lambda),
            ("shear", m.shear),
        ] {
            inputs.extend(optional(&format!("{section}.{key}"), v));
        }
    }
    if let Some(c) = &f.contact {
        inputs.extend(optional("contact.beta", c.beta));
        for (key, v) in [("p0", &c.p0), ("stress", &c.stress)] {
            match v {
                Some(FieldSpec::Number(x)) => {
                    inputs.push((format!("contact.{key}"), x.to_string()))
                }
                Some(FieldSpec::Expression(t)) => {
                    inputs.push((format!("contact.{key}"), format!("\"{t}\"")))
                }
                None => {}
            }
        }
    }
    // what holds and loads the body: a support or a load that is missing leaves the contact to
    // carry (or to hold) everything
    for (key, sections) in [
        ("dirichlet", f.dirichlet.len()),
        ("traction", f.traction.len()),
    ] {
        inputs.push((format!("[[{key}]]"), format!("{sections} section(s)")));
    }
    clause(&inputs)
}
