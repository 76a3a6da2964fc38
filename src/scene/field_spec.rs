//! A scene value that is a number or an expression of x, y, t.

use serde::{Deserialize, Serialize};

use crate::error::InputError;
use crate::field::{Expression, Field};

/// `10.0` or `"10*(1 + x*t)"` in a scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum FieldSpec {
    /// A constant.
    Number(f64),
    /// An expression of x, y, t.
    Expression(String),
}

impl FieldSpec {
    /// The field; `field` names the scene key in errors.
    pub fn to_field(&self, field: &str) -> Result<Field, InputError> {
        match self {
            FieldSpec::Number(c) => {
                let f = Field::Constant(*c);
                f.validate(field)?;
                Ok(f)
            }
            FieldSpec::Expression(text) => {
                let e = Expression::parse(field, text)?;
                // A constant written as a string ("6") still takes the constant fast path.
                let d = Field::Expression(e.clone()).dependence();
                if !d.x && !d.y && !d.t {
                    let c = e.eval(0.0, 0.0, 0.0);
                    let f = Field::Constant(c);
                    f.validate(field)?;
                    return Ok(f);
                }
                Ok(Field::Expression(e))
            }
        }
    }
}

impl Default for FieldSpec {
    fn default() -> Self {
        FieldSpec::Number(0.0)
    }
}
