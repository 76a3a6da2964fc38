//! Balancing a square matrix before an eigenvalue solve (Parlett & Reinsch 1969; LAPACK's dgebal
//! without permutation): a diagonal similarity A ← D⁻¹ A D with D a product of powers of 2, chosen
//! row by row until no row/column pair's off-diagonal 1-norms c + r shrink by more than 5%. Powers
//! of 2 make the similarity exact in floating point, so the eigenvalues are unchanged while the
//! norm, and with it the eigensolver's backward error, usually drops.

use faer::Mat;

/// A square matrix that can be balanced in place.
pub trait Balance {
    /// The order n.
    fn order(&self) -> usize;
    /// a_ij.
    fn entry(&self, i: usize, j: usize) -> f64;
    /// a_ij ← a_ij / f and a_ji ← a_ji · f for j = 0 … n − 1 (row i divided, column i multiplied).
    fn rescale(&mut self, i: usize, f: f64);
}

impl Balance for Mat<f64> {
    fn order(&self) -> usize {
        self.nrows()
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        self[(i, j)]
    }

    fn rescale(&mut self, i: usize, f: f64) {
        for j in 0..self.nrows() {
            self[(i, j)] /= f;
            self[(j, i)] *= f;
        }
    }
}

/// A row-major n × n matrix in a slice.
#[derive(Debug)]
pub struct RowMajor<'a> {
    pub a: &'a mut [f64],
    pub n: usize,
}

impl Balance for RowMajor<'_> {
    fn order(&self) -> usize {
        self.n
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        self.a[i * self.n + j]
    }

    fn rescale(&mut self, i: usize, f: f64) {
        let n = self.n;
        for j in 0..n {
            self.a[i * n + j] /= f;
            self.a[j * n + i] *= f;
        }
    }
}

/// Passes of one row's scaling search (see [`balance`]).
const MAX_PASSES: usize = 1100;

/// Balances `a` in place (at most 64 sweeps) and multiplies `scale[i]` by the factor applied to
/// row/column i, so that on return `a` = D⁻¹ A D with D = diag(scale) (when `scale` started at 1).
pub fn balance(a: &mut impl Balance, mut scale: Option<&mut [f64]>) {
    let n = a.order();
    for _sweep in 0..64 {
        let mut converged = true;
        for i in 0..n {
            let (mut c, mut r) = (0.0f64, 0.0f64);
            for j in 0..n {
                if j != i {
                    c += a.entry(j, i).abs();
                    r += a.entry(i, j).abs();
                }
            }
            // A non-finite sum (an infinite entry) has no balancing factor: leave the row; the
            // eigensolver's own finiteness check reports the matrix.
            if c == 0.0 || r == 0.0 || !(c + r).is_finite() {
                continue;
            }
            let total = c + r;
            let (mut f, mut c2, mut r2) = (1.0f64, c, r);
            // Each loop moves c2/r2 by 4 per pass: at most MAX_PASSES passes span the ratio of
            // the largest to the smallest positive double (2^2098); the bound also ends a pass
            // that underflows to 0.
            for _ in 0..MAX_PASSES {
                if c2 >= 0.5 * r2 {
                    break;
                }
                c2 *= 2.0;
                r2 *= 0.5;
                f *= 2.0;
            }
            for _ in 0..MAX_PASSES {
                if c2 < 2.0 * r2 {
                    break;
                }
                c2 *= 0.5;
                r2 *= 2.0;
                f *= 0.5;
            }
            if !f.is_finite() || f <= 0.0 {
                continue;
            }
            if c2 + r2 < 0.95 * total {
                converged = false;
                if let Some(s) = scale.as_deref_mut() {
                    s[i] *= f;
                }
                a.rescale(i, f);
            }
        }
        if converged {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    //! Balancing is an exact similarity with power-of-2 factors: D⁻¹ A D reproduced entry by entry
    //! from the returned scaling, the two storages give the same bits, and a badly scaled matrix's
    //! norm drops.
    use super::*;

    fn graded(n: usize) -> Vec<f64> {
        (0..n * n)
            .map(|k| {
                let (i, j) = (k / n, k % n);
                (1.0 + (i + 2 * j) as f64) * 10f64.powi(i as i32 - j as i32)
            })
            .collect()
    }

    #[test]
    fn infinite_and_extreme_entries_end_the_balancing() {
        // Once was an endless loop: inf >= 2 inf holds for ever.
        let mut a = vec![1.0, f64::INFINITY, 1.0, 1.0];
        balance(&mut RowMajor { a: &mut a, n: 2 }, None);
        assert_eq!(a[1], f64::INFINITY);
        // the widest finite ratios: the factors stay finite and positive
        let mut b = vec![0.0, f64::MAX, 5e-324, 0.0];
        let mut scale = vec![1.0; 2];
        balance(&mut RowMajor { a: &mut b, n: 2 }, Some(&mut scale));
        assert!(scale.iter().all(|s| s.is_finite() && *s > 0.0), "{scale:?}");
        assert!(b.iter().all(|v| v.is_finite()), "{b:?}");
    }

    #[test]
    fn balancing_is_an_exact_power_of_two_similarity_that_reduces_the_norm() {
        let n = 5;
        let a0 = graded(n);
        let mut a = a0.clone();
        let mut scale = vec![1.0; n];
        balance(&mut RowMajor { a: &mut a, n }, Some(&mut scale));
        for (i, d) in scale.iter().enumerate() {
            assert_eq!(d.log2().fract(), 0.0, "scale[{i}] = {d} is a power of 2");
        }
        for i in 0..n {
            for j in 0..n {
                assert_eq!(a[i * n + j], a0[i * n + j] / scale[i] * scale[j]);
            }
        }
        let norm = |m: &[f64]| m.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!(norm(&a) < 0.01 * norm(&a0), "{} vs {}", norm(&a), norm(&a0));
    }

    #[test]
    fn the_two_storages_give_the_same_bits() {
        let n = 6;
        let a0 = graded(n);
        let mut rm = a0.clone();
        balance(&mut RowMajor { a: &mut rm, n }, None);
        let mut m = Mat::from_fn(n, n, |i, j| a0[i * n + j]);
        balance(&mut m, None);
        for i in 0..n {
            for j in 0..n {
                assert_eq!(m[(i, j)].to_bits(), rm[i * n + j].to_bits());
            }
        }
    }
}
