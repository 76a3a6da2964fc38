//! Errors of a dynamic plane run against the manufactured solution
//! ([`crate::manufactured::dynamic_plane`]) at one time, on P1 triangles:
//!
//! - the energy norm ‖ε(u_h − u)‖_{L²(Ω)} (the P1 strain is constant per triangle, the exact one
//!   smooth: a degree-5 rule per triangle),
//! - the L² norm ‖u_h − u‖_{L²(Ω)} (degree-5 rule).
//!
//! Vectors are interleaved nodal values (u_x, u_y per node), as `PlaneBody::nodal` returns them.

use contactlab::fem::norms::{l2_errors, strain_errors};
use contactlab::fem::triangle_quadrature::TriangleRule;

use crate::manufactured::dynamic_plane::{jet_of, ManufacturedField};

/// The energy-norm and L² errors of `u` (interleaved nodal values) against u(·, t).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct FieldErrors {
    pub energy: f64,
    pub l2: f64,
}

/// ‖ε(u_h − u(t))‖ and ‖u_h − u(t)‖ on the mesh (nodes, triangles), both by the degree-5 rule,
/// u the exact displacement `field`.
pub fn field_errors(
    field: ManufacturedField,
    nodes: &[[f64; 2]],
    triangles: &[[usize; 3]],
    u: &[f64],
    t: f64,
) -> Result<FieldErrors, String> {
    let rule = TriangleRule::of_degree(5).map_err(|e| e.to_string())?;
    let [energy] = strain_errors(nodes, triangles, &rule, [u], |x| {
        [jet_of(field, x[0], x[1], t).strain()]
    });
    let [l2] = l2_errors(nodes, triangles, &rule, [u], |x| {
        [jet_of(field, x[0], x[1], t).u]
    });
    Ok(FieldErrors { energy, l2 })
}

#[cfg(test)]
mod tests {
    //! The error norms vanish on the interpolant of a field that P1 represents exactly, and they
    //! decrease at the P1 rates (1 in the energy norm, 2 in L²) for the manufactured u.
    use super::*;
    use contactlab::mesh::triangle::{Diagonal, TriangleMesh};

    use crate::manufactured::dynamic_plane::DynamicManufactured;
    use crate::manufactured::dynamic_plane::ManufacturedLaw;

    fn interpolation_errors(n: usize) -> FieldErrors {
        let mesh = TriangleMesh::rectangle([0.0, 0.0], [1.0, 1.0], [n, n], Diagonal::Up).unwrap();
        let m = DynamicManufactured::standard(ManufacturedLaw::Linear);
        let u = m.nodal(mesh.nodes(), 0.3, false);
        field_errors(
            ManufacturedField::Smooth,
            mesh.nodes(),
            mesh.triangles(),
            &u,
            0.3,
        )
        .unwrap()
    }

    #[test]
    fn interpolation_error_converges_at_the_p1_rates() {
        let (a, b) = (interpolation_errors(16), interpolation_errors(32));
        let energy_rate = (a.energy / b.energy).log2();
        let l2_rate = (a.l2 / b.l2).log2();
        assert!((energy_rate - 1.0).abs() < 0.05, "{energy_rate}");
        assert!((l2_rate - 2.0).abs() < 0.05, "{l2_rate}");
    }

    #[test]
    fn the_affine_field_is_represented_exactly() {
        let mesh = TriangleMesh::rectangle([0.0, 0.0], [1.0, 1.0], [3, 3], Diagonal::Up).unwrap();
        let m = DynamicManufactured::standard(ManufacturedLaw::Linear)
            .with_field(ManufacturedField::Affine);
        let u = m.nodal(mesh.nodes(), 0.3, false);
        let e = field_errors(
            ManufacturedField::Affine,
            mesh.nodes(),
            mesh.triangles(),
            &u,
            0.3,
        )
        .unwrap();
        assert!(e.l2 < 1e-15 && e.energy < 1e-15, "{e:?}");
        let smooth = field_errors(
            ManufacturedField::Smooth,
            mesh.nodes(),
            mesh.triangles(),
            &u,
            0.3,
        )
        .unwrap();
        assert!(smooth.l2 > 1e-3, "{smooth:?}");
    }

    #[test]
    fn wrong_time_gives_a_large_error() {
        let mesh = TriangleMesh::rectangle([0.0, 0.0], [1.0, 1.0], [8, 8], Diagonal::Up).unwrap();
        let m = DynamicManufactured::standard(ManufacturedLaw::Linear);
        let u = m.nodal(mesh.nodes(), 0.3, false);
        let same = field_errors(
            ManufacturedField::Smooth,
            mesh.nodes(),
            mesh.triangles(),
            &u,
            0.3,
        )
        .unwrap();
        let other = field_errors(
            ManufacturedField::Smooth,
            mesh.nodes(),
            mesh.triangles(),
            &u,
            0.6,
        )
        .unwrap();
        assert!(other.l2 > 10.0 * same.l2);
    }
}
