//! The rotating plate without pad in `moving_plate`: the spatial-frame spectrum is the
//! body-frame one shifted, λ = i(±ω_{n,m} − nΩ) (Hetzler 2009, (72)–(74)): every eigenvalue of
//! the assembled quadratic problem (full tensor basis and modal basis) against the frequencies
//! ω_{n,m} of the same radial discretization computed harmonic by harmonic (a symmetric
//! generalized eigenproblem per n, no gyroscopic term) — to round-off, from Ω → 0 through the
//! critical speeds; and the tracked branches of an Ω sweep (Campbell diagram) each staying on
//! one line |ω_{n,m} ± nΩ| through every crossing.

use serde::{Deserialize, Serialize};

use contactlab::model::moving::plate::modes::harmonic_frequencies;
use contactlab::model::moving::plate::{PlateData, PlateParameter, PlateProperties};
use contactlab::model::moving::stability::VerdictParams;
use contactlab::model::moving::stability_map::GridAxis;
use contactlab::model::moving::sweep::sweep;
use contactlab::solve::quadratic_eigen::QuadraticEigenParams;

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::moving::cases::plate::common::{plate_model, spectrum};
use crate::plot::{Figure, Series};

/// `[rotating]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RotatingSection {
    pub harmonics: usize,
    pub elements: usize,
    /// The modal model compared too.
    pub radial_modes: usize,
    pub speeds: Vec<f64>,
    /// C of the bound C · 2n ε ρ on |λ − i(±ω − nΩ)| (2n eigenvalues, ρ = max |λ|).
    pub round_off: f64,
}

/// `[campbell]`.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CampbellSection {
    pub harmonics: usize,
    pub elements: usize,
    pub radial_modes: usize,
    /// Ω up to this × the largest critical speed ω_{N,0}/N.
    pub speed_factor_to: f64,
    pub points: usize,
    pub round_off: f64,
}

/// The predicted imaginary parts for a model with `harmonics` and `count` radial functions
/// (or modes) per harmonic: i(±ω_{n,m} ∓ nΩ), both signs for n ≥ 1 (cos and sin).
fn predicted(
    plate: &PlateProperties,
    elements: usize,
    harmonics: usize,
    count: usize,
    omega: f64,
) -> Result<Vec<f64>, String> {
    let mut out = Vec::new();
    for n in 0..=harmonics {
        let w = harmonic_frequencies(plate, elements, n, count).map_err(|e| e.to_string())?;
        let s = n as f64 * omega;
        for wm in w {
            if n == 0 {
                out.extend([wm, -wm]);
            } else {
                out.extend([wm - s, -wm - s, wm + s, -wm + s]);
            }
        }
    }
    out.sort_by(f64::total_cmp);
    Ok(out)
}

/// The round-off unit of a model on `elements` radial elements with `harmonics`: 2n ε ρ of the
/// FULL tensor basis (n its coordinates, ρ its largest |λ| = max ω + NΩ): a modal model's
/// matrices are projections of the full ones and carry their absolute round-off.
fn full_unit(
    plate: &PlateProperties,
    elements: usize,
    harmonics: usize,
    omega: f64,
) -> Result<f64, String> {
    let nr = 2 * elements; // radial functions at most (value and slope per node)
    let mut rho: f64 = 0.0;
    for n in 0..=harmonics {
        let w = harmonic_frequencies(plate, elements, n, nr).map_err(|e| e.to_string())?;
        rho = rho.max(w.last().copied().unwrap_or(0.0) + n as f64 * omega.abs());
    }
    let coords = (2 * harmonics + 1) * nr;
    Ok(2.0 * coords as f64 * f64::EPSILON * rho)
}

/// Runs both checks.
pub fn run(
    plate: PlateProperties,
    r: &RotatingSection,
    c: &CampbellSection,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    spectrum_check(plate, r, report)?;
    campbell(plate, c, ctx, report)
}

fn spectrum_check(
    plate: PlateProperties,
    r: &RotatingSection,
    report: &mut CaseReport,
) -> Result<(), String> {
    let full = plate_model(plate, r.harmonics, r.elements, None)?;
    let modal = plate_model(plate, r.harmonics, r.elements, Some(r.radial_modes))?;
    let radial = full.dimension() / (2 * r.harmonics + 1);
    let mut checks = Vec::new();
    for (model, count, label) in [
        (&full, radial, "full basis"),
        (&modal, r.radial_modes, "modal basis"),
    ] {
        let (mut worst_im, mut worst_re) = (0.0f64, 0.0f64);
        for &omega in &r.speeds {
            let data = PlateData {
                angular_speed: omega,
                damping: 0.0,
                pad: None,
            };
            let ev = spectrum(model, &data, false)?.eigenvalues;
            let expect = predicted(&plate, r.elements, r.harmonics, count, omega)?;
            if expect.len() != ev.len() {
                return Err(format!(
                    "{label}: {} eigenvalues, {} predicted",
                    ev.len(),
                    expect.len()
                ));
            }
            let unit = full_unit(&plate, r.elements, r.harmonics, omega)?;
            let mut im: Vec<f64> = ev.iter().map(|l| l.im).collect();
            im.sort_by(f64::total_cmp);
            for (a, b) in im.iter().zip(&expect) {
                worst_im = worst_im.max((a - b).abs() / unit);
            }
            for l in &ev {
                worst_re = worst_re.max(l.re.abs() / unit);
            }
        }
        checks.push(Check::at_most(
            &format!(
                "{label} ({} coordinates): max |Im λ − (±ω_{{n,m}} ∓ nΩ)| in units of 2n ε ρ (n, ρ of the full basis)",
                model.dimension()
            ),
            worst_im,
            r.round_off,
        ));
        checks.push(Check::at_most(
            &format!("{label}: max |Re λ| in units of 2n ε ρ"),
            worst_re,
            r.round_off,
        ));
    }
    report.gates.push(GateVerdict::from_checks(
        format!(
            "rotating plate, N = {}, {} elements: spatial-frame eigenvalues = i(±ω_{{n,m}} − nΩ) at Ω ∈ {:?}",
            r.harmonics, r.elements, r.speeds
        ),
        "exact",
        checks,
        "ω_{n,m}: the same radial discretization solved harmonic by harmonic without rotation",
    ));
    Ok(())
}

fn campbell(
    plate: PlateProperties,
    c: &CampbellSection,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let model = plate_model(plate, c.harmonics, c.elements, Some(c.radial_modes))?;
    let mut lines = Vec::new();
    let mut top: f64 = 0.0;
    for n in 0..=c.harmonics {
        let w = harmonic_frequencies(&plate, c.elements, n, c.radial_modes)
            .map_err(|e| e.to_string())?;
        if n > 0 {
            top = top.max(w[0] / n as f64);
        }
        for wm in w {
            lines.push((n, wm));
        }
    }
    let axis = GridAxis::linspace(
        PlateParameter::AngularSpeed,
        0.0,
        c.speed_factor_to * top,
        c.points,
    )
    .map_err(|e| e.to_string())?;
    let base = PlateData {
        angular_speed: 0.0,
        damping: 0.0,
        pad: None,
    };
    let sw = sweep(
        &model,
        &base,
        &axis,
        QuadraticEigenParams::default(),
        &VerdictParams::default(),
        0,
    )
    .map_err(|e| e.to_string())?;
    // each branch must stay on one line Im λ = s ω_{n,m} − t nΩ (s, t = ±1) along the sweep
    let unit = full_unit(&plate, c.elements, c.harmonics, c.speed_factor_to * top)?;
    let mut worst: f64 = 0.0;
    let mut unmatched = 0;
    for branch in &sw.branches.branches {
        let mut best = f64::INFINITY;
        for &(n, w) in &lines {
            for s in [1.0, -1.0] {
                for t in [1.0, -1.0] {
                    let dev = branch
                        .iter()
                        .zip(&axis.values)
                        .map(|(l, o)| (l.im - (s * w - t * n as f64 * o)).abs())
                        .fold(0.0, f64::max);
                    best = best.min(dev);
                }
            }
        }
        if best / unit > c.round_off {
            unmatched += 1;
        }
        worst = worst.max(best / unit);
    }
    report.gates.push(GateVerdict::from_checks(
        format!(
            "Campbell diagram, N = {}, {} radial modes, Ω ∈ [0, {:.4}] ({} points): every tracked branch on one line ±ω_{{n,m}} ∓ nΩ",
            c.harmonics,
            c.radial_modes,
            c.speed_factor_to * top,
            c.points
        ),
        "exact",
        vec![
            Check::at_most("branches that leave their line (swapped at a crossing)", unmatched as f64, 0.0),
            Check::at_most("max deviation of a branch from its line in units of 2n ε ρ (n, ρ of the full basis)", worst, c.round_off),
        ],
        "the linear predictor carries branches straight through the crossings of the forward and backward waves",
    ));
    let mut f = Figure::new(format!(
        "Campbell diagram of the rotating plate (spatial frame), N = {}",
        c.harmonics
    ))
    .x_label("Ω")
    .y_label("|Im λ|")
    .y_range(0.0, lines.iter().map(|l| l.1).fold(0.0, f64::max) * 0.6);
    for (k, branch) in sw.branches.branches.iter().enumerate() {
        if branch.first().is_some_and(|l| l.im > 0.0) {
            f = f.series(
                Series::line(
                    if k == 0 { "tracked branches" } else { "" },
                    branch
                        .iter()
                        .zip(&axis.values)
                        .map(|(l, o)| (*o, l.im.abs())),
                )
                .color(0),
            );
        }
    }
    for n in 1..=c.harmonics {
        if let Some(&(_, w)) = lines.iter().find(|l| l.0 == n) {
            f = f.vertical_line(w / n as f64, format!("ω_{{{n},0}}/{n}"));
        }
    }
    ctx.plot(report, "campbell", &f)?;
    Ok(())
}
