//! The moving family's error functionals: what is read off a spectrum to compare it with an exact
//! one (frequencies, the upper half-plane eigenvalues in order), and the measures of a spectrum
//! that the verdicts and the exactness checks use.

use contactlab::model::moving::c64;

/// The eigenvalues in the upper half-plane, ascending in Im λ.
pub fn upper_half(ev: &[c64]) -> Vec<c64> {
    let mut v: Vec<c64> = ev.iter().copied().filter(|l| l.im > 0.0).collect();
    v.sort_by(|a, b| a.im.total_cmp(&b.im));
    v
}

/// The `count` lowest eigenvalues with Im λ > 0, or an error naming `what` when the spectrum has
/// fewer (a system whose oscillating modes were lost: never an index out of bounds).
pub fn lowest_oscillating(ev: &[c64], count: usize, what: &str) -> Result<Vec<c64>, String> {
    let mut v = upper_half(ev);
    if v.len() < count {
        return Err(format!(
            "{what}: {} eigenvalues with Im λ > 0 of {}, {count} needed",
            v.len(),
            ev.len()
        ));
    }
    v.truncate(count);
    Ok(v)
}

/// The positive frequencies Im λ > 0, ascending.
pub fn frequencies(ev: &[c64]) -> Vec<f64> {
    let mut f: Vec<f64> = ev.iter().filter(|l| l.im > 0.0).map(|l| l.im).collect();
    f.sort_by(f64::total_cmp);
    f
}

/// max Re λ: the growth rate of the fastest mode.
pub fn max_real_part(ev: &[c64]) -> f64 {
    ev.iter().map(|l| l.re).fold(f64::NEG_INFINITY, f64::max)
}

/// max |Re λ| / max |λ|: zero to round-off for an undamped gyroscopic system.
pub fn relative_real_part(ev: &[c64]) -> f64 {
    let rho = ev.iter().map(|l| l.norm()).fold(0.0, f64::max);
    ev.iter().map(|l| l.re.abs()).fold(0.0, f64::max) / rho
}

#[cfg(test)]
mod tests {
    //! The spectrum measures on a hand-made spectrum.
    use super::*;

    #[test]
    fn spectrum_measures_of_a_known_spectrum() {
        let ev = [
            c64::new(-0.1, 2.0),
            c64::new(-0.1, -2.0),
            c64::new(0.3, 1.0),
            c64::new(0.3, -1.0),
        ];
        assert_eq!(frequencies(&ev), vec![1.0, 2.0]);
        assert_eq!(upper_half(&ev)[0], c64::new(0.3, 1.0));
        assert_eq!(max_real_part(&ev), 0.3);
        let rho = c64::new(-0.1, 2.0).norm();
        assert_eq!(relative_real_part(&ev), 0.3 / rho);
    }
}
