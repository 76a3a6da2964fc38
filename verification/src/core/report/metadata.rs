//! Provenance of a report: crate version, git commit, compiler, host, date, threads.

use serde::{Deserialize, Serialize};

/// Where and when a report was produced.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Metadata {
    pub contactlab_version: String,
    pub git_commit: String,
    /// Whether the working tree had uncommitted changes (outside reports/).
    pub git_dirty: bool,
    pub rustc: String,
    pub host: String,
    pub os: String,
    pub cpus: usize,
    pub threads: usize,
    /// UTC, ISO 8601.
    pub date: String,
    /// `quick`, `default`, `full` (or `test`).
    pub tier: String,
}

impl Metadata {
    /// Collects the metadata of this process (commands that fail give `unknown`).
    pub fn collect(tier: &str) -> Self {
        let git = |args: &[&str]| {
            std::process::Command::new("git")
                .args(args)
                .output()
                .ok()
                .filter(|o| o.status.success())
                .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        };
        let commit = git(&["rev-parse", "HEAD"]).unwrap_or_else(|| "unknown".into());
        // Generated reports do not make the source tree dirty.
        let dirty = git(&[
            "status",
            "--porcelain",
            "--untracked-files=no",
            "--",
            ".",
            ":!reports",
        ])
        .map(|s| !s.is_empty())
        .unwrap_or(false);
        let host = std::fs::read_to_string("/etc/hostname")
            .map(|s| s.trim().to_string())
            .ok()
            .filter(|s| !s.is_empty())
            .or_else(|| std::env::var("HOSTNAME").ok())
            .unwrap_or_else(|| "unknown".into());
        Self {
            contactlab_version: contactlab::VERSION.to_string(),
            git_commit: commit,
            git_dirty: dirty,
            rustc: env!("CONTACTLAB_RUSTC_VERSION").to_string(),
            host,
            os: format!("{} {}", std::env::consts::OS, std::env::consts::ARCH),
            cpus: std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(1),
            threads: rayon::current_num_threads(),
            date: utc_now(),
            tier: tier.to_string(),
        }
    }
}

/// The current UTC time as `YYYY-MM-DDTHH:MM:SSZ` (civil-from-days, Howard Hinnant's algorithm).
pub fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs() as i64)
        .unwrap_or(0);
    let days = secs.div_euclid(86_400);
    let rem = secs.rem_euclid(86_400);
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + if m <= 2 { 1 } else { 0 };
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        (rem % 3600) / 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    //! Metadata: the date is well-formed ISO 8601 UTC.
    use super::*;

    #[test]
    fn utc_now_is_iso_8601() {
        let s = utc_now();
        assert_eq!(s.len(), 20, "{s}");
        assert!(s.ends_with('Z'));
        assert_eq!(&s[4..5], "-");
        assert!(s.starts_with("20"));
    }
}
