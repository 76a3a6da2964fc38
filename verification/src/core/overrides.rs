//! The one way a case varies a scene: dotted-key overrides of its TOML table, applied before the
//! scene is validated by the solver crate (so an override is checked exactly like a user's value).
//!
//! A key is a path of table names separated by dots, `foundation.p0` or `time.steps`; a segment
//! `name[i]` selects entry i of an array of tables and `name[*]` every entry
//! (`"dirichlet[*].support" = "rollers"`). Missing tables on the way are created.

use crate::core::format::CaseError;

/// Why an override cannot be applied.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("override `{key}`: {message}")]
pub struct OverrideError {
    pub key: String,
    pub message: String,
}

impl OverrideError {
    /// The same error as a case-file error of the case at `path`.
    pub fn in_case(self, path: &std::path::Path) -> CaseError {
        CaseError::Read {
            path: path.display().to_string(),
            message: self.to_string(),
        }
    }
}

/// One segment of a dotted key.
enum Segment<'a> {
    Key(&'a str),
    Entry(&'a str, usize),
    Every(&'a str),
}

fn segment(s: &str) -> Result<Segment<'_>, String> {
    match s.find('[') {
        None => Ok(Segment::Key(s)),
        Some(open) => {
            let name = &s[..open];
            let index = s[open + 1..]
                .strip_suffix(']')
                .ok_or_else(|| format!("segment `{s}`: expected name[index] or name[*]"))?;
            if index == "*" {
                Ok(Segment::Every(name))
            } else {
                index
                    .parse()
                    .map(|i| Segment::Entry(name, i))
                    .map_err(|_| format!("segment `{s}`: the index must be a number or *"))
            }
        }
    }
}

fn set_in(table: &mut toml::Table, path: &[&str], value: &toml::Value) -> Result<(), String> {
    let Some((first, rest)) = path.split_first() else {
        return Err("empty key".into());
    };
    match segment(first)? {
        Segment::Key(name) if rest.is_empty() => {
            table.insert(name.to_string(), value.clone());
            Ok(())
        }
        Segment::Key(name) => {
            let entry = table
                .entry(name.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            if !entry.is_table() {
                *entry = toml::Value::Table(toml::Table::new());
            }
            match entry {
                toml::Value::Table(inner) => set_in(inner, rest, value),
                _ => Err(format!("`{name}` is not a table")),
            }
        }
        Segment::Entry(name, _) | Segment::Every(name) if rest.is_empty() => {
            Err(format!("`{name}[…]` must be followed by a key"))
        }
        seg @ (Segment::Entry(..) | Segment::Every(..)) => {
            let (name, index) = match seg {
                Segment::Entry(n, i) => (n, Some(i)),
                Segment::Every(n) => (n, None),
                Segment::Key(_) => unreachable!("matched above"),
            };
            let Some(toml::Value::Array(items)) = table.get_mut(name) else {
                return Err(format!("`{name}` is not an array of tables"));
            };
            let len = items.len();
            let chosen: Vec<&mut toml::Value> = match index {
                Some(i) => items
                    .get_mut(i)
                    .map(|v| vec![v])
                    .ok_or_else(|| format!("`{name}` has {len} entries, no entry {i}"))?,
                None => items.iter_mut().collect(),
            };
            for item in chosen {
                match item {
                    toml::Value::Table(inner) => set_in(inner, rest, value)?,
                    _ => return Err(format!("an entry of `{name}` is not a table")),
                }
            }
            Ok(())
        }
    }
}

/// Sets one dotted key of `table`.
pub fn set(table: &mut toml::Table, key: &str, value: toml::Value) -> Result<(), OverrideError> {
    let path: Vec<&str> = key.split('.').collect();
    set_in(table, &path, &value).map_err(|message| OverrideError {
        key: key.to_string(),
        message,
    })
}

/// Removes one dotted key of `table` (a key that is absent is not an error: the result is the
/// same). Only plain table paths (no `[i]`) name what to remove.
pub fn remove(table: &mut toml::Table, key: &str) -> Result<(), OverrideError> {
    let error = |message: &str| OverrideError {
        key: key.to_string(),
        message: message.to_string(),
    };
    let mut parts: Vec<&str> = key.split('.').collect();
    let last = parts.pop().ok_or_else(|| error("empty key"))?;
    let mut t = table;
    for p in parts {
        if p.contains('[') {
            return Err(error("removal takes a plain table path"));
        }
        match t.get_mut(p) {
            Some(toml::Value::Table(inner)) => t = inner,
            Some(_) => return Err(error(&format!("`{p}` is not a table"))),
            None => return Ok(()),
        }
    }
    t.remove(last);
    Ok(())
}

/// Applies every override of `set` (dotted keys → values) to `table`, in key order.
pub fn apply(table: &mut toml::Table, overrides: &toml::Table) -> Result<(), OverrideError> {
    for (key, value) in overrides {
        set(table, key, value.clone())?;
    }
    Ok(())
}

/// `table` with `overrides` applied.
pub fn applied(table: &toml::Table, overrides: &toml::Table) -> Result<toml::Table, OverrideError> {
    let mut t = table.clone();
    apply(&mut t, overrides)?;
    Ok(t)
}

#[cfg(test)]
mod tests {
    //! Dotted keys reach nested tables (creating them), entries of arrays of tables, and every
    //! entry; a key that cannot be applied is an error naming it.
    use super::*;

    fn table(text: &str) -> toml::Table {
        text.parse().expect("valid TOML")
    }

    #[test]
    fn dotted_key_sets_a_nested_value_and_creates_missing_tables() {
        let mut t = table("[foundation]\np0 = 6.0\n");
        set(&mut t, "foundation.p0", toml::Value::Float(2.0)).expect("set");
        set(&mut t, "time.steps", toml::Value::Integer(40)).expect("created");
        assert_eq!(t["foundation"]["p0"].as_float(), Some(2.0));
        assert_eq!(t["time"]["steps"].as_integer(), Some(40));
    }

    #[test]
    fn array_entries_are_reached_one_by_one_or_all_at_once() {
        let mut t =
            table("[[dirichlet]]\nsupport = \"clamped\"\n[[dirichlet]]\nsupport = \"clamped\"\n");
        set(&mut t, "dirichlet[1].support", "rollers".into()).expect("one");
        assert_eq!(t["dirichlet"][0]["support"].as_str(), Some("clamped"));
        assert_eq!(t["dirichlet"][1]["support"].as_str(), Some("rollers"));
        set(&mut t, "dirichlet[*].support", "free".into()).expect("every");
        assert_eq!(t["dirichlet"][0]["support"].as_str(), Some("free"));
        assert_eq!(t["dirichlet"][1]["support"].as_str(), Some("free"));
    }

    #[test]
    fn removal_takes_a_key_out_and_tolerates_an_absent_one() {
        let mut t = table("[contact]\nstiffness = 1e6\ndepth = 0.1\n");
        remove(&mut t, "contact.stiffness").expect("removed");
        remove(&mut t, "contact.friction.depth").expect("absent");
        assert!(t["contact"].get("stiffness").is_none());
        assert_eq!(t["contact"]["depth"].as_float(), Some(0.1));
        assert!(remove(&mut t, "contact.depth.x").is_err());
    }

    #[test]
    fn an_impossible_override_is_an_error_naming_the_key() {
        let mut t = table("[[dirichlet]]\nsupport = \"clamped\"\n");
        let e = set(&mut t, "dirichlet[3].support", "x".into()).expect_err("no entry 3");
        assert!(e.to_string().contains("dirichlet[3].support"), "{e}");
        let e = set(&mut t, "mesh[x].a", 1.into()).expect_err("bad index");
        assert!(e.to_string().contains("index"), "{e}");
    }
}
