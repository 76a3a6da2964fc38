//! A time grid 0 = t_0 < … < t_N = T with steps k_n = t_n − t_{n−1} (Fernández & Sofonea 2004, §3:
//! a nonuniform partition of [0, T]).

use crate::error::{require_increasing_from_zero, require_positive, InputError};

/// The time grid of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeGrid {
    times: Vec<f64>,
}

impl TimeGrid {
    /// N equal steps: t_n = T n / N (computed from n, so t_N = T exactly).
    pub fn uniform(final_time: f64, steps: usize) -> Result<Self, InputError> {
        require_positive("time.final_time", final_time)?;
        require_steps(steps)?;
        let n = steps as f64;
        Ok(Self {
            times: (0..=steps).map(|i| final_time * (i as f64) / n).collect(),
        })
    }

    /// Power-law graded steps t_n = T (n/N)^q, q ≥ 1: small steps near t = 0 where an initial
    /// layer lives.
    pub fn graded(final_time: f64, steps: usize, exponent: f64) -> Result<Self, InputError> {
        require_positive("time.final_time", final_time)?;
        require_steps(steps)?;
        if !(exponent.is_finite() && (1.0..=10.0).contains(&exponent)) {
            return Err(InputError::new(
                "time.grading",
                exponent,
                "a number in [1, 10]",
            ));
        }
        let n = steps as f64;
        let mut times: Vec<f64> = (0..=steps)
            .map(|i| final_time * (i as f64 / n).powf(exponent))
            .collect();
        times[steps] = final_time;
        Self::from_times(times)
    }

    /// A grid from explicit times: finite, starting at 0, strictly increasing, at least one step.
    pub fn from_times(times: Vec<f64>) -> Result<Self, InputError> {
        require_increasing_from_zero("time.times", &times, 2, "times (1 step)")?;
        Ok(Self { times })
    }

    /// t_0, …, t_N.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The number of steps N.
    pub fn steps(&self) -> usize {
        self.times.len() - 1
    }

    /// T = t_N.
    pub fn final_time(&self) -> f64 {
        self.times[self.times.len() - 1]
    }

    /// k_n = t_n − t_{n−1}, n ≥ 1.
    #[inline]
    pub fn step(&self, n: usize) -> f64 {
        self.times[n] - self.times[n - 1]
    }

    /// The largest step, the k of the error estimates.
    pub fn k_max(&self) -> f64 {
        self.times
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(0.0, f64::max)
    }

    /// The index n with t_n = t up to 1e−9 T, if any.
    pub fn index_of(&self, t: f64) -> Option<usize> {
        let tol = 1e-9 * self.final_time();
        let idx = self.times.partition_point(|&tn| tn < t - tol);
        (idx < self.times.len() && (self.times[idx] - t).abs() <= tol).then_some(idx)
    }
}

fn require_steps(steps: usize) -> Result<(), InputError> {
    if steps == 0 {
        Err(InputError::new("time.steps", 0, "at least 1 step"))
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! Time grids: exact end time, grading, validation, lookup of output times.
    use super::*;

    #[test]
    fn uniform_grid_ends_exactly_at_t() {
        let g = TimeGrid::uniform(0.5, 50).unwrap();
        assert_eq!(g.final_time(), 0.5);
        assert_eq!(g.steps(), 50);
        assert!((g.step(7) - 0.01).abs() < 1e-15);
    }

    #[test]
    fn index_of_finds_grid_times_only() {
        let g = TimeGrid::uniform(0.5, 50).unwrap();
        assert_eq!(g.index_of(0.25), Some(25));
        assert_eq!(g.index_of(0.0), Some(0));
        assert_eq!(g.index_of(0.5), Some(50));
        assert_eq!(g.index_of(0.255), None);
    }

    #[test]
    fn graded_grid_is_increasing_and_ends_at_t() {
        let g = TimeGrid::graded(1.0, 20, 2.0).unwrap();
        assert_eq!(g.final_time(), 1.0);
        assert!(g.step(1) < g.step(20));
    }

    #[test]
    fn zero_steps_and_bad_times_are_rejected() {
        assert_eq!(TimeGrid::uniform(1.0, 0).unwrap_err().field, "time.steps");
        assert_eq!(
            TimeGrid::uniform(-1.0, 3).unwrap_err().field,
            "time.final_time"
        );
        assert_eq!(
            TimeGrid::from_times(vec![0.0, 0.2, 0.1]).unwrap_err().field,
            "time.times[2]"
        );
    }
}
