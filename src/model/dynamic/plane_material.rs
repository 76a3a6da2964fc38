//! The materials of a plane body: the body's density ρ and law W, and regions (2D physical
//! groups of a mesh file) with their own. The body's mass, internal force, tangent, stored energy
//! and discrete gradient sum element by element with each element's ρ_e and W_e
//! (Barboteu–Danan–Sofonea, "BDS", (1.15)–(1.17) with piecewise-constant data):
//!
//!   𝒲(u) = Σ_e |e| W_e(F_e(u)),   M_ab = Σ_e ρ_e ∫_e φ_a φ_b.
//!
//! The element → material table is built once, when the body is built: the time loops look an
//! element's material up by index and allocate nothing.

use std::sync::Arc;

use crate::error::{require_positive, InputError};
use crate::material::hyperelastic::Hyperelastic2d;

/// A region of a plane body with its own density and law: its triangles (sorted indices) take
/// ρ and W from here instead of the body's.
#[derive(Debug, Clone)]
pub struct BodyRegion {
    /// The group's name (for errors and descriptions).
    pub name: String,
    pub triangles: Vec<usize>,
    pub density: f64,
    pub law: Arc<dyn Hyperelastic2d>,
}

/// The element → material table: material 0 is the body's, material r + 1 region r's.
#[derive(Debug, Clone)]
pub(crate) struct ElementMaterials {
    densities: Vec<f64>,
    laws: Vec<Arc<dyn Hyperelastic2d>>,
    of_element: Vec<u32>,
}

impl ElementMaterials {
    /// The table of `elements` triangles: the body's `density` and `law` and the disjoint
    /// `regions` (errors name `region[r]`; overlapping regions name both).
    pub(crate) fn new(
        density: f64,
        law: &Arc<dyn Hyperelastic2d>,
        regions: &[BodyRegion],
        elements: usize,
    ) -> Result<Self, InputError> {
        require_positive("body.density", density)?;
        law.validate("body.material")?;
        let mut densities = vec![density];
        let mut laws = vec![law.clone()];
        let mut of_element = vec![0u32; elements];
        for (r, region) in regions.iter().enumerate() {
            require_positive(&format!("region[{r}].density"), region.density)?;
            region.law.validate(&format!("region[{r}].material"))?;
            if !region.triangles.windows(2).all(|w| w[0] < w[1]) {
                return Err(InputError::new(
                    format!("region[{r}]"),
                    &region.name,
                    "sorted, distinct triangle indices",
                ));
            }
            let index = u32::try_from(r + 1)
                .map_err(|_| InputError::new("region", regions.len(), "fewer than 2³² regions"))?;
            for &t in &region.triangles {
                match of_element.get_mut(t) {
                    None => {
                        return Err(InputError::new(
                            format!("region[{r}]"),
                            format!("triangle {t}"),
                            format!("triangles below {elements}"),
                        ))
                    }
                    Some(&mut other) if other != 0 => {
                        let other = other as usize - 1;
                        return Err(InputError::new(
                            format!("region[{r}].group"),
                            format!("\"{}\"", region.name),
                            format!(
                                "a region disjoint from region[{other}] (\"{}\"): triangle {t} \
                                 is in both",
                                regions[other].name
                            ),
                        ));
                    }
                    Some(slot) => *slot = index,
                }
            }
            densities.push(region.density);
            laws.push(region.law.clone());
        }
        Ok(Self {
            densities,
            laws,
            of_element,
        })
    }

    /// The material of element `e`: 0 the body's, r + 1 region r's.
    #[inline]
    pub(crate) fn index(&self, e: usize) -> usize {
        self.of_element[e] as usize
    }

    /// W_e, the law of element `e`.
    #[inline]
    pub(crate) fn law(&self, e: usize) -> &dyn Hyperelastic2d {
        self.laws[self.index(e)].as_ref()
    }

    /// ρ_e, the density of element `e`.
    #[inline]
    pub(crate) fn density(&self, e: usize) -> f64 {
        self.densities[self.index(e)]
    }

    /// Whether every material's law is small-strain (F_int linear).
    pub(crate) fn all_small_strain(&self) -> bool {
        self.laws.iter().all(|l| l.is_small_strain())
    }

    /// The largest longitudinal wave speed at rest over the materials (the shortest wave-crossing
    /// time h_min / c bounds every material's).
    pub(crate) fn wave_speed(&self) -> f64 {
        self.laws
            .iter()
            .zip(&self.densities)
            .map(|(l, &rho)| l.wave_speed(rho))
            .fold(f64::NEG_INFINITY, f64::max)
    }
}
