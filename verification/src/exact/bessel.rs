//! Bessel functions of integer order for the exact plate frequencies (`plate_annulus`).
//!
//! **J_n, Y_n** come from the `libm` crate (the FreeBSD/musl msun port: rational approximations
//! for orders 0 and 1, forward recurrence for Y_n and for J_n with n ≤ x, Miller's backward
//! recurrence for J_n with n > x).
//!
//! **I_n, K_n** are not in libm; they are computed here from integral representations by the
//! trapezoidal rule, which converges exponentially for these smooth, rapidly decaying integrands
//! (Trefethen & Weideman, SIAM Rev. 56 (2014) 385, §§3–5):
//!
//! ```text
//!   e^{−x} I_n(x) = x^n / (π (2n−1)!!) ∫₀^π exp(−2x sin²(θ/2)) sin^{2n}θ dθ        (A&S 9.6.18)
//!   e^{x}  K_n(x) = ∫₀^∞ exp(−2x sinh²(t/2)) cosh(nt) dt                            (A&S 9.6.24)
//! ```
//!
//! (x cos θ − x = −2x sin²(θ/2) and x cosh t − x = 2x sinh²(t/2) written without cancellation).
//! Poisson's form of I_n is used rather than (1/π)∫ e^{x cos θ} cos nθ dθ because its integrand is
//! positive: the cosine form loses all relative accuracy where I_n(x) ≪ 1 (I_6(0.05) ≈ 3e−13 is a
//! sum of O(1) terms of both signs). The Poisson integrand, extended evenly, is 2π-periodic and
//! entire, so the trapezoidal rule on [0, π] with halved end points is spectrally accurate; the
//! K_n integrand is entire and even in t, so the rule on the whole line (summed over t ≥ 0) is too.
//! Both are refined by halving the step (re-using the old nodes) until two successive sums agree
//! to `REFINE_TOL`; with the error falling like e^{−c/h} the accepted (finer) sum is then accurate
//! to round-off. All terms are positive, so the sums lose nothing to cancellation.
//!
//! Measured accuracy (tests below): the Wronskians I_n K_{n+1} + I_{n+1} K_n = 1/x and
//! J_{n+1} Y_n − J_n Y_{n+1} = 2/(πx) hold to ≤ 1e−13 relative for n = 0..6, x ∈ [0.05, 60], and
//! tabulated values are matched to ≤ 1e−14 relative.
//!
//! Domain: order n ≤ [`MAX_ORDER`], argument 0 < x < ∞ (x = 0 is allowed for J and I). Outside it
//! the functions return NaN, which the callers check.

/// The largest order supported (keeps x^n/(2n−1)!! and the K_n integrand within f64 for the
/// arguments the plate needs).
pub const MAX_ORDER: u32 = 64;

/// Two successive trapezoidal sums agreeing to this (relative) stop the refinement: the error of
/// the finer sum is then of order REFINE_TOL² (exponential convergence), below round-off.
const REFINE_TOL: f64 = 1e-11;

/// The largest number of nodes before the refinement gives up (never reached in the domain).
const MAX_NODES: usize = 1 << 20;

/// J_n(x) (libm).
pub fn bessel_j(n: u32, x: f64) -> f64 {
    if n > MAX_ORDER || x.is_nan() {
        return f64::NAN;
    }
    libm::jn(n as i32, x)
}

/// Y_n(x), x > 0 (libm).
pub fn bessel_y(n: u32, x: f64) -> f64 {
    if n > MAX_ORDER || x.is_nan() || x <= 0.0 {
        return f64::NAN;
    }
    libm::yn(n as i32, x)
}

/// e^{−x} I_n(x), x ≥ 0 (Poisson's integral, A&S 9.6.18, by the trapezoidal rule).
pub fn bessel_i_scaled(n: u32, x: f64) -> f64 {
    if n > MAX_ORDER || x.is_nan() || x < 0.0 || x.is_infinite() {
        return f64::NAN;
    }
    if x == 0.0 {
        return if n == 0 { 1.0 } else { 0.0 };
    }
    // x^n / (π (2n−1)!!), built factor by factor (no intermediate overflow in the domain).
    let mut prefactor = std::f64::consts::FRAC_1_PI;
    for k in 1..=n {
        prefactor *= x / f64::from(2 * k - 1);
    }
    let power = 2 * n as i32;
    let f = |theta: f64| {
        let s = (0.5 * theta).sin();
        (-2.0 * x * s * s).exp() * theta.sin().powi(power)
    };
    let pi = std::f64::consts::PI;
    // Resolve the bump of width ~1/sqrt(x) at θ = 0 from the start.
    let mut intervals = 16usize.max((2.0 * pi * x.sqrt()).ceil() as usize);
    let mut sum = 0.5 * (f(0.0) + f(pi));
    for k in 1..intervals {
        sum += f(pi * k as f64 / intervals as f64);
    }
    let mut estimate = sum * pi / intervals as f64;
    while intervals < MAX_NODES {
        // Halve the step: the new nodes are the midpoints of the old intervals.
        for k in 0..intervals {
            sum += f(pi * (2 * k + 1) as f64 / (2 * intervals) as f64);
        }
        intervals *= 2;
        let finer = sum * pi / intervals as f64;
        let converged = (finer - estimate).abs() <= REFINE_TOL * finer.abs();
        estimate = finer;
        if converged {
            break;
        }
    }
    prefactor * estimate
}

/// e^{x} K_n(x), x > 0 (A&S 9.6.24 by the trapezoidal rule on t ≥ 0).
pub fn bessel_k_scaled(n: u32, x: f64) -> f64 {
    if n > MAX_ORDER || x.is_nan() || x <= 0.0 || x.is_infinite() {
        return f64::NAN;
    }
    let nf = f64::from(n);
    // ln of the integrand: −2x sinh²(t/2) + ln cosh(nt), the latter as
    // nt + ln(1 + e^{−2nt}) − ln 2 (no overflow of cosh for large nt).
    let log_g = |t: f64| {
        let s = (0.5 * t).sinh();
        let u = nf * t;
        -2.0 * x * s * s + u + (-2.0 * u).exp().ln_1p() - std::f64::consts::LN_2
    };
    // The integrand is unimodal in t ≥ 0 (x sinh t = n tanh(nt) has at most one positive root):
    // walk outwards in coarse steps past the peak until it has fallen by e^{−50} ≈ 2e−22.
    let coarse = 0.125;
    let mut peak = log_g(0.0);
    let mut t_max = 0.0;
    loop {
        t_max += coarse;
        let lg = log_g(t_max);
        peak = peak.max(lg);
        if lg < peak - 50.0 {
            break;
        }
        if t_max > 1e3 {
            return f64::NAN;
        }
    }
    let g = |t: f64| log_g(t).exp();
    // Start with a step resolving the peak's width ~ 1/sqrt(x cosh t*) ≈ (n² + x²)^{−1/4}.
    let width = (nf * nf + x * x).sqrt().max(1.0).sqrt().recip();
    let mut h = (0.5 * width).min(coarse);
    let mut nodes = (t_max / h).ceil() as usize;
    h = t_max / nodes as f64;
    let mut sum = 0.5 * g(0.0);
    for k in 1..=nodes {
        sum += g(h * k as f64);
    }
    let mut estimate = sum * h;
    while nodes < MAX_NODES {
        for k in 0..nodes {
            sum += g(h * (k as f64 + 0.5));
        }
        nodes *= 2;
        h *= 0.5;
        let finer = sum * h;
        let converged = (finer - estimate).abs() <= REFINE_TOL * finer.abs();
        estimate = finer;
        if converged {
            break;
        }
    }
    estimate
}

/// I_n(x) = e^{x} (e^{−x} I_n(x)); overflows to ∞ beyond x ≈ 709.
pub fn bessel_i(n: u32, x: f64) -> f64 {
    bessel_i_scaled(n, x) * x.exp()
}

/// K_n(x) = e^{−x} (e^{x} K_n(x)).
pub fn bessel_k(n: u32, x: f64) -> f64 {
    bessel_k_scaled(n, x) * (-x).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    /// Arguments spread over [0.05, 60] (geometric, so the small-x end is sampled as densely as
    /// the oscillatory/exponential end).
    fn arguments() -> Vec<f64> {
        let count = 121;
        (0..count)
            .map(|k| 0.05 * (60.0f64 / 0.05).powf(k as f64 / (count - 1) as f64))
            .collect()
    }

    #[test]
    fn wronskian_of_i_and_k_holds_to_1e_13_for_orders_0_to_6() {
        // Setting: I_n K_{n+1} + I_{n+1} K_n = 1/x (A&S 9.6.15), both terms positive, so the
        // relative error of each function shows directly. Goal: the trapezoidal I_n and K_n are
        // accurate to ≤ 1e−13 relative over x ∈ [0.05, 60], n = 0..6 — including the corners
        // where I_n(x) ≈ 1e−13 (small x, n = 6) and K_n(x) ≈ 1e−28 (x = 60).
        let mut worst: f64 = 0.0;
        for n in 0..=6u32 {
            for &x in &arguments() {
                // The scaled product is exactly the unscaled one (e^{−x} e^{x} = 1).
                let w = bessel_i_scaled(n, x) * bessel_k_scaled(n + 1, x)
                    + bessel_i_scaled(n + 1, x) * bessel_k_scaled(n, x);
                worst = worst.max(rel(w, 1.0 / x));
            }
        }
        eprintln!("worst relative Wronskian defect {worst:e}");
        assert!(worst <= 1e-13, "worst relative Wronskian defect {worst:e}");
    }

    #[test]
    fn wronskian_of_j_and_y_holds_to_1e_13_for_orders_0_to_6() {
        // Setting: J_{n+1} Y_n − J_n Y_{n+1} = 2/(πx) (A&S 9.1.16, shifted). Goal: libm's J_n, Y_n
        // are accurate enough for the plate determinant (≤ 1e−13 relative over the same range).
        let mut worst: f64 = 0.0;
        for n in 0..=6u32 {
            for &x in &arguments() {
                let w = bessel_j(n + 1, x) * bessel_y(n, x) - bessel_j(n, x) * bessel_y(n + 1, x);
                worst = worst.max(rel(w, 2.0 / (std::f64::consts::PI * x)));
            }
        }
        eprintln!("worst relative Wronskian defect {worst:e}");
        assert!(worst <= 1e-13, "worst relative Wronskian defect {worst:e}");
    }

    #[test]
    fn modified_bessel_functions_match_tabulated_values_to_1e_14() {
        // Setting: values of I_n, K_n at a few arguments from an mpmath 1.3 evaluation at 30
        // digits (besseli/besselk, rounded to f64); they agree with A&S Tables 9.8 and 9.11 to the
        // tables' 10 digits, e.g. I_0(1) = 1.266065878, K_0(1) = 0.4210244382, I_1(1) =
        // 0.5651591040, K_1(1) = 0.6019072302. Goal: ≤ 1e−14 relative, the accuracy the plate
        // determinant is built on, over small and large arguments and orders.
        let table: [(u32, f64, f64, f64); 12] = [
            // (n, x, I_n(x), K_n(x))
            (0, 1.0, 1.2660658777520084, 0.42102443824070834),
            (1, 1.0, 0.565159103992485, 0.6019072301972346),
            (2, 1.0, 0.13574766976703828, 1.6248388986351774),
            (0, 0.1, 1.0025015629340956, 2.427069024702017),
            (1, 0.1, 0.050062526047092694, 9.853844780870606),
            (3, 0.1, 2.084635742232715e-5, 7990.012430465436),
            (0, 5.0, 27.239871823604446, 0.0036910983340425942),
            (1, 5.0, 24.335642142450528, 0.004044613445452165),
            (4, 5.0, 5.10823476364287, 0.015259065810500579),
            (0, 20.0, 43558282.559553534, 5.741237815336525e-10),
            (6, 0.05, 3.391144779466721e-13, 245729282399.83334),
            (2, 50.0, 2.816430640245194e20, 3.547931838858198e-23),
        ];
        let mut worst: f64 = 0.0;
        for (n, x, i_ref, k_ref) in table {
            let (i, k) = (bessel_i(n, x), bessel_k(n, x));
            worst = worst.max(rel(i, i_ref)).max(rel(k, k_ref));
            assert!(
                rel(i, i_ref) <= 1e-14,
                "I_{n}({x}) = {i:e}, table {i_ref:e}"
            );
            assert!(
                rel(k, k_ref) <= 1e-14,
                "K_{n}({x}) = {k:e}, table {k_ref:e}"
            );
        }
        eprintln!("worst relative deviation from the table {worst:e}");
    }

    #[test]
    fn out_of_domain_arguments_give_nan() {
        // Setting: the callers check for non-finite values; the functions must not panic or
        // return a plausible number outside their domain.
        assert!(bessel_k_scaled(0, 0.0).is_nan());
        assert!(bessel_k_scaled(0, -1.0).is_nan());
        assert!(bessel_y(1, 0.0).is_nan());
        assert!(bessel_i_scaled(MAX_ORDER + 1, 1.0).is_nan());
        assert!(bessel_i_scaled(0, f64::INFINITY).is_nan());
        assert_eq!(bessel_i_scaled(0, 0.0), 1.0);
        assert_eq!(bessel_i_scaled(3, 0.0), 0.0);
    }
}
