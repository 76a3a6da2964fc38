//! Memory checked before anything is allocated: each scene format estimates, from its counts
//! alone, the bytes its run will hold (meshes, operators and factors, time histories, snapshots)
//! and refuses a scene above the limit with an error that gives the estimate and the limit — not
//! a "capacity overflow" panic or an allocation abort halfway through a run.
//!
//! The limit: [`set_memory_limit`] (`verify scene --max-memory`), else the environment variable
//! `CONTACTLAB_MAX_MEMORY` (bytes, or with a suffix K, M, G, T), else half of the machine's memory
//! (`MemTotal` of /proc/meminfo), else 4 GiB.

//!
//! The files a run writes are checked the same way against a disk limit: [`set_disk_limit`]
//! (`verify scene --max-disk`), else `CONTACTLAB_MAX_DISK`, else 8 GiB.
//!
//! The model ([`RunSize`]): a run holds the program itself ([`PROGRAM_BYTES`]), its operators
//! (per mesh), what it records per output time (the snapshots, each copy the recorders keep,
//! and their text) and per step (the histories and their text): a file is written from its text
//! held whole in memory, so each recorded number counts 8 B as a double plus [`TEXT_BYTES`] as
//! text (pretty-printed JSON: indentation, digits, separators). Repeated output times count once.

use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::InputError;

static LIMIT_OVERRIDE: AtomicU64 = AtomicU64::new(0);
static DISK_OVERRIDE: AtomicU64 = AtomicU64::new(0);

/// The resident size of the program before it allocates a model (code, libraries, allocator):
/// 13–14 MiB measured for the smallest example scenes; 16 MiB counted.
pub const PROGRAM_BYTES: f64 = 16.0 * 1024.0 * 1024.0;

/// The bytes of one number in the JSON the scenes write (pretty-printed, one number a line
/// with its indentation: 33–38 B measured per number of a snapshot); 40 B counted.
pub const TEXT_BYTES: f64 = 40.0;

/// The default disk limit (bytes).
const DEFAULT_DISK: u64 = 8 << 30;

/// Sets the disk limit for this process (0: back to the default).
pub fn set_disk_limit(bytes: u64) {
    DISK_OVERRIDE.store(bytes, Ordering::Relaxed);
}

/// The disk limit in bytes and where it comes from.
pub fn disk_limit() -> (u64, &'static str) {
    let o = DISK_OVERRIDE.load(Ordering::Relaxed);
    if o > 0 {
        return (o, "--max-disk");
    }
    if let Some(b) = std::env::var("CONTACTLAB_MAX_DISK")
        .ok()
        .and_then(|v| parse_size(&v))
    {
        return (b, "CONTACTLAB_MAX_DISK");
    }
    (DEFAULT_DISK, "the default 8 GiB")
}

/// What a run holds and writes, from its counts: three terms each — per mesh, per output time
/// and per step — with the key (as written, with its value) that sets each count. The memory
/// check adds [`PROGRAM_BYTES`]; each check names the key of its largest term.
#[derive(Debug, Clone)]
pub struct RunSize {
    /// The key that sets the mesh size and its value as written.
    pub mesh_key: (String, String),
    /// The distinct output times (repeated times count once).
    pub outputs: f64,
    /// The steps N as written (N + 1 states are recorded).
    pub steps: f64,
    /// Bytes held: [per mesh (operators, factors, work vectors), per output time, per step].
    pub memory: [f64; 3],
    /// Bytes written: [per mesh, per output time, per step].
    pub disk: [f64; 3],
    /// How the memory estimate is made (for the message).
    pub memory_how: &'static str,
    /// How the disk estimate is made.
    pub disk_how: &'static str,
}

impl RunSize {
    /// The total bytes held (the program included) and written.
    pub fn totals(&self) -> (f64, f64) {
        let sum = |t: &[f64; 3]| t[0] + self.outputs * t[1] + (self.steps + 1.0) * t[2];
        (PROGRAM_BYTES + sum(&self.memory), sum(&self.disk))
    }

    /// The key of the largest term of `terms` and its value as written.
    fn key_of(&self, terms: &[f64; 3]) -> (String, String) {
        let parts = [
            terms[0],
            self.outputs * terms[1],
            (self.steps + 1.0) * terms[2],
        ];
        let largest = (0..3).fold(0, |b, i| if parts[i] > parts[b] { i } else { b });
        match largest {
            0 => self.mesh_key.clone(),
            // a snapshot's size is the mesh's: both keys drive this term
            1 => (
                format!("output.times × {}", self.mesh_key.0),
                format!("({} distinct times) × {}", self.outputs, self.mesh_key.1),
            ),
            _ => ("time.steps".into(), format!("{}", self.steps)),
        }
    }

    /// Refuses a run whose memory or files exceed their limits, naming the key of the largest
    /// term, the estimate, how it was made and the limit.
    pub fn require(&self) -> Result<(), InputError> {
        let (memory, disk) = self.totals();
        let (field, written) = self.key_of(&self.memory);
        require_memory(&field, written, memory, self.memory_how)?;
        let (field, written) = self.key_of(&self.disk);
        let (limit, source) = disk_limit();
        against_disk(&field, written, disk, self.disk_how, limit, source)
    }
}

/// Refuses files above the disk limit, naming the count that drives them (`field` =
/// `written`) and how the estimate was made (`how`).
pub fn require_disk(
    field: &str,
    written: impl std::fmt::Display,
    estimate: f64,
    how: &str,
) -> Result<(), InputError> {
    let (limit, source) = disk_limit();
    against_disk(field, written, estimate, how, limit, source)
}

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

/// The two limits a run is checked against, with their words.
#[derive(Clone, Copy)]
enum Limit {
    Memory,
    Disk,
}

fn against(
    field: &str,
    written: impl std::fmt::Display,
    estimate: f64,
    how: &str,
    limit: u64,
    source: &str,
) -> Result<(), InputError> {
    against_limit(
        Limit::Memory,
        field,
        written,
        estimate,
        how,
        (limit, source),
    )
}

fn against_disk(
    field: &str,
    written: impl std::fmt::Display,
    estimate: f64,
    how: &str,
    limit: u64,
    source: &str,
) -> Result<(), InputError> {
    against_limit(Limit::Disk, field, written, estimate, how, (limit, source))
}

/// Refuses an estimate above `limit`, naming the count that drives it and how it was made.
fn against_limit(
    kind: Limit,
    field: &str,
    written: impl std::fmt::Display,
    estimate: f64,
    how: &str,
    (limit, source): (u64, &str),
) -> Result<(), InputError> {
    if estimate.is_finite() && estimate <= limit as f64 {
        return Ok(());
    }
    let (what, verb, flag, env) = match kind {
        Limit::Memory => (
            "a scene that fits in memory",
            "needs",
            "--max-memory",
            "CONTACTLAB_MAX_MEMORY",
        ),
        Limit::Disk => (
            "a run whose files fit the disk limit",
            "writes",
            "--max-disk",
            "CONTACTLAB_MAX_DISK",
        ),
    };
    Err(InputError::new(
        field,
        written,
        format!(
            "{what}: it {verb} about {} ({how}), above the limit of {} ({source}; set it with \
             {flag} or {env})",
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
    fn files_above_the_disk_limit_name_the_output_times_and_the_limit() {
        let run = RunSize {
            mesh_key: ("body.divisions".into(), "[16, 8]".into()),
            outputs: 20_000.0,
            steps: 100.0,
            memory: [1e6, 1e3, 1e2],
            disk: [1e4, 1e5, 1e3],
            memory_how: "m",
            disk_how: "40 B per number",
        };
        let (_, disk) = run.totals();
        assert_eq!(disk, 1e4 + 2e9 + 1.01e5);
        let e = against_disk(
            "output.times",
            "(20000 distinct times)",
            disk,
            "d",
            1 << 30,
            "t",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("output.times") && e.contains("1.0 GiB"), "{e}");
        assert_eq!(run.key_of(&run.disk).0, "output.times × body.divisions");
        assert_eq!(run.key_of(&run.memory).0, "output.times × body.divisions");
        assert_eq!(run.key_of(&[1e9, 1.0, 1.0]).0, "body.divisions");
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
