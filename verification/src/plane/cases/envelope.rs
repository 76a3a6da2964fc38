//! Kind `plane_envelope`: the plane family at the edges of its range (docs/quasistatic.md, "The
//! range of the quasistatic family") on meshes not shaped for a case — Gmsh blocks with slanted
//! sides and a hole, fine generated rectangles — and many steps: every in-range point answers on
//! both solver paths and the two agree to round-off; a uniform grid factors A + θkB once whatever
//! N; inputs past the range are typed errors naming the key.

use std::path::Path;

use contactlab::error::Error;
use contactlab::model::quasistatic::plane_output::PlaneSolution;
use contactlab::scene::{Scene, Solution};
use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::{at_least, positive, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};

/// The case body of `plane_envelope`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeCase {
    pub plane_envelope: EnvelopeSpec,
}

/// `[plane_envelope]`: the points swept.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeSpec {
    /// Gmsh meshes of the holed block (relative to the case file), groups base, sides, top.
    pub meshes: Vec<String>,
    /// Generated 6 × 3 rectangles [n_x, n_y].
    pub rectangles: Vec<[usize; 2]>,
    /// Step counts N of every mesh.
    pub steps: Vec<usize>,
    /// Contact integrations ("gauss2", "nodal").
    pub integrations: Vec<String>,
    /// Step counts of the one-factorization check (on the first rectangle).
    pub factor_steps: Vec<usize>,
    /// ‖u_N(condensed) − u_N(Newton)‖∞ / ‖u_N‖∞ at most this multiple of ε √(n N).
    pub round_off_factor: f64,
}

impl EnvelopeCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: Self = case.body()?;
        let p = &c.plane_envelope;
        at_least(case.path(), "plane_envelope.steps", &p.steps, 1)?;
        at_least(
            case.path(),
            "plane_envelope.integrations",
            &p.integrations,
            1,
        )?;
        at_least(case.path(), "plane_envelope.rectangles", &p.rectangles, 1)?;
        positive(
            case.path(),
            "plane_envelope.round_off_factor",
            p.round_off_factor,
        )?;
        Ok(c)
    }
}

/// The notched block's data (examples/scenes/plane_gmsh_notched_block.toml: Kelvin–Voigt,
/// lubricated foundation β = 100, p0 = 2, traction −20 t on the top, rollers on the sides) on a
/// geometry table and its boundary parts.
/// Path "free": the condensed path with the block's rollers (fix_x: the vertical rigid motion is
/// carried by the contact, which only the condensed path does); otherwise clamped sides.
fn block_scene(geometry: &str, parts: [&str; 3], steps: usize, path: &str, extra: &str) -> String {
    let [sides, top, base] = parts;
    let (path, support) = match path {
        "free" => ("condensed", "fix_x"),
        p => (p, "clamped"),
    };
    format!(
        "model = \"plane\"\n[geometry]\n{geometry}\n[time]\nfinal_time = 1.0\nsteps = {steps}\n\
         scheme = \"midpoint\"\n[viscosity]\nlaw = \"paper\"\nmu = 30.0\neta = 20.0\n\
         [elasticity]\nlaw = \"plane_strain\"\nyoung = 100.0\npoisson = 0.3\n[[dirichlet]]\n{sides}\n\
         support = \"{support}\"\n[[traction]]\n{top}\nvalue = [0.0, \"-20*t\"]\n[contact]\n{base}\n\
         law = \"lubricated\"\nbeta = 100.0\np0 = 2.0\n{extra}\n[output]\ntimes = [1.0]\n\
         [solver]\npath = \"{path}\"\nstart_at_first_equilibrium = true\n"
    )
}

/// A mesh of the sweep: a Gmsh file or a rectangle.
#[derive(Debug, Clone)]
enum Mesh {
    Gmsh(String),
    Rectangle([usize; 2]),
}

impl Mesh {
    fn label(&self) -> String {
        match self {
            Mesh::Gmsh(f) => Path::new(f)
                .file_name()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default(),
            Mesh::Rectangle([nx, ny]) => format!("rectangle {nx}×{ny}"),
        }
    }

    fn scene(&self, steps: usize, path: &str, integration: &str) -> String {
        let extra = format!("integration = \"{integration}\"");
        match self {
            Mesh::Gmsh(file) => block_scene(
                &format!("shape = \"gmsh\"\nfile = \"{file}\""),
                ["group = \"sides\"", "group = \"top\"", "group = \"base\""],
                steps,
                path,
                &extra,
            ),
            Mesh::Rectangle([nx, ny]) => block_scene(
                &format!("size = [6.0, 3.0]\ndivisions = [{nx}, {ny}]"),
                [
                    "sides = [\"left\", \"right\"]",
                    "sides = [\"top\"]",
                    "sides = [\"bottom\"]",
                ],
                steps,
                path,
                &extra,
            ),
        }
    }
}

fn run_scene(text: &str) -> Result<PlaneSolution, Error> {
    match Scene::from_toml_str(text, "plane_envelope.toml")?.run()? {
        Solution::Plane(p) => Ok(p),
        _ => unreachable!("a plane scene gives a plane solution"),
    }
}

fn final_u(s: &PlaneSolution) -> &[f64] {
    s.snapshots.last().map(|x| x.u.as_slice()).unwrap_or(&[])
}

/// Runs the case.
pub fn run(case: &Case, _ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = EnvelopeCase::parse(case).map_err(|e| e.to_string())?;
    let spec = &c.plane_envelope;
    let dir = case.path().parent().unwrap_or(Path::new("."));
    let mut meshes: Vec<Mesh> = spec
        .meshes
        .iter()
        .map(|m| Mesh::Gmsh(dir.join(m).to_string_lossy().into_owned()))
        .collect();
    meshes.extend(spec.rectangles.iter().map(|r| Mesh::Rectangle(*r)));
    let (answers, agreement) = sweep_paths(spec, &meshes, report);
    report.gates.push(GateVerdict::from_checks(
        "every in-range point answers on both solver paths".into(),
        "plane_envelope",
        answers,
        "inside the stated range (docs/quasistatic.md) a run must converge: the condensed path's \
         stopping test at the computed round-off floor of its residual and the full Newton path \
         both reach it; a failure here is the false 'did not converge' of issue 31",
    ));
    report.gates.push(GateVerdict::from_checks(
        "the condensed and full Newton paths agree to round-off at every point".into(),
        "plane_envelope",
        agreement,
        "both solve the same discrete equations (a linear Kelvin–Voigt body, the piecewise-linear \
         lubricated law), the full path without condensation, with its own assembly and sparse \
         Jacobian: they differ by the round-off of n unknowns over N steps, ε √(n N) times the \
         stated factor; a stop short of the floor, or an answer accepted above it, shows here",
    ));
    report.gates.push(factorization_gate(
        spec,
        &meshes[meshes.len() - spec.rectangles.len()],
    ));
    report.gates.push(past_range_gate(&meshes[0]));
    Ok(())
}

/// Every mesh × N × integration on both paths: the table, the answers and the agreement checks.
fn sweep_paths(
    spec: &EnvelopeSpec,
    meshes: &[Mesh],
    report: &mut CaseReport,
) -> (Vec<Check>, Vec<Check>) {
    let mut rows = Vec::new();
    let mut answers = Vec::new();
    let mut agreement = Vec::new();
    for mesh in meshes {
        for &steps in &spec.steps {
            for integration in &spec.integrations {
                let what = format!("{}, N = {steps}, {integration}", mesh.label());
                let free = run_scene(&mesh.scene(steps, "free", integration));
                answers.push(Check::holds(
                    &format!(
                        "{what}: condensed path, rollers (a rigid motion carried by the contact)"
                    ),
                    free.is_ok(),
                    &free
                        .as_ref()
                        .err()
                        .map_or("converged".into(), |e| e.to_string()),
                ));
                let c = run_scene(&mesh.scene(steps, "condensed", integration));
                let n = run_scene(&mesh.scene(steps, "newton", integration));
                answers.push(Check::holds(
                    &format!("{what}: condensed path answers"),
                    c.is_ok(),
                    &c.as_ref()
                        .err()
                        .map_or("converged".into(), |e| e.to_string()),
                ));
                answers.push(Check::holds(
                    &format!("{what}: Newton path answers"),
                    n.is_ok(),
                    &n.as_ref()
                        .err()
                        .map_or("converged".into(), |e| e.to_string()),
                ));
                let (Ok(c), Ok(n)) = (c, n) else { continue };
                let (uc, un) = (final_u(&c), final_u(&n));
                let scale = uc.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let diff = uc
                    .iter()
                    .zip(un)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                let bound = ((c.stats.dofs * steps) as f64).sqrt() * f64::EPSILON;
                agreement.push(Check::at_most(
                    &format!(
                        "{what} ({} dofs): ‖Δu_N‖∞/‖u_N‖∞ over ε √(n N) = {bound:.2e}",
                        c.stats.dofs
                    ),
                    diff / scale / bound,
                    spec.round_off_factor,
                ));
                rows.push(vec![
                    mesh.label(),
                    c.stats.dofs.to_string(),
                    steps.to_string(),
                    integration.clone(),
                    c.stats.factorizations.to_string(),
                    c.stats.newton_iterations.to_string(),
                    format!(
                        "{} (rollers: {})",
                        c.stats.floor_stops,
                        free.as_ref()
                            .map_or("–".into(), |f| f.stats.floor_stops.to_string())
                    ),
                    n.stats.newton_iterations.to_string(),
                    n.stats.floor_stops.to_string(),
                    format!("{:.2e}", diff / scale),
                ]);
            }
        }
    }
    report.tables.push(Table {
        title: "the sweep: both paths at every point (floor stops: Newton solves stopped at the \
                computed round-off floor of their residual, above the requested tolerance)"
            .into(),
        header: [
            "mesh",
            "dofs",
            "N",
            "contact integration",
            "condensed: factorizations",
            "condensed: Newton iterations",
            "condensed: floor stops",
            "Newton: iterations",
            "Newton: floor stops",
            "‖Δu_N‖∞/‖u_N‖∞",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
    (answers, agreement)
}

/// One factorization of A + θkB per uniform grid, whatever N (t_n = T n / N gives step sizes that
/// differ in their last bits).
fn factorization_gate(spec: &EnvelopeSpec, mesh: &Mesh) -> GateVerdict {
    let checks = spec
        .factor_steps
        .iter()
        .map(|&n| {
            let what = format!("{}, N = {n}: sparse factorizations", mesh.label());
            match run_scene(&mesh.scene(n, "condensed", "gauss2")) {
                Ok(s) => Check::at_most(&what, s.stats.factorizations as f64, 1.0),
                Err(e) => Check::holds(&what, false, &e.to_string()),
            }
        })
        .collect();
    GateVerdict::from_checks(
        "a uniform grid factors the step operator once".into(),
        "plane_envelope",
        checks,
        "the step operator A + θkB depends on k only; steps equal up to the rounding of t_n − \
         t_{n−1} are one size (docs/quasistatic.md): 5 to 9 factorizations here were issue 31's \
         item 2",
    )
}

/// Past the range: a typed error naming the key as written.
fn past_range_gate(mesh: &Mesh) -> GateVerdict {
    let base = mesh.scene(20, "auto", "gauss2");
    let cases = [
        (
            "time.grading = 11 (range [1, 10])",
            base.replace("steps = 20", "steps = 20\ngrading = 11.0"),
            "time.grading",
        ),
        (
            "time.steps = 0",
            base.replace("steps = 20", "steps = 0"),
            "time.steps",
        ),
        (
            "contact.beta = -1",
            base.replace("beta = 100.0", "beta = -1.0"),
            "contact.beta",
        ),
    ];
    let checks = cases
        .iter()
        .map(|(what, text, key)| {
            let message = match run_scene(text) {
                Ok(_) => "accepted".to_string(),
                Err(e) => e.to_string(),
            };
            Check::holds(
                &format!("{what}: a typed error naming `{key}`"),
                message.contains(key),
                &message,
            )
        })
        .collect();
    GateVerdict::from_checks(
        "inputs past the range are typed errors naming the key".into(),
        "plane_envelope",
        checks,
        "past the range the family answers with an error that names what the user wrote, never a \
         quiet answer",
    )
}
