//! A body's mesh counts in a scene table, refined for the planner (docs/planner.md §5).
//!
//! The planner varies an integer M with h ∝ 1/M. A scene writes its mesh as the counts of a
//! generated shape; M is the shape's primary count and every count of the section scales with
//! it, rounded, so that the cells keep their shape:
//!
//! | shape | primary count (M) | other counts | length L (h = L / M) | nodes |
//! |---|---|---|---|---|
//! | `bar` | `elements` | — | `length` | M + 1 |
//! | `rectangle` | `divisions[0]` | `divisions[1]` | `size[0]` | (n_x + 1)(n_y + 1) |
//! | `disk` | `rings` | — | `radius` | 3 r (r + 1) + 1 |
//! | `annulus` | `radial` | `around` (≥ 3) | `outer − inner` | (radial + 1) × around |
//!
//! A Gmsh mesh (`shape = "gmsh"`) has no count to scale: the planner refuses it with an error
//! that says so (a finer mesh is the mesher's: `gmsh -refine`, or a smaller size field), rather
//! than splitting its triangles, which would keep the coarse polygon of a curved boundary and
//! converge to the solution on that polygon.

/// One count of a body section: its key, its value in the scene, the least value allowed.
#[derive(Debug, Clone, PartialEq)]
struct Count {
    /// The key (e.g. `radial`), or `divisions` with its entry.
    key: &'static str,
    entry: Option<usize>,
    value: usize,
    min: usize,
}

/// The mesh counts of one body section of a scene table, as the planner scales them.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyCounts {
    /// The section's dotted prefix, as an override names it (`body`, `body[1]`).
    prefix: String,
    shape: String,
    counts: Vec<Count>,
    /// The length the primary count divides.
    length: f64,
}

fn usize_of(section: &toml::Table, prefix: &str, key: &str) -> Result<usize, String> {
    match section.get(key) {
        Some(toml::Value::Integer(v)) if *v >= 1 => Ok(*v as usize),
        Some(v) => Err(format!("{prefix}.{key} = {v}: expected a count ≥ 1")),
        None => Err(format!("{prefix}.{key}: missing")),
    }
}

fn float_of(section: &toml::Table, prefix: &str, key: &str) -> Result<f64, String> {
    match section.get(key) {
        Some(toml::Value::Float(v)) if *v > 0.0 && v.is_finite() => Ok(*v),
        Some(toml::Value::Integer(v)) if *v > 0 => Ok(*v as f64),
        Some(v) => Err(format!("{prefix}.{key} = {v}: expected a positive length")),
        None => Err(format!("{prefix}.{key}: missing")),
    }
}

fn pair_of<T>(
    section: &toml::Table,
    prefix: &str,
    key: &str,
    f: impl Fn(&toml::Value) -> Option<T>,
) -> Result<[T; 2], String> {
    let bad = || format!("{prefix}.{key}: expected two values [x, y]");
    let a = section
        .get(key)
        .and_then(|v| v.as_array())
        .ok_or_else(bad)?;
    match a.as_slice() {
        [x, y] => Ok([f(x).ok_or_else(bad)?, f(y).ok_or_else(bad)?]),
        _ => Err(bad()),
    }
}

impl BodyCounts {
    /// The counts of the body section `section` (named `prefix` in errors and overrides).
    ///
    /// # Errors
    /// A Gmsh body (its mesh has no count to scale), an unknown shape, a count or length
    /// missing or not positive.
    pub fn read(section: &toml::Table, prefix: &str) -> Result<Self, String> {
        let shape = section
            .get("shape")
            .and_then(|s| s.as_str())
            .ok_or_else(|| format!("{prefix}.shape: missing"))?
            .to_string();
        let scalar = |key: &'static str, min: usize| -> Result<Count, String> {
            Ok(Count {
                key,
                entry: None,
                value: usize_of(section, prefix, key)?,
                min,
            })
        };
        let (counts, length) = match shape.as_str() {
            "bar" => (
                vec![scalar("elements", 1)?],
                float_of(section, prefix, "length")?,
            ),
            "rectangle" => {
                let d = pair_of(section, prefix, "divisions", |v| {
                    v.as_integer().filter(|n| *n >= 1).map(|n| n as usize)
                })?;
                let size = pair_of(section, prefix, "size", |v| {
                    v.as_float()
                        .or_else(|| v.as_integer().map(|n| n as f64))
                        .filter(|x| *x > 0.0 && x.is_finite())
                })?;
                (
                    (0..2)
                        .map(|i| Count {
                            key: "divisions",
                            entry: Some(i),
                            value: d[i],
                            min: 1,
                        })
                        .collect(),
                    size[0],
                )
            }
            "disk" => (
                vec![scalar("rings", 1)?],
                float_of(section, prefix, "radius")?,
            ),
            "annulus" => {
                let (inner, outer) = (
                    float_of(section, prefix, "inner")?,
                    float_of(section, prefix, "outer")?,
                );
                if outer <= inner {
                    return Err(format!(
                        "{prefix}.outer = {outer}: expected a radius > {prefix}.inner = {inner}"
                    ));
                }
                (
                    vec![scalar("radial", 1)?, scalar("around", 3)?],
                    outer - inner,
                )
            }
            "gmsh" => {
                return Err(format!(
                    "{prefix}.shape = \"gmsh\": the planner scales the counts of a generated \
                     shape (bar, rectangle, disk, annulus); a Gmsh mesh has none — refine it in \
                     the mesher (gmsh -refine, or a smaller mesh size) and plan the time step \
                     on each mesh"
                ))
            }
            other => {
                return Err(format!(
                    "{prefix}.shape = \"{other}\": expected bar, rectangle, disk or annulus"
                ))
            }
        };
        Ok(Self {
            prefix: prefix.to_string(),
            shape,
            counts,
            length,
        })
    }

    /// The primary count in the scene (M at the scene's resolution).
    pub fn primary(&self) -> usize {
        self.counts[0].value
    }

    /// The shape's name.
    pub fn shape(&self) -> &str {
        &self.shape
    }

    /// Every count scaled by `m / m0`, rounded, at least its least value.
    fn scaled(&self, m: usize, m0: usize) -> Vec<usize> {
        let f = m as f64 / m0.max(1) as f64;
        self.counts
            .iter()
            .enumerate()
            .map(|(i, c)| {
                if i == 0 && m0 == self.primary() {
                    m.max(c.min)
                } else {
                    ((c.value as f64 * f).round() as usize).max(c.min)
                }
            })
            .collect()
    }

    /// Adds to `set` the overrides that give the section's counts their values at M = `m`,
    /// where `m0` is the M of the scene's own counts.
    pub fn overrides(&self, m: usize, m0: usize, set: &mut toml::Table) {
        let values = self.scaled(m, m0);
        let int = |v: usize| toml::Value::Integer(v as i64);
        let mut divisions = Vec::new();
        for (c, v) in self.counts.iter().zip(values) {
            match c.entry {
                None => {
                    set.insert(format!("{}.{}", self.prefix, c.key), int(v));
                }
                Some(_) => divisions.push(int(v)),
            }
        }
        if !divisions.is_empty() {
            set.insert(
                format!("{}.divisions", self.prefix),
                toml::Value::Array(divisions),
            );
        }
    }

    /// The node count of the mesh at M = `m` (the table of the module docs).
    pub fn nodes(&self, m: usize, m0: usize) -> f64 {
        let v: Vec<f64> = self.scaled(m, m0).into_iter().map(|x| x as f64).collect();
        match self.shape.as_str() {
            "bar" => v[0] + 1.0,
            "rectangle" => (v[0] + 1.0) * (v[1] + 1.0),
            "disk" => 3.0 * v[0] * (v[0] + 1.0) + 1.0,
            // annulus
            _ => (v[0] + 1.0) * v[1],
        }
    }

    /// The nominal size h = L / M at M = `m` (module docs), where `m0` is the M of the scene's
    /// own counts: exactly ∝ 1/M, as the planner's h(M) = (h M)/M assumes.
    pub fn h(&self, m: usize, m0: usize) -> f64 {
        self.length * self.primary() as f64 / (m0.max(1) as f64 * m.max(1) as f64)
    }
}

/// A scene table whose bodies the planner refines: every body's counts scale with M, the first
/// body's primary count (`counts[0]`), and each run overrides `time.steps` and `time.scheme`.
#[derive(Debug, Clone)]
pub struct RefinedScene {
    /// The scene's table without `[output]` (a run records the state at T only).
    pub table: toml::Table,
    /// The scene's name in errors.
    pub source: String,
    /// Per body section, in order.
    pub counts: Vec<BodyCounts>,
}

impl RefinedScene {
    /// The scene `table` (named `source` in errors) with the counts of its body sections.
    pub fn new(mut table: toml::Table, source: &str, counts: Vec<BodyCounts>) -> Self {
        let _ = crate::core::overrides::remove(&mut table, "output");
        Self {
            table,
            source: source.to_string(),
            counts,
        }
    }

    /// M at the scene's own counts.
    pub fn m0(&self) -> usize {
        self.counts.first().map_or(1, BodyCounts::primary)
    }

    /// The scene's table at M = `elements`, N = `steps` and the scheme named `scheme`.
    ///
    /// # Errors
    /// An override that cannot be applied.
    pub fn table_at(
        &self,
        elements: usize,
        steps: usize,
        scheme: &str,
    ) -> Result<toml::Table, String> {
        let mut set = toml::Table::new();
        for c in &self.counts {
            c.overrides(elements, self.m0(), &mut set);
        }
        set.insert("time.steps".into(), toml::Value::Integer(steps as i64));
        set.insert("time.scheme".into(), toml::Value::String(scheme.into()));
        crate::core::overrides::applied(&self.table, &set).map_err(|e| e.to_string())
    }

    /// The first body's nominal h at M = `elements`.
    pub fn h(&self, elements: usize) -> f64 {
        self.counts
            .first()
            .map_or(1.0 / elements.max(1) as f64, |c| c.h(elements, self.m0()))
    }

    /// The work of a run: the total node count at M = `elements` times N = `steps`.
    pub fn work(&self, elements: usize, steps: usize) -> f64 {
        let nodes: f64 = self
            .counts
            .iter()
            .map(|c| c.nodes(elements, self.m0()))
            .sum();
        nodes * steps as f64
    }
}

#[cfg(test)]
mod tests {
    //! The counts of each shape scale with M and keep the cells' shape; a Gmsh body is refused
    //! with the reason.
    use super::*;

    fn section(text: &str) -> toml::Table {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn an_annulus_scales_radial_and_around_together() {
        let b = BodyCounts::read(
            &section("shape = \"annulus\"\ninner = 0.3\nouter = 0.5\nradial = 8\naround = 64"),
            "body",
        )
        .unwrap();
        assert_eq!(b.primary(), 8);
        let mut set = toml::Table::new();
        b.overrides(2, 8, &mut set);
        assert_eq!(set["body.radial"].as_integer(), Some(2));
        assert_eq!(set["body.around"].as_integer(), Some(16));
        assert_eq!(b.nodes(2, 8), 3.0 * 16.0);
        assert!((b.h(4, 8) - 0.05).abs() < 1e-15);
        // `around` never below 3
        let mut set = toml::Table::new();
        b.overrides(0, 8, &mut set);
        assert!(set["body.around"].as_integer().unwrap() >= 3);
    }

    #[test]
    fn a_rectangle_keeps_its_aspect_and_a_second_body_follows_the_first() {
        let b = BodyCounts::read(
            &section("shape = \"rectangle\"\nsize = [1.0, 0.5]\ndivisions = [5, 3]"),
            "body[1]",
        )
        .unwrap();
        let mut set = toml::Table::new();
        // the first body's M goes from 16 to 32: this body doubles too
        b.overrides(32, 16, &mut set);
        let d = set["body[1].divisions"].as_array().unwrap();
        assert_eq!((d[0].as_integer(), d[1].as_integer()), (Some(10), Some(6)));
        assert_eq!(b.nodes(32, 16), 11.0 * 7.0);
        // h of the first body's M, exactly ∝ 1/M
        assert!((b.h(32, 16) * 32.0 - b.h(8, 16) * 8.0).abs() < 1e-15);
    }

    #[test]
    fn a_gmsh_body_is_refused_with_the_reason() {
        let e =
            BodyCounts::read(&section("shape = \"gmsh\"\nfile = \"o.msh\""), "body").unwrap_err();
        assert!(
            e.contains("body.shape") && e.contains("gmsh -refine"),
            "{e}"
        );
        let e = BodyCounts::read(&section("shape = \"disk\"\nradius = 1.0"), "body").unwrap_err();
        assert!(e.contains("body.rings"), "{e}");
    }
}
