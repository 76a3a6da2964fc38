//! A second implementation of the rod's fully discrete schemes (Fernández & Sofonea 2004, (3.3),
//! and the implicit and midpoint variants; docs/quasistatic.md), written from the equations with
//! dense matrices, to check the solver's implementation at round-off.
//!
//! P1 elements on the uniform mesh x_i = i h (h = L/M), unknowns at x_1..x_M (u(0) = 0). With the
//! stiffness K_ij = ∫ φ_i' φ_j' dx (K_ii = 2/h, K_MM = 1/h, K_{i,i±1} = −1/h), the load vector
//! F_i(t) = ∫ f0(x, t) φ_i dx, e_M the unit vector of x_M = L, and
//!
//!   θ = 0 (explicit), 1 (implicit), 1/2 (midpoint);   τ_n = t_n, t_n, t_{n−1/2},
//!
//! step n finds w_n with
//!
//!   (a K + θ k b K) w_n + p_ν(w_n · e_M, τ_n) e_M = F(τ_n) − b K u_{n−1},    u_n = u_{n−1} + k w_n,
//!
//! for the lubricated law (2.8) p_ν(r, t) = β r_+ + p0(t). The scalar nonlinearity is solved in
//! closed form: with S = a K + θ k b K, S z = F − b K u_{n−1} and S y = e_M, w = z − p y and
//! w_M = z_M − p y_M; y_M > 0, so w_M > 0 requires w_M = (z_M − p0 y_M)/(1 + β y_M) > 0, and
//! otherwise w_M = z_M − p0 y_M ≤ 0 (the monotone law has exactly one solution).
//!
//! Nothing here uses the solver's code: the matrices are dense (nalgebra, LU), the load vector
//! is integrated exactly for loads affine in x (h(2 f_i + f_{i+1})/6 and h(f_i + 2 f_{i+1})/6 per
//! element; the data sets below are affine in x and [`RodData::check_affine`] verifies it), u_0
//! is the nodal interpolant of u0.

use std::sync::Arc;

use nalgebra::{DMatrix, DVector};

use contactlab::model::quasistatic::scheme::TimeScheme;

/// A function of (x, t).
pub type SpaceTimeFn = Arc<dyn Fn(f64, f64) -> f64 + Send + Sync>;
/// A function of one variable.
pub type ScalarFn = Arc<dyn Fn(f64) -> f64 + Send + Sync>;

/// The data of a rod run, as plain functions (the solver gets the same functions as fields).
#[derive(Clone)]
pub struct RodData {
    pub name: String,
    pub length: f64,
    pub final_time: f64,
    /// a, b, β.
    pub viscosity: f64,
    pub elasticity: f64,
    pub beta: f64,
    /// f0(x, t), affine in x.
    pub load: SpaceTimeFn,
    /// p0(t).
    pub oil_pressure: ScalarFn,
    /// u0(x), u0(0) = 0.
    pub initial: ScalarFn,
}

impl std::fmt::Debug for RodData {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "RodData({})", self.name)
    }
}

impl RodData {
    /// L = 1, T = 1, a = 1, b = 2, β = 3, f0 = 10 + 4 x sin 3t, p0 = 5 + 3 sin 4t,
    /// u0 = x(2 − x)/10: time-dependent data in every term, and an oil pressure that crosses the
    /// constant-data threshold (p0 = 5) so that the end alternately presses into the foundation
    /// (the damper acts) and recedes.
    pub fn switching_oil_pressure() -> Self {
        Self {
            name: "switching_oil_pressure".into(),
            length: 1.0,
            final_time: 1.0,
            viscosity: 1.0,
            elasticity: 2.0,
            beta: 3.0,
            load: Arc::new(|x, t| 10.0 + 4.0 * x * (3.0 * t).sin()),
            oil_pressure: Arc::new(|t| 5.0 + 3.0 * (4.0 * t).sin()),
            initial: Arc::new(|x| 0.1 * x * (2.0 - x)),
        }
    }

    /// Constant data, u0 = 0: the paper's rod (§4.1) with (L, T, a, b, β, f0, p0).
    #[allow(clippy::too_many_arguments)]
    pub fn constant(
        name: &str,
        (length, final_time): (f64, f64),
        (viscosity, elasticity, beta): (f64, f64, f64),
        load: f64,
        p0: f64,
    ) -> Self {
        Self {
            name: name.into(),
            length,
            final_time,
            viscosity,
            elasticity,
            beta,
            load: Arc::new(move |_, _| load),
            oil_pressure: Arc::new(move |_| p0),
            initial: Arc::new(|_| 0.0),
        }
    }

    /// The paper's data (L = 1, T = 0.5, a = b = β = 1, f0 = 10) with oil pressure p0.
    pub fn paper(p0: f64) -> Self {
        Self::constant(
            &format!("paper_p0_{p0}"),
            (1.0, 0.5),
            (1.0, 1.0, 1.0),
            10.0,
            p0,
        )
    }

    /// The data set of a name.
    pub fn named(name: &str) -> Option<Self> {
        [
            Self::switching_oil_pressure(),
            Self::paper(6.0),
            Self::paper(2.0),
        ]
        .into_iter()
        .find(|d| d.name == name)
    }

    /// Every data set's name.
    pub fn names() -> Vec<String> {
        [
            Self::switching_oil_pressure(),
            Self::paper(6.0),
            Self::paper(2.0),
        ]
        .into_iter()
        .map(|d| d.name)
        .collect()
    }

    /// Whether f0 is affine in x (the load vector is then integrated exactly): f0 at the
    /// midpoint of (0, L) equals the mean of its end values to round-off, at several times.
    pub fn check_affine(&self) -> bool {
        (0..=8).all(|i| {
            let t = self.final_time * i as f64 / 8.0;
            let (f0, f1) = ((self.load)(0.0, t), (self.load)(self.length, t));
            let fm = (self.load)(0.5 * self.length, t);
            (fm - 0.5 * (f0 + f1)).abs() <= 1e-13 * (1.0 + f0.abs() + f1.abs())
        })
    }
}

/// u_n at the nodes x_0..x_M for n = 0..N, and the end velocity w_n(L) for n = 1..N.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceRun {
    pub u: Vec<Vec<f64>>,
    pub end_velocity: Vec<f64>,
}

/// θ and τ_n of a scheme, written out here (not taken from the solver).
fn theta_and_data_time(scheme: TimeScheme, t_prev: f64, t: f64) -> (f64, f64) {
    match scheme {
        TimeScheme::Explicit => (0.0, t),
        TimeScheme::Implicit => (1.0, t),
        TimeScheme::Midpoint => (0.5, 0.5 * (t_prev + t)),
    }
}

/// Runs the scheme on M elements and N uniform steps.
pub fn reference_run(data: &RodData, m: usize, n: usize, scheme: TimeScheme) -> ReferenceRun {
    let h = data.length / m as f64;
    let k = data.final_time / n as f64;
    let (a, b, beta) = (data.viscosity, data.elasticity, data.beta);
    // K on the unknowns x_1..x_M (index i − 1)
    let mut stiffness = DMatrix::<f64>::zeros(m, m);
    for i in 0..m {
        stiffness[(i, i)] = if i + 1 == m { 1.0 / h } else { 2.0 / h };
        if i + 1 < m {
            stiffness[(i, i + 1)] = -1.0 / h;
            stiffness[(i + 1, i)] = -1.0 / h;
        }
    }
    let load_vector = |t: f64| -> DVector<f64> {
        let mut f = DVector::<f64>::zeros(m);
        for e in 0..m {
            let (x0, x1) = (e as f64 * h, (e + 1) as f64 * h);
            let (f0, f1) = ((data.load)(x0, t), (data.load)(x1, t));
            // left node e (unknown e − 1 unless e = 0), right node e + 1 (unknown e)
            if e > 0 {
                f[e - 1] += h * (2.0 * f0 + f1) / 6.0;
            }
            f[e] += h * (f0 + 2.0 * f1) / 6.0;
        }
        f
    };
    let mut u = DVector::<f64>::from_fn(m, |i, _| (data.initial)((i + 1) as f64 * h));
    let nodal =
        |u: &DVector<f64>| -> Vec<f64> { std::iter::once(0.0).chain(u.iter().copied()).collect() };
    let mut out = ReferenceRun {
        u: vec![nodal(&u)],
        end_velocity: Vec::new(),
    };
    let mut e_m = DVector::<f64>::zeros(m);
    e_m[m - 1] = 1.0;
    for step in 1..=n {
        let (t_prev, t) = ((step - 1) as f64 * k, step as f64 * k);
        let (theta, tau) = theta_and_data_time(scheme, t_prev, t);
        let s = &stiffness * (a + theta * k * b);
        let lu = s.lu();
        let rhs = load_vector(tau) - &stiffness * &u * b;
        let z = lu
            .solve(&rhs)
            .unwrap_or_else(|| DVector::from_element(m, f64::NAN));
        let y = lu
            .solve(&e_m)
            .unwrap_or_else(|| DVector::from_element(m, f64::NAN));
        let p0 = (data.oil_pressure)(tau);
        let (zm, ym) = (z[m - 1], y[m - 1]);
        let pressing = (zm - p0 * ym) / (1.0 + beta * ym);
        let w_end = if pressing > 0.0 {
            pressing
        } else {
            zm - p0 * ym
        };
        let p = beta * w_end.max(0.0) + p0;
        let w = z - y * p;
        u += &w * k;
        out.u.push(nodal(&u));
        out.end_velocity.push(w[m - 1]);
    }
    out
}

/// The round-off bound of two implementations of N steps on M elements:
/// C ε κ(K) N scale with κ(K) ≈ 4M²/π² + 1 (each step solves a system of condition at most
/// κ(K); the errors of N steps add at most linearly) and C = 16 (a few operations per entry of a
/// tridiagonal solve).
pub fn round_off_bound(m: usize, n: usize, scale: f64) -> f64 {
    let kappa = 4.0 * (m * m) as f64 / std::f64::consts::PI.powi(2) + 1.0;
    16.0 * f64::EPSILON * kappa * n as f64 * scale
}

/// max_n ‖a_n − b_n‖_∞ and max_n ‖b_n‖_∞ over two runs' nodal states (`None` when their
/// shapes differ).
pub fn max_difference(a: &[Vec<f64>], b: &[Vec<f64>]) -> Option<(f64, f64)> {
    if a.len() != b.len() || a.iter().zip(b).any(|(x, y)| x.len() != y.len()) {
        return None;
    }
    let mut diff = 0.0_f64;
    let mut scale = 0.0_f64;
    for (x, y) in a.iter().zip(b) {
        for (p, q) in x.iter().zip(y) {
            diff = diff.max((p - q).abs());
            scale = scale.max(q.abs());
        }
    }
    Some((diff, scale))
}

#[cfg(test)]
mod tests {
    //! The reference against what it must satisfy independently of the solver: constant data
    //! reach the static state of the BVP −b u'' = f0, b u'(L) = −p0 (P1 is nodally exact for it)
    //! with the damper inactive; a single implicit step with u0 = 0 solves (a + kb) K w = F − p e_M
    //! in closed form; the end velocity changes sign for the switching data.
    use super::*;

    fn constant() -> RodData {
        RodData::constant("constant", (1.0, 40.0), (1.0, 1.0, 1.0), 10.0, 6.0)
    }

    #[test]
    fn constant_data_reach_the_static_state() {
        // −u'' = 10, u(0) = 0, u'(1) = −6: u = 4x − 5x²; the end recedes (p0 = 6 > 5)
        let r = reference_run(&constant(), 10, 400, TimeScheme::Implicit);
        let last = r.u.last().unwrap();
        for (i, u) in last.iter().enumerate() {
            let x = i as f64 / 10.0;
            assert!((u - (4.0 * x - 5.0 * x * x)).abs() < 1e-12, "{i}: {u}");
        }
        assert!(r.end_velocity.iter().all(|w| *w <= 0.0));
    }

    #[test]
    fn one_implicit_step_solves_its_linear_system() {
        // u0 = 0, p0 = 6 > threshold: the end recedes, so (a + kb) K w = F − p0 e_M
        let d = RodData::constant("one step", (1.0, 0.1), (1.0, 1.0, 1.0), 10.0, 6.0);
        let r = reference_run(&d, 4, 1, TimeScheme::Implicit);
        // exact P1 solution of −(1.1) w'' = 10, w(0) = 0, 1.1 w'(1) = −6
        for (i, u) in r.u[1].iter().enumerate() {
            let x = i as f64 / 4.0;
            let w = (10.0 * x - 5.0 * x * x - 6.0 * x) / 1.1;
            assert!((u - 0.1 * w).abs() < 1e-14, "{i}: {u} vs {}", 0.1 * w);
        }
    }

    #[test]
    fn switching_data_are_affine_in_x_and_switch_the_damper() {
        let d = RodData::switching_oil_pressure();
        assert!(d.check_affine());
        let r = reference_run(&d, 20, 100, TimeScheme::Midpoint);
        assert!(r.end_velocity.iter().any(|w| *w > 0.0));
        assert!(r.end_velocity.iter().any(|w| *w < 0.0));
    }
}
