//! The list of model families, and what goes through it: loading a case (its header, then its
//! kind's format, checked by the family that owns the kind), running it, and `verify scene`.

use std::path::Path;
use std::time::Instant;

use contactlab::scene::Scene;

use crate::core::case::{read_dir, Case};
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;
use crate::family::Family;

/// Every family of the suite.
pub const FAMILIES: [&dyn Family; 5] = [
    &crate::rod::Rod,
    &crate::plane::Plane,
    &crate::dynamic::Dynamic,
    &crate::moving::Moving,
    &crate::multibody::Multibody,
];

/// Every case kind, in family order, then the fuzz campaign's.
pub fn kinds() -> Vec<&'static str> {
    FAMILIES
        .iter()
        .flat_map(|f| f.kinds().iter().copied())
        .chain(crate::robustness::KINDS)
        .collect()
}

/// The family that owns a case kind.
pub fn family_of(kind: &str) -> Option<&'static dyn Family> {
    FAMILIES.iter().copied().find(|f| f.kinds().contains(&kind))
}

/// Checks a case with its kind's format.
pub fn check(case: &Case) -> Result<(), CaseError> {
    if crate::robustness::KINDS.contains(&case.header.kind.as_str()) {
        let c: crate::robustness::FuzzCase = case.body()?;
        return c.check(case.path());
    }
    match family_of(&case.header.kind) {
        Some(f) => f.check(case),
        None => Err(case.unknown_kind(&kinds())),
    }
}

/// Reads one case file and checks it.
pub fn load(path: &Path) -> Result<Case, CaseError> {
    let case = Case::read(path)?;
    check(&case)?;
    Ok(case)
}

/// Reads and checks every case of a directory (sorted by file name).
pub fn load_all(dir: &Path) -> Result<Vec<Case>, CaseError> {
    let cases = read_dir(dir)?;
    for c in &cases {
        check(c)?;
    }
    Ok(cases)
}

/// Runs one case and returns its report; a failure to set up or run is recorded in the report
/// (and fails it), never a panic.
pub fn run(case: &Case, ctx: &RunContext) -> CaseReport {
    let start = Instant::now();
    let mut report = CaseReport::new(&case.header, ctx.metadata.clone());
    let fuzz = crate::robustness::KINDS.contains(&case.header.kind.as_str());
    let outcome = match family_of(&case.header.kind) {
        Some(f) => f.run(case, ctx, &mut report),
        // the campaign runs scenes through `verify scene`'s runner, passed in (it imports no
        // family)
        None if fuzz => case
            .body::<crate::robustness::FuzzCase>()
            .map_err(|e| e.to_string())
            .and_then(|c| crate::robustness::run(case, &c, run_scene, &mut report)),
        None => Err(format!(
            "no family owns the case kind `{}`",
            case.header.kind
        )),
    };
    if let Err(message) = outcome {
        report.failure = Some(message);
    }
    report.wall_seconds = start.elapsed().as_secs_f64();
    report.conclude();
    report
}

/// The marker of a directory `verify scene` writes: its files are the runs' own.
const OUT_MARKER: &str = ".contactlab-scene-out";

/// Creates `out` and checks that a file can be written there, before any solving: an unwritable
/// `--out` must not cost a whole run. Files of an earlier run there (a directory with the marker)
/// are removed, so that no old `errors.json` or `map.json` stays beside the new results; a
/// directory holding files `verify scene` did not write is refused with their list
/// (subdirectories are left alone: other runs' outputs). Returns the files removed.
pub fn writable_out(out: &Path) -> Result<Vec<String>, String> {
    std::fs::create_dir_all(out).map_err(|e| format!("--out {}: {e}", out.display()))?;
    let mut entries: Vec<String> = std::fs::read_dir(out)
        .map_err(|e| format!("--out {}: {e}", out.display()))?
        .flatten()
        .filter(|e| e.path().is_file())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| n != OUT_MARKER)
        .collect();
    entries.sort();
    let ours = out.join(OUT_MARKER).exists();
    if !entries.is_empty() && !ours {
        let shown: Vec<&str> = entries.iter().take(8).map(String::as_str).collect();
        return Err(format!(
            "--out {}: holds {} file(s) `verify scene` did not write ({}{}): choose an empty or \
             new directory",
            out.display(),
            entries.len(),
            shown.join(", "),
            if entries.len() > 8 { ", …" } else { "" }
        ));
    }
    let mut removed = Vec::new();
    for name in &entries {
        let path = out.join(name);
        if path.is_file() {
            std::fs::remove_file(&path)
                .map_err(|e| format!("--out {}: cannot remove {name}: {e}", out.display()))?;
            removed.push(name.clone());
        }
    }
    std::fs::write(
        out.join(OUT_MARKER),
        b"written by verify scene; its files are replaced by the next run\n",
    )
    .map_err(|e| format!("--out {}: not writable: {e}", out.display()))?;
    Ok(removed)
}

/// `verify scene FILE --out DIR`: the solver crate reads and validates the scene once
/// (`Scene::load`, which dispatches on its `model`), and the family that writes that model's
/// results runs it. Returns a summary.
pub fn run_scene(file: &Path, out: &Path) -> Result<String, String> {
    run_scene_with(file, out, false)
}

/// Turns on the ParaView output of a scene (`[output] vtk = true`); an error for a model that
/// has none.
pub fn request_vtk(scene: &mut Scene) -> Result<(), String> {
    match scene {
        Scene::Rod(s) => s.vtk = true,
        Scene::Plane(s) => s.file.output.vtk = true,
        Scene::Dynamic(s) => s.file.output.vtk = true,
        Scene::Multibody(s) => s.file.output.vtk = true,
        Scene::Moving(_) => {
            return Err(format!(
                "--vtk: model `{}` writes no ParaView files (rod, plane, dynamic and multibody \
                 scenes do)",
                scene.model()
            ))
        }
    }
    Ok(())
}

/// [`run_scene`]; with `vtk`, as if the scene said `[output] vtk = true` (`verify scene --vtk`).
pub fn run_scene_with(file: &Path, out: &Path, vtk: bool) -> Result<String, String> {
    let source = file.display().to_string();
    let mut scene = Scene::load(file).map_err(|e| format!("{source}: {e}"))?;
    if vtk {
        request_vtk(&mut scene).map_err(|e| format!("{source}: {e}"))?;
    }
    // a ParaView series without an output time would cost the whole run for nothing
    let (wants_vtk, no_times) = match &scene {
        Scene::Rod(s) => (s.vtk, s.output.snapshot_times.is_empty()),
        Scene::Plane(s) => (s.file.output.vtk, s.output.snapshot_times.is_empty()),
        Scene::Dynamic(s) => (s.file.output.vtk, s.file.output.times.is_empty()),
        Scene::Multibody(s) => (s.file.output.vtk, s.file.output.times.is_empty()),
        Scene::Moving(_) => (false, false),
    };
    if wants_vtk && no_times {
        return Err(format!(
            "{source}: output.vtk: no output time to write (list them in [output] times)"
        ));
    }
    let removed = writable_out(out)?;
    let model = scene.model();
    let family = FAMILIES
        .iter()
        .find(|f| f.models().contains(&model))
        .ok_or_else(|| format!("{source}: no family writes the results of model `{model}`"))?;
    let summary = family.write_scene(&scene, &source, out)?;
    Ok(if removed.is_empty() {
        summary
    } else {
        format!(
            "{summary}\n(removed {} file(s) of an earlier run in {}: {})",
            removed.len(),
            out.display(),
            removed.join(", ")
        )
    })
}

/// `verify plan`: plans the cheapest discretization of a scene meeting `request`
/// (`core::plan`), runs it and writes `plan.json`, `plan.md` and `plan.svg` into `out`; returns
/// the Markdown summary. `base` sets the first round's finest pilot (M₀, N₀) instead of the
/// scene's own resolution. Rod scenes (errors against their `[exact]` solution, or
/// self-convergence of u_h(L, T) and σ_h(L, T) without one), plane scenes on a rectangle, and
/// dynamic and multibody scenes on generated shapes (self-convergence of their functionals at T;
/// docs/planner.md). An empty `request.functional` takes the model's default: `paper_E` for a
/// rod scene with `[exact]`, `end_displacement` without, `contact_force` for a plane scene, the
/// rebound velocity (or a displacement) for a dynamic scene, the first body's `velocity_x` for
/// a multibody scene.
pub fn plan_scene(
    file: &Path,
    request: &crate::core::plan::PlanRequest,
    base: Option<(usize, usize)>,
    out: &Path,
) -> Result<String, String> {
    use crate::core::plan::{plan, plan_with_base, PlanRequest, Plannable};
    fn run<P: Plannable>(
        p: &P,
        request: &PlanRequest,
        base: Option<(usize, usize)>,
    ) -> Result<crate::core::plan::PlanResult, String> {
        match base {
            Some(b) => plan_with_base(p, request, b),
            None => plan(p, request),
        }
    }
    let source = file.display().to_string();
    let text = std::fs::read_to_string(file).map_err(|e| format!("{source}: {e}"))?;
    let table: toml::Table = toml::from_str(&text).map_err(|e| format!("{source}: {e}"))?;
    if let Some((m, n)) = base {
        if m == 0 || n == 0 {
            return Err(format!("--base {m},{n}: expected M₀ ≥ 1 and N₀ ≥ 1"));
        }
    }
    let mut request = request.clone();
    let model = table.get("model").and_then(|m| m.as_str()).unwrap_or("");
    // the families that read the table themselves (a Gmsh body is refused before its mesh is
    // read)
    let result = match model {
        "plane" => {
            if request.functional.is_empty() {
                request.functional = "contact_force".into();
            }
            let p = crate::plane::scene_plan::PlaneScenePlan::from_table(table, &source)?;
            run(&p, &request, base)?
        }
        "dynamic" if table.get("body").is_some_and(|b| b.is_array()) => {
            let p = crate::multibody::scene_plan::MultibodyScenePlan::from_table(
                table,
                &source,
                &request.functional,
            )?;
            request.functional = p.functional().to_string();
            run(&p, &request, base)?
        }
        "dynamic" => {
            let p = crate::dynamic::scene_plan::DynamicScenePlan::from_table(
                table,
                &source,
                &request.functional,
            )?;
            request.functional = p.functional().to_string();
            run(&p, &request, base)?
        }
        _ => match Scene::from_toml_str(&text, &source).map_err(|e| format!("{source}: {e}"))? {
            Scene::Rod(rod) => {
                if request.functional.is_empty() {
                    request.functional = if rod.exact.is_some() {
                        "paper_E"
                    } else {
                        "end_displacement"
                    }
                    .into();
                }
                let p = crate::rod::plan::RodPlan::from_text(&text, &source)?;
                run(&p, &request, base)?
            }
            other => {
                return Err(format!(
                    "{source}: the planner does not plan model `{}` scenes: an eigenvalue \
                     problem has no mesh–step trade to choose (its convergence in the basis \
                     size is what the moving cases gate); it plans rod, plane, dynamic and \
                     multibody scenes",
                    other.model()
                ))
            }
        },
    };
    writable_out(out)?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let json = serde_json::to_string_pretty(&result).map_err(|e| e.to_string())?;
    std::fs::write(out.join("plan.json"), json).map_err(|e| e.to_string())?;
    let md = result.markdown();
    std::fs::write(out.join("plan.md"), &md).map_err(|e| e.to_string())?;
    crate::plot::write_svg(&result.figure(&source), &out.join("plan.svg"))
        .map_err(|e| e.to_string())?;
    Ok(md)
}
