//! What a Rust type is as a TOML value: a number, a string with accepted values, an array, a table
//! whose keys are a struct's fields, … — the idents resolved to the `#[derive(Deserialize)]`
//! structs and enums of the scan (an ambiguity is an error naming both).

use std::path::Path;

use crate::scene_keys::source::{Shape, Source, TypeDef, VariantDef};

/// What is below a value: the keys of a table, of each table of an array, of each entry of a
/// map, or of an enum's data-carrying variants.
#[derive(Clone, Copy)]
pub enum Below<'a> {
    Nothing,
    Table(&'a TypeDef),
    TableArray(&'a TypeDef),
    Map(&'a TypeDef),
    Variants(&'a TypeDef),
}

/// A type as a TOML value.
#[derive(Clone)]
pub struct Desc<'a> {
    /// As the reference writes it: `number`, `array of 2 strings`, `table`, …
    pub ty: String,
    /// The accepted strings and their docs (enums of unit variants).
    pub values: Vec<(String, String)>,
    /// `Option<T>`.
    pub optional: bool,
    pub below: Below<'a>,
    /// The value of `Default::default()` as TOML, when the type makes it plain.
    pub default: Option<String>,
}

impl Desc<'_> {
    fn leaf(ty: &str, default: Option<&str>) -> Self {
        Desc {
            ty: ty.to_string(),
            values: Vec::new(),
            optional: false,
            below: Below::Nothing,
            default: default.map(str::to_string),
        }
    }
}

/// The type definition `name` referred to from `file` (`path`: the type's path as written, e.g.
/// `crate::mesh::triangle::Diagonal`): the one Deserialize type of that name, else the one at
/// the written path, in the same file, or in the same directory; two candidates left is an error
/// naming both.
pub fn resolve<'a>(
    source: &'a Source,
    name: &str,
    path: &[String],
    file: &Path,
) -> Result<Option<&'a TypeDef>, String> {
    let all: Vec<&TypeDef> = source
        .types
        .iter()
        .filter(|t| t.deserialize && t.name == name)
        .collect();
    if all.len() <= 1 {
        return Ok(all.first().copied());
    }
    let module: Vec<&str> = path
        .iter()
        .skip_while(|s| *s == "crate")
        .take(path.len().saturating_sub(1))
        .map(String::as_str)
        .collect();
    let by_path = |t: &&&TypeDef| {
        let f = t.file.with_extension("");
        let parts: Vec<String> = f
            .components()
            .map(|c| c.as_os_str().to_string_lossy().to_string())
            .filter(|c| c != "mod")
            .collect();
        path.first().is_some_and(|s| s == "crate") && parts == module
    };
    let tiers: [&dyn Fn(&&&TypeDef) -> bool; 3] = [&by_path, &|t| t.file == file, &|t| {
        t.file.parent() == file.parent()
    }];
    for tier in tiers {
        let found: Vec<&&TypeDef> = all.iter().filter(tier).collect();
        if found.len() == 1 {
            return Ok(Some(found[0]));
        }
    }
    Err(format!(
        "{}: the type {name} is ambiguous: {}",
        file.display(),
        all.iter()
            .map(|t| format!("{} ({})", t.name, t.file.display()))
            .collect::<Vec<_>>()
            .join(" and ")
    ))
}

/// The TOML value of the type `ty`, written in `file`.
pub fn describe<'a>(source: &'a Source, ty: &syn::Type, file: &Path) -> Result<Desc<'a>, String> {
    match ty {
        syn::Type::Path(p) => {
            let segments: Vec<String> = p
                .path
                .segments
                .iter()
                .map(|s| s.ident.to_string())
                .collect();
            let last = p.path.segments.last().ok_or("an empty type path")?;
            let name = last.ident.to_string();
            let args: Vec<&syn::Type> = match &last.arguments {
                syn::PathArguments::AngleBracketed(a) => a
                    .args
                    .iter()
                    .filter_map(|g| match g {
                        syn::GenericArgument::Type(t) => Some(t),
                        _ => None,
                    })
                    .collect(),
                _ => Vec::new(),
            };
            named(source, &name, &segments, &args, file)
        }
        syn::Type::Array(a) => {
            let inner = describe(source, &a.elem, file)?;
            let n = match &a.len {
                syn::Expr::Lit(syn::ExprLit {
                    lit: syn::Lit::Int(i),
                    ..
                }) => i.base10_digits().to_string(),
                _ => "N".to_string(),
            };
            let default = inner.default.as_ref().and_then(|d| {
                let n: usize = n.parse().ok()?;
                Some(format!("[{}]", vec![d.as_str(); n].join(", ")))
            });
            Ok(Desc {
                ty: format!("array of {n} {}", plural(&inner.ty)),
                values: inner.values,
                default,
                ..Desc::leaf("", None)
            })
        }
        syn::Type::Reference(r) => describe(source, &r.elem, file),
        syn::Type::Paren(p) => describe(source, &p.elem, file),
        syn::Type::Group(g) => describe(source, &g.elem, file),
        other => Err(format!(
            "{}: a scene type this generator does not know: {}",
            file.display(),
            kind_name(other)
        )),
    }
}

fn kind_name(t: &syn::Type) -> &'static str {
    match t {
        syn::Type::Tuple(_) => "a tuple",
        syn::Type::Slice(_) => "a slice",
        syn::Type::TraitObject(_) => "a trait object",
        _ => "this kind of type",
    }
}

fn named<'a>(
    source: &'a Source,
    name: &str,
    segments: &[String],
    args: &[&syn::Type],
    file: &Path,
) -> Result<Desc<'a>, String> {
    let arg = |i: usize| {
        args.get(i)
            .copied()
            .ok_or_else(|| format!("{}: {name} without its type argument", file.display()))
    };
    Ok(match name {
        "Option" => Desc {
            optional: true,
            ..describe(source, arg(0)?, file)?
        },
        "Box" | "Arc" | "Rc" => describe(source, arg(0)?, file)?,
        "Vec" => {
            let inner = describe(source, arg(0)?, file)?;
            match inner.below {
                Below::Table(t) => Desc {
                    below: Below::TableArray(t),
                    ..Desc::leaf("array of tables", Some("[]"))
                },
                _ => Desc {
                    values: inner.values,
                    ..Desc::leaf(&format!("array of {}", plural(&inner.ty)), Some("[]"))
                },
            }
        }
        "HashMap" | "BTreeMap" | "IndexMap" => {
            let inner = describe(source, arg(1)?, file)?;
            let below = match inner.below {
                Below::Table(t) => Below::Map(t),
                _ => Below::Nothing,
            };
            Desc {
                values: inner.values,
                below,
                ..Desc::leaf(&format!("table of {}", plural(&inner.ty)), Some("{}"))
            }
        }
        "f64" | "f32" => Desc::leaf("number", Some("0.0")),
        "usize" | "u8" | "u16" | "u32" | "u64" => Desc::leaf("integer ≥ 0", Some("0")),
        "isize" | "i8" | "i16" | "i32" | "i64" => Desc::leaf("integer", Some("0")),
        "bool" => Desc::leaf("boolean", Some("false")),
        "String" | "str" | "PathBuf" | "Path" => Desc::leaf("string", Some("\"\"")),
        "FieldSpec" => Desc::leaf("number or expression of x, y, t", Some("0.0")),
        "Table" | "Value" if segments.first().is_some_and(|s| s == "toml") || name == "Table" => {
            Desc::leaf("table (free-form)", None)
        }
        _ => {
            let def = resolve(source, name, segments, file)?.ok_or_else(|| {
                format!(
                    "{}: the type {} is neither a known value type nor a Deserialize struct or \
                     enum of src/",
                    file.display(),
                    segments.join("::")
                )
            })?;
            definition(source, def)?
        }
    })
}

fn definition<'a>(source: &'a Source, def: &'a TypeDef) -> Result<Desc<'a>, String> {
    match &def.shape {
        Shape::Struct { fields, named } => {
            if !named && fields.len() == 1 {
                return describe(source, &fields[0].ty, &def.file);
            }
            if !named {
                return Err(format!(
                    "{}: the tuple struct {} is not a scene value",
                    def.file.display(),
                    def.name
                ));
            }
            Ok(Desc {
                below: Below::Table(def),
                ..Desc::leaf("table", None)
            })
        }
        Shape::Enum(variants) => enumeration(source, def, variants),
    }
}

fn enumeration<'a>(
    source: &'a Source,
    def: &'a TypeDef,
    variants: &'a [VariantDef],
) -> Result<Desc<'a>, String> {
    let live: Vec<&VariantDef> = variants.iter().filter(|v| !v.serde.skip).collect();
    let units: Vec<(String, String)> = live
        .iter()
        .filter(|v| v.fields.is_empty())
        .map(|v| (variant_name(def, v), first_paragraph(&v.doc)))
        .collect();
    let default = live
        .iter()
        .find(|v| v.is_default)
        .map(|v| format!("\"{}\"", variant_name(def, v)));
    if def.serde.untagged {
        let mut alternatives = Vec::new();
        for v in &live {
            let alt = match (v.named, v.fields.as_slice()) {
                (false, [one]) => describe(source, &one.ty, &def.file)?.ty,
                (true, _) => "table".to_string(),
                _ => continue,
            };
            if !alternatives.contains(&alt) {
                alternatives.push(alt);
            }
        }
        let below = if live.iter().any(|v| v.named) {
            Below::Variants(def)
        } else {
            Below::Nothing
        };
        return Ok(Desc {
            below,
            ..Desc::leaf(&alternatives.join(", or "), None)
        });
    }
    if def.serde.tag.is_some() {
        return Ok(Desc {
            below: Below::Variants(def),
            ..Desc::leaf("table", None)
        });
    }
    if units.len() == live.len() {
        return Ok(Desc {
            values: units,
            default,
            ..Desc::leaf("string", None)
        });
    }
    Ok(Desc {
        values: units,
        below: Below::Variants(def),
        ..Desc::leaf("string or table", None)
    })
}

/// The name a variant is written with.
pub fn variant_name(def: &TypeDef, v: &VariantDef) -> String {
    v.serde
        .rename
        .clone()
        .unwrap_or_else(|| rename(&v.name, def.serde.rename_all.as_deref(), true))
}

/// `name` (a Rust field in snake_case, or a variant in PascalCase when `pascal`) under a serde
/// `rename_all` rule.
pub fn rename(name: &str, rule: Option<&str>, pascal: bool) -> String {
    let words: Vec<String> = if pascal {
        let mut w: Vec<String> = Vec::new();
        for c in name.chars() {
            if c.is_uppercase() || w.is_empty() {
                w.push(String::new());
            }
            if let Some(last) = w.last_mut() {
                last.extend(c.to_lowercase());
            }
        }
        w
    } else {
        name.split('_').map(str::to_string).collect()
    };
    let cap = |w: &String| {
        let mut c = w.chars();
        c.next()
            .map(|f| f.to_uppercase().chain(c).collect::<String>())
            .unwrap_or_default()
    };
    match rule {
        Some("snake_case") => words.join("_"),
        Some("lowercase") => words.concat(),
        Some("UPPERCASE") => words.concat().to_uppercase(),
        Some("SCREAMING_SNAKE_CASE") => words.join("_").to_uppercase(),
        Some("kebab-case") => words.join("-"),
        Some("SCREAMING-KEBAB-CASE") => words.join("-").to_uppercase(),
        Some("PascalCase") => words.iter().map(cap).collect(),
        Some("camelCase") => {
            let p: String = words.iter().map(cap).collect();
            let mut c = p.chars();
            c.next()
                .map(|f| f.to_lowercase().chain(c).collect())
                .unwrap_or_default()
        }
        _ => name.to_string(),
    }
}

/// The first paragraph of a doc comment, on one line.
pub fn first_paragraph(doc: &str) -> String {
    doc.split("\n\n")
        .next()
        .unwrap_or("")
        .lines()
        .map(str::trim)
        .collect::<Vec<_>>()
        .join(" ")
}

fn plural(ty: &str) -> String {
    match ty {
        "number" => "numbers".into(),
        "string" => "strings".into(),
        "boolean" => "booleans".into(),
        "integer" => "integers".into(),
        "integer ≥ 0" => "integers ≥ 0".into(),
        "table" => "tables".into(),
        "number or expression of x, y, t" => "numbers or expressions of x, y, t".into(),
        other => format!("({other})"),
    }
}
