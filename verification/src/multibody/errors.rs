//! The measured functionals of multibody runs: a body's centre-of-mass velocity (its momentum
//! Σ (M v)_I over its mass, with the consistent mass matrix) and the contact interval of a run.

use contactlab::model::multibody::audit::MultibodyRecord;
use contactlab::model::multibody::bodies::BodySet;

/// The centre-of-mass velocity of body `b`: Σ_I (M v)_I / m_b, `v` the system's velocity.
/// `scratch` holds M v on return (the system's size).
pub fn centre_velocity(bodies: &BodySet, b: usize, v: &[f64], scratch: &mut [f64]) -> [f64; 2] {
    bodies.mass_mul(v, scratch);
    let mut p = [0.0; 2];
    let mesh = &bodies.body(b).data().mesh;
    for node in 0..mesh.nodes().len() {
        for (c, pc) in p.iter_mut().enumerate() {
            if let Some(d) = bodies.dof(b, node, c) {
                *pc += scratch[d];
            }
        }
    }
    let m = bodies.mass_of(b);
    [p[0] / m, p[1] / m]
}

/// The times of the first and the last step with an active constraint (None: no contact).
pub fn contact_interval(records: &[MultibodyRecord]) -> Option<(f64, f64)> {
    let first = records.iter().find(|r| r.active > 0)?;
    let last = records.iter().rev().find(|r| r.active > 0)?;
    Some((first.time, last.time))
}

#[cfg(test)]
mod tests {
    //! A body in rigid translation has its translation velocity as its centre velocity (the
    //! consistent mass matrix's rows sum to the nodal masses); the contact interval reads the first
    //! and last active records.
    use std::sync::Arc;

    use contactlab::field::Field;
    use contactlab::material::hyperelastic::LinearElastic;
    use contactlab::mesh::triangle::{Diagonal, TriangleMesh};
    use contactlab::model::dynamic::bar::MassMatrix;
    use contactlab::model::dynamic::plane_body::{PlaneBody, PlaneBodyData};

    use super::*;

    #[test]
    fn rigid_translation_has_its_velocity_as_centre_velocity() {
        let body = PlaneBody::new(PlaneBodyData {
            mesh: TriangleMesh::rectangle([0.0, 0.0], [2.0, 1.0], [4, 3], Diagonal::Up).unwrap(),
            density: 3.0,
            law: Arc::new(LinearElastic::from_young_poisson(1.0, 0.2).unwrap()),
            dirichlet: vec![],
            traction: vec![],
            body_force: [Field::Constant(0.0), Field::Constant(0.0)],
            mass: MassMatrix::Consistent,
            regions: vec![],
        })
        .unwrap();
        let bodies = BodySet::new(vec![Arc::new(body)]).unwrap();
        let mut v = vec![0.0; bodies.dofs()];
        bodies.rigid_velocity(0, [0.7, -0.2], 0.0, [0.0, 0.0], &mut v);
        let mut scratch = vec![0.0; v.len()];
        let c = centre_velocity(&bodies, 0, &v, &mut scratch);
        assert!((c[0] - 0.7).abs() < 1e-14 && (c[1] + 0.2).abs() < 1e-14);
    }

    #[test]
    fn contact_interval_reads_the_active_records() {
        let rec = |t: f64, active: usize| MultibodyRecord {
            time: t,
            active,
            ..Default::default()
        };
        let r = [rec(0.0, 0), rec(0.1, 1), rec(0.2, 2), rec(0.3, 0)];
        assert_eq!(contact_interval(&r), Some((0.1, 0.2)));
        assert_eq!(contact_interval(&r[..1]), None);
    }
}
