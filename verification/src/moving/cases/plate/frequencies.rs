//! The non-rotating plate in `moving_plate`: the natural frequencies ω_{n,m} (n = 0 … N nodal
//! diameters, m = 0, 1, … nodal circles) of the radial Hermite discretization against the roots
//! of the exact characteristic equation (`exact::plate_annulus`: Bessel J, Y, I, K), with the
//! observed rates in the element size h: the annulus clamped at r = a with each outer edge, and
//! the full disc with the paper's centre conditions w(0) = 0, w_r(0) = 0.

use std::path::Path;

use serde::{Deserialize, Serialize};

use contactlab::model::moving::plate::modes::harmonic_frequencies;
use contactlab::model::moving::plate::{OuterEdge, PlateProperties};

use crate::core::format::{at_least, invalid, CaseError};
use crate::core::gate::RateGate;
use crate::core::report::case_report::CaseReport;
use crate::exact::plate_annulus::{self, AnnularPlate};
use crate::moving::study::SeriesSelect;
use crate::plot::{Figure, Series};

/// `[frequencies]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FrequenciesSection {
    pub outer_edges: Vec<OuterEdge>,
    /// n = 0 … harmonics.
    pub harmonics: usize,
    /// m = 0 … nodal_circles − 1.
    pub nodal_circles: usize,
    pub elements: Vec<usize>,
    /// The full disc (a = 0) with the paper's centre conditions: its outer edge.
    pub centre_outer_edge: OuterEdge,
    pub centre_elements: Vec<usize>,
}

impl FrequenciesSection {
    /// Checks the numbers.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        at_least(p, "frequencies.outer_edges", &self.outer_edges, 1)?;
        at_least(p, "frequencies.elements", &self.elements, 3)?;
        at_least(p, "frequencies.centre_elements", &self.centre_elements, 3)?;
        if self.nodal_circles == 0 {
            return Err(invalid(p, "frequencies.nodal_circles", 0, "at least 1"));
        }
        if self.harmonics < 2 {
            return Err(invalid(
                p,
                "frequencies.harmonics",
                self.harmonics,
                "at least 2",
            ));
        }
        Ok(())
    }
}

/// One level of one series.
#[derive(Debug, Clone, Serialize)]
pub struct FrequencyLevel {
    pub series: String,
    pub elements: usize,
    pub h: f64,
    /// (n, m, ω_h, ω_exact, relative error).
    pub modes: Vec<(usize, usize, f64, f64, f64)>,
    pub error: f64,
    /// The bound of the round-off of the relative frequency error: the program solves the
    /// inverse problem through the strain factor of K_n (`model::moving::plate::modes`), which
    /// perturbs λ = ω² by about ε √(λ_max λ), i.e. ω by ε √(λ_max/λ)/2 relatively (the largest
    /// over the checked modes). Reported: a bound, not the floor.
    pub floor: f64,
}

fn exact_edge(e: OuterEdge) -> plate_annulus::OuterEdge {
    match e {
        OuterEdge::Free => plate_annulus::OuterEdge::Free,
        OuterEdge::Clamped => plate_annulus::OuterEdge::Clamped,
        OuterEdge::SimplySupported => plate_annulus::OuterEdge::SimplySupported,
    }
}

/// The levels of `series` for harmonics `ns` of `plate` against `exact`.
fn levels(
    series: &str,
    plate: &PlateProperties,
    exact: &AnnularPlate,
    ns: &[usize],
    circles: usize,
    elements: &[usize],
) -> Result<Vec<FrequencyLevel>, String> {
    let mut reference = Vec::new();
    for &n in ns {
        let skip = exact.zero_frequency_modes(n);
        let w = exact
            .natural_frequencies(n, circles, plate.bending_stiffness, plate.mass_per_area)
            .map_err(|e| format!("{series}, n = {n}: {e}"))?;
        reference.push((n, skip, w));
    }
    let mut out = Vec::new();
    for &ne in elements {
        let mut modes = Vec::new();
        let mut floor: f64 = 0.0;
        for (n, skip, w) in &reference {
            let fe = harmonic_frequencies(plate, ne, *n, 2 * ne + 2).map_err(|e| e.to_string())?;
            let top = fe.last().copied().unwrap_or(0.0);
            for (m, we) in w.iter().enumerate() {
                floor = floor.max(f64::EPSILON * top / (2.0 * we));
                let wh = fe[m + skip];
                modes.push((*n, m, wh, *we, (wh - we).abs() / we));
            }
        }
        let error = modes.iter().map(|m| m.4).fold(0.0, f64::max);
        out.push(FrequencyLevel {
            series: series.to_string(),
            elements: ne,
            h: (plate.outer_radius - plate.inner_radius) / ne as f64,
            modes,
            error,
            floor,
        });
    }
    Ok(out)
}

/// Runs the frequency study: every series, its rate gate (by `series` name), the figure.
pub fn run(
    plate: PlateProperties,
    f: &FrequenciesSection,
    gates: &[RateGate<SeriesSelect>],
    report: &mut CaseReport,
) -> Result<(Vec<FrequencyLevel>, Figure), String> {
    let all_n: Vec<usize> = (0..=f.harmonics).collect();
    let mut all = Vec::new();
    for &edge in &f.outer_edges {
        let p = PlateProperties {
            outer_edge: edge,
            ..plate
        };
        let exact =
            AnnularPlate::annulus(p.inner_radius, p.outer_radius, p.poisson, exact_edge(edge));
        all.extend(levels(
            edge.key(),
            &p,
            &exact,
            &all_n,
            f.nodal_circles,
            &f.elements,
        )?);
    }
    let centre = PlateProperties {
        inner_radius: 0.0,
        outer_edge: f.centre_outer_edge,
        ..plate
    };
    let exact = AnnularPlate::point_clamped_disc(
        centre.outer_radius,
        centre.poisson,
        exact_edge(f.centre_outer_edge),
    );
    let higher: Vec<usize> = (2..=f.harmonics).collect();
    all.extend(levels(
        "centre n ≥ 2",
        &centre,
        &exact,
        &higher,
        f.nodal_circles,
        &f.centre_elements,
    )?);
    all.extend(levels(
        "centre n = 0",
        &centre,
        &exact,
        &[0],
        f.nodal_circles,
        &f.centre_elements,
    )?);
    all.extend(levels(
        "centre n = 1",
        &centre,
        &exact,
        &[1],
        f.nodal_circles,
        &f.centre_elements,
    )?);
    for g in gates {
        let sel: Vec<&FrequencyLevel> =
            all.iter().filter(|l| l.series == g.select.series).collect();
        if sel.is_empty() {
            return Err(format!("gate series {} matches no study", g.select.series));
        }
        let h: Vec<f64> = sel.iter().map(|l| l.h).collect();
        let e: Vec<f64> = sel.iter().map(|l| l.error).collect();
        report.gates.push(g.criteria.evaluate(
            format!(
                "{}: max relative error of ω_{{n,m}} (n = 0…{}, m < {}) against the Bessel roots vs h",
                g.select.series, f.harmonics, f.nodal_circles
            ),
            &h,
            &e,
        ));
    }
    // n = 1 of the full disc: the point slope constraint w_r(0) = 0 has no reaction of bounded
    // energy, so the discrete frequencies converge to the disc constrained by w(0) = 0 alone
    // only logarithmically: errors that fall at every refinement, slower than any power ≥ 0.3
    let one: Vec<&FrequencyLevel> = all.iter().filter(|l| l.series == "centre n = 1").collect();
    let rates: Vec<f64> = one
        .windows(2)
        .map(|w| (w[0].error / w[1].error).ln() / (w[0].h / w[1].h).ln())
        .collect();
    let tilt: Vec<f64> = f
        .centre_elements
        .iter()
        .map(|&ne| harmonic_frequencies(&centre, ne, 1, 1).map(|w| w[0]))
        .collect::<Result<_, _>>()
        .map_err(|e| e.to_string())?;
    report.gates.push(crate::core::gate::GateVerdict::from_checks(
        format!(
            "full disc, n = 1: logarithmic convergence to the disc held by w(0) = 0 alone (errors {:.3e} → {:.3e}; the constrained tilt ω = {:.4} → {:.4})",
            one.first().map_or(0.0, |l| l.error),
            one.last().map_or(0.0, |l| l.error),
            tilt.first().copied().unwrap_or(0.0),
            tilt.last().copied().unwrap_or(0.0)
        ),
        "asymptotic",
        vec![
            crate::core::gate::Check::holds(
                "the error falls at every refinement and the tilt frequency too",
                rates.iter().all(|r| *r > 0.0) && tilt.windows(2).all(|w| w[1] < w[0]),
                "monotone",
            ),
            crate::core::gate::Check::holds(
                &format!("pairwise rates fall towards 0 ({:.3} → {:.3})", rates.first().copied().unwrap_or(0.0), rates.last().copied().unwrap_or(0.0)),
                rates.windows(2).all(|w| w[1] < w[0]),
                "sub-algebraic: an algebraic rate would stay constant",
            ),
            crate::core::gate::Check::at_most(
                "largest pairwise rate",
                rates.iter().copied().fold(0.0, f64::max),
                0.3,
            ),
        ],
        "a point constraint on the slope is not bounded in H² (Kirchhoff): the n = 1 solution r ln r has infinite energy",
    ));
    let mut fig =
        Figure::new("non-rotating plate: frequencies against the exact characteristic equation")
            .x_label("h")
            .y_label("max relative error")
            .log_log();
    let mut names: Vec<&str> = all.iter().map(|l| l.series.as_str()).collect();
    names.dedup();
    for (k, name) in names.iter().enumerate() {
        fig = fig.series(
            Series::line_markers(
                *name,
                all.iter()
                    .filter(|l| l.series == *name)
                    .map(|l| (l.h, l.error)),
            )
            .color(k),
        );
    }
    let fig = fig.reference_slope(4.0, "slope 4");
    Ok((all, fig))
}
