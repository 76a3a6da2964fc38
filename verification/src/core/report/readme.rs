//! `verify readme`: the numbers of README.md, generated from the committed reports.
//!
//! README.md holds blocks between `<!-- generated: NAME -->` and `<!-- end generated -->`; this
//! module renders each block from `reports/` (the deterministic `<case>.json` files, and
//! `benchmarks.json` of `verify benches`) and writes them in place. `verify readme --check`
//! fails when a block differs from what the reports give, and a test of the verification crate
//! does the same, so a number in the README cannot drift from the reports.
//!
//! Blocks: `evidence` (per case: verdict, gates, the fitted rates grouped by expected rate),
//! `benchmarks` (criterion's means against the budgets, and the ratio budgets), `tiers` (each
//! tier's cases and their recorded time), `multibody_conservation` (the conservation table of
//! `multibody_impact`), the planner's tables (`rod_plan`, `plane_plan`, `plane_plan_self`,
//! `dynamic_plan_self`) and `plan_example` (the README's `verify plan` command's output).

use std::collections::BTreeMap;
use std::path::Path;

use serde_json::Value;

use crate::core::report::benchmarks::human;

/// A rendered block by name.
pub type Blocks = BTreeMap<String, String>;

fn read(path: &Path) -> Result<Value, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The `<case>.json` files of a reports directory, sorted by case id.
fn case_reports(dir: &Path) -> Result<Vec<Value>, String> {
    let mut paths: Vec<_> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.ends_with(".json")
                && !name.ends_with(".timings.json")
                && name != "benchmarks.json"
                && name != crate::core::report::manifest::MANIFEST
        })
        .collect();
    paths.sort();
    paths.iter().map(|p| read(p)).collect()
}

/// The fitted rates of a case's rate gates, grouped by expected rate:
/// `2 (×4): 1.991 – 2.004`.
fn rates(report: &Value) -> String {
    let mut by_expected: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for g in report["gates"].as_array().into_iter().flatten() {
        let (Some(fit), Some(check)) = (g.get("rate_fit"), g["checks"].get(0)) else {
            continue;
        };
        let Some(rate) = fit["rate"].as_f64() else {
            continue;
        };
        // the first check is "fitted rate … in [low, high]": the expected rate is the midpoint
        let limit = check["limit"].as_str().unwrap_or("");
        let expected = limit
            .trim_start_matches("in [")
            .trim_end_matches(']')
            .split(", ")
            .filter_map(|x| x.parse::<f64>().ok())
            .collect::<Vec<_>>();
        if expected.len() != 2 {
            continue;
        }
        let e = 0.5 * (expected[0] + expected[1]);
        by_expected
            .entry(
                format!("{:.4}", e)
                    .trim_end_matches('0')
                    .trim_end_matches('.')
                    .to_string(),
            )
            .or_default()
            .push(rate);
    }
    by_expected
        .iter()
        .map(|(e, r)| {
            let lo = r.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = r.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            if r.len() == 1 {
                format!("{e}: {lo:.3}")
            } else {
                format!("{e} (×{}): {lo:.3} – {hi:.3}", r.len())
            }
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The `evidence` block: one row per case — its title (what it establishes), tier, verdict, the
/// gates passed and the fitted rates grouped by expected rate.
pub fn evidence(reports: &Path) -> Result<String, String> {
    let mut s = String::from(
        "| case | what it establishes | tier | verdict | gates passed | fitted rates, by expected rate |\n|---|---|---|---|---|---|\n",
    );
    for r in case_reports(reports)? {
        let gates = r["gates"].as_array().cloned().unwrap_or_default();
        let passed = gates
            .iter()
            .filter(|g| g["passed"].as_bool() == Some(true))
            .count();
        let verdict = match (r.get("passed"), r.get("passed_without_timings")) {
            (Some(Value::Bool(true)), _) => "pass",
            (_, Some(Value::Bool(true))) => "pass (timings apart)",
            _ => "**FAIL**",
        };
        s.push_str(&format!(
            "| `{}` | {} | {} | {} | {}/{} | {} |\n",
            r["id"].as_str().unwrap_or("?"),
            r["title"].as_str().unwrap_or("").replace('|', "\\|"),
            r["tier"].as_str().unwrap_or("?"),
            verdict,
            passed,
            gates.len(),
            rates(&r)
        ));
    }
    Ok(s)
}

/// The `tiers` block: per tier of `verify` (they nest: quick ⊂ default ⊂ full) its cases and the
/// sum of their run times in the committed full run (`<case>.timings.json`, the 2-core reference
/// machine), beside the tier's budget.
pub fn tiers(reports: &Path) -> Result<String, String> {
    let mut s = String::from(
        "| command | cases | their recorded time | budget | what for |\n|---|---|---|---|---|\n",
    );
    let cases = case_reports(reports)?;
    let rank = |t: &str| match t {
        "quick" => 0,
        "default" => 1,
        _ => 2,
    };
    for (tier, command, budget, purpose) in [
        (0, "`verify --quick`", "20 s", "CI; a check while you work"),
        (
            1,
            "`verify`",
            "90 s",
            "what to run first: every model family and every kind of claim (rates, identities, \
             extremes, exact and pinned values, audits, performance)",
        ),
        (
            2,
            "`verify --full`",
            "none",
            "the long studies too (finest levels, the 10⁴-scene fuzz campaign, the large \
             work–precision and performance runs): the committed `reports/`",
        ),
    ] {
        let mut n = 0;
        let mut seconds = 0.0;
        for r in &cases {
            if rank(r["tier"].as_str().unwrap_or("full")) > tier {
                continue;
            }
            n += 1;
            let id = r["id"].as_str().unwrap_or("?");
            let t = read(&reports.join(format!("{id}.timings.json")))?;
            seconds += t
                .pointer("/leaves/~1wall_seconds")
                .and_then(Value::as_f64)
                .ok_or_else(|| format!("{id}.timings.json: no /wall_seconds"))?;
        }
        s.push_str(&format!(
            "| {command} | {n} | {seconds:.1} s | {budget} | {purpose} |\n"
        ));
    }
    Ok(s)
}

/// The `benchmarks` block, from `reports/benchmarks.json`.
pub fn benchmarks(reports: &Path) -> Result<String, String> {
    let b = read(&reports.join("benchmarks.json"))?;
    let mut s = String::from("| benchmark | criterion mean | budget |\n|---|---|---|\n");
    for m in b["measurements"].as_array().into_iter().flatten() {
        let mean = m["mean_seconds"].as_f64().unwrap_or(f64::NAN);
        let budget = m["budget_seconds"]
            .as_f64()
            .map(|b| {
                let within = m["within_budget"].as_bool() == Some(true);
                format!(
                    "{} ({})",
                    human(b),
                    if within { "within" } else { "**over**" }
                )
            })
            .unwrap_or_default();
        s.push_str(&format!(
            "| `{}` | {} | {} |\n",
            m["bench"].as_str().unwrap_or("?"),
            human(mean),
            budget
        ));
    }
    let ratios = b["ratios"].as_array().into_iter().flatten();
    let mut first = true;
    for r in ratios {
        if first {
            s.push_str(
                "\n| ratio of means | value (range from the 95% intervals) | at most |\n|---|---|---|\n",
            );
            first = false;
        }
        let f = |k: &str| r[k].as_f64().unwrap_or(f64::NAN);
        s.push_str(&format!(
            "| `{}` / `{}` | {:.3} ({:.3} – {:.3}) | {} ({}) |\n",
            r["numerator"].as_str().unwrap_or("?"),
            r["denominator"].as_str().unwrap_or("?"),
            f("ratio"),
            f("ratio_low"),
            f("ratio_high"),
            f("max"),
            if r["within_budget"].as_bool() == Some(true) {
                "within"
            } else {
                "**over**"
            }
        ));
    }
    Ok(s)
}

/// The table of `case`'s report whose title starts with `title`, as Markdown, with the columns
/// `columns` (by header) in that order.
pub fn case_table(
    reports: &Path,
    case: &str,
    title: &str,
    columns: &[&str],
) -> Result<String, String> {
    let path = reports.join(format!("{case}.json"));
    let r = read(&path)?;
    let table = r["tables"]
        .as_array()
        .into_iter()
        .flatten()
        .find(|t| t["title"].as_str().is_some_and(|s| s.starts_with(title)))
        .ok_or_else(|| format!("{}: no table titled `{title}…`", path.display()))?;
    let header: Vec<&str> = table["header"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|h| h.as_str().unwrap_or(""))
        .collect();
    let index: Vec<usize> = columns
        .iter()
        .map(|c| {
            header
                .iter()
                .position(|h| h == c)
                .ok_or_else(|| format!("{}: table `{title}…` has no column `{c}`", path.display()))
        })
        .collect::<Result<_, _>>()?;
    let mut s = format!(
        "| {} |\n|{}\n",
        columns.join(" | "),
        "---|".repeat(columns.len())
    );
    for row in table["rows"].as_array().into_iter().flatten() {
        let cells: Vec<String> = index
            .iter()
            .map(|&i| match &row[i] {
                Value::String(t) => t.clone(),
                Value::Null => "—".into(),
                v => v.to_string(),
            })
            .collect();
        s.push_str(&format!("| {} |\n", cells.join(" | ")));
    }
    Ok(s)
}

/// The `plan_example` block: the models table and the decision of `reports/plan_example/plan.md`
/// (what the README's `verify plan` command writes; a test runs the command and compares).
pub fn plan_example(reports: &Path) -> Result<String, String> {
    let path = reports.join("plan_example/plan.md");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let start = text
        .find("| scheme |")
        .ok_or_else(|| format!("{}: no models table", path.display()))?;
    Ok(text[start..]
        .replace("## Decision\n\n", "Decision: ")
        .trim_end()
        .to_string()
        + "\n")
}

/// Every block.
pub fn render(reports: &Path) -> Result<Blocks, String> {
    let mut b = Blocks::new();
    b.insert("evidence".into(), evidence(reports)?);
    b.insert("benchmarks".into(), benchmarks(reports)?);
    b.insert("tiers".into(), tiers(reports)?);
    b.insert(
        "rod_plan".into(),
        case_table(
            reports,
            "rod_plan",
            "The planner on",
            &crate::core::plan::PLAN_TABLE_COLUMNS,
        )?,
    );
    let mut plane_columns: Vec<&str> = crate::core::plan::PLAN_TABLE_COLUMNS[..9].to_vec();
    plane_columns.push("work n²·N");
    b.insert(
        "plane_plan".into(),
        case_table(reports, "plane_plan", "The planner on", &plane_columns)?,
    );
    b.insert(
        "plane_plan_self".into(),
        case_table(
            reports,
            "plane_plan_self",
            "The planner by self-convergence",
            &[
                "target",
                "scheme",
                "M",
                "N",
                "predicted error",
                "estimated error (pilots' F*)",
                "achieved error vs F(4M, 4N)",
                "band U",
                "observed order",
                "achieved / target",
            ],
        )?,
    );
    b.insert(
        "dynamic_plan_self".into(),
        case_table(
            reports,
            "dynamic_plan_self",
            "The planner by self-convergence",
            &[
                "target",
                "answer",
                "pilot rounds",
                "scheme",
                "M",
                "N",
                "predicted error",
                "estimated error (pilots' F*)",
                "achieved error vs F(4M, 4N)",
                "band U",
                "achieved / target",
            ],
        )?,
    );
    b.insert("plan_example".into(), plan_example(reports)?);
    b.insert(
        "multibody_conservation".into(),
        case_table(
            reports,
            "multibody_impact",
            "Runs at resolution 1",
            &[
                "run",
                "μ",
                "energy change / E_0",
                "activation work / E_0",
                "switch work / E_0",
                "identity ratio",
                "unchanged ratio",
                "P ratio",
                "J ratio",
                "friction work / E_0",
                "rebound ring 0",
                "contact duration",
            ],
        )?,
    );
    Ok(b)
}

/// `text` with every generated block replaced by its rendering; an error names a block of the
/// text that has no rendering, or a block without its end marker.
pub fn fill(text: &str, blocks: &Blocks) -> Result<String, String> {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find("<!-- generated: ") {
        let after = &rest[i + "<!-- generated: ".len()..];
        let name_end = after
            .find(" -->")
            .ok_or("an unterminated <!-- generated: marker")?;
        let name = &after[..name_end];
        let body_start = i + "<!-- generated: ".len() + name_end + " -->".len();
        let end = rest[body_start..]
            .find("<!-- end generated -->")
            .ok_or_else(|| format!("block `{name}` has no <!-- end generated -->"))?;
        let block = blocks
            .get(name)
            .ok_or_else(|| format!("no generator for the block `{name}`"))?;
        out.push_str(&rest[..body_start]);
        out.push('\n');
        out.push_str(block);
        rest = &rest[body_start + end..];
    }
    out.push_str(rest);
    Ok(out)
}

#[cfg(test)]
mod tests {
    //! Blocks are replaced between their markers and nowhere else; unknown and unterminated
    //! blocks are errors; rates are grouped by expected rate.
    use super::*;
    use serde_json::json;

    #[test]
    fn blocks_are_filled_between_their_markers() {
        let mut b = Blocks::new();
        b.insert("x".into(), "NEW\n".into());
        let text = "a\n<!-- generated: x -->\nOLD\n<!-- end generated -->\nb\n";
        assert_eq!(
            fill(text, &b).unwrap(),
            "a\n<!-- generated: x -->\nNEW\n<!-- end generated -->\nb\n"
        );
        assert!(fill("<!-- generated: y -->\n<!-- end generated -->", &b).is_err());
        assert!(fill("<!-- generated: x -->\nno end", &b).is_err());
    }

    #[test]
    fn rates_are_grouped_by_expected_rate() {
        let gate = |rate: f64, low: f64, high: f64| json!({"rate_fit": {"rate": rate}, "checks": [{"limit": format!("in [{low}, {high}]")}]});
        let r =
            json!({"gates": [gate(1.01, 0.95, 1.05), gate(0.99, 0.95, 1.05), gate(2.0, 1.9, 2.1)]});
        assert_eq!(rates(&r), "1 (×2): 0.990 – 1.010; 2: 2.000");
    }
}
