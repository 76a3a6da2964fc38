//! The source scan: every `.rs` file under the solver crate's `src/` parsed with `syn`, and its
//! structs and enums (outside `#[cfg(test)]` modules) kept with what decides the keys a scene
//! file may hold: whether they derive `Deserialize`, their serde attributes, their doc comments,
//! and their fields or variants. Also kept: the functions that return a literal (the targets of
//! `#[serde(default = "…")]`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use syn::meta::ParseNestedMeta;
use syn::{Attribute, Expr, Lit, LitStr};

/// A `#[serde(default)]` or `#[serde(default = "path")]`.
#[derive(Debug, Clone, PartialEq)]
pub enum DefaultAttr {
    /// `Default::default()` of the field's type.
    Trait,
    /// The function at this path.
    Function(String),
}

/// The serde attributes that decide keys (`deserialize_with`, `bound`, … are read and ignored).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SerdeAttrs {
    pub rename: Option<String>,
    pub rename_all: Option<String>,
    pub aliases: Vec<String>,
    pub default: Option<DefaultAttr>,
    pub flatten: bool,
    pub skip: bool,
    pub tag: Option<String>,
    pub content: Option<String>,
    pub untagged: bool,
}

/// A field of a struct or of an enum variant (`ident` is `None` for a tuple field).
#[derive(Clone)]
pub struct FieldDef {
    pub ident: Option<String>,
    pub ty: syn::Type,
    pub doc: String,
    pub serde: SerdeAttrs,
}

/// A variant of an enum.
#[derive(Clone)]
pub struct VariantDef {
    pub name: String,
    pub fields: Vec<FieldDef>,
    /// Whether its fields are named (`V { a: f64 }`) rather than a tuple (`V(f64)`).
    pub named: bool,
    pub doc: String,
    pub serde: SerdeAttrs,
    /// Marked `#[default]`.
    pub is_default: bool,
}

/// A struct's fields or an enum's variants.
#[derive(Clone)]
pub enum Shape {
    Struct { fields: Vec<FieldDef>, named: bool },
    Enum(Vec<VariantDef>),
}

/// A struct or enum of the solver crate.
#[derive(Clone)]
pub struct TypeDef {
    pub name: String,
    /// The file, relative to the scanned directory (`scene/rod.rs`).
    pub file: PathBuf,
    pub doc: String,
    pub deserialize: bool,
    pub serde: SerdeAttrs,
    pub shape: Shape,
}

/// Everything the scan keeps.
#[derive(Default)]
pub struct Source {
    pub types: Vec<TypeDef>,
    /// (file, function name) → the literal the function returns (`"ideal".into()` → `ideal`).
    pub literal_fns: BTreeMap<(PathBuf, String), String>,
}

/// Parses every `.rs` file under `src` (sorted, so the scan is deterministic).
pub fn scan(src: &Path) -> Result<Source, String> {
    let mut files = Vec::new();
    collect_files(src, &mut files)?;
    files.sort();
    let mut out = Source::default();
    for path in files {
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let parsed = syn::parse_file(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let rel = path.strip_prefix(src).unwrap_or(&path).to_path_buf();
        scan_items(&parsed.items, &rel, &mut out)?;
    }
    Ok(out)
}

fn collect_files(dir: &Path, out: &mut Vec<PathBuf>) -> Result<(), String> {
    let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for entry in entries {
        let path = entry.map_err(|e| format!("{}: {e}", dir.display()))?.path();
        if path.is_dir() {
            collect_files(&path, out)?;
        } else if path.extension().is_some_and(|x| x == "rs") {
            out.push(path);
        }
    }
    Ok(())
}

fn scan_items(items: &[syn::Item], file: &Path, out: &mut Source) -> Result<(), String> {
    let err = |e: syn::Error| format!("{}: {e}", file.display());
    for item in items {
        match item {
            syn::Item::Struct(s) => {
                let (fields, named) = fields(&s.fields).map_err(err)?;
                out.types.push(TypeDef {
                    name: s.ident.to_string(),
                    file: file.to_path_buf(),
                    doc: doc(&s.attrs),
                    deserialize: derives_deserialize(&s.attrs),
                    serde: serde_attrs(&s.attrs).map_err(err)?,
                    shape: Shape::Struct { fields, named },
                });
            }
            syn::Item::Enum(e) => {
                let mut variants = Vec::new();
                for v in &e.variants {
                    let (fields, named) = fields(&v.fields).map_err(err)?;
                    variants.push(VariantDef {
                        name: v.ident.to_string(),
                        fields,
                        named,
                        doc: doc(&v.attrs),
                        serde: serde_attrs(&v.attrs).map_err(err)?,
                        is_default: v.attrs.iter().any(|a| a.path().is_ident("default")),
                    });
                }
                out.types.push(TypeDef {
                    name: e.ident.to_string(),
                    file: file.to_path_buf(),
                    doc: doc(&e.attrs),
                    deserialize: derives_deserialize(&e.attrs),
                    serde: serde_attrs(&e.attrs).map_err(err)?,
                    shape: Shape::Enum(variants),
                });
            }
            syn::Item::Fn(f) => {
                if let Some(lit) = returned_literal(&f.block) {
                    out.literal_fns
                        .insert((file.to_path_buf(), f.sig.ident.to_string()), lit);
                }
            }
            syn::Item::Mod(m) if !is_cfg_test(&m.attrs) => {
                if let Some((_, inner)) = &m.content {
                    scan_items(inner, file, out)?;
                }
            }
            _ => {}
        }
    }
    Ok(())
}

fn fields(f: &syn::Fields) -> Result<(Vec<FieldDef>, bool), syn::Error> {
    let named = matches!(f, syn::Fields::Named(_));
    let mut out = Vec::new();
    for field in f.iter() {
        out.push(FieldDef {
            ident: field.ident.as_ref().map(|i| i.to_string()),
            ty: field.ty.clone(),
            doc: doc(&field.attrs),
            serde: serde_attrs(&field.attrs)?,
        });
    }
    Ok((out, named))
}

/// The doc comment: the `#[doc = "…"]` lines, each without its first space, joined by newlines.
fn doc(attrs: &[Attribute]) -> String {
    let mut lines = Vec::new();
    for a in attrs {
        if let syn::Meta::NameValue(nv) = &a.meta {
            if nv.path.is_ident("doc") {
                if let Expr::Lit(syn::ExprLit {
                    lit: Lit::Str(s), ..
                }) = &nv.value
                {
                    let v = s.value();
                    lines.push(v.strip_prefix(' ').unwrap_or(&v).trim_end().to_string());
                }
            }
        }
    }
    lines.join("\n").trim().to_string()
}

fn is_cfg_test(attrs: &[Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("cfg") && a.parse_args::<syn::Ident>().is_ok_and(|i| i == "test")
    })
}

fn derives_deserialize(attrs: &[Attribute]) -> bool {
    let mut found = false;
    for a in attrs.iter().filter(|a| a.path().is_ident("derive")) {
        let _ = a.parse_nested_meta(|m| {
            if m.path
                .segments
                .last()
                .is_some_and(|s| s.ident == "Deserialize")
            {
                found = true;
            }
            Ok(())
        });
    }
    found
}

fn serde_attrs(attrs: &[Attribute]) -> Result<SerdeAttrs, syn::Error> {
    let mut s = SerdeAttrs::default();
    for a in attrs.iter().filter(|a| a.path().is_ident("serde")) {
        a.parse_nested_meta(|m| {
            let key = m
                .path
                .get_ident()
                .map(|i| i.to_string())
                .unwrap_or_default();
            match key.as_str() {
                "rename" => s.rename = deserialize_name(&m)?.or(s.rename.take()),
                "rename_all" => s.rename_all = deserialize_name(&m)?.or(s.rename_all.take()),
                "alias" => s.aliases.push(m.value()?.parse::<LitStr>()?.value()),
                "default" => {
                    s.default = Some(if m.input.peek(syn::Token![=]) {
                        DefaultAttr::Function(m.value()?.parse::<LitStr>()?.value())
                    } else {
                        DefaultAttr::Trait
                    })
                }
                "flatten" => s.flatten = true,
                "skip" | "skip_deserializing" => s.skip = true,
                "tag" => s.tag = Some(m.value()?.parse::<LitStr>()?.value()),
                "content" => s.content = Some(m.value()?.parse::<LitStr>()?.value()),
                "untagged" => s.untagged = true,
                _ => skip_meta(&m)?,
            }
            Ok(())
        })?;
    }
    Ok(s)
}

/// `rename = "x"` or `rename(deserialize = "x", serialize = "y")`: the name read.
fn deserialize_name(m: &ParseNestedMeta) -> Result<Option<String>, syn::Error> {
    if m.input.peek(syn::Token![=]) {
        return Ok(Some(m.value()?.parse::<LitStr>()?.value()));
    }
    let mut name = None;
    m.parse_nested_meta(|inner| {
        if inner.path.is_ident("deserialize") {
            name = Some(inner.value()?.parse::<LitStr>()?.value());
        } else {
            skip_meta(&inner)?;
        }
        Ok(())
    })?;
    Ok(name)
}

/// Consumes an attribute this scan does not need (`deserialize_with = "…"`, `bound(…)`).
fn skip_meta(m: &ParseNestedMeta) -> Result<(), syn::Error> {
    if m.input.peek(syn::Token![=]) {
        m.value()?.parse::<Expr>()?;
    } else if m.input.peek(syn::token::Paren) {
        m.parse_nested_meta(|inner| skip_meta(&inner))?;
    }
    Ok(())
}

/// The literal a function body of one expression returns: `"ideal".into()`, `"x".to_string()`,
/// `String::from("x")`, `3.0`, `true`.
fn returned_literal(block: &syn::Block) -> Option<String> {
    let [syn::Stmt::Expr(e, None)] = block.stmts.as_slice() else {
        return None;
    };
    literal(e)
}

fn literal(e: &Expr) -> Option<String> {
    match e {
        Expr::Lit(l) => match &l.lit {
            Lit::Str(s) => Some(format!("\"{}\"", s.value())),
            Lit::Float(f) => Some(f.base10_digits().to_string()),
            Lit::Int(i) => Some(i.base10_digits().to_string()),
            Lit::Bool(b) => Some(b.value.to_string()),
            _ => None,
        },
        Expr::MethodCall(m)
            if m.args.is_empty()
                && ["into", "to_string", "to_owned"].contains(&m.method.to_string().as_str()) =>
        {
            literal(&m.receiver)
        }
        Expr::Call(c) if c.args.len() == 1 => literal(&c.args[0]),
        _ => None,
    }
}
