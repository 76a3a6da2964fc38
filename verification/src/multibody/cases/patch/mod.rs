//! Case kind `multibody_patch`: the contact patch test (Taylor & Papadopoulos 1991) for
//! node-to-segment contact with Lagrange multipliers, against the exact uniform state of
//! [`crate::exact::contact_patch`] (docs/multibody.md, the patch test).
//!
//! **Setting.** A lower block A = (0, L) × (0, H_A) on rollers, an upper block B on top of it
//! loaded by the uniform pressure p, meeting along the flat interface y = H_A with
//! non-matching meshes (n_A and n_B cells along it, sharing only the two end nodes); linear
//! law, frictionless contact, the static solve. Exact: σ_yy = −p, σ_xx = σ_xy = 0,
//! σ_zz = −ν p in both blocks, affine displacements, the nodal contact force p w_i.
//!
//! **Two-pass passes.** With both passes every node of either side lies on the other side's
//! segments; on a flat interface whose ends coincide that forces both traces onto one straight
//! line (a trace is linear between its own nodes, and each interior node of one lies inside a
//! segment of the other). The uniform state meets these constraints, and its consistent loads
//! (p w_i on either side, the trapezoidal weights) have equal resultants p L and equal moments
//! p L²/2 — the only two conditions for them to be in the range of the constraints' transpose
//! (orthogonal to the kernel {a + b x} of the constraint map). So the uniform state is an
//! equilibrium of the discrete problem, and the solver must find it to round-off.
//!
//! **Why the two-pass multipliers are not unique.** n_A + n_B + 2 constraints act on the
//! n_A + n_B + 2 vertical interface displacements and leave the two-dimensional kernel
//! {a + b x}: the constraint map has rank n_A + n_B, and its transpose a two-dimensional
//! kernel too. That kernel is where the two passes write the same gap twice: at the two shared
//! end nodes, B's end node on A's end segment and A's end node on B's end segment give the
//! same constraint y_B − y_A = 0, and only the sum of their two multipliers is determined. The
//! interior multipliers are unique. The case gates only what is unique: displacements,
//! stresses, the total force, and the nodal forces the multipliers assemble to (the interior
//! multipliers follow from those).
//!
//! **Single-pass fails.** One pass transmits the slave's forces λ_i to the master by linear
//! interpolation at the slave nodes; the master then receives Σ_i λ_i N_j(x_i) ≠ p w_j: the
//! uniform state is no equilibrium, the contact pressure oscillates at the mesh scale. Those
//! errors are self-equilibrated (zero resultant and moment), so they stay in a layer of a few
//! cells along the interface: refining both meshes at a fixed ratio repeats the same pattern,
//! the nodal pressure error and the largest stress error do not converge (rate 0) while the
//! layer's area shrinks like h — the L² stress error converges at rate 1/2.
//!
//! **Different materials.** The constraint is written in the current configuration, the law is
//! small-strain: the traces stretch by 1 + ε_xx^A and 1 + ε_xx^B, ε_xx = ν (1 + ν) p / E. When
//! these differ the two traces' consistent loads have moments differing by
//! p L²/2 (ε_xx^B − ε_xx^A) = O(p²/E) and the uniform state is no longer an equilibrium of the
//! two-pass constraints: the relative stress error grows linearly in p (rate 1), and vanishes
//! to round-off for materials of different E but equal ν (1 + ν)/E.
//!
//! **Round-off.** The gaps see u only through the positions x = X + u, stored to ε |X| ≤ ε L:
//! the interface displacements are fixed to ~ε L, relative ε E/p; the stresses differentiate
//! nodal values over h. With the linear solve's relative error ~ε, the two-pass errors
//! (relative to p, to max |u*|, to p w, to p L) are bounded by
//! F ε (L/h_min)(1 + E_max/p), F from `[roundoff]`.

pub mod format;
pub mod measure;
pub mod report;
pub mod setup;

use serde::Serialize;

use contactlab::model::multibody::solver::MultibodyParams;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::exact::contact_patch::{Block, ContactPatch};
use crate::multibody::cases::patch::format::{PatchCase, RefinementKeys};
use crate::multibody::cases::patch::measure::{measure, PatchErrors};
use crate::multibody::cases::patch::report::{
    materials_report, mesh_table, plot_mesh, refinement_figure, refinement_table, Measured,
    PressureLevel,
};
use crate::multibody::cases::patch::setup::{solve, Passes, PatchMesh};

/// Every enforcement of the per-mesh study.
const ENFORCEMENTS: [Passes; 3] = [
    Passes::Single {
        slave: Block::Upper,
    },
    Passes::Single {
        slave: Block::Lower,
    },
    Passes::Two,
];

/// Checks a case of this kind.
pub fn check(case: &Case) -> Result<(), CaseError> {
    PatchCase::from_case(case).map(|_| ())
}

/// F ε (L/h_min)(1 + E_max/p) (module docs).
fn roundoff_bound(factor: f64, patch: &ContactPatch, mesh: &PatchMesh) -> f64 {
    let e_max = patch.lower.young.max(patch.upper.young);
    factor * f64::EPSILON * (patch.length / mesh.h_min(patch)) * (1.0 + e_max / patch.pressure)
}

/// The round-off checks of a two-pass run.
fn roundoff_checks(label: &str, e: &PatchErrors, bound: f64) -> Vec<Check> {
    vec![
        Check::at_most(&format!("{label}: max |σ − σ*|/p"), e.stress_max, bound),
        Check::at_most(
            &format!("{label}: max |u − u*|/max|u*|"),
            e.displacement_max,
            bound,
        ),
        Check::at_most(
            &format!("{label}: max |f_i − p w_i|/(p w)"),
            e.interface_force_max,
            bound,
        ),
        Check::at_most(&format!("{label}: |Σλ − pL|/(pL)"), e.total_force, bound),
        Check::at_most(&format!("{label}: max |g|/max|u*|"), e.gap_max, bound),
    ]
}

/// What `data.json` holds: every run's errors.
#[derive(Serialize)]
struct Data<'a> {
    meshes: Vec<(String, &'static str, &'a PatchErrors)>,
    refinement: Vec<(String, f64, &'a PatchErrors, &'a PatchErrors)>,
    materials: Vec<(f64, f64, &'a PatchErrors, &'a PatchErrors)>,
}

/// Runs a case of this kind.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let file = PatchCase::from_case(case).map_err(|e| e.to_string())?;
    let params = MultibodyParams::default();
    let patch = file.same_material();
    let factor = file.roundoff.factor;

    // the patch test per mesh ratio
    let mut measured = Vec::new();
    let mut shown = Vec::new();
    for (i, m) in file.meshes.iter().enumerate() {
        for passes in ENFORCEMENTS {
            let run = solve(&patch, m.mesh(), passes, &params)?;
            let errors = measure(&patch, &run);
            let entry = Measured {
                mesh: m.mesh(),
                passes,
                errors,
            };
            if i == 0 {
                shown.push((
                    run,
                    Measured {
                        mesh: entry.mesh,
                        passes,
                        errors: entry.errors.clone(),
                    },
                ));
            }
            measured.push(entry);
        }
    }
    let bound_of = |mesh: &PatchMesh| roundoff_bound(factor, &patch, mesh);
    let mut two_pass = Vec::new();
    let mut single = Vec::new();
    for m in &measured {
        let label = format!("{} {}", m.mesh.ratio(), m.passes.label());
        match m.passes {
            Passes::Two => two_pass.extend(roundoff_checks(&label, &m.errors, bound_of(&m.mesh))),
            Passes::Single { .. } => single.push(Check::at_least(
                &format!("{label}: max |σ − σ*|/p (fails the patch test)"),
                m.errors.stress_max,
                file.single_pass.min_stress_error,
            )),
        }
    }
    report.gates.push(GateVerdict::from_checks(
        "two-pass: the uniform state to round-off on every mesh ratio".into(),
        "reference",
        two_pass,
        &file.roundoff.note,
    ));
    report.gates.push(GateVerdict::from_checks(
        "single-pass: fails the patch test on every mesh ratio, either side slave".into(),
        "reference",
        single,
        &file.single_pass.note,
    ));
    mesh_table(report, &measured, &bound_of);
    plot_mesh(ctx, report, &patch, &shown)?;

    // refinement at a fixed ratio
    let mut levels = Vec::new();
    if let Some(rf) = &file.refinement {
        levels = refine(&patch, rf, &params)?;
        let h: Vec<f64> = levels.iter().map(|l| l.0).collect();
        let checks = levels
            .iter()
            .flat_map(|(_, _, t)| {
                roundoff_checks(
                    &format!("{} two-pass", t.mesh.ratio()),
                    &t.errors,
                    bound_of(&t.mesh),
                )
            })
            .collect();
        report.gates.push(GateVerdict::from_checks(
            "two-pass under refinement: the uniform state to round-off on every level".into(),
            "reference",
            checks,
            &file.roundoff.note,
        ));
        for g in &rf.gates {
            let errors: Vec<f64> = levels
                .iter()
                .map(|(_, s, _)| single_error(&s.errors, &g.select.error))
                .collect();
            report.gates.push(g.criteria.evaluate(
                format!(
                    "single-pass (B slave) under refinement at {}: {} vs h",
                    rf.mesh.mesh().ratio(),
                    g.select.error
                ),
                &h,
                &errors,
            ));
        }
        refinement_table(report, &levels);
        ctx.plot(report, "refinement", &refinement_figure(&levels))?;
    }

    // different materials against p
    let mut pressure_levels = Vec::new();
    if let Some(mt) = &file.materials {
        let equal = mt.equal_lateral_strain();
        for &p in &mt.pressures {
            let different = file.patch(mt.lower, mt.upper, p);
            let same_strain = file.patch(mt.lower, equal, p);
            let mesh = mt.mesh.mesh();
            let d = measure(&different, &solve(&different, mesh, Passes::Two, &params)?);
            let e = measure(
                &same_strain,
                &solve(&same_strain, mesh, Passes::Two, &params)?,
            );
            pressure_levels.push(PressureLevel {
                pressure: p,
                mismatch: different.lateral_strain_mismatch(),
                equal_bound: roundoff_bound(factor, &same_strain, &mesh),
                different: d,
                equal: e,
            });
        }
        let ps: Vec<f64> = pressure_levels.iter().map(|l| l.pressure).collect();
        let errs: Vec<f64> = pressure_levels
            .iter()
            .map(|l| l.different.stress_max)
            .collect();
        report.gates.push(mt.gate.evaluate(
            format!(
                "two-pass, E, ν = ({}, {}) below and ({}, {}) above: max |σ − σ*|/p vs p",
                mt.lower.young, mt.lower.poisson, mt.upper.young, mt.upper.poisson
            ),
            &ps,
            &errs,
        ));
        let checks = pressure_levels
            .iter()
            .flat_map(|l| {
                roundoff_checks(
                    &format!(
                        "p = {:e}, E = {} and {}, equal ν(1 + ν)/E",
                        l.pressure, mt.lower.young, equal.young
                    ),
                    &l.equal,
                    l.equal_bound,
                )
            })
            .collect();
        report.gates.push(GateVerdict::from_checks(
            format!(
                "two-pass with different E but equal lateral strains (ν = {} below, {:.10} above): the uniform state to round-off at every p",
                mt.lower.poisson, equal.poisson
            ),
            "reference",
            checks,
            &file.roundoff.note,
        ));
        materials_report(ctx, report, &pressure_levels)?;
    }

    ctx.write_data(
        report,
        &Data {
            meshes: measured
                .iter()
                .map(|m| (m.mesh.ratio(), m.passes.label(), &m.errors))
                .collect(),
            refinement: levels
                .iter()
                .map(|(h, s, t)| (s.mesh.ratio(), *h, &s.errors, &t.errors))
                .collect(),
            materials: pressure_levels
                .iter()
                .map(|l| (l.pressure, l.mismatch, &l.different, &l.equal))
                .collect(),
        },
    )?;
    Ok(())
}

/// The named error of a single-pass run (0 when absent).
fn single_error(e: &PatchErrors, name: &str) -> f64 {
    match name {
        "stress_max" => e.stress_max,
        "stress_l2" => e.stress_l2,
        "displacement_max" => e.displacement_max,
        "pressure_max" => e.pressure_max.unwrap_or(0.0),
        _ => f64::NAN,
    }
}

/// Single-pass (B slave) and two-pass on every refinement level: (h_min, single, two).
fn refine(
    patch: &ContactPatch,
    rf: &RefinementKeys,
    params: &MultibodyParams,
) -> Result<Vec<(f64, Measured, Measured)>, String> {
    let mut levels = Vec::new();
    for &f in &rf.factors {
        let mesh = rf.mesh.mesh().refined(f);
        let run = |passes: Passes| -> Result<Measured, String> {
            let r = solve(patch, mesh, passes, params)?;
            Ok(Measured {
                mesh,
                passes,
                errors: measure(patch, &r),
            })
        };
        let s = run(Passes::Single {
            slave: Block::Upper,
        })?;
        let t = run(Passes::Two)?;
        levels.push((mesh.h_min(patch), s, t));
    }
    Ok(levels)
}
