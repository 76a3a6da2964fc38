//! `verify compare BEFORE AFTER [--noise BEFORE2]`: are two report directories the same numbers?
//!
//! Every JSON file under BEFORE (`<case>.json`, `<case>/data.json`) is compared leaf by leaf with
//! the same file under AFTER. Numbers must be bit-identical; a file, a leaf or an array entry
//! present on one side only is a structural difference. Left out of the comparison, and counted:
//!
//! - timings, which no two runs share: the `metadata` object, every key that names a time
//!   (`wall_seconds`, `cpu_seconds`, `seconds`, `solver_seconds`, `ns_per_dof_step`, …), and every
//!   table column whose header gives a unit of time (`loop (s)`, `per step (ms)`, `µs/step`);
//! - with `--noise BEFORE2` (further runs of the same code; repeatable), every leaf that differs
//!   between BEFORE and one of them — the timings written into check values and derived columns.
//!
//! Strings are compared too — tables hold their numbers as formatted text — and must be equal,
//! except the prose of a case (`explanation`, `note`, and the case `kind`, a label): a reworded
//! explanation or a renamed kind is listed for review and does not fail the comparison.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::Value;

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

/// Keys whose values are timings.
fn is_timing_key(key: &str) -> bool {
    key == "metadata"
        || key == "seconds"
        || key.ends_with("_seconds")
        || key.starts_with("seconds_")
        || key.starts_with("ns_per_")
}

/// Whether a leaf is prose (its path ends in a prose key).
fn is_prose(path: &str) -> bool {
    ["/explanation", "/note", "/kind"]
        .iter()
        .any(|k| path.ends_with(k))
}

/// Whether a table column header gives a unit of time.
fn is_timing_header(header: &str) -> bool {
    ["(s)", "(ms)", "µs", "s/step", "seconds", "(ms", "(s,"]
        .iter()
        .any(|u| header.contains(u))
}

/// The leaves of a JSON value by path (`/gates[3]/checks[0]/observed`), timing keys and timing
/// table columns left out (and counted).
fn leaves(v: &Value, path: &str, out: &mut BTreeMap<String, Value>, timing: &mut usize) {
    match v {
        Value::Object(map) if map.contains_key("header") && map.contains_key("rows") => {
            let timing_columns: Vec<bool> = map["header"]
                .as_array()
                .map(|h| {
                    h.iter()
                        .map(|c| c.as_str().is_some_and(is_timing_header))
                        .collect()
                })
                .unwrap_or_default();
            for (k, x) in map {
                if k != "rows" {
                    leaves(x, &format!("{path}/{k}"), out, timing);
                    continue;
                }
                for (r, row) in x.as_array().into_iter().flatten().enumerate() {
                    for (c, cell) in row.as_array().into_iter().flatten().enumerate() {
                        if timing_columns.get(c).copied().unwrap_or(false) {
                            *timing += 1;
                        } else {
                            leaves(cell, &format!("{path}/rows[{r}][{c}]"), out, timing);
                        }
                    }
                }
            }
        }
        Value::Object(map) => {
            for (k, x) in map {
                if is_timing_key(k) {
                    *timing += count_leaves(x);
                } else {
                    leaves(x, &format!("{path}/{k}"), out, timing);
                }
            }
        }
        Value::Array(items) => {
            if items.is_empty() {
                out.insert(format!("{path}[]"), Value::Null);
            }
            for (i, x) in items.iter().enumerate() {
                leaves(x, &format!("{path}[{i}]"), out, timing);
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
            } else if p.extension().is_some_and(|x| x == "json") {
                if let Ok(rel) = p.strip_prefix(dir) {
                    out.push(rel.to_path_buf());
                }
            }
        }
    }
    out.sort();
    Ok(out)
}

fn read_leaves(path: &Path, timing: &mut usize) -> Result<BTreeMap<String, Value>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let v: Value = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut out = BTreeMap::new();
    leaves(&v, "", &mut out, timing);
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
    }
    Ok(c)
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
}
