//! The typed error of a case file and the checks every kind's format uses: each names the field
//! as the case file writes it, the value found and what was expected.

use std::fmt::Display;
use std::path::Path;

/// Why a case file is unusable.
#[derive(Debug, thiserror::Error)]
pub enum CaseError {
    /// The file cannot be read or is not valid TOML of its kind's format.
    #[error("{path}: {message}")]
    Read { path: String, message: String },
    /// A value is out of its admissible range.
    #[error("{path}: invalid {field} = {value}: expected {expected}")]
    Invalid {
        path: String,
        field: String,
        value: String,
        expected: String,
    },
}

/// An invalid field of the case file at `path`.
pub fn invalid(path: &Path, field: &str, value: impl Display, expected: &str) -> CaseError {
    CaseError::Invalid {
        path: path.display().to_string(),
        field: field.to_string(),
        value: value.to_string(),
        expected: expected.to_string(),
    }
}

/// `v` is finite and > 0.
pub fn positive(path: &Path, field: &str, v: f64) -> Result<(), CaseError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(path, field, v, "a finite number > 0"))
    }
}

/// A list has at least `n` entries.
pub fn at_least<T>(path: &Path, field: &str, v: &[T], n: usize) -> Result<(), CaseError> {
    if v.len() >= n {
        Ok(())
    } else {
        Err(invalid(
            path,
            field,
            format!("{} entries", v.len()),
            &format!("at least {n} entries"),
        ))
    }
}

/// A section the case's kind requires is present.
pub fn required<'a, T>(path: &Path, field: &str, v: &'a Option<T>) -> Result<&'a T, CaseError> {
    v.as_ref()
        .ok_or_else(|| invalid(path, field, "(missing)", "a section for this kind of case"))
}

#[cfg(test)]
mod tests {
    //! Each check names the field and the value it rejects.
    use super::*;

    #[test]
    fn positive_rejects_zero_nan_and_infinity_naming_the_field() {
        let p = Path::new("c.toml");
        assert!(positive(p, "x", 1.0).is_ok());
        for v in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = positive(p, "gate[0].tolerance", v).expect_err("rejected");
            assert!(e.to_string().contains("gate[0].tolerance"), "{e}");
        }
    }

    #[test]
    fn at_least_and_required_name_what_is_missing() {
        let p = Path::new("c.toml");
        let e = at_least(p, "levels", &[1], 2).expect_err("too short");
        assert!(e.to_string().contains("1 entries"), "{e}");
        let none: Option<u8> = None;
        let e = required(p, "stability", &none).expect_err("missing");
        assert!(e.to_string().contains("stability"), "{e}");
    }
}
