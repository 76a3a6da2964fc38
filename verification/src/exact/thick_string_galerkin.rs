//! An independent sine-Galerkin model of the thick string with friction and an oscillator in the
//! bushing (Hetzler 2009, §4.2.1–4.2.2, weak form (100); docs/moving_continua.md), written here
//! from the weak form and nothing else: the flutter reference of the moving cases at equal
//! discretization.
//!
//! The weak form (100) in dimensionless variables, ideal contact, p = μ c̄ h̄:
//!
//! ```text
//!   ∫₀¹ [δw (ẅ + 2v̄ ẇ' + v̄² w'' + ᾱ ẇ) + δw' w'] dξ − δw(ā) c̄ (u − w(ā))
//!     + δu [m̄ ü + c̄ (u − w(ā))] = (p/2) (w(ā) − u) δw'(ā).
//! ```
//!
//! With w = Σ_k Φ_k q_k, Φ_k = √2 sin(kπξ), and δw = Φ_j the integrals are written out from the
//! products of sines and cosines (product-to-sum, then ∫₀¹ sin(mπξ) dξ = (1 − (−1)^m)/(mπ) and
//! ∫₀¹ cos(mπξ) dξ = δ_{m0} for integers m):
//!
//! ```text
//!   ∫ sin(jπξ) sin(kπξ) = ½ [C(j − k) − C(j + k)],   ∫ cos(jπξ) cos(kπξ) = ½ [C(j − k) + C(j + k)],
//!   ∫ sin(jπξ) cos(kπξ) = ½ [S(j + k) + S(j − k)],   S(m) = (1 − (−1)^m)/(mπ), S(0) = 0, C(m) = δ_{m0},
//! ```
//!
//! so that, on the coordinates (q, u),
//!
//! ```text
//!   M = diag(2 I_ss, m̄),   C = [ ᾱ 2 I_ss + 2v̄ · 2kπ I_sc(j, k)   0 ; 0   0 ],
//!   K = [ 2jkπ² I_cc − v̄² 2(kπ)² I_ss + c̄ φφᵀ − (p/2) φ'φᵀ    −c̄ φ + (p/2) φ' ;  −c̄ φᵀ   c̄ ],
//! ```
//!
//! with φ_j = Φ_j(ā), φ'_j = Φ_j'(ā): the friction's virtual work moved to the left-hand side
//! (row j of the string, columns q and u). The eigenvalues of λ² M + λ C + K are those of the
//! first-order matrix A = [[0, I], [−M⁻¹K, −M⁻¹C]], computed by nalgebra's real Schur
//! decomposition — a different eigensolver from the program's (faer, and its own Francis QR).

use nalgebra::{Complex, DMatrix};

/// The thick string with the oscillator in ideal contact (dimensionless data (79)–(82), (103)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThickString {
    /// v̄.
    pub speed: f64,
    /// ᾱ.
    pub damping: f64,
    /// c̄.
    pub stiffness: f64,
    /// m̄.
    pub mass: f64,
    /// ā.
    pub position: f64,
    /// p = μ c̄ h̄.
    pub control: f64,
    /// ε: the contact patch's width (0: point contact; `thick_string_patch`).
    pub patch: f64,
}

/// The matrices of λ² M + λ C + K on (q_1 … q_N, u).
#[derive(Debug, Clone, PartialEq)]
pub struct GalerkinMatrices {
    pub mass: DMatrix<f64>,
    pub velocity: DMatrix<f64>,
    pub stiffness: DMatrix<f64>,
}

/// ∫₀¹ cos(mπξ) dξ for an integer m.
fn int_cos(m: i64) -> f64 {
    if m == 0 {
        1.0
    } else {
        0.0
    }
}

/// ∫₀¹ sin(mπξ) dξ for an integer m.
fn int_sin(m: i64) -> f64 {
    if m == 0 {
        0.0
    } else {
        let parity = if m.rem_euclid(2) == 0 { 1.0 } else { -1.0 };
        (1.0 - parity) / (m as f64 * std::f64::consts::PI)
    }
}

/// ∫₀¹ sin(jπξ) sin(kπξ) dξ.
fn i_ss(j: i64, k: i64) -> f64 {
    0.5 * (int_cos(j - k) - int_cos(j + k))
}

/// ∫₀¹ cos(jπξ) cos(kπξ) dξ.
fn i_cc(j: i64, k: i64) -> f64 {
    0.5 * (int_cos(j - k) + int_cos(j + k))
}

/// ∫₀¹ sin(jπξ) cos(kπξ) dξ.
fn i_sc(j: i64, k: i64) -> f64 {
    0.5 * (int_sin(j + k) + int_sin(j - k))
}

impl ThickString {
    /// The sine-Galerkin matrices with N = `modes` functions (see the module docs).
    pub fn galerkin(&self, modes: usize) -> GalerkinMatrices {
        let n = modes;
        let pi = std::f64::consts::PI;
        let s2 = std::f64::consts::SQRT_2;
        let (v, a) = (self.speed, self.position);
        let (c, p) = (self.stiffness, self.control);
        // what the bushing reads: point values, or patch means (1/ε)∫ Φ_j over [a − ε/2, a + ε/2]
        // = √2 (cos(jπa₋) − cos(jπa₊))/(jπε) and mean slopes √2 (sin(jπa₊) − sin(jπa₋))/ε
        let eps = self.patch;
        let (am, ap) = (a - 0.5 * eps, a + 0.5 * eps);
        let phi: Vec<f64> = (1..=n)
            .map(|j| {
                let jp = j as f64 * pi;
                if eps > 0.0 {
                    s2 * ((jp * am).cos() - (jp * ap).cos()) / (jp * eps)
                } else {
                    s2 * (jp * a).sin()
                }
            })
            .collect();
        let dphi: Vec<f64> = (1..=n)
            .map(|j| {
                let jp = j as f64 * pi;
                if eps > 0.0 {
                    s2 * ((jp * ap).sin() - (jp * am).sin()) / eps
                } else {
                    s2 * jp * (jp * a).cos()
                }
            })
            .collect();
        let mut m = DMatrix::zeros(n + 1, n + 1);
        let mut cm = DMatrix::zeros(n + 1, n + 1);
        let mut k = DMatrix::zeros(n + 1, n + 1);
        for row in 0..n {
            let j = row as i64 + 1;
            for col in 0..n {
                let kk = col as i64 + 1;
                let (jf, kf) = (j as f64, kk as f64);
                // ⟨Φ_j, Φ_k⟩, ⟨Φ_j, Φ_k'⟩, ⟨Φ_j', Φ_k'⟩, ⟨Φ_j, Φ_k''⟩
                let mass = 2.0 * i_ss(j, kk);
                let transport = 2.0 * kf * pi * i_sc(j, kk);
                let prestress = 2.0 * jf * kf * pi * pi * i_cc(j, kk);
                let curvature = -2.0 * (kf * pi).powi(2) * i_ss(j, kk);
                m[(row, col)] = mass;
                cm[(row, col)] = self.damping * mass + 2.0 * v * transport;
                k[(row, col)] = prestress + v * v * curvature + c * phi[row] * phi[col]
                    - 0.5 * p * dphi[row] * phi[col];
            }
            k[(row, n)] = -c * phi[row] + 0.5 * p * dphi[row];
            k[(n, row)] = -c * phi[row];
        }
        m[(n, n)] = self.mass;
        k[(n, n)] = c;
        GalerkinMatrices {
            mass: m,
            velocity: cm,
            stiffness: k,
        }
    }

    /// The eigenvalues of the sine-Galerkin model with N = `modes` functions.
    pub fn galerkin_eigenvalues(&self, modes: usize) -> Result<Vec<Complex<f64>>, String> {
        self.galerkin(modes).eigenvalues()
    }
}

impl GalerkinMatrices {
    /// The first-order matrix A = [[0, I], [−M⁻¹K, −M⁻¹C]] (M diagonal and positive).
    pub fn first_order(&self) -> Result<DMatrix<f64>, String> {
        let n = self.mass.nrows();
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        for i in 0..n {
            let mi = self.mass[(i, i)];
            if mi.is_nan() || mi <= 0.0 {
                return Err(format!("mass[{i}, {i}] = {mi}: not positive"));
            }
            for j in 0..n {
                if i != j && self.mass[(i, j)] != 0.0 {
                    return Err(format!(
                        "mass[{i}, {j}] = {}: not diagonal",
                        self.mass[(i, j)]
                    ));
                }
                a[(n + i, j)] = -self.stiffness[(i, j)] / mi;
                a[(n + i, n + j)] = -self.velocity[(i, j)] / mi;
            }
            a[(i, n + i)] = 1.0;
        }
        Ok(a)
    }

    /// The eigenvalues of λ² M + λ C + K, by the real Schur form of the first-order matrix.
    pub fn eigenvalues(&self) -> Result<Vec<Complex<f64>>, String> {
        let a = self.first_order()?;
        let schur = nalgebra::linalg::Schur::try_new(a, f64::EPSILON, 100_000)
            .ok_or("the Schur iteration did not converge")?;
        Ok(schur.complex_eigenvalues().iter().copied().collect())
    }
}

#[cfg(test)]
mod tests {
    //! Setting: the reference's closed-form integrals and the string alone. Goal: the integrals
    //! equal their quadrature; at v̄ = 0 without oscillator coupling the frequencies are kπ.
    use super::*;

    #[test]
    fn written_out_integrals_equal_their_quadrature() {
        let pi = std::f64::consts::PI;
        let quad = |f: &dyn Fn(f64) -> f64| {
            // composite midpoint rule with 20000 panels: error ~ 1e-9 for these integrands
            let m = 20000;
            (0..m).map(|i| f((i as f64 + 0.5) / m as f64)).sum::<f64>() / m as f64
        };
        for j in 1..6i64 {
            for k in 1..6i64 {
                let (jf, kf) = (j as f64 * pi, k as f64 * pi);
                let ss = quad(&|x| (jf * x).sin() * (kf * x).sin());
                let cc = quad(&|x| (jf * x).cos() * (kf * x).cos());
                let sc = quad(&|x| (jf * x).sin() * (kf * x).cos());
                assert!((ss - i_ss(j, k)).abs() < 1e-8, "ss {j} {k}");
                assert!((cc - i_cc(j, k)).abs() < 1e-8, "cc {j} {k}");
                assert!((sc - i_sc(j, k)).abs() < 1e-8, "sc {j} {k}: {sc}");
            }
        }
    }

    #[test]
    fn string_at_rest_with_a_tiny_oscillator_has_frequencies_k_pi() {
        let d = ThickString {
            speed: 0.0,
            damping: 0.0,
            stiffness: 1e-12,
            mass: 1.0,
            position: 0.3,
            control: 0.0,
            patch: 0.0,
        };
        let mut f: Vec<f64> = d
            .galerkin_eigenvalues(6)
            .unwrap()
            .iter()
            .filter(|l| l.im > 1e-3)
            .map(|l| l.im)
            .collect();
        f.sort_by(f64::total_cmp);
        for (k, w) in f.iter().enumerate() {
            let e = (k + 1) as f64 * std::f64::consts::PI;
            assert!((w - e).abs() < 1e-9 * e, "{k}: {w}");
        }
    }
}
