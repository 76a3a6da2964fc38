//! The planner on a rod scene (`core::plan`): the scene's own (M, N) as the finest pilot, its
//! `[exact]` solution for the errors, the explicit scheme's bound k < 2a/b (docs/rod.md).

use contactlab::model::quasistatic::scheme::TimeScheme;
use contactlab::scene::rod::RodScene;

use crate::core::plan::Plannable;
use crate::core::study::Study;
use crate::core::sweep::Level;
use crate::rod::study::{time_loop_seconds, Discretization, ExactSpec, RodStudy};

/// A rod scene's study with its own resolution.
pub struct RodPlan {
    pub study: RodStudy,
    pub base: (usize, usize),
}

impl RodPlan {
    /// From a scene's text (`source` names it in errors): it must name an `[exact]` solution.
    pub fn from_text(text: &str, source: &str) -> Result<Self, String> {
        let scene = RodScene::from_toml_str(text, source).map_err(|e| e.to_string())?;
        let exact: ExactSpec = match &scene.exact {
            Some(t) => t
                .clone()
                .try_into()
                .map_err(|e: toml::de::Error| format!("{source}: [exact]: {e}"))?,
            None => {
                return Err(format!(
                    "{source}: the planner needs an [exact] table (the errors of the pilots are \
                     measured against it; self-convergence is not implemented yet)"
                ))
            }
        };
        let table: toml::Table = toml::from_str(text).map_err(|e| format!("{source}: {e}"))?;
        let study = RodStudy::new(Some(&table), Some(&exact), &Discretization::default())
            .map_err(|e| format!("{source}: {e}"))?;
        Ok(Self {
            study,
            base: (scene.mesh.elements(), scene.grid.steps()),
        })
    }
}

impl Study for RodPlan {
    type Scheme = TimeScheme;

    fn default_scheme(&self) -> TimeScheme {
        self.study.default_scheme()
    }

    fn run_level(
        &self,
        elements: usize,
        steps: usize,
        scheme: TimeScheme,
        time_error: bool,
    ) -> Result<Level, String> {
        self.study.run_level(elements, steps, scheme, time_error)
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
    /// scheme's E carries its velocity at t_n, first order too. The nodal and end errors are
    /// exact in space (no p).
    fn expected_orders(&self, _scheme: TimeScheme, functional: &str) -> (Option<f64>, Option<f64>) {
        match functional {
            "paper_E" => (Some(1.0), Some(1.0)),
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

    /// 100 ε times the largest |u_h(L, T)| of the pilots: below it the errors are round-off.
    fn floor(&self, _functional: &str, pilots: &[Level]) -> f64 {
        let scale = pilots.iter().map(|l| l.u_end.abs()).fold(0.0, f64::max);
        100.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE)
    }
}
