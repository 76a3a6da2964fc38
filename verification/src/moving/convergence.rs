//! The convergence of a string's frequencies in the three bases, shared by `moving_string` and
//! `moving_oscillator`: the `[convergence]` format, one level per (basis, size) at each speed,
//! the rate gates of the `[[gate]]` series `basis/speed`, and the convergence figures.

use std::path::Path;

use serde::{Deserialize, Serialize};

use contactlab::model::moving::finite_element_basis::ElementKind;
use contactlab::model::moving::string_data::MovingStringData;
use contactlab::model::moving::string_model::StringDiscretization;

use crate::core::format::{at_least, CaseError};
use crate::core::gate::RateGate;
use crate::core::report::case_report::CaseReport;
use crate::moving::errors::{frequencies, relative_real_part};
use crate::moving::study::{string_eigenvalues, SeriesSelect};
use crate::plot::{Figure, Series};

/// The bases of a convergence study, in the order of their levels, with the label of their
/// discretization parameter (1/N for the sine basis, the element size h otherwise).
pub const BASES: [(&str, &str); 3] = [("sine", "1/N"), ("p1", "h"), ("hermite", "h")];

/// `[convergence]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Convergence {
    pub speeds: Vec<f64>,
    /// The error is the largest relative error of the first `modes_checked` frequencies.
    pub modes_checked: usize,
    pub sine_modes: Vec<usize>,
    pub p1_elements: Vec<usize>,
    pub hermite_elements: Vec<usize>,
}

impl Convergence {
    /// Checks that there is a speed and at least two sizes of every basis.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        at_least(p, "convergence.speeds", &self.speeds, 1)?;
        for (f, v) in [
            ("convergence.sine_modes", &self.sine_modes),
            ("convergence.p1_elements", &self.p1_elements),
            ("convergence.hermite_elements", &self.hermite_elements),
        ] {
            at_least(p, f, v, 2)?;
        }
        Ok(())
    }

    /// The discretizations of the study: (basis, size, h, discretization) for N sine modes
    /// (h = 1/N), then P1 and Hermite elements of size h = 1/M.
    pub fn plans(&self) -> Vec<(&'static str, usize, f64, StringDiscretization)> {
        let elements = |kind: ElementKind, m: usize| StringDiscretization::FiniteElements {
            kind,
            elements: m,
        };
        self.sine_modes
            .iter()
            .map(|&n| {
                (
                    "sine",
                    n,
                    1.0 / n as f64,
                    StringDiscretization::Sine { modes: n },
                )
            })
            .chain(
                self.p1_elements
                    .iter()
                    .map(|&m| ("p1", m, 1.0 / m as f64, elements(ElementKind::P1, m))),
            )
            .chain(self.hermite_elements.iter().map(|&m| {
                (
                    "hermite",
                    m,
                    1.0 / m as f64,
                    elements(ElementKind::Hermite, m),
                )
            }))
            .collect()
    }

    /// The levels at speed v̄ = `speed` of the string with data `d`: every discretization of
    /// [`Convergence::plans`] against the exact frequencies `exact` of the first modes (their
    /// number is `modes_checked`), with max |Re λ| / (n ε max |λ|) (n eigenvalues) when
    /// `real_parts` is set.
    pub fn levels(
        &self,
        speed: f64,
        d: &MovingStringData,
        exact: &[f64],
        real_parts: bool,
    ) -> Result<Vec<Level>, String> {
        let mut levels = Vec::new();
        for (basis, size, h, disc) in self.plans() {
            let ev = string_eigenvalues(disc, d)?;
            let f = frequencies(&ev);
            if f.len() < exact.len() {
                return Err(format!(
                    "{basis} with {size}: fewer than {} frequencies",
                    exact.len()
                ));
            }
            let mode_errors: Vec<f64> = exact
                .iter()
                .enumerate()
                .map(|(k, e)| (f[k] - e).abs() / e)
                .collect();
            levels.push(Level {
                basis: basis.into(),
                speed,
                size,
                h,
                error: mode_errors.iter().copied().fold(0.0, f64::max),
                mode_errors,
                real_part_round_off: real_parts
                    .then(|| relative_real_part(&ev) / (ev.len() as f64 * f64::EPSILON)),
            });
        }
        Ok(levels)
    }

    /// The convergence figures, one per basis of [`BASES`] with the reference slope of
    /// `slopes` (in the same order): the largest relative error of the checked frequencies
    /// against 1/N or h, one series per speed. `what` names the error in the titles.
    pub fn figures(&self, levels: &[Level], what: &str, slopes: [f64; 3]) -> Vec<Figure> {
        BASES
            .iter()
            .zip(slopes)
            .map(|(&(basis, label), slope)| {
                let mut f =
                    Figure::new(format!("{basis}: {what} (modes 1–{})", self.modes_checked))
                        .x_label(label)
                        .y_label("max relative error")
                        .log_log();
                for (k, &v) in self.speeds.iter().enumerate() {
                    let pts: Vec<(f64, f64)> = levels
                        .iter()
                        .filter(|l| l.basis == basis && l.speed == v)
                        .map(|l| (l.h, l.error))
                        .collect();
                    f = f.series(Series::line_markers(format!("v̄ = {v}"), pts).color(k));
                }
                f.reference_slope(slope, format!("slope {slope}"))
            })
            .collect()
    }
}

/// One discretization level.
#[derive(Debug, Clone, Serialize)]
pub struct Level {
    pub basis: String,
    pub speed: f64,
    pub size: usize,
    pub h: f64,
    /// Relative error of each checked mode.
    pub mode_errors: Vec<f64>,
    /// The largest of `mode_errors`.
    pub error: f64,
    /// max |Re λ| / (n ε max |λ|) (n eigenvalues), where measured.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub real_part_round_off: Option<f64>,
}

/// Evaluates each rate gate on its series `basis/speed` of `levels` (error against 1/N or h)
/// into `report`; `what` names the error in the gate's title. An error when a series matches
/// no level.
pub fn rate_gates(
    gates: &[RateGate<SeriesSelect>],
    levels: &[Level],
    what: &str,
    report: &mut CaseReport,
) -> Result<(), String> {
    for g in gates {
        let (basis, v) = g.select.series.split_once('/').unwrap_or(("", ""));
        let v: f64 = v.parse().unwrap_or(f64::NAN);
        let sel: Vec<&Level> = levels
            .iter()
            .filter(|l| l.basis == basis && l.speed == v)
            .collect();
        if sel.is_empty() {
            return Err(format!("gate series {} matches no run", g.select.series));
        }
        let h: Vec<f64> = sel.iter().map(|l| l.h).collect();
        let e: Vec<f64> = sel.iter().map(|l| l.error).collect();
        report.gates.push(g.criteria.evaluate(
            format!(
                "{basis}, v̄ = {v}: {what} vs {}",
                if basis == "sine" { "1/N" } else { "h" }
            ),
            &h,
            &e,
        ));
    }
    Ok(())
}
