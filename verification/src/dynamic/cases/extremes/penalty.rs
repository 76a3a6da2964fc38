//! `[[penalty]]` of `dynamic_extremes`: the penalty stiffness r over many decades on an impact.
//! Per run: the condition of the step Jacobian J = α M + θ K + Σ_i w_i N_i′(p_i) e_i e_iᵀ (full
//! path) and of its Schur complement on the contact dofs (condensed path) by a dense symmetric
//! eigen-decomposition, at the peak of the impact and in the worst case; Newton iterations and
//! backtracks; the largest penetration; the energy identities (1.48)/(1.49)/HLT 3.7 (BDS; HLT).
//! Over the sweep: the asymptotic slope of the largest penetration and of κ(J) in r, and the
//! agreement of the solver paths.

use nalgebra::{DMatrix, SymmetricEigen};

use contactlab::contact::compliance::{energy_consistent, penalty};
use contactlab::model::dynamic::contact_model::NormalTreatment;
use contactlab::model::dynamic::newton::NodeForces;
use contactlab::model::dynamic::scheme::DynamicScheme;
use contactlab::model::dynamic::solver::StepView;
use contactlab::scene::dynamic::DynamicScene;

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::plot::{Figure, Series};

use super::common::{header, push_run_gate, run_one, set1, slope_line, slug, Run};
use super::PenaltySpec;

/// The state of the step with the largest contact force: u_{n−1}, u_n and each contact node's
/// p_{n−1}, p_n.
#[derive(Debug, Clone, Default)]
struct PeakState {
    force: f64,
    u_prev: Vec<f64>,
    u_now: Vec<f64>,
    p_prev: Vec<f64>,
    p_now: Vec<f64>,
}

/// Tracks [`PeakState`] along a run.
#[derive(Debug, Default)]
struct PeakTracker {
    u_last: Vec<f64>,
    p_last: Vec<f64>,
    peak: PeakState,
}

impl PeakTracker {
    fn observe(&mut self, v: &StepView<'_>) {
        let p: Vec<f64> = v.forces.iter().map(|f: &NodeForces| f.p).collect();
        if v.step > 0 && v.record.contact_force > self.peak.force {
            self.peak = PeakState {
                force: v.record.contact_force,
                u_prev: self.u_last.clone(),
                u_now: v.displacement.to_vec(),
                p_prev: self.p_last.clone(),
                p_now: p.clone(),
            };
        }
        self.u_last.clear();
        self.u_last.extend_from_slice(v.displacement);
        self.p_last = p;
    }
}

/// Condition numbers of the step Jacobian, λ_max/λ_min (∞ when not positive definite).
#[derive(Debug, Clone, Copy)]
struct Conditions {
    /// J at the peak state, and its Schur complement on the contact dofs.
    peak: f64,
    peak_schur: f64,
    /// J with every contact node in contact over the whole step (the law's full slope on every
    /// Γ3 normal dof): the worst case of the run.
    worst: f64,
    worst_schur: f64,
}

/// The condition numbers of the step Jacobian J = α M + θ K(u) + Σ_i w_i N_i′ e_{ν,i} e_{ν,i}ᵀ
/// and of its Schur complement S = J_ΓΓ − J_ΓI J_II⁻¹ J_IΓ on the contact dofs Γ (what the
/// condensed path factors), (i) at the peak state, N_i′ the slope of the node's compliance law
/// at (p_{n−1}, p_n) there, and (ii) in the worst case, every node in contact at both ends of
/// the step (N′ = r for the penalty force, r/2 for the energy-consistent one). For
/// r w_i ≫ λ_max(α M + θ K) the largest eigenvalue is ≈ r max_i w_i and κ grows like r.
fn conditions(scene: &DynamicScene, peak: &PeakState) -> Option<Conditions> {
    let (peak_full, peak_schur) = condition_numbers(scene, peak, false)?;
    let (worst, worst_schur) = condition_numbers(scene, peak, true)?;
    Some(Conditions {
        peak: peak_full,
        peak_schur,
        worst,
        worst_schur,
    })
}

fn condition_numbers(scene: &DynamicScene, peak: &PeakState, worst: bool) -> Option<(f64, f64)> {
    let pb = &scene.problem;
    let body = &pb.body;
    let contact = pb.contact.as_ref()?;
    let n = body.dofs();
    let k = pb.final_time / pb.steps as f64;
    let alpha = pb.scheme.alpha(k);
    let pattern = body.pattern();
    let mut values: Vec<f64> = body.mass().iter().map(|m| alpha * m).collect();
    let u_prev = if peak.u_prev.len() == n {
        peak.u_prev.clone()
    } else {
        vec![0.0; n]
    };
    let u_now = if peak.u_now.len() == n {
        peak.u_now.clone()
    } else {
        vec![0.0; n]
    };
    match (body.linear_stiffness(), pb.scheme) {
        (Some(kv), s) => {
            let theta = if s == DynamicScheme::Newmark {
                1.0
            } else {
                0.5
            };
            for (v, kk) in values.iter_mut().zip(kv) {
                *v += theta * kk;
            }
        }
        (None, DynamicScheme::Newmark) => body.add_tangent(&u_now, 1.0, &mut values),
        (None, DynamicScheme::Midpoint) => {
            let mid: Vec<f64> = u_prev
                .iter()
                .zip(&u_now)
                .map(|(a, b)| 0.5 * (a + b))
                .collect();
            body.add_tangent(&mid, 0.5, &mut values);
        }
        (None, DynamicScheme::Gonzalez) => {
            body.add_discrete_gradient_tangent(&u_prev, &u_now, 1.0, &mut values)
        }
    }
    let mut j = DMatrix::<f64>::zeros(n, n);
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    for col in 0..n {
        for s in cp[col]..cp[col + 1] {
            j[(ri[s], col)] = values[s];
            j[(col, ri[s])] = values[s];
        }
    }
    for (i, nd) in contact.nodes.iter().enumerate() {
        let (q, p) = if worst {
            (1e-3, 2e-3)
        } else {
            (
                peak.p_prev.get(i).copied().unwrap_or(0.0),
                peak.p_now.get(i).copied().unwrap_or(0.0),
            )
        };
        let slope = match contact.treatment {
            NormalTreatment::Penalty { stiffness } => penalty(stiffness, p).slope,
            NormalTreatment::EnergyConsistent { stiffness }
            | NormalTreatment::HauretLeTallecTilted { stiffness }
            | NormalTreatment::LimitedPenetration { stiffness, .. } => {
                energy_consistent(stiffness, q, p).slope
            }
            NormalTreatment::Signorini => 0.0,
        };
        j[(nd.normal_dof, nd.normal_dof)] += nd.weight * slope;
    }
    let kappa = |m: DMatrix<f64>| -> f64 {
        let ev = SymmetricEigen::new(m).eigenvalues;
        let (lo, hi) = ev
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        if lo > 0.0 {
            hi / lo
        } else {
            f64::INFINITY
        }
    };
    let gamma = contact.dofs();
    let mut is_gamma = vec![false; n];
    for &g in &gamma {
        is_gamma[g] = true;
    }
    let interior: Vec<usize> = (0..n).filter(|&i| !is_gamma[i]).collect();
    let jii = j.select_rows(&interior).select_columns(&interior);
    let jig = j.select_rows(&interior).select_columns(&gamma);
    let jgg = j.select_rows(&gamma).select_columns(&gamma);
    let schur = match jii.cholesky() {
        Some(ch) => {
            let x = ch.solve(&jig);
            let s = &jgg - jig.transpose() * x;
            kappa(0.5 * (&s + s.transpose()))
        }
        None => f64::INFINITY,
    };
    Some((kappa(j), schur))
}

pub(super) fn run_penalty(
    index: usize,
    spec: &PenaltySpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let study = format!("penalty: {}", spec.name);
    struct Point {
        r: f64,
        path: String,
        run: Run,
        kappa: Option<Conditions>,
    }
    let mut points: Vec<Point> = Vec::new();
    for path in &spec.paths {
        for &r in &spec.stiffness {
            let mut set = set1("contact.stiffness", r);
            set.insert("solver.path".into(), path.clone().into());
            let mut tracker = PeakTracker::default();
            let run = run_one(
                &format!("r = {r:.0e}, {path} path"),
                &spec.scene,
                &set,
                &mut |v| tracker.observe(v),
            )?;
            let kappa =
                if path == "auto" && run.scene.problem.body.dofs() <= spec.condition_max_dofs {
                    conditions(&run.scene, &tracker.peak)
                } else {
                    None
                };
            points.push(Point {
                r,
                path: path.clone(),
                run,
                kappa,
            });
        }
    }
    let mut rows = Vec::new();
    for p in &points {
        let (its, max_it) = p.run.newton();
        let mut checks = Vec::new();
        if p.run.completed() {
            checks.extend(p.run.audit_checks());
            checks.push(Check::at_most(
                &format!("{}: Newton iterations of the worst step", p.run.label),
                max_it as f64,
                spec.max_newton_iterations as f64,
            ));
        }
        push_run_gate(
            report,
            &study,
            &p.run,
            checks,
            "a correct run (identities at round-off) or a typed error",
            &spec.note,
        );
        let steps = p.run.records().len().saturating_sub(1).max(1);
        let difference = points
            .iter()
            .find(|q| q.r == p.r && q.path == spec.paths[0])
            .map(|q| {
                let (a, b) = (q.run.max_penetration(), p.run.max_penetration());
                (a - b).abs() / a.abs().max(b.abs())
            })
            .unwrap_or(f64::NAN);
        rows.push(vec![
            format!("{:.0e}", p.r),
            p.path.clone(),
            format!("{difference:.1e}"),
            p.run.outcome(),
            p.kappa.map_or("—".into(), |k| format!("{:.3e}", k.peak)),
            p.kappa
                .map_or("—".into(), |k| format!("{:.3e}", k.peak_schur)),
            p.kappa.map_or("—".into(), |k| format!("{:.3e}", k.worst)),
            p.kappa
                .map_or("—".into(), |k| format!("{:.3e}", k.worst_schur)),
            format!("{:.4e}", p.run.max_penetration()),
            format!("{:.4e}", p.run.max_contact_force()),
            format!("{:.2} / {max_it}", its as f64 / steps as f64),
            format!("{}", p.run.backtracks()),
            format!("{:.2e}", p.run.summary_value(|s| s.max_drift_1_48)),
            format!("{:.2e}", p.run.summary_value(|s| s.max_drift_1_49)),
            format!("{:.2e}", p.run.summary_value(|s| s.max_drift_3_7)),
        ]);
    }
    // study-level gates on the model's own path
    let auto: Vec<&Point> = points.iter().filter(|p| p.path == spec.paths[0]).collect();
    let tail: Vec<(f64, f64)> = auto
        .iter()
        .filter(|p| p.r >= spec.slope_from && p.run.completed())
        .map(|p| (p.r, p.run.max_penetration()))
        .collect();
    let slope = log_slope(&tail);
    let mut checks = vec![Check::within(
        &format!(
            "slope of ln(max penetration) against ln r for r ≥ {:.0e} ({} path)",
            spec.slope_from, spec.paths[0]
        ),
        slope,
        spec.expected_slope,
        spec.slope_tolerance,
    )];
    let decreasing = auto
        .windows(2)
        .all(|w| w[1].run.max_penetration() < w[0].run.max_penetration());
    checks.push(Check::holds(
        "max penetration decreases strictly with r",
        decreasing,
        "monotone",
    ));
    if let Some(expected) = spec.expected_condition_slope {
        let from = spec.condition_slope_from.unwrap_or(spec.slope_from);
        let kp: Vec<(f64, f64)> = auto
            .iter()
            .filter(|p| p.r >= from)
            .filter_map(|p| p.kappa.map(|k| (p.r, k.worst)))
            .collect();
        checks.push(Check::holds(
            "the step Jacobian and its Schur complement are positive definite, at the peak and in the worst case (finite κ)",
            auto.iter().all(|p| {
                p.kappa.is_none_or(|k| {
                    [k.peak, k.peak_schur, k.worst, k.worst_schur]
                        .iter()
                        .all(|v| v.is_finite())
                })
            }),
            "λ_min > 0",
        ));
        checks.push(Check::within(
            &format!("slope of ln κ(J) (worst case) against ln r for r ≥ {from:.0e}"),
            log_slope(&kp),
            expected,
            spec.slope_tolerance,
        ));
    }
    if let (Some(tol), true) = (spec.path_agreement, spec.paths.len() > 1) {
        let mut worst: f64 = 0.0;
        let up_to = spec.path_agreement_up_to.unwrap_or(f64::INFINITY);
        for p in auto.iter().filter(|p| p.r <= up_to && p.run.completed()) {
            for q in points
                .iter()
                .filter(|q| q.path != p.path && q.r == p.r && q.run.completed())
            {
                let (a, b) = (p.run.max_penetration(), q.run.max_penetration());
                worst = worst.max((a - b).abs() / a.abs().max(b.abs()));
            }
        }
        checks.push(Check::at_most(
            &format!(
                "largest relative difference of the max penetration between the paths (completed runs, r ≤ {up_to:.0e})"
            ),
            worst,
            tol,
        ));
    }
    report.gates.push(GateVerdict::from_checks(
        format!("{study}: trends in r"),
        "extreme",
        checks,
        &spec.note,
    ));
    report.tables.push(Table {
        title: format!("{study} ({})", points[0].run.scene.problem.body.describe()),
        header: header(&[
            "r",
            "path",
            "Δp_max vs first path",
            "outcome",
            "κ(J) at peak",
            "κ(S_Γ) at peak",
            "κ(J) worst",
            "κ(S_Γ) worst",
            "max penetration",
            "max contact force",
            "Newton its per step (mean / max)",
            "backtracks",
            "max |R(1.48)|/E_ref",
            "max |R(1.49)|/E_ref",
            "max |R(3.7)|/E_ref",
        ]),
        rows,
    });
    // plots
    let mut pen = Figure::new(format!("{}: largest penetration against r", spec.name))
        .x_label("penalty stiffness r")
        .y_label("max_n max_i p_i")
        .log_log();
    let mut its = Figure::new("Newton iterations per step")
        .x_label("penalty stiffness r")
        .y_label("iterations")
        .semilog_x();
    let mut cond = Figure::new("condition at the peak of the impact")
        .x_label("penalty stiffness r")
        .y_label("κ = λ_max / λ_min")
        .log_log();
    for (c, path) in spec.paths.iter().enumerate() {
        let pts: Vec<&Point> = points.iter().filter(|p| &p.path == path).collect();
        pen = pen.series(
            Series::line_markers(
                format!("{path} path"),
                pts.iter().map(|p| (p.r, p.run.max_penetration())),
            )
            .color(c),
        );
        its = its
            .series(
                Series::line_markers(
                    format!("{path}: mean"),
                    pts.iter().map(|p| {
                        let n = p.run.records().len().saturating_sub(1).max(1);
                        (p.r, p.run.newton().0 as f64 / n as f64)
                    }),
                )
                .color(c),
            )
            .series(
                Series::line_markers(
                    format!("{path}: max"),
                    pts.iter().map(|p| (p.r, p.run.newton().1 as f64)),
                )
                .color(c)
                .dashed(),
            );
    }
    // reference power laws over the asymptotic ranges, anchored a factor 2 below the data
    let r_max = spec.stiffness.iter().copied().fold(0.0, f64::max);
    if let Some(p0) = auto
        .iter()
        .find(|p| p.r >= spec.slope_from && p.run.completed())
    {
        let y0 = 0.5 * p0.run.max_penetration();
        pen = pen
            .series(slope_line(
                &format!("slope {}", spec.expected_slope),
                (p0.r, y0),
                r_max,
                spec.expected_slope,
            ))
            .series(slope_line("slope −1", (p0.r, y0), r_max, -1.0).color(6));
    }
    cond = cond
        .series(
            Series::line_markers(
                "κ(J) worst case",
                points
                    .iter()
                    .filter_map(|p| p.kappa.map(|k| (p.r, k.worst))),
            )
            .color(0),
        )
        .series(
            Series::line_markers(
                "κ(S_Γ) worst case",
                points
                    .iter()
                    .filter_map(|p| p.kappa.map(|k| (p.r, k.worst_schur))),
            )
            .color(1),
        )
        .series(
            Series::line_markers(
                "κ(J) at the peak",
                points.iter().filter_map(|p| p.kappa.map(|k| (p.r, k.peak))),
            )
            .color(0)
            .dashed(),
        )
        .series(
            Series::line_markers(
                "κ(S_Γ) at the peak",
                points
                    .iter()
                    .filter_map(|p| p.kappa.map(|k| (p.r, k.peak_schur))),
            )
            .color(1)
            .dashed(),
        );
    let from = spec.condition_slope_from.unwrap_or(spec.slope_from);
    if let Some(k0) = auto
        .iter()
        .find(|p| p.r >= from)
        .and_then(|p| p.kappa.map(|k| (p.r, k.worst)))
    {
        cond = cond.series(slope_line("slope 1", (k0.0, 0.5 * k0.1), r_max, 1.0));
    }
    ctx.panels(
        report,
        &format!("penalty_{index}_{}", slug(&spec.name)),
        &format!(
            "{}: penetration, Newton iterations and condition against r",
            spec.name
        ),
        &[pen, its, cond],
        3,
    )
}

/// Least-squares slope of ln y against ln x.
fn log_slope(points: &[(f64, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    sxy / sxx
}
