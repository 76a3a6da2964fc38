//! `dynamic_manufactured`: time and space rates of the 2D dynamic solver on the manufactured
//! solution of [`crate::manufactured::dynamic_plane`] (plane strain, clamped top, tractions on
//! the sides, Γ3 in persistent normal-compliance contact with the foundation {x2 ≤ 0}).
//!
//! Time study: one mesh, steps N_1 < … < N_L per (scheme, contact force), on the affine field of
//! [`crate::manufactured::dynamic_plane::ManufacturedField::Affine`]: u = (1 − y)(b(t), −a(t)) is
//! affine in space, so with the consistent mass its nodal interpolant solves the semi-discrete
//! equations exactly (uniform F, Div Π = 0, an affine f0 = ρ ü integrated exactly, a uniform
//! penetration a(t) on Γ3 whose nodal compliance is exact), and ‖u_N − u(T)‖_{L²} is the time
//! error alone, against the exact solution — no reference run of the same code. Expected
//! (persistent contact, so the energy-consistent force of BDS (1.46) is r (p_n + p_{n−1})/2, the
//! trapezoidal value at t_{n−1/2}):
//!
//! | scheme            | force              | order in k | why |
//! |-------------------|--------------------|------------|-----|
//! | midpoint, gonzalez | energy_consistent | 2 | every term of the step equation at t_{n−1/2} (BDS (1.36), (1.41)) |
//! | midpoint, gonzalez | penalty           | 1 | r p_n at t_n in an equation collocated at t_{n−1/2}: an O(k) defect |
//! | newmark           | penalty            | 2 | the trapezoidal rule collocates every term, the penalty included, at t_n |
//!
//! Space study: n × n meshes with N = c·n steps (k ∝ h), midpoint-type scheme with the
//! energy-consistent force: ‖ε(u_N − u(T))‖ = O(h) and ‖u_N − u(T)‖_{L²} = O(h²) (P1; the O(k²)
//! time error is O(h²), below the energy error and of the L² error's order, so both rates hold).
//!
//! Every run is audited (BDS Propositions 1.1, 1.3; HLT Proposition 3.7): Gonzalez's scheme, and
//! the midpoint rule with the linear law, with the energy-consistent force satisfy the identities
//! at round-off, the body force and tractions doing work (the audit's external work dᵀ f(t_{n−1/2})
//! is the work of the load the scheme applies).

pub mod format;
pub mod report;
pub mod runs;

use crate::core::case::Case;
use crate::core::format::CaseError;

use crate::core::context::RunContext;
use crate::core::report::case_report::CaseReport;
use crate::dynamic::cases::manufactured::format::{
    Combination, ErrorName, ManufacturedCase, Study,
};
use crate::dynamic::cases::manufactured::report::{
    audit_gates, persistence_gate, rate_gate, space_outputs, time_outputs, RateSeries,
};
use crate::dynamic::cases::manufactured::runs::{
    max_frequency, run_space_study, run_time_study, RunResult,
};
use crate::manufactured::dynamic_plane::DynamicManufactured;

/// Checks the case's format.
pub fn check(case: &Case) -> Result<(), CaseError> {
    case.body::<ManufacturedCase>()?.check(&case.path)
}

/// Runs the case.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c: ManufacturedCase = case.body().map_err(|e| e.to_string())?;
    c.check(&case.path).map_err(|e| e.to_string())?;
    let m = DynamicManufactured::standard(c.law);
    let mut all_runs: Vec<RunResult> = Vec::new();
    let mut series: Vec<(Study, Option<Combination>, ErrorName, RateSeries)> = Vec::new();
    if let Some(t) = &c.time_study {
        let runs = run_time_study(&m, c.mass, t, ctx, &case.header.id)?;
        let omega = max_frequency(&m, c.mass, t.divisions)?;
        time_outputs(ctx, report, &m, t, omega, &runs, &mut series)?;
        all_runs.extend(runs);
    }
    if let Some(s) = &c.space_study {
        let runs = run_space_study(&m, c.mass, s, ctx, &case.header.id)?;
        space_outputs(ctx, report, s, &runs, &mut series)?;
        all_runs.extend(runs);
    }
    for (i, g) in c.gate.iter().enumerate() {
        report.gates.push(rate_gate(i, g, &series)?);
    }
    report.gates.push(persistence_gate(&all_runs));
    audit_gates(report, &c, &all_runs);
    Ok(())
}
