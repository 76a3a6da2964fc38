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
    /// `residual` and `tolerance` are on the same scale, so they compare like with like: both
    /// relative to the residual's scale (the plane and multibody steps; there `tolerance` is the
    /// effective threshold max(requested tolerance, computed round-off floor)) or both absolute
    /// (the rod's scalar contact equation).
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
    /// The active set of a contact problem kept changing between the same states: the
    /// semismooth Newton method cycled instead of converging.
    #[error(
        "step {step} (t = {time}): the contact active set cycles (period {period}, {iterations} \
         iterations, residual {residual:e}); changing constraints: {constraints} — a smaller step, \
         or penalty enforcement, usually settles it"
    )]
    ActiveSetCycle {
        step: usize,
        time: f64,
        iterations: usize,
        residual: f64,
        period: usize,
        /// The constraints whose state changed within the cycle (slave node and master).
        constraints: String,
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
    /// The dynamic step's Newton method reached its iteration cap with the residual above both
    /// the requested tolerance and the residual's computed round-off floor. All three numbers are
    /// relative to the same scale s (the largest term of R); `row` is the unknown whose residual
    /// exceeds its own floor the most, by `excess`.
    #[error(
        "step {step} (t = {time}): the dynamic step's Newton method did not converge in \
         {iterations} iterations: relative residual ‖R‖∞/s = {residual:e} above the relative \
         tolerance {tolerance:e} and the relative round-off floor {floor:e} (unknown {row}'s \
         residual is {excess:.3e} times its floor)"
    )]
    DynamicNewtonNotConverged {
        step: usize,
        time: f64,
        iterations: usize,
        residual: f64,
        tolerance: f64,
        floor: f64,
        row: usize,
        excess: f64,
    },
    /// An energy–momentum multibody run whose energy rose, beyond the audit's tolerance, without
    /// external or friction work to supply it: a constraint that activated or switched segment did
    /// positive work λ (g₁ − g₀) > 0 (a node re-activated from inside the master; the work is
    /// −λ g₀ ≤ 0 only from outside, docs/multibody.md §4).
    #[error(
        "step {step} (t = {time}): the energy rose to E = {energy:e} = {ratio} E_0 (E_0 = \
         {initial:e}) with no external or friction work to supply it ({rise:e} beyond the work \
         done, tolerance {tolerance:e}): {constraint} did the {kind} work {work:e} > 0 (it \
         re-entered the master from inside; the work λ (g₁ − g₀) is −λ g₀ ≤ 0 only from outside) \
         — a smaller step, two-pass contact, or `allow_energy_gain = true` in its \
         [[contact_pair]] to accept the gain"
    )]
    EnergyGain {
        step: usize,
        time: f64,
        /// E_n and E_0, and E_n / E_0.
        energy: f64,
        initial: f64,
        ratio: f64,
        /// E_n − E_0 − Σ (W_ext + W_T) and its tolerance.
        rise: f64,
        tolerance: f64,
        /// The constraint that did the largest positive work in the step ("pair 0 slave node 10
        /// on segment 0"), `"activation"` or `"segment-switch"`, and the work.
        constraint: String,
        kind: String,
        work: f64,
    },
}

/// A mesh file (Gmsh `.msh`) that cannot be used: which file, where in it, what is wrong.
///
/// Displayed as `mesh file <file>: <location>: <problem>`; the location names the element or node
/// by its tag in the file (`element 17 (surface 1)`, `node 4`), a physical group by its name, or a
/// byte offset for a syntax error.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("mesh file {file}: {location}: {problem}")]
pub struct MeshFileError {
    /// The file as given (a path, or a label for bytes).
    pub file: String,
    /// Where: `element 17 (surface 1)`, `node 4`, `physical group "seal"`, `byte 120`, `file`.
    pub location: String,
    /// What is wrong.
    pub problem: MeshProblem,
}

/// What is wrong with a mesh file ([`MeshFileError`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshProblem {
    /// The file cannot be read.
    #[error("cannot be read: {0}")]
    Io(String),
    /// The text or bytes do not follow the format.
    #[error("not a valid .msh file: {0}")]
    Syntax(String),
    /// A format version or variant that is not read.
    #[error("format {0} is not read (formats read: 4.1 ASCII and binary, 2.2 ASCII)")]
    UnsupportedFormat(String),
    /// A count beyond what the file's length can hold, or beyond the hard maximum.
    #[error("{what} = {count} exceeds {limit}")]
    TooLarge {
        what: String,
        count: u64,
        limit: String,
    },
    /// An element type other than 3-node triangles, 2-node lines and points.
    #[error(
        "element type {code} ({name}) is not supported: only 3-node triangles (and 2-node lines \
         of boundary groups; points are ignored)"
    )]
    UnsupportedElement { code: u32, name: String },
    /// An element that names a node the file does not define.
    #[error("refers to node {0}, which the file does not define")]
    UnknownNode(u64),
    /// A node off the plane z = 0.
    #[error("z = {z:e}: expected a plane mesh in z = 0 (|z| <= {tolerance:e})")]
    NotPlanar { z: f64, tolerance: f64 },
    /// A triangle whose area is zero to the stated tolerance.
    #[error(
        "degenerate triangle (nodes {nodes:?}): |area| = {area:e} <= {tolerance:e} \
         (1e-12 h², h the longest triangle edge of the mesh)"
    )]
    DegenerateTriangle {
        nodes: [u64; 3],
        area: f64,
        tolerance: f64,
    },
    /// Two nodes at the same position.
    #[error(
        "node {node} and node {other} are duplicates: distance {distance:e} <= {tolerance:e} \
         (1e-12 × the bounding box diagonal)"
    )]
    DuplicateNode {
        node: u64,
        other: u64,
        distance: f64,
        tolerance: f64,
    },
    /// Nodes used by no triangle.
    #[error("{count} node(s) used by no triangle (first: {first:?})")]
    UnusedNodes { count: usize, first: Vec<u64> },
    /// A line of a boundary group that is not a boundary edge of the triangles.
    #[error("the line (nodes {nodes:?}) of physical group \"{group}\" is not a boundary edge of the mesh")]
    NotOnBoundary { group: String, nodes: [u64; 2] },
    /// An edge shared by more than two triangles.
    #[error("the edge (nodes {nodes:?}) is shared by {triangles} triangles: a non-manifold mesh")]
    NonManifoldEdge { nodes: [u64; 2], triangles: usize },
    /// A boundary node where more than two boundary edges meet (two parts touching at a point).
    #[error("{edges} boundary edges meet at this node: a non-manifold boundary")]
    NonManifoldNode { edges: usize },
    /// No triangles.
    #[error("no 3-node triangles (a 2D physical group must contain the surface)")]
    NoTriangles,
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
    /// A mesh file that cannot be used.
    #[error(transparent)]
    Mesh(#[from] MeshFileError),
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
