//! `moving_disc`: the particle pressed on a rotating disc (Hetzler 2009, §4.2.3, (109)–(112)).
//!
//! - The damping μN/(|Ω| r0) is recovered from the eigenvalues of the linearized model,
//!   −m (λ₁ + λ₂) (Vieta), to round-off across Ω from overdamped (real eigenvalues) to lightly
//!   damped: an exact check of a frictional-contact linearization.
//! - The linearization itself is checked independently: the radial friction force is written
//!   again here from the relative velocity v_rel = ṙ e_r − Ω r e_t and differentiated by
//!   automatic differentiation (num-dual) at the steady state: ∂F_r/∂ṙ = −μN/(|Ω| r0) and
//!   ∂F_r/∂r = 0 to round-off.

use std::path::Path;

use num_dual::{Dual64, DualNum};
use serde::{Deserialize, Serialize};

use contactlab::model::moving::disc::DiscParticle;
use contactlab::solve::quadratic_eigen::QuadraticEigenParams;

use crate::core::context::RunContext;
use crate::core::format::positive;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::plot::{Figure, Series};

/// The case format of `moving_disc`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DiscCase {
    /// The particle (its angular speed is swept).
    pub particle: DiscParticle,
    pub sweep: DiscSweep,
}

/// `[sweep]`: Ω from `from` to `to`, geometric.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DiscSweep {
    pub from: f64,
    pub to: f64,
    pub points: usize,
    /// |d_recovered − μN/(Ω r0)| ≤ this × ε m max|λ| (round-off of the eigenvalues); also the
    /// bound, in units of ε, of the relative difference of the automatic derivative and
    /// μN/(Ω r0), of |∂F_r/∂r| r0/(μN), and of the two force formulas (a few rounded operations
    /// each: a square root, a division, two products).
    pub round_off_factor: f64,
}

impl DiscCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        self.particle.validate().map_err(|e| {
            crate::core::format::invalid(p, &format!("particle.{}", e.field), &e.value, &e.expected)
        })?;
        positive(p, "sweep.from", self.sweep.from)?;
        positive(p, "sweep.to", self.sweep.to)?;
        positive(p, "sweep.round_off_factor", self.sweep.round_off_factor)?;
        if self.sweep.points < 2 {
            return Err(crate::core::format::invalid(
                p,
                "sweep.points",
                self.sweep.points,
                ">= 2",
            ));
        }
        Ok(())
    }
}

/// F_r from the relative velocity, in any dual number type: the particle moves with ṙ e_r, the
/// disc's material under it with Ω r e_t; friction opposes v_rel = ṙ e_r − Ω r e_t.
fn radial_friction<D: DualNum<Primitive = f64> + Copy>(p: &DiscParticle, r: D, rdot: D) -> D {
    let vt = r * (-p.angular_speed);
    let speed = (rdot * rdot + vt * vt).sqrt();
    -(rdot / speed) * (p.friction_coefficient * p.normal_force)
}

#[derive(Debug, Clone, Serialize)]
struct Row {
    omega: f64,
    damping: f64,
    recovered: f64,
    round_off_units: f64,
    eigenvalues: Vec<[f64; 2]>,
    ad_damping: f64,
    ad_stiffness: f64,
}

/// Runs the case.
pub fn run(case: &DiscCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let s = &case.sweep;
    let (l0, l1) = (s.from.ln(), s.to.ln());
    let mut rows = Vec::new();
    for i in 0..s.points {
        let omega = (l0 + (l1 - l0) * i as f64 / (s.points - 1) as f64).exp();
        let p = DiscParticle {
            angular_speed: omega,
            ..case.particle
        };
        let sys = p.system().map_err(|e| e.to_string())?;
        let ev = sys
            .eigen(QuadraticEigenParams::default())
            .map_err(|e| e.to_string())?
            .eigenvalues;
        let recovered = -p.mass * ev.iter().map(|l| l.re).sum::<f64>();
        let rho = ev.iter().map(|l| l.norm()).fold(0.0, f64::max);
        let d = p.friction_damping();
        let round_off_units = (recovered - d).abs() / (f64::EPSILON * p.mass * rho);
        let dv = radial_friction(&p, Dual64::from(p.radius), Dual64::from(0.0).derivative()).eps;
        let dr = radial_friction(&p, Dual64::from(p.radius).derivative(), Dual64::from(0.0)).eps;
        rows.push(Row {
            omega,
            damping: d,
            recovered,
            round_off_units,
            eigenvalues: ev.iter().map(|l| [l.re, l.im]).collect(),
            ad_damping: -dv,
            ad_stiffness: dr,
        });
    }
    let worst_units = rows.iter().map(|r| r.round_off_units).fold(0.0, f64::max);
    let worst_rel = rows
        .iter()
        .map(|r| (r.recovered - r.damping).abs() / r.damping)
        .fold(0.0, f64::max);
    let overdamped = rows
        .iter()
        .filter(|r| r.eigenvalues.iter().all(|l| l[1] == 0.0))
        .count();
    report.gates.push(GateVerdict::from_checks(
        format!("damping μN/(Ω r0) recovered from the eigenvalues, Ω ∈ [{}, {}]", s.from, s.to),
        "exact",
        vec![
            Check::at_most(
                "max |−m(λ₁ + λ₂) − μN/(Ω r0)| in units of ε m max|λ|",
                worst_units,
                s.round_off_factor,
            ),
            Check::holds(
                &format!("{overdamped} overdamped and {} underdamped points (largest relative error {worst_rel:.2e})", rows.len() - overdamped),
                overdamped > 0 && overdamped < rows.len(),
                "both regimes covered",
            ),
        ],
        "Vieta: λ₁ + λ₂ = −d/m for m λ² + d λ + c = 0",
    ));
    let worst_ad = rows
        .iter()
        .map(|r| {
            ((r.ad_damping - r.damping).abs() / r.damping).max(
                r.ad_stiffness.abs() * case.particle.radius
                    / (case.particle.friction_coefficient * case.particle.normal_force),
            )
        })
        .fold(0.0, f64::max);
    let worst_force = rows
        .iter()
        .map(|r| {
            let p = DiscParticle {
                angular_speed: r.omega,
                ..case.particle
            };
            let (rr, vv) = (p.radius * 1.01, 0.3 * r.omega * p.radius);
            (p.friction_force(rr, vv) - radial_friction(&p, rr, vv)).abs()
                / (p.friction_coefficient * p.normal_force)
        })
        .fold(0.0, f64::max);
    report.gates.push(GateVerdict::from_checks(
        "the linearization against automatic differentiation of the friction force".into(),
        "exact",
        vec![
            Check::at_most(
                "max relative |∂F_r/∂ṙ (num-dual) + μN/(Ω r0)|, and |∂F_r/∂r| r0/(μN), in units of ε",
                worst_ad / f64::EPSILON,
                s.round_off_factor,
            ),
            Check::at_most(
                "the model's F_r(r, ṙ) against the independent one, off the steady state, / μN, in units of ε",
                worst_force / f64::EPSILON,
                s.round_off_factor,
            ),
        ],
        "F_r = −μN ṙ/sqrt(ṙ² + (Ωr)²) written from v_rel = ṙ e_r − Ω r e_t",
    ));
    let f = Figure::new("particle on the rotating disc: friction damping against Ω")
        .x_label("Ω")
        .y_label("damping")
        .log_log()
        .series(
            Series::line("μN/(Ω r0) (112)", rows.iter().map(|r| (r.omega, r.damping)))
                .color(6)
                .dashed(),
        )
        .series(
            Series::markers(
                "−m(λ₁ + λ₂) from the eigenvalues",
                rows.iter().map(|r| (r.omega, r.recovered)),
            )
            .color(1),
        )
        .horizontal_line(
            2.0 * (case.particle.mass * case.particle.stiffness).sqrt(),
            "critical damping 2 sqrt(mc)",
        );
    let g = Figure::new("eigenvalues of m Δr̈ + (μN/(Ω r0)) Δṙ + c Δr = 0 as Ω grows")
        .x_label("Re λ")
        .y_label("Im λ")
        .series(
            Series::markers(
                "λ(Ω)",
                rows.iter().flat_map(|r| {
                    r.eigenvalues
                        .iter()
                        .map(|l| (l[0], l[1]))
                        .collect::<Vec<_>>()
                }),
            )
            .color(0),
        )
        .vertical_line(0.0, "Re λ = 0");
    ctx.panels(
        report,
        "disc",
        "Particle on the rotating disc: the friction-induced damping μN/(Ω r0), recovered from the eigenvalues; the eigenvalues move from the real axis (slow disc) towards the imaginary axis (fast disc)",
        &[f, g],
        2,
    )?;
    ctx.write_data(report, &rows)
}
