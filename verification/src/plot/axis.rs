//! Axis ranges and tick marks, computed in *axis space*: the value itself on a linear axis,
//! its base-10 logarithm on a logarithmic one. Pure functions, no drawing.

use super::Scale;

/// Largest magnitude accepted on a linear axis; larger values are treated like non-finite ones,
/// so that spans and paddings stay finite.
const LINEAR_LIMIT: f64 = 1e300;

/// An axis ready to draw: its range in axis space and its tick marks.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Axis {
    pub scale: Scale,
    /// Lower end of the range, in axis space.
    pub lo: f64,
    /// Upper end of the range, in axis space (`hi > lo`, both finite).
    pub hi: f64,
    /// Labelled ticks: position in axis space and label.
    pub major: Vec<(f64, String)>,
    /// Unlabelled light grid positions, in axis space.
    pub minor: Vec<f64>,
}

impl Axis {
    /// Fraction of the way from `lo` to `hi` of an axis-space value.
    pub fn fraction(&self, t: f64) -> f64 {
        (t - self.lo) / (self.hi - self.lo)
    }
}

/// Maps a data value to axis space; `None` when it cannot be drawn on this scale
/// (non-finite, or not positive on a log axis).
pub(crate) fn to_axis(scale: Scale, v: f64) -> Option<f64> {
    match scale {
        Scale::Linear if v.is_finite() && v.abs() <= LINEAR_LIMIT => Some(v),
        Scale::Log if v.is_finite() && v > 0.0 => Some(v.log10()),
        _ => None,
    }
}

/// A user-given data range mapped to axis space, or `None` when it is unusable
/// (non-finite, empty, reversed, or not positive on a log axis).
pub(crate) fn user_range(scale: Scale, range: Option<(f64, f64)>) -> Option<(f64, f64)> {
    let (a, b) = range?;
    let (lo, hi) = (to_axis(scale, a)?, to_axis(scale, b)?);
    let mag = lo.abs().max(hi.abs());
    (hi > lo && hi - lo > 1e-12 * mag && (hi - lo).is_finite()).then_some((lo, hi))
}

/// Automatic range (axis space) covering `values` (axis space, all finite) with a little padding.
/// Linear: 5 % each side, constant data padded by 10 % of its magnitude (or 1).
/// Log: padded by 5 % of the span (at least 0.03 decade), snapped to whole decades when that
/// widens each end by less than 0.3 decade; constant data get one decade each side.
pub(crate) fn auto_range(scale: Scale, values: &[f64]) -> (f64, f64) {
    let finite = values.iter().copied().filter(|v| v.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if lo > hi {
        return (0.0, 1.0); // no values: [0, 1] on a linear axis, [1, 10] on a log one
    }
    match scale {
        Scale::Linear => {
            let mag = lo.abs().max(hi.abs());
            let span = hi - lo;
            if span > 1e-12 * mag && span.is_finite() && span > 0.0 {
                let pad = 0.05 * span;
                (lo - pad, hi + pad)
            } else {
                let pad = if mag > 1e-300 { 0.1 * mag } else { 1.0 };
                (lo - pad, hi + pad)
            }
        }
        Scale::Log => {
            let span = hi - lo;
            if span < 1e-9 {
                ((lo - 0.5).floor(), (hi + 0.5).ceil())
            } else {
                let pad = (0.05 * span).max(0.03);
                let (mut lo, mut hi) = (lo - pad, hi + pad);
                if lo - lo.floor() <= 0.3 {
                    lo = lo.floor();
                }
                if hi.ceil() - hi <= 0.3 {
                    hi = hi.ceil();
                }
                (lo, hi)
            }
        }
    }
}

/// Builds the axis for a range in axis space, with at most about `max_labels` labelled ticks.
pub(crate) fn build_axis(scale: Scale, (lo, hi): (f64, f64), max_labels: usize) -> Axis {
    let max_labels = max_labels.max(2);
    let (major, minor) = match scale {
        Scale::Linear => (linear_ticks(lo, hi, max_labels), Vec::new()),
        Scale::Log => log_ticks(lo, hi, max_labels),
    };
    Axis {
        scale,
        lo,
        hi,
        major,
        minor,
    }
}

/// Number of decimals needed to write `x` (a tick step) exactly, at most 12.
fn decimals_for(x: f64) -> usize {
    (0..=12)
        .find(|&d| {
            let s = x * 10f64.powi(d as i32);
            (s - s.round()).abs() <= 1e-6 * s.abs().max(1.0)
        })
        .unwrap_or(12)
}

/// "Nice" linear ticks (steps 1, 2, 2.5 or 5 times a power of ten).
fn linear_ticks(lo: f64, hi: f64, max_labels: usize) -> Vec<(f64, String)> {
    let span = hi - lo;
    if !(span > 0.0 && span.is_finite()) {
        return Vec::new();
    }
    let raw = span / max_labels as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw * (1.0 - 1e-9))
        .unwrap_or(10.0 * mag);
    if !(step > 0.0 && step.is_finite()) {
        return Vec::new();
    }
    let i0 = (lo / step - 1e-9).ceil();
    let i1 = (hi / step + 1e-9).floor();
    if !(i0.is_finite() && i1.is_finite()) || i1 - i0 > 100.0 {
        return Vec::new();
    }
    let maxabs = lo.abs().max(hi.abs());
    let scientific = !(1e-3..1e5).contains(&maxabs);
    let mut ticks = Vec::new();
    let mut i = i0;
    while i <= i1 {
        let mut v = i * step;
        if v.abs() < step * 1e-6 {
            v = 0.0;
        }
        ticks.push((v, format_linear(v, step, maxabs, scientific)));
        i += 1.0;
    }
    ticks
}

/// Formats a linear tick value so that neighbouring ticks `step` apart are distinguishable.
fn format_linear(v: f64, step: f64, maxabs: f64, scientific: bool) -> String {
    if v == 0.0 {
        return "0".to_string();
    }
    if scientific {
        let e = maxabs.log10().floor();
        let d = decimals_for(step / 10f64.powf(e));
        format!("{v:.d$e}")
    } else {
        let d = decimals_for(step);
        format!("{v:.d$}")
    }
}

/// Label of `k × 10^e` on a log axis: plain decimals when `plain`, else scientific (`2e-3`).
fn log_label(k: u32, e: i32, plain: bool) -> String {
    if plain {
        let d = (-e).max(0) as usize;
        format!("{:.d$}", f64::from(k) * 10f64.powi(e))
    } else if k == 1 {
        format!("1e{e}")
    } else {
        format!("{k}e{e}")
    }
}

/// Log-axis ticks: decades (thinned to at most `max_labels`), minor lines at 2…9 times a decade;
/// for ranges narrower than two decades, ticks at 1, 2, 5 (or 1…9) times a decade.
/// Labels are plain decimals when all labelled exponents lie in −2…3, scientific otherwise.
fn log_ticks(lo: f64, hi: f64, max_labels: usize) -> (Vec<(f64, String)>, Vec<f64>) {
    const EPS: f64 = 1e-9;
    let inside = |t: f64| t >= lo - EPS && t <= hi + EPS;
    let e_lo = lo.floor() as i32;
    let e_hi = hi.ceil() as i32;
    let decades: Vec<i32> = (e_lo..=e_hi).filter(|&e| inside(f64::from(e))).collect();

    // (k, e) of the labelled ticks, and positions of light lines.
    let mut labelled: Vec<(u32, i32)> = Vec::new();
    let mut minor: Vec<f64> = Vec::new();
    if decades.len() >= 2 {
        let mut stride = decades.len().div_ceil(max_labels).max(1) as i32;
        if decades.iter().filter(|e| e.rem_euclid(stride) == 0).count() < 2 {
            stride = 1;
        }
        for &e in &decades {
            if e.rem_euclid(stride) == 0 {
                labelled.push((1, e));
            } else {
                minor.push(f64::from(e));
            }
        }
        if stride == 1 && hi - lo <= 8.0 {
            for e in e_lo..=e_hi {
                for k in 2..=9u32 {
                    let t = f64::from(k).log10() + f64::from(e);
                    if inside(t) {
                        minor.push(t);
                    }
                }
            }
        }
    } else {
        let candidates = |ks: &[u32]| -> Vec<(u32, i32)> {
            (e_lo..=e_hi)
                .flat_map(|e| ks.iter().map(move |&k| (k, e)))
                .filter(|&(k, e)| inside(f64::from(k).log10() + f64::from(e)))
                .collect()
        };
        labelled = candidates(&[1, 2, 5]);
        if labelled.len() < 2 {
            labelled = candidates(&[1, 2, 3, 4, 5, 6, 7, 8, 9]);
        }
        if labelled.len() > max_labels {
            labelled = candidates(&[1, 2, 5]);
        }
        for (k, e) in candidates(&[1, 2, 3, 4, 5, 6, 7, 8, 9]) {
            if !labelled.contains(&(k, e)) {
                minor.push(f64::from(k).log10() + f64::from(e));
            }
        }
    }
    let plain = labelled.iter().all(|&(_, e)| (-2..=3).contains(&e));
    let mut major: Vec<(f64, String)> = labelled
        .iter()
        .map(|&(k, e)| (f64::from(k).log10() + f64::from(e), log_label(k, e, plain)))
        .collect();
    if major.len() < 2 {
        // Very narrow range: label the two ends.
        major = [lo, hi]
            .iter()
            .map(|&t| (t, format!("{:.3e}", 10f64.powf(t))))
            .collect();
        minor.clear();
    }
    (major, minor)
}

#[cfg(test)]
mod tests {
    // Setting: pure range and tick computations, no drawing.
    // Goal: pin padding, decade snapping, tick labels and robustness on degenerate input.
    use super::*;

    #[test]
    fn log_auto_range_snaps_to_nearby_decades() {
        let vals = [2e-3f64.log10(), 8e-2f64.log10()];
        assert_eq!(auto_range(Scale::Log, &vals), (-3.0, -1.0));
    }

    #[test]
    fn log_auto_range_pads_data_sitting_on_decades() {
        let (lo, hi) = auto_range(Scale::Log, &[-3.0, -1.0]);
        assert!(
            lo < -3.0 && lo > -3.5 && hi > -1.0 && hi < -0.5,
            "{lo} {hi}"
        );
    }

    #[test]
    fn constant_data_gets_a_nonzero_range_on_both_scales() {
        let (lo, hi) = auto_range(Scale::Linear, &[3.0, 3.0]);
        assert!(lo < 3.0 && hi > 3.0);
        let (lo, hi) = auto_range(Scale::Linear, &[0.0]);
        assert_eq!((lo, hi), (-1.0, 1.0));
        let (lo, hi) = auto_range(Scale::Log, &[-3.0]);
        assert_eq!((lo, hi), (-4.0, -2.0));
    }

    #[test]
    fn log_tick_labels_are_scientific_outside_minus_two_to_three() {
        let axis = build_axis(Scale::Log, (-6.0, -1.0), 8);
        let labels: Vec<&str> = axis.major.iter().map(|(_, l)| l.as_str()).collect();
        assert_eq!(labels, ["1e-6", "1e-5", "1e-4", "1e-3", "1e-2", "1e-1"]);
        let axis = build_axis(Scale::Log, (-2.0, 1.0), 8);
        let labels: Vec<&str> = axis.major.iter().map(|(_, l)| l.as_str()).collect();
        assert_eq!(labels, ["0.01", "0.1", "1", "10"]);
    }

    #[test]
    fn many_decades_are_thinned_to_the_label_budget() {
        let axis = build_axis(Scale::Log, (-16.0, 0.0), 6);
        assert!(
            axis.major.len() <= 6 && axis.major.len() >= 2,
            "{:?}",
            axis.major
        );
    }

    #[test]
    fn narrow_log_range_still_gets_two_labels() {
        let axis = build_axis(Scale::Log, (0.3f64.log10(), 0.5f64.log10()), 6);
        assert!(axis.major.len() >= 2, "{:?}", axis.major);
        let axis = build_axis(Scale::Log, (0.0, 1e-6), 6);
        assert_eq!(axis.major.len(), 2);
    }

    #[test]
    fn linear_ticks_are_round_and_without_float_noise() {
        let axis = build_axis(Scale::Linear, (-0.05, 1.05), 6);
        let labels: Vec<&str> = axis.major.iter().map(|(_, l)| l.as_str()).collect();
        assert_eq!(
            labels,
            ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"].map(|s| {
                if s == "0.0" {
                    "0"
                } else {
                    s
                }
            })
        );
        let axis = build_axis(Scale::Linear, (0.0, 3e6), 6);
        assert!(axis.major.iter().any(|(_, l)| l.contains('e')));
    }

    #[test]
    fn unusable_user_ranges_are_ignored() {
        assert_eq!(user_range(Scale::Log, Some((0.0, 1.0))), None);
        assert_eq!(user_range(Scale::Linear, Some((2.0, 1.0))), None);
        assert_eq!(user_range(Scale::Linear, Some((f64::NAN, 1.0))), None);
        assert_eq!(user_range(Scale::Log, Some((1.0, 100.0))), Some((0.0, 2.0)));
    }
}
