//! Memory checked before anything is allocated: each scene format estimates, from its counts
//! alone, the bytes its run will hold (meshes, operators and factors, time histories, snapshots)
//! and refuses a scene above the limit with an error that gives the estimate and the limit — not
//! a "capacity overflow" panic or an allocation abort halfway through a run.
//!
//! The limit: [`set_memory_limit`] (`verify scene --max-memory`), else the environment variable
//! `CONTACTLAB_MAX_MEMORY` (bytes, or with a suffix K, M, G, T), else half of the machine's memory
//! (`MemTotal` of /proc/meminfo), else 4 GiB.

use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::InputError;

static LIMIT_OVERRIDE: AtomicU64 = AtomicU64::new(0);

/// Sets the limit for this process (0: back to the default).
pub fn set_memory_limit(bytes: u64) {
    LIMIT_OVERRIDE.store(bytes, Ordering::Relaxed);
}

/// Parses a size such as `8G`, `512M`, `1e9` (bytes).
pub fn parse_size(text: &str) -> Option<u64> {
    let t = text.trim();
    let (num, mult) = match t.chars().last()? {
        'K' | 'k' => (&t[..t.len() - 1], 1u64 << 10),
        'M' | 'm' => (&t[..t.len() - 1], 1 << 20),
        'G' | 'g' => (&t[..t.len() - 1], 1 << 30),
        'T' | 't' => (&t[..t.len() - 1], 1 << 40),
        _ => (t, 1),
    };
    let v: f64 = num.trim().parse().ok()?;
    let bytes = v * mult as f64;
    (bytes.is_finite() && bytes >= 1.0 && bytes < u64::MAX as f64).then_some(bytes as u64)
}

/// The limit in bytes and where it comes from.
pub fn memory_limit() -> (u64, &'static str) {
    let o = LIMIT_OVERRIDE.load(Ordering::Relaxed);
    if o > 0 {
        return (o, "--max-memory");
    }
    if let Some(b) = std::env::var("CONTACTLAB_MAX_MEMORY")
        .ok()
        .and_then(|v| parse_size(&v))
    {
        return (b, "CONTACTLAB_MAX_MEMORY");
    }
    let total = std::fs::read_to_string("/proc/meminfo").ok().and_then(|m| {
        m.lines()
            .find(|l| l.starts_with("MemTotal:"))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|kb| kb.parse::<u64>().ok())
    });
    match total {
        Some(kb) => (kb * 1024 / 2, "half of the machine's memory"),
        None => (4 << 30, "the default 4 GiB"),
    }
}

/// Refuses an estimate above the limit, naming the count that drives it (`field` = `written`) and
/// how the estimate was made (`how`). Estimates are in f64: a count of 2⁶³ must not overflow the
/// arithmetic that checks it.
pub fn require_memory(
    field: &str,
    written: impl std::fmt::Display,
    estimate: f64,
    how: &str,
) -> Result<(), InputError> {
    let (limit, source) = memory_limit();
    against(field, written, estimate, how, limit, source)
}

fn against(
    field: &str,
    written: impl std::fmt::Display,
    estimate: f64,
    how: &str,
    limit: u64,
    source: &str,
) -> Result<(), InputError> {
    if estimate.is_finite() && estimate <= limit as f64 {
        return Ok(());
    }
    Err(InputError::new(
        field,
        written,
        format!(
            "a scene that fits in memory: it needs about {} ({how}), above the limit of {} \
             ({source}; set it with --max-memory or CONTACTLAB_MAX_MEMORY)",
            human(estimate),
            human(limit as f64)
        ),
    ))
}

/// The number of distinct values among `times` (a time written twice is recorded once).
pub fn distinct_times(times: &[f64]) -> usize {
    let mut t = times.to_vec();
    t.sort_by(f64::total_cmp);
    t.dedup();
    t.len()
}

/// A byte count for people.
fn human(b: f64) -> String {
    if !b.is_finite() {
        return "more than any machine has".into();
    }
    let units = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = b;
    let mut i = 0;
    while v >= 1024.0 && i + 1 < units.len() {
        v /= 1024.0;
        i += 1;
    }
    if i + 1 == units.len() && v >= 1024.0 {
        format!("{b:.2e} B")
    } else {
        format!("{v:.1} {}", units[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_suffixes_and_reject_nonsense() {
        assert_eq!(parse_size("512"), Some(512));
        assert_eq!(parse_size("2K"), Some(2048));
        assert_eq!(parse_size("1.5G"), Some(3 << 29));
        assert_eq!(parse_size("0"), None);
        assert_eq!(parse_size("-3M"), None);
        assert_eq!(parse_size("lots"), None);
    }

    #[test]
    fn an_estimate_above_the_limit_is_an_error_with_both_figures() {
        let mib = 1 << 20;
        assert!(against("mesh.elements", 10, 1000.0, "x", mib, "test").is_ok());
        let e = against("mesh.elements", 1e18, 8e18, "8 B per node", mib, "test")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("mesh.elements") && e.contains("EiB") && e.contains("1.0 MiB"),
            "{e}"
        );
        let e = against("time.steps", "huge", f64::INFINITY, "y", mib, "test")
            .unwrap_err()
            .to_string();
        assert!(e.contains("more than any machine has"), "{e}");
    }
}
