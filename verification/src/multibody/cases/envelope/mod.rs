//! Case kind `multibody_envelope`: the family's range edges swept on the head-on bars of
//! docs/multibody.md §13.1 (two linear plane-strain bars L × H, ν = 0 — exactly the 1D bar —,
//! ρ = E = 1, at ±v, the gap g0 = 2 v · onset_steps · k so the onset has the same phase in the step
//! on every level, k = courant · h/c, single pass, Lagrange multipliers, energy–momentum unless a
//! sweep says otherwise), each point run to `after_release` past the exact release t0 + 2L/c.
//!
//! Points: `[[sweep]]` tables of speeds v/c × meshes M (one row or square cells, one or two
//! passes, a scheme), each marked inside the range or past it with the outcomes the docs name for
//! it; `[[overlap]]` starts the bars `depth` into each other through a scene file (the overlap
//! check is the scene reader's), refused or `initial_overlap = "resolve"`.
//!
//! Gates ([`gates`]), each with its reason:
//!
//! - (a) **range**: every point inside completes (the audit may flag held nodes' switch work at
//!   concave kinks of square cells, docs §10); every point past it ends with one of its declared
//!   outcomes — a typed error (`EnergyGain`, `ActiveSetCycle`, `NewtonNotConverged`,
//!   `NoEquilibrium`), Newmark's warning (`newmark_warning`: `scheme_energy_warning`), the audit's
//!   flag of positive set-change work (`audit_flag`), or the overlap error naming the pair — never
//!   a quiet answer;
//! - (b) **rebound rate**: the centre velocities at T against the exact swap ±v → ∓v
//!   ([`crate::exact::bar_impact::HeadOnBars`]) converge like the dispersive release front,
//!   O(h^{2/3}) (docs §13.1, `multibody_bars`): the fitted rate with its 95 % confidence interval
//!   against 2/3 and the finest error under the error model's ceiling
//!   ([`crate::core::gate::RateCriteria`]), at every speed of a `[[rate]]`'s sweep;
//! - (c) **energy**: E_T − E_0 ≤ the round-off floor of the energy sums, E recomputed from the
//!   initial and final states by an independent P1 assembly ([`energy`]): the energy–momentum step
//!   changes the energy only by the activation work −λ g₀ ≤ 0;
//! - (d) **momentum**: |P_T − P_0| ≤ its round-off floor, recomputed likewise: free bars, equal
//!   and opposite contact forces.

pub mod energy;
pub mod format;
pub mod gates;
pub mod points;
pub mod report;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;

use format::EnvelopeCase;

/// Checks a case of this kind.
pub fn check(case: &Case) -> Result<(), CaseError> {
    EnvelopeCase::from_case(case).map(|_| ())
}

/// Runs a case of this kind.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let file = EnvelopeCase::from_case(case).map_err(|e| e.to_string())?;
    let runs = points::run_all(&file)?;
    report.gates.extend(gates::gates(&file, &runs));
    report.tables.push(report::points_table(&file, &runs));
    report::plots(&file, ctx, report, &runs)
}
