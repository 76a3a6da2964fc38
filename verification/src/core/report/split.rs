//! A case report split in two: what every run of the same code reproduces bit for bit, and what
//! varies from run to run (timings, the run's metadata).
//!
//! `reports/<case>.json` holds the deterministic part; `reports/<case>.timings.json` the rest, as
//! a map from JSON pointers (into the full report) to values, with the run's metadata. The rule
//! that decides what varies, in order:
//!
//! - the `metadata` object (git commit, host, date, tier);
//! - a gate marked `"timing": true` (its checks compare measured times or ratios of them): the
//!   whole gate leaves the deterministic `gates` array;
//! - every key that names a time (`wall_seconds`, `cpu_seconds`, `seconds`, `ns_per_dof_step`,
//!   `cpu_per_point_us`, …);
//! - every table cell in a column listed in the table's `timing_columns`, or whose header gives
//!   a unit of time (`loop (s)`, `per step (ms)`, `µs/step`) or says `timing` (a ratio of
//!   times: `step / solve (timing ratio)`): the cell becomes `null`.
//!
//! `verify` checks this split by running cases twice in its tests: the deterministic parts must
//! be equal to the bit (`tests/determinism.rs`).

use serde_json::{Map, Value};

/// Keys whose values are timings.
pub fn is_timing_key(key: &str) -> bool {
    key == "seconds"
        || key.ends_with("_seconds")
        || key.starts_with("seconds_")
        || key.starts_with("ns_per_")
        || key.ends_with("_us")
        || key.ends_with("_ms")
        || key.ends_with("_ns")
}

/// Whether a table column header gives a unit of time.
pub fn is_timing_header(header: &str) -> bool {
    [
        "(s)", "(ms)", "µs", "s/step", "seconds", "(ms", "(s,", "timing",
    ]
    .iter()
    .any(|u| header.contains(u))
}

/// A report in two parts.
#[derive(Debug, Clone, PartialEq)]
pub struct Split {
    /// The report with every varying leaf taken out.
    pub deterministic: Value,
    /// `{"metadata": …, "leaves": {pointer: value}, "gates": [timing gates]}`.
    pub varying: Value,
}

/// Splits a serialized case report (any JSON value: other files split the same way).
///
/// A report with timing gates has a `passed` that depends on them: it moves to the varying part,
/// and the deterministic part says `passed_without_timings` (no failure, every other gate passed).
pub fn split(report: &Value) -> Split {
    let mut leaves = Map::new();
    let mut gates = Vec::new();
    let mut metadata = Value::Null;
    let mut deterministic = strip(report, "", &mut leaves, &mut gates, &mut metadata);
    if !gates.is_empty() {
        if let Value::Object(map) = &mut deterministic {
            if let Some(p) = map.remove("passed") {
                leaves.insert("/passed".into(), p);
                let kept_pass = map.get("gates").and_then(Value::as_array).is_some_and(|g| {
                    g.iter()
                        .all(|g| g.get("passed").and_then(Value::as_bool) == Some(true))
                });
                let no_failure = map.get("failure").is_none_or(Value::is_null);
                map.insert(
                    "passed_without_timings".into(),
                    Value::Bool(kept_pass && no_failure),
                );
            }
        }
    }
    let mut varying = Map::new();
    varying.insert("metadata".into(), metadata);
    varying.insert("gates".into(), Value::Array(gates));
    varying.insert("leaves".into(), Value::Object(leaves));
    Split {
        deterministic,
        varying: Value::Object(varying),
    }
}

fn is_table(map: &Map<String, Value>) -> bool {
    map.contains_key("header") && map.contains_key("rows")
}

fn is_timing_gate(v: &Value) -> bool {
    v.get("timing").and_then(Value::as_bool) == Some(true)
}

fn strip(
    v: &Value,
    path: &str,
    leaves: &mut Map<String, Value>,
    gates: &mut Vec<Value>,
    metadata: &mut Value,
) -> Value {
    match v {
        Value::Object(map) if is_table(map) => {
            let flagged: Vec<usize> = map
                .get("timing_columns")
                .and_then(Value::as_array)
                .map(|a| {
                    a.iter()
                        .filter_map(|x| x.as_u64().map(|c| c as usize))
                        .collect()
                })
                .unwrap_or_default();
            let timing: Vec<bool> = map["header"]
                .as_array()
                .map(|h| {
                    h.iter()
                        .enumerate()
                        .map(|(c, x)| {
                            flagged.contains(&c) || x.as_str().is_some_and(is_timing_header)
                        })
                        .collect()
                })
                .unwrap_or_default();
            let mut out = Map::new();
            for (k, x) in map {
                if k != "rows" {
                    out.insert(
                        k.clone(),
                        strip(x, &format!("{path}/{k}"), leaves, gates, metadata),
                    );
                    continue;
                }
                let rows = x
                    .as_array()
                    .into_iter()
                    .flatten()
                    .enumerate()
                    .map(|(r, row)| {
                        let cells = row
                            .as_array()
                            .into_iter()
                            .flatten()
                            .enumerate()
                            .map(|(c, cell)| {
                                if timing.get(c).copied().unwrap_or(false) {
                                    leaves.insert(format!("{path}/rows/{r}/{c}"), cell.clone());
                                    Value::Null
                                } else {
                                    cell.clone()
                                }
                            })
                            .collect();
                        Value::Array(cells)
                    })
                    .collect();
                out.insert(k.clone(), Value::Array(rows));
            }
            Value::Object(out)
        }
        Value::Object(map) => {
            let mut out = Map::new();
            for (k, x) in map {
                let at = format!("{path}/{k}");
                if path.is_empty() && k == "metadata" {
                    *metadata = x.clone();
                } else if is_timing_key(k) {
                    leaves.insert(at, x.clone());
                } else if path.is_empty() && k == "gates" {
                    let kept = x
                        .as_array()
                        .into_iter()
                        .flatten()
                        .enumerate()
                        .filter_map(|(i, g)| {
                            if is_timing_gate(g) {
                                gates.push(g.clone());
                                None
                            } else {
                                Some(strip(g, &format!("{at}/{i}"), leaves, gates, metadata))
                            }
                        })
                        .collect();
                    out.insert(k.clone(), Value::Array(kept));
                } else {
                    out.insert(k.clone(), strip(x, &at, leaves, gates, metadata));
                }
            }
            Value::Object(out)
        }
        Value::Array(items) => Value::Array(
            items
                .iter()
                .enumerate()
                .map(|(i, x)| strip(x, &format!("{path}/{i}"), leaves, gates, metadata))
                .collect(),
        ),
        other => other.clone(),
    }
}

#[cfg(test)]
mod tests {
    //! The split: metadata, timing keys, timing gates and timing columns (flagged or by header)
    //! leave the deterministic part and are kept, by pointer, in the varying part.
    use super::*;
    use serde_json::json;

    #[test]
    fn timings_metadata_and_timing_gates_leave_the_deterministic_part() {
        let r = json!({
            "id": "c",
            "passed": false,
            "failure": null,
            "wall_seconds": 3.5,
            "metadata": {"git": "abc"},
            "gates": [
                {"name": "rate", "checks": [{"observed": 1.0}]},
                {"name": "budget", "timing": true, "checks": [{"observed": 0.2}]}
            ],
            "sweeps": [{"levels": [{"h": 0.5, "cpu_seconds": 0.1, "cpu_per_point_us": 7.0}]}],
            "tables": [{"title": "t", "header": ["M", "loop (s)", "step/solve"],
                        "timing_columns": [2],
                        "rows": [["10", "0.3", "2.1"]]}]
        });
        let s = split(&r);
        let d = &s.deterministic;
        assert_eq!(d["id"], "c");
        assert!(d.get("wall_seconds").is_none());
        assert!(d.get("metadata").is_none());
        assert_eq!(d["gates"].as_array().map(Vec::len), Some(1));
        assert!(
            d.get("passed").is_none(),
            "the verdict depends on a timing gate"
        );
        assert_eq!(
            d["passed_without_timings"], false,
            "the kept gate has no verdict"
        );
        assert_eq!(d["sweeps"][0]["levels"][0], json!({"h": 0.5}));
        assert_eq!(d["tables"][0]["rows"][0], json!(["10", null, null]));
        let v = &s.varying;
        assert_eq!(v["metadata"]["git"], "abc");
        assert_eq!(v["gates"][0]["name"], "budget");
        assert_eq!(v["leaves"]["/wall_seconds"], 3.5);
        assert_eq!(v["leaves"]["/sweeps/0/levels/0/cpu_seconds"], 0.1);
        assert_eq!(v["leaves"]["/tables/0/rows/0/1"], "0.3");
        assert_eq!(v["leaves"]["/tables/0/rows/0/2"], "2.1");
    }

    #[test]
    fn a_report_without_timings_is_unchanged() {
        let r = json!({"id": "c", "gates": [{"name": "g", "checks": []}], "tables": []});
        assert_eq!(split(&r).deterministic, r);
    }
}
