//! The planner on the dynamic manufactured problem (`core::plan`; docs/planner.md §4): the
//! smooth field of `manufactured/dynamic_plane.rs` on n × n squares (M = n) with N uniform
//! steps, in persistent compliance contact, its errors at T against the exact solution. The
//! "schemes" a plan chooses among are the combinations of an integrator with a contact force
//! that `dynamic_manufactured` verifies; all are implicit (no step bound).

use std::fmt;

use serde::{Deserialize, Serialize};

use contactlab::model::dynamic::bar::MassMatrix;
use contactlab::model::dynamic::scheme::DynamicScheme;

use crate::core::plan::Plannable;
use crate::core::study::Study;
use crate::core::sweep::{Level, Measured};
use crate::dynamic::cases::manufactured::format::{Combination, ContactForce};
use crate::dynamic::cases::manufactured::runs::solve;
use crate::manufactured::dynamic_plane::DynamicManufactured;

/// A scheme with its contact force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PlanCombination {
    /// The midpoint rule with the energy-consistent force: second order in k.
    #[default]
    MidpointEnergyConsistent,
    /// The midpoint rule with the penalty force at t_n: first order in k.
    MidpointPenalty,
    /// Newmark's trapezoidal rule with the penalty force: second order in k.
    NewmarkPenalty,
}

impl PlanCombination {
    pub const ALL: [PlanCombination; 3] = [
        Self::MidpointEnergyConsistent,
        Self::MidpointPenalty,
        Self::NewmarkPenalty,
    ];

    fn combination(self) -> Combination {
        let (scheme, treatment) = match self {
            Self::MidpointEnergyConsistent => {
                (DynamicScheme::Midpoint, ContactForce::EnergyConsistent)
            }
            Self::MidpointPenalty => (DynamicScheme::Midpoint, ContactForce::Penalty),
            Self::NewmarkPenalty => (DynamicScheme::Newmark, ContactForce::Penalty),
        };
        Combination {
            scheme,
            treatment,
            full_path: false,
        }
    }

    /// The order in k at T (`dynamic_manufactured_linear`: 2.000, 0.999, 2.000).
    fn time_order(self) -> f64 {
        match self {
            Self::MidpointPenalty => 1.0,
            _ => 2.0,
        }
    }
}

impl fmt::Display for PlanCombination {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::MidpointEnergyConsistent => "midpoint+energy_consistent",
            Self::MidpointPenalty => "midpoint+penalty",
            Self::NewmarkPenalty => "newmark+penalty",
        })
    }
}

/// The dynamic manufactured problem with the resolution of its first pilot round.
pub struct DynamicPlan {
    pub exact: DynamicManufactured,
    pub base: (usize, usize),
}

impl Study for DynamicPlan {
    type Scheme = PlanCombination;

    fn default_scheme(&self) -> PlanCombination {
        PlanCombination::default()
    }

    /// One run on n × n squares with N steps (consistent mass): `l2_final` = ‖u_N − u(T)‖ and
    /// `energy_final` = ‖ε(u_N − u(T))‖.
    fn run_level(
        &self,
        elements: usize,
        steps: usize,
        scheme: PlanCombination,
        _time_error: bool,
    ) -> Result<Level, String> {
        Level::timed(elements, steps, scheme, || {
            let r = solve(
                &self.exact,
                MassMatrix::Consistent,
                elements,
                steps,
                scheme.combination(),
            )?;
            let mut errors = std::collections::BTreeMap::new();
            errors.insert("l2_final".to_string(), r.errors.l2);
            errors.insert("energy_final".to_string(), r.errors.energy);
            Ok::<_, String>(Measured {
                h: std::f64::consts::SQRT_2 / elements as f64,
                k: self.exact.final_time / steps as f64,
                errors,
                u_end: self.scale(),
                stats: r.stats,
            })
        })
    }
}

impl DynamicPlan {
    /// max |u(x, T)| of the exact field over a 9 × 9 grid of the unit square.
    fn scale(&self) -> f64 {
        let nodes: Vec<[f64; 2]> = (0..81)
            .map(|i| [(i % 9) as f64 / 8.0, (i / 9) as f64 / 8.0])
            .collect();
        self.exact
            .nodal(&nodes, self.exact.final_time, false)
            .iter()
            .fold(0.0, |m, v| m.max(v.abs()))
    }
}

impl Plannable for DynamicPlan {
    fn base(&self) -> (usize, usize) {
        self.base
    }

    fn final_time(&self) -> f64 {
        self.exact.final_time
    }

    fn schemes(&self) -> Vec<PlanCombination> {
        PlanCombination::ALL.to_vec()
    }

    fn stability_bound(&self, _scheme: PlanCombination) -> Option<f64> {
        None
    }

    /// P1: the L² error at T second order in h, the energy error first order; in k the
    /// combination's order ([`PlanCombination`]).
    fn expected_orders(
        &self,
        scheme: PlanCombination,
        functional: &str,
    ) -> (Option<f64>, Option<f64>) {
        match functional {
            "l2_final" => (Some(2.0), Some(scheme.time_order())),
            "energy_final" => (Some(1.0), Some(scheme.time_order())),
            _ => (None, None),
        }
    }

    fn seconds(
        &self,
        elements: usize,
        steps: usize,
        scheme: PlanCombination,
    ) -> Result<f64, String> {
        crate::core::cpu_clock::min_thread_cpu_seconds(3, || {
            solve(
                &self.exact,
                MassMatrix::Consistent,
                elements,
                steps,
                scheme.combination(),
            )
            .map(|_| ())
        })
    }

    /// n²·N: each step solves on the (condensed) linear system of the n² nodes.
    fn work(&self, elements: usize, steps: usize) -> f64 {
        (elements as f64).powi(2) * steps as f64
    }

    fn work_label(&self) -> &'static str {
        "n²·N"
    }

    /// 100 ε max |u(T)|.
    fn floor(&self, _functional: &str, _pilots: &[Level]) -> f64 {
        100.0 * f64::EPSILON * self.scale().max(f64::MIN_POSITIVE)
    }
}
