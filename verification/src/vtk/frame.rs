//! One output time as ParaView reads it: the mesh (points in 3D with z = 0, cells) and the named
//! point and cell arrays.

/// The cells of a frame.
#[derive(Debug, Clone, PartialEq)]
pub enum Cells {
    /// P1 triangles (VTK_TRIANGLE), counter-clockwise node triples.
    Triangles(Vec<[usize; 3]>),
    /// Line segments (VTK_LINE), node pairs: an interval mesh.
    Lines(Vec<[usize; 2]>),
}

impl Cells {
    /// The number of cells.
    pub fn len(&self) -> usize {
        match self {
            Cells::Triangles(t) => t.len(),
            Cells::Lines(l) => l.len(),
        }
    }

    /// Whether there is no cell.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The largest node index (None without cells).
    fn max_node(&self) -> Option<usize> {
        match self {
            Cells::Triangles(t) => t.iter().flatten().copied().max(),
            Cells::Lines(l) => l.iter().flatten().copied().max(),
        }
    }
}

/// The values of an array.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    F64(Vec<f64>),
    /// Integer labels (the body id).
    I32(Vec<i32>),
}

impl Values {
    fn len(&self) -> usize {
        match self {
            Values::F64(v) => v.len(),
            Values::I32(v) => v.len(),
        }
    }
}

/// A named array of `components` values per point or per cell (tuples stored one after the
/// other; a tensor is 9 components, row-major 3 × 3).
#[derive(Debug, Clone, PartialEq)]
pub struct Array {
    pub name: String,
    pub components: usize,
    pub values: Values,
}

impl Array {
    /// A scalar per entity.
    pub fn scalars(name: &str, values: Vec<f64>) -> Self {
        Self {
            name: name.to_string(),
            components: 1,
            values: Values::F64(values),
        }
    }

    /// A plane vector per entity, written as (x, y, 0).
    pub fn plane_vectors(name: &str, xy: impl IntoIterator<Item = [f64; 2]>) -> Self {
        Self {
            name: name.to_string(),
            components: 3,
            values: Values::F64(xy.into_iter().flat_map(|v| [v[0], v[1], 0.0]).collect()),
        }
    }

    /// A symmetric tensor per entity from its in-plane components (11, 22, 12) and its
    /// out-of-plane 33 component (13 = 23 = 0), written as the full row-major 3 × 3 matrix.
    pub fn plane_tensors(name: &str, t: impl IntoIterator<Item = ([f64; 3], f64)>) -> Self {
        Self {
            name: name.to_string(),
            components: 9,
            values: Values::F64(
                t.into_iter()
                    .flat_map(|(s, s33)| [s[0], s[2], 0.0, s[2], s[1], 0.0, 0.0, 0.0, s33])
                    .collect(),
            ),
        }
    }

    /// Integer labels per entity.
    pub fn labels(name: &str, values: Vec<i32>) -> Self {
        Self {
            name: name.to_string(),
            components: 1,
            values: Values::I32(values),
        }
    }
}

/// One output time.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    pub time: f64,
    /// Node coordinates (x, y, 0) — or (x, 0, 0) on an interval.
    pub points: Vec<[f64; 3]>,
    pub cells: Cells,
    pub point_data: Vec<Array>,
    pub cell_data: Vec<Array>,
}

impl Frame {
    /// Checks the frame: a finite time, finite points, cells that name existing points, unique
    /// array names, each array `components × (points or cells)` long, every value finite. The
    /// error names the array and the time.
    pub fn check(&self) -> Result<(), String> {
        let at = format!("t = {}", self.time);
        if !self.time.is_finite() {
            return Err(format!("VTK output: the time {} is not finite", self.time));
        }
        if let Some(i) = self
            .points
            .iter()
            .position(|p| !p.iter().all(|x| x.is_finite()))
        {
            return Err(format!(
                "VTK output at {at}: the coordinates of point {i} are not finite: {:?}",
                self.points[i]
            ));
        }
        if let Some(m) = self.cells.max_node() {
            if m >= self.points.len() {
                return Err(format!(
                    "VTK output at {at}: a cell names point {m} of {}",
                    self.points.len()
                ));
            }
        }
        let mut names: Vec<&str> = Vec::new();
        for (kind, arrays, count) in [
            ("point", &self.point_data, self.points.len()),
            ("cell", &self.cell_data, self.cells.len()),
        ] {
            for a in arrays {
                if names.contains(&a.name.as_str()) {
                    return Err(format!("VTK output at {at}: two arrays named `{}`", a.name));
                }
                names.push(&a.name);
                if a.components == 0 || a.values.len() != a.components * count {
                    return Err(format!(
                        "VTK output at {at}: {kind} array `{}` has {} values, expected {} × {count}",
                        a.name,
                        a.values.len(),
                        a.components
                    ));
                }
                if let Values::F64(v) = &a.values {
                    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                        return Err(format!(
                            "VTK output at {at}: {kind} array `{}` has the non-finite value {} at \
                             {kind} {} (component {}); no file written",
                            a.name,
                            v[i],
                            i / a.components,
                            i % a.components
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! The checks of a frame: a non-finite value is refused with the array's name and the time;
    //! a wrong length with the expected one.
    use super::*;

    fn frame() -> Frame {
        Frame {
            time: 0.5,
            points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            cells: Cells::Triangles(vec![[0, 1, 2]]),
            point_data: vec![Array::plane_vectors("displacement", [[0.0, 0.0]; 3])],
            cell_data: vec![Array::scalars("von_mises", vec![1.0])],
        }
    }

    #[test]
    fn a_non_finite_value_is_an_error_naming_array_and_time() {
        assert!(frame().check().is_ok());
        let mut f = frame();
        f.cell_data[0] = Array::scalars("von_mises", vec![f64::NAN]);
        let e = f.check().unwrap_err();
        assert!(e.contains("von_mises") && e.contains("t = 0.5"), "{e}");
    }

    #[test]
    fn a_wrong_length_is_an_error() {
        let mut f = frame();
        f.point_data[0] = Array::plane_vectors("displacement", [[0.0, 0.0]; 2]);
        let e = f.check().unwrap_err();
        assert!(
            e.contains("displacement") && e.contains("expected 3 × 3"),
            "{e}"
        );
    }
}
