//! Part 1 of `plane_gmsh`: format equivalence. The unit square's files (written by Gmsh from
//! `examples/meshes/unit_square.geo`: the triangles of our rectangle mesh with `diagonal = "up"`,
//! in Gmsh's node and element order) run the manufactured problem; so does our own generated
//! rectangle (`TriangleMesh::rectangle`, n × n squares). Gmsh's mesher, the three readers, the
//! group → boundary-part map and the scene-independent problem set-up all stand between the two.
//!
//! **Gate 1, each file against the rectangle.** Nodes are matched by position (each file node to
//! the grid node it rounds to; the map must be a bijection); δ is the largest coordinate offset
//! between matched nodes. The nodal solutions u_N must agree within (module
//! [`super::conditioning`])
//!
//!   max_i |u_rect − u_file| ≤ N κ (2 · 17 δ/h + c ε) max|u_rect|,
//!
//! κ = κ₂(K_A + θ k K_B) of the rectangle, 17 δ/h the relative change of the stiffness and load
//! under nodes moved by δ, c = `round_off_factor` for the two solves' round-off, N steps carrying
//! each step's error at most once. A mis-ordered node or element map, a group on the wrong side,
//! a reoriented triangle left clockwise gives an O(1) difference.
//!
//! **Gate 2, the formats against each other.** The same triangles and groups (index for index)
//! and coordinates compared with the first file's: where they are bit-identical, the solutions
//! must be bit-identical (deterministic solver: same input, same bits); where they differ (an
//! ASCII file keeps 16 significant digits, the binary file the doubles), the same bound with δ
//! the largest coordinate difference — which must itself be within the rounding of 16 digits,
//! 5·10⁻¹⁶ max|x| (a reader that loses digits, e.g. parses single precision, fails here).

use std::collections::BTreeMap;

use serde::Deserialize;

use contactlab::model::quasistatic::plane::ContactIntegration;
use contactlab::model::quasistatic::plane_solver::SolverPath;

use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::plane::cases::gmsh::conditioning::{step_condition_number, GEOMETRY_SENSITIVITY};
use crate::plane::cases::gmsh::study::{final_displacement, square_problem};
use crate::plane::study::{Discretization, ExactSpec};

/// `[equivalence]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EquivalenceSpec {
    /// The unit square's files (relative to the repository root); the first is the reference of
    /// the format comparison.
    pub files: Vec<String>,
    /// n of the generated n × n rectangle (the files' squares per side).
    pub divisions: usize,
    /// N time steps.
    pub steps: usize,
    /// c of the round-off term c ε of the bound (module docs).
    pub round_off_factor: f64,
}

/// The relative rounding of a coordinate written with 16 significant digits (Gmsh's `%.16g`).
const DIGITS: f64 = 5e-16;

/// The perturbation bound N κ (2 · 17 δ/h + c ε), relative to max|u|.
fn bound(steps: usize, kappa: f64, delta: f64, h: f64, c: f64) -> f64 {
    steps as f64 * kappa * (2.0 * GEOMETRY_SENSITIVITY * delta / h + c * f64::EPSILON)
}

/// Runs part 1 and adds its two gates.
pub fn run(
    spec: &EquivalenceSpec,
    exact: &ExactSpec,
    d: &Discretization,
    report: &mut CaseReport,
) -> Result<(), String> {
    let exact = exact.manufactured()?;
    let integration = d.contact_integration.unwrap_or(ContactIntegration::Gauss2);
    let scheme = d.scheme.unwrap_or_default();
    let path = d.solver_path.unwrap_or(SolverPath::Auto);
    let n = spec.divisions;
    let rect = exact.problem(n, integration)?;
    let u_rect = final_displacement(&rect, spec.steps, scheme, path)?;
    let scale = u_rect.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let step = exact.final_time / spec.steps as f64;
    let kappa = step_condition_number(&rect, scheme.theta() * step)?;
    let h = 1.0 / n as f64;
    // grid index (i, j) of a point of the unit square
    let key = |p: [f64; 2]| {
        (
            (p[0] * n as f64).round() as i64,
            (p[1] * n as f64).round() as i64,
        )
    };
    let rect_index: BTreeMap<(i64, i64), usize> = rect
        .mesh
        .nodes()
        .iter()
        .enumerate()
        .map(|(i, &p)| (key(p), i))
        .collect();
    let mut rows = Vec::new();
    let mut checks = Vec::new();
    let mut runs = Vec::new();
    for file in &spec.files {
        let problem = square_problem(&exact, file, integration)?;
        let u = final_displacement(&problem, spec.steps, scheme, path)?;
        let nodes = problem.mesh.nodes();
        let mut hit = vec![false; rect.mesh.nodes().len()];
        let (mut delta, mut diff) = (0.0f64, 0.0f64);
        let mut bijection = nodes.len() == hit.len();
        for (j, &q) in nodes.iter().enumerate() {
            let Some(&i) = rect_index.get(&key(q)) else {
                bijection = false;
                continue;
            };
            bijection &= !std::mem::replace(&mut hit[i], true);
            let p = rect.mesh.nodes()[i];
            delta = delta.max((p[0] - q[0]).abs()).max((p[1] - q[1]).abs());
            for c in 0..2 {
                diff = diff.max((u_rect[2 * i + c] - u[2 * j + c]).abs() / scale);
            }
        }
        let limit = bound(spec.steps, kappa, delta, h, spec.round_off_factor);
        checks.push(Check::holds(
            &format!("{file}: every node is one grid node of the rectangle"),
            bijection,
            "a bijection",
        ));
        checks.push(Check::at_most(
            &format!(
                "{file}: max relative nodal difference of u_N (δ = {delta:e}, the bound \
                 N κ (2·17 δ/h + c ε))"
            ),
            diff,
            limit,
        ));
        rows.push(vec![
            file.clone(),
            format!("{delta:e}"),
            format!("{diff:e}"),
            format!("{limit:e}"),
        ]);
        runs.push((file.clone(), problem, u));
    }
    report.gates.push(GateVerdict::from_checks(
        format!("format equivalence: each file against the generated {n} × {n} rectangle"),
        "independent",
        checks,
        &format!(
            "Gmsh's mesh of unit_square.geo against our own rectangle (same triangles): u_N node \
             by node, relative to max|u_N| = {scale:e}, within N κ (2·17 δ/h + c ε) with N = {}, \
             κ = κ₂(K_A + θ k K_B) = {kappa:.1} computed on the rectangle, h = 1/{n}, δ the \
             largest coordinate offset of the file's nodes (Gmsh writes them off the grid by \
             ≤ 2e-12), c = {}; a node or element mis-mapped or a group on the wrong side gives \
             O(1)",
            spec.steps, spec.round_off_factor
        ),
    ));
    // the formats against the first file
    let mut checks = Vec::new();
    if let Some(((first, p0, u0), rest)) = runs.split_first() {
        for (file, p, u) in rest {
            let same_topology = p.mesh.triangles() == p0.mesh.triangles()
                && p.mesh.boundary() == p0.mesh.boundary();
            checks.push(Check::holds(
                &format!("{file}: the triangles and boundary edges of {first}, index for index"),
                same_topology,
                "identical",
            ));
            let delta = p
                .mesh
                .nodes()
                .iter()
                .zip(p0.mesh.nodes())
                .fold(0.0f64, |m, (a, b)| {
                    m.max((a[0] - b[0]).abs()).max((a[1] - b[1]).abs())
                });
            let extent = p0
                .mesh
                .nodes()
                .iter()
                .fold(0.0f64, |m, a| m.max(a[0].abs()).max(a[1].abs()));
            checks.push(Check::at_most(
                &format!(
                    "{file}: largest coordinate difference from {first} (16 significant digits \
                     of an ASCII file: ≤ 5e-16 × max|x| = {:e})",
                    DIGITS * extent
                ),
                delta,
                DIGITS * extent,
            ));
            let diff = u
                .iter()
                .zip(u0)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs() / scale));
            let limit = if delta == 0.0 {
                0.0
            } else {
                bound(spec.steps, kappa, delta, h, spec.round_off_factor)
            };
            checks.push(Check::at_most(
                &format!(
                    "{file}: max relative difference of u_N from {first} (coordinates differ by \
                     {delta:e}: {})",
                    if delta == 0.0 {
                        "same input, same bits"
                    } else {
                        "the bound with this δ"
                    }
                ),
                diff,
                limit,
            ));
            rows.push(vec![
                format!("{file} vs {first}"),
                format!("{delta:e}"),
                format!("{diff:e}"),
                format!("{limit:e}"),
            ]);
        }
    }
    if !checks.is_empty() {
        report.gates.push(GateVerdict::from_checks(
            "format equivalence: the formats against each other".into(),
            "identity",
            checks,
            "the files hold the same mesh; bit-identical coordinates must give bit-identical \
             solutions (a deterministic solver), differing ones (ASCII keeps 16 digits) stay \
             within the perturbation bound with δ their difference",
        ));
    }
    report.tables.push(Table {
        title: format!(
            "Format equivalence: u_N on the unit square, {n} × {n}, N = {} (κ = {kappa:.1})",
            spec.steps
        ),
        header: vec![
            "mesh".into(),
            "δ (coordinates)".into(),
            "max |Δu| / max |u|".into(),
            "bound".into(),
        ],
        rows,
    });
    Ok(())
}
