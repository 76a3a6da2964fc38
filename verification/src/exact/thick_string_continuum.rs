//! The continuum characteristic function of the thick string with friction and an oscillator in
//! the bushing (Hetzler 2009, §4.2.2, weak form (100); docs/moving_continua.md), derived here:
//! the reference for the converged eigenvalues and flutter onsets of the moving cases.
//!
//! **Interior.** w = W(ξ) e^{λτ}, u = U e^{λτ}: away from ā, λ²W + ᾱλW + 2v̄λW' − b W'' = 0 with
//! b = 1 − v̄², solved by e^{sξ}, s_{1,2} = (v̄λ ± sqrt(λ² + bᾱλ))/b. With W(0) = W(1) = 0:
//! W = A f_L on [0, ā), W = B f_R on (ā, 1], f_L = e^{s₁ξ} − e^{s₂ξ},
//! f_R = e^{s₁(ξ−1)} − e^{s₂(ξ−1)}.
//!
//! **At the bushing.** The friction's virtual work (p/2)(w(ā) − u) δw'(ā) tests the derivative of
//! δw at a point, so it is not bounded on H¹ and W may jump at ā. Reading the weak form with the
//! distributional derivatives W' = {W'} + [W] δ_ā and W'' = {W''} + [W'] δ_ā + [W] δ'_ā and
//! collecting the coefficients of δw(ā) and δw'(ā) gives, with the oscillator's
//! U = c̄ W̄/(m̄λ² + c̄), W̄ − U = g W̄, g = m̄λ²/(m̄λ² + c̄), W̄ the mean of the one-sided values
//! (the value a sine series takes at a jump):
//!
//! ```text
//!   δw'(ā):   b [W]  = (p/2) g W̄
//!   δw(ā):    b [W'] = 2v̄λ [W] + c̄ g W̄,
//! ```
//!
//! i.e. the friction opens a jump of the displacement, and the transport 2v̄ ẇ' across that jump
//! adds a point force 2v̄λ[W]. For p = 0 the jump closes and the conditions are those of the thin
//! string (`moving_string::OscillatorCharacteristic`). With l = f_L(ā), l' = f_L'(ā),
//! r = f_R(ā), r' = f_R'(ā) the two conditions are linear in (A, B); with each row multiplied
//! by D = m̄λ² + c̄ (which clears the pole of g) the system reads
//!
//! ```text
//!   row 1:  A (−D b l − (pG/4) l)                 + B (D b r − (pG/4) r)
//!   row 2:  A (D (b l' − 2v̄λ l) + (c̄G/2) l)      + B (D (−b r' + 2v̄λ r) + (c̄G/2) r),
//!
//!   G = g D = m̄λ².
//! ```
//!
//! Writing entry (i, j) as D α_ij + G β_ij, the β rows are parallel (both ∝ (l, r)), so
//! det β = 0 and the determinant is D times
//!
//! ```text
//!   F(λ) = D det α + G (α₁₁β₂₂ + β₁₁α₂₂ − α₁₂β₂₁ − β₁₂α₂₁),
//! ```
//!
//! the function used. (The determinant itself vanishes at D = 0, λ = ±i sqrt(c̄/m̄), for every
//! p: a spurious root at the oscillator's bare frequency, found at v̄ = 0.9 of the map's data,
//! where a string mode passes near it.) Swapping s₁ and s₂ changes the sign of both columns, so F
//! does not depend on the branch of the square root. F also vanishes where s₁ = s₂ (λ = 0,
//! λ = −bᾱ), which are not eigenvalues.

use nalgebra::Complex;

use super::thick_string_galerkin::ThickString;

type C64 = Complex<f64>;

/// The characteristic function F(λ) of the continuum (see the module docs); for a contact patch
/// (`d.patch > 0`) that of `thick_string_patch`.
pub fn characteristic(d: &ThickString, lambda: C64) -> C64 {
    if d.patch > 0.0 {
        return super::thick_string_patch::patch_characteristic(d, d.patch, lambda);
    }
    let v = d.speed;
    let b = 1.0 - v * v;
    let root = (lambda * lambda + lambda * (b * d.damping)).sqrt();
    let s1 = (lambda * v + root) / b;
    let s2 = (lambda * v - root) / b;
    let a = d.position;
    let (e1l, e2l) = ((s1 * a).exp(), (s2 * a).exp());
    let (e1r, e2r) = ((s1 * (a - 1.0)).exp(), (s2 * (a - 1.0)).exp());
    let l = e1l - e2l;
    let dl = s1 * e1l - s2 * e2l;
    let r = e1r - e2r;
    let dr = s1 * e1r - s2 * e2r;
    let dd = lambda * lambda * d.mass + d.stiffness;
    let gg = lambda * lambda * d.mass;
    let p = d.control;
    let c = d.stiffness;
    let two_v_l = lambda * (2.0 * v);
    // Entry (i, j) of the D-multiplied system is D α_ij + G β_ij.
    let (al11, al12) = (-(l * b), r * b);
    let (al21, al22) = (dl * b - two_v_l * l, -(dr * b) + two_v_l * r);
    let (be11, be12) = (-(l * (p / 4.0)), -(r * (p / 4.0)));
    let (be21, be22) = (l * (c / 2.0), r * (c / 2.0));
    // det = D² det α + D G (α11 β22 + β11 α22 − α12 β21 − β12 α21) + G² det β, det β = 0:
    // F̂ = det / D.
    dd * (al11 * al22 - al12 * al21) + gg * (al11 * be22 + be11 * al22 - al12 * be21 - be12 * al21)
}

/// The root of `f` near `guess` by the secant method, to |Δλ| ≤ 4ε max(|λ|, 1).
pub fn secant_root(f: impl Fn(C64) -> C64, guess: C64) -> Result<C64, String> {
    let mut x0 = guess * (1.0 + 1e-7) + C64::new(1e-9, 0.0);
    let mut x1 = guess;
    let (mut f0, mut f1) = (f(x0), f(x1));
    for _ in 0..200 {
        let denom = f1 - f0;
        if denom.norm() == 0.0 {
            break;
        }
        let x2 = x1 - f1 * (x1 - x0) / denom;
        if !(x2.re.is_finite() && x2.im.is_finite()) {
            return Err(format!("secant diverged from {guess}"));
        }
        let step = (x2 - x1).norm();
        (x0, f0) = (x1, f1);
        x1 = x2;
        f1 = f(x1);
        if step <= 4.0 * f64::EPSILON * x1.norm().max(1.0) {
            return Ok(x1);
        }
    }
    if f1.norm() == 0.0 {
        Ok(x1)
    } else {
        Err(format!(
            "secant did not converge from {guess} (last iterate {x1}, |F| = {:e})",
            f1.norm()
        ))
    }
}

/// The root of the continuum's F near `guess`.
pub fn continuum_root(d: &ThickString, guess: C64) -> Result<C64, String> {
    secant_root(|l| characteristic(d, l), guess)
}

/// Follows the root that starts near `guess` at p = 0 through the control parameters `controls`
/// (ascending, from 0), each step starting from the linear extrapolation of the previous two
/// roots. A step that moves the root by more than a tenth of its modulus is refused (a jump to
/// another branch).
pub fn track_in_control(d: &ThickString, guess: C64, controls: &[f64]) -> Result<Vec<C64>, String> {
    let mut roots: Vec<C64> = Vec::with_capacity(controls.len());
    for (i, &p) in controls.iter().enumerate() {
        let at = ThickString { control: p, ..*d };
        let g = match i {
            0 => guess,
            1 => roots[0],
            _ => {
                let span = controls[i - 1] - controls[i - 2];
                let t = if span == 0.0 {
                    0.0
                } else {
                    (p - controls[i - 1]) / span
                };
                roots[i - 1] + (roots[i - 1] - roots[i - 2]) * t
            }
        };
        let r = continuum_root(&at, g)?;
        if i > 0 && (r - roots[i - 1]).norm() > 0.1 * roots[i - 1].norm() {
            return Err(format!(
                "p = {p}: the root jumped from {} to {r}",
                roots[i - 1]
            ));
        }
        roots.push(r);
    }
    Ok(roots)
}

/// The flutter onset of one branch: the smallest p in (0, `p_max`] at which the root followed
/// from `guess` at p = 0 crosses into Re λ > 0, located by tracking in `steps` equal steps and
/// then bisecting the crossing step to |Δp| ≤ `tolerance`. `None` when the branch stays stable.
pub fn branch_onset(
    d: &ThickString,
    guess: C64,
    p_max: f64,
    steps: usize,
    tolerance: f64,
) -> Result<Option<(f64, C64)>, String> {
    let controls: Vec<f64> = (0..=steps)
        .map(|i| p_max * i as f64 / steps as f64)
        .collect();
    let roots = track_in_control(d, guess, &controls)?;
    let Some(i) = (1..roots.len()).find(|&i| roots[i].re > 0.0) else {
        return Ok(None);
    };
    if roots[i - 1].re > 0.0 {
        return Err("unstable at p = 0".into());
    }
    let (mut lo, mut hi) = (controls[i - 1], controls[i]);
    let (mut r_lo, mut r_hi) = (roots[i - 1], roots[i]);
    while hi - lo > tolerance {
        let mid = 0.5 * (lo + hi);
        let t = (mid - lo) / (hi - lo);
        let r = continuum_root(
            &ThickString { control: mid, ..*d },
            r_lo + (r_hi - r_lo) * t,
        )?;
        if r.re > 0.0 {
            (hi, r_hi) = (mid, r);
        } else {
            (lo, r_lo) = (mid, r);
        }
    }
    let mid = 0.5 * (lo + hi);
    let r = continuum_root(&ThickString { control: mid, ..*d }, 0.5 * (r_lo + r_hi))?;
    Ok(Some((mid, r)))
}

/// The roots of F at p = 0 (the control of `d` is ignored) near the lowest `count` frequencies of
/// the independent sine-Galerkin model with `guess_modes` functions (Im λ > 0), each refined to a
/// root of F; an error when a root lands far from its guess or two guesses find the same root.
pub fn roots_at_rest(
    d: &ThickString,
    guess_modes: usize,
    count: usize,
) -> Result<Vec<C64>, String> {
    let d0 = ThickString { control: 0.0, ..*d };
    let mut guess: Vec<C64> = d0
        .galerkin_eigenvalues(guess_modes)?
        .into_iter()
        .filter(|l| l.im > 0.0)
        .collect();
    guess.sort_by(|a, b| a.im.total_cmp(&b.im));
    let mut roots = Vec::new();
    for g in guess.into_iter().take(count) {
        let r = continuum_root(&d0, g)?;
        if (r - g).norm() > 0.05 * g.norm() {
            return Err(format!("the root {r} is far from its guess {g}"));
        }
        if roots.iter().any(|x: &C64| (x - r).norm() < 1e-8 * r.norm()) {
            return Err(format!("two guesses found the same root {r}"));
        }
        roots.push(r);
    }
    Ok(roots)
}

/// The continuum's flutter onset: see [`continuum_onset`].
#[derive(Debug, Clone, Copy)]
pub struct ContinuumOnset {
    /// p*, the smallest onset over the followed branches.
    pub onset: f64,
    /// The critical root at p*.
    pub critical: C64,
    /// The largest Re λ of the other followed branches at p*.
    pub others_max_re: f64,
    /// The number of branches followed.
    pub branches: usize,
}

/// The flutter onset of the continuum `d` (its control ignored): the lowest `branches` roots at
/// p = 0 ([`roots_at_rest`]) each followed in (0, `p_max`] ([`branch_onset`], `steps` steps,
/// bisection to 1e-13 p_max); p* is the smallest onset, and the other branches are followed to
/// p* to report their largest real part there. `None` when every followed branch stays stable
/// up to `p_max`.
pub fn continuum_onset(
    d: &ThickString,
    guess_modes: usize,
    branches: usize,
    p_max: f64,
    steps: usize,
) -> Result<Option<ContinuumOnset>, String> {
    let start = roots_at_rest(d, guess_modes, branches)?;
    let d0 = ThickString { control: 0.0, ..*d };
    let mut best: Option<(f64, C64)> = None;
    for &g in &start {
        if let Some((p, l)) = branch_onset(&d0, g, p_max, steps, 1e-13 * p_max)? {
            if best.is_none_or(|b| p < b.0) {
                best = Some((p, l));
            }
        }
    }
    let Some((p_star, crit)) = best else {
        return Ok(None);
    };
    let controls: Vec<f64> = (0..=steps)
        .map(|i| p_star * i as f64 / steps as f64)
        .collect();
    let mut others: f64 = f64::NEG_INFINITY;
    for &g in &start {
        let r = track_in_control(&d0, g, &controls)?[steps];
        if (r - crit).norm() > 1e-6 * crit.norm() {
            others = others.max(r.re);
        }
    }
    Ok(Some(ContinuumOnset {
        onset: p_star,
        critical: crit,
        others_max_re: others,
        branches: start.len(),
    }))
}

#[cfg(test)]
mod tests {
    //! Setting: cases with known roots. Goal: without friction F reduces to the thin string's
    //! function (the same roots); at ā = 1/2 the even string modes, which vanish at the bushing,
    //! stay roots for any friction.
    use super::*;
    use crate::exact::moving_string::{string_eigenvalue, OscillatorCharacteristic};

    fn data(position: f64, control: f64) -> ThickString {
        ThickString {
            speed: 0.4,
            damping: 0.0,
            stiffness: 3.0,
            mass: 0.5,
            position,
            control,
            patch: 0.0,
        }
    }

    #[test]
    fn without_friction_the_roots_are_the_thin_strings() {
        let d = data(0.3, 0.0);
        let thin = OscillatorCharacteristic {
            speed: d.speed,
            damping: 0.0,
            stiffness: d.stiffness,
            mass: d.mass,
            position: d.position,
        };
        for g in [2.0, 4.5, 8.0] {
            let a = thin.refine(C64::new(0.0, g)).unwrap();
            let b = continuum_root(&d, a * (1.0 + 1e-6)).unwrap();
            assert!((a - b).norm() < 1e-12 * a.norm(), "{a} vs {b}");
        }
    }

    #[test]
    fn nodal_modes_are_roots_for_any_friction() {
        for p in [0.0, 0.3, 2.0] {
            let d = data(0.5, p);
            let l = C64::new(0.0, string_eigenvalue(2, d.speed));
            let r = continuum_root(&d, l * (1.0 + 1e-3)).unwrap();
            assert!((r - l).norm() < 1e-12 * l.norm(), "p = {p}: {r} vs {l}");
        }
    }
}
