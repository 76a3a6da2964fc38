//! The rollers' floating problem under the other foundation laws: whether an equilibrium exists is
//! decided by the range of p_ν over the contact points (Σ_g W_g p_ν(r_g) must reach the load R on
//! the free vertical translation), and each law has its own range:
//!
//! - linear, β > 0 (p_ν = β r): (−∞, ∞) — every load has an equilibrium, and the mean sinking has
//!   the closed form of `runs` with p0 = 0 and no receding part;
//! - linear, β = 0 (p_ν ≡ 0): {0} — a contact that carries no pressure cannot hold the body, so
//!   the first loaded step stops with `NoEquilibrium` naming the bounds (0, 0);
//! - lubricated, β = 0 (p_ν ≡ p0): {p0 L} — only the load p0 L is balanced; any other stops with
//!   `NoEquilibrium` naming (p0 L, p0 L), not with a root search that cannot converge.
//!
//! The expected bounds and load are computed here from the scene's data (L from the contact
//! edges, R(τ_1) by Gauss quadrature of the traction), not read from the solver; on the upward
//! translation v = (0, 1) they read −R and −p0 L (ν = (0, −1)).

use contactlab::error::{Error as LabError, SolveError};
use contactlab::model::quasistatic::plane::Support;

use super::format::{PaperTestSpec, Reading};
use super::runs::{contact_length, load_resultant, run_one};
use crate::core::gate::{Check, GateVerdict};
use crate::plane::scene::{variant, Variant};

/// The damper p0 of the lubricated run at β = 0: small enough that the first step's load is above
/// p0 L (so that only the law's range, not the load's sign, decides).
const LUBRICATED_P0: f64 = 0.1;

/// The case's scene with its contact law replaced by `law` (keys `beta` and, for the lubricated
/// law, `p0`).
fn with_law(
    scene: &toml::Table,
    law: &str,
    beta: f64,
    p0: Option<f64>,
) -> Result<toml::Table, String> {
    let mut table = scene.clone();
    let contact = table
        .get_mut("contact")
        .and_then(|c| c.as_table_mut())
        .ok_or("[scene]: the floating problem needs a [scene.contact] table")?;
    contact.insert("law".into(), toml::Value::String(law.into()));
    contact.insert("beta".into(), toml::Value::Float(beta));
    match p0 {
        Some(p) => contact.insert("p0".into(), toml::Value::Float(p)),
        None => contact.remove("p0"),
    };
    Ok(table)
}

/// The plain rollers scheme on the coarsest mesh with `law` must stop at step 1 with
/// `NoEquilibrium` whose reason names the load −R(τ_1) on the upward translation and the bounds
/// (−p L, −p L) of the constant pressure p = `p_of_length`.
fn stops_without_equilibrium(
    table: &toml::Table,
    spec: &PaperTestSpec,
    what: &str,
    p_of_length: f64,
) -> Result<Check, String> {
    let scene = variant(
        table,
        Variant {
            support: Some(Support::FixX),
            start_at_first_equilibrium: Some(false),
            divisions: Some(spec.meshes[0]),
            ..Default::default()
        },
    )?;
    let times = scene.grid.times();
    let tau = scene.scheme.data_time(times[0], times[1]);
    // On the free motion v = (0, 1) the downward load gives −R(τ_1), and pressures p on Γ3
    // (ν = (0, −1)) give −∫ p (written 0 − x: no "−0" in the message).
    let load = 0.0 - load_resultant(&scene.problem, tau);
    let bound = 0.0 - p_of_length * contact_length(&scene.problem);
    let bounds = format!("({bound:.6}, {bound:.6})");
    let named_load = format!("{load:.6} N");
    let outcome = scene.solve();
    let (ok, text) = match &outcome {
        Err(e @ LabError::Solve(SolveError::NoEquilibrium { step, reason, .. })) => (
            *step == 1 && reason.contains(&bounds) && reason.contains(&named_load),
            e.to_string(),
        ),
        Err(e) => (false, e.to_string()),
        Ok(_) => (false, "ran without error".into()),
    };
    Ok(Check::holds(
        &format!("{what}: {text}"),
        ok,
        &format!("NoEquilibrium at step 1 naming the load {named_load} and the bounds {bounds}"),
    ))
}

/// The gate: the linear law's run against its closed form, and the two laws of bounded range
/// stopping with the bounds named.
pub fn floating_laws(
    scene: &toml::Table,
    spec: &PaperTestSpec,
    steps: usize,
) -> Result<GateVerdict, String> {
    let beta = spec.von_mises_beta;
    let linear = with_law(scene, "linear", beta, None)?;
    let (run, _) = run_one(&linear, Reading::Rollers, spec.meshes[0], beta)?;
    let limit = spec.sinking_round_off_factor * f64::EPSILON * steps as f64;
    let mut checks = vec![Check::holds(
        &format!(
            "linear law β = {beta}: {} steps skipped",
            run.skipped_steps.len()
        ),
        run.skipped_steps.is_empty(),
        "none (p_ν = β r reaches every load)",
    )];
    match run.sinking_closed_form {
        Some(c) => checks.push(Check::at_most(
            &format!(
                "linear law β = {beta}, {0}×{0}: mean u_y on Γ3 {1:.10} vs the closed form −(1/L) Σ_n k R(τ_n)/β = {c:.10}: relative difference",
                run.divisions, run.contact_line_mean
            ),
            ((run.contact_line_mean - c) / c).abs(),
            limit,
        )),
        None => checks.push(Check::holds(
            "linear law: a closed form",
            false,
            "constant data and no body force",
        )),
    }
    checks.push(stops_without_equilibrium(
        &with_law(scene, "linear", 0.0, None)?,
        spec,
        "linear law β = 0 (p_ν ≡ 0)",
        0.0,
    )?);
    checks.push(stops_without_equilibrium(
        &with_law(scene, "lubricated", 0.0, Some(LUBRICATED_P0))?,
        spec,
        &format!("lubricated law β = 0, p0 = {LUBRICATED_P0} (p_ν ≡ p0)"),
        LUBRICATED_P0,
    )?);
    Ok(GateVerdict::from_checks(
        "rollers under the other laws: an equilibrium exactly when the law's range of p_ν reaches the load".into(),
        "paper_test",
        checks,
        "linear β > 0: range (−∞, ∞), the closed form; linear β = 0: {0}; lubricated β = 0: {p0 L} — bounds computed from the scene",
    ))
}
