//! Eigenvalue branches along a parameter sweep (loci, Campbell diagrams).
//!
//! At each new parameter value s_i the eigenvalues are matched to the branches by predicting
//! every branch linearly from its last two points, λ̂ = λ_{i−1} + (λ_{i−1} − λ_{i−2}) (s_i −
//! s_{i−1}) / (s_{i−1} − s_{i−2}), and solving the assignment problem
//! min_π Σ_b |λ_{π(b)} − λ̂_b| exactly (Hungarian algorithm, Kuhn 1955 / Munkres 1957, O(n³)).
//! The linear predictor carries branches straight through crossings (where nearest-neighbour
//! matching swaps them); the global assignment never maps two branches to one eigenvalue.

use faer::c64;
use serde::Serialize;

use crate::error::InputError;

/// The branches of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EigenBranches {
    /// The parameter values s_i.
    pub parameters: Vec<f64>,
    /// `branches[b][i]`: branch b at s_i. Branches are numbered by the eigenvalues at s_0 sorted
    /// by imaginary part, then real part ([Re, Im] pairs in JSON).
    #[serde(serialize_with = "crate::model::moving::serialize_complex_rows")]
    pub branches: Vec<Vec<c64>>,
    /// The largest |λ − λ̂| of an assigned eigenvalue, relative to the spectral scale at that
    /// step (a measure of how far the predictor had to reach; small means unambiguous).
    pub max_relative_prediction_error: f64,
}

/// Tracks the branches through `steps[i]` (the eigenvalues at `parameters[i]`; all of the same
/// length; the parameters strictly monotone).
pub fn track_branches(parameters: &[f64], steps: &[Vec<c64>]) -> Result<EigenBranches, InputError> {
    if parameters.len() != steps.len() || steps.is_empty() {
        return Err(InputError::new(
            "sweep.points",
            format!("{} parameters, {} spectra", parameters.len(), steps.len()),
            "one spectrum per parameter value, at least one",
        ));
    }
    let n = steps[0].len();
    for (i, s) in steps.iter().enumerate() {
        if s.len() != n {
            return Err(InputError::new(
                format!("sweep.spectrum[{i}]"),
                format!("{} eigenvalues", s.len()),
                format!("{n} eigenvalues, as at the first point"),
            ));
        }
    }
    for i in 1..parameters.len() {
        let (d, d0) = (
            parameters[i] - parameters[i - 1],
            parameters[1] - parameters[0],
        );
        if !(d.is_finite() && d != 0.0 && d.signum() == d0.signum()) {
            return Err(InputError::new(
                format!("sweep.parameters[{i}]"),
                parameters[i],
                "strictly monotone finite parameter values",
            ));
        }
    }
    let mut first = steps[0].clone();
    first.sort_by(|a, b| a.im.total_cmp(&b.im).then(a.re.total_cmp(&b.re)));
    let mut branches: Vec<Vec<c64>> = first.iter().map(|&l| vec![l]).collect();
    let mut worst = 0.0f64;
    let mut cost = vec![vec![0.0; n]; n];
    for i in 1..steps.len() {
        let predicted: Vec<c64> = branches
            .iter()
            .map(|b| {
                if i >= 2 {
                    let r = (parameters[i] - parameters[i - 1])
                        / (parameters[i - 1] - parameters[i - 2]);
                    b[i - 1] + (b[i - 1] - b[i - 2]) * r
                } else {
                    b[i - 1]
                }
            })
            .collect();
        for (row, p) in cost.iter_mut().zip(&predicted) {
            for (c, l) in row.iter_mut().zip(&steps[i]) {
                let d = (l - p).norm();
                *c = if d.is_finite() { d } else { 1e300 };
            }
        }
        let assignment = hungarian(&cost);
        let scale = steps[i].iter().map(|l| l.norm()).fold(1e-300, f64::max);
        for (b, &j) in assignment.iter().enumerate() {
            worst = worst.max(cost[b][j] / scale);
            branches[b].push(steps[i][j]);
        }
    }
    Ok(EigenBranches {
        parameters: parameters.to_vec(),
        branches,
        max_relative_prediction_error: worst,
    })
}

/// The minimum-cost perfect assignment of a square cost matrix: `result[row] = column`
/// (Hungarian algorithm with potentials, O(n³)).
pub fn hungarian(cost: &[Vec<f64>]) -> Vec<usize> {
    let n = cost.len();
    let inf = f64::INFINITY;
    let mut u = vec![0.0; n + 1];
    let mut v = vec![0.0; n + 1];
    let mut p = vec![0usize; n + 1];
    let mut way = vec![0usize; n + 1];
    for i in 1..=n {
        p[0] = i;
        let mut j0 = 0usize;
        let mut minv = vec![inf; n + 1];
        let mut used = vec![false; n + 1];
        loop {
            used[j0] = true;
            let i0 = p[j0];
            let mut delta = inf;
            let mut j1 = 0usize;
            for j in 1..=n {
                if !used[j] {
                    let cur = cost[i0 - 1][j - 1] - u[i0] - v[j];
                    if cur < minv[j] {
                        minv[j] = cur;
                        way[j] = j0;
                    }
                    if minv[j] < delta {
                        delta = minv[j];
                        j1 = j;
                    }
                }
            }
            for j in 0..=n {
                if used[j] {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
            if j0 == 0 || p[j0] == 0 {
                break;
            }
        }
        while j0 != 0 {
            let j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
        }
    }
    let mut result = vec![0usize; n];
    for j in 1..=n {
        if p[j] > 0 {
            result[p[j] - 1] = j - 1;
        }
    }
    result
}

#[cfg(test)]
mod tests {
    //! Setting: two straight branches that cross, sampled coarsely. Goal: the predictor keeps
    //! each branch on its line through the crossing; the assignment is optimal.
    use super::*;

    #[test]
    fn crossing_branches_are_not_swapped() {
        let s: Vec<f64> = (0..11).map(|i| i as f64 * 0.1).collect();
        // branch A: im = 1 + s, branch B: im = 2 − s; they cross at s = 0.5.
        let steps: Vec<Vec<c64>> = s
            .iter()
            .map(|&x| {
                let mut v = vec![c64::new(0.0, 1.0 + x), c64::new(0.0, 2.0 - x)];
                if x > 0.55 {
                    v.reverse(); // the solver's order changes after the crossing
                }
                v
            })
            .collect();
        let b = track_branches(&s, &steps).unwrap();
        for (i, &x) in s.iter().enumerate() {
            assert!((b.branches[0][i].im - (1.0 + x)).abs() < 1e-12);
            assert!((b.branches[1][i].im - (2.0 - x)).abs() < 1e-12);
        }
    }

    #[test]
    fn hungarian_finds_the_optimal_assignment() {
        let cost = vec![
            vec![4.0, 1.0, 3.0],
            vec![2.0, 0.0, 5.0],
            vec![3.0, 2.0, 2.0],
        ];
        let a = hungarian(&cost);
        let total: f64 = a.iter().enumerate().map(|(i, &j)| cost[i][j]).sum();
        assert_eq!(total, 5.0);
    }

    #[test]
    fn mismatched_spectra_are_input_errors() {
        let e = track_branches(&[0.0, 1.0], &[vec![c64::new(0.0, 1.0)], vec![]]).unwrap_err();
        assert_eq!(e.field, "sweep.spectrum[1]");
    }
}
