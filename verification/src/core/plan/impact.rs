//! What the dynamic and the two-body scene plans share (`dynamic/scene_plan.rs`,
//! `multibody/scene_plan.rs`, docs/planner.md §1–§3): a scene of generated shapes whose counts
//! scale with M ([`RefinedScene`]), planned by self-convergence.
//!
//! - No expected orders: an impact's regularity is the scene's, so the orders are not checked
//!   against a theory; the misfit, the edges of the searched interval and the chosen run carry
//!   the weight (docs/planner.md §3).
//! - No stability bound: every scheme of these families is implicit.
//! - The work is nodes × N (each Newton iteration of a step is a sparse solve over the nodes).
//! - The cost of a pilot is its own run's CPU time on its thread: a run is long against the
//!   clock's noise, and parallel pilots then do not inflate one another's seconds.
//! - The floor is 100 ε times the largest magnitude of the functional over the pilots.

use crate::core::plan::refine::RefinedScene;
use crate::core::plan::{value_floor, Plannable};
use crate::core::study::Study;
use crate::core::sweep::Level;

/// A scene plan of the impact families; every such plan is [`Plannable`] as the module docs say.
pub trait ImpactScenePlan: Study {
    /// The scene's own resolution (M₀, N₀).
    fn base(&self) -> (usize, usize);
    /// T (k = T/N).
    fn final_time(&self) -> f64;
    /// The schemes the scene's treatment allows.
    fn schemes(&self) -> Vec<Self::Scheme>;
    /// The scene, its bodies' counts scaled with M.
    fn refined(&self) -> &RefinedScene;
    /// The CPU seconds of one time loop at (M, N, scheme), on its thread.
    fn time_loop_seconds(
        &self,
        elements: usize,
        steps: usize,
        scheme: Self::Scheme,
    ) -> Result<f64, String>;
}

impl<T: ImpactScenePlan> Plannable for T {
    fn base(&self) -> (usize, usize) {
        ImpactScenePlan::base(self)
    }

    fn final_time(&self) -> f64 {
        ImpactScenePlan::final_time(self)
    }

    fn schemes(&self) -> Vec<T::Scheme> {
        ImpactScenePlan::schemes(self)
    }

    fn stability_bound(&self, _scheme: T::Scheme) -> Option<f64> {
        None
    }

    fn expected_orders(&self, _scheme: T::Scheme, _functional: &str) -> (Option<f64>, Option<f64>) {
        (None, None)
    }

    fn floor(&self, functional: &str, pilots: &[Level]) -> f64 {
        value_floor(functional, pilots)
    }

    fn seconds(&self, elements: usize, steps: usize, scheme: T::Scheme) -> Result<f64, String> {
        self.time_loop_seconds(elements, steps, scheme)
    }

    fn work(&self, elements: usize, steps: usize) -> f64 {
        self.refined().work(elements, steps)
    }

    fn work_label(&self) -> &'static str {
        "nodes·N"
    }

    fn run_seconds(&self, level: &Level) -> Option<f64> {
        Some(level.thread_seconds)
    }
}
