//! C¹ Hermite cubic shape functions on an interval element (value and slope at both ends), with
//! their first and second derivatives: the radial basis of the rotating plate and the Hermite
//! basis of the moving string.

/// Hermite shape functions on an element of length h at local t ∈ [0, 1]:
/// (value, d/dr, d²/dr²) of the four local functions (value, slope at the left; at the right).
pub fn hermite_shapes(h: f64, t: f64) -> [[f64; 4]; 3] {
    let (t2, t3) = (t * t, t * t * t);
    [
        [
            1.0 - 3.0 * t2 + 2.0 * t3,
            h * (t - 2.0 * t2 + t3),
            3.0 * t2 - 2.0 * t3,
            h * (t3 - t2),
        ],
        [
            (6.0 * t2 - 6.0 * t) / h,
            1.0 - 4.0 * t + 3.0 * t2,
            (6.0 * t - 6.0 * t2) / h,
            3.0 * t2 - 2.0 * t,
        ],
        [
            (12.0 * t - 6.0) / (h * h),
            (6.0 * t - 4.0) / h,
            (6.0 - 12.0 * t) / (h * h),
            (6.0 * t - 2.0) / h,
        ],
    ]
}

#[cfg(test)]
mod tests {
    //! Setting: an element of length 0.3. Goal: the derivatives of the shapes equal central
    //! differences of the shapes.
    use super::*;

    #[test]
    fn hermite_derivatives_match_finite_differences() {
        let h = 0.3;
        let dt = 1e-6;
        for &t in &[0.1, 0.45, 0.9] {
            let s = hermite_shapes(h, t);
            let (p, m) = (hermite_shapes(h, t + dt), hermite_shapes(h, t - dt));
            for k in 0..4 {
                let d1 = (p[0][k] - m[0][k]) / (2.0 * dt * h);
                let d2 = (p[1][k] - m[1][k]) / (2.0 * dt * h);
                assert!((d1 - s[1][k]).abs() < 1e-7, "d1 {k}");
                assert!((d2 - s[2][k]).abs() < 1e-6, "d2 {k}");
            }
        }
    }
}
