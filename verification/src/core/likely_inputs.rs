//! The inputs a solver failure most likely comes from, named as the user wrote them.
//!
//! A step that does not converge, a singular or indefinite matrix, an active set that cycles:
//! the solver finds the problem at a step, far from the keys that caused it. What sets a step's
//! difficulty is its scales — the step k = T/N against the body's wave and contact times, the
//! stiffness of the material and of a penalty against the inertia, the loads — so a failure's
//! message ends with those keys and their values as written, the first place to look.

/// `"; the inputs that set the step's scales (check these first): k₁ = v₁, k₂ = v₂, …"`; empty
/// when there is none.
pub fn clause(inputs: &[(String, String)]) -> String {
    if inputs.is_empty() {
        return String::new();
    }
    let list = inputs
        .iter()
        .map(|(k, v)| format!("{k} = {v}"))
        .collect::<Vec<_>>()
        .join(", ");
    format!("; the inputs that set the step's scales (check these first): {list}")
}

/// `(key, value)` for an optional number.
pub fn optional(key: &str, value: Option<f64>) -> Option<(String, String)> {
    value.map(|v| (key.to_string(), v.to_string()))
}

/// The time grid's keys: final time and steps, with the step k = T/N they give.
pub fn time_grid(final_time: f64, steps: Option<usize>) -> Vec<(String, String)> {
    let mut v = vec![("time.final_time".to_string(), final_time.to_string())];
    if let Some(n) = steps {
        v.push((
            "time.steps".to_string(),
            format!("{n} (k = {:e})", final_time / n.max(1) as f64),
        ));
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_clause_lists_each_key_with_its_value_and_the_step() {
        let mut inputs = time_grid(2.0, Some(4));
        inputs.extend(optional("contact.stiffness", Some(1e13)));
        inputs.extend(optional("contact.depth", None));
        let c = clause(&inputs);
        assert_eq!(
            c,
            "; the inputs that set the step's scales (check these first): time.final_time = 2, \
             time.steps = 4 (k = 5e-1), contact.stiffness = 10000000000000"
        );
        assert_eq!(clause(&[]), "");
    }
}
