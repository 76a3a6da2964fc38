//! Figures of the moving-continuum cases, built with the report's plot API: eigenvalue loci,
//! Campbell diagrams, root loci, stability maps with their regions and boundaries, time
//! histories.

use contactlab::model::moving::branches::EigenBranches;
use contactlab::model::moving::stability::Verdict;
use contactlab::model::moving::stability_map::StabilityMap;

use crate::plot::{Figure, Series};

/// The palette index of each verdict (Okabe–Ito: green, black, orange, vermillion).
pub fn verdict_color(v: Verdict) -> usize {
    match v {
        Verdict::Stable => 2,
        Verdict::Marginal => 6,
        Verdict::Divergence => 4,
        Verdict::Flutter => 1,
    }
}

/// Branches with Im λ ≥ 0 at the first parameter value, at most `max` of them, lowest first.
pub fn upper_branches(b: &EigenBranches, max: usize) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..b.branches.len())
        .filter(|&i| b.branches[i][0].im >= -1e-12)
        .collect();
    idx.sort_by(|&i, &j| {
        b.branches[i][0]
            .im
            .total_cmp(&b.branches[j][0].im)
            .then(b.branches[i][0].re.total_cmp(&b.branches[j][0].re))
    });
    idx.truncate(max);
    idx
}

/// Re λ and Im λ of the chosen branches against the parameter (the loci), and the Campbell
/// diagram (|Im λ| against the parameter), with optional exact curves.
pub fn loci_figures(
    title: &str,
    x_label: &str,
    b: &EigenBranches,
    chosen: &[usize],
    exact: &[Series],
) -> (Figure, Figure) {
    let mut re = Figure::new(format!("{title}: Re λ (growth rate)"))
        .x_label(x_label)
        .y_label("Re λ");
    let mut im = Figure::new(format!("{title}: Campbell diagram"))
        .x_label(x_label)
        .y_label("Im λ (frequency)");
    for (k, &i) in chosen.iter().enumerate() {
        let name = if k < 6 {
            format!("branch {}", k + 1)
        } else {
            String::new()
        };
        let pts_re: Vec<(f64, f64)> = b
            .parameters
            .iter()
            .zip(&b.branches[i])
            .map(|(&s, l)| (s, l.re))
            .collect();
        let pts_im: Vec<(f64, f64)> = b
            .parameters
            .iter()
            .zip(&b.branches[i])
            .map(|(&s, l)| (s, l.im))
            .collect();
        re = re.series(Series::line(name.clone(), pts_re).color(k));
        im = im.series(Series::line(name, pts_im).color(k));
    }
    for s in exact {
        im = im.series(s.clone());
    }
    (re, im)
}

/// The root locus: Im λ against Re λ of the chosen branches as the parameter varies.
pub fn root_locus(title: &str, b: &EigenBranches, chosen: &[usize]) -> Figure {
    let mut f = Figure::new(format!("{title}: root locus"))
        .x_label("Re λ")
        .y_label("Im λ");
    for (k, &i) in chosen.iter().enumerate() {
        let pts: Vec<(f64, f64)> = b.branches[i].iter().map(|l| (l.re, l.im)).collect();
        f = f.series(Series::line(String::new(), pts).color(k));
    }
    f.vertical_line(0.0, "Re λ = 0")
}

/// The stability map: one marker series per verdict on a subsampled grid (≤ `max_side` per
/// axis), plus the boundary of the unstable region (the first unstable y of every x column).
pub fn map_figure<P>(
    title: &str,
    x_label: &str,
    y_label: &str,
    map: &StabilityMap<P>,
    max_side: usize,
    log_y: bool,
) -> Figure {
    let nx = map.x.values.len();
    let ny = map.y.values.len();
    let sx = nx.div_ceil(max_side.max(1));
    let sy = ny.div_ceil(max_side.max(1));
    let mut f = Figure::new(title).x_label(x_label).y_label(y_label);
    if log_y {
        f = f.y_scale(crate::plot::Scale::Log);
    }
    for v in Verdict::ALL {
        let mut pts = Vec::new();
        for iy in (0..ny).step_by(sy) {
            for ix in (0..nx).step_by(sx) {
                if map.at(ix, iy).is_some_and(|a| a.verdict == v) {
                    pts.push((map.x.values[ix], map.y.values[iy]));
                }
            }
        }
        if !pts.is_empty() {
            f = f.series(Series::markers(v.name(), pts).color(verdict_color(v)));
        }
    }
    // The second layer: points whose unresolved eigenvalues (above ω_res) are unstable — the
    // basis's warning, not the verdict.
    let mut warn = Vec::new();
    for iy in (0..ny).step_by(sy) {
        for ix in (0..nx).step_by(sx) {
            if map.at(ix, iy).is_some_and(|a| a.unresolved.is_present()) {
                warn.push((map.x.values[ix], map.y.values[iy]));
            }
        }
    }
    if !warn.is_empty() {
        f = f.series(
            Series::markers("unstable above ω_res (discretization warning)", warn).color(8),
        );
    }
    f.series(
        Series::line("boundary (first unstable point)", boundary(map))
            .color(6)
            .dashed(),
    )
}

/// The boundary of a map: for every x, the smallest y whose verdict is unstable (skipped when
/// none is).
pub fn boundary<P>(map: &StabilityMap<P>) -> Vec<(f64, f64)> {
    let nx = map.x.values.len();
    (0..nx)
        .filter_map(|ix| {
            (0..map.y.values.len())
                .find(|&iy| map.at(ix, iy).is_some_and(|a| a.verdict.is_unstable()))
                .map(|iy| (map.x.values[ix], map.y.values[iy]))
        })
        .collect()
}

/// ln ‖y(t)‖ with the predicted slope max Re λ drawn through the last point.
pub fn history_figure(title: &str, times: &[f64], log_norms: &[f64], predicted: f64) -> Figure {
    let step = (times.len() / 600).max(1);
    let pts: Vec<(f64, f64)> = times
        .iter()
        .zip(log_norms)
        .step_by(step)
        .map(|(t, y)| (*t, *y))
        .collect();
    let (t1, y1) = (
        times.last().copied().unwrap_or(0.0),
        log_norms.last().copied().unwrap_or(0.0),
    );
    let t0 = t1 * 0.5;
    Figure::new(title)
        .x_label("τ")
        .y_label("ln ‖(q, q̇)‖")
        .series(Series::line("time integration (RK4)", pts).color(0))
        .series(
            Series::line(
                format!("slope max Re λ = {predicted:.4e}"),
                vec![(t0, y1 - predicted * (t1 - t0)), (t1, y1)],
            )
            .color(1)
            .dashed(),
        )
}
