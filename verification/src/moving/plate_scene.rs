//! `verify scene` for the rotating plate (`model = "rotating_plate"`, format in
//! `contactlab::scene::moving`): runs the analysed point, every sweep and the map, and writes
//!
//! - `solution.json`: the plate, the pad, the discretization, the point's eigenvalues (and
//!   eigenvectors when asked) with the verdict and the solver's statistics, and per harmonic n the
//!   non-rotating frequencies ω_{n,m} with the spatial-frame waves they predict at the scene's Ω
//!   (ω_{n,m} + n|Ω|, |ω_{n,m} − n|Ω||) and the critical speeds ω_{n,m}/n;
//! - `sweep_<i>.json` and `map.json`: as the string's (`scene.rs`);
//! - `spectrum.svg` (Re λ against Im λ at the point); `sweep_<i>.svg`: the Campbell diagram
//!   (|Im λ| of the tracked branches against the parameter, with the predicted lines of the
//!   non-rotating frequencies dashed when the parameter is Ω), max Re λ and Re λ of the branches
//!   against the parameter; `map.svg`: the verdicts on the grid.

use std::path::Path;

use serde::Serialize;

use contactlab::model::moving::plate::{PadData, PlateParameter, PlateProperties};
use contactlab::model::moving::stability::StabilityAssessment;
use contactlab::model::moving::sweep::Sweep;
use contactlab::scene::moving::{HarmonicWaves, PlateSceneResult, RotatingPlateScene};

use crate::moving::plots::{loci_figures, map_figure};
use crate::moving::scene_json::{map_json, map_summary, sweep_json, unresolved_warning};
use crate::plot::{write_panels_svg, write_svg, Figure, Series};

/// The discretization as `solution.json` writes it.
#[derive(Serialize)]
struct DiscretizationJson {
    harmonics: usize,
    elements: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    radial_modes: Option<usize>,
    coordinates: usize,
}

/// `solution.json`.
#[derive(Serialize)]
struct SolutionJson<'a> {
    title: &'a str,
    plate: &'a PlateProperties,
    angular_speed: f64,
    damping: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pad: Option<&'a PadData>,
    discretization: DiscretizationJson,
    coordinates: &'a [String],
    eigenvalues: &'a [[f64; 2]],
    #[serde(skip_serializing_if = "Option::is_none")]
    eigenvectors: Option<&'a Vec<Vec<[f64; 2]>>>,
    assessment: &'a StabilityAssessment,
    stats: &'a contactlab::solve::quadratic_eigen::QuadraticEigenStats,
    harmonics: &'a [HarmonicWaves],
}

/// Runs a plate scene and writes its files; returns a one-line summary.
pub fn write_plate(s: &RotatingPlateScene, source: &str, out: &Path) -> Result<String, String> {
    let r = s.run().map_err(|e| format!("{source}: {e}"))?;
    let title = if s.title.is_empty() {
        source.to_string()
    } else {
        s.title.clone()
    };
    let write = |name: &str, json: Result<String, String>| {
        let json = json.map_err(|e| format!("{source}: {name}: {e}"))?;
        std::fs::write(out.join(name), json)
            .map_err(|e| format!("{}: {e}", out.join(name).display()))
    };
    let d = s.model.discretization();
    let solution = SolutionJson {
        title: &title,
        plate: s.model.properties(),
        angular_speed: r.angular_speed,
        damping: r.damping,
        pad: r.pad.as_ref(),
        discretization: DiscretizationJson {
            harmonics: (d.angular.len() - 1) / 2,
            elements: d.elements,
            radial_modes: d.radial_modes,
            coordinates: r.coordinates.len(),
        },
        coordinates: &r.coordinates,
        eigenvalues: &r.eigenvalues,
        eigenvectors: r.eigenvectors.as_ref(),
        assessment: &r.assessment,
        stats: &r.stats,
        harmonics: &r.harmonics,
    };
    write(
        "solution.json",
        crate::core::json_out::finite_json(&solution, true),
    )?;
    write_svg(&spectrum_figure(&title, &r), &out.join("spectrum.svg"))
        .map_err(|e| e.to_string())?;
    for (i, sw) in r.sweeps.iter().enumerate() {
        write(
            &format!("sweep_{i}.json"),
            crate::core::json_out::finite_json(&sweep_json(sw), true),
        )?;
        write_panels_svg(
            &sweep_figures(&title, sw, &r.harmonics),
            3,
            &out.join(format!("sweep_{i}.svg")),
        )
        .map_err(|e| e.to_string())?;
    }
    if let Some(map) = &r.map {
        write(
            "map.json",
            crate::core::json_out::finite_json(&map_json(map), false),
        )?;
        let f = map_figure(
            &format!("{title}: stability map"),
            map.x.parameter.symbol(),
            map.y.parameter.symbol(),
            map,
            60,
            false,
        );
        write_svg(&f, &out.join("map.svg")).map_err(|e| e.to_string())?;
    }
    let critical = r
        .harmonics
        .iter()
        .filter_map(|h| h.critical_speeds.first().map(|&c| (h.n, c)))
        .min_by(|a, b| a.1.total_cmp(&b.1));
    Ok(format!(
        "{source}: {} at Ω = {} (max Re λ = {:.6e}, tolerance {:.1e}), {} eigenvalues{}; lowest \
         critical speed {}{}{}",
        r.assessment.verdict.name(),
        r.angular_speed,
        r.assessment.max_real_part,
        r.assessment.tolerance,
        r.eigenvalues.len(),
        unresolved_warning(&r.assessment),
        critical.map_or("(none: N = 0)".to_string(), |(n, c)| format!(
            "ω_{{{n},0}}/{n} = {c:.6}"
        )),
        if r.sweeps.is_empty() {
            String::new()
        } else {
            format!(", {} sweep(s)", r.sweeps.len())
        },
        r.map.as_ref().map_or(String::new(), map_summary)
    ))
}

fn spectrum_figure(title: &str, r: &PlateSceneResult) -> Figure {
    Figure::new(format!(
        "{title}: eigenvalues at Ω = {} ({})",
        r.angular_speed,
        r.assessment.verdict.name()
    ))
    .x_label("Re λ")
    .y_label("Im λ")
    .series(Series::markers("λ", r.eigenvalues.iter().map(|l| (l[0], l[1]))).color(0))
    .vertical_line(0.0, "Re λ = 0")
}

/// The top of the Campbell diagram: the highest fundamental line (m = 0) at the sweep's largest
/// |Ω| (when the sweep is over Ω), with a margin; it shows every critical speed.
fn campbell_top(harmonics: &[HarmonicWaves], max_omega: f64) -> f64 {
    1.15 * harmonics
        .iter()
        .filter_map(|h| h.frequencies.first().map(|w| w + h.n as f64 * max_omega))
        .fold(0.0, f64::max)
}

/// The predicted spatial-frame lines of harmonic n over the Ω values `omegas`: ω + n|Ω| and
/// |ω − n|Ω|| (with its zero at the critical speed when that lies inside).
fn predicted_lines(h: &HarmonicWaves, omegas: &[f64]) -> Vec<Vec<(f64, f64)>> {
    let nf = h.n as f64;
    let (lo, hi) = omegas
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let mut lines = Vec::new();
    for &w in &h.frequencies {
        let forward: Vec<(f64, f64)> = omegas.iter().map(|&o| (o, w + nf * o.abs())).collect();
        let mut backward: Vec<(f64, f64)> = omegas
            .iter()
            .map(|&o| (o, (w - nf * o.abs()).abs()))
            .collect();
        if h.n > 0 {
            for c in [w / nf, -w / nf] {
                if c > lo && c < hi {
                    backward.push((c, 0.0));
                }
            }
            backward.sort_by(|a, b| a.0.total_cmp(&b.0));
            lines.push(forward);
        }
        lines.push(backward);
    }
    lines
}

/// The Campbell diagram, max Re λ and Re λ of the branches against the swept parameter.
fn sweep_figures(
    title: &str,
    sw: &Sweep<PlateParameter>,
    harmonics: &[HarmonicWaves],
) -> [Figure; 3] {
    let b = &sw.branches;
    let sym = sw.axis.parameter.symbol();
    let omega_sweep = sw.axis.parameter == PlateParameter::AngularSpeed;
    let max_omega = if omega_sweep {
        sw.axis.values.iter().fold(0.0, |a: f64, x| a.max(x.abs()))
    } else {
        0.0
    };
    let top = campbell_top(harmonics, max_omega);
    // one branch of each conjugate pair (Im λ ≥ 0 at the start) that comes below the top
    let chosen: Vec<usize> = (0..b.branches.len())
        .filter(|&i| {
            b.branches[i][0].im >= -1e-12 * (1.0 + top)
                && b.branches[i].iter().any(|l| l.im.abs() <= top)
        })
        .collect();
    let mut campbell = Figure::new(format!("{title}: Campbell diagram"))
        .x_label(sym)
        .y_label("|Im λ| (spatial-frame frequency)");
    for (k, &i) in chosen.iter().enumerate() {
        let name = if k == 0 { "computed |Im λ|" } else { "" };
        let pts: Vec<(f64, f64)> = b
            .parameters
            .iter()
            .zip(&b.branches[i])
            .map(|(&p, l)| (p, l.im.abs()))
            .collect();
        campbell = campbell.series(Series::line(name, pts).color(0));
    }
    if omega_sweep {
        for h in harmonics {
            for (k, line) in predicted_lines(h, &sw.axis.values).into_iter().enumerate() {
                let name = if k == 0 {
                    format!("ω_{{n,m}} ± nΩ, n = {}", h.n)
                } else {
                    String::new()
                };
                campbell = campbell.series(Series::line(name, line).color(1 + h.n).dashed());
            }
        }
    }
    if top > 0.0 && top.is_finite() {
        campbell = campbell.y_range(0.0, top);
    }
    let max_re = Figure::new(format!("{title}: max Re λ"))
        .x_label(sym)
        .y_label("max Re λ")
        .series(
            Series::line(
                "max Re λ",
                sw.axis
                    .values
                    .iter()
                    .zip(&sw.assessments)
                    .map(|(&p, a)| (p, a.max_real_part)),
            )
            .color(1),
        )
        .horizontal_line(0.0, "Re λ = 0");
    let (re, _) = loci_figures(title, sym, b, &chosen, &[]);
    [campbell, max_re, re]
}
