//! The linearized equations of a moving continuum,
//!
//! ```text
//!   M q̈ + (α D + v G) q̇ + (K(v) + K_c + p K_f + p N) q = 0      (Hetzler 2009, (33), (86), (103), (108)),
//! ```
//!
//! stored by physical part, so that the structure the paper proves can be checked on the
//! discrete matrices: M, D, K symmetric, G skew (gyroscopic, when R_P = 0), N skew (circulatory).

use faer::{Mat, MatRef};

use crate::error::InputError;
use crate::solve::quadratic_eigen::{
    solve_quadratic_eigen, QuadraticEigen, QuadraticEigenError, QuadraticEigenParams,
};

/// M q̈ + (damping + gyroscopic) q̇ + (stiffness + circulatory) q = 0, every part already
/// multiplied by its parameter (ᾱ D, v̄ G, p N).
#[derive(Debug, Clone, PartialEq)]
pub struct MovingSystem {
    /// M (symmetric).
    pub mass: Mat<f64>,
    /// ᾱ D (symmetric).
    pub damping: Mat<f64>,
    /// v̄ G (skew when the boundary term R_P vanishes).
    pub gyroscopic: Mat<f64>,
    /// The symmetric part of the stiffness: K(v̄) + K_c + p K_f.
    pub stiffness: Mat<f64>,
    /// The skew (circulatory) part of the stiffness: p N.
    pub circulatory: Mat<f64>,
    /// The name of each coordinate (`q1`, …, `u`, `y_c`).
    pub coordinates: Vec<String>,
}

impl MovingSystem {
    /// All parts zero, n = `coordinates.len()`.
    pub fn zeros(coordinates: Vec<String>) -> Self {
        let n = coordinates.len();
        Self {
            mass: Mat::zeros(n, n),
            damping: Mat::zeros(n, n),
            gyroscopic: Mat::zeros(n, n),
            stiffness: Mat::zeros(n, n),
            circulatory: Mat::zeros(n, n),
            coordinates,
        }
    }

    /// The number of coordinates n.
    pub fn dimension(&self) -> usize {
        self.coordinates.len()
    }

    /// C = ᾱ D + v̄ G into `out` (n × n).
    pub fn velocity_matrix_into(&self, out: &mut Mat<f64>) {
        let n = self.dimension();
        for j in 0..n {
            for i in 0..n {
                out[(i, j)] = self.damping[(i, j)] + self.gyroscopic[(i, j)];
            }
        }
    }

    /// K_total = stiffness + circulatory into `out` (n × n).
    pub fn stiffness_matrix_into(&self, out: &mut Mat<f64>) {
        let n = self.dimension();
        for j in 0..n {
            for i in 0..n {
                out[(i, j)] = self.stiffness[(i, j)] + self.circulatory[(i, j)];
            }
        }
    }

    /// C = ᾱ D + v̄ G.
    pub fn velocity_matrix(&self) -> Mat<f64> {
        let n = self.dimension();
        let mut c = Mat::zeros(n, n);
        self.velocity_matrix_into(&mut c);
        c
    }

    /// K_total = stiffness + circulatory.
    pub fn stiffness_matrix(&self) -> Mat<f64> {
        let n = self.dimension();
        let mut k = Mat::zeros(n, n);
        self.stiffness_matrix_into(&mut k);
        k
    }

    /// The eigenvalues (and, if asked, eigenvectors) of (λ² M + λ C + K_total) x = 0.
    pub fn eigen(
        &self,
        params: QuadraticEigenParams,
    ) -> Result<QuadraticEigen, QuadraticEigenError> {
        solve_quadratic_eigen(
            self.mass.as_ref(),
            self.velocity_matrix().as_ref(),
            self.stiffness_matrix().as_ref(),
            params,
        )
    }

    /// Eliminates a massless coordinate y (zero row and column in M, D and G) exactly by static
    /// condensation: its equation k_yy y + Σ k_yj q_j = 0 gives y = −Σ k_yj q_j / k_yy, so
    ///
    ///   K_cond = K_rr − K_ry K_yr / k_yy   (the Schur complement of the total stiffness),
    ///
    /// then split again into symmetric and skew parts. The finite eigenvalues of the singular-mass
    /// problem are exactly those of the condensed one. For a stiff penalty (k_yy ≫ the rest) the
    /// subtraction cancels digits (relative error ~ ε k_yy / k_rest); models that know their
    /// structure condense without cancellation (see `penalty.rs`).
    pub fn condense_massless(&self, index: usize) -> Result<MovingSystem, InputError> {
        let n = self.dimension();
        if index >= n {
            return Err(InputError::new(
                "condensation.coordinate",
                index,
                format!("a coordinate index < {n}"),
            ));
        }
        for (name, m) in [
            ("mass", &self.mass),
            ("damping", &self.damping),
            ("gyroscopic", &self.gyroscopic),
        ] {
            for j in 0..n {
                if m[(index, j)] != 0.0 || m[(j, index)] != 0.0 {
                    return Err(InputError::new(
                        format!("condensation.{}", self.coordinates[index]),
                        format!(
                            "{name}[{index}, {j}] = {}",
                            m[(index, j)].max(m[(j, index)])
                        ),
                        "a massless coordinate (zero row and column in M, D and G)",
                    ));
                }
            }
        }
        let k = self.stiffness_matrix();
        let kyy = k[(index, index)];
        if !(kyy.is_finite() && kyy != 0.0) {
            return Err(InputError::new(
                format!("condensation.{}", self.coordinates[index]),
                kyy,
                "a non-zero stiffness on the massless coordinate",
            ));
        }
        let keep: Vec<usize> = (0..n).filter(|&i| i != index).collect();
        let coords = keep.iter().map(|&i| self.coordinates[i].clone()).collect();
        let mut out = MovingSystem::zeros(coords);
        let m = keep.len();
        let pick = |a: &Mat<f64>| Mat::from_fn(m, m, |i, j| a[(keep[i], keep[j])]);
        out.mass = pick(&self.mass);
        out.damping = pick(&self.damping);
        out.gyroscopic = pick(&self.gyroscopic);
        let kc = Mat::from_fn(m, m, |i, j| {
            k[(keep[i], keep[j])] - k[(keep[i], index)] * k[(index, keep[j])] / kyy
        });
        split_symmetric_skew(kc.as_ref(), &mut out.stiffness, &mut out.circulatory);
        Ok(out)
    }
}

/// sym = (A + Aᵀ)/2, skew = (A − Aᵀ)/2.
pub fn split_symmetric_skew(a: MatRef<'_, f64>, sym: &mut Mat<f64>, skew: &mut Mat<f64>) {
    let n = a.nrows();
    for j in 0..n {
        for i in 0..n {
            sym[(i, j)] = 0.5 * (a[(i, j)] + a[(j, i)]);
            skew[(i, j)] = 0.5 * (a[(i, j)] - a[(j, i)]);
        }
    }
}

#[cfg(test)]
mod tests {
    //! Setting: a 2-dof system with a massless second coordinate. Goal: condensation gives the
    //! series spring and rejects coordinates that carry mass.
    use super::*;

    #[test]
    fn condensing_a_massless_coordinate_gives_springs_in_series() {
        let mut s = MovingSystem::zeros(vec!["u".into(), "y".into()]);
        s.mass[(0, 0)] = 1.0;
        // springs c = 2 (u–y) and k = 6 (y–ground): series stiffness 2·6/8 = 1.5.
        s.stiffness = Mat::from_fn(2, 2, |i, j| [[2.0, -2.0], [-2.0, 8.0]][i][j]);
        let c = s.condense_massless(1).unwrap();
        assert_eq!(c.coordinates, vec!["u".to_string()]);
        assert!((c.stiffness[(0, 0)] - 1.5).abs() < 1e-15);
        let e = s.condense_massless(0).unwrap_err();
        assert_eq!(e.field, "condensation.u");
        assert!(s.condense_massless(2).is_err());
    }
}
