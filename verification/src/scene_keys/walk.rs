//! The walk: from a model's scene-file struct through its fields, recursively, to one row per key
//! as a user writes it (`geometry.size`, `[[dirichlet]].support`, `contact.friction.law`), with
//! the serde attributes honoured (`rename`, `rename_all`, `alias`, `default`, `flatten`, `skip`,
//! `tag`, `untagged`).

use std::path::Path;

use crate::scene_keys::source::{DefaultAttr, FieldDef, Shape, Source, TypeDef};
use crate::scene_keys::types::{describe, first_paragraph, rename, variant_name, Below, Desc};

/// One key of a scene file.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// As a user writes it: `rod.length`, `[[dirichlet]].where`.
    pub path: String,
    /// Other names serde accepts for it.
    pub aliases: Vec<String>,
    /// `number`, `string`, `array of 2 numbers`, `table`, …
    pub ty: String,
    /// `required`, `optional`, `default: …`, with the variant that takes the key when only one
    /// does.
    pub requirement: String,
    /// The first paragraph of the field's doc comment (empty: undocumented).
    pub meaning: String,
    /// The accepted strings with their docs (enum-valued keys).
    pub values: Vec<(String, String)>,
    /// Where the key is declared: `scene/rod.rs: RodSection.length`.
    pub origin: String,
}

/// The rows of the struct `root` (a model's scene-file type).
pub fn walk(source: &Source, root: &TypeDef) -> Result<Vec<Row>, String> {
    let mut rows = Vec::new();
    let mut stack = Vec::new();
    fields(source, Owner::of(root)?, "", "", &mut stack, &mut rows)?;
    Ok(rows)
}

/// The fields of a struct or of a struct-like enum variant, with what of their owner decides
/// their keys.
struct Owner<'a> {
    file: &'a Path,
    /// `RodSection`, or `Enum::Variant`.
    name: String,
    rename_all: Option<&'a str>,
    /// `#[serde(default)]` on the container.
    container_default: bool,
    fields: &'a [FieldDef],
}

impl<'a> Owner<'a> {
    fn of(def: &'a TypeDef) -> Result<Self, String> {
        let Shape::Struct { fields, .. } = &def.shape else {
            return Err(format!(
                "{}: {} is not a struct",
                def.file.display(),
                def.name
            ));
        };
        Ok(Owner {
            file: &def.file,
            name: def.name.clone(),
            rename_all: def.serde.rename_all.as_deref(),
            container_default: def.serde.default.is_some(),
            fields,
        })
    }
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

/// The keys of the struct `def`, below `prefix`; `when` is the variant condition, if any.
fn fields<'a>(
    source: &'a Source,
    def: Owner<'a>,
    prefix: &str,
    when: &str,
    stack: &mut Vec<String>,
    rows: &mut Vec<Row>,
) -> Result<(), String> {
    let id = format!("{}::{}", def.file.display(), def.name);
    if stack.contains(&id) {
        return Err(format!(
            "{}: the type {} contains itself",
            def.file.display(),
            def.name
        ));
    }
    stack.push(id);
    for f in def.fields.iter().filter(|f| !f.serde.skip) {
        let ident = f.ident.clone().unwrap_or_default();
        let d = describe(source, &f.ty, def.file)?;
        if f.serde.flatten {
            match d.below {
                Below::Table(t) => fields(source, Owner::of(t)?, prefix, when, stack, rows)?,
                Below::Map(_) | Below::Nothing if d.ty.starts_with("table") => {
                    let row = row(source, &def, f, &d, join(prefix, "<any key>"), when);
                    rows.push(row);
                }
                _ => {
                    return Err(format!(
                        "{}: {}.{ident} is flattened but is not a table",
                        def.file.display(),
                        def.name
                    ))
                }
            }
            continue;
        }
        let key = f
            .serde
            .rename
            .clone()
            .unwrap_or_else(|| rename(&ident, def.rename_all, false));
        let path = join(prefix, &key);
        match d.below {
            Below::TableArray(t) => {
                let header = format!("[[{}]]", strip_brackets(&path));
                rows.push(row(source, &def, f, &d, header.clone(), when));
                fields(source, Owner::of(t)?, &header, when, stack, rows)?;
            }
            Below::Table(t) => {
                rows.push(row(source, &def, f, &d, path.clone(), when));
                fields(source, Owner::of(t)?, &path, when, stack, rows)?;
            }
            Below::Map(t) => {
                rows.push(row(source, &def, f, &d, path.clone(), when));
                fields(
                    source,
                    Owner::of(t)?,
                    &format!("{path}.<name>"),
                    when,
                    stack,
                    rows,
                )?;
            }
            Below::Variants(e) => {
                rows.push(row(source, &def, f, &d, path.clone(), when));
                variants(source, e, &path, when, stack, rows)?;
            }
            Below::Nothing => rows.push(row(source, &def, f, &d, path, when)),
        }
    }
    stack.pop();
    Ok(())
}

/// `[[a]].b` → `a.b` (the header of an array of tables nested in one).
fn strip_brackets(path: &str) -> String {
    path.replace("[[", "").replace("]]", "")
}

/// The keys of an enum's data-carrying variants below `prefix`: internally tagged, the tag key
/// and each variant's keys under its tag value; externally tagged, a table per variant;
/// untagged, each variant's keys.
fn variants<'a>(
    source: &'a Source,
    e: &'a TypeDef,
    prefix: &str,
    when: &str,
    stack: &mut Vec<String>,
    rows: &mut Vec<Row>,
) -> Result<(), String> {
    let Shape::Enum(list) = &e.shape else {
        return Ok(());
    };
    let live: Vec<_> = list.iter().filter(|v| !v.serde.skip).collect();
    if let Some(tag) = &e.serde.tag {
        rows.push(Row {
            path: join(prefix, tag),
            aliases: Vec::new(),
            ty: "string".into(),
            requirement: with_when("required".into(), when),
            // no field declares the tag: the enum's doc says what it chooses
            meaning: first_paragraph(&e.doc),
            values: live
                .iter()
                .map(|v| (variant_name(e, v), first_paragraph(&v.doc)))
                .collect(),
            origin: format!("{}: {} (serde tag)", e.file.display(), e.name),
        });
    }
    for v in live {
        let name = variant_name(e, v);
        let cond = match (&e.serde.tag, e.serde.untagged) {
            (Some(tag), _) => format!("{tag} = \"{name}\""),
            (None, true) => format!("the {name} form"),
            (None, false) => String::new(),
        };
        let when = [when, cond.as_str()]
            .iter()
            .filter(|s| !s.is_empty())
            .copied()
            .collect::<Vec<_>>()
            .join(", ");
        let here = if e.serde.tag.is_none() && !e.serde.untagged {
            join(prefix, &name)
        } else {
            prefix.to_string()
        };
        if v.named {
            let owner = Owner {
                file: &e.file,
                name: format!("{}::{}", e.name, v.name),
                rename_all: v.serde.rename_all.as_deref(),
                container_default: false,
                fields: &v.fields,
            };
            fields(source, owner, &here, &when, stack, rows)?;
        } else if let [one] = v.fields.as_slice() {
            let d = describe(source, &one.ty, &e.file)?;
            if let Below::Table(t) = d.below {
                fields(source, Owner::of(t)?, &here, &when, stack, rows)?;
            }
        }
    }
    Ok(())
}

fn with_when(requirement: String, when: &str) -> String {
    if when.is_empty() {
        requirement
    } else {
        format!("{requirement} (with {when})")
    }
}

fn row(source: &Source, def: &Owner, f: &FieldDef, d: &Desc, path: String, when: &str) -> Row {
    Row {
        path,
        aliases: f.serde.aliases.clone(),
        ty: d.ty.clone(),
        requirement: with_when(requirement(source, def, f, d), when),
        meaning: first_paragraph(&f.doc),
        values: d.values.clone(),
        origin: format!(
            "{}: {}.{}",
            def.file.display(),
            def.name,
            f.ident.clone().unwrap_or_default()
        ),
    }
}

fn requirement(source: &Source, def: &Owner, f: &FieldDef, d: &Desc) -> String {
    let plain = |v: &Option<String>| match v {
        Some(v) => format!("default: `{v}`"),
        None => "default: see meaning".to_string(),
    };
    match &f.serde.default {
        Some(_) if d.optional => "optional".into(),
        Some(DefaultAttr::Function(path)) => {
            let name = path.rsplit("::").next().unwrap_or(path);
            plain(
                &source
                    .literal_fns
                    .get(&(def.file.to_path_buf(), name.to_string()))
                    .cloned(),
            )
        }
        Some(DefaultAttr::Trait) => match d.below {
            Below::Table(_) => "optional".into(),
            _ => plain(&d.default),
        },
        None if d.optional => "optional".into(),
        None if def.container_default => "default: see meaning".into(),
        None => "required".into(),
    }
}
