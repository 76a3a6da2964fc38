//! The choice: the cheapest (M, N, scheme) whose predicted error meets the target, inside what
//! the pilots support and below each scheme's stability bound (docs/planner.md §3).
//!
//! For each scheme with a valid model, h(M) = (h M)/M and k(N) = (k N)/N (the pilots' own
//! products: uniform or fixed-grading grids), the search runs over the integers
//! M ∈ [M_min, X · M_max] and N ∈ [N_min, X · N_max] of its pilots (X = [`EXTRAPOLATION`]) with
//! k(N) ≤ [`STABILITY_MARGIN`] × the scheme's bound; for each M the smallest N whose predicted
//! error is at most [`AIM`] × target (the error falls with N), priced by the cost model; the
//! cheapest over M and the schemes wins. The aim below the target leaves room for the model's
//! error, so the achieved error lands in [0.5, 1] × target; its price is (1/AIM)^(1/p + 1/q)
//! in work where the work is M·N (1.38 at p = q = 1), against a choice that met the target
//! exactly.

use serde::Serialize;

use crate::core::plan::model::ErrorModel;
use crate::stats::cost_model::CostModelFit;

/// The predicted error the choice aims at, as a fraction of the target.
pub const AIM: f64 = 0.85;
/// How far beyond its finest pilot (in M and in N) a scheme's model is trusted.
pub const EXTRAPOLATION: f64 = 4.0;
/// The largest step allowed, as a fraction of an explicit scheme's stability bound.
pub const STABILITY_MARGIN: f64 = 0.9;

/// One scheme's fitted models and the range its pilots cover.
#[derive(Debug, Clone)]
pub struct SchemeModels {
    pub scheme: String,
    pub error: ErrorModel,
    pub cost: CostModelFit,
    /// h·M and k·N of the pilots (h = hm / M, k = kn / N).
    pub hm: f64,
    pub kn: f64,
    /// The pilots' smallest and largest M and N.
    pub m_range: (usize, usize),
    pub n_range: (usize, usize),
    /// The largest stable step (explicit schemes), None where there is no bound.
    pub stability_bound: Option<f64>,
    /// (M, N) held inside the pilots' range: the model lacks the term in h (in k) the theory
    /// expects (a one-term fallback where that term was merely small over the pilots), so it
    /// says nothing about coarser or finer M (N).
    pub held: (bool, bool),
}

/// A candidate discretization with its predictions.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Choice {
    pub scheme: String,
    pub elements: usize,
    pub steps: usize,
    pub h: f64,
    pub k: f64,
    pub predicted_error: f64,
    pub predicted_cost: f64,
}

impl SchemeModels {
    fn at(&self, m: usize, n: usize) -> Choice {
        let (h, k) = (self.hm / m as f64, self.kn / n as f64);
        Choice {
            scheme: self.scheme.clone(),
            elements: m,
            steps: n,
            h,
            k,
            predicted_error: self.error.predict(h, k),
            predicted_cost: self.cost.predict(m as f64, n as f64),
        }
    }

    /// The smallest stable N.
    fn n_stable(&self) -> usize {
        match self.stability_bound {
            Some(b) if b > 0.0 => (self.kn / (STABILITY_MARGIN * b)).ceil().max(1.0) as usize,
            _ => 1,
        }
    }

    /// The cheapest (M, N) with predicted error ≤ `goal` for M ∈ [m_lo, m_hi], N ∈ [n_lo, n_hi].
    pub fn cheapest(
        &self,
        goal: f64,
        (m_lo, m_hi): (usize, usize),
        (n_lo, n_hi): (usize, usize),
    ) -> Option<Choice> {
        let n_lo = n_lo.max(self.n_stable());
        if n_lo > n_hi {
            return None;
        }
        let mut best: Option<Choice> = None;
        for m in m_lo..=m_hi {
            // the error falls with N: bisect for the smallest N meeting the goal
            if self.at(m, n_hi).predicted_error > goal {
                continue;
            }
            let (mut lo, mut hi) = (n_lo, n_hi);
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if self.at(m, mid).predicted_error <= goal {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            let c = self.at(m, lo);
            if best
                .as_ref()
                .is_none_or(|b| c.predicted_cost < b.predicted_cost)
            {
                best = Some(c);
            }
        }
        best
    }

    /// The search box the pilots support.
    pub fn supported(&self) -> ((usize, usize), (usize, usize)) {
        let x = |v: usize| ((v as f64) * EXTRAPOLATION).round() as usize;
        let range = |(lo, hi): (usize, usize), held: bool| (lo, if held { hi } else { x(hi) });
        (
            range(self.m_range, self.held.0),
            range(self.n_range, self.held.1),
        )
    }
}

/// The cheapest choice over every scheme for the goal `AIM · target`, inside what each scheme's
/// pilots support (ties keep the earlier scheme).
pub fn choose(models: &[SchemeModels], target: f64) -> Option<Choice> {
    let mut best: Option<Choice> = None;
    for s in models {
        let (mr, nr) = s.supported();
        if let Some(c) = s.cheapest(AIM * target, mr, nr) {
            if best
                .as_ref()
                .is_none_or(|b| c.predicted_cost < b.predicted_cost)
            {
                best = Some(c);
            }
        }
    }
    best
}

/// Where the models say the target would be met without the pilots' limits (M and N from 1/16
/// of the coarsest to 1000 times the finest pilot, a held parameter within its pilots' range):
/// where the next round of pilots should be.
pub fn unsupported(models: &[SchemeModels], target: f64) -> Option<Choice> {
    let mut best: Option<Choice> = None;
    for s in models {
        // a held parameter stays inside the pilots' range (`SchemeModels::held`)
        let range = |(lo, hi): (usize, usize), held: bool| {
            if held {
                (lo, hi)
            } else {
                ((lo / 16).max(1), hi.saturating_mul(1000))
            }
        };
        let (m_lo, m_hi) = range(s.m_range, s.held.0);
        let n_box = range(s.n_range, s.held.1);
        // geometric M, then bisection in N
        let mut m = m_lo;
        while m <= m_hi {
            if let Some(c) = s.cheapest(AIM * target, (m, m), n_box) {
                if best
                    .as_ref()
                    .is_none_or(|b| c.predicted_cost < b.predicted_cost)
                {
                    best = Some(c);
                }
            }
            m = ((m as f64) * 1.05).ceil() as usize;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::error_model::{Combination, ErrorModelFit};

    fn models(c_h: f64, c_k: f64, bound: Option<f64>) -> SchemeModels {
        SchemeModels {
            scheme: "s".into(),
            error: ErrorModel::Joint(ErrorModelFit {
                combination: Combination::Quadrature,
                p: 1.0,
                p_ci: (1.0, 1.0),
                q: 1.0,
                q_ci: (1.0, 1.0),
                c_h,
                c_k,
                confidence: 0.95,
                points_used: 9,
                residual_std: 0.0,
                iterations: 0,
            }),
            cost: CostModelFit {
                log_constant: 0.0,
                a: 1.0,
                a_ci: (1.0, 1.0),
                b: 1.0,
                b_ci: (1.0, 1.0),
                confidence: 0.95,
                points_used: 9,
                residual_std: 0.0,
            },
            hm: 1.0,
            kn: 1.0,
            m_range: (4, 16),
            n_range: (4, 16),
            stability_bound: bound,
            held: (false, false),
        }
    }

    /// Exhaustive search over the same box: the bisection must find the same optimum.
    fn brute(s: &SchemeModels, goal: f64) -> Option<Choice> {
        let ((m0, m1), (n0, n1)) = s.supported();
        let mut best: Option<Choice> = None;
        for m in m0..=m1 {
            for n in n0.max(s.n_stable())..=n1 {
                let c = s.at(m, n);
                if c.predicted_error <= goal
                    && best
                        .as_ref()
                        .is_none_or(|b| c.predicted_cost < b.predicted_cost)
                {
                    best = Some(c);
                }
            }
        }
        best
    }

    #[test]
    fn the_choice_equals_an_exhaustive_search_and_meets_the_aim() {
        for (c_h, c_k) in [(1.0, 1.0), (4.0, 0.5), (0.2, 3.0)] {
            let s = models(c_h, c_k, None);
            for target in [0.5, 0.2, 0.1, 0.05] {
                let c = choose(std::slice::from_ref(&s), target);
                let b = brute(&s, AIM * target);
                assert_eq!(
                    c.as_ref().map(|x| x.predicted_cost),
                    b.as_ref().map(|x| x.predicted_cost)
                );
                if let Some(c) = c {
                    assert!(c.predicted_error <= AIM * target);
                }
            }
        }
    }

    #[test]
    fn the_step_never_exceeds_the_stability_margin() {
        // a cheap-in-N model that would like large steps
        let s = models(1.0, 0.01, Some(0.2));
        let c = choose(std::slice::from_ref(&s), 0.2).unwrap();
        assert!(c.k <= STABILITY_MARGIN * 0.2 + 1e-15, "{c:?}");
        assert_eq!(c.steps, (1.0 / (STABILITY_MARGIN * 0.2)).ceil() as usize);
    }

    #[test]
    fn a_target_beyond_the_pilots_is_not_chosen_but_located() {
        let s = models(1.0, 1.0, None);
        // M, N ≤ 64: the smallest reachable error is √2/64 ≈ 0.022
        assert!(choose(std::slice::from_ref(&s), 0.01).is_none());
        let far = unsupported(std::slice::from_ref(&s), 0.01).unwrap();
        assert!(
            far.elements > 64 && far.predicted_error <= AIM * 0.01,
            "{far:?}"
        );
    }

    #[test]
    fn a_held_parameter_stays_inside_the_pilots_range_even_where_the_model_is_blind_to_it() {
        // a time-only law (the space term lost in the fit): coarser meshes look free to it
        let mut s = models(0.0, 1.0, None);
        s.error = ErrorModel::TimeOnly {
            c: 1.0,
            q: 1.0,
            residual_std: 0.0,
        };
        let free = unsupported(std::slice::from_ref(&s), 0.01).unwrap();
        assert_eq!(free.elements, 1, "{free:?}");
        s.held = (true, false);
        let held = unsupported(std::slice::from_ref(&s), 0.01).unwrap();
        assert_eq!(held.elements, s.m_range.0, "{held:?}");
        let chosen = choose(std::slice::from_ref(&s), 0.1).unwrap();
        assert!((4..=16).contains(&chosen.elements), "{chosen:?}");
    }
}
