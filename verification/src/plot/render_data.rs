//! A figure's data in axis space: its series mapped through the axis scales (points that
//! cannot be drawn dropped), their colours, and the reference slopes anchored on them.

use super::axis::to_axis;
use super::colormap::PALETTE;
use super::figure::{Figure, Scale, Series};

/// log10(2): the reference slopes sit a factor 2 below their anchor point.
pub(super) const LOG10_2: f64 = std::f64::consts::LOG10_2;

/// A series mapped to axis space.
pub(super) struct Prepared<'a> {
    pub(super) series: &'a Series,
    pub(super) color: usize,
    /// Points in axis space; `None` for points that cannot be drawn on these scales.
    pub(super) points: Vec<Option<(f64, f64)>>,
    pub(super) drawable: usize,
}

/// Maps every series of the figure to axis space and gives it its colour.
pub(super) fn prepare(figure: &Figure) -> Vec<Prepared<'_>> {
    let colors = assign_colors(&figure.series);
    figure
        .series
        .iter()
        .zip(colors)
        .map(|(s, color)| {
            let points: Vec<Option<(f64, f64)>> = s
                .points
                .iter()
                .map(|&(x, y)| Some((to_axis(figure.x_scale, x)?, to_axis(figure.y_scale, y)?)))
                .collect();
            let drawable = points.iter().flatten().count();
            Prepared {
                series: s,
                color,
                points,
                drawable,
            }
        })
        .collect()
}

/// Colour of each series: explicit indices as given, automatic ones in palette order,
/// skipping colours chosen explicitly elsewhere while any remain.
pub(super) fn assign_colors(series: &[Series]) -> Vec<usize> {
    let n = PALETTE.len();
    let explicit: Vec<usize> = series
        .iter()
        .filter_map(|s| s.style.color.map(|c| c % n))
        .collect();
    let mut next = 0usize;
    series
        .iter()
        .map(|s| match s.style.color {
            Some(c) => c % n,
            None => {
                let free = (0..n)
                    .map(|k| (next + k) % n)
                    .find(|c| !explicit.contains(c));
                let c = free.unwrap_or(next % n);
                next = c + 1;
                c
            }
        })
        .collect()
}

/// A reference slope line in axis space.
pub(super) struct RefLine<'a> {
    pub(super) label: &'a str,
    pub(super) from: (f64, f64),
    pub(super) to: (f64, f64),
}

/// What a series offers as an anchor for reference slopes (log–log axis space).
pub(super) struct Anchor {
    /// The smallest-x drawable point (the first of them on ties).
    pub(super) finest: (f64, f64),
    /// Largest drawable x.
    pub(super) x_max: f64,
    /// Least-squares slope of the drawable points, if they have distinct x.
    pub(super) slope: Option<f64>,
}

pub(super) fn anchor_of(points: &[Option<(f64, f64)>]) -> Option<Anchor> {
    let pts: Vec<(f64, f64)> = points.iter().flatten().copied().collect();
    let &finest = pts.iter().reduce(|a, b| if b.0 < a.0 { b } else { a })?;
    let x_max = pts.iter().map(|p| p.0).fold(finest.0, f64::max);
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let slope = (sxx > 1e-18).then(|| sxy / sxx).filter(|s| s.is_finite());
    Some(Anchor {
        finest,
        x_max,
        slope,
    })
}

/// Reference lines, each a factor 2 below the finest (smallest-x) point of an anchor series and
/// spanning that series' x range (one decade if it has a single x). The anchor is, among the
/// series whose fitted log–log slope is within 0.3 of the fitted slope nearest the reference
/// slope, the one giving the lowest line (so the line runs under all of them); failing any
/// fitted slope, the first series with a drawable point.
pub(super) fn reference_lines<'a>(figure: &'a Figure, prepared: &[Prepared]) -> Vec<RefLine<'a>> {
    if figure.x_scale != Scale::Log || figure.y_scale != Scale::Log {
        return Vec::new();
    }
    let anchors: Vec<Anchor> = prepared
        .iter()
        .filter_map(|s| anchor_of(&s.points))
        .collect();
    let Some(first) = anchors.first() else {
        return Vec::new();
    };
    figure
        .reference_slopes
        .iter()
        .filter(|r| r.slope.is_finite())
        .filter_map(|r| {
            let p = r.slope;
            let intercept = |a: &&Anchor| a.finest.1 - p * a.finest.0;
            let misfit = |a: &&Anchor| a.slope.map_or(f64::INFINITY, |s| (s - p).abs());
            let best = anchors
                .iter()
                .map(|a| misfit(&a))
                .fold(f64::INFINITY, f64::min);
            let anchor = anchors
                .iter()
                .filter(|a| best.is_finite() && misfit(a) <= best + 0.3)
                .min_by(|a, b| intercept(a).total_cmp(&intercept(b)))
                .unwrap_or(first);
            let (x0, y0) = anchor.finest;
            let x1 = if anchor.x_max - x0 < 1e-9 {
                x0 + 1.0
            } else {
                anchor.x_max
            };
            let ya = y0 - LOG10_2;
            let yb = ya + p * (x1 - x0);
            (yb.is_finite() && (-330.0..=310.0).contains(&yb)).then_some(RefLine {
                label: &r.label,
                from: (x0, ya),
                to: (x1, yb),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    // Setting: colour assignment and reference-line geometry, without drawing.
    // Goal: pin the automatic colour order and the anchor of reference slopes.
    use super::*;

    #[test]
    fn automatic_colors_skip_explicitly_chosen_ones() {
        let s = |c: Option<usize>| {
            let mut s = Series::line("s", vec![(1.0, 1.0)]);
            s.style.color = c;
            s
        };
        let colors = assign_colors(&[s(None), s(Some(1)), s(None), s(Some(9))]);
        assert_eq!(colors, vec![0, 1, 2, 1]);
    }

    #[test]
    fn reference_line_sits_a_factor_two_below_the_finest_point() {
        let fig = Figure::new("t")
            .log_log()
            .series(Series::line(
                "a",
                vec![(0.1, 1e-2), (0.01, 1e-4), (f64::NAN, 1.0)],
            ))
            .reference_slope(2.0, "slope 2");
        let prepared = prepare(&fig);
        let refs = reference_lines(&fig, &prepared);
        assert_eq!(refs.len(), 1);
        assert!((refs[0].from.0 + 2.0).abs() < 1e-12);
        assert!((refs[0].from.1 - (-4.0 - LOG10_2)).abs() < 1e-12);
        assert!((refs[0].to.0 + 1.0).abs() < 1e-12);
        assert!((refs[0].to.1 - (-2.0 - LOG10_2)).abs() < 1e-12);
    }

    #[test]
    fn each_reference_slope_runs_under_the_lowest_series_of_matching_order() {
        let hs = [0.1, 0.05, 0.025];
        let fig = Figure::new("t")
            .log_log()
            .series(Series::line("first order", hs.map(|h| (h, h))))
            .series(Series::line("second order", hs.map(|h| (h, h * h))))
            .series(Series::line(
                "second order, lower",
                hs.map(|h| (h, 0.1 * h * h)),
            ))
            .reference_slope(1.0, "slope 1")
            .reference_slope(2.0, "slope 2")
            .reference_slope(4.0, "slope 4")
            .reference_slope(f64::INFINITY, "dropped");
        let refs = reference_lines(&fig, &prepare(&fig));
        assert_eq!(refs.len(), 3);
        let finest = 0.025f64.log10();
        let below = |y: f64| y.log10() - LOG10_2;
        assert!((refs[0].from.1 - below(0.025)).abs() < 1e-12);
        assert!((refs[1].from.1 - below(0.1 * 0.025 * 0.025)).abs() < 1e-12);
        // No series near slope 4: the group nearest in slope (2) is used, its lowest member.
        assert!((refs[2].from.1 - below(0.1 * 0.025 * 0.025)).abs() < 1e-12);
        assert!(refs.iter().all(|r| (r.from.0 - finest).abs() < 1e-12));
    }
}
