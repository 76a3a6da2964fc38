//! Self-convergence without an exact solution: the values F_i of a functional on runs at
//! (h_i, k_i) fitted by
//!
//! F(h, k) ≈ F* + a h^p + b k^q,
//!
//! the two-parameter Richardson model: F* is the extrapolated value, a h^p and b k^q the space and
//! time parts of the discretization error (signed). The fit is by variable projection: for fixed
//! (p, q) the model is linear in (F*, a, b), solved by least squares; the residual sum of squares
//! is minimised over (p, q) on a grid of step 0.02 in [0.2, 5], then refined on a grid of step
//! 5e−4 around the best point. Deterministic (no random starts), and it cannot diverge.
//!
//! Where one part is negligible over every run (its largest magnitude below [`NEGLIGIBLE`] times
//! the other's), its order is not determined by the data: the one-part model F* + b k^q (or
//! F* + a h^p) is fitted instead, and the missing order is reported as None.

use serde::Serialize;

use crate::stats::FitError;

/// A part whose largest magnitude over the runs is below this fraction of the other's is
/// negligible.
pub const NEGLIGIBLE: f64 = 0.01;
/// The order grid: [ORDER_MIN, ORDER_MAX].
const ORDER_MIN: f64 = 0.2;
const ORDER_MAX: f64 = 5.0;

/// The fitted model F* + a h^p + b k^q (a part left out: its coefficient 0, its order None).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Extrapolation {
    /// F*, the extrapolated value.
    pub value: f64,
    pub a: f64,
    pub p: Option<f64>,
    pub b: f64,
    pub q: Option<f64>,
    /// rms residual / rms |F_i − F*|: the model's misfit relative to the discretization errors
    /// it describes.
    pub relative_residual: f64,
    pub points: usize,
}

impl Extrapolation {
    /// The model of values that do not change over the runs: F = `value`, no error.
    pub fn constant(value: f64, points: usize) -> Self {
        Self {
            value,
            a: 0.0,
            p: None,
            b: 0.0,
            q: None,
            relative_residual: 0.0,
            points,
        }
    }

    /// The bound |a| h^p + |b| k^q of the discretization error at (h, k) (the parts' magnitudes
    /// added: no point of cancellation between them is ever relied upon).
    pub fn error_bound(&self, h: f64, k: f64) -> f64 {
        let s = self.p.map_or(0.0, |p| self.a.abs() * h.powf(p));
        let t = self.q.map_or(0.0, |q| self.b.abs() * k.powf(q));
        s + t
    }

    /// A part whose fitted order lies on the edge of the searched interval [0.2, 5] (within the
    /// refinement's step): the residual still falls beyond it, so the data do not determine that
    /// order — ("p" or "q", the order).
    pub fn order_at_search_bound(&self) -> Option<(&'static str, f64)> {
        let at_edge = |o: f64| o <= ORDER_MIN + 1e-3 || o >= ORDER_MAX - 1e-3;
        [("p", self.p), ("q", self.q)]
            .into_iter()
            .find_map(|(name, o)| o.filter(|&o| at_edge(o)).map(|o| (name, o)))
    }

    /// F(h, k) of the model.
    pub fn predict(&self, h: f64, k: f64) -> f64 {
        let s = self.p.map_or(0.0, |p| self.a * h.powf(p));
        let t = self.q.map_or(0.0, |q| self.b * k.powf(q));
        self.value + s + t
    }
}

/// Least squares of f ≈ Σ_j c_j φ_j (columns `basis`, 2 or 3 of them): (c, residual sum of
/// squares), None when the normal equations are singular.
fn linear_fit(basis: &[Vec<f64>], f: &[f64]) -> Option<(Vec<f64>, f64)> {
    let m = basis.len();
    let mut g = vec![vec![0.0; m]; m];
    let mut r = vec![0.0; m];
    for i in 0..m {
        for j in 0..m {
            g[i][j] = basis[i].iter().zip(&basis[j]).map(|(x, y)| x * y).sum();
        }
        r[i] = basis[i].iter().zip(f).map(|(x, y)| x * y).sum();
    }
    // Gaussian elimination with partial pivoting (m ≤ 3)
    let scale = (0..m).map(|i| g[i][i].abs()).fold(0.0, f64::max);
    for c in 0..m {
        let piv = (c..m).max_by(|&x, &y| g[x][c].abs().total_cmp(&g[y][c].abs()))?;
        if g[piv][c].abs() <= 1e-13 * scale {
            return None;
        }
        g.swap(c, piv);
        r.swap(c, piv);
        for row in c + 1..m {
            let f = g[row][c] / g[c][c];
            for col in c..m {
                g[row][col] -= f * g[c][col];
            }
            r[row] -= f * r[c];
        }
    }
    let mut x = vec![0.0; m];
    for c in (0..m).rev() {
        let s: f64 = (c + 1..m).map(|j| g[c][j] * x[j]).sum();
        x[c] = (r[c] - s) / g[c][c];
    }
    let rss = f
        .iter()
        .enumerate()
        .map(|(i, fi)| {
            let model: f64 = (0..m).map(|j| x[j] * basis[j][i]).sum();
            (fi - model).powi(2)
        })
        .sum();
    Some((x, rss))
}

/// The best order(s) on the grid and its refinement: `eval(p, q)` → residual sum of squares
/// (None: singular); `two` = whether q is searched too.
fn search(two: bool, eval: &dyn Fn(f64, f64) -> Option<f64>) -> Option<(f64, f64)> {
    // the best (p, q, rss) over a grid of step `step`, starting from `best`
    let scan = |best: Option<(f64, f64, f64)>,
                (lo_p, hi_p): (f64, f64),
                (lo_q, hi_q): (f64, f64),
                step: f64| {
        let mut best = best;
        let np = ((hi_p - lo_p) / step).round() as usize;
        let nq = if two {
            ((hi_q - lo_q) / step).round() as usize
        } else {
            0
        };
        for i in 0..=np {
            let p = lo_p + step * i as f64;
            for j in 0..=nq {
                let q = lo_q + step * j as f64;
                if let Some(rss) = eval(p, q) {
                    if best.is_none_or(|b: (f64, f64, f64)| rss < b.2) {
                        best = Some((p, q, rss));
                    }
                }
            }
        }
        best
    };
    let coarse = scan(None, (ORDER_MIN, ORDER_MAX), (ORDER_MIN, ORDER_MAX), 0.02);
    let (p0, q0, _) = coarse?;
    let near = |v: f64| ((v - 0.02).max(ORDER_MIN), (v + 0.02).min(ORDER_MAX));
    scan(coarse, near(p0), near(q0), 5e-4).map(|(p, q, _)| (p, q))
}

fn check(h: &[f64], k: &[f64], f: &[f64]) -> Result<(), FitError> {
    for (name, v) in [("h", h), ("k", k)] {
        if v.len() != f.len() {
            return Err(FitError::LengthMismatch {
                name,
                found: v.len(),
                expected: f.len(),
            });
        }
        if let Some((index, &value)) = v
            .iter()
            .enumerate()
            .find(|(_, x)| !(x.is_finite() && **x > 0.0))
        {
            return Err(FitError::InvalidValue { name, index, value });
        }
    }
    if let Some((index, &value)) = f.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(FitError::InvalidValue {
            name: "value",
            index,
            value,
        });
    }
    if f.len() < 6 {
        return Err(FitError::TooFewPoints {
            needed: 6,
            found: f.len(),
        });
    }
    Ok(())
}

fn distinct(v: &[f64]) -> usize {
    let mut s: Vec<f64> = v.to_vec();
    s.sort_by(f64::total_cmp);
    s.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * b.abs());
    s.len()
}

/// The model (value, a, p, b, q) with its relative residual over the runs.
fn finish(
    (value, a, p, b, q): (f64, f64, Option<f64>, f64, Option<f64>),
    h: &[f64],
    k: &[f64],
    f: &[f64],
) -> Extrapolation {
    let mut e = Extrapolation {
        value,
        a,
        p,
        b,
        q,
        relative_residual: 0.0,
        points: f.len(),
    };
    let n = f.len() as f64;
    let res: f64 = f
        .iter()
        .zip(h.iter().zip(k))
        .map(|(fi, (hi, ki))| (fi - e.predict(*hi, *ki)).powi(2))
        .sum::<f64>()
        / n;
    let spread: f64 = f.iter().map(|fi| (fi - value).powi(2)).sum::<f64>() / n;
    e.relative_residual = if spread > 0.0 {
        (res / spread).sqrt()
    } else {
        0.0
    };
    e
}

/// Fits F* + a h^p + b k^q to the values `f` at (`h`, `k`) (module docs).
///
/// # Errors
/// Mismatched lengths, a non-positive h or k, a non-finite value, fewer than 6 runs, fewer than
/// 3 distinct h or k (the orders are then not determined).
pub fn fit_extrapolation(h: &[f64], k: &[f64], f: &[f64]) -> Result<Extrapolation, FitError> {
    check(h, k, f)?;
    for (parameter, v) in [("p", h), ("q", k)] {
        if distinct(v) < 3 {
            return Err(FitError::Unidentifiable {
                parameter,
                reason: format!("{} distinct values; 3 are needed", distinct(v)),
            });
        }
    }
    let ones = vec![1.0; f.len()];
    let powers = |x: &[f64], r: f64| x.iter().map(|v| v.powf(r)).collect::<Vec<f64>>();
    let two = |p: f64, q: f64| {
        linear_fit(&[ones.clone(), powers(h, p), powers(k, q)], f).map(|(_, rss)| rss)
    };
    let constant = f.iter().all(|v| *v == f[0]);
    if constant {
        return Ok(finish((f[0], 0.0, None, 0.0, None), h, k, f));
    }
    let (p, q) = search(true, &two).ok_or(FitError::RankDeficient { ratio: 0.0 })?;
    let (c, _) = linear_fit(&[ones.clone(), powers(h, p), powers(k, q)], f)
        .ok_or(FitError::RankDeficient { ratio: 0.0 })?;
    let max_of =
        |x: &[f64], c: f64, r: f64| x.iter().map(|v| (c * v.powf(r)).abs()).fold(0.0, f64::max);
    let (space, time) = (max_of(h, c[1], p), max_of(k, c[2], q));
    if space < NEGLIGIBLE * time || time < NEGLIGIBLE * space {
        // one part: its order alone
        let (x, in_space) = if space < NEGLIGIBLE * time {
            (k, false)
        } else {
            (h, true)
        };
        let one = |r: f64, _: f64| linear_fit(&[ones.clone(), powers(x, r)], f).map(|(_, rss)| rss);
        let (r, _) = search(false, &one).ok_or(FitError::RankDeficient { ratio: 0.0 })?;
        let (c, _) = linear_fit(&[ones.clone(), powers(x, r)], f)
            .ok_or(FitError::RankDeficient { ratio: 0.0 })?;
        return Ok(if in_space {
            finish((c[0], c[1], Some(r), 0.0, None), h, k, f)
        } else {
            finish((c[0], 0.0, None, c[1], Some(r)), h, k, f)
        });
    }
    Ok(finish((c[0], c[1], Some(p), c[2], Some(q)), h, k, f))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(f: impl Fn(f64, f64) -> f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let (mut h, mut k, mut v) = (Vec::new(), Vec::new(), Vec::new());
        for &hi in &[0.2, 0.1, 0.05] {
            for &ki in &[0.08, 0.04, 0.02] {
                h.push(hi);
                k.push(ki);
                v.push(f(hi, ki));
            }
        }
        (h, k, v)
    }

    #[test]
    fn a_richardson_model_with_opposite_signs_is_recovered() {
        // space error positive, time error negative: the errors partly cancel on some runs
        let (h, k, f) = grid(|h, k| 3.0 + 0.7 * h * h - 0.4 * k);
        let e = fit_extrapolation(&h, &k, &f).unwrap();
        assert!((e.value - 3.0).abs() < 1e-4, "{e:?}");
        assert!((e.p.unwrap() - 2.0).abs() < 2e-3 && (e.q.unwrap() - 1.0).abs() < 2e-3);
        assert!((e.a - 0.7).abs() < 5e-3 && (e.b + 0.4).abs() < 5e-3);
        // the bound adds the magnitudes: never below the true error
        let (hh, kk): (f64, f64) = (0.01, 0.005);
        let truth = (0.7 * hh * hh - 0.4 * kk).abs();
        assert!(e.error_bound(hh, kk) >= 0.99 * truth);
    }

    #[test]
    fn a_part_negligible_over_every_run_leaves_its_order_undetermined() {
        let (h, k, f) = grid(|_, k| -1.0 + 2.0 * k * k);
        let e = fit_extrapolation(&h, &k, &f).unwrap();
        assert_eq!(e.p, None);
        assert!(
            (e.q.unwrap() - 2.0).abs() < 1e-3 && (e.value + 1.0).abs() < 1e-6,
            "{e:?}"
        );
    }

    #[test]
    fn a_model_that_does_not_describe_the_runs_shows_a_large_relative_residual() {
        // an oscillating functional: no power law
        let (h, k, f) = grid(|h, k| (40.0 * h).sin() + (90.0 * k).cos());
        let e = fit_extrapolation(&h, &k, &f).unwrap();
        assert!(e.relative_residual > 0.15, "{e:?}");
    }

    #[test]
    fn an_order_beyond_the_searched_interval_is_flagged_on_its_edge() {
        // a space part of order 7, steeper than any order searched: the fit stops at p = 5,
        // and says that p is not determined; a part of order 2 is not flagged
        let (h, k, f) = grid(|h, k| 1.0 + 40.0 * h.powi(7) + 0.5 * k * k);
        let e = fit_extrapolation(&h, &k, &f).unwrap();
        assert_eq!(
            e.order_at_search_bound().map(|(n, _)| n),
            Some("p"),
            "{e:?}"
        );
        let (h, k, f) = grid(|h, k| 1.0 + 0.7 * h * h + 0.5 * k);
        assert_eq!(
            fit_extrapolation(&h, &k, &f)
                .unwrap()
                .order_at_search_bound(),
            None
        );
    }

    #[test]
    fn too_few_distinct_steps_are_a_typed_error() {
        let h = [0.1, 0.05, 0.025, 0.1, 0.05, 0.025];
        let k = [0.1, 0.1, 0.1, 0.05, 0.05, 0.05];
        let f = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        assert!(matches!(
            fit_extrapolation(&h, &k, &f),
            Err(FitError::Unidentifiable { parameter: "q", .. })
        ));
    }
}
