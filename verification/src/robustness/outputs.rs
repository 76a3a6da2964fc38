//! What a run wrote, checked for numbers that are not finite: JSON has no NaN or ∞ (serde writes
//! `null`), so a `null` where the writers never put one is a non-finite number; a plot with NaN
//! or ∞ in its coordinates is one too.

use std::path::Path;

/// The keys whose value may be `null` by design: none (absent values are left out).
const NULLABLE: [&str; 0] = [];

/// The first non-finite value in the files under `dir`: `file: /json/pointer` or `file: NaN`.
pub fn first_non_finite(dir: &Path) -> Option<String> {
    let mut entries: Vec<_> = std::fs::read_dir(dir).ok()?.flatten().collect();
    entries.sort_by_key(|e| e.path());
    for e in entries {
        let path = e.path();
        let name = path.file_name()?.to_string_lossy().to_string();
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue;
        };
        if name.ends_with(".json") {
            let Ok(v) = serde_json::from_str::<serde_json::Value>(&text) else {
                return Some(format!("{name}: not valid JSON"));
            };
            if let Some(p) = null_at(&v, "") {
                return Some(format!("{name}: null (a non-finite number) at {p}"));
            }
        } else if name.ends_with(".vtu") {
            if let Some(w) = vtu_non_finite(&path) {
                return Some(format!("{name}: {w}"));
            }
        } else if name.ends_with(".svg")
            && (text.contains("NaN") || text.contains("=\"inf") || text.contains("=\"-inf"))
        {
            return Some(format!("{name}: NaN or ∞ in the plot"));
        }
    }
    None
}

fn null_at(v: &serde_json::Value, at: &str) -> Option<String> {
    match v {
        serde_json::Value::Null => Some(at.to_string()),
        serde_json::Value::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(i, x)| null_at(x, &format!("{at}/{i}"))),
        serde_json::Value::Object(o) => o.iter().find_map(|(k, x)| {
            if x.is_null() && NULLABLE.contains(&k.as_str()) {
                None
            } else {
                null_at(x, &format!("{at}/{k}"))
            }
        }),
        _ => None,
    }
}

/// The first non-finite number of a `.vtu` file (points or any Float64/Float32 data array), read
/// back with vtkio — the arrays are base64 binary, so a text scan cannot see them; a file vtkio
/// cannot read is reported too.
fn vtu_non_finite(path: &Path) -> Option<String> {
    use vtkio::model::{Attribute, DataSet};
    let vtk = match vtkio::Vtk::import(path) {
        Ok(v) => v,
        Err(e) => return Some(format!("not a readable VTK file ({e})")),
    };
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        return None;
    };
    for piece in pieces {
        let Ok(p) = piece.into_loaded_piece_data(None) else {
            return Some("a piece vtkio cannot load".into());
        };
        let bad = |b: &vtkio::IOBuffer| {
            b.clone()
                .cast_into::<f64>()
                .is_some_and(|v| v.iter().any(|x| !x.is_finite()))
        };
        if bad(&p.points) {
            return Some("a point that is not finite".into());
        }
        for a in p.data.point.iter().chain(&p.data.cell) {
            if let Attribute::DataArray(d) = a {
                if bad(&d.data) {
                    return Some(format!("NaN or ∞ in the array {}", d.name));
                }
            }
        }
    }
    None
}
