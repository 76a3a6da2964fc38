//! The JSON a scene writes, with every number finite.
//!
//! JSON has no NaN or ∞: serde writes them as `null`. The scene outputs hold no intended `null`
//! (absent values are left out), so a `null` in them is a number that is not finite — a run that
//! would "succeed" with NaN in its results. It is refused with its place (a JSON pointer), and
//! the scene fails with that error instead of writing it.

use serde::Serialize;

/// The JSON of `value` (pretty-printed or compact), or the JSON pointer of its first non-finite
/// number.
pub fn finite_json<T: Serialize>(value: &T, pretty: bool) -> Result<String, String> {
    let text = if pretty {
        serde_json::to_string_pretty(value)
    } else {
        serde_json::to_string(value)
    }
    .map_err(|e| e.to_string())?;
    // the scan holds nothing beside the text; the parsed tree (several times the text: a
    // `Value` per number) is built only to name the place of a null
    if !has_null(&text) {
        return Ok(text);
    }
    let parsed: serde_json::Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    let at = first_null(&parsed, "").unwrap_or_else(|| "/".into());
    Err(format!(
        "a number that is not finite (NaN or ∞) at {at}; the file is not written"
    ))
}

/// Whether the JSON `text` holds the literal `null` outside its strings (one pass over the
/// bytes: a `"` opens or closes a string unless escaped by a `\`).
fn has_null(text: &str) -> bool {
    let b = text.as_bytes();
    let mut in_string = false;
    let mut i = 0;
    while i < b.len() {
        match (in_string, b[i]) {
            (true, b'\\') => i += 1,
            (_, b'"') => in_string = !in_string,
            (false, b'n') if b[i..].starts_with(b"null") => return true,
            _ => {}
        }
        i += 1;
    }
    false
}

/// The JSON pointer of the first `null` in `v`.
pub fn first_null(v: &serde_json::Value, at: &str) -> Option<String> {
    match v {
        serde_json::Value::Null => Some(if at.is_empty() { "/".into() } else { at.into() }),
        serde_json::Value::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(i, x)| first_null(x, &format!("{at}/{i}"))),
        serde_json::Value::Object(o) => o
            .iter()
            .find_map(|(k, x)| first_null(x, &format!("{at}/{k}"))),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    //! A NaN anywhere is refused with its place; finite values pass unchanged.
    use super::*;

    #[test]
    fn a_nan_is_refused_with_its_pointer() {
        #[derive(Serialize)]
        struct S {
            a: Vec<f64>,
            b: f64,
        }
        let ok = S {
            a: vec![1.0, 2.5],
            b: -3.0,
        };
        assert_eq!(
            finite_json(&ok, true).unwrap(),
            serde_json::to_string_pretty(&ok).unwrap()
        );
        let bad = S {
            a: vec![1.0, f64::NAN],
            b: 0.0,
        };
        assert!(finite_json(&bad, false).unwrap_err().contains("/a/1"));
        let inf = S {
            a: vec![],
            b: f64::INFINITY,
        };
        assert!(finite_json(&inf, true).unwrap_err().contains("/b"));
    }

    #[test]
    fn a_null_inside_a_string_is_text_not_a_number() {
        assert!(!has_null(r#"{"title": "null \\\" null", "a": [1, 2]}"#));
        assert!(has_null(r#"{"title": "x\\\"", "a": [1, null]}"#));
        assert!(finite_json(&("null", 1.0), true).is_ok());
    }
}
