//! The contact problem condensed onto the Γ3 dofs:
//!
//!   S w_Γ + C_Γᵀ W p_ν(C_Γ w_Γ + G α) = b̂,        Gᵀ W p_ν(C_Γ w_Γ + G α) = b_R,
//!
//! with S = L_ΓΓ L_ΓΓᵀ the Schur complement of the step operator on the Γ3 dofs, C_Γ the contact
//! points' normal-velocity rows, W the quadrature weights, b̂ the condensed right-hand side and —
//! only for a body that Γ1 leaves free to move rigidly — α the amplitude of the free rigid motion R,
//! G = C R and b_R = Rᵀ b the load on it.
//!
//! For fixed α the first equation is the gradient of a strictly convex functional (S is SPD and
//! p_ν monotone), so semismooth Newton with the SPD generalized Jacobian S + C_Γᵀ W diag(p_ν') C_Γ
//! and a backtracking line search converges; for piecewise-linear laws it is exact once the active
//! set is right. The Jacobian is factored once per set of slopes and reused while they do not
//! change (typically from step to step). The rigid-motion equation is a nondecreasing scalar
//! equation in α, solved by safeguarded Newton after an existence check: the contact forces can
//! only balance loads inside the range the law's pressures allow.

use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par};

use crate::contact::normal_law::{NormalLaw, SpaceTime};
use crate::solve::dense_cholesky::cholesky_factor;
use crate::solve::scalar_semismooth::{solve_increasing, Evaluation, ScalarNewtonParams};

/// Why the condensed contact problem was not solved.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactFailure {
    /// `residual` and `floor` relative to the magnitudes of the residual's terms.
    NotConverged {
        iterations: usize,
        residual: f64,
        floor: f64,
    },
    NonFinite,
    NoEquilibrium(String),
}

/// Parameters of the condensed contact Newton method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactNewtonParams {
    pub relative_tolerance: f64,
    pub max_iterations: usize,
}

impl Default for ContactNewtonParams {
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-13,
            max_iterations: 200,
        }
    }
}

/// One contact point's row of C_Γ: (Γ index, coefficient) pairs.
pub type ContactRow = Vec<(usize, f64)>;

/// The condensed contact problem of one step operator, with its factorization cache.
#[derive(Debug)]
pub struct CondensedContact {
    /// S (m × m).
    pub s: Mat<f64>,
    pub rows: Vec<ContactRow>,
    /// G = C R per point (q = 0 or 1 column).
    pub g: Vec<f64>,
    pub weights: Vec<f64>,
    pub points: Vec<SpaceTime>,
    cache_slopes: Vec<f64>,
    /// The Cholesky factor L of the cached Jacobian (lower triangle; `Par::Seq`: the same bits
    /// whatever the thread count).
    cache: Option<Mat<f64>>,
    /// The Newton right-hand side, m × 1 (allocated once).
    rhs: Mat<f64>,
    /// Point values, and Σ|terms| of each r (the round-off scale of r).
    r: Vec<f64>,
    r_abs: Vec<f64>,
    p: Vec<f64>,
    dp: Vec<f64>,
    /// Γ vectors: the residual and the magnitudes of its terms per row.
    res: Vec<f64>,
    res_abs: Vec<f64>,
    step: Vec<f64>,
    trial: Vec<f64>,
    pub factorizations: usize,
    /// Solves that stopped at the round-off floor of the residual above the requested tolerance.
    pub floor_stops: usize,
}

/// The norms of the condensed residual at one iterate.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ResidualNorms {
    /// ‖res‖∞ and ‖res‖₂.
    inf: f64,
    two: f64,
    /// max_i a_i, the sum of the magnitudes of the terms of row i.
    scale: f64,
    /// The round-off floor of ‖res‖∞ relative to `scale`: (√m + 2) ε.
    floor: f64,
}

impl ResidualNorms {
    /// ‖res‖∞ / scale.
    fn relative(&self) -> f64 {
        self.inf / self.scale.max(f64::MIN_POSITIVE)
    }
}

impl CondensedContact {
    /// The problem for Schur complement `s`, point rows, G, weights and positions.
    pub fn new(
        s: Mat<f64>,
        rows: Vec<ContactRow>,
        g: Vec<f64>,
        weights: Vec<f64>,
        points: Vec<SpaceTime>,
    ) -> Self {
        let (m, nc) = (s.nrows(), weights.len());
        Self {
            s,
            rows,
            g,
            weights,
            points,
            cache_slopes: Vec::new(),
            cache: None,
            rhs: Mat::zeros(m, 1),
            r: vec![0.0; nc],
            r_abs: vec![0.0; nc],
            p: vec![0.0; nc],
            dp: vec![0.0; nc],
            res: vec![0.0; m],
            res_abs: vec![0.0; m],
            step: vec![0.0; m],
            trial: vec![0.0; m],
            factorizations: 0,
            floor_stops: 0,
        }
    }

    /// Number of contact points.
    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// Whether there are no contact points.
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }

    /// r = C_Γ w + G α and the law at r.
    fn eval_points(&mut self, law: &dyn NormalLaw, w: &[f64], alpha: f64, t: f64) {
        for (pt, row) in self.rows.iter().enumerate() {
            let mut r = if self.g.is_empty() {
                0.0
            } else {
                self.g[pt] * alpha
            };
            let mut r_abs = r.abs();
            for &(i, c) in row {
                r += c * w[i];
                r_abs += (c * w[i]).abs();
            }
            let at = SpaceTime {
                t,
                ..self.points[pt]
            };
            self.r[pt] = r;
            self.r_abs[pt] = r_abs;
            self.p[pt] = law.value(r, at);
            self.dp[pt] = law.derivative(r, at);
        }
    }

    /// The energy ½ wᵀ S w − b̂ᵀ w + Σ_g W_g Ψ(r_g) whose gradient is the residual (needs
    /// `eval_points` at w and a law with a potential), or `None`.
    fn energy(&self, law: &dyn NormalLaw, w: &[f64], b: &[f64], t: f64) -> Option<f64> {
        let m = w.len();
        let mut e = 0.0;
        for i in 0..m {
            let mut sw = 0.0;
            for j in 0..m {
                sw += self.s[(i, j)] * w[j];
            }
            e += 0.5 * w[i] * sw - b[i] * w[i];
        }
        for g in 0..self.len() {
            let at = SpaceTime {
                t,
                ..self.points[g]
            };
            e += self.weights[g] * law.potential(self.r[g], at)?;
        }
        Some(e)
    }

    /// res = S w + C_Γᵀ W p − b̂ (needs `eval_points` at w); returns its [`ResidualNorms`].
    ///
    /// Row i of the residual is a sum of terms S_ij w_j, −b̂_i and c W p_ν; its scale is the sum of
    /// their magnitudes a_i = Σ_j |S_ij w_j| + |b̂_i| + Σ |c W p_ν| (+ |c W p_ν′| Σ|c w|, the
    /// round-off of r carried through the law's slope). Near the solution the terms cancel (500-fold
    /// on a 4 000-node mesh), so the computed residual cannot go below its round-off floor
    /// (√m + 2) ε a_i: √m ε a_i for the rounding of a sum of m terms (the probabilistic bound of
    /// floating-point summation) and 2 ε a_i for w itself, representable only to ε |w_j|.
    fn residual(&mut self, w: &[f64], b: &[f64]) -> ResidualNorms {
        let m = w.len();
        self.res_abs.iter_mut().for_each(|a| *a = 0.0);
        for i in 0..m {
            let mut sw = 0.0;
            let mut sw_abs = 0.0;
            for j in 0..m {
                let term = self.s[(i, j)] * w[j];
                sw += term;
                sw_abs += term.abs();
            }
            self.res[i] = sw - b[i];
            self.res_abs[i] = sw_abs + b[i].abs();
        }
        for (pt, row) in self.rows.iter().enumerate() {
            let f = self.weights[pt] * self.p[pt];
            // p_ν amplifies the round-off of r (a sum of terms of size r_abs) by its slope.
            let f_noise = self.weights[pt] * self.dp[pt] * self.r_abs[pt];
            for &(i, c) in row {
                self.res[i] += c * f;
                self.res_abs[i] += (c * f).abs() + (c * f_noise).abs();
            }
        }
        let inf = self.res.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let two = self.res.iter().map(|v| v * v).sum::<f64>().sqrt();
        let scale = self.res_abs.iter().fold(0.0f64, |a, v| a.max(*v));
        let floor = ((m as f64).sqrt() + 2.0) * f64::EPSILON;
        ResidualNorms {
            inf,
            two,
            scale,
            floor,
        }
    }

    /// Factors S + C_Γᵀ W diag(p′) C_Γ unless the slopes are those of the cached factor.
    fn factor(&mut self) -> Result<(), ContactFailure> {
        if self.cache.is_some() && self.cache_slopes == self.dp {
            return Ok(());
        }
        let mut j = self.s.clone();
        for (pt, row) in self.rows.iter().enumerate() {
            let d = self.weights[pt] * self.dp[pt];
            if d != 0.0 {
                for &(a, ca) in row {
                    for &(b, cb) in row {
                        j[(a, b)] += d * ca * cb;
                    }
                }
            }
        }
        let l = cholesky_factor(j.as_ref()).map_err(|_| ContactFailure::NonFinite)?;
        self.cache = Some(l);
        self.cache_slopes.clone_from(&self.dp);
        self.factorizations += 1;
        Ok(())
    }

    /// Solves the first equation for w_Γ at fixed α (in place, from the given guess). Returns the
    /// Newton iteration count.
    pub fn solve(
        &mut self,
        law: &dyn NormalLaw,
        t: f64,
        b: &[f64],
        alpha: f64,
        w: &mut [f64],
        params: &ContactNewtonParams,
    ) -> Result<usize, ContactFailure> {
        let m = w.len();
        self.eval_points(law, w, alpha, t);
        let mut norms = self.residual(w, b);
        for it in 0..=params.max_iterations {
            if !norms.inf.is_finite() {
                return Err(ContactFailure::NonFinite);
            }
            // Converged: below the requested tolerance or at the computed round-off floor (both
            // relative to the same scale, the magnitudes of the residual's terms).
            let relative = norms.relative();
            if relative <= params.relative_tolerance {
                return Ok(it);
            }
            if relative <= norms.floor {
                self.floor_stops += 1;
                return Ok(it);
            }
            if it == params.max_iterations {
                return Err(ContactFailure::NotConverged {
                    iterations: it,
                    residual: relative,
                    floor: norms.floor,
                });
            }
            self.factor()?;
            for i in 0..m {
                self.rhs[(i, 0)] = -self.res[i];
            }
            if let Some(l) = &self.cache {
                solve_lower_triangular_in_place(l.as_ref(), self.rhs.as_mut(), Par::Seq);
                solve_upper_triangular_in_place(l.transpose(), self.rhs.as_mut(), Par::Seq);
            }
            for i in 0..m {
                self.step[i] = self.rhs[(i, 0)];
            }
            if self.step.iter().any(|v| !v.is_finite()) {
                return Err(ContactFailure::NonFinite);
            }
            let (next, lambda) = self.line_search(law, t, b, alpha, w, norms.two);
            if lambda < 1e-9 && next.two >= norms.two {
                // No descent along the Newton direction even at λ = 2⁻³⁰: the residual is at its
                // round-off, whatever the estimate of the floor says.
                self.floor_stops += 1;
                return Ok(it + 1);
            }
            norms = next;
        }
        unreachable!("the loop returns")
    }

    /// Backtracking along `self.step` from `w` (overwritten with the accepted point): on the
    /// energy when the law has a potential (the Newton direction of a strictly convex functional
    /// is a descent direction, so this globalizes), otherwise on ‖res‖₂. Returns the norms at the
    /// accepted point and the step length λ (λ < 1e-9: no decrease found).
    fn line_search(
        &mut self,
        law: &dyn NormalLaw,
        t: f64,
        b: &[f64],
        alpha: f64,
        w: &mut [f64],
        base: f64,
    ) -> (ResidualNorms, f64) {
        let m = w.len();
        let e0 = self.energy(law, w, b, t);
        let mut lambda = 1.0;
        self.trial.copy_from_slice(w);
        let slope: f64 = self.step.iter().zip(&self.res).map(|(d, r)| d * r).sum();
        loop {
            for i in 0..m {
                w[i] = self.trial[i] + lambda * self.step[i];
            }
            self.eval_points(law, w, alpha, t);
            let norms = self.residual(w, b);
            let accept = match (e0, self.energy(law, w, b, t)) {
                (Some(e0), Some(e1)) => {
                    e1 <= e0 + 1e-4 * lambda * slope || (e1 - e0).abs() <= 1e-15 * e0.abs()
                }
                _ => norms.two < base,
            };
            if accept || lambda < 1e-9 {
                return (norms, lambda);
            }
            lambda *= 0.5;
        }
    }

    /// dφ/dα for φ(α) = Gᵀ W p(r(α)): with D = W diag(p′), dw/dα = −J⁻¹ C_Γᵀ D G,
    /// dr/dα = C_Γ dw/dα + G, dφ/dα = Gᵀ D dr/dα (uses the cached J of the last Newton step).
    fn floating_slope(&mut self) -> Result<f64, ContactFailure> {
        self.factor()?;
        self.rhs.fill(0.0);
        for (pt, row) in self.rows.iter().enumerate() {
            let d = self.weights[pt] * self.dp[pt] * self.g[pt];
            for &(i, c) in row {
                self.rhs[(i, 0)] -= c * d;
            }
        }
        if let Some(l) = &self.cache {
            solve_lower_triangular_in_place(l.as_ref(), self.rhs.as_mut(), Par::Seq);
            solve_upper_triangular_in_place(l.transpose(), self.rhs.as_mut(), Par::Seq);
        }
        let mut slope = 0.0;
        for (pt, row) in self.rows.iter().enumerate() {
            let mut dr = self.g[pt];
            for &(i, c) in row {
                dr += c * self.rhs[(i, 0)];
            }
            slope += self.g[pt] * self.weights[pt] * self.dp[pt] * dr;
        }
        Ok(slope)
    }

    /// The limits of α ↦ Gᵀ W p_ν(r(α)) as α → ∓∞: every point that moves with the rigid motion
    /// (G_g ≠ 0) goes to ±∞ in r, where p_ν tends to the ends of its range.
    fn attainable(&self, law: &dyn NormalLaw, t: f64) -> (f64, f64) {
        let (mut lo, mut hi) = (0.0, 0.0);
        for g in 0..self.len() {
            let gg = self.g[g];
            if gg == 0.0 {
                continue;
            }
            let (inf, sup) = law.range(SpaceTime {
                t,
                ..self.points[g]
            });
            let w = self.weights[g] * gg;
            let (at_plus, at_minus) = if gg > 0.0 { (sup, inf) } else { (inf, sup) };
            hi += w * at_plus;
            lo += w * at_minus;
        }
        (lo, hi)
    }

    /// Solves the floating problem: w_Γ(α) from [`Self::solve`], and α from
    /// Gᵀ W p_ν(r(α)) = b_R. Returns (α, total Newton iterations).
    #[allow(clippy::too_many_arguments)]
    pub fn solve_floating(
        &mut self,
        law: &dyn NormalLaw,
        t: f64,
        b: &[f64],
        b_r: f64,
        w: &mut [f64],
        alpha_guess: f64,
        params: &ContactNewtonParams,
    ) -> Result<(f64, usize), ContactFailure> {
        let (lo, hi) = self.attainable(law, t);
        let finite = |v: f64| if v.is_finite() { v.abs() } else { 0.0 };
        let scale = b_r
            .abs()
            .max(finite(lo))
            .max(finite(hi))
            .max(f64::MIN_POSITIVE);
        if !(lo < b_r - 1e-12 * scale && b_r + 1e-12 * scale < hi) {
            return Err(ContactFailure::NoEquilibrium(format!(
                "Γ1 leaves a rigid motion free and only the contact carries it: the load on that motion \
                 is {b_r:.6} N but the contact forces can only balance loads in ({lo:.6}, {hi:.6}) N \
                 (the pressures of the contact law are bounded)"
            )));
        }
        let mut total = 0usize;
        let mut failure: Option<ContactFailure> = None;
        let root = solve_increasing(
            |alpha| {
                let nan = Evaluation {
                    value: f64::NAN,
                    slope: 1.0,
                    scale: 1.0,
                };
                if failure.is_some() {
                    return nan;
                }
                match self.solve(law, t, b, alpha, w, params) {
                    Ok(it) => total += it,
                    Err(e) => {
                        failure = Some(e);
                        return nan;
                    }
                }
                let mut value = -b_r;
                let mut mag = b_r.abs();
                for g in 0..self.len() {
                    let term = self.g[g] * self.weights[g] * self.p[g];
                    value += term;
                    mag += term.abs();
                }
                let slope = match self.floating_slope() {
                    Ok(s) => s,
                    Err(e) => {
                        failure = Some(e);
                        return nan;
                    }
                };
                // The inner solve leaves w accurate to its relative tolerance; φ inherits that error
                // amplified by its slope (large for stiff dampers): the outer tolerance accounts
                // for it instead of asking for the impossible.
                let r_scale = self.r.iter().fold(0.0f64, |a, v| a.max(v.abs())) + alpha.abs();
                let noise = 100.0 * params.relative_tolerance * slope.abs() * r_scale;
                Evaluation {
                    value,
                    slope,
                    scale: mag + noise / 8.0 / f64::EPSILON,
                }
            },
            alpha_guess,
            &ScalarNewtonParams {
                relative_tolerance: 8.0 * f64::EPSILON,
                max_iterations: 200,
            },
        );
        if let Some(f) = failure {
            return Err(f);
        }
        match root {
            Ok(root) => {
                total += self.solve(law, t, b, root.r, w, params)?;
                Ok((root.r, total))
            }
            Err(e) => {
                // |φ| and its absolute tolerance τ · scale: relative to the scale both
                let scale = e.tolerance / (8.0 * f64::EPSILON);
                Err(ContactFailure::NotConverged {
                    iterations: e.iterations,
                    residual: e.residual.abs() / scale.max(f64::MIN_POSITIVE),
                    floor: 8.0 * f64::EPSILON,
                })
            }
        }
    }

    /// W p at the last evaluation, per point.
    pub fn weighted_pressures(&self, out: &mut [f64]) {
        for g in 0..self.len() {
            out[g] = self.weights[g] * self.p[g];
        }
    }

    /// r and p_ν at the last evaluation.
    pub fn velocities(&self) -> &[f64] {
        &self.r
    }

    /// p_ν at the last evaluation.
    pub fn pressures(&self) -> &[f64] {
        &self.p
    }

    /// Number of active points (p_ν′ > 0) at the last evaluation.
    pub fn active_count(&self) -> usize {
        self.dp.iter().filter(|&&d| d > 0.0).count()
    }
}
