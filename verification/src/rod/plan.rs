//! The planner on a rod scene (`core::plan`): the scene's own (M, N) as the finest pilot, its
//! `[exact]` solution for the errors, the explicit scheme's bound k < 2a/b (docs/rod.md).

use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::scene::rod::RodScene;

use crate::core::plan::{Based, Plannable};
use crate::core::sweep::Level;
use crate::rod::study::{time_loop_seconds, Discretization, ExactSpec, RodStudy};

/// A rod study with the resolution of its first pilot round.
pub type RodPlan = Based<RodStudy>;

impl RodPlan {
    /// From a scene's text (`source` names it in errors). With an `[exact]` table the errors are
    /// measured against it; without one the planner uses self-convergence on the values
    /// `end_displacement` (u_h(L, T)) and `contact_stress` (σ_h(L, T)).
    pub fn from_text(text: &str, source: &str) -> Result<Self, String> {
        let scene = RodScene::from_toml_str(text, source).map_err(|e| e.to_string())?;
        let exact: Option<ExactSpec> = match &scene.exact {
            Some(t) => Some(
                t.clone()
                    .try_into()
                    .map_err(|e: toml::de::Error| format!("{source}: [exact]: {e}"))?,
            ),
            None => None,
        };
        let table: toml::Table = toml::from_str(text).map_err(|e| format!("{source}: {e}"))?;
        let study = RodStudy::new(Some(&table), exact.as_ref(), &Discretization::default())
            .map_err(|e| format!("{source}: {e}"))?;
        Ok(Self {
            study,
            base: (scene.mesh.elements(), scene.grid.steps()),
        })
    }
}

impl Plannable for RodPlan {
    fn base(&self) -> (usize, usize) {
        self.base
    }

    fn final_time(&self) -> f64 {
        self.study.problem.final_time
    }

    fn schemes(&self) -> Vec<TimeScheme> {
        TimeScheme::ALL.to_vec()
    }

    fn stability_bound(&self, scheme: TimeScheme) -> Option<f64> {
        (scheme == TimeScheme::Explicit).then(|| self.study.problem.explicit_stability_bound())
    }

    /// The paper's energy error E: first order in h (P1 in the energy norm) and first order in k
    /// for the θ = 0 and θ = 1 schemes (`rod_p0_6_explicit`, `rod_schemes`); the midpoint
    /// scheme's E carries its velocity at t_n, first order too. The nodal and end values are
    /// exact in space (no p): the end displacement at T is first order in k for θ = 0, 1 and
    /// second order for the midpoint scheme; the contact stress at T carries the velocity at T,
    /// first order for every scheme.
    fn expected_orders(&self, scheme: TimeScheme, functional: &str) -> (Option<f64>, Option<f64>) {
        match functional {
            "paper_E" => (Some(1.0), Some(1.0)),
            "end_displacement" if self.study.exact.is_none() => (
                None,
                Some(if scheme == TimeScheme::Midpoint {
                    2.0
                } else {
                    1.0
                }),
            ),
            "contact_stress" => (None, Some(1.0)),
            _ => (None, None),
        }
    }

    fn seconds(&self, elements: usize, steps: usize, scheme: TimeScheme) -> Result<f64, String> {
        let solver = self
            .study
            .solver(elements, steps, scheme)
            .map_err(|e| e.to_string())?;
        time_loop_seconds(&solver, 3)
    }

    /// M·N: the rod's step is a condensed scalar contact solve and one pass over the nodes.
    fn work(&self, elements: usize, steps: usize) -> f64 {
        elements as f64 * steps as f64
    }

    /// 100 ε times the largest |u_h(L, T)| of the pilots (and of the functional's values):
    /// below it the errors are round-off.
    fn floor(&self, functional: &str, pilots: &[Level]) -> f64 {
        let scale = pilots
            .iter()
            .map(|l| {
                let v = l.values.get(functional).map_or(0.0, |v| v.abs());
                l.u_end.abs().max(v)
            })
            .fold(0.0, f64::max);
        100.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE)
    }
}
