//! Case kind `multibody_bars`: two plane-strain bars meeting end to end, against the exact 1D
//! wave solutions of [`crate::exact::bar_impact`] (docs/multibody.md).
//!
//! **Why 2D bars are 1D.** With ν = 0 the plane-strain law has λ = 0 and μ = E/2: the field
//! u = (u(x, t), 0) has ε_yy = ε_xy = 0, σ_xx = E u_x and σ_yy = σ_xy = 0, so the free top and
//! bottom carry no traction and the momentum equation is ρ u_tt = E u_xx: the bar equation with
//! c = √(E/ρ) (the P-wave speed √((λ + 2μ)/ρ) at ν = 0). Each bar's exact motion is the 1D one,
//! uniform across the height H, and the contact force is A σ with A = H (per unit thickness).
//! The discrete motion is not exactly 1D (the diagonals of the P1 triangles couple x and y in
//! the consistent mass): `transverse_max` measures it (O(h)).
//!
//! **The configurations.** `head_on`: two bars of length L at ±v: by symmetry each is the free
//! bar hitting a wall (contact 2L/c, stress ρ c v, rebound ∓v). `striker`: a bar of length L1 at v
//! hits a bar of length L2 ≥ L1 at rest: contact 2L1/c with stress ρ c v/2, the striker at rest
//! after it, the target with the momentum ρ A L1 v (its centre velocity v L1/L2) carrying all the
//! energy. The left bar's contact end holds the slave nodes, the right bar's the master
//! segments (two passes: also the reverse pair); Lagrange multipliers.
//!
//! **What converges and how** (the 1D P1 midpoint bar against a wall, `dynamic_bar_wall`, is
//! the reference): the exact solution has jumps of u_t and σ on the fronts; P1 elements with a
//! midpoint-type rule propagate them with a dispersion error that smears a front over
//! ~(h² c t)^{1/3}, so when the unloading front returns to the contact the force falls early by
//! an impulse O(h^{2/3}): the centre velocities after the release are off by O(h^{2/3}). The
//! contact force chatters from step to step (the held end node's velocity flips under the
//! midpoint rule), but its mean over the plateau is the exact stress. The energy–momentum
//! scheme conserves energy in every step except where a constraint closes a gap g₀ > 0 within
//! the step: the constraint does the work −λ g₀ (EM §6.2). At the first contact, from the
//! rigid approach, the step is linear: λ is proportional to the penetration (v k − g₀) it
//! prevents and W = −K_eff v² k² φ(1 − φ), φ = g₀/(v k) the phase of the onset in the step; at a
//! fixed Courant number K_eff k² ∝ ρ H h, so W/E_0 = C φ(1 − φ) h/L: rate 1 when φ(1 − φ) is the
//! same on every level (onsets at t0 = k_0 (n + 1/3): φ = 1/3, 2/3, 1/3, … as k halves). At a
//! fixed h, k → 0, it tends to the kinetic energy of the caught end nodes, ∝ 2 φ(1 − φ) v²/(Gᵀ
//! M⁻¹ G): it vanishes with h, not with k alone.
//!
//! Errors measured by every run: [`measure`]; the format: [`format`]; gates: [`gates`].

pub mod format;
pub mod gates;
pub mod measure;
pub mod report;
pub mod run;
pub mod setup;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::report::case_report::CaseReport;

use format::BarsCase;

/// Checks a case of this kind.
pub fn check(case: &Case) -> Result<(), CaseError> {
    BarsCase::from_case(case).map(|_| ())
}

/// Runs a case of this kind.
pub fn run(case: &Case, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let file = BarsCase::from_case(case).map_err(|e| e.to_string())?;
    let jobs = run::jobs(&file);
    let outcomes = run::run_all(&file, &jobs)?;
    report.gates.extend(gates::gates(&file, &outcomes));
    report.tables.push(report::exact_table(&file));
    report.tables.push(report::runs_table(&file, &outcomes));
    report::plot_histories(&file, ctx, report, &outcomes)?;
    report::plot_convergence(&file, ctx, report, &outcomes)
}
