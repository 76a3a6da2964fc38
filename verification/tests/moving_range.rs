//! The moving-continua family at the edges of its range (issue 31, items 3 and 4).

use contactlab::model::moving::finite_element_basis::ElementKind;
use contactlab::model::moving::resolution::model_resolution_limit;
use contactlab::model::moving::stability::{assess_resolved, VerdictParams};
use contactlab::model::moving::string_data::ContactModel;
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};
use contactlab_verify::moving::study::{flutter_onset, model_eigenvalues, Bushing};

/// Issue 16's data: v̄ = 0.37, ᾱ = 0.03, c̄ = 4.2, m̄ = 0.35, ā = 0.41.
const ISSUE16: (f64, f64, Bushing) = (
    0.37,
    0.03,
    Bushing {
        stiffness: 4.2,
        mass: 0.35,
        position: 0.41,
    },
);
/// The continuum's onset for issue 16's data (moving_flutter).
const P_STAR: f64 = 0.123924612;

fn verdict_onset(disc: StringDiscretization) -> f64 {
    let (speed, damping, bushing) = ISSUE16;
    let model = MovingStringModel::new(disc, Default::default()).unwrap();
    let limit = model_resolution_limit(&model, speed);
    let params = VerdictParams::default();
    let unstable = |p: f64| -> Result<f64, String> {
        let d = bushing.data(speed, damping, ContactModel::Ideal, p / bushing.stiffness);
        let ev = model_eigenvalues(&model, &d)?;
        let a = assess_resolved(&ev, &params, limit);
        Ok(if a.verdict.is_unstable() { 1.0 } else { -1.0 })
    };
    flutter_onset(unstable, "p", 0.5 * P_STAR, 1e-7, 1e3).unwrap()
}

fn resolved_zero_onset(disc: StringDiscretization) -> f64 {
    let (speed, damping, bushing) = ISSUE16;
    let model = MovingStringModel::new(disc, Default::default()).unwrap();
    let limit = model_resolution_limit(&model, speed);
    let g = |p: f64| -> Result<f64, String> {
        let d = bushing.data(speed, damping, ContactModel::Ideal, p / bushing.stiffness);
        let ev = model_eigenvalues(&model, &d)?;
        Ok(ev
            .iter()
            .filter(|l| l.im.abs() <= limit)
            .map(|l| l.re)
            .fold(f64::NEG_INFINITY, f64::max))
    };
    flutter_onset(g, "p", 0.5 * P_STAR, 1e-8, 1e3).unwrap()
}

/// Issue 31, item 3: the flutter onset read from the library's verdict (bisection in p on
/// `assess_resolved(..).verdict`, default parameters) converges to the continuum's p* at rate 1
/// up to N = 320 sines. Measured before the fix (band 1e-7 max|λ| over the whole spectrum):
/// pairwise rates 0.87, 0.40, −0.32, −0.76 (N = 20 … 320); after (band τ(λ) of each
/// eigenvalue): errors 3.84e-3, 1.81e-3, 8.65e-4, 4.40e-4, 2.23e-4, pairwise rates 1.082, 1.068,
/// 0.975, 0.982 — the verdict's onset sits 4.8e-6 above the zero of the largest resolved Re λ
/// (τ(λ*) / (d Re λ/dp) = 2e-7 / 0.041) at every N. Gate: each pairwise rate ≥ 0.92 and the
/// three finest within 0.08 of 1 (the tolerance of `moving_flutter`'s issue-16 onset gate).
/// Reason for the coarsest pair's 1.082: the onset's higher-order term oscillates with the
/// fractional part of N ā (ā = 0.41), pre-asymptotically faster than rate 1 — the zero of the
/// largest resolved Re λ, which no band touches, shows 1.084 there. About 30 s in release
/// (N = 320: 642 × 642 companion spectra in the bisection).
#[test]
fn verdict_onset_converges_at_rate_one_to_320_sines() {
    let sizes = [20usize, 40, 80, 160, 320];
    let errors: Vec<f64> = sizes
        .iter()
        .map(|&n| (verdict_onset(StringDiscretization::Sine { modes: n }) - P_STAR).abs())
        .collect();
    let pairs = sizes.len() - 1;
    for (k, (w, e)) in sizes.windows(2).zip(errors.windows(2)).enumerate() {
        let rate = (e[0] / e[1]).ln() / (w[1] as f64 / w[0] as f64).ln();
        let ok = rate >= 0.92 && (k + 3 < pairs || rate <= 1.08);
        assert!(
            ok,
            "N = {} → {}: errors {:e} → {:e}, rate {rate}",
            w[0], w[1], e[0], e[1]
        );
    }
}

#[test]
#[ignore]
fn measure_verdict_onsets() {
    let discs: Vec<(String, StringDiscretization)> = std::env::var("DISCS")
        .unwrap_or("s20,s40,s80,s160,s320".into())
        .split(',')
        .map(|s| {
            let n: usize = s[1..].parse().unwrap();
            let d = match &s[..1] {
                "s" => StringDiscretization::Sine { modes: n },
                "p" => StringDiscretization::FiniteElements {
                    kind: ElementKind::P1,
                    elements: n,
                },
                _ => StringDiscretization::FiniteElements {
                    kind: ElementKind::Hermite,
                    elements: n,
                },
            };
            (s.to_string(), d)
        })
        .collect();
    let mut prev: Option<(f64, f64, f64)> = None;
    for (name, d) in discs {
        let n: f64 = name[1..].parse().unwrap();
        let t = std::time::Instant::now();
        let v = verdict_onset(d);
        let z = resolved_zero_onset(d);
        let (ev, ez) = ((v - P_STAR).abs(), (z - P_STAR).abs());
        {
            let (speed, damping, bushing) = ISSUE16;
            let model = MovingStringModel::new(d, Default::default()).unwrap();
            let limit = model_resolution_limit(&model, speed);
            let spec = |p: f64| {
                let dd = bushing.data(speed, damping, ContactModel::Ideal, p / bushing.stiffness);
                model_eigenvalues(&model, &dd).unwrap()
            };
            let e0 = spec(z);
            let e1 = spec(z * 1.001);
            let g0 = e0
                .iter()
                .filter(|l| l.im.abs() <= limit)
                .map(|l| l.re)
                .fold(f64::NEG_INFINITY, f64::max);
            let g1 = e1
                .iter()
                .filter(|l| l.im.abs() <= limit)
                .map(|l| l.re)
                .fold(f64::NEG_INFINITY, f64::max);
            let slope = (g1 - g0) / (0.001 * z);
            let rho_all = e0.iter().map(|l| l.norm()).fold(0.0, f64::max);
            let rho_res = e0
                .iter()
                .filter(|l| l.im.abs() <= limit)
                .map(|l| l.norm())
                .fold(0.0, f64::max);
            let unresolved = assess_resolved(&e0, &VerdictParams::default(), limit).unresolved;
            println!(
                "   unresolved unstable at the zero onset: {} from {:.3e} to {:.3e}",
                unresolved.count, unresolved.frequency_from, unresolved.frequency_to
            );
            println!("   limit {limit:.3e} rho_all {rho_all:.3e} rho_res {rho_res:.3e} slope {slope:.3e}");
        }
        let rates = prev
            .map(|(n0, e0v, e0z)| {
                (
                    (e0v / ev).ln() / (n / n0).ln(),
                    (e0z / ez).ln() / (n / n0).ln(),
                )
            })
            .unwrap_or((f64::NAN, f64::NAN));
        println!(
            "{name}: verdict {v:.9} err {ev:.3e} rate {:.3} | zero {z:.9} err {ez:.3e} rate {:.3} ({:.1} s)",
            rates.0,
            rates.1,
            t.elapsed().as_secs_f64()
        );
        prev = Some((n, ev, ez));
    }
}

use contactlab::model::moving::plate::modes::harmonic_frequencies;
use contactlab::model::moving::plate::PlateProperties;
use contactlab_verify::exact::plate_annulus::{AnnularPlate, OuterEdge as ExactEdge};

/// The largest relative error of ω_{n,m} (n = 0 … 2, m = 0, 1) of the free-edge annulus on
/// `elements` radial elements against the Bessel roots, and that of the lowest critical speed
/// min_{n = 1, 2} ω_{n,0}/n (attained at n = 2).
fn plate_errors(elements: usize, refs: &[Vec<f64>]) -> (f64, f64) {
    let plate = PlateProperties::default();
    let mut err: f64 = 0.0;
    let mut crit = f64::INFINITY;
    for (n, reference) in refs.iter().enumerate() {
        let w = harmonic_frequencies(&plate, elements, n, 2).unwrap();
        for (wh, we) in w.iter().zip(reference) {
            err = err.max((wh - we).abs() / we);
        }
        if n >= 1 {
            crit = crit.min(w[0] / n as f64);
        }
    }
    let exact = (1..refs.len())
        .map(|n| refs[n][0] / n as f64)
        .fold(f64::INFINITY, f64::min);
    (err, (crit - exact).abs() / exact)
}

/// Issue 31, item 4 (measured at the fix, n = 0 … 4: 2.0e-7, 1.2e-8, 7.8e-10, 4.9e-11 at
/// M = 64, 128, 256, 512, pairwise rates 3.98, 3.995, 3.996; before it, through the mass
/// factor, 1.5e-7 at 128 and 1e-4 at 512). The gate: M = 512 at least as accurate as M = 64,
/// and within the discretization error model e(64)(64/512)^r with r the rate measured on the
/// coarse pair 32 → 64 (3.92: the rate approaches 4 from below, so the model extrapolated from
/// the coarse pair bounds the fine errors), for the frequencies and the lowest critical speed.
/// About 2 s (M = 512, three harmonics).
#[test]
fn plate_frequencies_keep_rate_four_to_512_elements() {
    let plate = PlateProperties::default();
    let exact = AnnularPlate::annulus(
        plate.inner_radius,
        plate.outer_radius,
        plate.poisson,
        ExactEdge::Free,
    );
    let refs: Vec<Vec<f64>> = (0..=2)
        .map(|n| {
            exact
                .natural_frequencies(n, 2, plate.bending_stiffness, plate.mass_per_area)
                .unwrap()
        })
        .collect();
    let (e32, c32) = plate_errors(32, &refs);
    let (e64, c64) = plate_errors(64, &refs);
    let (e512, c512) = plate_errors(512, &refs);
    let rate = (e32 / e64).log2();
    let crit_rate = (c32 / c64).log2();
    assert!((3.5..=4.5).contains(&rate), "coarse rate {rate}");
    let model = e64 * (64.0f64 / 512.0).powf(rate);
    let crit_model = c64 * (64.0f64 / 512.0).powf(crit_rate);
    assert!(
        e512 <= e64 && e512 <= model,
        "frequencies: e(512) = {e512:e}, e(64) = {e64:e}, model {model:e}"
    );
    assert!(
        c512 <= c64 && c512 <= crit_model,
        "critical speed: e(512) = {c512:e}, e(64) = {c64:e}, model {crit_model:e}"
    );
}

/// Issue 31: past the critical speed the fixed-fixed string's Ritz models flutter with a growth
/// rate that grows with N (the continuum's eigenvalues inπ(1 − v̄²) stay imaginary): the verdict
/// must carry the supercritical warning, below v̄ = 1 it must not, and λ₁ converges either way.
#[test]
fn past_the_critical_speed_the_verdict_carries_a_warning_whose_growth_rate_grows_with_n() {
    use contactlab::model::moving::linearized::assess_point;
    use contactlab::model::moving::stability::Verdict;
    use contactlab::model::moving::string_data::MovingStringData;
    for v in [0.5f64, 1.5] {
        let exact = std::f64::consts::PI * (1.0 - v * v).abs();
        let (mut rates, mut errors) = (Vec::new(), Vec::new());
        for n in [20, 40] {
            let model =
                MovingStringModel::new(StringDiscretization::Sine { modes: n }, Default::default())
                    .unwrap();
            let d = MovingStringData {
                speed: v,
                damping: 0.0,
                oscillator: None,
            };
            let ev = model_eigenvalues(&model, &d).unwrap();
            let a = assess_point(&model, &d, &ev, &VerdictParams::default());
            let lowest = ev
                .iter()
                .filter(|l| l.im > 0.0)
                .map(|l| l.im)
                .fold(f64::INFINITY, f64::min);
            errors.push((lowest - exact).abs() / exact);
            match a.supercritical {
                None => {
                    assert!(v < 1.0, "no warning at v̄ = {v}");
                    assert_eq!(a.verdict, Verdict::Marginal);
                }
                Some(w) => {
                    assert!(v > 1.0, "a warning at v̄ = {v}");
                    assert_eq!(a.verdict, Verdict::Flutter);
                    rates.push(w.discrete_growth_rate);
                }
            }
        }
        assert!(errors[1] < errors[0], "v̄ = {v}: λ₁ errors {errors:?}");
        assert!(rates.windows(2).all(|r| r[1] > r[0]), "v̄ = {v}: {rates:?}");
    }
}
