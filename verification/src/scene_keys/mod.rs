//! `verify scene-keys`: the reference of every scene key, `docs/scenes.md`, generated from the
//! solver's scene types — their fields, serde attributes and doc comments — so that each key is
//! documented once, beside its declaration.
//!
//! `source` parses the solver crate's `src/` with `syn`; `types` resolves a field's type to a
//! TOML value; `walk` goes from each model's scene-file struct (`models`) to one row per key;
//! `render` writes the Markdown.

pub mod models;
pub mod render;
pub mod source;
pub mod types;
pub mod walk;

use std::path::Path;
use std::process::ExitCode;

pub use crate::scene_keys::models::ModelKeys;
use crate::scene_keys::source::Source;

/// The keys of every model, from the solver crate's source directory `src`.
pub fn generate(src: &Path) -> Result<Vec<ModelKeys>, String> {
    let source = source::scan(src)?;
    models::MODELS
        .iter()
        .map(|&(model, root, file)| model_keys(&source, model, None, root, file))
        .chain(
            models::VARIANTS
                .iter()
                .map(|&(name, model, how, root, file)| {
                    model_keys(&source, name, Some((model, how)), root, file)
                }),
        )
        .collect()
}

fn model_keys(
    source: &Source,
    model: &'static str,
    selected_by: Option<(&'static str, &'static str)>,
    root: &str,
    file: &str,
) -> Result<ModelKeys, String> {
    let def = types::resolve(source, root, &[], Path::new(file))?
        .filter(|d| d.file == Path::new(file))
        .ok_or_else(|| format!("{model}: no Deserialize struct {root} in src/{file}"))?;
    let mut rows = walk::walk(source, def)?;
    for (after, row) in models::extra_rows(model) {
        let at = rows
            .iter()
            .rposition(|r| r.path == after || r.path.starts_with(&format!("{after}.")))
            .ok_or_else(|| format!("{model}: no key {after} for {}", row.path))?;
        rows.insert(at + 1, row);
    }
    Ok(ModelKeys {
        model,
        selected_by,
        root: root.to_string(),
        file: file.to_string(),
        doc: rows
            .iter()
            .find(|r| r.path == "model" && !r.meaning.is_empty())
            .map_or_else(|| types::first_paragraph(&def.doc), |r| r.meaning.clone()),
        rows,
    })
}

/// The keys without a doc comment on their field: `model: key path (file: Type.field)`.
pub fn undocumented(models: &[ModelKeys]) -> Vec<String> {
    models
        .iter()
        .flat_map(|m| {
            m.rows
                .iter()
                .filter(|r| r.meaning.trim().is_empty())
                .map(move |r| format!("{}: {} ({})", m.model, r.path, r.origin))
        })
        .collect()
}

/// `docs/scenes.md` as the generator writes it, from the repository at `root`.
pub fn reference(root: &Path) -> Result<String, String> {
    Ok(render::render(&generate(&root.join("src"))?))
}

/// `verify scene-keys [--check]`: writes `docs/scenes.md`, or with `check` exits 1 when it
/// differs from what the generator writes (2 on an error).
pub fn run_command(root: &Path, check: bool) -> ExitCode {
    let path = root.join("docs/scenes.md");
    let text = match reference(root) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if check {
        return if std::fs::read_to_string(&path).ok().as_deref() == Some(text.as_str()) {
            println!("docs/scenes.md: equal to the scene types' doc comments");
            ExitCode::SUCCESS
        } else {
            println!("docs/scenes.md: differs from the scene types (run `verify scene-keys`)");
            ExitCode::from(1)
        };
    }
    match std::fs::write(&path, text) {
        Ok(()) => {
            println!("wrote {}", path.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(2)
        }
    }
}
