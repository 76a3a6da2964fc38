//! Scalar data fields f(x, y, t): loads, pressures, initial values.
//!
//! A field is a constant, a parsed expression of `x`, `y` and `t` (scene files), or a Rust closure.
//! Each field knows which variables it depends on, so a model can take the fast path: a load that
//! does not depend on t is assembled and solved once; one that depends on t only is a scalar
//! multiple of a precomputed vector.

use std::fmt;
use std::sync::Arc;

mod syntax;

use exmex::{Express, FlatEx, FloatOpsFactory};

use crate::error::InputError;

/// The evaluator of a parsed expression: exmex's float operators, our number literals.
type Flat = FlatEx<f64, FloatOpsFactory<f64>, syntax::TomlNumber>;

/// Which variables a field depends on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Dependence {
    pub x: bool,
    pub y: bool,
    pub t: bool,
}

impl Dependence {
    /// Depends on space (x or y).
    pub fn on_space(&self) -> bool {
        self.x || self.y
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Variable {
    X,
    Y,
    T,
}

/// A parsed expression of x, y, t: numbers as TOML writes them (`1e-3`, `2.5E+2`, `1_000`),
/// `+ - * / ^`, functions (`sin`, `exp`, `sqrt`, `abs`, …, `atan2(a, b)`, `min(a, b)`), constants
/// `PI`, `E`, `TAU`; the grammar is in [`syntax`].
#[derive(Clone)]
pub struct Expression {
    text: String,
    flat: Arc<Flat>,
    order: Vec<Variable>,
}

/// The longest expression a scene may give (the longest in the examples and cases: 520).
pub const MAX_EXPRESSION_LENGTH: usize = 4000;

impl Expression {
    /// Parses `text`; `field` names the scene field in the error.
    pub fn parse(field: &str, text: &str) -> Result<Self, InputError> {
        // Bounded before parsing: a 50 000-term `x+x+…` in a load kept runs busy past 20 s with no
        // output (issue 11's fuzzing): every evaluation, per quadrature point and step, walks
        // every term.
        if text.len() > MAX_EXPRESSION_LENGTH {
            return Err(InputError::new(
                field,
                format!("({} characters)", text.len()),
                format!(
                    "an expression of at most {MAX_EXPRESSION_LENGTH} characters (a formula, not \
                     a table: tabulated data belong in a mesh or a file format)"
                ),
            ));
        }
        let refuse = |why: String| {
            InputError::new(
                field,
                format!("\"{text}\""),
                format!("an expression of x, y, t ({why})"),
            )
        };
        syntax::check(text).map_err(refuse)?;
        // The grammar check passed; a refusal by the evaluator would be a form the grammar
        // admits and exmex does not, reported without exmex's internal words.
        let flat = Flat::parse(&syntax::normalized(text)).map_err(|_| {
            refuse(
                "a form the evaluator does not read: write it with explicit `*` and parentheses"
                    .into(),
            )
        })?;
        let mut order = Vec::with_capacity(3);
        for name in flat.var_names() {
            order.push(match name.as_str() {
                "x" => Variable::X,
                "y" => Variable::Y,
                "t" => Variable::T,
                other => {
                    return Err(InputError::new(
                        field,
                        format!("\"{text}\""),
                        format!("an expression of x, y, t only (unknown variable `{other}`)"),
                    ))
                }
            });
        }
        let expression = Self {
            text: text.to_string(),
            flat: Arc::new(flat),
            order,
        };
        let probe = expression.eval(0.25, 0.25, 0.25);
        if probe.is_nan()
            && expression
                .flat
                .eval(&vec![0.25; expression.order.len()])
                .is_err()
        {
            return Err(InputError::new(
                field,
                format!("\"{text}\""),
                "an expression that evaluates",
            ));
        }
        Ok(expression)
    }

    /// The source text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The value at (x, y, t); NaN if the evaluator fails (callers check finiteness).
    #[inline]
    pub fn eval(&self, x: f64, y: f64, t: f64) -> f64 {
        let mut args = [0.0; 3];
        for (slot, var) in args.iter_mut().zip(&self.order) {
            *slot = match var {
                Variable::X => x,
                Variable::Y => y,
                Variable::T => t,
            };
        }
        self.flat
            .eval(&args[..self.order.len()])
            .unwrap_or(f64::NAN)
    }

    fn dependence(&self) -> Dependence {
        Dependence {
            x: self.order.contains(&Variable::X),
            y: self.order.contains(&Variable::Y),
            t: self.order.contains(&Variable::T),
        }
    }
}

/// A closure field with its declared dependence.
pub type FieldFn = Arc<dyn Fn(f64, f64, f64) -> f64 + Send + Sync>;

/// A scalar field f(x, y, t).
#[derive(Clone)]
pub enum Field {
    /// A constant.
    Constant(f64),
    /// A parsed expression.
    Expression(Expression),
    /// A closure f(x, y, t) and the variables it depends on.
    Function(FieldFn, Dependence),
}

impl Field {
    /// A closure field; `dependence` must name every variable the closure reads.
    pub fn function(
        dependence: Dependence,
        f: impl Fn(f64, f64, f64) -> f64 + Send + Sync + 'static,
    ) -> Self {
        Field::Function(Arc::new(f), dependence)
    }

    /// The value at (x, y, t).
    #[inline]
    pub fn eval(&self, x: f64, y: f64, t: f64) -> f64 {
        match self {
            Field::Constant(c) => *c,
            Field::Expression(e) => e.eval(x, y, t),
            Field::Function(f, _) => f(x, y, t),
        }
    }

    /// The variables the field depends on.
    pub fn dependence(&self) -> Dependence {
        match self {
            Field::Constant(_) => Dependence::default(),
            Field::Expression(e) => e.dependence(),
            Field::Function(_, d) => *d,
        }
    }

    /// The constant value, if the field is constant.
    pub fn as_constant(&self) -> Option<f64> {
        match self {
            Field::Constant(c) => Some(*c),
            _ => None,
        }
    }

    /// Checks that a constant is finite (expressions and closures are checked where evaluated).
    pub fn validate(&self, field: &str) -> Result<(), InputError> {
        match self {
            Field::Constant(c) if !c.is_finite() => Err(InputError::new(
                field,
                c,
                "a finite number or an expression of x, y, t",
            )),
            _ => Ok(()),
        }
    }
}

impl From<f64> for Field {
    fn from(c: f64) -> Self {
        Field::Constant(c)
    }
}

impl fmt::Debug for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Field::Constant(c) => write!(f, "{c}"),
            Field::Expression(e) => write!(f, "\"{}\"", e.text),
            Field::Function(_, d) => write!(f, "<function of {d:?}>"),
        }
    }
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    //! Fields: parsing, variable detection and evaluation order of scene expressions.
    use super::*;

    #[test]
    fn expression_maps_variables_by_name_not_position() {
        let e = Expression::parse("f", "10*x + t^2 - y").unwrap();
        assert_eq!(e.eval(0.5, 2.0, 3.0), 10.0 * 0.5 + 9.0 - 2.0);
        let f = Field::Expression(e);
        assert_eq!(
            f.dependence(),
            Dependence {
                x: true,
                y: true,
                t: true
            }
        );
    }

    #[test]
    fn time_only_expression_is_detected() {
        let f = Field::Expression(Expression::parse("p0", "2 + sin(t)").unwrap());
        assert_eq!(
            f.dependence(),
            Dependence {
                x: false,
                y: false,
                t: true
            }
        );
        assert!((f.eval(7.0, 0.0, 0.3) - (2.0 + 0.3f64.sin())).abs() < 1e-15);
    }

    #[test]
    fn unknown_variable_is_an_input_error_naming_the_field() {
        let err = Expression::parse("rod.load", "3*z").err().unwrap();
        assert_eq!(err.field, "rod.load");
        assert!(err.expected.contains('z'), "{err}");
    }

    #[test]
    fn an_overlong_expression_is_refused_before_parsing() {
        let text = vec!["x"; 25_000].join("+");
        let err = Expression::parse("traction[0].value[1]", &text)
            .err()
            .unwrap();
        assert_eq!(err.field, "traction[0].value[1]");
        assert!(err.expected.contains("at most 4000 characters"), "{err}");
        assert!(Expression::parse("rod.load", &vec!["x"; 1000].join("+")).is_ok());
    }

    #[test]
    fn syntax_error_is_an_input_error_with_its_position() {
        let err = Expression::parse("rod.load", "3*(x").err().unwrap();
        assert_eq!(err.field, "rod.load");
        assert!(err.expected.contains("position 3"), "{err}");
    }

    #[test]
    fn scientific_notation_evaluates_as_toml_reads_it() {
        for (text, t, want) in [
            ("1e-3*t + 10", 2.0, 1e-3 * 2.0 + 10.0),
            ("10 + 2.5e2*t", 2.0, 10.0 + 2.5e2 * 2.0),
            ("10 + 1E-3*t", 2.0, 10.0 + 1e-3 * 2.0),
            ("1_000.5*t", 2.0, 2001.0),
            ("6.02e+23 / 1e23", 0.0, 6.02e23 / 1e23),
            ("2*e", 0.0, 2.0 * std::f64::consts::E),
            ("2^-2*t", 4.0, 1.0),
        ] {
            let e = Expression::parse("load", text).unwrap();
            assert_eq!(e.eval(0.0, 0.0, t), want, "{text}");
        }
    }

    #[test]
    fn non_finite_constant_is_rejected() {
        assert!(Field::Constant(f64::NAN).validate("rod.load").is_err());
        assert!(Field::Constant(1.0).validate("rod.load").is_ok());
    }
}
