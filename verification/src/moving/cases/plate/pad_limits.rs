//! The limits of the pad model in `moving_plate_pad`: its stiffness against the virtual work of
//! the friction force written here, the flutter onset μ* converged in the basis, k_p → ∞
//! against the point-constrained plate, and many harmonics without a false verdict.

use serde::Serialize;

use contactlab::model::moving::linearized::LinearizedModel;
use contactlab::model::moving::plate::modes::harmonic_frequencies;
use contactlab::model::moving::plate::{PlateData, PlateParameter, RotatingPlateModel};
use contactlab::model::moving::stability::{assess, Verdict, VerdictParams};
use contactlab::model::moving::stability_map::GridAxis;
use contactlab::model::moving::sweep::sweep;
use contactlab::model::moving::system::MovingSystem;
use contactlab::model::moving::{c64, Mat};
use contactlab::solve::quadratic_eigen::QuadraticEigenParams;

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict, RateCriteria};
use crate::core::report::case_report::CaseReport;
use crate::moving::cases::plate::common::{plate_model, spectrum};
use crate::moving::cases::plate::pad_format::PadCase;
use crate::moving::study::flutter_onset;
use crate::plot::{Figure, Series};

/// Per speed Ω: (harmonics, radial modes, coordinates, μ*) of each basis.
pub type OnsetRows = Vec<(f64, Vec<(usize, usize, usize, f64)>)>;

/// What the limits write to data.json.
#[derive(Debug, Clone, Serialize)]
pub struct LimitsData {
    virtual_work_error: f64,
    virtual_work_bound: f64,
    /// Per speed: (harmonics, radial modes, coordinates, μ*).
    onsets: OnsetRows,
    /// (k_p, max relative frequency error against the constrained plate, ρ / min |λ|, verdict).
    stiff_pad: Vec<(f64, f64, f64, Verdict)>,
    harmonics_verdicts: Vec<(f64, Verdict)>,
}

/// Runs the limits.
pub fn run(
    case: &PadCase,
    model: &RotatingPlateModel,
    omega_c: f64,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<LimitsData, String> {
    let (virtual_work_error, virtual_work_bound) = virtual_work(case, model, report)?;
    let onsets = onsets(case, ctx, report)?;
    let stiff_pad = stiff_pad(case, model, omega_c, ctx, report)?;
    let harmonics_verdicts = many_harmonics(case, report)?;
    Ok(LimitsData {
        virtual_work_error,
        virtual_work_bound,
        onsets,
        stiff_pad,
        harmonics_verdicts,
    })
}

/// K(μ) − K(0) against the virtual work of the friction force on the upper surface, written
/// here: the disc's surface moves with sign(Ω) e_φ, friction −μN sign(Ω) e_φ acts at z = h/2,
/// where a Kirchhoff plate moves in-plane by u_φ = −z (1/r) ∂w/∂φ; N = k_p w (the linear part).
/// So δW = μ k_p w sign(Ω) (h/2)(1/r_p) ∂δw/∂φ and ΔK = −μ k_p sign(Ω) h/(2 r_p) ∂_φΦ Φᵀ, with
/// ∂_φΦ by central differences of the basis values (error δ² N³/6 + ε/δ relative).
fn virtual_work(
    case: &PadCase,
    model: &RotatingPlateModel,
    report: &mut CaseReport,
) -> Result<(f64, f64), String> {
    let (mu, delta) = (0.4, 1e-4);
    let h = case.plate.thickness;
    let pad = case.pad;
    let (v, _) = model.point_values(pad.radius, pad.angle);
    let (vp, _) = model.point_values(pad.radius, pad.angle + delta);
    let (vm, _) = model.point_values(pad.radius, pad.angle - delta);
    let dphi: Vec<f64> = vp
        .iter()
        .zip(&vm)
        .map(|(a, b)| (a - b) / (2.0 * delta))
        .collect();
    let mut worst: f64 = 0.0;
    let mut scale: f64 = 0.0;
    for sign in [1.0, -1.0] {
        let mut d = PlateData {
            angular_speed: sign * 0.7,
            damping: 0.0,
            pad: Some(pad.with_friction(0.0)),
        };
        let k0 = model
            .system(&d)
            .map_err(|e| e.to_string())?
            .stiffness_matrix();
        if let Some(p) = d.pad.as_mut() {
            p.friction = mu;
        }
        let k1 = model
            .system(&d)
            .map_err(|e| e.to_string())?
            .stiffness_matrix();
        let c = mu * pad.stiffness * sign * h / (2.0 * pad.radius);
        let n = model.dimension();
        for i in 0..n {
            for j in 0..n {
                let expected = -c * dphi[i] * v[j];
                worst = worst.max((k1[(i, j)] - k0[(i, j)] - expected).abs());
                scale = scale.max(expected.abs());
            }
        }
    }
    let nh = case.basis.harmonics as f64;
    let bound = delta * delta * nh.powi(3) / 6.0 + 10.0 * f64::EPSILON / delta;
    let rel = worst / scale;
    report.gates.push(GateVerdict::from_checks(
        "the pad's friction stiffness against the virtual work of the friction force on the upper surface (Ω > 0 and Ω < 0)".into(),
        "independent",
        vec![Check::at_most(
            &format!("max |ΔK − (−μ k_p sign(Ω) h/(2r_p) ∂_φΦ Φᵀ)| / max |ΔK| (∂_φ by central differences, δ = {delta})"),
            rel,
            bound,
        )],
        "bound δ²N³/6 + 10ε/δ: the truncation of the central difference of cos Nφ and its round-off",
    ));
    Ok((rel, bound))
}

/// max Re λ at μ on `model` with damping α at Ω.
fn growth(model: &RotatingPlateModel, case: &PadCase, omega: f64, mu: f64) -> Result<f64, String> {
    let d = PlateData {
        angular_speed: omega,
        damping: case.friction.damping,
        pad: Some(case.pad.with_friction(mu)),
    };
    let ev = spectrum(model, &d, false)?.eigenvalues;
    Ok(ev.iter().map(|l| l.re).fold(f64::NEG_INFINITY, f64::max))
}

fn onsets(case: &PadCase, ctx: &RunContext, report: &mut CaseReport) -> Result<OnsetRows, String> {
    let o = &case.onset;
    let plate = case.plate.properties();
    let mut all = Vec::new();
    let mut fig = Figure::new(format!(
        "flutter onset μ* against the basis size (α = {})",
        case.friction.damping
    ))
    .x_label("coordinates")
    .y_label("μ*");
    for (si, &omega) in o.speeds.iter().enumerate() {
        let mut rows = Vec::new();
        for &[harmonics, modes] in &o.bases {
            let model = plate_model(plate, harmonics, o.elements, Some(modes))?;
            let mu = flutter_onset(|m| growth(&model, case, omega, m), "μ", 0.05, 1e-10, 1e3)?;
            rows.push((harmonics, modes, model.dimension(), mu));
        }
        let k = rows.len();
        let (a, b, c) = (rows[k - 3].3, rows[k - 2].3, rows[k - 1].3);
        let last = (c - b).abs() / c;
        report.gates.push(GateVerdict::from_checks(
            format!("flutter onset at Ω = {omega} converged in the basis: μ* = {c:.6}"),
            "convergence",
            vec![
                Check::at_most(
                    "relative change of μ* between the two largest bases",
                    last,
                    o.converged_to,
                ),
                Check::at_most(
                    "|Δμ*| of the last refinement / |Δμ*| of the one before (contraction)",
                    (c - b).abs() / (b - a).abs().max(f64::MIN_POSITIVE),
                    1.0,
                ),
            ],
            "bases (harmonics N, radial modes m) in the order of the case file",
        ));
        fig = fig.series(
            Series::line_markers(
                format!("Ω = {omega}"),
                rows.iter().map(|r| (r.2 as f64, r.3)),
            )
            .color(si),
        );
        all.push((omega, rows));
    }
    ctx.plot(report, "pad_onset_convergence", &fig)?;
    Ok(all)
}

/// Q = [u, Z] orthogonal with u = v/|v| (Householder): Z spans v⊥.
fn complement(v: &[f64]) -> Mat<f64> {
    let n = v.len();
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let s = if v[0] >= 0.0 { 1.0 } else { -1.0 };
    // H = I − 2 w wᵀ/(wᵀw), w = u + s e1: H u = −s e1, so H's columns 2..n span u⊥
    let mut w: Vec<f64> = v.iter().map(|x| x / norm).collect();
    w[0] += s;
    let ww: f64 = w.iter().map(|x| x * x).sum();
    Mat::from_fn(n, n - 1, |i, j| {
        let col = j + 1;
        f64::from(u8::from(i == col)) - 2.0 * w[i] * w[col] / ww
    })
}

fn upper_frequencies(ev: &[c64], count: usize) -> Vec<f64> {
    let mut f: Vec<f64> = ev.iter().filter(|l| l.im > 0.0).map(|l| l.im).collect();
    f.sort_by(f64::total_cmp);
    f.truncate(count);
    f
}

fn stiff_pad(
    case: &PadCase,
    model: &RotatingPlateModel,
    omega_c: f64,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<Vec<(f64, f64, f64, Verdict)>, String> {
    let s = &case.stiff_pad;
    let omega = s.speed_factor * omega_c;
    let free = PlateData {
        angular_speed: omega,
        damping: 0.0,
        pad: None,
    };
    let system = model.system(&free).map_err(|e| e.to_string())?;
    let (v, _) = model.point_values(case.pad.radius, case.pad.angle);
    let z = complement(&v);
    let project = |a: &Mat<f64>| z.transpose() * a * &z;
    let mut constrained = MovingSystem::zeros(vec![String::new(); z.ncols()]);
    constrained.mass = project(&system.mass);
    constrained.gyroscopic = project(&system.gyroscopic);
    constrained.stiffness = project(&system.stiffness);
    let reference = upper_frequencies(
        &constrained
            .eigen(QuadraticEigenParams::default())
            .map_err(|e| e.to_string())?
            .eigenvalues,
        s.frequencies,
    );
    let mut rows = Vec::new();
    for &kp in s.stiffnesses.iter().chain(&s.extreme_stiffnesses) {
        let mut d = free;
        d.pad = Some(case.pad.with_friction(0.0));
        if let Some(p) = d.pad.as_mut() {
            p.stiffness = kp;
        }
        let ev = spectrum(model, &d, false)?.eigenvalues;
        let f = upper_frequencies(&ev, s.frequencies);
        let err = f
            .iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).abs() / b)
            .fold(0.0, f64::max);
        let rho = ev.iter().map(|l| l.norm()).fold(0.0, f64::max);
        let small = ev.iter().map(|l| l.norm()).fold(f64::INFINITY, f64::min);
        rows.push((
            kp,
            err,
            rho / small,
            assess(&ev, &VerdictParams::default()).verdict,
        ));
    }
    let k = s.stiffnesses.len();
    let param: Vec<f64> = rows[..k].iter().map(|r| 1.0 / r.0).collect();
    let errors: Vec<f64> = rows[..k].iter().map(|r| r.1).collect();
    report.gates.push(
        RateCriteria {
            expected_rate: s.expected_rate,
            tolerance: s.tolerance,
            ci_width: s.ci_width,
            ceiling_factor: None,
            note: "a penalty spring converges to the point constraint like 1/k_p".into(),
        }
        .evaluate(
            format!(
                "k_p → ∞ at Ω = {}Ω_c: the lowest {} frequencies against the plate with w(r_p, φ_p) = 0 (eliminated), vs 1/k_p",
                s.speed_factor, s.frequencies
            ),
            &param,
            &errors,
        ),
    );
    let false_verdicts = rows.iter().filter(|r| r.3 != Verdict::Marginal).count();
    let worst_cond = rows.iter().map(|r| r.2).fold(0.0, f64::max);
    report.gates.push(GateVerdict::from_checks(
        format!(
            "stiff frictionless pads up to k_p = {:e} below Ω_c: no false verdict (conditioning ρ/min|λ| up to {worst_cond:.2e})",
            rows.last().map_or(0.0, |r| r.0)
        ),
        "theorem",
        vec![Check::at_most(
            "points not marginal (undamped, positive definite stiffness)",
            false_verdicts as f64,
            0.0,
        )],
        "Thomson–Tait: every eigenvalue on the imaginary axis",
    ));
    let f = Figure::new("stiff pad: frequencies against the point-constrained plate")
        .x_label("1/k_p")
        .y_label("max relative error")
        .log_log()
        .series(
            Series::line_markers(
                "lowest frequencies",
                param.iter().copied().zip(errors.iter().copied()),
            )
            .color(0),
        )
        .reference_slope(s.expected_rate, format!("slope {}", s.expected_rate));
    ctx.plot(report, "pad_stiff_limit", &f)?;
    Ok(rows)
}

fn many_harmonics(case: &PadCase, report: &mut CaseReport) -> Result<Vec<(f64, Verdict)>, String> {
    let hs = case.harmonics;
    let plate = case.plate.properties();
    let model = plate_model(
        plate,
        hs.harmonics,
        case.basis.elements,
        Some(hs.radial_modes),
    )?;
    let mut top: f64 = 0.0;
    let mut lowest = f64::INFINITY;
    for n in 1..=hs.harmonics {
        let w =
            harmonic_frequencies(&plate, case.basis.elements, n, 1).map_err(|e| e.to_string())?;
        top = top.max(w[0] / n as f64);
        lowest = lowest.min(w[0] / n as f64);
    }
    let axis = GridAxis::linspace(
        PlateParameter::AngularSpeed,
        0.0,
        hs.speed_factor_to * top,
        hs.speeds,
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
    let verdicts: Vec<(f64, Verdict)> = axis
        .values
        .iter()
        .zip(&sw.assessments)
        .map(|(o, a)| (*o, a.verdict))
        .collect();
    let mut pad_base = base;
    pad_base.pad = Some(case.pad.with_friction(0.0));
    let below = GridAxis::linspace(PlateParameter::AngularSpeed, 0.0, 0.99 * lowest, hs.speeds)
        .map_err(|e| e.to_string())?;
    let with_pad = sweep(
        &model,
        &pad_base,
        &below,
        QuadraticEigenParams::default(),
        &VerdictParams::default(),
        0,
    )
    .map_err(|e| e.to_string())?;
    let bad = sw
        .assessments
        .iter()
        .chain(&with_pad.assessments)
        .filter(|a| a.verdict != Verdict::Marginal)
        .count();
    report.gates.push(GateVerdict::from_checks(
        format!(
            "N = {} harmonics ({} coordinates): no false verdict from Ω = 0 to {}× the largest critical speed {top:.4} (no pad), and below Ω_c with the frictionless pad",
            hs.harmonics,
            model.dimension(),
            hs.speed_factor_to
        ),
        "theorem",
        vec![Check::at_most(
            &format!("points not marginal of {}", sw.assessments.len() + with_pad.assessments.len()),
            bad as f64,
            0.0,
        )],
        "without pad each harmonic is (λ + inΩ)² M + K = 0: purely imaginary λ at every Ω, also beyond the critical speeds",
    ));
    Ok(verdicts)
}
