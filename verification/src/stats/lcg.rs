//! A deterministic pseudo-random sequence for sampling test points (64-bit linear congruential
//! generator with Knuth's MMIX constants): the same seed gives the same points on every machine.

/// The generator's state.
#[derive(Debug, Clone)]
pub struct Lcg(pub u64);

impl Lcg {
    /// The next value in [−1, 1).
    pub fn next_signed(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        2.0 * ((self.0 >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }

    /// The next value in [0, 1).
    pub fn next_unit(&mut self) -> f64 {
        0.5 * (self.next_signed() + 1.0)
    }
}

#[cfg(test)]
mod tests {
    //! The sequence is reproducible and stays in its interval.
    use super::*;

    #[test]
    fn same_seed_same_sequence_within_bounds() {
        let (mut a, mut b) = (Lcg(7), Lcg(7));
        for _ in 0..1000 {
            let (x, y) = (a.next_signed(), b.next_signed());
            assert_eq!(x.to_bits(), y.to_bits());
            assert!((-1.0..1.0).contains(&x));
            assert!((0.0..1.0).contains(&a.next_unit()));
            b.next_unit();
        }
    }
}
