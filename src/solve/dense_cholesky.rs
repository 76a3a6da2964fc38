//! The Cholesky factor of a small dense symmetric positive definite matrix (faer, `Par::Seq`),
//! shared by the quadratic eigensolver and the linear ODE integrator (both factor a mass matrix).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::{Mat, MatRef, Par};

/// The Cholesky factor of `a` = L Lᵀ: L in the lower triangle (only the lower triangle of `a` is
/// read; the strictly upper triangle keeps `a`'s entries), or the index of the first pivot that
/// is not positive.
pub fn cholesky_factor(a: MatRef<'_, f64>) -> Result<Mat<f64>, usize> {
    let mut factor = a.to_owned();
    let mut buf = MemBuffer::new(llt::factor::cholesky_in_place_scratch::<f64>(
        a.nrows(),
        Par::Seq,
        Default::default(),
    ));
    llt::factor::cholesky_in_place(
        factor.as_mut(),
        Default::default(),
        Par::Seq,
        MemStack::new(&mut buf),
        Default::default(),
    )
    .map_err(|e| {
        let llt::factor::LltError::NonPositivePivot { index } = e;
        index
    })?;
    Ok(factor)
}
