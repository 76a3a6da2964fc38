//! `verify --list`: every case with its kind, tier and last measured run time (from the reports),
//! and what each tier costs.

use std::collections::BTreeMap;
use std::fmt::Write;

use crate::core::case::{Case, Tier};

/// The catalogue, a line per case, then the cases and recorded seconds of each tier.
pub fn render(cases: &[Case], recorded: &BTreeMap<String, f64>) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<36} {:<24} {:<8} {:>10}  title",
        "case", "kind", "tier", "last (s)"
    );
    for c in cases {
        let last = recorded
            .get(&c.header.id)
            .map(|t| format!("{t:.2}"))
            .unwrap_or_else(|| "—".into());
        let _ = writeln!(
            s,
            "{:<36} {:<24} {:<8} {:>10}  {}",
            c.header.id,
            c.header.kind,
            c.header.tier.name(),
            last,
            c.header.title
        );
    }
    let _ = writeln!(s);
    for (tier, flag) in [
        (Tier::Quick, "verify --quick"),
        (Tier::Default, "verify"),
        (Tier::Full, "verify --full"),
    ] {
        let in_tier: Vec<&Case> = cases
            .iter()
            .filter(|c| c.header.tier.runs_in(tier))
            .collect();
        let seconds: f64 = in_tier
            .iter()
            .filter_map(|c| recorded.get(&c.header.id))
            .sum();
        let unknown = in_tier
            .iter()
            .filter(|c| !recorded.contains_key(&c.header.id))
            .count();
        let _ = writeln!(
            s,
            "{:<16} {:>3} cases, {:>7.1} s recorded{}",
            flag,
            in_tier.len(),
            seconds,
            if unknown > 0 {
                format!(" (+{unknown} never run)")
            } else {
                String::new()
            }
        );
    }
    s
}
