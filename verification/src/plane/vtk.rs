//! The ParaView series of a plane scene (`[output] vtk = true`): one frame per snapshot.
//!
//! Point data: `displacement` u (x, y, 0); `velocity` w = u̇ of the scheme (absent at t_0, where
//! the quasistatic problem defines none); on the contact boundary Γ3 (zero elsewhere)
//! `contact_pressure` p_ν, `contact_normal_velocity` w_ν, `contact_active` (1 where
//! p_ν′(w_ν) > 0: the damper acts), `contact_node` (1 on Γ3). The pressure and normal velocity at
//! the contact points (Gauss points or nodes, the solver's contact integration) are carried to
//! the Γ3 nodes by the lumped L² projection q_i = Σ_g W_g φ_i(x_g) q_g / Σ_g W_g φ_i(x_g), which
//! keeps the resultant Σ_i m_i p_i = Σ_g W_g p_g. There is no gap: the damped-response law acts on
//! the normal velocity of a body that stays on its foundation (Fernández & Sofonea 2004, (2.5)),
//! and no slip: Γ3 carries a given tangential traction, no friction.
//!
//! Cell data: `strain` ε(u) of P1 (in-plane; 33 entry 0), `stress` σ = A ε(w) + B ε(u) as the
//! solver records it with σ_33, `von_mises` of (σ_11, σ_22, σ_33, σ_12)
//! ([`contactlab::material::stress_state::von_mises`]), `body_id` (0), `region` (the index of the
//! triangle's `[[region]]` + 1, 0 where `[viscosity]` and `[elasticity]` apply). σ_33 = 0 (plane
//! stress) unless the triangle's B is `law = "plane_strain"`: then σ_33 = a1_B tr ε(u) +
//! a1_A tr ε(w) with the triangle's A and B (= κ (σ_11 + σ_22) for the elastic part; a1_A the
//! viscosity's first constant, μ for the paper's and the saturating law, whose saturating term
//! has no 33 component).

use contactlab::contact::normal_law::SpaceTime;
use contactlab::fem::triangle_p1::P1Triangle;
use contactlab::material::plane_law::PlaneLaw;
use contactlab::material::stress_state::von_mises;
use contactlab::model::quasistatic::plane_dofs::PlaneDofs;
use contactlab::model::quasistatic::plane_output::{PlaneSnapshot, PlaneSolution};
use contactlab::scene::plane::{MaterialSection, PlaneScene};

use crate::vtk::{Array, Cells, Frame};

/// The first constant a1 of a law read as 3D isotropic (σ_33 = a1 tr τ in plane strain).
fn first_constant(
    law: &dyn PlaneLaw,
    section: &MaterialSection,
    field: &str,
) -> Result<f64, String> {
    match (law.as_linear(), section.law.as_str(), section.mu) {
        (Some(l), _, _) => Ok(l.a1),
        (None, "saturating", Some(mu)) => Ok(mu),
        _ => Err(format!(
            "VTK output: σ_33 of plane strain is not defined for {field}.law = \"{}\"",
            section.law
        )),
    }
}

/// The Γ3 nodes of each contact point with φ_i(x_g) (from the rows of the contact operator:
/// (C w)_g = Σ_i φ_i(x_g) w_i · ν_g), and the nodal masses m_i = Σ_g W_g φ_i(x_g).
fn contact_projection(dofs: &PlaneDofs, n_nodes: usize) -> (Vec<Vec<(usize, f64)>>, Vec<f64>) {
    let mut mass = vec![0.0; n_nodes];
    let rows = dofs
        .contact_points
        .iter()
        .map(|p| {
            let mut nodes: Vec<(usize, f64)> = Vec::new();
            for &(dof, c) in &p.entries {
                match nodes.iter_mut().find(|(n, _)| *n == dof / 2) {
                    Some(slot) => slot.1 += c * c,
                    None => nodes.push((dof / 2, c * c)),
                }
            }
            for (n, phi2) in nodes.iter_mut() {
                // |φ ν| = φ for a unit normal
                *phi2 = phi2.sqrt();
                mass[*n] += p.weight * *phi2;
            }
            nodes
        })
        .collect();
    (rows, mass)
}

/// The frames of a plane solution.
pub fn frames(scene: &PlaneScene, sol: &PlaneSolution) -> Result<Vec<Frame>, String> {
    let problem = &scene.problem;
    let roles = problem.validate().map_err(|e| e.to_string())?;
    let dofs = PlaneDofs::new(problem, roles).map_err(|e| e.to_string())?;
    let n = sol.nodes.len();
    let (rows, mass) = contact_projection(&dofs, n);
    // (a1_A, a1_B) of each material (the scene's, then each region's) whose B is plane strain
    let file = &scene.file;
    let mut sections = vec![(&file.viscosity, &file.elasticity, String::new())];
    for (r, region) in file.region.iter().enumerate() {
        sections.push((
            region.viscosity.as_ref().unwrap_or(&file.viscosity),
            region.elasticity.as_ref().unwrap_or(&file.elasticity),
            format!("region[{r}]."),
        ));
    }
    let mut a1 = Vec::with_capacity(sections.len());
    for (m, (viscosity, elasticity, prefix)) in sections.iter().enumerate() {
        let (law_a, law_b) = match m.checked_sub(1) {
            None => (&problem.viscosity, &problem.elasticity),
            Some(r) => (
                &problem.regions[r].viscosity,
                &problem.regions[r].elasticity,
            ),
        };
        a1.push(if elasticity.law == "plane_strain" {
            Some((
                first_constant(&**law_a, viscosity, &format!("{prefix}viscosity"))?,
                first_constant(&**law_b, elasticity, &format!("{prefix}elasticity"))?,
            ))
        } else {
            None
        });
    }
    let elements: Vec<P1Triangle> = sol
        .triangles
        .iter()
        .map(|t| P1Triangle::new([sol.nodes[t[0]], sol.nodes[t[1]], sol.nodes[t[2]]]))
        .collect();
    let points: Vec<[f64; 3]> = sol.nodes.iter().map(|p| [p[0], p[1], 0.0]).collect();
    let regions: Vec<i32> = (0..elements.len())
        .map(|e| problem.region_index(e).map_or(0, |r| r as i32 + 1))
        .collect();
    let strains = |v: &[f64]| -> Vec<[f64; 3]> {
        sol.triangles
            .iter()
            .zip(&elements)
            .map(|(t, el)| el.strain(&std::array::from_fn(|p| v[2 * t[p / 2] + p % 2])))
            .collect()
    };
    let nodal = |s: &PlaneSnapshot, q: &[f64], name: &str| -> Result<Vec<f64>, String> {
        if q.len() != rows.len() {
            return Err(format!(
                "VTK output at t = {}: {} {name} values for {} contact points",
                s.t,
                q.len(),
                rows.len()
            ));
        }
        let mut out = vec![0.0; n];
        for ((row, p), qg) in rows.iter().zip(&dofs.contact_points).zip(q) {
            for &(i, phi) in row {
                out[i] += p.weight * phi * qg;
            }
        }
        for (o, m) in out.iter_mut().zip(&mass) {
            if *m > 0.0 {
                *o /= m;
            }
        }
        Ok(out)
    };
    let mut frames = Vec::with_capacity(sol.snapshots.len());
    for s in &sol.snapshots {
        let eps_u = strains(&s.u);
        let eps_w = s.w.as_deref().map(strains);
        let s33: Vec<f64> = (0..elements.len())
            .map(|e| match a1[regions[e] as usize] {
                Some((a1_a, a1_b)) => {
                    a1_b * (eps_u[e][0] + eps_u[e][1])
                        + eps_w.as_ref().map_or(0.0, |w| a1_a * (w[e][0] + w[e][1]))
                }
                None => 0.0,
            })
            .collect();
        let mut point_data = vec![Array::plane_vectors(
            "displacement",
            (0..n).map(|i| [s.u[2 * i], s.u[2 * i + 1]]),
        )];
        if let Some(w) = &s.w {
            point_data.push(Array::plane_vectors(
                "velocity",
                (0..n).map(|i| [w[2 * i], w[2 * i + 1]]),
            ));
        }
        let pressure = nodal(s, &s.contact_pressure, "pressure")?;
        let velocity = nodal(s, &s.contact_velocity, "normal velocity")?;
        let active: Vec<f64> = (0..n)
            .map(|i| match &problem.contact {
                Some(c) if mass[i] > 0.0 => {
                    let at = SpaceTime {
                        x: sol.nodes[i][0],
                        y: sol.nodes[i][1],
                        t: s.t,
                    };
                    f64::from(u8::from(c.law.derivative(velocity[i], at) > 0.0))
                }
                _ => 0.0,
            })
            .collect();
        point_data.push(Array::scalars("contact_pressure", pressure));
        point_data.push(Array::scalars("contact_normal_velocity", velocity));
        point_data.push(Array::scalars("contact_active", active));
        point_data.push(Array::scalars(
            "contact_node",
            mass.iter().map(|&m| f64::from(u8::from(m > 0.0))).collect(),
        ));
        let cell_data = vec![
            Array::plane_tensors("strain", eps_u.iter().map(|e| (*e, 0.0))),
            Array::plane_tensors("stress", s.stress.iter().copied().zip(s33.iter().copied())),
            Array::scalars(
                "von_mises",
                s.stress
                    .iter()
                    .zip(&s33)
                    .map(|(st, z)| von_mises(st, *z))
                    .collect(),
            ),
            Array::labels("body_id", vec![0; elements.len()]),
            Array::labels("region", regions.clone()),
        ];
        frames.push(Frame {
            time: s.t,
            points: points.clone(),
            cells: Cells::Triangles(sol.triangles.clone()),
            point_data,
            cell_data,
        });
    }
    Ok(frames)
}

#[cfg(test)]
mod tests {
    //! A small plane scene (4 × 2 squares, plane strain, a lubricated foundation) written as a
    //! series and read back with vtkio's reader: the arrays come back bit for bit (Float64 in
    //! base64), the collection lists the snapshot times, and the projected contact pressure keeps
    //! the resultant Σ_g W_g p_g the solver records. A secondary check; the independent one reads
    //! the files with meshio (`.ci/vtk-check`).
    use super::*;
    use contactlab::scene::Scene;
    use vtkio::model::{Attribute, DataSet, IOBuffer};

    const SCENE: &str = r#"
model = "plane"
[geometry]
size = [2.0, 1.0]
divisions = [4, 2]
[time]
final_time = 1.0
steps = 10
scheme = "implicit"
[viscosity]
law = "paper"
mu = 1.0
eta = 2.0
[elasticity]
law = "plane_strain"
young = 100.0
poisson = 0.3
[[dirichlet]]
sides = ["left"]
support = "clamped"
[[traction]]
sides = ["top"]
value = [0.0, "-5*t"]
[contact]
sides = ["bottom"]
law = "lubricated"
beta = 50.0
p0 = 1.0
[output]
times = [0.5, 1.0]
vtk = true
"#;

    fn f64s(a: &Attribute) -> (String, Vec<f64>) {
        match a {
            Attribute::DataArray(d) => match &d.data {
                IOBuffer::F64(v) => (d.name.clone(), v.clone()),
                other => (
                    d.name.clone(),
                    other.clone().cast_into::<f64>().unwrap_or_default(),
                ),
            },
            Attribute::Field { name, .. } => (name.clone(), Vec::new()),
        }
    }

    #[test]
    fn plane_series_reads_back_with_vtkio() {
        let Ok(Scene::Plane(scene)) = Scene::from_toml_str(SCENE, "test.toml") else {
            panic!("the test scene is a plane scene");
        };
        let sol = scene.solver().unwrap().solve(&scene.output).unwrap();
        let frames = frames(&scene, &sol).unwrap();
        assert_eq!(frames.len(), 2);
        let dir = std::env::temp_dir().join(format!("contactlab-vtk-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let written = crate::vtk::write_series(&dir, "solution", "test", &frames).unwrap();
        assert_eq!(written.len(), 3);
        let pvd = std::fs::read_to_string(dir.join("solution.pvd")).unwrap();
        let entries = crate::vtk::pvd::entries(&pvd).unwrap();
        let times: Vec<f64> = entries.iter().map(|e| e.0).collect();
        assert_eq!(times, vec![0.5, 1.0]);
        for ((_, file), frame) in entries.iter().zip(&frames) {
            let vtk = vtkio::Vtk::import(dir.join(file)).unwrap();
            let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
                panic!("an UnstructuredGrid");
            };
            let piece = pieces[0].load_piece_data(None).unwrap();
            assert_eq!(piece.num_points(), sol.nodes.len());
            assert_eq!(piece.cells.types.len(), sol.triangles.len());
            for (attrs, arrays) in [
                (&piece.data.point, &frame.point_data),
                (&piece.data.cell, &frame.cell_data),
            ] {
                assert_eq!(attrs.len(), arrays.len());
                for (a, expected) in attrs.iter().zip(arrays) {
                    let (name, values) = f64s(a);
                    assert_eq!(name, expected.name);
                    let want: Vec<f64> = match &expected.values {
                        crate::vtk::Values::F64(v) => v.clone(),
                        crate::vtk::Values::I32(v) => v.iter().map(|&i| f64::from(i)).collect(),
                    };
                    assert_eq!(values, want, "{name}");
                }
            }
        }
        // the lumped projection keeps the resultant: Σ_i m_i p_i = Σ_g W_g p_g
        let s = sol.snapshots.last().unwrap();
        let roles = scene.problem.validate().unwrap();
        let dofs = PlaneDofs::new(&scene.problem, roles).unwrap();
        let (_, mass) = contact_projection(&dofs, sol.nodes.len());
        let crate::vtk::Values::F64(p) = &frames[1].point_data[2].values else {
            panic!("contact_pressure is Float64");
        };
        let nodal: f64 = mass.iter().zip(p).map(|(m, p)| m * p).sum();
        let points: f64 = dofs
            .contact_points
            .iter()
            .zip(&s.contact_pressure)
            .map(|(g, p)| g.weight * p)
            .sum();
        assert!(
            (nodal - points).abs() <= 1e-12 * points.abs().max(1.0),
            "{nodal} {points}"
        );
        assert!(points > 0.0);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn region_and_plane_strain_sigma_33_follow_each_triangles_materials() {
        // The two-material strip of examples/meshes/bimaterial_strip.msh: "soft" takes the
        // scene's laws, "stiff" its own (plane strain both; E, ν and μ_A differ). Each cell's
        // `region` is its group's index + 1 and σ_33 = λ_B tr ε(u) + μ_A tr ε(w) with its own
        // constants, λ_B = E ν / ((1 + ν)(1 − 2ν)) written here.
        let text = r#"
model = "plane"
[geometry]
shape = "gmsh"
file = "../examples/meshes/bimaterial_strip.msh"
[time]
final_time = 1.0
steps = 4
scheme = "implicit"
[viscosity]
law = "paper"
mu = 1.0
eta = 2.0
[elasticity]
law = "plane_strain"
young = 100.0
poisson = 0.3
[[region]]
group = "stiff"
viscosity = { law = "paper", mu = 3.0, eta = 4.0 }
elasticity = { law = "plane_strain", young = 400.0, poisson = 0.2 }
[[dirichlet]]
group = "left"
support = "clamped"
[[traction]]
group = "right"
value = ["t", "-t"]
[output]
times = [1.0]
"#;
        let Ok(Scene::Plane(scene)) = Scene::from_toml_str(text, "strip.toml") else {
            panic!("the test scene is a plane scene");
        };
        let sol = scene.solver().unwrap().solve(&scene.output).unwrap();
        let frame = &frames(&scene, &sol).unwrap()[0];
        let cell = |name: &str| frame.cell_data.iter().find(|a| a.name == name).unwrap();
        let crate::vtk::Values::I32(region) = &cell("region").values else {
            panic!("integer labels");
        };
        let stiff = &scene.problem.regions[0].triangles;
        assert_eq!(stiff.len(), 44);
        let crate::vtk::Values::F64(stress) = &cell("stress").values else {
            panic!("floats");
        };
        let lambda = |e: f64, nu: f64| e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let snap = &sol.snapshots[0];
        let w = snap.w.as_ref().unwrap();
        for (e, t) in sol.triangles.iter().enumerate() {
            let in_stiff = stiff.binary_search(&e).is_ok();
            assert_eq!(region[e], i32::from(in_stiff), "cell {e}");
            let el = P1Triangle::new([sol.nodes[t[0]], sol.nodes[t[1]], sol.nodes[t[2]]]);
            let tr = |v: &[f64]| {
                let s = el.strain(&std::array::from_fn(|p| v[2 * t[p / 2] + p % 2]));
                s[0] + s[1]
            };
            let (lb, mu_a) = if in_stiff {
                (lambda(400.0, 0.2), 3.0)
            } else {
                (lambda(100.0, 0.3), 1.0)
            };
            let s33 = lb * tr(&snap.u) + mu_a * tr(w);
            let got = stress[9 * e + 8];
            assert!(
                (got - s33).abs() <= 1e-12 * s33.abs().max(1e-3),
                "cell {e}: {got} vs {s33}"
            );
        }
    }
}
