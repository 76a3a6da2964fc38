//! `verify compare BEFORE AFTER [--noise BEFORE2]`: are two report directories the same numbers?
//!
//! Every JSON file under BEFORE (`<case>.json`, `<case>/data.json`; not the `*.timings.json`) is
//! compared leaf by leaf with the same file under AFTER, after the split of
//! [`crate::core::report::split`]: only the deterministic part is compared. Numbers must be
//! bit-identical; a file, a leaf or an array entry present on one side only is a structural
//! difference. Left out, and counted: the varying leaves (timings, timing gates, metadata), and
//! with `--noise BEFORE2` (further runs of the same code; repeatable) every leaf that differs
//! between BEFORE and one of them (there should be none: a noise leaf is a timing the split does
//! not know).
//!
//! Strings are compared too — tables hold their numbers as formatted text — and must be equal,
//! except the prose of a case (`explanation`, `note`, and the case `kind`, a label): a reworded
//! explanation or a renamed kind is listed for review and does not fail the comparison.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::core::report::manifest::MANIFEST;
use crate::core::report::split::split;

/// Where two report trees differ.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Comparison {
    /// JSON files compared.
    pub files: usize,
    /// Numeric leaves compared and equal / different.
    pub numbers_equal: usize,
    pub numbers_changed: Vec<Change>,
    /// String and boolean leaves compared and equal / different (prose apart).
    pub text_equal: usize,
    pub text_changed: Vec<Change>,
    /// Prose leaves (`explanation`, `note`, `kind`) that differ.
    pub prose_changed: Vec<Change>,
    /// Files or leaves on one side only.
    pub structure: Vec<String>,
    /// Leaves left out as timings (by key) and as noise (differing between the two baselines).
    pub timing_leaves: usize,
    pub noise_leaves: usize,
}

/// One differing leaf.
#[derive(Debug, Clone, PartialEq)]
pub struct Change {
    /// `file: /path/to/leaf`.
    pub at: String,
    pub before: String,
    pub after: String,
}

impl Comparison {
    /// No number, no text outside the prose and no structure changed.
    pub fn same(&self) -> bool {
        self.numbers_changed.is_empty() && self.text_changed.is_empty() && self.structure.is_empty()
    }

    /// A readable summary, every difference listed.
    pub fn render(&self) -> String {
        let mut s = format!(
            "{} JSON files; numbers: {} equal, {} changed; text: {} equal, {} changed; \
             prose: {} changed; structure: {} differences; left out: {} timing leaves, \
             {} noise leaves\n",
            self.files,
            self.numbers_equal,
            self.numbers_changed.len(),
            self.text_equal,
            self.text_changed.len(),
            self.prose_changed.len(),
            self.structure.len(),
            self.timing_leaves,
            self.noise_leaves
        );
        for c in &self.numbers_changed {
            s.push_str(&format!("number {}: {} -> {}\n", c.at, c.before, c.after));
        }
        for d in &self.structure {
            s.push_str(&format!("structure {d}\n"));
        }
        for c in &self.text_changed {
            s.push_str(&format!("text {}: {:?} -> {:?}\n", c.at, c.before, c.after));
        }
        for c in &self.prose_changed {
            s.push_str(&format!(
                "prose {}: {:?} -> {:?}\n",
                c.at, c.before, c.after
            ));
        }
        s
    }
}

/// Whether a leaf is prose (its path ends in a prose key).
fn is_prose(path: &str) -> bool {
    ["/explanation", "/note", "/kind"]
        .iter()
        .any(|k| path.ends_with(k))
}

/// The leaves of a JSON value by path (`/gates[3]/checks[0]/observed`).
fn leaves(v: &Value, path: &str, out: &mut BTreeMap<String, Value>) {
    match v {
        Value::Object(map) => {
            for (k, x) in map {
                leaves(x, &format!("{path}/{k}"), out);
            }
        }
        Value::Array(items) => {
            if items.is_empty() {
                out.insert(format!("{path}[]"), Value::Null);
            }
            for (i, x) in items.iter().enumerate() {
                leaves(x, &format!("{path}[{i}]"), out);
            }
        }
        other => {
            out.insert(path.to_string(), other.clone());
        }
    }
}

fn count_leaves(v: &Value) -> usize {
    match v {
        Value::Object(m) => m.values().map(count_leaves).sum(),
        Value::Array(a) => a.iter().map(count_leaves).sum(),
        _ => 1,
    }
}

/// Every `*.json` below `dir`, as paths relative to it, sorted.
fn json_files(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let entries = std::fs::read_dir(&d).map_err(|e| format!("{}: {e}", d.display()))?;
        for e in entries {
            let p = e.map_err(|e| format!("{}: {e}", d.display()))?.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "json")
                && !p.to_string_lossy().ends_with(".timings.json")
                // the run's manifest: its rows and sections carry times and the shard count;
                // its numbers are the case files'
                && !(d == dir && p.file_name().is_some_and(|n| n == MANIFEST))
            {
                if let Ok(rel) = p.strip_prefix(dir) {
                    out.push(rel.to_path_buf());
                }
            }
        }
    }
    out.sort();
    Ok(out)
}

/// The deterministic leaves of a JSON file ([`split`]: a report written before the split is
/// split the same way); `timing` counts the varying leaves left out.
fn read_leaves(path: &Path, timing: &mut usize) -> Result<BTreeMap<String, Value>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let v: Value = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let parts = split(&v);
    *timing += count_leaves(&parts.varying["leaves"]) + count_leaves(&parts.varying["gates"]);
    let mut out = BTreeMap::new();
    leaves(&parts.deterministic, "", &mut out);
    Ok(out)
}

fn show(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Compares the report trees `before` and `after`; `noise` are further runs of `before`'s code.
pub fn compare(before: &Path, after: &Path, noise: &[PathBuf]) -> Result<Comparison, String> {
    let mut c = Comparison::default();
    let files_before = json_files(before)?;
    let files_after = json_files(after)?;
    for f in &files_after {
        if !files_before.contains(f) {
            c.structure
                .push(format!("{}: only in {}", f.display(), after.display()));
        }
    }
    for f in &files_before {
        if !files_after.contains(f) {
            c.structure
                .push(format!("{}: only in {}", f.display(), before.display()));
            continue;
        }
        compare_file(&mut c, before, after, f, noise)?;
    }
    Ok(c)
}

/// `verify --check REFERENCE`: compares the case reports `<id>.json` of a fresh run (in `fresh`)
/// with the committed ones in `reference`, for the cases of the run only.
pub fn check(reference: &Path, fresh: &Path, ids: &[String]) -> Result<Comparison, String> {
    let mut c = Comparison::default();
    for id in ids {
        let f = PathBuf::from(format!("{id}.json"));
        if !reference.join(&f).exists() {
            c.structure.push(format!(
                "{}: not in {} (a new case: commit its report)",
                f.display(),
                reference.display()
            ));
            continue;
        }
        compare_file(&mut c, reference, fresh, &f, &[])?;
    }
    Ok(c)
}

/// Compares one file `f` of two trees into `c`.
fn compare_file(
    c: &mut Comparison,
    before: &Path,
    after: &Path,
    f: &Path,
    noise: &[PathBuf],
) -> Result<(), String> {
    c.files += 1;
    let mut timing = 0;
    let a = read_leaves(&before.join(f), &mut timing)?;
    let b = read_leaves(&after.join(f), &mut 0)?;
    c.timing_leaves += timing;
    let mut runs = Vec::new();
    for dir in noise.iter().filter(|d| d.join(f).exists()) {
        runs.push(read_leaves(&dir.join(f), &mut 0)?);
    }
    for (k, va) in &a {
        let at = format!("{}: {k}", f.display());
        if runs.iter().any(|n| n.get(k) != Some(va)) {
            c.noise_leaves += 1;
            continue;
        }
        let Some(vb) = b.get(k) else {
            c.structure
                .push(format!("{at}: only in {}", before.display()));
            continue;
        };
        let numeric = va.is_number() || vb.is_number();
        let equal = match (va, vb) {
            (Value::Number(x), Value::Number(y)) => match (x.as_f64(), y.as_f64()) {
                (Some(x), Some(y)) => x.to_bits() == y.to_bits(),
                _ => x == y,
            },
            _ => va == vb,
        };
        match (equal, numeric) {
            (true, true) => c.numbers_equal += 1,
            (true, false) => c.text_equal += 1,
            (false, true) => c.numbers_changed.push(Change {
                at,
                before: show(va),
                after: show(vb),
            }),
            (false, false) => {
                let change = Change {
                    at,
                    before: show(va),
                    after: show(vb),
                };
                if is_prose(k) {
                    c.prose_changed.push(change);
                } else {
                    c.text_changed.push(change);
                }
            }
        }
    }
    for k in b.keys().filter(|k| !a.contains_key(*k)) {
        c.structure
            .push(format!("{}: {k}: only in {}", f.display(), after.display()));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    //! Equal trees compare equal; a changed number, a missing leaf and a changed string are each
    //! found; timings and noise are left out.
    use super::*;

    fn tree(name: &str, files: &[(&str, &str)]) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("contactlab-compare-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        for (f, text) in files {
            let p = dir.join(f);
            std::fs::create_dir_all(p.parent().expect("parent")).expect("dir");
            std::fs::write(p, text).expect("write");
        }
        dir
    }

    #[test]
    fn changes_are_found_and_timings_left_out() {
        let a = tree(
            "a",
            &[
                (
                    "c.json",
                    r#"{"x": 1.5, "wall_seconds": 2.0, "kind": "k", "t": [["0.1", "3"]],
                   "tab": {"header": ["n", "loop (s)"], "rows": [["4", "0.25"]]}}"#,
                ),
                ("c/data.json", r#"{"y": [1, 2]}"#),
            ],
        );
        let same = tree(
            "same",
            &[
                (
                    "c.json",
                    r#"{"x": 1.5, "wall_seconds": 9.0, "kind": "k", "t": [["0.1", "3"]],
                   "tab": {"header": ["n", "loop (s)"], "rows": [["4", "0.75"]]}}"#,
                ),
                ("c/data.json", r#"{"y": [1, 2]}"#),
            ],
        );
        let r = compare(&a, &same, &[]).expect("compares");
        assert!(r.same() && r.prose_changed.is_empty(), "{}", r.render());
        assert_eq!(r.timing_leaves, 2);

        let changed = tree(
            "changed",
            &[
                (
                    "c.json",
                    r#"{"x": 1.5000000000000002, "kind": "k2", "t": [["0.2", "3"]],
                        "tab": {"header": ["n", "loop (s)"], "rows": [["4", "0.5"]]}}"#,
                ),
                ("c/data.json", r#"{"y": [1]}"#),
            ],
        );
        let r = compare(&a, &changed, &[]).expect("compares");
        assert_eq!(r.numbers_changed.len(), 1, "{}", r.render());
        assert_eq!(r.text_changed.len(), 1, "{}", r.render());
        assert_eq!(r.prose_changed.len(), 1, "{}", r.render());
        assert_eq!(r.structure.len(), 1, "{}", r.render());
        assert!(!r.same());

        // With a second baseline in which the table cell differs, that cell is noise.
        let noise = tree(
            "noise",
            &[
                (
                    "c.json",
                    r#"{"x": 1.5, "kind": "k", "t": [["0.3", "3"]],
                   "tab": {"header": ["n", "loop (s)"], "rows": [["4", "0.1"]]}}"#,
                ),
                ("c/data.json", r#"{"y": [1, 2]}"#),
            ],
        );
        let r = compare(&a, &changed, std::slice::from_ref(&noise)).expect("compares");
        assert_eq!(r.noise_leaves, 1);
        assert!(r.text_changed.is_empty(), "{}", r.render());
        for d in [a, same, changed, noise] {
            let _ = std::fs::remove_dir_all(d);
        }
    }

    #[test]
    fn check_compares_the_cases_of_the_run_only_and_flags_a_new_case() {
        let reference = tree(
            "ref",
            &[
                ("a.json", r#"{"x": 1.0}"#),
                ("b.json", r#"{"x": 2.0}"#),
                ("a.timings.json", r#"{"leaves": {"/wall_seconds": 1.0}}"#),
            ],
        );
        let fresh = tree("fresh", &[("a.json", r#"{"x": 1.0}"#)]);
        let r = check(&reference, &fresh, &["a".to_string()]).expect("checks");
        assert!(r.same(), "{}", r.render());
        assert_eq!(r.files, 1);
        let r = check(&reference, &fresh, &["a".into(), "c".into()]).expect("checks");
        assert!(
            !r.same(),
            "a case without a committed report fails the check"
        );
        let drifted = tree("drift", &[("a.json", r#"{"x": 1.0000000000000002}"#)]);
        assert!(!check(&reference, &drifted, &["a".into()])
            .expect("checks")
            .same());
        for d in [reference, fresh, drifted] {
            let _ = std::fs::remove_dir_all(d);
        }
    }
}
