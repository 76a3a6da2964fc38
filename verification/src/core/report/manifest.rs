//! `run.json`: what a run of `verify` ran — its tier, its shard, the whole selection the shards
//! share, every case's rendered summary row and section, the metadata and the wall time — and
//! `verify merge`, which joins the directories of the N shards of one run into the directory an
//! unsharded run would have written: the same case files, a `report.md` of the same cases in the
//! same order, and one `run.json`.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::core::report::markdown::{assemble, CaseMarkdown};
use crate::core::report::metadata::Metadata;

/// The manifest's file name in a run's output directory.
pub const MANIFEST: &str = "run.json";

/// A run of `verify` (one shard of it, or all of it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunManifest {
    /// `quick`, `default` or `full`.
    pub tier: String,
    /// This run's shard (1-based) and the number of shards (1/1 for an unsharded run).
    pub shard_index: usize,
    pub shard_count: usize,
    /// Every case of the run before sharding, in catalogue order (the same in every shard).
    pub selection: Vec<String>,
    /// The cases this shard ran, in catalogue order.
    pub cases: Vec<CaseMarkdown>,
    pub metadata: Metadata,
    /// Wall time of the run (s); for a merged run, the sum over its shards.
    pub total_seconds: f64,
}

impl RunManifest {
    /// Writes `run.json` and `report.md` into `out`.
    pub fn write(&self, out: &Path) -> Result<PathBuf, String> {
        let json = serde_json::to_string_pretty(self).map_err(|e| e.to_string())?;
        let path = out.join(MANIFEST);
        std::fs::write(&path, json).map_err(|e| format!("{}: {e}", path.display()))?;
        let md = assemble(
            &self.cases,
            &self.metadata,
            self.total_seconds,
            self.shard_count,
        );
        let md_path = out.join("report.md");
        std::fs::write(&md_path, md).map_err(|e| format!("{}: {e}", md_path.display()))?;
        Ok(md_path)
    }

    /// Reads `<dir>/run.json`.
    pub fn read(dir: &Path) -> Result<Self, String> {
        let path = dir.join(MANIFEST);
        let text = std::fs::read_to_string(&path).map_err(|e| {
            format!(
                "{}: {e} (not the output directory of a `verify` run)",
                path.display()
            )
        })?;
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
    }
}

/// What `verify merge` joined.
#[derive(Debug, Clone, PartialEq)]
pub struct Merged {
    pub manifest: RunManifest,
    pub report: PathBuf,
}

/// Joins the output directories of the shards 1/N … N/N of one run into `out`: checks that they
/// are the shards of the same run (tier, N, selection, commit), each shard once and each case of
/// the selection in exactly one; copies every case's files (`<id>.json`, `<id>.timings.json`,
/// `<id>/`) and writes `report.md` and `run.json` over the whole selection.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<Merged, String> {
    if dirs.is_empty() {
        return Err("verify merge: no shard directory given".into());
    }
    let shards: Vec<RunManifest> = dirs
        .iter()
        .map(|d| RunManifest::read(d))
        .collect::<Result<_, _>>()?;
    let first = &shards[0];
    for (d, s) in dirs.iter().zip(&shards) {
        let differs = |what: &str, a: &str, b: &str| {
            format!(
                "{}: {what} is {b}, but {} has {a}: not shards of the same run",
                d.display(),
                dirs[0].display()
            )
        };
        if s.tier != first.tier {
            return Err(differs("the tier", &first.tier, &s.tier));
        }
        if s.shard_count != first.shard_count {
            return Err(differs(
                "the number of shards",
                &first.shard_count.to_string(),
                &s.shard_count.to_string(),
            ));
        }
        if s.selection != first.selection {
            return Err(differs(
                "the case selection",
                &format!("{} cases", first.selection.len()),
                &format!("{} other cases", s.selection.len()),
            ));
        }
        if s.metadata.git_commit != first.metadata.git_commit {
            return Err(differs(
                "the commit",
                &first.metadata.git_commit,
                &s.metadata.git_commit,
            ));
        }
    }
    let n = first.shard_count;
    let given: Vec<usize> = shards.iter().map(|s| s.shard_index).collect();
    let missing: Vec<String> = (1..=n)
        .filter(|i| !given.contains(i))
        .map(|i| format!("{i}/{n}"))
        .collect();
    if !missing.is_empty() || given.len() != n {
        return Err(format!(
            "verify merge: expected the {n} shards 1/{n} … {n}/{n} once each; given {}; missing {}",
            given
                .iter()
                .map(|i| format!("{i}/{n}"))
                .collect::<Vec<_>>()
                .join(", "),
            if missing.is_empty() {
                "none (a shard is given twice)".to_string()
            } else {
                missing.join(", ")
            }
        ));
    }
    let mut seen = BTreeSet::new();
    for s in &shards {
        for c in &s.cases {
            if !seen.insert(c.id.clone()) {
                return Err(format!("verify merge: case {} is in two shards", c.id));
            }
        }
    }
    let absent: Vec<&String> = first
        .selection
        .iter()
        .filter(|id| !seen.contains(*id))
        .collect();
    if !absent.is_empty() || seen.len() != first.selection.len() {
        return Err(format!(
            "verify merge: the shards do not hold the cases {absent:?} of the selection (a shard \
             that stopped early?), or hold cases outside it"
        ));
    }
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let mut cases = Vec::with_capacity(first.selection.len());
    for id in &first.selection {
        let (dir, case) = dirs
            .iter()
            .zip(&shards)
            .find_map(|(d, s)| s.cases.iter().find(|c| &c.id == id).map(|c| (d, c)))
            .ok_or_else(|| format!("verify merge: case {id} in no shard"))?;
        for name in [format!("{id}.json"), format!("{id}.timings.json")] {
            let from = dir.join(&name);
            std::fs::copy(&from, out.join(&name))
                .map_err(|e| format!("{}: {e}", from.display()))?;
        }
        let case_dir = dir.join(id);
        if case_dir.is_dir() {
            copy_dir(&case_dir, &out.join(id))?;
        }
        cases.push(case.clone());
    }
    let manifest = RunManifest {
        tier: first.tier.clone(),
        shard_index: 1,
        shard_count: n,
        selection: first.selection.clone(),
        cases,
        metadata: first.metadata.clone(),
        total_seconds: shards.iter().map(|s| s.total_seconds).sum(),
    };
    let report = manifest.write(out)?;
    Ok(Merged { manifest, report })
}

/// Copies the directory `from` (files and subdirectories) to `to`.
fn copy_dir(from: &Path, to: &Path) -> Result<(), String> {
    std::fs::create_dir_all(to).map_err(|e| format!("cannot create {}: {e}", to.display()))?;
    let entries = std::fs::read_dir(from).map_err(|e| format!("{}: {e}", from.display()))?;
    for entry in entries {
        let entry = entry.map_err(|e| format!("{}: {e}", from.display()))?;
        let path = entry.path();
        let target = to.join(entry.file_name());
        if path.is_dir() {
            copy_dir(&path, &target)?;
        } else {
            std::fs::copy(&path, &target).map_err(|e| format!("{}: {e}", path.display()))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    //! Merging: two shards of one run give the whole run's manifest and report; shards of
    //! different runs, a missing shard, or a case in two shards are refused by name.
    use super::*;

    fn metadata() -> Metadata {
        let mut m = Metadata::collect("quick");
        m.git_commit = "abc".into();
        m
    }

    fn case(id: &str) -> CaseMarkdown {
        CaseMarkdown {
            id: id.into(),
            passed: true,
            wall_seconds: 1.0,
            row: format!("| {id} |"),
            section: format!("\n## {id}\n"),
        }
    }

    fn shard(dir: &Path, index: usize, ids: &[&str]) -> PathBuf {
        let d = dir.join(format!("s{index}"));
        std::fs::create_dir_all(d.join(ids[0])).expect("tmp dir");
        for id in ids {
            std::fs::write(d.join(format!("{id}.json")), format!("{{\"id\":\"{id}\"}}"))
                .expect("write");
            std::fs::write(d.join(format!("{id}.timings.json")), "{}").expect("write");
        }
        std::fs::write(d.join(ids[0]).join("plot.svg"), "<svg/>").expect("write");
        RunManifest {
            tier: "quick".into(),
            shard_index: index,
            shard_count: 2,
            selection: vec!["a".into(), "b".into(), "c".into()],
            cases: ids.iter().map(|id| case(id)).collect(),
            metadata: metadata(),
            total_seconds: ids.len() as f64,
        }
        .write(&d)
        .expect("manifest");
        d
    }

    fn tmp(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("contactlab-merge-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn two_shards_join_into_the_selection_in_catalogue_order() {
        let d = tmp("ok");
        let s1 = shard(&d, 1, &["c", "a"]);
        let s2 = shard(&d, 2, &["b"]);
        let m = merge(&[s2, s1], &d.join("out")).expect("merge");
        let ids: Vec<&str> = m.manifest.cases.iter().map(|c| c.id.as_str()).collect();
        assert_eq!(ids, ["a", "b", "c"]);
        assert_eq!(m.manifest.total_seconds, 3.0);
        let md = std::fs::read_to_string(&m.report).expect("report");
        assert!(md.find("| a |") < md.find("| b |") && md.find("| b |") < md.find("| c |"));
        assert!(md.contains("2 shards"));
        assert!(d.join("out/c/plot.svg").is_file() && d.join("out/b.timings.json").is_file());
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_missing_shard_or_a_case_in_two_shards_is_refused() {
        let d = tmp("bad");
        let s1 = shard(&d, 1, &["a", "c"]);
        let e = merge(std::slice::from_ref(&s1), &d.join("out")).expect_err("2/2 missing");
        assert!(e.contains("missing 2/2"), "{e}");
        let s2 = shard(&d, 2, &["b", "c"]);
        let e = merge(&[s1.clone(), s2], &d.join("out")).expect_err("c twice");
        assert!(e.contains("case c is in two shards"), "{e}");
        let s2 = shard(&d, 2, &["b"]);
        let mut other = RunManifest::read(&s2).expect("read");
        other.metadata.git_commit = "def".into();
        other.write(&s2).expect("write");
        let e = merge(&[s1, s2], &d.join("out")).expect_err("another commit");
        assert!(e.contains("the commit"), "{e}");
        let _ = std::fs::remove_dir_all(&d);
    }
}
