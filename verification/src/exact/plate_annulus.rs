//! The exact natural frequencies of an annular Kirchhoff plate clamped at its inner edge (or at its
//! centre), derived here: the independent reference for the rotating plate of Hetzler 2009, §4.1
//! (docs/moving_continua.md), whose body-frame spectrum this is. Plate theory and the tables
//! compared with: A.W. Leissa, *Vibration of Plates*, NASA SP-160 (1969), ch. 2.
//!
//! **Equation.** D ∇⁴w + ρh ẅ = 0 on a ≤ r ≤ b. With w = W(r) cos(nφ) e^{iωt} and
//! β⁴ = ρh ω²/D, (∇²_n ∇²_n − β⁴) W = 0, ∇²_n W = W'' + W'/r − n²W/r², which factors into
//! (∇²_n + β²)(∇²_n − β²) W = 0:
//!
//! ```text
//!   W = A J_n(βr) + B Y_n(βr) + C I_n(βr) + E K_n(βr),
//!   ∇²_n Z = σ β² Z,   σ = −1 for J_n, Y_n (Bessel's equation),   σ = +1 for I_n, K_n.
//! ```
//!
//! The frequency parameter is λ = βb, so ω = (λ/b)² sqrt(D/ρh).
//!
//! **Edge operators.** With M_r = −D (w_rr + ν(w_r/r + w_φφ/r²)), the twisting moment
//! M_rφ = −(1−ν) D ∂_r(w_φ/r), the shear Q_r = −D ∂_r ∇²w and Kirchhoff's effective shear
//! V_r = Q_r + (1/r) ∂_φ M_rφ (the twisting moment along the edge is statically a shear), the
//! factor cos nφ (∂_φφ → −n²) leaves
//!
//! ```text
//!   M_r = −D [W'' + ν (W'/r − n² W/r²)]                             (× cos nφ)
//!   V_r = −D [(∇²_n W)' − (1−ν) n² (W'/r − W/r²) / r]               (× cos nφ)
//! ```
//!
//! (from (1/r)∂_φ ∂_r(w_φ/r) = (1/r) ∂_r(w_φφ/r) → −n² (W'/r − W/r²)/r). These are the natural
//! boundary terms of the energy (D/2)∫[(∇²w)² − 2(1−ν)(w_rr (w_r/r + w_φφ/r²) − (∂_r(w_φ/r))²)] dA,
//! which the tests check independently: the Rayleigh quotient of a computed mode equals β⁴
//! only if the free-edge conditions are the energy's. Conditions: clamped W = W' = 0, simply
//! supported W = M_r = 0, free M_r = V_r = 0.
//!
//! **Rows.** In x = βr with z = Z(x) and x-derivatives, W' = β z', and Bessel's equation gives
//! z'' = σz − z'/x + n²z/x², (∇²_n Z)' = σβ³ z'. Dividing M_r by −Dβ² and V_r by −Dβ³ (positive
//! row factors, which do not move roots):
//!
//! ```text
//!   deflection  z                         moment  z'' + ν (z'/x − n² z/x²)
//!   slope       z'                        shear   σ z' − (1−ν) n² (z'/x − z/x²) / x
//! ```
//!
//! with z' from J_n' = (J_{n−1} − J_{n+1})/2 (same for Y; J_{−1} = −J_1), I_n' = I_{n+1} + (n/x) I_n
//! and K_n' = −K_{n−1} − (n/x) K_n (K_{−1} = K_1): sums of like-signed terms for I and K.
//!
//! **Cases** ([`InnerSupport`]).
//! 1. *Clamped inner edge* r = a > 0: rows W(a), W'(a) and the two outer conditions at r = b, four
//!    columns: a 4 × 4 determinant.
//! 2. *Solid disc* (a = 0, nothing at the centre): only the regular J_n, I_n, the two outer rows: a
//!    2 × 2 determinant (Leissa's Table 2.1 for the clamped edge, Leissa & Narita, J. Sound Vib.
//!    70 (1980) 221 for simple support, Blevins 1979, Table 11-1 for the free edge).
//! 3. *Point-clamped centre* (a = 0, W(0) = 0 and W'(0) = 0: Hetzler's conditions for the full
//!    disc). An admissible W has finite energy; near r = 0 the biharmonic part of W behaves like
//!    r^n, r^{n+2}, r^{−n}, r^{2−n} (n ≥ 2), r, r³, r^{−1}, r ln r (n = 1), 1, r², ln r, r² ln r
//!    (n = 0), and the energy ∫ (W'')² r dr is finite for r^n, r^{n+2} and, at n = 0, for r² ln r.
//!    - n ≥ 2: J_n, I_n ~ r^n satisfy both conditions: the solid disc's 2 × 2 determinant.
//!    - n = 0: besides J_0, I_0, the point-force solution G = Y_0 + (2/π) K_0 is admissible. From
//!      Y_0 = (2/π)(ln(x/2) + γ) J_0 + (2/π)(x²/4 − …) and K_0 = −(ln(x/2) + γ) I_0 + (x²/4 + …)
//!      (A&S 9.1.13, 9.6.13): G = (2/π)(ln(x/2) + γ)(J_0 − I_0) + (2/π)(x²/2 + O(x⁶)), and
//!      J_0 − I_0 = −x²/2 + O(x⁶), so G = −(x²/π) ln x + O(x²) is finite with G(0) = 0 and
//!      G'(0) = 0. W = A J_0 + C I_0 + E G, the slope condition holds for every such W, and
//!      W(0) = A + C = 0 with the two outer rows gives a 3 × 3 determinant.
//!    - n = 1: the only solutions with a slope at r = 0 that differs from that of a regular one,
//!      r ln r cos φ and r^{−1} cos φ, have infinite energy (W'' ~ 1/r, ∫ r^{−2} r dr = ∞): a
//!      point value of the gradient is not a bounded functional on H² in 2D, so the slope
//!      constraint carries no energy-bounded reaction and is lost in the limit. The exact spectrum
//!      is that of the disc with W(0) = 0 only, which W = A J_1 + C I_1 satisfies automatically:
//!      the solid disc's n = 1 spectrum (for a free edge including the rigid tilt W = r, λ = 0).
//!      Likewise a clamped hole of radius a → 0 tends to it only like 1/ln(1/a) (measured: the
//!      n = 1 roots of a/b = 10⁻³ are still 1.28 and 4.67 against 0 and 4.52), and a
//!      discretization that clamps the slope at a centre node converges to it only as slowly
//!      (logarithmically in h). For n = 0 the hole's roots approach the point-clamped disc's like
//!      a² ln²a, for n ≥ 2 the solid disc's like a^{2(n−1)}.
//!
//! **Scaling.** The I column is multiplied by e^{−βb} and the K column by e^{βa} (I_n(βr) e^{−βb},
//! K_n(βr) e^{βa}, evaluated as the scaled functions of `bessel` times e^{β(r−b)}, e^{β(a−r)}), then
//! every column is divided by its Euclidean norm. Positive column factors do not move roots; the
//! normalized determinant is continuous in λ, bounded by 1 (Hadamard) and has no poles, so every
//! sign change is a root (checked anyway: |F| at the refined root must be ≪ |F| at the bracket,
//! which also refuses roots that round-off has blurred).
//!
//! **Roots.** F(λ) is scanned from [`LAMBDA_MIN`] in steps of [`SCAN_STEP`]; sign changes are
//! refined by bisection to a bracket ≤ 4ελ. A double root, or two roots closer than the step,
//! does not change sign and is missed. None is expected (two modes of one n at one λ need the
//! whole 2 × 2 block of outer conditions, on the solutions that satisfy the inner ones, to
//! vanish), and a test checks that a five times finer scan finds the same roots.

use super::bessel::{bessel_i_scaled, bessel_j, bessel_k_scaled, bessel_y};

/// The largest number of nodal diameters accepted.
pub const MAX_ORDER: usize = 20;
/// The scan gives up beyond this frequency parameter.
pub const LAMBDA_MAX: f64 = 200.0;
/// The scan starts here (every root of the supported cases with a/b ≥ [`MIN_HOLE_RATIO`] is larger;
/// zero roots, the rigid modes of free plates, are counted by `zero_frequency_modes`).
pub const LAMBDA_MIN: f64 = 0.05;
/// The default scan step in λ.
pub const SCAN_STEP: f64 = 0.01;
/// The smallest hole accepted, a/b. Below it the Y_n and K_n columns (both ~ x^{−n} at x = βa)
/// are parallel to within x², and for n = 1 the roots lose digits (1e−12 relative at a/b = 1e−3,
/// 4e−10 at 1e−4, against a 40-digit evaluation); smaller holes: the point-clamped centre.
pub const MIN_HOLE_RATIO: f64 = 1e-3;

/// A refined root is accepted only if |F| there is below this fraction of |F| at its bracket:
/// for F near-linear on the bracket this bounds the root's error from round-off in F by about
/// RESOLVED_RATIO × step (1e−10 at the default step), and it refuses a pole.
const RESOLVED_RATIO: f64 = 1e-8;

/// The condition at the outer edge r = b.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OuterEdge {
    /// M_r = V_r = 0.
    Free,
    /// W = W' = 0.
    Clamped,
    /// W = M_r = 0.
    SimplySupported,
}

/// What holds the plate inside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum InnerSupport {
    /// An annulus a ≤ r ≤ b clamped at r = a > 0: W(a) = W'(a) = 0.
    ClampedEdge { radius: f64 },
    /// The full disc with W(0) = 0 and W'(0) = 0 (Hetzler 2009, §4.1; see the module docs for
    /// n = 0 and n = 1).
    PointClampedCentre,
    /// The full disc with nothing at the centre (Leissa's tables).
    SolidDisc,
}

/// A Kirchhoff plate: annulus or disc of outer radius b.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnnularPlate {
    pub inner: InnerSupport,
    pub outer_radius: f64,
    pub poisson: f64,
    pub outer: OuterEdge,
}

/// Invalid input, or a root search that failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlateExactError {
    #[error("{field} = {value}: expected {expected}")]
    InvalidInput {
        field: &'static str,
        value: f64,
        expected: &'static str,
    },
    #[error("only {found} of {wanted} frequency parameters for n = {n} below λ = {limit}")]
    TooFewRoots {
        n: usize,
        found: usize,
        wanted: usize,
        limit: f64,
    },
    #[error(
        "the sign change of F in [{lo}, {hi}] (n = {n}) is not resolved as a root: |F| = {value:e} \
         at the refined point (a pole, or F lost to round-off)"
    )]
    Unresolved {
        n: usize,
        lo: f64,
        hi: f64,
        value: f64,
    },
    #[error("the characteristic matrix is not finite at λ = {lambda} (n = {n})")]
    NonFinite { n: usize, lambda: f64 },
}

/// One solution family: a column of the determinant.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Part {
    J,
    Y,
    I,
    K,
    /// G = Y_0 + (2/π) K_0 (n = 0 only).
    PointForce,
}

/// A row of the determinant: a condition at the radius ratio r/b, or W(0) = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Row {
    Deflection(f64),
    Slope(f64),
    Moment(f64),
    Shear(f64),
    CentreDeflection,
}

/// z, z', z'' and (∇²_n z)' = σ z' in x = βr, with the column's scaling.
#[derive(Debug, Clone, Copy, Default)]
struct Jet {
    z: f64,
    dz: f64,
    d2z: f64,
    dlap: f64,
}

impl Jet {
    /// The jet of σ-type solution with value z, slope dz, times the factor c.
    fn from_slope(n: usize, x: f64, sigma: f64, z: f64, dz: f64, c: f64) -> Jet {
        let nn = (n * n) as f64;
        let (z, dz) = (c * z, c * dz);
        Jet {
            z,
            dz,
            d2z: sigma * z - dz / x + nn * z / (x * x),
            dlap: sigma * dz,
        }
    }
}

/// The scaled characteristic matrix (k × k, k ≤ 4) and the column norms divided out.
struct System {
    parts: Vec<Part>,
    matrix: [[f64; 4]; 4],
    norms: [f64; 4],
}

impl AnnularPlate {
    /// An annulus clamped at r = a.
    pub fn annulus(inner_radius: f64, outer_radius: f64, poisson: f64, outer: OuterEdge) -> Self {
        AnnularPlate {
            inner: InnerSupport::ClampedEdge {
                radius: inner_radius,
            },
            outer_radius,
            poisson,
            outer,
        }
    }

    /// The full disc with W(0) = W'(0) = 0.
    pub fn point_clamped_disc(outer_radius: f64, poisson: f64, outer: OuterEdge) -> Self {
        AnnularPlate {
            inner: InnerSupport::PointClampedCentre,
            outer_radius,
            poisson,
            outer,
        }
    }

    /// The full disc, nothing at the centre.
    pub fn solid_disc(outer_radius: f64, poisson: f64, outer: OuterEdge) -> Self {
        AnnularPlate {
            inner: InnerSupport::SolidDisc,
            outer_radius,
            poisson,
            outer,
        }
    }

    /// Checks the data (b > 0, −1 < ν ≤ 1/2, 10⁻³ ≤ a/b < 1) and n ≤ [`MAX_ORDER`].
    pub fn validate(&self, n: usize) -> Result<(), PlateExactError> {
        let invalid = |field, value, expected| PlateExactError::InvalidInput {
            field,
            value,
            expected,
        };
        let b = self.outer_radius;
        if !(b.is_finite() && b > 0.0) {
            return Err(invalid("outer_radius", b, "a finite positive radius"));
        }
        let nu = self.poisson;
        if !(nu > -1.0 && nu <= 0.5) {
            return Err(invalid("poisson", nu, "−1 < ν ≤ 1/2"));
        }
        if let InnerSupport::ClampedEdge { radius } = self.inner {
            let ratio = radius / b;
            if !(MIN_HOLE_RATIO..1.0).contains(&ratio) {
                return Err(invalid(
                    "inner_radius",
                    radius,
                    "10⁻³ b ≤ a < b (for a = 0 use the point-clamped centre)",
                ));
            }
        }
        if n > MAX_ORDER {
            return Err(invalid("n", n as f64, "at most 20 nodal diameters"));
        }
        Ok(())
    }

    /// a/b (0 for the discs).
    fn hole_ratio(&self) -> f64 {
        match self.inner {
            InnerSupport::ClampedEdge { radius } => radius / self.outer_radius,
            _ => 0.0,
        }
    }

    /// The columns and rows of the case (module docs, "Cases").
    fn layout(&self, n: usize) -> (Vec<Part>, Vec<Row>) {
        let outer = match self.outer {
            OuterEdge::Free => [Row::Moment(1.0), Row::Shear(1.0)],
            OuterEdge::Clamped => [Row::Deflection(1.0), Row::Slope(1.0)],
            OuterEdge::SimplySupported => [Row::Deflection(1.0), Row::Moment(1.0)],
        };
        match self.inner {
            InnerSupport::ClampedEdge { .. } => {
                let alpha = self.hole_ratio();
                let mut rows = vec![Row::Deflection(alpha), Row::Slope(alpha)];
                rows.extend(outer);
                (vec![Part::J, Part::Y, Part::I, Part::K], rows)
            }
            InnerSupport::PointClampedCentre if n == 0 => {
                let mut rows = vec![Row::CentreDeflection];
                rows.extend(outer);
                (vec![Part::J, Part::I, Part::PointForce], rows)
            }
            _ => (vec![Part::J, Part::I], outer.to_vec()),
        }
    }

    /// The jet of one column at x = λρ (ρ = r/b), scaled as in the module docs.
    fn jet(&self, part: Part, n: usize, lambda: f64, x: f64) -> Jet {
        let nf = n as f64;
        let m = n as u32;
        match part {
            Part::J | Part::Y => {
                let f = |k: u32| match part {
                    Part::J => bessel_j(k, x),
                    _ => bessel_y(k, x),
                };
                // Z_{−1} = −Z_1 for J and Y.
                let below = if n == 0 { -f(1) } else { f(m - 1) };
                Jet::from_slope(n, x, -1.0, f(m), 0.5 * (below - f(m + 1)), 1.0)
            }
            Part::I => {
                let (i0, i1) = (bessel_i_scaled(m, x), bessel_i_scaled(m + 1, x));
                Jet::from_slope(n, x, 1.0, i0, i1 + nf / x * i0, (x - lambda).exp())
            }
            Part::K => {
                let k0 = bessel_k_scaled(m, x);
                let below = bessel_k_scaled(if n == 0 { 1 } else { m - 1 }, x);
                let c = (lambda * self.hole_ratio() - x).exp();
                Jet::from_slope(n, x, 1.0, k0, -below - nf / x * k0, c)
            }
            Part::PointForce => {
                let y = self.jet(Part::Y, 0, lambda, x);
                let (k0, k1) = (bessel_k_scaled(0, x), bessel_k_scaled(1, x));
                let k =
                    Jet::from_slope(0, x, 1.0, k0, -k1, std::f64::consts::FRAC_2_PI * (-x).exp());
                Jet {
                    z: y.z + k.z,
                    dz: y.dz + k.dz,
                    d2z: y.d2z + k.d2z,
                    dlap: y.dlap + k.dlap,
                }
            }
        }
    }

    /// One matrix entry.
    fn entry(&self, row: Row, part: Part, n: usize, lambda: f64) -> f64 {
        let nu = self.poisson;
        let nn = (n * n) as f64;
        let at = |rho: f64| {
            let x = lambda * rho;
            (x, self.jet(part, n, lambda, x))
        };
        match row {
            Row::CentreDeflection => match part {
                Part::J => 1.0,
                Part::I => (-lambda).exp(),
                _ => 0.0,
            },
            Row::Deflection(rho) => at(rho).1.z,
            Row::Slope(rho) => at(rho).1.dz,
            Row::Moment(rho) => {
                let (x, j) = at(rho);
                j.d2z + nu * (j.dz / x - nn * j.z / (x * x))
            }
            Row::Shear(rho) => {
                let (x, j) = at(rho);
                j.dlap - (1.0 - nu) * nn * (j.dz / x - j.z / (x * x)) / x
            }
        }
    }

    /// The normalized characteristic matrix at λ.
    fn system(&self, n: usize, lambda: f64) -> Result<System, PlateExactError> {
        let (parts, rows) = self.layout(n);
        let k = parts.len();
        let mut matrix = [[0.0; 4]; 4];
        let mut norms = [1.0; 4];
        for (j, &part) in parts.iter().enumerate() {
            for (i, &row) in rows.iter().enumerate() {
                matrix[i][j] = self.entry(row, part, n, lambda);
            }
            let big = (0..k).fold(0.0f64, |m, i| m.max(matrix[i][j].abs()));
            if !(big.is_finite() && big > 0.0) {
                return Err(PlateExactError::NonFinite { n, lambda });
            }
            let norm = big
                * (0..k)
                    .map(|i| (matrix[i][j] / big).powi(2))
                    .sum::<f64>()
                    .sqrt();
            for row in matrix.iter_mut().take(k) {
                row[j] /= norm;
            }
            norms[j] = norm;
        }
        Ok(System {
            parts,
            matrix,
            norms,
        })
    }

    fn check_lambda(lambda: f64) -> Result<(), PlateExactError> {
        if lambda.is_finite() && lambda > 0.0 && lambda <= LAMBDA_MAX {
            Ok(())
        } else {
            Err(PlateExactError::InvalidInput {
                field: "lambda",
                value: lambda,
                expected: "0 < λ ≤ 200",
            })
        }
    }

    /// The characteristic function F(λ) (λ = βb): the determinant of the column-normalized matrix,
    /// |F| ≤ 1; its zeros are the frequency parameters.
    pub fn characteristic(&self, n: usize, lambda: f64) -> Result<f64, PlateExactError> {
        self.validate(n)?;
        Self::check_lambda(lambda)?;
        let s = self.system(n, lambda)?;
        Ok(determinant(s.matrix, s.parts.len()))
    }

    /// The number of zero-frequency (rigid) modes with n nodal diameters: the free solid disc's
    /// translation (n = 0) and tilt (n = 1), the tilt of the free point-clamped disc (n = 1).
    /// They are not in [`frequency_parameters`](Self::frequency_parameters).
    pub fn zero_frequency_modes(&self, n: usize) -> usize {
        match (self.inner, self.outer) {
            (InnerSupport::SolidDisc, OuterEdge::Free) if n <= 1 => 1,
            (InnerSupport::PointClampedCentre, OuterEdge::Free) if n == 1 => 1,
            _ => 0,
        }
    }

    /// The `count` smallest positive frequency parameters λ = βb with n nodal diameters, ascending.
    /// Entry m has m nodal circles inside the plate (not counting a clamped edge) for the annulus
    /// and for the clamped and simply supported discs; for free discs Leissa counts the rigid modes'
    /// index too ([`zero_frequency_modes`](Self::zero_frequency_modes) of them precede entry 0).
    pub fn frequency_parameters(
        &self,
        n: usize,
        count: usize,
    ) -> Result<Vec<f64>, PlateExactError> {
        self.frequency_parameters_with_step(n, count, SCAN_STEP)
    }

    /// As [`frequency_parameters`](Self::frequency_parameters) with the scan step given
    /// (0 < step ≤ 0.1).
    pub fn frequency_parameters_with_step(
        &self,
        n: usize,
        count: usize,
        step: f64,
    ) -> Result<Vec<f64>, PlateExactError> {
        self.validate(n)?;
        if !(step > 0.0 && step <= 0.1) {
            return Err(PlateExactError::InvalidInput {
                field: "step",
                value: step,
                expected: "0 < step ≤ 0.1",
            });
        }
        let f = |lambda: f64| -> Result<f64, PlateExactError> {
            let s = self.system(n, lambda)?;
            Ok(determinant(s.matrix, s.parts.len()))
        };
        let mut roots = Vec::new();
        let (mut lo, mut f_lo) = (LAMBDA_MIN, f(LAMBDA_MIN)?);
        let mut k = 0usize;
        while roots.len() < count {
            k += 1;
            let hi = LAMBDA_MIN + k as f64 * step;
            if hi > LAMBDA_MAX {
                return Err(PlateExactError::TooFewRoots {
                    n,
                    found: roots.len(),
                    wanted: count,
                    limit: LAMBDA_MAX,
                });
            }
            let f_hi = f(hi)?;
            if f_hi == 0.0 {
                roots.push(hi);
            } else if f_lo != 0.0 && (f_lo < 0.0) != (f_hi < 0.0) {
                roots.push(bisect(&f, n, (lo, f_lo), (hi, f_hi))?);
            }
            (lo, f_lo) = (hi, f_hi);
        }
        Ok(roots)
    }

    /// ω = (λ/b)² sqrt(D/ρh) for the `count` smallest positive λ (rad/s in consistent units).
    pub fn natural_frequencies(
        &self,
        n: usize,
        count: usize,
        bending_stiffness: f64,
        mass_per_area: f64,
    ) -> Result<Vec<f64>, PlateExactError> {
        for (field, value) in [
            ("bending_stiffness", bending_stiffness),
            ("mass_per_area", mass_per_area),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(PlateExactError::InvalidInput {
                    field,
                    value,
                    expected: "a finite positive number",
                });
            }
        }
        let b = self.outer_radius;
        let c = (bending_stiffness / mass_per_area).sqrt();
        Ok(self
            .frequency_parameters(n, count)?
            .into_iter()
            .map(|l| (l / b).powi(2) * c)
            .collect())
    }

    /// The mode shape W(r) at a root λ (arbitrary normalization: the null vector of the
    /// normalized matrix has unit length), from the cofactors of the row that gives the largest.
    pub fn mode_shape(&self, n: usize, lambda: f64) -> Result<ModeShape, PlateExactError> {
        self.validate(n)?;
        Self::check_lambda(lambda)?;
        let s = self.system(n, lambda)?;
        let k = s.parts.len();
        let mut best = (0.0, [0.0; 4]);
        for drop in 0..k {
            let mut c = [0.0; 4];
            for (j, cj) in c.iter_mut().enumerate().take(k) {
                let mut minor = [[0.0; 4]; 4];
                let rows = (0..k).filter(|&i| i != drop);
                for (mi, i) in rows.enumerate() {
                    let cols = (0..k).filter(|&l| l != j);
                    for (mj, l) in cols.enumerate() {
                        minor[mi][mj] = s.matrix[i][l];
                    }
                }
                let sign = if (drop + j) % 2 == 0 { 1.0 } else { -1.0 };
                *cj = sign * determinant(minor, k - 1);
            }
            let size = c.iter().map(|v| v * v).sum::<f64>().sqrt();
            if size > best.0 {
                best = (size, c);
            }
        }
        let (size, c) = best;
        let coefficients = (0..k)
            .map(|j| (s.parts[j], c[j] / size / s.norms[j]))
            .collect();
        Ok(ModeShape {
            plate: *self,
            n,
            lambda,
            coefficients,
        })
    }
}

/// A mode W(r) = Σ c_j Z_j(βr) (scaled columns): see [`AnnularPlate::mode_shape`].
#[derive(Debug, Clone, PartialEq)]
pub struct ModeShape {
    plate: AnnularPlate,
    n: usize,
    lambda: f64,
    coefficients: Vec<(Part, f64)>,
}

impl ModeShape {
    /// (W, W', W'') at r (a ≤ r ≤ b; r > 0 for the discs).
    pub fn eval(&self, r: f64) -> Result<[f64; 3], PlateExactError> {
        let p = &self.plate;
        let b = p.outer_radius;
        let a = p.hole_ratio() * b;
        if !(r >= a && r > 0.0 && r <= b) {
            return Err(PlateExactError::InvalidInput {
                field: "r",
                value: r,
                expected: "a ≤ r ≤ b, r > 0",
            });
        }
        let beta = self.lambda / b;
        let x = beta * r;
        let mut w = [0.0; 3];
        for &(part, c) in &self.coefficients {
            let j = p.jet(part, self.n, self.lambda, x);
            w[0] += c * j.z;
            w[1] += c * beta * j.dz;
            w[2] += c * beta * beta * j.d2z;
        }
        Ok(w)
    }
}

/// Refines a sign change by bisection to a bracket ≤ 4ελ; errors if |F| at the result is not
/// small against |F| at the bracket (a pole, or a root lost to round-off).
fn bisect<F>(f: &F, n: usize, lo: (f64, f64), hi: (f64, f64)) -> Result<f64, PlateExactError>
where
    F: Fn(f64) -> Result<f64, PlateExactError>,
{
    let scale = lo.1.abs().max(hi.1.abs());
    let (lo0, hi0) = (lo.0, hi.0);
    let ((mut a, mut fa), mut b) = (lo, hi.0);
    for _ in 0..200 {
        let mid = 0.5 * (a + b);
        if b - a <= 4.0 * f64::EPSILON * b || mid <= a || mid >= b {
            break;
        }
        let fm = f(mid)?;
        if fm == 0.0 {
            return Ok(mid);
        }
        if (fm < 0.0) == (fa < 0.0) {
            (a, fa) = (mid, fm);
        } else {
            b = mid;
        }
    }
    let root = 0.5 * (a + b);
    let value = f(root)?.abs();
    if value > RESOLVED_RATIO * scale {
        return Err(PlateExactError::Unresolved {
            n,
            lo: lo0,
            hi: hi0,
            value,
        });
    }
    Ok(root)
}

/// The determinant of the leading k × k block by Gaussian elimination with partial pivoting.
fn determinant(mut m: [[f64; 4]; 4], k: usize) -> f64 {
    let mut det = 1.0;
    for c in 0..k {
        let p = (c..k)
            .max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))
            .unwrap_or(c);
        if m[p][c] == 0.0 {
            return 0.0;
        }
        if p != c {
            m.swap(p, c);
            det = -det;
        }
        det *= m[c][c];
        for i in c + 1..k {
            let factor = m[i][c] / m[c][c];
            for j in c..k {
                m[i][j] -= factor * m[c][j];
            }
        }
    }
    det
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    /// Composite 3-point Gauss–Legendre on [lo, hi] (order 6).
    fn gauss<F: Fn(f64) -> f64>(f: F, lo: f64, hi: f64, panels: usize) -> f64 {
        let nodes = [-(0.6f64.sqrt()), 0.0, 0.6f64.sqrt()];
        let weights = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
        let h = (hi - lo) / panels as f64;
        let mut sum = 0.0;
        for p in 0..panels {
            let mid = lo + (p as f64 + 0.5) * h;
            for (x, w) in nodes.iter().zip(weights) {
                sum += w * f(mid + 0.5 * h * x);
            }
        }
        0.5 * h * sum
    }

    /// The Rayleigh quotient U/T of the computed mode at λ in the energy with Poisson ratio `nu`,
    /// ∫[(W'' + P)² − 2(1−ν)(W'' P − n² Q²)] r dr / ∫ W² r dr, P = W'/r − n²W/r²,
    /// Q = W'/r − W/r² (the φ-integrals cancel); discs are integrated in t with r = b t², which
    /// smooths the r² ln r of the point force at r = 0.
    fn rayleigh_quotient(plate: &AnnularPlate, n: usize, lambda: f64, nu: f64) -> f64 {
        let panels = 400;
        let mode = plate.mode_shape(n, lambda).unwrap();
        let nn = (n * n) as f64;
        let b = plate.outer_radius;
        let density = |r: f64| {
            let [w, dw, d2w] = mode.eval(r).unwrap();
            let p = dw / r - nn * w / (r * r);
            let q = dw / r - w / (r * r);
            let strain = (d2w + p).powi(2) - 2.0 * (1.0 - nu) * (d2w * p - nn * q * q);
            (strain * r, w * w * r)
        };
        let (u, t) = match plate.inner {
            InnerSupport::ClampedEdge { radius } => (
                gauss(|r| density(r).0, radius, b, panels),
                gauss(|r| density(r).1, radius, b, panels),
            ),
            _ => {
                let jac = |t: f64| 2.0 * b * t;
                (
                    gauss(|t| density(b * t * t).0 * jac(t), 0.0, 1.0, panels),
                    gauss(|t| density(b * t * t).1 * jac(t), 0.0, 1.0, panels),
                )
            }
        };
        u / t
    }

    /// The outer-edge determinant (the rows of `plate.outer`) of the two solutions of
    /// (∇²_n∇²_n − β⁴)W = 0 started at the clamped edge r = a with W = W' = 0 and
    /// (∇²_n W, (∇²_n W)') = (1, 0), (0, 1), by RK4. The state is y = (W, W', U, U'),
    /// U = ∇²_n W, y' = A(r) y with W'' = U − W'/r + n²W/r², U'' = β⁴W − U'/r + n²U/r². The two
    /// solutions u, v are carried as the compound P = u vᵀ − v uᵀ (P' = AP + PAᵀ), whose growth is
    /// e^{βr} and not e^{2βr} with a cancelling difference: at λ = 60 the two solutions themselves
    /// are parallel to round-off. The determinant of the edge rows c₁, c₂ is c₁ᵀ P c₂.
    fn shooting_determinant(plate: &AnnularPlate, n: usize, lambda: f64, steps: usize) -> f64 {
        let InnerSupport::ClampedEdge { radius: a } = plate.inner else {
            panic!("shooting needs an inner edge");
        };
        let (b, nu, nn) = (plate.outer_radius, plate.poisson, (n * n) as f64);
        let beta4 = (lambda / b).powi(4);
        type M4 = [[f64; 4]; 4];
        let system = |r: f64| -> M4 {
            let (ir, ir2) = (1.0 / r, 1.0 / (r * r));
            [
                [0.0, 1.0, 0.0, 0.0],
                [nn * ir2, -ir, 1.0, 0.0],
                [0.0, 0.0, 0.0, 1.0],
                [beta4, 0.0, nn * ir2, -ir],
            ]
        };
        let rhs = |r: f64, p: &M4| -> M4 {
            let m = system(r);
            std::array::from_fn(|i| {
                std::array::from_fn(|j| (0..4).map(|k| m[i][k] * p[k][j] + p[i][k] * m[j][k]).sum())
            })
        };
        let add = |p: &M4, k: &M4, c: f64| -> M4 {
            std::array::from_fn(|i| std::array::from_fn(|j| p[i][j] + c * k[i][j]))
        };
        let mut p = [[0.0; 4]; 4];
        p[2][3] = 1.0;
        p[3][2] = -1.0;
        let h = (b - a) / steps as f64;
        for s in 0..steps {
            let r = a + s as f64 * h;
            let k1 = rhs(r, &p);
            let k2 = rhs(r + 0.5 * h, &add(&p, &k1, 0.5 * h));
            let k3 = rhs(r + 0.5 * h, &add(&p, &k2, 0.5 * h));
            let k4 = rhs(r + h, &add(&p, &k3, h));
            p = std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    p[i][j] + h / 6.0 * (k1[i][j] + 2.0 * k2[i][j] + 2.0 * k3[i][j] + k4[i][j])
                })
            });
        }
        // The edge rows as functionals of (W, W', U, U') at r = b: W'' = U − W'/b + n²W/b².
        let c = 1.0 - nu;
        let deflection = [1.0, 0.0, 0.0, 0.0];
        let slope = [0.0, 1.0, 0.0, 0.0];
        let moment = [c * nn / (b * b), -c / b, 1.0, 0.0];
        let shear = [c * nn / (b * b * b), -c * nn / (b * b), 0.0, 1.0];
        let (c1, c2) = match plate.outer {
            OuterEdge::Free => (moment, shear),
            OuterEdge::Clamped => (deflection, slope),
            OuterEdge::SimplySupported => (deflection, moment),
        };
        (0..4)
            .map(|i| (0..4).map(|j| c1[i] * p[i][j] * c2[j]).sum::<f64>())
            .sum()
    }

    /// The root of the shooting determinant in [guess − 1e−3, guess + 1e−3], by bisection.
    fn shooting_root(plate: &AnnularPlate, n: usize, guess: f64, steps: usize) -> f64 {
        let f = |l: f64| shooting_determinant(plate, n, l, steps);
        let (mut lo, mut hi) = (guess - 1e-3, guess + 1e-3);
        let f_lo = f(lo);
        assert!(
            f_lo * f(hi) < 0.0,
            "no sign change of the shooting determinant near {guess}"
        );
        while hi - lo > 1e-15 * guess {
            let mid = 0.5 * (lo + hi);
            if (f(mid) < 0.0) == (f_lo < 0.0) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// The number of sign changes of W on a fine grid of (a, b) (the nodal circles).
    fn nodal_circles(plate: &AnnularPlate, n: usize, lambda: f64) -> usize {
        let mode = plate.mode_shape(n, lambda).unwrap();
        let b = plate.outer_radius;
        let a = plate.hole_ratio() * b;
        let samples = 1500;
        let values: Vec<f64> = (1..samples)
            .map(|k| mode.eval(a + (b - a) * k as f64 / samples as f64).unwrap()[0])
            .collect();
        let scale = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let signs: Vec<bool> = values
            .iter()
            .filter(|v| v.abs() > 1e-9 * scale)
            .map(|v| *v > 0.0)
            .collect();
        signs.windows(2).filter(|w| w[0] != w[1]).count()
    }

    #[test]
    fn clamped_solid_disc_matches_leissa_table_2_1() {
        // Setting: the solid disc clamped at r = b (no centre condition), the roots of
        // J_n(λ) I_n'(λ) − J_n'(λ) I_n(λ) = 0. Goal: Leissa (1969), Table 2.1, λ² = 10.2158,
        // 39.771 (n = 0), 21.26 (n = 1), 34.88 (n = 2), to half a unit of the last digit given,
        // and the roots λ = 3.19622, 6.30644, 4.61090, 5.90568 to half a unit of the sixth digit.
        // (4.61089, often quoted, is 4.6108999 truncated.)
        let plate = AnnularPlate::solid_disc(1.0, 0.3, OuterEdge::Clamped);
        let table: [(usize, usize, f64, f64, f64); 4] = [
            // (n, entry, λ² and half its last unit, λ to six digits)
            (0, 0, 10.2158, 5e-5, 3.19622),
            (0, 1, 39.771, 5e-4, 6.30644),
            (1, 0, 21.26, 5e-3, 4.61090),
            (2, 0, 34.88, 5e-3, 5.90568),
        ];
        for (n, entry, l2, tol, l_ref) in table {
            let l = plate.frequency_parameters(n, entry + 1).unwrap()[entry];
            assert!(
                (l * l - l2).abs() <= tol,
                "n = {n}, entry {entry}: λ² = {}, table {l2}",
                l * l
            );
            assert!(
                (l - l_ref).abs() <= 5e-6,
                "n = {n}, entry {entry}: λ = {l}, {l_ref}"
            );
        }
    }

    #[test]
    fn free_solid_disc_matches_the_tables_for_poisson_0_3() {
        // Setting: the completely free solid disc, ν = 0.3; λ² = ωb² sqrt(ρh/D) as tabulated by
        // Blevins (Formulas for Natural Frequency and Mode Shape, 1979, Table 11-1), labelled
        // (n, s) with s nodal circles; the rigid modes (0, 0) and (1, 0) are not listed by
        // `frequency_parameters`, so (0, 1) and (1, 1) are its first entries. Goal: the moment and
        // effective-shear rows (with the twist term) reproduce every tabulated digit.
        //
        // Leissa's Table 2.5 (ν = 0.33; from older sources) lists 5.253 (2,0), 9.084 (0,1),
        // 12.23 (3,0), 20.52 (1,1); this function gives 5.2620, 9.0689, 12.2439, 20.5131 at
        // ν = 0.33, 0.03–0.17 % off — not gated: the same code reproduces the ν = 0.3 table to all
        // digits below, the Rayleigh-quotient test confirms the roots as eigenvalues of the plate
        // energy, and a 30-digit mpmath evaluation agrees to 1e−15.
        let plate = AnnularPlate::solid_disc(1.0, 0.3, OuterEdge::Free);
        let table: [(usize, usize, f64, f64); 7] = [
            // (n, entry, λ², half a unit of the last digit)
            (2, 0, 5.358, 5e-4),
            (0, 0, 9.003, 5e-4),
            (3, 0, 12.439, 5e-4),
            (1, 0, 20.475, 5e-4),
            (4, 0, 21.835, 5e-4),
            (2, 1, 35.260, 5e-4),
            (0, 1, 38.443, 5e-4),
        ];
        for (n, entry, l2, tol) in table {
            let roots = plate.frequency_parameters(n, entry + 1).unwrap();
            let got = roots[entry].powi(2);
            assert!(
                (got - l2).abs() <= tol,
                "n = {n}, entry {entry}: λ² = {got}, table {l2}"
            );
        }
    }

    #[test]
    fn simply_supported_solid_disc_matches_leissa_and_narita_1980() {
        // Setting: the solid disc simply supported at r = b, ν = 0.3. Goal: the six-figure λ² of
        // Leissa & Narita, J. Sound Vib. 70 (1980) 221, for (n, s) = (0,0), (1,0), (2,0), (0,1),
        // (3,0), (1,1): pins the moment row M_r with ν and n².
        let plate = AnnularPlate::solid_disc(1.0, 0.3, OuterEdge::SimplySupported);
        let table: [(usize, usize, f64, f64); 6] = [
            (0, 0, 4.93515, 5e-6),
            (1, 0, 13.8982, 5e-5),
            (2, 0, 25.6133, 5e-5),
            (0, 1, 29.7200, 5e-5),
            (3, 0, 39.9573, 5e-5),
            (1, 1, 48.4789, 5e-5),
        ];
        for (n, entry, l2, tol) in table {
            let got = plate.frequency_parameters(n, entry + 1).unwrap()[entry].powi(2);
            assert!(
                (got - l2).abs() <= tol,
                "n = {n}, entry {entry}: λ² = {got}, table {l2}"
            );
        }
    }

    #[test]
    fn roots_agree_with_a_30_digit_mpmath_evaluation_to_1e_14() {
        // Setting: the annulus a/b = 0.2 clamped inside, free outside, ν = 0.3, n = 0..4, and the
        // free point-clamped disc, n = 0 (the 3 × 3 determinant with G = Y_0 + (2/π)K_0). The
        // references are the roots of the same determinants written with mpmath 1.3's Bessel
        // functions at 30 digits (K_n' = −(K_{n−1} + K_{n+1})/2; mpmath's besselk silently ignores
        // a derivative argument), rounded to f64. Goal: the f64 Bessel functions, scaling and
        // bisection lose nothing: ≤ 1e−14 relative (4ελ bracket plus the determinant's round-off).
        let annulus = AnnularPlate::annulus(0.2, 1.0, 0.3, OuterEdge::Free);
        let table: [(usize, [f64; 2]); 5] = [
            (0, [2.276200520104217, 5.6825389322938005]),
            (1, [2.1938612635149775, 5.875856128800248]),
            (2, [2.5391144107264663, 6.477596518391302]),
            (3, [3.551714673030378, 7.443795079787965]),
            (4, [4.675365210525682, 8.61347179855577]),
        ];
        let mut worst: f64 = 0.0;
        for (n, expected) in table {
            let roots = annulus.frequency_parameters(n, 2).unwrap();
            for (l, e) in roots.iter().zip(expected) {
                worst = worst.max(rel(*l, e));
            }
        }
        let disc = AnnularPlate::point_clamped_disc(1.0, 0.3, OuterEdge::Free);
        let roots = disc.frequency_parameters(0, 2).unwrap();
        for (l, e) in roots.iter().zip([1.9369997472327252, 4.572537662226385]) {
            worst = worst.max(rel(*l, e));
        }
        eprintln!("worst relative deviation from mpmath: {worst:e}");
        assert!(worst <= 1e-14, "worst relative deviation {worst:e}");
    }

    #[test]
    fn annulus_roots_are_roots_of_an_rk4_shooting_determinant() {
        // Setting: the clamped–free annulus a/b = 0.2 (ν = 0.3, n = 0..4, two roots each) and the
        // clamped–clamped and clamped–simply-supported annulus a/b = 0.5 (n = 0, 3), solved
        // again without Bessel functions: RK4 from the clamped edge (compound-matrix form), the
        // root of the outer 2 × 2 determinant found by bisection, with N = 200 and 400 steps. Goal: the Bessel roots
        // agree with the shooting roots within the RK4 error model: |λ_2N − λ| ≤ 3 × the
        // Richardson estimate |λ_N − λ_2N|/15 of the error of λ_2N (O(h⁴)), plus 1e−12 λ for
        // the bisection floors.
        let cases: [(AnnularPlate, &[usize]); 3] = [
            (
                AnnularPlate::annulus(0.2, 1.0, 0.3, OuterEdge::Free),
                &[0, 1, 2, 3, 4],
            ),
            (
                AnnularPlate::annulus(0.5, 1.0, 0.3, OuterEdge::Clamped),
                &[0, 3],
            ),
            (
                AnnularPlate::annulus(0.5, 1.0, 0.3, OuterEdge::SimplySupported),
                &[0, 3],
            ),
        ];
        let mut worst_ratio: f64 = 0.0;
        for (plate, orders) in cases {
            for &n in orders {
                for l in plate.frequency_parameters(n, 2).unwrap() {
                    let coarse = shooting_root(&plate, n, l, 200);
                    let fine = shooting_root(&plate, n, l, 400);
                    let predicted = (coarse - fine).abs() / 15.0;
                    let err = (fine - l).abs();
                    assert!(
                        err <= 3.0 * predicted + 1e-12 * l,
                        "{:?} n = {n}: λ = {l}, shooting {fine} (coarse {coarse})",
                        plate.outer
                    );
                    worst_ratio = worst_ratio.max(err / predicted);
                }
            }
        }
        eprintln!("worst |λ_2N − λ| / Richardson estimate: {worst_ratio:.3}");
    }

    #[test]
    fn characteristic_stays_bounded_up_to_lambda_60_and_its_high_roots_are_right() {
        // Setting: the free annulus a/b = 0.2 (n = 0 and 4) up to λ = 60, where unscaled I_n(βb)
        // ~ e^{60} and K_n(βb) ~ e^{−60} would leave the determinant at the mercy of its largest
        // entries. Goal: the scaled, column-normalized F is finite with |F| ≤ 1 (Hadamard) on the
        // whole scan, and the highest root below 60 is a root of the RK4 shooting determinant
        // (N = 2000, 4000 steps; same error model as the low roots).
        let plate = AnnularPlate::annulus(0.2, 1.0, 0.3, OuterEdge::Free);
        for n in [0, 4] {
            let mut biggest: f64 = 0.0;
            for k in 0..=5990 {
                let f = plate.characteristic(n, 0.05 + 0.01 * k as f64).unwrap();
                assert!(f.is_finite());
                biggest = biggest.max(f.abs());
            }
            assert!(biggest <= 1.0 + 1e-12, "n = {n}: max |F| = {biggest}");
            let roots = plate.frequency_parameters(n, 16).unwrap();
            let l = roots.into_iter().rfind(|&l| l <= 60.0).unwrap();
            let coarse = shooting_root(&plate, n, l, 2000);
            let fine = shooting_root(&plate, n, l, 4000);
            let predicted = (coarse - fine).abs() / 15.0;
            eprintln!("n = {n}: λ = {l}, shooting {fine}, Richardson estimate {predicted:e}");
            assert!(
                (fine - l).abs() <= 3.0 * predicted + 1e-12 * l,
                "n = {n}: λ = {l}, {fine}"
            );
        }
    }

    #[test]
    fn rayleigh_quotient_of_the_modes_is_lambda_to_the_fourth() {
        // Setting: the computed modes W at the computed λ, put into the plate energy (module docs)
        // with 3-point Gauss on 400 panels: U/T = β⁴ (b = 1) holds exactly iff W satisfies the ODE, the
        // essential conditions and the *natural* conditions of that energy, so this checks the
        // moment and effective-shear rows independently of their derivation, and the point-force
        // column G (whose U/T includes the point reaction only if W(0) = 0). Cases: the free
        // annulus a/b = 0.2, n = 0..4; the free solid disc n = 2; the free point-clamped disc
        // n = 0; the simply supported solid disc n = 1. Goal: |U/T − λ⁴|/λ⁴ ≤ 1e−9 (the
        // quadrature error, measured below 1e−11), against a defect of ≥ 1e−3 for the mode of a
        // plate with the wrong Poisson ratio (ν = 0.2 put into the ν = 0.3 energy).
        let annulus = AnnularPlate::annulus(0.2, 1.0, 0.3, OuterEdge::Free);
        let mut cases: Vec<(AnnularPlate, usize)> = (0..=4).map(|n| (annulus, n)).collect();
        cases.push((AnnularPlate::solid_disc(1.0, 0.3, OuterEdge::Free), 2));
        cases.push((
            AnnularPlate::point_clamped_disc(1.0, 0.3, OuterEdge::Free),
            0,
        ));
        cases.push((
            AnnularPlate::solid_disc(1.0, 0.3, OuterEdge::SimplySupported),
            1,
        ));
        let mut worst: f64 = 0.0;
        for (plate, n) in cases {
            for l in plate.frequency_parameters(n, 2).unwrap() {
                let q = rayleigh_quotient(&plate, n, l, plate.poisson);
                worst = worst.max(rel(q, l.powi(4)));
            }
        }
        eprintln!("worst relative Rayleigh-quotient defect: {worst:e}");
        assert!(worst <= 1e-9, "worst defect {worst:e}");
        // Negative control: the mode of the ν = 0.2 annulus (n = 2) in the ν = 0.3 energy. Its
        // natural conditions are not those of the energy, so U/T ≠ λ⁴; by Rayleigh's principle
        // U/T also stays above the ν = 0.3 plate's own λ⁴.
        let other = AnnularPlate::annulus(0.2, 1.0, 0.2, OuterEdge::Free);
        let l = other.frequency_parameters(2, 1).unwrap()[0];
        let q = rayleigh_quotient(&other, 2, l, 0.3);
        let defect = rel(q, l.powi(4));
        let own = annulus.frequency_parameters(2, 1).unwrap()[0].powi(4);
        eprintln!("ν = 0.2 mode in the ν = 0.3 energy: defect {defect:e}, U/T = {q} ≥ {own}");
        assert!(
            defect >= 1e-3,
            "the energy check is blind to the edge conditions: {defect:e}"
        );
        assert!(q >= own, "Rayleigh's principle: {q} < {own}");
    }

    #[test]
    fn mode_index_counts_nodal_circles() {
        // Setting: sign changes of W on (a, b) for the first three roots. Goal: the labelling in
        // the docs of `frequency_parameters`: entry m has m + (number of rigid modes) nodal
        // circles (the free discs' rigid modes take the lowest indices, as in Leissa's (n, s)).
        let plates = [
            AnnularPlate::annulus(0.2, 1.0, 0.3, OuterEdge::Free),
            AnnularPlate::annulus(0.5, 1.0, 0.3, OuterEdge::Clamped),
            AnnularPlate::solid_disc(1.0, 0.3, OuterEdge::Clamped),
            AnnularPlate::solid_disc(1.0, 0.3, OuterEdge::Free),
            AnnularPlate::point_clamped_disc(1.0, 0.3, OuterEdge::Free),
        ];
        for plate in plates {
            for n in 0..=4 {
                let shift = plate.zero_frequency_modes(n);
                for (m, l) in plate
                    .frequency_parameters(n, 3)
                    .unwrap()
                    .into_iter()
                    .enumerate()
                {
                    let circles = nodal_circles(&plate, n, l);
                    assert_eq!(circles, m + shift, "{plate:?}, n = {n}, entry {m}, λ = {l}");
                }
            }
        }
    }

    #[test]
    fn a_shrinking_clamped_hole_raises_no_root_below_the_point_clamped_disc() {
        // Setting: the annulus clamped at r = a with the outer edge free, a/b = 0.2 … 1e−3,
        // n = 0..4. Extending W by 0 into r < a makes it the disc with W = 0 on the core, a
        // subspace of the point-clamped disc's (W(0) = 0) and shrinking with a; by the min–max
        // principle every root (rigid modes counted) is ≥ the point-clamped disc's of the same
        // index and falls as a decreases. Goal: both inequalities; the approach is reported:
        // n = 0 like a² ln²a to the point-supported disc, n = 1 like 1/ln(1/a) (the slope
        // constraint fades), n ≥ 2 like a^{2(n−1)} to the solid disc.
        let ratios = [0.2, 0.1, 0.03, 1e-2, 3e-3, 1e-3];
        let disc = AnnularPlate::point_clamped_disc(1.0, 0.3, OuterEdge::Free);
        for n in 0..=4 {
            let mut limit = vec![0.0; disc.zero_frequency_modes(n)];
            limit.extend(disc.frequency_parameters(n, 2).unwrap());
            let mut previous = [f64::INFINITY; 2];
            let mut line = format!("n = {n}: limit {:.6} {:.6};", limit[0], limit[1]);
            for ratio in ratios {
                let plate = AnnularPlate::annulus(ratio, 1.0, 0.3, OuterEdge::Free);
                let roots = plate.frequency_parameters(n, 2).unwrap();
                for m in 0..2 {
                    assert!(roots[m] >= limit[m], "n = {n}, a/b = {ratio}, m = {m}");
                    assert!(roots[m] <= previous[m], "n = {n}, a/b = {ratio}, m = {m}");
                    previous[m] = roots[m];
                }
                line += &format!(
                    " a/b={ratio:e}: {:.3e} {:.3e};",
                    roots[0] - limit[0],
                    roots[1] - limit[1]
                );
            }
            eprintln!("{line}");
        }
    }

    #[test]
    fn a_five_times_finer_scan_finds_the_same_roots() {
        // Setting: the sign scan misses roots closer than its step (module docs). Goal: for the
        // annulus a/b = 0.2 and the point-clamped disc (free edges, n = 0..4, five roots) the
        // default step 0.01 and a step of 0.002 give the same roots, to the bisection's bracket.
        let plates = [
            AnnularPlate::annulus(0.2, 1.0, 0.3, OuterEdge::Free),
            AnnularPlate::point_clamped_disc(1.0, 0.3, OuterEdge::Free),
        ];
        for plate in plates {
            for n in 0..=4 {
                let coarse = plate.frequency_parameters(n, 5).unwrap();
                let fine = plate.frequency_parameters_with_step(n, 5, 0.002).unwrap();
                for (c, f) in coarse.iter().zip(&fine) {
                    assert!(rel(*c, *f) <= 1e-14, "n = {n}: {c} vs {f}");
                }
            }
        }
    }

    #[test]
    fn frequency_parameter_does_not_depend_on_the_size_and_sets_omega() {
        // Setting: the same plate at b = 1 and b = 2.5 (a/b = 0.3 kept), D = 3, ρh = 5. Goal:
        // λ = βb is dimensionless (equal for both) and ω = (λ/b)² sqrt(D/ρh).
        let small = AnnularPlate::annulus(0.3, 1.0, 0.3, OuterEdge::Free);
        let large = AnnularPlate::annulus(0.75, 2.5, 0.3, OuterEdge::Free);
        let l_small = small.frequency_parameters(2, 2).unwrap();
        let l_large = large.frequency_parameters(2, 2).unwrap();
        let omega = large.natural_frequencies(2, 2, 3.0, 5.0).unwrap();
        for ((a, b), w) in l_small.iter().zip(&l_large).zip(&omega) {
            assert!(rel(*a, *b) <= 1e-13);
            assert!(rel(*w, (b / 2.5).powi(2) * (0.6f64).sqrt()) <= 1e-15);
        }
    }

    #[test]
    fn invalid_input_is_refused_naming_the_field() {
        // Setting: every input the functions accept from a caller. Goal: typed errors naming the
        // field, no panics, and a bounded search.
        let field = |e: PlateExactError| match e {
            PlateExactError::InvalidInput { field, .. } => field,
            other => panic!("unexpected {other}"),
        };
        let ok = AnnularPlate::annulus(0.2, 1.0, 0.3, OuterEdge::Free);
        let bad_b = AnnularPlate {
            outer_radius: -1.0,
            ..ok
        };
        assert_eq!(
            field(bad_b.frequency_parameters(0, 1).unwrap_err()),
            "outer_radius"
        );
        let bad_nu = AnnularPlate { poisson: 0.7, ..ok };
        assert_eq!(
            field(bad_nu.frequency_parameters(0, 1).unwrap_err()),
            "poisson"
        );
        let bad_a = AnnularPlate::annulus(1.0, 1.0, 0.3, OuterEdge::Free);
        assert_eq!(
            field(bad_a.frequency_parameters(0, 1).unwrap_err()),
            "inner_radius"
        );
        let tiny_a = AnnularPlate::annulus(1e-4, 1.0, 0.3, OuterEdge::Free);
        assert_eq!(
            field(tiny_a.characteristic(0, 1.0).unwrap_err()),
            "inner_radius"
        );
        assert_eq!(
            field(ok.frequency_parameters(MAX_ORDER + 1, 1).unwrap_err()),
            "n"
        );
        assert_eq!(field(ok.characteristic(0, 0.0).unwrap_err()), "lambda");
        assert_eq!(field(ok.characteristic(0, f64::NAN).unwrap_err()), "lambda");
        assert_eq!(
            field(ok.frequency_parameters_with_step(0, 1, 0.5).unwrap_err()),
            "step"
        );
        assert_eq!(
            field(ok.natural_frequencies(0, 1, 0.0, 1.0).unwrap_err()),
            "bending_stiffness"
        );
        assert_eq!(
            field(
                ok.natural_frequencies(0, 1, 1.0, f64::INFINITY)
                    .unwrap_err()
            ),
            "mass_per_area"
        );
        let mode = ok
            .mode_shape(0, ok.frequency_parameters(0, 1).unwrap()[0])
            .unwrap();
        assert_eq!(field(mode.eval(0.1).unwrap_err()), "r");
        // A ring too narrow to have 3 roots below λ = 200 (λ ≈ 4.73/0.03, 7.85/0.03, …).
        let ring = AnnularPlate::annulus(0.97, 1.0, 0.3, OuterEdge::Clamped);
        assert!(matches!(
            ring.frequency_parameters(0, 3),
            Err(PlateExactError::TooFewRoots {
                found: 1,
                wanted: 3,
                ..
            })
        ));
        assert_eq!(
            ok.characteristic(0, 1.0),
            ok.characteristic(0, 1.0),
            "deterministic"
        );
    }
}
