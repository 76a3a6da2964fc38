//! Typed errors. Every error carries the data a user needs to act on it: which field, which value,
//! what was expected; which step, which time, which iteration, which residual.

use std::fmt::Display;

/// Invalid user input: a scene value, a parameter, a mesh.
///
/// Displayed as `invalid <field> = <value>: expected <expected>`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid {field} = {value}: expected {expected}")]
pub struct InputError {
    /// Dotted path of the offending field, as written in a scene (`rod.viscosity`, `mesh.elements`).
    pub field: String,
    /// The value that was given, formatted.
    pub value: String,
    /// What a valid value looks like.
    pub expected: String,
}

impl InputError {
    /// An input error for `field` holding `value`, which should have been `expected`.
    pub fn new(field: impl Into<String>, value: impl Display, expected: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            value: readable(&value.to_string()),
            expected: expected.into(),
        }
    }

    /// The same error with `prefix.` prepended to its field path.
    pub fn within(mut self, prefix: &str) -> Self {
        self.field = format!("{prefix}.{}", self.field);
        self
    }
}

/// Longest text of one value or word shown in a message.
const LONGEST_SHOWN: usize = 120;

/// `text` with every number written in more than 24 characters (1e308 prints 309 digits) in
/// scientific notation, and every word longer than [`LONGEST_SHOWN`] characters (a 50 000-term
/// expression) cut, with its length said.
pub fn readable(text: &str) -> String {
    let mut out = String::with_capacity(text.len().min(4 * LONGEST_SHOWN));
    for (i, word) in text.split(' ').enumerate() {
        if i > 0 {
            out.push(' ');
        }
        let core = word.trim_matches(|c: char| "`'\",;:()[]".contains(c));
        if core.len() > 24 {
            if let Ok(x) = core.parse::<f64>() {
                out.push_str(&word.replacen(core, &format!("{x:e}"), 1));
                continue;
            }
        }
        if word.chars().count() > LONGEST_SHOWN {
            let head: String = word.chars().take(LONGEST_SHOWN).collect();
            out.push_str(&format!("{head}… ({} characters)", word.chars().count()));
        } else {
            out.push_str(word);
        }
    }
    out
}

/// `value` if it is finite and strictly positive.
pub fn require_positive(field: &str, value: f64) -> Result<f64, InputError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(InputError::new(field, value, "a finite number > 0"))
    }
}

/// `value` if it is finite and non-negative.
pub fn require_nonnegative(field: &str, value: f64) -> Result<f64, InputError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(InputError::new(field, value, "a finite number >= 0"))
    }
}

/// `value` if it is finite.
pub fn require_finite(field: &str, value: f64) -> Result<f64, InputError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(InputError::new(field, value, "a finite number"))
    }
}

/// Checks that `values` starts at 0 and increases strictly through finite numbers; `field` is the
/// scene path of the list (`mesh.nodes`, `time.times`) and `minimum` its required length.
pub fn require_increasing_from_zero(
    field: &str,
    values: &[f64],
    minimum: usize,
    what: &str,
) -> Result<(), InputError> {
    if values.len() < minimum {
        return Err(InputError::new(
            field,
            format!("{} values", values.len()),
            format!("at least {minimum} {what}"),
        ));
    }
    if values[0] != 0.0 {
        return Err(InputError::new(format!("{field}[0]"), values[0], "0"));
    }
    for i in 1..values.len() {
        if !values[i].is_finite() || values[i] <= values[i - 1] {
            return Err(InputError::new(
                format!("{field}[{i}]"),
                values[i],
                format!("a finite number > {field}[{}] = {}", i - 1, values[i - 1]),
            ));
        }
    }
    Ok(())
}

/// A solver failure, with where and when it happened.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// The nonsmooth step equation was not solved to round-off within the iteration budget.
    #[error(
        "step {step} (t = {time}): semismooth Newton did not converge in {iterations} iterations \
         (residual {residual:e}, tolerance {tolerance:e})"
    )]
    NewtonNotConverged {
        step: usize,
        time: f64,
        iterations: usize,
        residual: f64,
        tolerance: f64,
    },
    /// A non-finite number appeared; nothing after it would be meaningful.
    #[error("step {step} (t = {time}): non-finite {quantity} ({value}){hint}")]
    NonFinite {
        step: usize,
        time: f64,
        quantity: String,
        value: f64,
        /// Why it probably happened (e.g. an explicit step above its stability bound), or empty.
        hint: String,
    },
    /// The step problem has no solution (or none that is unique): e.g. a body held only by its
    /// contact under a load the contact forces cannot balance.
    #[error("step {step} (t = {time}): the step problem has no solution: {reason}")]
    NoEquilibrium {
        step: usize,
        time: f64,
        reason: String,
    },
    /// An eigenproblem failed at a parameter point (`v̄ = 0.5, p = 2`).
    #[error("at {at}: {source}")]
    Eigenproblem {
        at: String,
        #[source]
        source: crate::solve::quadratic_eigen::QuadraticEigenError,
    },
    /// The run was stopped from outside (Ctrl-C or a time limit; [`crate::run_control`]).
    #[error("stopped at {at}: {reason}")]
    Stopped { at: String, reason: String },
    /// A factorization met a zero, negative or non-finite pivot.
    #[error("singular or indefinite {operator}: pivot {pivot:e} at row {row}")]
    Singular {
        operator: String,
        row: usize,
        pivot: f64,
    },
}

/// Any error of the crate.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// Invalid input.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A solver failure.
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// A scene file that cannot be read or parsed.
    #[error("scene {source_name}: {message}")]
    Scene {
        source_name: String,
        message: String,
    },
}

#[cfg(test)]
mod tests {
    //! Messages stay readable whatever the input: long numbers in scientific notation, long words
    //! cut with their length.
    use super::*;

    #[test]
    fn long_numbers_and_words_are_shown_readably() {
        let e = InputError::new("rod.length", -1e308, "a finite number > 0");
        assert_eq!(e.value, "-1e308");
        let long = vec!["x"; 1000].join("+");
        let r = readable(&format!("invalid `{long}` here"));
        assert!(
            r.contains("… (2001 characters)") && r.ends_with(" here"),
            "{r}"
        );
        assert!(r.len() < 200);
        assert_eq!(
            readable("type: floating point `0.000000000000000000000000000001`, expected"),
            "type: floating point `1e-30`, expected"
        );
        assert_eq!(readable("a = 2.5 and b = 3"), "a = 2.5 and b = 3");
    }
}
