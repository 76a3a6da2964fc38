//! The level rule: which levels of a sweep enter a rate fit. One rule, applied the same way by
//! every rate gate of every family (no level is excluded by hand).
//!
//! The levels are sorted coarse to fine (`p` descending) and `r_i` is the pairwise rate between
//! levels `i` and `i + 1`. Two kinds of level are left out, and the report says which and why:
//!
//! 1. **Floor** (at the fine end). A level whose error is below [`FLOOR_MARGIN`] times the floor
//!    `F` of the sweep is dominated by something other than the discretization being refined:
//!    round-off, the solver's tolerance, or the error of the *other* variable (the space error of a
//!    k-sweep at fixed h). `F` is supplied by the family that knows it (0 when nothing is known:
//!    then no level is a floor). Only a run of levels at the fine end is cut, so a floor cannot
//!    hide a coarse level.
//! 2. **Pre-asymptotic** (at the coarse end). The fit uses the longest run of the finest levels
//!    whose pairwise rates all lie within the gate's `tolerance` of their median: starting from
//!    the three finest levels (two rates), the next coarser level joins while every rate of the
//!    run, its own included, stays within `tolerance` of the run's median; the first level that
//!    would break this, and every coarser one, is pre-asymptotic (the rates are still drifting
//!    there). The rule looks at the rates only, never at the expected rate, so it cannot select
//!    levels that agree with the expectation.
//!
//! At least three levels must remain (two pairwise rates and one degree of freedom for the
//! confidence interval); otherwise the gate fails and says so.

use serde::Serialize;

/// A level is a floor when its error is below this multiple of the floor `F` (the floor then
/// contributes more than about a tenth of the error, enough to bend the observed rate).
pub const FLOOR_MARGIN: f64 = 10.0;

/// The fewest levels a fit may use.
pub const MIN_LEVELS: usize = 3;

/// Why a level was left out of the fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Exclusion {
    /// The pairwise rates were still drifting here (coarse end).
    PreAsymptotic,
    /// The error is within [`FLOOR_MARGIN`] of the sweep's floor (fine end).
    Floor,
}

/// One level as the rule saw it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelStatus {
    /// The parameter (`h` or `k`).
    pub param: f64,
    pub error: f64,
    /// `None` when the level enters the fit.
    pub excluded: Option<Exclusion>,
}

/// The outcome of the rule on one sweep: every level, coarse to fine, with its status.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelWindow {
    pub levels: Vec<LevelStatus>,
    /// The floor `F` the rule was given (0: none known).
    pub floor: f64,
}

impl LevelWindow {
    /// The (param, error) pairs that enter the fit, coarse to fine.
    pub fn used(&self) -> (Vec<f64>, Vec<f64>) {
        self.levels
            .iter()
            .filter(|l| l.excluded.is_none())
            .map(|l| (l.param, l.error))
            .unzip()
    }

    /// How many levels enter the fit.
    pub fn count(&self) -> usize {
        self.levels.iter().filter(|l| l.excluded.is_none()).count()
    }

    /// One line for reports: `used 4 of 6 levels (1 pre-asymptotic, 1 floor)`.
    pub fn describe(&self) -> String {
        let pre = self
            .levels
            .iter()
            .filter(|l| l.excluded == Some(Exclusion::PreAsymptotic))
            .count();
        let floor = self
            .levels
            .iter()
            .filter(|l| l.excluded == Some(Exclusion::Floor))
            .count();
        let mut s = format!("used {} of {} levels", self.count(), self.levels.len());
        if pre + floor > 0 {
            let mut parts = Vec::new();
            if pre > 0 {
                parts.push(format!("{pre} pre-asymptotic"));
            }
            if floor > 0 {
                parts.push(format!("{floor} at the floor {:e}", self.floor));
            }
            s.push_str(&format!(" ({})", parts.join(", ")));
        }
        s
    }
}

/// The median of a non-empty slice (the mean of the two middle values for an even length).
fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Applies the level rule to one sweep. `param` and `error` pair up (any order; levels whose
/// values are not finite and positive are kept with their status for the report but never
/// used); `tolerance` is the gate's rate tolerance, `floor` the sweep's floor (0: none).
pub fn asymptotic_window(param: &[f64], error: &[f64], tolerance: f64, floor: f64) -> LevelWindow {
    let mut levels: Vec<LevelStatus> = param
        .iter()
        .zip(error)
        .map(|(&p, &e)| LevelStatus {
            param: p,
            error: e,
            excluded: None,
        })
        .collect();
    levels.sort_by(|a, b| b.param.total_cmp(&a.param));
    let floor = if floor.is_finite() && floor > 0.0 {
        floor
    } else {
        0.0
    };
    // 1. floors, from the fine end
    for l in levels.iter_mut().rev() {
        if floor > 0.0 && l.error < FLOOR_MARGIN * floor {
            l.excluded = Some(Exclusion::Floor);
        } else {
            break;
        }
    }
    // 2. pre-asymptotic levels: grow the run of finest levels while its rates agree
    let candidates: Vec<usize> = (0..levels.len())
        .filter(|&i| levels[i].excluded.is_none())
        .collect();
    if candidates.len() > MIN_LEVELS {
        let rate = |a: usize, b: usize| {
            let (a, b) = (&levels[a], &levels[b]);
            (a.error.ln() - b.error.ln()) / (a.param.ln() - b.param.ln())
        };
        let rates: Vec<f64> = candidates.windows(2).map(|w| rate(w[0], w[1])).collect();
        // the run starts with the two finest rates and takes rates[first..]
        let mut first = rates.len() - (MIN_LEVELS - 1);
        while first > 0 {
            let run = &rates[first - 1..];
            let m = median(run);
            if run
                .iter()
                .all(|r| r.is_finite() && (r - m).abs() <= tolerance)
            {
                first -= 1;
            } else {
                break;
            }
        }
        for &i in &candidates[..first] {
            levels[i].excluded = Some(Exclusion::PreAsymptotic);
        }
    }
    LevelWindow { levels, floor }
}

#[cfg(test)]
mod tests {
    //! The rule on synthetic sweeps: a clean power law keeps every level; a coarse level with a
    //! different rate is pre-asymptotic; errors at a stated floor are cut at the fine end only;
    //! three levels always remain; the expected rate plays no part.
    use super::*;

    fn halving(n: usize) -> Vec<f64> {
        (0..n).map(|i| 0.5_f64.powi(i as i32)).collect()
    }

    #[test]
    fn a_clean_power_law_keeps_every_level() {
        let h = halving(6);
        let e: Vec<f64> = h.iter().map(|h| 2.0 * h * h).collect();
        let w = asymptotic_window(&h, &e, 0.05, 0.0);
        assert_eq!(w.count(), 6);
        assert_eq!(w.describe(), "used 6 of 6 levels");
    }

    #[test]
    fn coarse_levels_with_drifting_rates_are_pre_asymptotic() {
        let h = halving(7);
        // E = h² + 3 h⁴: rates 2.9, 2.6, 2.3, … → 2
        let e: Vec<f64> = h.iter().map(|h| h * h + 3.0 * h.powi(4)).collect();
        let w = asymptotic_window(&h, &e, 0.05, 0.0);
        assert_eq!(w.levels[0].excluded, Some(Exclusion::PreAsymptotic));
        assert!(w.levels.last().unwrap().excluded.is_none());
        let (p, e) = w.used();
        let r =
            (e[e.len() - 2].ln() - e[e.len() - 1].ln()) / (p[p.len() - 2] / p[p.len() - 1]).ln();
        assert!((r - 2.0).abs() < 0.05, "{r}");
    }

    #[test]
    fn errors_at_the_floor_are_cut_at_the_fine_end_only() {
        let h = halving(6);
        let floor = 1e-3;
        let e: Vec<f64> = h.iter().map(|h| h * h + floor).collect();
        let w = asymptotic_window(&h, &e, 0.05, floor);
        // h² < 9e-3 (h ≤ 1/16) puts the error below 10 F
        let excluded: Vec<_> = w.levels.iter().map(|l| l.excluded).collect();
        assert_eq!(excluded[5], Some(Exclusion::Floor));
        assert_eq!(excluded[4], Some(Exclusion::Floor));
        assert!(w.describe().contains("at the floor"), "{}", w.describe());
    }

    #[test]
    fn at_least_three_levels_remain() {
        let h = halving(5);
        let e = [1.0, 0.9, 0.2, 0.19, 0.01];
        let w = asymptotic_window(&h, &e, 0.01, 0.0);
        assert!(w.count() >= MIN_LEVELS);
    }

    #[test]
    fn the_rule_does_not_depend_on_the_expected_rate() {
        // a wrong-order scheme (rate 1 everywhere) keeps every level: the gate will then fail on
        // the fitted rate, not hide behind the level rule
        let h = halving(6);
        let e: Vec<f64> = h.to_vec();
        assert_eq!(asymptotic_window(&h, &e, 0.05, 0.0).count(), 6);
    }
}
