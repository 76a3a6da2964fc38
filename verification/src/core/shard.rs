//! `verify --shard I/N`: a deterministic 1/N of a run's cases, balanced by their last measured
//! run times, so that N jobs (CI matrix jobs, a cluster's job array) finish together and
//! `verify merge` joins their results into the report of one unsharded run.
//!
//! The partition is the longest-processing-time rule: cases sorted by run time (longest first,
//! ties by id), each given to the shard with the least time so far (ties: the lowest index).
//! Its input is the case list and the run times committed in `reports/` — the same at a commit on
//! every machine — so every job of an array computes the same partition without talking to the
//! others. A case without a recorded time counts [`UNKNOWN_SECONDS`].

use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;
use std::str::FromStr;

/// The run time assumed for a case that has none recorded (a new case).
pub const UNKNOWN_SECONDS: f64 = 1.0;

/// Shard `index` (1-based) of `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// The whole run: one shard.
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The largest number of shards accepted (more than any catalogue has cases is pointless, and the
/// bound keeps a typo like `1/1000000000` from allocating).
pub const MAX_SHARDS: usize = 1000;

impl FromStr for Shard {
    type Err = String;

    /// `I/N` with 1 ≤ I ≤ N ≤ [`MAX_SHARDS`].
    fn from_str(s: &str) -> Result<Self, String> {
        let expected = format!("I/N with 1 ≤ I ≤ N ≤ {MAX_SHARDS}, e.g. 2/3");
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| format!("--shard = {s:?}: expected {expected}"))?;
        let parse = |t: &str| t.trim().parse::<usize>().ok();
        match (parse(i), parse(n)) {
            (Some(index), Some(count)) if 1 <= index && index <= count && count <= MAX_SHARDS => {
                Ok(Shard { index, count })
            }
            _ => Err(format!("--shard = {s:?}: expected {expected}")),
        }
    }
}

/// The shard (0-based) of every case: `cases` are (id, seconds) pairs in catalogue order; the
/// result has one entry per case, in the same order.
pub fn partition(cases: &[(String, f64)], count: usize) -> Vec<usize> {
    let count = count.max(1);
    let mut order: Vec<usize> = (0..cases.len()).collect();
    order.sort_by(|&a, &b| {
        cases[b]
            .1
            .total_cmp(&cases[a].1)
            .then_with(|| cases[a].0.cmp(&cases[b].0))
    });
    let mut load = vec![0.0_f64; count];
    let mut shard_of = vec![0; cases.len()];
    for i in order {
        let mut best = 0;
        for s in 1..count {
            if load[s] < load[best] {
                best = s;
            }
        }
        load[best] += cases[i].1;
        shard_of[i] = best;
    }
    shard_of
}

/// The last measured run time of every case whose `<id>.timings.json` is in `reports` (the
/// `/wall_seconds` leaf the report writes); cases without one are absent.
pub fn recorded_seconds(reports: &Path, ids: &[String]) -> BTreeMap<String, f64> {
    let mut out = BTreeMap::new();
    for id in ids {
        let path = reports.join(format!("{id}.timings.json"));
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue;
        };
        let Ok(value) = serde_json::from_str::<serde_json::Value>(&text) else {
            continue;
        };
        if let Some(s) = value
            .pointer("/leaves/~1wall_seconds")
            .and_then(|v| v.as_f64())
            .filter(|s| s.is_finite() && *s >= 0.0)
        {
            out.insert(id.clone(), s);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    //! The partition: every case in exactly one shard, balanced, independent of nothing but its
    //! input; the `I/N` syntax refused out of range.
    use super::*;

    fn cases(times: &[f64]) -> Vec<(String, f64)> {
        times
            .iter()
            .enumerate()
            .map(|(i, &t)| (format!("case_{i:02}"), t))
            .collect()
    }

    #[test]
    fn every_case_lands_in_exactly_one_shard_and_the_loads_are_balanced() {
        let c = cases(&[90.0, 30.0, 20.0, 20.0, 10.0, 8.0, 5.0, 3.0, 1.0, 1.0, 0.5]);
        let s = partition(&c, 3);
        assert_eq!(s.len(), c.len());
        let mut load = [0.0; 3];
        for (i, &k) in s.iter().enumerate() {
            load[k] += c[i].1;
        }
        // the 90 s case alone is the longest shard; the others share the rest evenly
        assert_eq!(load[0], 90.0);
        assert!((load[1] - load[2]).abs() <= 1.0, "{load:?}");
    }

    #[test]
    fn the_partition_depends_only_on_ids_and_times() {
        let c = cases(&[1.0, 1.0, 1.0, 1.0, 1.0]);
        assert_eq!(partition(&c, 2), partition(&c, 2));
        // equal times: ties broken by id, so the order of the input does not matter
        let mut r = c.clone();
        r.reverse();
        let a = partition(&c, 2);
        let mut b = partition(&r, 2);
        b.reverse();
        assert_eq!(a, b);
    }

    #[test]
    fn one_shard_holds_everything_and_more_shards_than_cases_leave_some_empty() {
        let c = cases(&[3.0, 2.0]);
        assert_eq!(partition(&c, 1), vec![0, 0]);
        let s = partition(&c, 5);
        assert_ne!(s[0], s[1]);
    }

    #[test]
    fn shard_syntax_is_checked() {
        assert_eq!("2/3".parse::<Shard>(), Ok(Shard { index: 2, count: 3 }));
        for bad in ["0/3", "4/3", "3", "a/b", "1/0", "1/1001", "-1/2"] {
            let e = bad.parse::<Shard>().expect_err(bad);
            assert!(e.contains(bad), "{e}");
        }
    }
}
