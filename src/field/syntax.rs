//! The grammar of a scene expression, checked before the evaluator sees the text, so that a
//! mistake is reported in our words with its character position.
//!
//! ```text
//! sum     := product (('+' | '-') product)*
//! product := unary (('*' | '/') unary)*
//! unary   := ('+' | '-') unary | power
//! power   := atom ('^' unary)?
//! atom    := number | x | y | t | constant | function '(' sum ')'
//!          | binary '(' sum ',' sum ')' | '(' sum ')'
//! number  := digits ('.' digits?)? exponent? | '.' digits exponent?
//! digits  := [0-9] ('_'? [0-9])*        exponent := ('e' | 'E') ('+' | '-')? digits
//! ```
//!
//! A number is every float literal a TOML number accepts (`1e-3`, `2.5E+2`, `1_000.5`; signs are
//! the unary operators), plus the forms `.5` and `5.` that scene files have always accepted.
//! Positions count characters from 1.

use exmex::MatchLiteral;

/// The variables an expression may read.
pub const VARIABLES: [&str; 3] = ["x", "y", "t"];
/// Named constants (π, e, τ).
pub const CONSTANTS: [&str; 6] = ["PI", "π", "E", "e", "TAU", "τ"];
/// Functions of one argument.
pub const FUNCTIONS: [&str; 26] = [
    "abs", "signum", "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "asinh",
    "acosh", "atanh", "floor", "round", "ceil", "trunc", "fract", "exp", "sqrt", "cbrt", "ln",
    "log2", "log10", "log",
];
/// Functions of two arguments, written `name(a, b)`.
pub const BINARY_FUNCTIONS: [&str; 3] = ["atan2", "min", "max"];

/// Length in bytes of the number literal at the start of `text`, with its exponent; `None` if
/// `text` does not start with one. A trailing `e` without digits is not part of the literal.
pub fn number_length(text: &str) -> Option<usize> {
    let b = text.as_bytes();
    let digits = |mut i: usize| -> usize {
        if i >= b.len() || !b[i].is_ascii_digit() {
            return i;
        }
        i += 1;
        while i < b.len() {
            if b[i].is_ascii_digit() {
                i += 1;
            } else if b[i] == b'_' && i + 1 < b.len() && b[i + 1].is_ascii_digit() {
                i += 2;
            } else {
                break;
            }
        }
        i
    };
    let int_end = digits(0);
    let mut end = int_end;
    if end < b.len() && b[end] == b'.' {
        let frac_end = digits(end + 1);
        if int_end == 0 && frac_end == end + 1 {
            return None;
        }
        end = frac_end;
    }
    if end == 0 {
        return None;
    }
    if end < b.len() && (b[end] == b'e' || b[end] == b'E') {
        let mut i = end + 1;
        if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
            i += 1;
        }
        let exp_end = digits(i);
        if exp_end > i {
            end = exp_end;
        }
    }
    Some(end)
}

/// The evaluator's literal matcher: our number grammar, without the digit separators (which
/// [`normalized`] removes before the evaluator parses the text).
#[derive(Clone, Debug)]
pub struct TomlNumber;

impl MatchLiteral for TomlNumber {
    fn is_literal(text: &str) -> Option<&str> {
        number_length(text).map(|n| &text[..n])
    }
}

/// `text` with the digit separators of its number literals removed (`1_000` → `1000`).
pub fn normalized(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    let mut after_name = false;
    while let Some(c) = rest.chars().next() {
        if !after_name {
            if let Some(n) = number_length(rest) {
                out.extend(rest[..n].chars().filter(|&c| c != '_'));
                rest = &rest[n..];
                continue;
            }
        }
        after_name = c.is_alphanumeric() || c == '_';
        out.push(c);
        rest = &rest[c.len_utf8()..];
    }
    out
}

#[derive(Clone, Debug, PartialEq)]
enum Token<'a> {
    Number(&'a str),
    Name(&'a str),
    Operator(char),
    Open,
    Close,
    Comma,
    End,
}

impl Token<'_> {
    fn describe(&self) -> String {
        match self {
            Token::Number(s) => format!("the number `{s}`"),
            Token::Name(s) => format!("`{s}`"),
            Token::Operator(c) => format!("`{c}`"),
            Token::Open => "`(`".into(),
            Token::Close => "`)`".into(),
            Token::Comma => "`,`".into(),
            Token::End => "the end of the expression".into(),
        }
    }
}

/// A token and its character position (from 1).
type Located<'a> = (Token<'a>, usize);

/// A syntax mistake: what is wrong, in words, with its character position.
pub type SyntaxError = String;

fn tokens(text: &str) -> Result<Vec<Located<'_>>, SyntaxError> {
    let mut out = Vec::new();
    let mut byte = 0;
    while byte < text.len() {
        let rest = &text[byte..];
        let position = text[..byte].chars().count() + 1;
        let c = rest.chars().next().unwrap_or(' ');
        let (token, len) = if c.is_whitespace() {
            byte += c.len_utf8();
            continue;
        } else if let Some(n) = number_length(rest) {
            let tail = &rest[n..];
            if tail.starts_with(['e', 'E'])
                && !tail[1..].starts_with(|c: char| c.is_alphanumeric() || c == '_')
            {
                return Err(format!(
                    "the number `{}` at position {position} has an exponent without digits \
                     (write e.g. {}e3, or {}*e for Euler's number)",
                    &rest[..=n],
                    &rest[..n],
                    &rest[..n]
                ));
            }
            (Token::Number(&rest[..n]), n)
        } else if c.is_alphabetic() || c == '_' {
            let n = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            (Token::Name(&rest[..n]), n)
        } else {
            let token = match c {
                '+' | '-' | '*' | '/' | '^' => Token::Operator(c),
                '(' => Token::Open,
                ')' => Token::Close,
                ',' => Token::Comma,
                _ => {
                    return Err(format!(
                        "the character `{c}` at position {position} is not part of an expression \
                         (numbers, x, y, t, + - * / ^, parentheses and functions such as sin)"
                    ))
                }
            };
            (token, c.len_utf8())
        };
        out.push((token, position));
        byte += len;
    }
    out.push((Token::End, text.chars().count() + 1));
    Ok(out)
}

struct Parser<'a> {
    tokens: Vec<Located<'a>>,
    next: usize,
}

impl<'a> Parser<'a> {
    fn peek(&self) -> &Located<'a> {
        &self.tokens[self.next.min(self.tokens.len() - 1)]
    }

    fn bump(&mut self) -> Located<'a> {
        let t = self.peek().clone();
        self.next += 1;
        t
    }

    fn sum(&mut self) -> Result<(), SyntaxError> {
        self.product()?;
        while matches!(self.peek().0, Token::Operator('+' | '-')) {
            self.bump();
            self.product()?;
        }
        Ok(())
    }

    fn product(&mut self) -> Result<(), SyntaxError> {
        self.unary()?;
        while matches!(self.peek().0, Token::Operator('*' | '/')) {
            self.bump();
            self.unary()?;
        }
        Ok(())
    }

    fn unary(&mut self) -> Result<(), SyntaxError> {
        if matches!(self.peek().0, Token::Operator('+' | '-')) {
            self.bump();
            return self.unary();
        }
        self.atom()?;
        if matches!(self.peek().0, Token::Operator('^')) {
            self.bump();
            self.unary()?;
        }
        Ok(())
    }

    fn expect_close(&mut self, open_at: usize) -> Result<(), SyntaxError> {
        match self.bump() {
            (Token::Close, _) => Ok(()),
            (Token::End, _) => Err(format!(
                "the `(` at position {open_at} is never closed (a `)` is missing)"
            )),
            (other, at) => Err(format!(
                "expected `)` (closing the `(` at position {open_at}) or an operator at position \
                 {at}, found {}",
                other.describe()
            )),
        }
    }

    fn arguments(&mut self, name: &str, at: usize) -> Result<(), SyntaxError> {
        let binary = BINARY_FUNCTIONS.contains(&name);
        match self.bump() {
            (Token::Open, open_at) => {
                self.sum()?;
                if binary {
                    match self.bump() {
                        (Token::Comma, _) => self.sum()?,
                        (other, at2) => {
                            return Err(format!(
                                "`{name}` at position {at} takes two arguments `{name}(a, b)`; \
                                 expected `,` at position {at2}, found {}",
                                other.describe()
                            ))
                        }
                    }
                }
                self.expect_close(open_at)
            }
            (other, at2) => Err(format!(
                "the function `{name}` at position {at} needs its argument in parentheses \
                 (`{name}(…)`), found {} at position {at2}",
                other.describe()
            )),
        }
    }

    fn atom(&mut self) -> Result<(), SyntaxError> {
        match self.bump() {
            (Token::Number(_), _) => Ok(()),
            (Token::Name(n), _) if VARIABLES.contains(&n) || CONSTANTS.contains(&n) => Ok(()),
            (Token::Name(n), at) if FUNCTIONS.contains(&n) || BINARY_FUNCTIONS.contains(&n) => {
                self.arguments(n, at)
            }
            (Token::Name(n), at) if ["inf", "nan", "infinity"].contains(&n) => Err(format!(
                "`{n}` at position {at}: an expression takes finite numbers only"
            )),
            (Token::Name(n), at) => Err(format!(
                "unknown name `{n}` at position {at} (the variables are x, y, t; the constants \
                 PI, E, TAU; functions such as sin, exp, sqrt, abs)"
            )),
            (Token::Open, open_at) => {
                self.sum()?;
                self.expect_close(open_at)
            }
            (Token::End, at) => Err(format!(
                "the expression ends at position {at} where a number, a variable or `(` is \
                 expected"
            )),
            (other, at) => Err(format!(
                "expected a number, a variable (x, y, t), a function or `(` at position {at}, \
                 found {}",
                other.describe()
            )),
        }
    }
}

/// Checks `text` against the grammar; the error says what is wrong and where.
pub fn check(text: &str) -> Result<(), SyntaxError> {
    let mut parser = Parser {
        tokens: tokens(text)?,
        next: 0,
    };
    if parser.tokens.len() == 1 {
        return Err("the expression is empty".into());
    }
    parser.sum()?;
    match parser.bump() {
        (Token::End, _) => Ok(()),
        (Token::Close, at) => Err(format!("the `)` at position {at} closes no `(`")),
        (other, at) => Err(format!(
            "an operator is missing before {} at position {at} (write `*` for a product)",
            other.describe()
        )),
    }
}

#[cfg(test)]
mod tests {
    //! The number grammar and the positions of syntax mistakes.
    use super::*;

    #[test]
    fn every_toml_float_form_is_one_number() {
        for (text, len) in [
            ("1e-3*t", 4),
            ("2.5e2", 5),
            ("1E-3", 4),
            ("6.626e-34", 9),
            ("1e+06", 5),
            ("224_617.445_991_228", 19),
            ("1_000", 5),
            ("3.1415", 6),
            (".5", 2),
            ("5.", 2),
            ("5.e3", 4),
        ] {
            assert_eq!(number_length(text), Some(len), "{text}");
        }
        assert_eq!(number_length("e3"), None);
        assert_eq!(number_length("."), None);
        assert_eq!(number_length("_1"), None);
        assert_eq!(number_length("1_"), Some(1));
        assert_eq!(number_length("2e"), Some(1));
    }

    #[test]
    fn separators_are_removed_from_numbers_only() {
        assert_eq!(normalized("1_000*t + 2.5e2"), "1000*t + 2.5e2");
        assert_eq!(normalized("sin(1_0.0_1)"), "sin(10.01)");
    }

    #[test]
    fn mistakes_name_their_position_in_our_words() {
        let cases = [
            ("3*(x", "position 3 is never closed"),
            ("x)", "`)` at position 2 closes no"),
            ("2x", "missing before `x` at position 2"),
            ("1e*t", "exponent without digits"),
            ("3*z", "unknown name `z` at position 3"),
            ("x +", "ends at position 4"),
            ("sin x", "needs its argument in parentheses"),
            ("x $ 2", "character `$` at position 3"),
            ("", "empty"),
            ("inf*t", "finite numbers only"),
            ("atan2(x)", "two arguments"),
        ];
        for (text, words) in cases {
            let e = check(text).err().unwrap_or_default();
            assert!(e.contains(words), "{text}: {e}");
            assert!(!e.contains("node") && !e.contains("op."), "{text}: {e}");
        }
    }

    #[test]
    fn the_examples_forms_pass() {
        for text in [
            "1e-3*t + 10",
            "10 + 2.5e2*t",
            "10 + 1E-3*t",
            "-x^2 + sin(2*PI*t)",
            "min(x, 2) + atan2(y, x)",
            "-(-t)",
            "2^-3",
            "e*x",
        ] {
            assert!(check(text).is_ok(), "{text}: {:?}", check(text));
        }
    }
}
