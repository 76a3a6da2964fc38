//! `moving_time_check`: every kind of verdict confirmed by time integration (`growth.rs`): the
//! growth rate of ln ‖(q, q̇)‖ observed with RK4 equals max Re λ, for stable, marginal,
//! divergent and fluttering systems of every model (string, string with oscillator under ideal
//! and penalty contact, thick string with friction, gyroscopic–circulatory without damping),
//! and the particle on the rotating disc integrated with its nonlinear friction force.

use std::path::Path;

use serde::{Deserialize, Serialize};

use contactlab::model::moving::disc::DiscParticle;
use contactlab::model::moving::stability::{assess, Verdict, VerdictParams};
use contactlab::model::moving::string_data::{ContactModel, MovingStringData, OscillatorData};
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};
use contactlab::solve::quadratic_eigen::QuadraticEigenParams;

use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::format::{invalid, positive};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::moving::plots::history_figure;
use crate::moving::study::{check_growth, envelope_slope, GrowthCheck};

/// The case format of `moving_time_check`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TimeCase {
    /// |σ_observed − max Re λ| ≤ absolute + relative · |max Re λ|.
    pub absolute_tolerance: f64,
    pub relative_tolerance: f64,
    pub point: Vec<StringPoint>,
    pub disc_point: Vec<DiscPoint>,
}

/// `[[point]]`: a string system.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StringPoint {
    pub name: String,
    pub modes: usize,
    pub speed: f64,
    pub damping: f64,
    pub stiffness: Option<f64>,
    pub mass: Option<f64>,
    pub position: Option<f64>,
    pub penalty_stiffness: Option<f64>,
    pub control_parameter: Option<f64>,
    /// stable | marginal | divergence | flutter.
    pub expect: Verdict,
    pub duration: f64,
}

/// `[[disc_point]]`: the particle on the disc, integrated with the nonlinear friction force.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DiscPoint {
    pub name: String,
    pub particle: DiscParticle,
    /// The initial radial displacement Δr(0) / r0.
    pub amplitude: f64,
    pub expect: Verdict,
    pub duration: f64,
}

impl TimeCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        positive(p, "absolute_tolerance", self.absolute_tolerance)?;
        positive(p, "relative_tolerance", self.relative_tolerance)?;
        for (i, s) in self.point.iter().enumerate() {
            positive(p, &format!("point[{i}].duration"), s.duration)?;
            let has = [s.stiffness, s.mass, s.position]
                .iter()
                .filter(|x| x.is_some())
                .count();
            if has != 0 && has != 3 {
                return Err(invalid(
                    p,
                    &format!("point[{i}]"),
                    &s.name,
                    "stiffness, mass and position together (an oscillator) or none",
                ));
            }
        }
        for (i, d) in self.disc_point.iter().enumerate() {
            positive(p, &format!("disc_point[{i}].duration"), d.duration)?;
            d.particle.validate().map_err(|e| {
                invalid(
                    p,
                    &format!("disc_point[{i}].particle"),
                    &e.value,
                    &e.to_string(),
                )
            })?;
        }
        Ok(())
    }
}

impl StringPoint {
    fn data(&self) -> MovingStringData {
        MovingStringData {
            speed: self.speed,
            damping: self.damping,
            oscillator: match (self.stiffness, self.mass, self.position) {
                (Some(c), Some(m), Some(a)) => {
                    let contact = self.penalty_stiffness.map_or(ContactModel::Ideal, |k| {
                        ContactModel::Penalty { stiffness: k }
                    });
                    let ks = match contact {
                        ContactModel::Ideal => c,
                        ContactModel::Penalty { stiffness } => stiffness,
                    };
                    Some(OscillatorData {
                        stiffness: c,
                        mass: m,
                        position: a,
                        contact,
                        friction: self.control_parameter.unwrap_or(0.0) / ks,
                        patch_width: 0.0,
                    })
                }
                _ => None,
            },
        }
    }
}

/// One checked point.
#[derive(Debug, Clone, Serialize)]
struct Row {
    name: String,
    expected: Verdict,
    verdict: Verdict,
    check: GrowthCheck,
}

/// Integrates m r̈ + c (r − r0) = F_r(r, ṙ) (nonlinear friction) by RK4 and returns (t, ln E)
/// with E = sqrt(c Δr² + m ṙ²).
fn integrate_disc(p: &DiscParticle, amplitude: f64, duration: f64) -> (Vec<f64>, Vec<f64>, f64) {
    let omega = (p.stiffness / p.mass).sqrt();
    let k = (0.02 / omega).min(duration / 2000.0);
    let steps = (duration / k).ceil() as usize;
    let f = |x: f64, v: f64| -> (f64, f64) {
        (
            v,
            (-p.stiffness * x + p.friction_force(p.radius + x, v)) / p.mass,
        )
    };
    let (mut x, mut v) = (amplitude * p.radius, 0.0);
    let every = (steps / 4000).max(1);
    let (mut ts, mut ys) = (Vec::new(), Vec::new());
    for n in 0..=steps {
        if n % every == 0 {
            ts.push(n as f64 * k);
            ys.push((p.stiffness * x * x + p.mass * v * v).sqrt().ln());
        }
        let (a1, b1) = f(x, v);
        let (a2, b2) = f(x + 0.5 * k * a1, v + 0.5 * k * b1);
        let (a3, b3) = f(x + 0.5 * k * a2, v + 0.5 * k * b2);
        let (a4, b4) = f(x + k * a3, v + k * b3);
        x += k / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
        v += k / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4);
    }
    (ts, ys, k)
}

/// Runs the case.
pub fn run(case: &TimeCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let verdict_params = VerdictParams::default();
    let mut rows = Vec::new();
    let mut figs = Vec::new();
    let tol = |sigma: f64| case.absolute_tolerance + case.relative_tolerance * sigma.abs();
    for (i, pt) in case.point.iter().enumerate() {
        let model = MovingStringModel::new(
            StringDiscretization::Sine { modes: pt.modes },
            Default::default(),
        )
        .map_err(|e| e.to_string())?;
        let sys = model
            .system(&pt.data())
            .map_err(|e| format!("{}: {e}", pt.name))?;
        let ev = sys
            .eigen(QuadraticEigenParams::default())
            .map_err(|e| format!("{}: {e}", pt.name))?
            .eigenvalues;
        let a = assess(&ev, &verdict_params);
        let (check, traj) = check_growth(
            &sys,
            a.max_real_part,
            a.spectral_scale,
            pt.duration,
            1000 + i as u64,
        )
        .map_err(|e| format!("{}: {e}", pt.name))?;
        report.gates.push(GateVerdict::from_checks(
            format!("{}: {}", pt.name, a.verdict.name()),
            "time_check",
            vec![
                Check::holds(
                    &format!("verdict {} (expected {})", a.verdict.name(), pt.expect.name()),
                    a.verdict == pt.expect,
                    pt.expect.name(),
                ),
                Check::within(
                    &format!("observed growth rate (RK4, τ ∈ [{:.0}, {:.0}]) vs max Re λ = {:.6e}", 0.5 * check.duration, check.duration, check.predicted),
                    check.observed,
                    check.predicted,
                    tol(check.predicted),
                ),
            ],
            "an integration of the linear system from a pseudo-random state, independent of the eigensolver",
        ));
        figs.push(history_figure(
            &pt.name,
            &traj.times,
            &traj.log_norms,
            check.predicted,
        ));
        rows.push(Row {
            name: pt.name.clone(),
            expected: pt.expect,
            verdict: a.verdict,
            check,
        });
    }
    for dp in &case.disc_point {
        let sys = dp.particle.system().map_err(|e| e.to_string())?;
        let ev = sys
            .eigen(QuadraticEigenParams::default())
            .map_err(|e| e.to_string())?
            .eigenvalues;
        let a = assess(&ev, &verdict_params);
        let (ts, ys, k) = integrate_disc(&dp.particle, dp.amplitude, dp.duration);
        let observed = envelope_slope(&ts, &ys, 0.5 * dp.duration, 10);
        let check = GrowthCheck {
            predicted: a.max_real_part,
            observed,
            step: k,
            duration: dp.duration,
            steps: (dp.duration / k).ceil() as usize,
        };
        report.gates.push(GateVerdict::from_checks(
            format!("{}: {}", dp.name, a.verdict.name()),
            "time_check",
            vec![
                Check::holds(
                    &format!("verdict {} (expected {})", a.verdict.name(), dp.expect.name()),
                    a.verdict == dp.expect,
                    dp.expect.name(),
                ),
                Check::within(
                    &format!("observed decay of the nonlinear system (Δr(0) = {:.0e} r0) vs max Re λ = {:.6e}", dp.amplitude, a.max_real_part),
                    observed,
                    a.max_real_part,
                    tol(a.max_real_part),
                ),
            ],
            "the nonlinear friction force −μN ṙ/sqrt(ṙ² + (Ωr)²), integrated: its small-amplitude decay is the linearization's",
        ));
        figs.push(
            history_figure(&dp.name, &ts, &ys, a.max_real_part).y_label("ln sqrt(cΔr² + mṙ²)"),
        );
        rows.push(Row {
            name: dp.name.clone(),
            expected: dp.expect,
            verdict: a.verdict,
            check,
        });
    }
    ctx.panels(
        report,
        "histories",
        "Time integration of each checked system: ln ‖(q, q̇)‖ against τ with the slope max Re λ of its eigenvalues",
        &figs,
        3,
    )?;
    ctx.write_data(report, &rows)
}
