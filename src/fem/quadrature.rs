//! Gauss–Legendre quadrature: n points integrate polynomials of degree 2n − 1 exactly.

use crate::error::InputError;

/// Gauss–Legendre points and weights on the reference interval (−1, 1).
#[derive(Debug, Clone, PartialEq)]
pub struct GaussLegendre {
    points: Vec<f64>,
    weights: Vec<f64>,
}

impl GaussLegendre {
    /// The n-point rule, 1 ≤ n ≤ 64: points are the roots of the Legendre polynomial P_n, found by
    /// Newton's method from Chebyshev guesses to round-off; weights w_i = 2 / ((1 − x_i²) P_n'(x_i)²).
    pub fn new(n: usize) -> Result<Self, InputError> {
        if !(1..=64).contains(&n) {
            return Err(InputError::new("quadrature.points", n, "1 to 64 points"));
        }
        let mut points = vec![0.0; n];
        let mut weights = vec![0.0; n];
        for i in 0..n.div_ceil(2) {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (p, d) = legendre(n, x);
                dp = d;
                let dx = p / d;
                x -= dx;
                if dx.abs() <= 1e-16 {
                    break;
                }
            }
            let (_, d) = legendre(n, x);
            if d != 0.0 {
                dp = d;
            }
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            points[i] = -x;
            points[n - 1 - i] = x;
            weights[i] = w;
            weights[n - 1 - i] = w;
        }
        if n % 2 == 1 {
            points[n / 2] = 0.0;
        }
        Ok(Self { points, weights })
    }

    /// Points on (−1, 1).
    pub fn points(&self) -> &[f64] {
        &self.points
    }

    /// Weights (summing to 2).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// ∫_a^b f dx.
    #[inline]
    pub fn integrate(&self, a: f64, b: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (a + b);
        self.points
            .iter()
            .zip(&self.weights)
            .map(|(&s, &w)| w * f(mid + half * s))
            .sum::<f64>()
            * half
    }
}

/// (P_n(x), P_n'(x)) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    if n == 0 {
        return (1.0, 0.0);
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

#[cfg(test)]
mod tests {
    //! Gauss–Legendre: exactness degree 2n − 1 and failure at degree 2n, for n = 1..12.
    use super::*;

    #[test]
    fn n_points_integrate_degree_2n_minus_1_exactly() {
        for n in 1..=12 {
            let q = GaussLegendre::new(n).unwrap();
            for deg in 0..2 * n {
                let exact = if deg % 2 == 0 {
                    2.0 / (deg as f64 + 1.0)
                } else {
                    0.0
                };
                let got = q.integrate(-1.0, 1.0, |x| x.powi(deg as i32));
                assert!(
                    (got - exact).abs() < 1e-14,
                    "n = {n}, degree {deg}: {got} vs {exact}"
                );
            }
            if n <= 6 {
                let deg = 2 * n;
                let got = q.integrate(-1.0, 1.0, |x| x.powi(deg as i32));
                let gap = (got - 2.0 / (deg as f64 + 1.0)).abs();
                assert!(
                    gap > 1e-10,
                    "n = {n} should not be exact at degree 2n (gap {gap})"
                );
            }
        }
    }

    #[test]
    fn mapped_interval_integral() {
        let q = GaussLegendre::new(3).unwrap();
        assert!((q.integrate(1.0, 3.0, |x| x * x) - 26.0 / 3.0).abs() < 1e-13);
    }

    #[test]
    fn zero_points_is_an_error() {
        assert!(GaussLegendre::new(0).is_err());
    }
}
