//! A verification case: one TOML file in `verification/cases/`.
//!
//! Every case file starts with the same header keys — `id`, `title`, `kind`, `tier`,
//! `explanation` — read once here into [`CaseHeader`]. The rest of the file is the case's *body*:
//! it belongs to the case's kind, whose format parses it (with unknown keys as errors) through
//! [`Case::body`]. This module knows no kind and no model family; the registry decides which
//! family owns a kind.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::core::format::{invalid, CaseError};

/// Which runs include the case. The tiers nest: `verify --quick` (CI, under 20 s) runs the
/// `quick` cases; `verify` (what a newcomer runs first, under 90 s) runs the `quick` and `default`
/// ones; `verify --full` runs every case, the long studies too (the committed `reports/`).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default, Serialize, Deserialize,
)]
#[serde(rename_all = "snake_case")]
pub enum Tier {
    Quick,
    #[default]
    Default,
    Full,
}

impl Tier {
    /// Whether a case of this tier runs in a run of tier `run` (quick ⊂ default ⊂ full).
    pub fn runs_in(self, run: Tier) -> bool {
        self <= run
    }

    /// The tier's name as case files and reports write it.
    pub fn name(self) -> &'static str {
        match self {
            Tier::Quick => "quick",
            Tier::Default => "default",
            Tier::Full => "full",
        }
    }
}

/// The keys every case file has, whatever its kind.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CaseHeader {
    pub id: String,
    pub title: String,
    /// The case kind; the registry finds the family that owns it.
    pub kind: String,
    #[serde(default)]
    pub tier: Tier,
    /// Why the gates expect what they expect (regularity, floors, superconvergence).
    pub explanation: String,
}

/// The header keys, removed from the table before the body goes to its kind.
const HEADER_KEYS: [&str; 5] = ["id", "title", "kind", "tier", "explanation"];

/// A case read from disk: its header, and its body for the kind's format.
#[derive(Debug, Clone)]
pub struct Case {
    pub path: PathBuf,
    pub header: CaseHeader,
    /// Everything but the header keys.
    pub body: toml::Table,
}

impl Case {
    /// Reads one case file (header only; the kind's format is checked by the registry).
    pub fn read(path: &Path) -> Result<Self, CaseError> {
        let text = std::fs::read_to_string(path).map_err(|e| CaseError::Read {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Self::from_text(path, &text)
    }

    /// A case from TOML text (`path` labels errors).
    pub fn from_text(path: &Path, text: &str) -> Result<Self, CaseError> {
        let read_error = |message: String| CaseError::Read {
            path: path.display().to_string(),
            message,
        };
        let mut body: toml::Table = text
            .parse()
            .map_err(|e: toml::de::Error| read_error(e.to_string()))?;
        let mut head = toml::Table::new();
        for key in HEADER_KEYS {
            if let Some(v) = body.remove(key) {
                head.insert(key.to_string(), v);
            }
        }
        let header: CaseHeader = head
            .try_into()
            .map_err(|e: toml::de::Error| read_error(e.to_string()))?;
        Ok(Self {
            path: path.to_path_buf(),
            header,
            body,
        })
    }

    /// The body parsed into a kind's format (which denies unknown keys).
    pub fn body<T: DeserializeOwned>(&self) -> Result<T, CaseError> {
        self.parse_table(self.body.clone())
    }

    /// The body parsed into two formats (each denying unknown keys): the keys named in `keys`
    /// into `G`, the others into `T`. For a body whose sections the core reads (`G`) and the
    /// family the rest (`T`).
    pub fn body_split<G: DeserializeOwned, T: DeserializeOwned>(
        &self,
        keys: &[&str],
    ) -> Result<(G, T), CaseError> {
        let mut rest = self.body.clone();
        let mut part = toml::Table::new();
        for &key in keys {
            if let Some(v) = rest.remove(key) {
                part.insert(key.to_string(), v);
            }
        }
        Ok((self.parse_table(part)?, self.parse_table(rest)?))
    }

    /// `table` parsed into the format `T`; errors name the case file.
    fn parse_table<T: DeserializeOwned>(&self, table: toml::Table) -> Result<T, CaseError> {
        table
            .try_into()
            .map_err(|e: toml::de::Error| CaseError::Read {
                path: self.path.display().to_string(),
                message: e.to_string(),
            })
    }

    /// The case file's path, for error messages of the kind's checks.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The error of a case whose kind is not among `kinds`.
    pub fn unknown_kind(&self, kinds: &[&str]) -> CaseError {
        invalid(
            &self.path,
            "kind",
            &self.header.kind,
            &format!("one of {}", kinds.join(", ")),
        )
    }
}

/// Reads the header of every `*.toml` of a directory, sorted by file name; ids must be unique and
/// equal to the file names.
pub fn read_dir(dir: &Path) -> Result<Vec<Case>, CaseError> {
    let entries = std::fs::read_dir(dir).map_err(|e| CaseError::Read {
        path: dir.display().to_string(),
        message: e.to_string(),
    })?;
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    let cases: Vec<Case> = paths
        .iter()
        .map(|p| Case::read(p))
        .collect::<Result<_, _>>()?;
    for (i, c) in cases.iter().enumerate() {
        if cases[..i].iter().any(|d| d.header.id == c.header.id) {
            return Err(invalid(
                &c.path,
                "id",
                &c.header.id,
                "an id no other case uses",
            ));
        }
        if c.path.file_stem().and_then(|s| s.to_str()) != Some(c.header.id.as_str()) {
            return Err(invalid(
                &c.path,
                "id",
                &c.header.id,
                "the file name without .toml",
            ));
        }
    }
    Ok(cases)
}

#[cfg(test)]
mod tests {
    //! The header is read once and removed from the body, so a kind's format (which denies
    //! unknown keys) sees only its own keys; a missing header key is an error naming it.
    use super::*;

    const TEXT: &str = r#"
id = "c"
title = "t"
kind = "k"
tier = "quick"
explanation = "e"
[body_section]
x = 1
"#;

    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Body {
        body_section: toml::Table,
    }

    #[test]
    fn header_keys_are_read_once_and_removed_from_the_body() {
        let c = Case::from_text(Path::new("c.toml"), TEXT).expect("parses");
        assert_eq!(c.header.kind, "k");
        assert_eq!(c.header.tier, Tier::Quick);
        assert!(c.body.get("id").is_none());
        let b: Body = c.body().expect("the body has only its own keys");
        assert_eq!(b.body_section.get("x"), Some(&toml::Value::Integer(1)));
    }

    #[test]
    fn a_missing_header_key_is_an_error_naming_it() {
        let e = Case::from_text(
            Path::new("c.toml"),
            "id = \"c\"\ntitle = \"t\"\nkind = \"k\"",
        )
        .expect_err("no explanation");
        assert!(e.to_string().contains("explanation"), "{e}");
    }

    #[test]
    fn an_unknown_body_key_is_an_error_naming_it() {
        let text = TEXT.replace("[body_section]", "stray = 2\n[body_section]");
        let c = Case::from_text(Path::new("c.toml"), &text).expect("parses");
        let e = c.body::<Body>().err().expect("stray key");
        assert!(e.to_string().contains("stray"), "{e}");
    }
}
