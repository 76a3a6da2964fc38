//! `[[lines]]` of `moving_map`: more maps through the rank-one fast path, each along another
//! friction axis or contact model, every point against faer's eigensolver on the point-by-point
//! assembly.
//!
//! The map over (v̄, p) with ideal contact reads the rank-one factor R s with coefficient
//! −κ/2, κ = c_eff / c̄ = 1 (p = μh̄c̄): it cannot tell κ from 1/κ, and it never forms the
//! series-spring stiffness c_eff = c̄k̄_p/(c̄ + k̄_p) of the penalty bushing. Along μh̄ the
//! coefficient is −c_eff/2, and with a penalty bushing c_eff ≠ c̄; the lines written in a case
//! reach those factors, and a wrong one moves the spectrum away from faer's.

use serde::Deserialize;

use contactlab::model::moving::stability::Verdict;
use contactlab::model::moving::stability_map::{
    string_stability_map, GridAxis, StabilityMapParams,
};
use contactlab::model::moving::string_data::{ContactModel, MovingStringData, StringParameter};
use contactlab::model::moving::string_model::MovingStringModel;
use contactlab::solve::quadratic_eigen::{EigenKernel, QuadraticEigenParams};

use crate::core::format::{invalid, positive, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::moving::study::Bushing;

/// The friction axis of a line map.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum LineAxis {
    /// μh̄.
    Friction,
    /// p = μh̄ c̄ (ideal) or μh̄ k̄_p (penalty).
    ControlParameter,
}

impl LineAxis {
    fn parameter(self) -> StringParameter {
        match self {
            LineAxis::Friction => StringParameter::Friction,
            LineAxis::ControlParameter => StringParameter::ControlParameter,
        }
    }
}

/// One `[[lines]]` entry: a map over (v̄ ∈ [0, `speed_to`], `axis` ∈ [0, `to`]).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LineMap {
    pub axis: LineAxis,
    /// k̄_p of a penalty bushing (series springs); absent: ideal contact.
    pub penalty_stiffness: Option<f64>,
    pub to: f64,
    pub points: usize,
    pub speed_to: f64,
    pub speeds: usize,
}

impl LineMap {
    /// Checks the numbers of the entry `[[lines]]` number `i`.
    pub fn check(&self, p: &std::path::Path, i: usize) -> Result<(), CaseError> {
        positive(p, &format!("lines[{i}].to"), self.to)?;
        positive(p, &format!("lines[{i}].speed_to"), self.speed_to)?;
        if let Some(k) = self.penalty_stiffness {
            positive(p, &format!("lines[{i}].penalty_stiffness"), k)?;
        }
        if self.points < 2 || self.speeds < 2 {
            return Err(invalid(
                p,
                &format!("lines[{i}].points"),
                self.points.min(self.speeds),
                ">= 2 points and speeds",
            ));
        }
        Ok(())
    }

    fn contact(&self) -> ContactModel {
        match self.penalty_stiffness {
            Some(stiffness) => ContactModel::Penalty { stiffness },
            None => ContactModel::Ideal,
        }
    }

    fn label(&self) -> String {
        let contact = match self.penalty_stiffness {
            Some(k) => format!("penalty bushing k̄_p = {k}"),
            None => "ideal contact".into(),
        };
        format!(
            "(v̄, {}) ∈ [0, {}] × [0, {}], {}",
            self.axis.parameter().symbol(),
            self.speed_to,
            self.to,
            contact
        )
    }
}

fn params(kernel: EigenKernel) -> StabilityMapParams {
    StabilityMapParams {
        threads: 0,
        verdict: Default::default(),
        eigen: QuadraticEigenParams {
            kernel,
            ..Default::default()
        },
    }
}

/// Runs every line map: the fast path must be taken (the model offers the rank-one factors),
/// and its verdicts and max Re λ must be faer's to `round_off` n ε max|λ|; the table counts the
/// verdicts, so that a map that never crosses the boundary shows.
#[allow(clippy::too_many_arguments)]
pub fn run_lines(
    lines: &[LineMap],
    model: &MovingStringModel,
    bushing: &Bushing,
    damping: f64,
    modes: usize,
    round_off: f64,
    report: &mut CaseReport,
) -> Result<(), String> {
    let unit = (2 * (modes + 1)) as f64 * f64::EPSILON;
    let mut rows = Vec::new();
    for line in lines {
        let base: MovingStringData = bushing.data(0.0, damping, line.contact(), 0.0);
        let axis = line.axis.parameter();
        let fast = model.friction_rank_one(&base, axis).is_some();
        let x = GridAxis::linspace(StringParameter::Speed, 0.0, line.speed_to, line.speeds)
            .map_err(|e| e.to_string())?;
        let y = GridAxis::linspace(axis, 0.0, line.to, line.points).map_err(|e| e.to_string())?;
        let map = string_stability_map(model, &base, &x, &y, &params(EigenKernel::SmallDense))
            .map_err(|e| e.to_string())?;
        let reference = string_stability_map(model, &base, &x, &y, &params(EigenKernel::Faer))
            .map_err(|e| e.to_string())?;
        let (mut disagree, mut worst, mut flutter) = (0, 0.0_f64, 0);
        for (a, r) in map.points.iter().zip(&reference.points) {
            worst =
                worst.max((a.max_real_part - r.max_real_part).abs() / (unit * r.spectral_scale));
            let marginal = a.verdict == Verdict::Marginal || r.verdict == Verdict::Marginal;
            if a.verdict != r.verdict && !marginal {
                disagree += 1;
            }
            if r.verdict == Verdict::Flutter {
                flutter += 1;
            }
        }
        let n = map.points.len();
        rows.push(vec![
            line.label(),
            n.to_string(),
            flutter.to_string(),
            disagree.to_string(),
            format!("{worst:.3}"),
        ]);
        report.gates.push(GateVerdict::from_checks(
            format!("the rank-one fast path along {}: every point against faer", line.label()),
            "exact",
            vec![
                Check::holds(
                    "the model offers the rank-one factors along this axis (the fast path runs)",
                    fast,
                    "offered",
                ),
                Check::holds(
                    &format!("{disagree} of {n} verdicts differ ({flutter} flutter in faer's map)"),
                    disagree == 0 && flutter > 0 && flutter < n,
                    "0 differ, and the map crosses the flutter boundary",
                ),
                Check::at_most(
                    "max |Δ max Re λ| in units of n ε max|λ|",
                    worst,
                    round_off,
                ),
            ],
            "the rank-one line kernel against faer's dense eigensolver on the companion matrix assembled point by point",
        ));
    }
    if !rows.is_empty() {
        report.tables.push(Table {
            title:
                "the rank-one fast path along other friction axes and contact models, against faer"
                    .into(),
            header: vec![
                "map".into(),
                "points".into(),
                "flutter (faer)".into(),
                "verdicts differ".into(),
                "max |Δ max Re λ| / (n ε max|λ|)".into(),
            ],
            rows,
        });
    }
    Ok(())
}
