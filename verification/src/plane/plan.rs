//! The planner on a plane manufactured problem (`core::plan`): n × n squares of the unit square
//! (M = n) and N uniform steps, the errors against the manufactured solution, the explicit
//! scheme's bound k < 2 / max(b₂/a₂, (2b₁ + b₂)/(2a₁ + a₂)) (docs/quasistatic.md, stability note:
//! an upper bound of λ_max(K_A⁻¹K_B) on every mesh).

use contactlab::model::quasistatic::plane_stability::constitutive_ratio;
use contactlab::model::quasistatic::plane_step::PlaneStep;
use contactlab::model::quasistatic::scheme::TimeScheme;

use crate::core::cpu_clock::min_thread_cpu_seconds;
use crate::core::plan::{Based, Plannable};
use crate::core::sweep::Level;
use crate::plane::study::PlaneStudy;

/// A plane manufactured study with the resolution of its first pilot round.
pub type PlanePlan = Based<PlaneStudy>;

impl Plannable for PlanePlan {
    fn base(&self) -> (usize, usize) {
        self.base
    }

    fn final_time(&self) -> f64 {
        self.study.exact.final_time
    }

    fn schemes(&self) -> Vec<TimeScheme> {
        TimeScheme::ALL.to_vec()
    }

    /// 2 / the constitutive ratio of linear A and B. For a nonlinear law no bound is known: the
    /// bound 0 leaves every explicit pilot out, so the plan uses the implicit schemes.
    fn stability_bound(&self, scheme: TimeScheme) -> Option<f64> {
        if scheme != TimeScheme::Explicit {
            return None;
        }
        let a = self.study.exact.viscosity.solver_law();
        let b = self.study.exact.elasticity.solver_law();
        match (a.as_linear(), b.as_linear()) {
            (Some(a), Some(b)) => Some(2.0 / constitutive_ratio(a, b)),
            // no bound is known: an explicit step of any size is refused
            _ => Some(0.0),
        }
    }

    /// P1 elements: the energy-norm errors (`paper_E`, `energy_final`) are first order in h, the
    /// L² error at T second order; in k, first order for θ = 0, 1 and second order for the
    /// midpoint scheme at T — except `paper_E`, which carries the velocity at t_n (first order
    /// for every scheme, as on the rod).
    fn expected_orders(&self, scheme: TimeScheme, functional: &str) -> (Option<f64>, Option<f64>) {
        let q_final = if scheme == TimeScheme::Midpoint {
            2.0
        } else {
            1.0
        };
        match functional {
            "paper_E" => (Some(1.0), Some(1.0)),
            "energy_final" => (Some(1.0), Some(q_final)),
            "l2_final" => (Some(2.0), Some(q_final)),
            _ => (None, None),
        }
    }

    /// CPU seconds of the solver's construction (the factorization of A + θkB) and its run, min
    /// of 3.
    fn seconds(&self, elements: usize, steps: usize, scheme: TimeScheme) -> Result<f64, String> {
        min_thread_cpu_seconds(3, || {
            let mut solver = self.study.solver(elements, steps, scheme)?;
            let mut sink = 0.0;
            solver
                .run(&mut |s: &PlaneStep<'_>| sink += s.u.first().copied().unwrap_or(0.0))
                .map_err(|e| e.to_string())?;
            std::hint::black_box(sink);
            Ok(())
        })
    }

    /// n²·N: each step of the condensed linear path is a solve with the factors of A + θkB
    /// (≈ n² log n) and the contact on the n boundary nodes.
    fn work(&self, elements: usize, steps: usize) -> f64 {
        (elements as f64).powi(2) * steps as f64
    }

    fn work_label(&self) -> &'static str {
        "n²·N"
    }

    /// 100 ε times the largest nodal |u_N| of the pilots.
    fn floor(&self, _functional: &str, pilots: &[Level]) -> f64 {
        let scale = pilots.iter().map(|l| l.u_end.abs()).fold(0.0, f64::max);
        100.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE)
    }
}
