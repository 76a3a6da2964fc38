//! Kind `plane_gmsh`: the Gmsh reader (`contactlab::mesh::gmsh`) and the scene's `shape = "gmsh"`,
//! `group = "…"` and `[[region]]`, against evidence the reader did not compute.
//!
//! 1. **Format equivalence** ([`equivalence`]): the unit square read from each of its files (4.1
//!    ASCII, 4.1 binary, 2.2 ASCII) gives the nodal solution of our own generated rectangle with
//!    the same triangles, node by node, within a perturbation bound; the formats agree with each
//!    other bit for bit where their coordinates do.
//! 2. **Convergence on Gmsh meshes** ([`study`]): a manufactured solution of
//!    `manufactured/plane.rs` on the files' meshes, its sides selected by the files' groups; the
//!    core's sweeps and rate gates.
//! 3. **The two-material strip** ([`strip`]): a scene with a `[[region]]` against the closed form
//!    of `exact/bimaterial_strip.rs`, to round-off.
//! 4. **Mesh checks** ([`mesh_checks`]): small crafted files, one per defect, each refused with a
//!    typed error naming the element or node.
//!
//! Mesh paths in the case file are relative to the repository root.

pub mod conditioning;
pub mod equivalence;
pub mod files;
pub mod mesh_checks;
pub mod strip;
pub mod study;

use std::path::Path;

use serde::Deserialize;

use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::convergence;
use crate::core::format::{invalid, positive, CaseError};
use crate::core::report::case_report::CaseReport;
use crate::plane::errors::PLANE_ERRORS;
use crate::plane::study::{Discretization, ExactSpec};
use crate::plot::{TriangleField, TriangleMeshPlot};

use files::{read_mesh, repository_root};

/// The plane keys of a `plane_gmsh` body (the sweeps and rate gates are the core's).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GmshKeys {
    /// The manufactured solution of parts 1 and 2 (as `plane_convergence`'s `[exact]`).
    pub exact: ExactSpec,
    #[serde(default)]
    pub discretization: Discretization,
    pub equivalence: equivalence::EquivalenceSpec,
    pub convergence: study::MeshSeries,
    pub strip: strip::StripSpec,
    pub mesh_checks: mesh_checks::MeshChecksSpec,
    #[serde(default)]
    pub plots: Plots,
}

/// `[plots]`: meshes drawn in the report (no gate).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plots {
    #[serde(default)]
    pub meshes: Vec<String>,
}

/// The case body of `plane_gmsh`.
pub type GmshCase = convergence::ConvergenceCase<GmshKeys, TimeScheme>;

/// `file` exists under the repository root, or the case error naming `field`.
fn existing(path: &Path, field: &str, file: &str) -> Result<(), CaseError> {
    if repository_root().join(file).is_file() {
        Ok(())
    } else {
        Err(invalid(
            path,
            field,
            file,
            "a mesh file (relative to the repository root)",
        ))
    }
}

/// Parses and checks the case body.
pub fn parse(case: &Case) -> Result<GmshCase, CaseError> {
    let c = GmshCase::parse(case, &PLANE_ERRORS)?;
    let path = case.path();
    let k = &c.family;
    k.exact.check(path)?;
    if k.equivalence.files.is_empty() {
        return Err(invalid(
            path,
            "equivalence.files",
            "[]",
            "one or more mesh files",
        ));
    }
    for (i, f) in k.equivalence.files.iter().enumerate() {
        existing(path, &format!("equivalence.files[{i}]"), f)?;
    }
    positive(
        path,
        "equivalence.round_off_factor",
        k.equivalence.round_off_factor,
    )?;
    if k.equivalence.divisions == 0 || k.equivalence.steps == 0 {
        return Err(invalid(
            path,
            "equivalence",
            "divisions or steps = 0",
            "divisions ≥ 1 and steps ≥ 1",
        ));
    }
    if !k.convergence.mesh.contains("{n}") {
        return Err(invalid(
            path,
            "convergence.mesh",
            &k.convergence.mesh,
            "a path with {n} (replaced by each level's elements)",
        ));
    }
    for (i, s) in c.spec.sweeps.iter().enumerate() {
        if s.time_error {
            return Err(invalid(
                path,
                &format!("sweep[{i}].time_error"),
                true,
                "false (plane_gmsh has no same-mesh time reference)",
            ));
        }
        for (j, &n) in s.elements.iter().enumerate() {
            existing(
                path,
                &format!("sweep[{i}].elements[{j}]"),
                &k.convergence.file(n),
            )?;
        }
    }
    for (i, g) in c.spec.gates.iter().enumerate() {
        if g.select.error == crate::plane::cases::convergence::SAME_CODE_ERROR {
            return Err(invalid(
                path,
                &format!("gate[{i}].error"),
                &g.select.error,
                "an error against the exact solution",
            ));
        }
    }
    k.strip.check(path)?;
    existing(path, "strip.mesh", &k.strip.mesh)?;
    k.mesh_checks.check(path)?;
    for (i, f) in k.plots.meshes.iter().enumerate() {
        existing(path, &format!("plots.meshes[{i}]"), f)?;
    }
    Ok(c)
}

/// Runs the case: the convergence sweeps (the core's gates and plots), then the equivalence, the
/// strip and the mesh checks, then the mesh plots.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = parse(case).map_err(|e| e.to_string())?;
    let k = &c.family;
    let study = study::GmshStudy::from_case(&k.exact, &k.discretization, &k.convergence)?;
    convergence::run(&c.spec, &study, ctx, report)?;
    equivalence::run(&k.equivalence, &k.exact, &k.discretization, report)?;
    strip::run(&k.strip, report)?;
    mesh_checks::run(&k.mesh_checks, ctx, report)?;
    let mut plots = Vec::new();
    for file in &k.plots.meshes {
        let g = read_mesh(file)?;
        let counts = format!(
            "{} nodes, {} triangles; groups: {}",
            g.mesh.nodes().len(),
            g.mesh.triangles().len(),
            g.boundary_groups
                .keys()
                .chain(g.regions.keys())
                .cloned()
                .collect::<Vec<_>>()
                .join(", ")
        );
        let mut plot = TriangleMeshPlot::new(
            format!("{file} ({counts})"),
            g.mesh.nodes().to_vec(),
            g.mesh.triangles().to_vec(),
        )
        .wireframe(true);
        if g.regions.len() > 1 {
            // each triangle coloured by the index of its 2D group (alphabetical)
            let mut region = vec![f64::NAN; g.mesh.triangles().len()];
            for (i, triangles) in g.regions.values().enumerate() {
                for &t in triangles {
                    region[t] = i as f64;
                }
            }
            let names: Vec<String> = g
                .regions
                .keys()
                .enumerate()
                .map(|(i, k)| format!("{k} = {i}"))
                .collect();
            plot = plot.field(TriangleField::per_triangle(
                format!("region: {}", names.join(", ")),
                region,
            ));
        }
        plots.push(plot);
    }
    if !plots.is_empty() {
        ctx.triangle_panels(report, "meshes", "The Gmsh meshes", &plots, 1)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    //! The `plane_gmsh` format: the committed case parses; a mesh pattern without `{n}`, a level
    //! whose file does not exist, a same-code time reference and incompatible strip materials
    //! are typed errors naming the field.
    use super::*;

    fn committed() -> String {
        std::fs::read_to_string(repository_root().join("verification/cases/plane_gmsh.toml"))
            .expect("the committed case")
    }

    fn parsed(text: &str) -> Result<GmshCase, CaseError> {
        parse(&Case::from_text(Path::new("plane_gmsh.toml"), text)?)
    }

    fn error(from: &str, to: &str) -> String {
        let text = committed();
        assert!(text.contains(from), "{from}");
        parsed(&text.replacen(from, to, 1))
            .map(|_| ())
            .expect_err("a typed error")
            .to_string()
    }

    #[test]
    fn the_committed_case_parses() {
        parsed(&committed()).expect("parses");
    }

    #[test]
    fn wrong_meshes_times_and_materials_are_typed_errors() {
        let e = error("unit_square_{n}.msh", "unit_square.msh");
        assert!(e.contains("convergence.mesh"), "{e}");
        let e = error("elements = [4, 8,", "elements = [3, 8,");
        assert!(e.contains("sweep[0].elements[0]"), "{e}");
        let e = error("name = \"h\"", "name = \"h\"\ntime_error = true");
        assert!(e.contains("sweep[0].time_error"), "{e}");
        let e = error("second = { a1 = 4.5,", "second = { a1 = 5.5,");
        assert!(e.contains("strip.second") && e.contains("lateral"), "{e}");
        let e = error("\"duplicate_node\",", "\"degenerate_triangle\",");
        assert!(e.contains("mesh_checks.defects[1]"), "{e}");
    }
}
