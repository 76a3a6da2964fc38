//! `moving_penalty`: the penalty bushing (Hetzler 2009, (87)–(91), (104)–(108)) against ideal
//! contact.
//!
//! The bushing coordinate y_c is massless, so M is singular. Its equation
//! k̄_p (y_c − w(ā)) = c̄ (u − y_c) (and no friction term) makes the contact layer and the spring
//! two springs in series, c_eff = c̄ k̄_p/(c̄ + k̄_p) = c̄ − c̄²/k̄_p + O(k̄_p⁻²), and turns the
//! penalty friction force (μ k̄_p h̄/2)(w(ā) − y_c) into (μ h̄/2) c_eff (w(ā) − u). Hence:
//!
//! - Without friction: the penalty eigenvalues converge to the ideal ones at rate 1 in 1/k̄_p.
//!   The DAE pencil solved by QZ, the generic Schur condensation and the series-spring
//!   condensation agree.
//! - With friction: the nominal control parameter p = μ k̄_p h̄ of (108) — the coefficient of the
//!   circulatory matrix of the uncondensed system — grows linearly in k̄_p, and so does the
//!   penalty model's flutter boundary p*(v̄) in that parameter: it moves away from the ideal
//!   model's (the paper's warning). In the physical friction product μh̄, however, the boundary
//!   of the penalty model is the ideal model's with the spring c_eff, μh̄* = p*_ideal(c_eff)/c_eff,
//!   and converges to the ideal boundary at rate 1 in 1/k̄_p. A finite, physical k̄_p (a compliant
//!   contact layer, k̄_p ~ c̄) moves the boundary substantially — up or down, depending on v̄ —
//!   and k̄_p → ∞ recovers the kinematically exact contact. The verdict at a given friction
//!   depends on k̄_p: the penalty stiffness carries physics.

mod format;

pub use format::{Friction, Frictionless, Model, PenaltyCase, PenaltyMap};

use serde::Serialize;

use contactlab::model::moving::properties::skew_defect;
use contactlab::model::moving::stability::Verdict;
use contactlab::model::moving::stability_map::{
    string_stability_map, GridAxis, StabilityMapParams,
};
use contactlab::model::moving::string_data::{ContactModel, MovingStringData, StringParameter};
use contactlab::model::moving::string_model::{
    MovingStringModel, MovingStringParams, PenaltyCondensation, StringDiscretization,
};

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::moving::errors::{lowest_oscillating, max_real_part};
use crate::moving::plots::map_figure;
use crate::moving::study::{flutter_onset, model_eigenvalues, pencil_eigen};
use crate::plot::{Figure, Series};
use crate::stats::rate_fit::fit_rate;

/// The smallest friction product μh̄ in (0, hi] with max Re λ > 0, by bisection (the system at
/// μh̄ = 0 must be stable).
fn critical_friction(
    model: &MovingStringModel,
    base: &MovingStringData,
    hi: f64,
    rel_tol: f64,
) -> Result<f64, String> {
    let at = |mu_h: f64| -> Result<f64, String> {
        let mut d = *base;
        StringParameter::Friction
            .set(&mut d, mu_h)
            .map_err(|e| e.to_string())?;
        model_eigenvalues(model, &d).map(|ev| max_real_part(&ev))
    };
    flutter_onset(at, "μh̄", hi, rel_tol, 1e12)
}

/// The flutter boundary at one speed: (v̄, [(k̄_p (∞: ideal), μh̄*, nominal p*)]).
type BoundaryRow = (f64, Vec<(f64, f64, f64)>);

/// Runs the case.
pub fn run(case: &PenaltyCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let m = &case.model;
    let disc = StringDiscretization::Sine { modes: m.modes };
    let series =
        MovingStringModel::new(disc, MovingStringParams::default()).map_err(|e| e.to_string())?;
    let schur = MovingStringModel::new(
        disc,
        MovingStringParams {
            condensation: PenaltyCondensation::Schur,
        },
    )
    .map_err(|e| e.to_string())?;

    // Frictionless: convergence to ideal contact and agreement of the three paths.
    let f = &case.frictionless;
    let mc = f.modes_checked;
    let ideal = lowest_oscillating(
        &model_eigenvalues(
            &series,
            &m.bushing()
                .data(f.speed, f.damping, ContactModel::Ideal, 0.0),
        )?,
        mc,
        "ideal contact",
    )?;
    let mut conv = Vec::new();
    let mut agree: f64 = 0.0;
    let mut infinite_counts = Vec::new();
    for &kp in &f.penalties {
        let d = m.bushing().data(
            f.speed,
            f.damping,
            ContactModel::Penalty { stiffness: kp },
            0.0,
        );
        let pen = lowest_oscillating(
            &model_eigenvalues(&series, &d)?,
            mc,
            &format!("series springs, k̄_p = {kp}"),
        )?;
        let err = (0..f.modes_checked)
            .map(|k| (pen[k] - ideal[k]).norm() / ideal[k].norm())
            .fold(0.0, f64::max);
        conv.push((kp, err));
        if kp <= f.agreement_up_to {
            let via_schur = lowest_oscillating(
                &model_eigenvalues(&schur, &d)?,
                mc,
                &format!("Schur complement, k̄_p = {kp}"),
            )?;
            let full = series.system_with_bushing(&d).map_err(|e| e.to_string())?;
            let qz = pencil_eigen(&full).map_err(|e| e.to_string())?;
            infinite_counts.push((kp, qz.stats.infinite_eigenvalues));
            let via_qz = lowest_oscillating(&qz.eigenvalues, mc, &format!("QZ, k̄_p = {kp}"))?;
            // round-off unit: n ε (1 + k̄_p/c̄), n the order of the uncondensed pencil
            let unit = (2 * full.dimension()) as f64 * f64::EPSILON * (1.0 + kp / m.stiffness);
            for k in 0..f.modes_checked {
                agree = agree
                    .max((via_schur[k] - pen[k]).norm() / pen[k].norm() / unit)
                    .max((via_qz[k] - pen[k]).norm() / pen[k].norm() / unit);
            }
        }
    }
    let inv: Vec<f64> = conv.iter().map(|c| 1.0 / c.0).collect();
    let errs: Vec<f64> = conv.iter().map(|c| c.1).collect();
    report.gates.push(case.convergence_gate.criteria.evaluate(
        format!(
            "frictionless: penalty → ideal eigenvalues vs 1/k̄_p (v̄ = {})",
            f.speed
        ),
        &inv,
        &errs,
    ));
    report.gates.push(GateVerdict::from_checks(
        "the DAE (QZ), the Schur complement and the series springs agree".into(),
        "exact",
        vec![
            Check::at_most(
                &format!("max relative difference of the lowest {} eigenvalues, k̄_p ≤ {:.0e}, in units of n ε (1 + k̄_p/c̄)", f.modes_checked, f.agreement_up_to),
                agree,
                f.agreement_round_off,
            ),
            Check::holds(
                &format!("QZ finds 2 infinite eigenvalues (the massless y_c): {:?}", infinite_counts.iter().map(|c| c.1).collect::<Vec<_>>()),
                infinite_counts.iter().all(|c| c.1 == 2),
                "one massless coordinate = two infinite eigenvalues of the companion pencil",
            ),
        ],
        "condensing the massless bushing is exact: the finite eigenvalues of the singular-mass pencil",
    ));

    // With friction: nominal parameter, and flutter boundaries.
    let fr = &case.friction;
    let mut nominal = Vec::new();
    for &kp in &fr.penalties {
        let d = m.bushing().data(
            0.5,
            fr.damping,
            ContactModel::Penalty { stiffness: kp },
            0.1,
        );
        let full = series.system_with_bushing(&d).map_err(|e| e.to_string())?;
        let cond = series.system(&d).map_err(|e| e.to_string())?;
        nominal.push((
            kp,
            full.circulatory.norm_l2(),
            cond.circulatory.norm_l2(),
            skew_defect(full.circulatory.as_ref()),
        ));
    }
    let ideal_n = series
        .system(&m.bushing().data(0.5, fr.damping, ContactModel::Ideal, 0.1))
        .map_err(|e| e.to_string())?
        .circulatory
        .norm_l2();
    let large: Vec<&(f64, f64, f64, f64)> = nominal
        .iter()
        .filter(|x| x.0 >= 10.0 * m.stiffness)
        .collect();
    let slope = fit_rate(
        &large.iter().map(|x| x.0).collect::<Vec<_>>(),
        &large.iter().map(|x| x.1).collect::<Vec<_>>(),
        large.len(),
        0.95,
    )
    .map_err(|e| e.to_string())?;
    let last = nominal.last().copied().unwrap_or((0.0, 0.0, 0.0, 0.0));
    let n_full = (last_dimension(&series, m, fr)?) as f64;
    report.gates.push(GateVerdict::from_checks(
        "the nominal circulatory parameter p = μ k̄_p h̄ grows with k̄_p; its effect does not".into(),
        "penalty",
        vec![
            Check::at_most(
                "|log–log slope − 1| of ‖p N‖ (uncondensed, (108)) against k̄_p, k̄_p ≥ 10 c̄, in units of n ε",
                (slope.rate - 1.0).abs() / (n_full * f64::EPSILON),
                1.0,
            ),
            Check::at_most(
                &format!(
                    "condensed ‖p N‖ at k̄_p = {:.0e} vs the ideal model's: |relative difference − c̄/(c̄ + k̄_p)| in units of n ε",
                    last.0
                ),
                ((last.2 - ideal_n).abs() / ideal_n - m.stiffness / (m.stiffness + last.0)).abs()
                    / (n_full * f64::EPSILON),
                1.0,
            ),
        ],
        "(107) multiplies R by μ k̄_p h̄ exactly, so ‖pN‖ ∝ k̄_p (a slope other than 1 means the penalty friction is scaled by something else, e.g. c̄); condensed, the friction force (μh̄/2)c_eff(w(ā) − u) makes N = (c_eff/c̄) N_ideal, a relative difference of exactly c̄/(c̄ + k̄_p); both to the round-off of Frobenius norms of order-n matrices, n ε",
    ));

    let mut boundary_rows: Vec<BoundaryRow> = Vec::new();
    let mut identity_err: f64 = 0.0;
    let mut conv_rows: Vec<(f64, f64)> = Vec::new();
    for &v in &fr.speeds {
        let ideal_b = m.bushing().data(v, fr.damping, ContactModel::Ideal, 0.0);
        let mu_ideal = critical_friction(&series, &ideal_b, 0.05, fr.bisection_tolerance)?;
        let mut row = vec![(f64::INFINITY, mu_ideal, mu_ideal * m.stiffness)];
        for &kp in &fr.penalties {
            let pen_b =
                m.bushing()
                    .data(v, fr.damping, ContactModel::Penalty { stiffness: kp }, 0.0);
            let mu_pen = critical_friction(&schur, &pen_b, mu_ideal, fr.bisection_tolerance)?;
            // The ideal model with the series spring c_eff, computed independently.
            let c_eff = m.stiffness * kp / (m.stiffness + kp);
            let mut eff = ideal_b;
            StringParameter::OscillatorStiffness
                .set(&mut eff, c_eff)
                .map_err(|e| e.to_string())?;
            let mu_eff = critical_friction(&series, &eff, mu_ideal, fr.bisection_tolerance)?;
            identity_err = identity_err.max((mu_pen - mu_eff).abs() / mu_eff);
            if v == fr.speeds[0] {
                conv_rows.push((kp, (mu_pen - mu_ideal).abs() / mu_ideal));
            }
            row.push((kp, mu_pen, mu_pen * kp));
        }
        boundary_rows.push((v, row));
    }
    report.gates.push(GateVerdict::from_checks(
        "penalty flutter boundary = ideal boundary with the series spring c_eff".into(),
        "exact",
        vec![Check::at_most(
            "max |μh̄*_penalty (Schur) − p*_ideal(c_eff)/c_eff| / μh̄* vs two bisection brackets",
            identity_err,
            2.0 * fr.bisection_tolerance,
        )],
        "two independent paths: the Schur-condensed bushing system, and the ideal model with c̄ → c_eff; two bisections of growth rates that agree to round-off locate their zeros within two bracket widths",
    ));
    let large: Vec<&(f64, f64)> = conv_rows
        .iter()
        .filter(|x| x.0 >= 10.0 * m.stiffness)
        .collect();
    report.gates.push(case.boundary_gate.criteria.evaluate(
        format!(
            "critical μh̄ of the penalty model → ideal vs 1/k̄_p (v̄ = {})",
            fr.speeds[0]
        ),
        &large.iter().map(|x| 1.0 / x.0).collect::<Vec<_>>(),
        &large.iter().map(|x| x.1).collect::<Vec<_>>(),
    ));
    // Nominal p* against k̄_p: moves away linearly.
    let mut checks = Vec::new();
    for (v, row) in &boundary_rows {
        let pts: Vec<(f64, f64)> = row
            .iter()
            .skip(1)
            .filter(|x| x.0 >= 10.0 * m.stiffness)
            .map(|x| (x.0, x.2))
            .collect();
        let fit = fit_rate(
            &pts.iter().map(|x| x.0).collect::<Vec<_>>(),
            &pts.iter().map(|x| x.1).collect::<Vec<_>>(),
            pts.len(),
            0.95,
        )
        .map_err(|e| e.to_string())?;
        let p_ideal = row[0].2;
        let p_far = row.last().map_or(f64::NAN, |x| x.2);
        checks.push(Check::within(
            &format!("v̄ = {v}: log–log slope of the nominal p* = μ k̄_p h̄* against k̄_p"),
            fit.rate,
            1.0,
            fr.nominal_slope_tolerance,
        ));
        checks.push(Check::holds(
            &format!(
                "v̄ = {v}: nominal p* at k̄_p = {:.0e} is {:.1}× the ideal p* = μ c̄ h̄*",
                row.last().map_or(0.0, |x| x.0),
                p_far / p_ideal
            ),
            p_far / p_ideal > 10.0,
            "the boundary in p moves away from the ideal one",
        ));
    }
    report.gates.push(GateVerdict::from_checks(
        "the paper's warning: in p = μ k̄_p h̄ the penalty flutter boundary moves away as k̄_p grows".into(),
        "penalty",
        checks,
        "p* = k̄_p μh̄* with μh̄* → the ideal value: p* grows like k̄_p, so k̄_p must be the physical contact stiffness",
    ));

    // Map over (v̄, k̄_p) at a fixed friction product.
    let mp = &case.map;
    let mu_ref = critical_friction(
        &series,
        &m.bushing()
            .data(mp.reference_speed, fr.damping, ContactModel::Ideal, 0.0),
        0.05,
        fr.bisection_tolerance,
    )?;
    let mu_h = mp.friction_factor * mu_ref;
    let base = m.bushing().data(
        mp.reference_speed,
        fr.damping,
        ContactModel::Penalty { stiffness: 1.0 },
        mu_h,
    );
    let x = GridAxis::linspace(StringParameter::Speed, 0.0, mp.speed_to, mp.speeds)
        .map_err(|e| e.to_string())?;
    let (l0, l1) = (mp.penalty_from.ln(), mp.penalty_to.ln());
    let y = GridAxis {
        parameter: StringParameter::PenaltyStiffness,
        values: (0..mp.penalties)
            .map(|i| (l0 + (l1 - l0) * i as f64 / (mp.penalties - 1) as f64).exp())
            .collect(),
    };
    let map = string_stability_map(&series, &base, &x, &y, &StabilityMapParams::default())
        .map_err(|e| e.to_string())?;
    // Along v̄ = reference speed the boundary is k̄_p* with μh̄ c_eff(k̄_p*) = ... : check the
    // verdicts below/above the ideal-with-c_eff prediction on the grid column nearest it.
    let ix = x
        .values
        .iter()
        .enumerate()
        .min_by(|a, b| {
            (a.1 - mp.reference_speed)
                .abs()
                .total_cmp(&(b.1 - mp.reference_speed).abs())
        })
        .map_or(0, |(i, _)| i);
    let v_ref = x.values[ix];
    let mut wrong = 0;
    let mut column = Vec::new();
    for (iy, &kp) in y.values.iter().enumerate() {
        let c_eff = m.stiffness * kp / (m.stiffness + kp);
        let mut eff = m
            .bushing()
            .data(v_ref, fr.damping, ContactModel::Ideal, 0.0);
        StringParameter::OscillatorStiffness
            .set(&mut eff, c_eff)
            .map_err(|e| e.to_string())?;
        let mu_eff = critical_friction(&series, &eff, mu_ref, fr.bisection_tolerance)?;
        let predicted_unstable = mu_h > mu_eff * (1.0 + 1e-6);
        let predicted_stable = mu_h < mu_eff * (1.0 - 1e-6);
        // A point within the verdict tolerance of the axis is Marginal and agrees with both.
        let got = map.at(ix, iy).map(|a| a.verdict);
        let disagrees = match got {
            Some(Verdict::Marginal) => false,
            Some(v) => {
                (predicted_unstable && !v.is_unstable()) || (predicted_stable && v.is_unstable())
            }
            None => true,
        };
        if disagrees {
            wrong += 1;
        }
        column.push((kp, mu_eff, got.map(|v| v.name())));
    }
    report.gates.push(GateVerdict::from_checks(
        format!("(v̄, k̄_p) map at μh̄ = {:.3}× the ideal critical value", mp.friction_factor),
        "penalty",
        vec![
            Check::holds(
                &format!("v̄ = {v_ref:.3}: {wrong} of {} verdicts along k̄_p differ from the ideal model with c_eff", y.values.len()),
                wrong == 0,
                "0",
            ),
            Check::holds(
                &format!(
                    "the verdict changes along k̄_p on that column: {} stable, {} flutter points",
                    column.iter().filter(|c| c.2 == Some("stable")).count(),
                    column.iter().filter(|c| c.2 == Some("flutter")).count()
                ),
                column.iter().any(|c| c.2 == Some("stable"))
                    && column.iter().any(|c| c.2 == Some("flutter")),
                "both verdicts occur: the same friction is stable or not depending on k̄_p",
            ),
        ],
        "the verdict depends on k̄_p through c_eff: the penalty stiffness is physics, not numerics",
    ));

    // Plots.
    let mut fp = Figure::new("flutter boundary in the nominal p = μ k̄_p h̄ (moves away)")
        .x_label("v̄")
        .y_label("critical p")
        .semilog_y();
    let mut fm = Figure::new("flutter boundary in the friction product μh̄ (converges)")
        .x_label("v̄")
        .y_label("critical μh̄");
    let ncols = boundary_rows[0].1.len();
    for j in 0..ncols {
        let label = if j == 0 {
            "ideal contact".to_string()
        } else {
            format!("k̄_p = {}", boundary_rows[0].1[j].0)
        };
        let pts_p: Vec<(f64, f64)> = boundary_rows.iter().map(|(v, r)| (*v, r[j].2)).collect();
        let pts_m: Vec<(f64, f64)> = boundary_rows.iter().map(|(v, r)| (*v, r[j].1)).collect();
        let (sp, sm) = if j == 0 {
            (
                Series::line_markers(label.clone(), pts_p).color(6).dashed(),
                Series::line_markers(label, pts_m).color(6).dashed(),
            )
        } else {
            (
                Series::line_markers(label.clone(), pts_p).color(j - 1),
                Series::line_markers(label, pts_m).color(j - 1),
            )
        };
        fp = fp.series(sp);
        fm = fm.series(sm);
    }
    ctx.panels(
        report,
        "flutter_boundaries",
        "Penalty contact with friction: the flutter boundary in the nominal p = μ k̄_p h̄ moves away from the ideal one as k̄_p grows; in μh̄ it converges to it",
        &[fp, fm],
        2,
    )?;
    let fc = Figure::new("frictionless: penalty eigenvalues → ideal contact")
        .x_label("1/k̄_p")
        .y_label("max relative eigenvalue difference")
        .log_log()
        .series(
            Series::line_markers(
                "lowest 4 eigenvalues",
                conv.iter().map(|c| (1.0 / c.0, c.1)),
            )
            .color(0),
        )
        .series(
            Series::line_markers(
                format!("critical μh̄ with friction, v̄ = {}", fr.speeds[0]),
                conv_rows.iter().map(|c| (1.0 / c.0, c.1)),
            )
            .color(1),
        )
        .reference_slope(1.0, "slope 1");
    ctx.plot(report, "penalty_convergence", &fc)?;
    let fmap = map_figure(
        &format!(
            "verdicts over (v̄, k̄_p) at μh̄ = {:.4} ({}× ideal critical at v̄ = {})",
            mu_h, mp.friction_factor, mp.reference_speed
        ),
        "v̄",
        "k̄_p",
        &map,
        60,
        true,
    );
    ctx.plot(report, "map_speed_penalty", &fmap)?;

    #[derive(Serialize)]
    struct Data<'a> {
        frictionless_convergence: &'a [(f64, f64)],
        path_agreement: f64,
        nominal_circulatory_norm: &'a [(f64, f64, f64, f64)],
        ideal_circulatory_norm: f64,
        boundaries: &'a [BoundaryRow],
        identity_error: f64,
        critical_friction_convergence: &'a [(f64, f64)],
        map_friction: f64,
        map_stable: usize,
        map_flutter: usize,
        map_column: &'a [(f64, f64, Option<&'static str>)],
    }
    ctx.write_data(
        report,
        &Data {
            frictionless_convergence: &conv,
            path_agreement: agree,
            nominal_circulatory_norm: &nominal,
            ideal_circulatory_norm: ideal_n,
            boundaries: &boundary_rows,
            identity_error: identity_err,
            critical_friction_convergence: &conv_rows,
            map_friction: mu_h,
            map_stable: map.count(Verdict::Stable),
            map_flutter: map.count(Verdict::Flutter),
            map_column: &column,
        },
    )?;
    Ok(())
}

/// The order of the uncondensed (q, u, y_c) system of the friction study.
fn last_dimension(series: &MovingStringModel, m: &Model, fr: &Friction) -> Result<usize, String> {
    let d = m.bushing().data(
        0.5,
        fr.damping,
        ContactModel::Penalty { stiffness: 1.0 },
        0.1,
    );
    Ok(series
        .system_with_bushing(&d)
        .map_err(|e| e.to_string())?
        .dimension())
}
