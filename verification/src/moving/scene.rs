//! `verify scene` for moving-continuum scenes (`model = "moving_string"` or `"disc_particle"`,
//! format in `contactlab::scene::moving`; `"rotating_plate"` in `plate_scene.rs`): runs the
//! analysed point, every sweep and the map, and writes into the output directory
//!
//! - `eigenvalues.json`: the point's data, eigenvalues [Re, Im] (and eigenvectors when asked),
//!   the verdict with its tolerance, the solver's statistics;
//! - `sweep_<i>.json`: for each sweep, the parameter values, every spectrum, the verdicts and
//!   growth rates, and the tracked branches;
//! - `map.json`: the grid, and per point the verdict, max Re λ and the critical eigenvalue, and
//!   the count of unstable eigenvalues above the resolution limit (the discretization warning);
//! - SVG plots: the spectrum, the loci and Campbell diagram of each sweep, the map.

use std::path::Path;

use serde::Serialize;

use contactlab::model::moving::stability::StabilityAssessment;
use contactlab::scene::moving::{MovingScene, StringSceneResult};

use crate::moving::plots::{loci_figures, map_figure, root_locus, upper_branches};
use crate::moving::scene_json::{
    map_json, map_summary, supercritical_warning, sweep_json, unresolved_warning,
};
use crate::plot::{write_panels_svg, write_svg, Figure, Series};

#[derive(Serialize)]
struct PointJson<'a> {
    title: &'a str,
    coordinates: &'a [String],
    control_parameter: f64,
    eigenvalues: &'a [[f64; 2]],
    #[serde(skip_serializing_if = "Option::is_none")]
    eigenvectors: Option<&'a Vec<Vec<[f64; 2]>>>,
    assessment: &'a StabilityAssessment,
    stats: &'a contactlab::solve::quadratic_eigen::QuadraticEigenStats,
}

/// Runs a moving scene and writes its files; returns a one-line summary.
pub fn write_scene(scene: &MovingScene, source: &str, out: &Path) -> Result<String, String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let write = |name: &str, json: String| {
        std::fs::write(out.join(name), json)
            .map_err(|e| format!("{}: {e}", out.join(name).display()))
    };
    let svg = |name: &str, f: &Figure| write_svg(f, &out.join(name)).map_err(|e| e.to_string());
    match scene {
        MovingScene::String(s) => {
            let r = s.run().map_err(|e| format!("{source}: {e}"))?;
            let title = if s.title.is_empty() {
                source.to_string()
            } else {
                s.title.clone()
            };
            write(
                "eigenvalues.json",
                crate::core::json_out::finite_json(
                    &PointJson {
                        title: &title,
                        coordinates: &r.coordinates,
                        control_parameter: r.control_parameter,
                        eigenvalues: &r.eigenvalues,
                        eigenvectors: r.eigenvectors.as_ref(),
                        assessment: &r.assessment,
                        stats: &r.stats,
                    },
                    true,
                )
                .map_err(|e| format!("{source}: eigenvalues.json: {e}"))?,
            )?;
            svg("spectrum.svg", &spectrum_figure(&title, &r))?;
            for (i, sw) in r.sweeps.iter().enumerate() {
                write(
                    &format!("sweep_{i}.json"),
                    crate::core::json_out::finite_json(&sweep_json(sw), true)
                        .map_err(|e| format!("{source}: sweep_{i}.json: {e}"))?,
                )?;
                let chosen = upper_branches(&sw.branches, 8);
                let sym = sw.axis.parameter.symbol();
                let (re, im) = loci_figures(&title, sym, &sw.branches, &chosen, &[]);
                let rl = root_locus(&format!("{title}, {sym} sweep"), &sw.branches, &chosen);
                write_panels_svg(&[im, re, rl], 3, &out.join(format!("sweep_{i}.svg")))
                    .map_err(|e| e.to_string())?;
            }
            if let Some(map) = &r.map {
                write(
                    "map.json",
                    crate::core::json_out::finite_json(&map_json(map), false)
                        .map_err(|e| format!("{source}: map.json: {e}"))?,
                )?;
                svg(
                    "map.svg",
                    &map_figure(
                        &format!("{title}: stability map"),
                        map.x.parameter.symbol(),
                        map.y.parameter.symbol(),
                        map,
                        60,
                        false,
                    ),
                )?;
            }
            Ok(format!(
                "{source}: {} at the scene's point (max Re λ = {:.6e}, tolerance {:.1e}), {} eigenvalues{}{}{}{}",
                r.assessment.verdict.name(),
                r.assessment.max_real_part,
                r.assessment.tolerance,
                r.eigenvalues.len(),
                unresolved_warning(&r.assessment),
                supercritical_warning(&r.assessment),
                if r.sweeps.is_empty() { String::new() } else { format!(", {} sweep(s)", r.sweeps.len()) },
                r.map.as_ref().map_or(String::new(), map_summary)
            ))
        }
        MovingScene::Plate(p) => crate::moving::plate_scene::write_plate(p, source, out),
        MovingScene::Disc(d) => {
            let r = d.run().map_err(|e| format!("{source}: {e}"))?;
            write(
                "eigenvalues.json",
                crate::core::json_out::finite_json(&r, true)
                    .map_err(|e| format!("{source}: eigenvalues.json: {e}"))?,
            )?;
            for (i, sw) in r.sweeps.iter().enumerate() {
                let f = Figure::new(format!(
                    "{}: friction damping against {}",
                    d.title,
                    sw.parameter.key()
                ))
                .x_label(sw.parameter.key())
                .y_label("damping")
                .log_log()
                .series(
                    Series::line(
                        "μN/(|Ω| r0)",
                        sw.values
                            .iter()
                            .zip(&sw.points)
                            .map(|(v, p)| (*v, p.friction_damping)),
                    )
                    .color(6)
                    .dashed(),
                )
                .series(
                    Series::markers(
                        "−m(λ₁ + λ₂)",
                        sw.values
                            .iter()
                            .zip(&sw.points)
                            .map(|(v, p)| (*v, p.recovered_damping)),
                    )
                    .color(1),
                );
                svg(&format!("sweep_{i}.svg"), &f)?;
            }
            Ok(format!(
                "{source}: {} (damping μN/(Ω r0) = {:.6e}, recovered {:.6e}), {} sweep(s)",
                r.point.assessment.verdict.name(),
                r.point.friction_damping,
                r.point.recovered_damping,
                r.sweeps.len()
            ))
        }
    }
}

fn spectrum_figure(title: &str, r: &StringSceneResult) -> Figure {
    Figure::new(format!(
        "{title}: eigenvalues ({})",
        r.assessment.verdict.name()
    ))
    .x_label("Re λ")
    .y_label("Im λ")
    .series(Series::markers("λ", r.eigenvalues.iter().map(|l| (l[0], l[1]))).color(0))
    .vertical_line(0.0, "Re λ = 0")
}
