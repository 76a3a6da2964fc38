//! The linearized friction in the bushing of the thick string (Hetzler 2009, §4.2.2).
//!
//! Friction on the upper and lower faces of a string of thickness h, with normal forces that
//! vary with the spring (ideal contact) or the penalty layer, does the virtual work
//!
//! ```text
//!   ideal   (99):  δW_C = (μ c̄ h̄ / 2) (w(ā) − u)   δw'(ā)
//!   penalty (105): δW_C = (μ k̄_p h̄ / 2) (w(ā) − y_c) δw'(ā)
//! ```
//!
//! With w = Φ q this is δqᵀ (p/2) Φ'(ā)ᵀ (Φ(ā) q − s), s = u or y_c, i.e. δxᵀ p R x with
//!
//! ```text
//!   R = ½ [ Φ'(ā)ᵀ Φ(ā)   −Φ'(ā)ᵀ ]      ((101)–(102), (107): rows q, columns q and s),
//! ```
//!
//! a generalized force on the right-hand side of the weak form, so the equations of motion carry
//! −p R in their stiffness. Its symmetric part is the friction stiffness p K_f = −p (R + Rᵀ)/2
//! and its skew part the circulatory matrix p N = −p (R − Rᵀ)/2 (the paper's decomposition
//! R4 = K4 + N4, (103), written with the sign of the force moved to the left-hand side).

use faer::Mat;

/// Adds −p R to the stiffness parts: the symmetric half to `stiffness`, the skew half to
/// `circulatory`. `slopes` = Φ'(ā), `values` = Φ(ā) on the string coordinates 0..N;
/// `partner` is the index of s (u for ideal contact, y_c for the penalty bushing).
pub fn add_friction(
    p: f64,
    values: &[f64],
    slopes: &[f64],
    partner: usize,
    stiffness: &mut Mat<f64>,
    circulatory: &mut Mat<f64>,
) {
    if p == 0.0 {
        return;
    }
    let n = values.len();
    let half = 0.5 * p;
    // −p R: entries (i, j) = −(p/2) Φ'_i Φ_j on the string block, (i, s) = +(p/2) Φ'_i.
    let mut add = |i: usize, j: usize, r: f64| {
        // r is the entry of −pR at (i, j); its transpose partner has 0.
        stiffness[(i, j)] += 0.5 * r;
        stiffness[(j, i)] += 0.5 * r;
        circulatory[(i, j)] += 0.5 * r;
        circulatory[(j, i)] -= 0.5 * r;
    };
    for i in 0..n {
        for j in 0..n {
            add(i, j, -half * slopes[i] * values[j]);
        }
        add(i, partner, half * slopes[i]);
    }
}

#[cfg(test)]
mod tests {
    //! Setting: one string coordinate and a partner. Goal: the split parts add up to −pR and are
    //! symmetric and skew.
    use super::*;

    #[test]
    fn parts_add_up_to_minus_p_r() {
        let mut k = Mat::<f64>::zeros(2, 2);
        let mut n = Mat::<f64>::zeros(2, 2);
        add_friction(2.0, &[3.0], &[5.0], 1, &mut k, &mut n);
        // R = ½ [[5·3, −5], [0, 0]]; −2R = [[−15, 5], [0, 0]].
        let total = [[-15.0, 5.0], [0.0, 0.0]];
        for i in 0..2 {
            for j in 0..2 {
                assert!((k[(i, j)] + n[(i, j)] - total[i][j]).abs() < 1e-14);
                assert_eq!(k[(i, j)], k[(j, i)]);
                assert_eq!(n[(i, j)], -n[(j, i)]);
            }
        }
    }
}
