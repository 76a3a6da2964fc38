//! Interval meshes 0 = x_0 < x_1 < … < x_M = L of the rod (0, L).

use serde::{Deserialize, Serialize};

use crate::error::{require_increasing_from_zero, require_positive, InputError};

/// Which end of the interval a graded mesh refines towards.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GradingEnd {
    /// Refine towards x = 0 (the clamped end).
    Start,
    /// Refine towards x = L (the contact end).
    End,
}

/// A mesh of (0, L) by M elements.
#[derive(Debug, Clone, PartialEq)]
pub struct IntervalMesh {
    nodes: Vec<f64>,
}

impl IntervalMesh {
    /// M equal elements: x_i = L i / M (computed from i, not accumulated).
    pub fn uniform(length: f64, elements: usize) -> Result<Self, InputError> {
        require_positive("mesh.length", length)?;
        require_elements(elements)?;
        let m = elements as f64;
        let nodes = (0..=elements).map(|i| length * (i as f64) / m).collect();
        Ok(Self { nodes })
    }

    /// Power-law grading: x_i = L (i/M)^q towards x = 0, or L (1 − (1 − i/M)^q) towards x = L,
    /// with q in [1, 10] (q = 1 is uniform) and ε M^q < 1 (the smallest element's relative
    /// round-off, see below).
    pub fn graded(
        length: f64,
        elements: usize,
        exponent: f64,
        towards: GradingEnd,
    ) -> Result<Self, InputError> {
        require_positive("mesh.length", length)?;
        require_elements(elements)?;
        if !(exponent.is_finite() && (1.0..=10.0).contains(&exponent)) {
            return Err(InputError::new(
                "grading.exponent",
                exponent,
                "a number in [1, 10]",
            ));
        }
        let m = elements as f64;
        // The smallest element L M^(−q) is stored through nodes near L with an absolute error
        // ε L / 2, so its length, and the answer, carry a relative round-off ε M^q (measured by
        // rod_envelope: 6e-8 at q = 2, M = 2·10⁴, where ε M^q = 8.9e-8). Past ε M^q = 1 no digit
        // is right and nodes coincide.
        let round_off = exponent * m.ln() + f64::EPSILON.ln();
        if round_off >= 0.0 {
            let q_max = -f64::EPSILON.ln() / m.ln();
            return Err(InputError::new(
                "grading.exponent",
                exponent,
                format!(
                    "q < {q_max:.2} with {elements} elements: the smallest element L·M^(−q) = \
                     {:.1e} L would carry a relative round-off ε·M^q = {:.1e} ≥ 1 (fewer \
                     elements or a smaller grading)",
                    (-exponent * m.ln()).exp(),
                    round_off.exp()
                ),
            ));
        }
        let mut nodes: Vec<f64> = (0..=elements)
            .map(|i| {
                let s = i as f64 / m;
                match towards {
                    GradingEnd::Start => length * s.powf(exponent),
                    GradingEnd::End => length * (1.0 - (1.0 - s).powf(exponent)),
                }
            })
            .collect();
        nodes[elements] = length;
        Self::from_nodes(nodes)
    }

    /// A mesh from explicit nodes: finite, starting at 0 (the clamped end), strictly increasing,
    /// at least two.
    pub fn from_nodes(nodes: Vec<f64>) -> Result<Self, InputError> {
        require_increasing_from_zero("mesh.nodes", &nodes, 2, "nodes (1 element)")?;
        Ok(Self { nodes })
    }

    /// The nodes x_0, …, x_M.
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// The number of elements M.
    pub fn elements(&self) -> usize {
        self.nodes.len() - 1
    }

    /// L = x_M.
    pub fn length(&self) -> f64 {
        self.nodes[self.nodes.len() - 1]
    }

    /// Element e = (x_e, x_{e+1}).
    #[inline]
    pub fn element(&self, e: usize) -> (f64, f64) {
        (self.nodes[e], self.nodes[e + 1])
    }

    /// The largest element length, the h of the error estimates.
    pub fn h_max(&self) -> f64 {
        self.nodes
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(0.0, f64::max)
    }

    /// The smallest element length.
    pub fn h_min(&self) -> f64 {
        self.nodes
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min)
    }

    /// The element containing x (the last one for x = L); `None` outside [0, L].
    pub fn locate(&self, x: f64) -> Option<usize> {
        if !(x >= 0.0 && x <= self.length()) {
            return None;
        }
        let idx = self.nodes.partition_point(|&xi| xi <= x);
        Some(idx.saturating_sub(1).min(self.elements() - 1))
    }
}

fn require_elements(elements: usize) -> Result<(), InputError> {
    if elements == 0 {
        Err(InputError::new("mesh.elements", 0, "at least 1 element"))
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! Interval meshes: node placement, grading, validation, point location.
    use super::*;

    #[test]
    fn uniform_nodes_are_exact_multiples() {
        let m = IntervalMesh::uniform(1.0, 100).unwrap();
        assert_eq!(m.nodes()[25], 0.25);
        assert_eq!(m.length(), 1.0);
        assert!((m.h_max() - 0.01).abs() < 1e-15);
    }

    #[test]
    fn graded_towards_end_has_smallest_element_at_end() {
        let m = IntervalMesh::graded(2.0, 10, 2.0, GradingEnd::End).unwrap();
        let (a, b) = m.element(9);
        assert!((b - a - m.h_min()).abs() < 1e-15);
        assert_eq!(m.length(), 2.0);
    }

    #[test]
    fn zero_elements_is_an_error_naming_the_field() {
        let err = IntervalMesh::uniform(1.0, 0).unwrap_err();
        assert_eq!(err.field, "mesh.elements");
    }

    #[test]
    fn non_increasing_nodes_are_rejected() {
        let err = IntervalMesh::from_nodes(vec![0.0, 0.5, 0.5, 1.0]).unwrap_err();
        assert_eq!(err.field, "mesh.nodes[2]");
    }

    #[test]
    fn locate_finds_the_containing_element() {
        let m = IntervalMesh::uniform(1.0, 4).unwrap();
        assert_eq!(m.locate(0.0), Some(0));
        assert_eq!(m.locate(0.3), Some(1));
        assert_eq!(m.locate(0.5), Some(2));
        assert_eq!(m.locate(1.0), Some(3));
        assert_eq!(m.locate(1.5), None);
        assert_eq!(m.locate(f64::NAN), None);
    }
}
