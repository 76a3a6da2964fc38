//! The JSON and summary pieces every moving scene writer shares (`scene.rs` for the string and
//! the disc, `plate_scene.rs` for the plate): a sweep's `sweep_<i>.json`, a map's `map.json`, the
//! map's verdict counts and a point's discretization warning, for any model's parameter type.

use serde::Serialize;

use contactlab::model::moving::stability::{StabilityAssessment, Verdict};
use contactlab::model::moving::stability_map::{AxisParameter, StabilityMap};
use contactlab::model::moving::sweep::Sweep;

/// `sweep_<i>.json`.
#[derive(Serialize)]
pub struct SweepJson<'a> {
    parameter: &'static str,
    values: &'a [f64],
    verdicts: Vec<Verdict>,
    max_real_part: Vec<f64>,
    spectra: Vec<Vec<[f64; 2]>>,
    branches: Vec<Vec<[f64; 2]>>,
}

/// The JSON of a sweep of any model.
pub fn sweep_json<P: AxisParameter>(sw: &Sweep<P>) -> SweepJson<'_> {
    SweepJson {
        parameter: sw.axis.parameter.key(),
        values: &sw.axis.values,
        verdicts: sw.assessments.iter().map(|a| a.verdict).collect(),
        max_real_part: sw.assessments.iter().map(|a| a.max_real_part).collect(),
        spectra: sw
            .spectra
            .iter()
            .map(|s| s.iter().map(|l| [l.re, l.im]).collect())
            .collect(),
        branches: sw
            .branches
            .branches
            .iter()
            .map(|b| b.iter().map(|l| [l.re, l.im]).collect())
            .collect(),
    }
}

/// The discretization warning of a point: unstable eigenvalues above the resolution limit.
pub fn unresolved_warning(a: &StabilityAssessment) -> String {
    if !a.unresolved.is_present() {
        return String::new();
    }
    format!(
        "; warning: {} unstable eigenvalue(s) above the resolution limit ω_res = {:.4e} (|Im λ| from {:.4e} to {:.4e}, max Re λ = {:.3e}) — the basis's, not the continuum's: excluded from the verdict. Refining does not remove them: their number grows with the basis and they stay above ω_res, which grows with it",
        a.unresolved.count,
        a.resolution_limit,
        a.unresolved.frequency_from,
        a.unresolved.frequency_to,
        a.unresolved.max_real_part
    )
}

/// The supercritical warning of a point: the string past |v̄| = 1, whose verdict is the
/// discrete model's (`contactlab::model::moving::resolution`).
pub fn supercritical_warning(a: &StabilityAssessment) -> String {
    let Some(w) = a.supercritical else {
        return String::new();
    };
    format!(
        "; warning: v̄ = {} is past the critical speed 1: the string between fixed guides is overdetermined there and the continuum's eigenvalues λ_n = inπ(1 − v̄²) are imaginary (marginal); this verdict is the discrete model's ({} eigenvalue(s) with Re λ above their band, growth rate {:.3e}), and refining does not remove it: the growth rate grows with the basis",
        w.speed, w.unstable_eigenvalues, w.discrete_growth_rate
    )
}

/// The verdict counts of a map, for the summary line.
pub fn map_summary<P>(m: &StabilityMap<P>) -> String {
    format!(
        ", map {} × {}: {} stable, {} marginal, {} divergence, {} flutter ({} points with \
         unstable unresolved eigenvalues: the basis's, not the verdict)",
        m.x.values.len(),
        m.y.values.len(),
        m.count(Verdict::Stable),
        m.count(Verdict::Marginal),
        m.count(Verdict::Divergence),
        m.count(Verdict::Flutter),
        m.count_unresolved()
    )
}

/// `map.json`.
#[derive(Serialize)]
pub struct MapJson<'a> {
    x_parameter: &'static str,
    x: &'a [f64],
    y_parameter: &'static str,
    y: &'a [f64],
    /// Row-major (point (ix, iy) at iy·nx + ix).
    verdict: Vec<&'static str>,
    max_real_part: Vec<f64>,
    critical_eigenvalue: Vec<[f64; 2]>,
    tolerance: Vec<f64>,
    /// ρ = max |λ| per point (the scale of the eigensolver's round-off).
    spectral_scale: Vec<f64>,
    /// The number of unstable eigenvalues above the resolution limit (the warning layer).
    unresolved_unstable: Vec<usize>,
}

/// The JSON of a map of any model.
pub fn map_json<P: AxisParameter>(m: &StabilityMap<P>) -> MapJson<'_> {
    MapJson {
        x_parameter: m.x.parameter.key(),
        x: &m.x.values,
        y_parameter: m.y.parameter.key(),
        y: &m.y.values,
        verdict: m.points.iter().map(|a| a.verdict.name()).collect(),
        max_real_part: m.points.iter().map(|a| a.max_real_part).collect(),
        critical_eigenvalue: m
            .points
            .iter()
            .map(|a| [a.critical_re, a.critical_im])
            .collect(),
        tolerance: m.points.iter().map(|a| a.tolerance).collect(),
        spectral_scale: m.points.iter().map(|a| a.spectral_scale).collect(),
        unresolved_unstable: m.points.iter().map(|a| a.unresolved.count).collect(),
    }
}
