//! The audit's own evidence: a second implementation of the run summary, written here from its
//! definition (docs/multibody.md §8), and the injected-defect controls.
//!
//! Every audit gate reads "ratio ≤ 1". A summary whose tolerance is looser than the round-off it
//! claims, or whose ratio is computed wrongly, passes every correct run — only a run with a known
//! defect tells it apart. The controls take the records of a real run (its ratios ρ ≤ 1) and add
//! to its last step a defect of exactly `f` tolerances in one audited quantity — the energy
//! identity's residual, the energy of a step without a set change, P_x, P_y, J, the friction work
//! of a step — the tolerance computed here from the definition. The summary must flag it: its
//! ratio is then f ± ρ (|x + δ| lies within |x| of δ), every other quantity unchanged. Each
//! summary (of the clean and of every defective record set) must also equal this module's to
//! 1e-12 relative, field by field.
//!
//! The definition (per step n ≥ 1, record 0 the initial state; C = 2, the round-off constant):
//! - identity: |Σ_{j=1..n} r_j| over C ε Σ_{j=0..n} s_j + Σ_{j=1..n} ν_j;
//! - a step without a set change: |E_n − E_{n−1} − W_ext − W_T| over C ε s_n + ν_n + the holding
//!   constraints' gap work;
//! - friction: the step's W_T over C ε s_n + ν_n (≤ 1: friction only dissipates);
//! - P (each component) and J: |P_n − P_0| over C ε (S_0 + S_n + Σ_{j=1..n} ρ_j) + Σ_{j=1..n} μ_j,
//!   S the round-off scale Σ|(Mv)_I| (resp. Σ|x_I||(Mv)_I|), ρ_j the step impulse's round-off
//!   scale, μ_j the Newton residual's impulse.

use contactlab::model::multibody::audit::{MultibodyRecord, MultibodySummary};

use crate::core::gate::Check;
use crate::core::report::case_report::Table;

/// C of the round-off tolerance C ε Σ s (docs/multibody.md §8).
const C: f64 = 2.0;

/// Relative agreement required between the library's summary and this one (the same sums in the
/// same order give the same bits; the slack allows a reordering of the arithmetic).
pub const AGREEMENT: f64 = 1e-12;

fn tiny() -> f64 {
    f64::MIN_POSITIVE
}

/// Running sums s_k = Σ_{j=1..k} f(record j), k = 1..N.
fn running(steps: &[MultibodyRecord], f: impl Fn(&MultibodyRecord) -> f64) -> Vec<f64> {
    steps
        .iter()
        .scan(0.0, |acc, r| {
            *acc += f(r);
            Some(*acc)
        })
        .collect()
}

fn max_of(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, f64::max)
}

/// The tolerances of step n (1 ≤ n ≤ N) as the definition states them.
#[derive(Debug, Clone, Copy)]
pub struct StepTolerances {
    pub identity: f64,
    pub step: f64,
    pub unchanged: f64,
    pub momentum: f64,
    pub angular: f64,
}

/// The tolerances of every step n = 1..N (index n − 1).
pub fn tolerances(records: &[MultibodyRecord]) -> Vec<StepTolerances> {
    let Some((first, steps)) = records.split_first() else {
        return Vec::new();
    };
    let eps = C * f64::EPSILON;
    let scale = running(steps, |r| r.identity_scale);
    let newton = running(steps, |r| r.newton_bound);
    let p_round = running(steps, |r| r.momentum_round_off);
    let p_newton = running(steps, |r| r.momentum_bound);
    let j_round = running(steps, |r| r.angular_round_off);
    let j_newton = running(steps, |r| r.angular_bound);
    steps
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let step = (eps * r.identity_scale + r.newton_bound).max(tiny());
            StepTolerances {
                identity: (eps * (first.identity_scale + scale[i]) + newton[i]).max(tiny()),
                step,
                unchanged: step + r.holding_gap_work,
                momentum: (eps * (first.momentum_scale + r.momentum_scale + p_round[i])
                    + p_newton[i])
                    .max(tiny()),
                angular: (eps * (first.angular_scale + r.angular_scale + j_round[i]) + j_newton[i])
                    .max(tiny()),
            }
        })
        .collect()
}

/// The summary of `records` from the definition (module docs).
pub fn reference_summary(records: &[MultibodyRecord]) -> MultibodySummary {
    let Some((first, steps)) = records.split_first() else {
        return MultibodySummary::default();
    };
    let tol = tolerances(records);
    let e0 = first.energy.abs().max(tiny());
    let drift = running(steps, |r| r.identity_residual);
    let unchanged_steps = || {
        steps
            .iter()
            .enumerate()
            .filter(|(_, r)| r.activated == 0 && r.released == 0 && r.switches == 0)
    };
    let energy_change = |i: usize| {
        let previous = if i == 0 { first } else { &steps[i - 1] };
        let r = &steps[i];
        (r.energy - previous.energy - r.external_work - r.friction_work).abs()
    };
    let dp = |r: &MultibodyRecord, c: usize| (r.momentum[c] - first.momentum[c]).abs();
    let dj = |r: &MultibodyRecord| (r.angular_momentum - first.angular_momentum).abs();
    let activation_work: f64 = steps.iter().map(|r| r.activation_work).sum();
    let friction_ratio = steps
        .iter()
        .zip(&tol)
        .map(|(r, t)| r.friction_work / t.step)
        .fold(f64::NEG_INFINITY, f64::max);
    let ratio_x = max_of(steps.iter().zip(&tol).map(|(r, t)| dp(r, 0) / t.momentum));
    let ratio_y = max_of(steps.iter().zip(&tol).map(|(r, t)| dp(r, 1) / t.momentum));
    MultibodySummary {
        steps: steps.len(),
        energy_drift: max_of(steps.iter().map(|r| (r.energy - first.energy).abs() / e0)),
        identity_ratio: max_of(drift.iter().zip(&tol).map(|(d, t)| d.abs() / t.identity)),
        unchanged_ratio: max_of(
            unchanged_steps().map(|(i, _)| energy_change(i) / tol[i].unchanged),
        ),
        unchanged_relative: max_of(unchanged_steps().map(|(i, _)| energy_change(i) / e0)),
        activation_work,
        activation_relative: activation_work.abs() / e0,
        friction_work: steps.iter().map(|r| r.friction_work).sum(),
        friction_ratio: if steps.is_empty() {
            0.0
        } else {
            friction_ratio
        },
        momentum_ratio: ratio_x.max(ratio_y),
        momentum_ratio_x: ratio_x,
        momentum_ratio_y: ratio_y,
        angular_ratio: max_of(steps.iter().zip(&tol).map(|(r, t)| dj(r) / t.angular)),
        momentum_relative: max_of(steps.iter().map(|r| {
            dp(r, 0).max(dp(r, 1)) / first.momentum_scale.max(r.momentum_scale).max(tiny())
        })),
        angular_relative: max_of(
            steps
                .iter()
                .map(|r| dj(r) / first.angular_scale.max(r.angular_scale).max(tiny())),
        ),
        max_newton_iterations: steps.iter().map(|r| r.newton_iterations).max().unwrap_or(0),
        steps_with_contact: steps.iter().filter(|r| r.active > 0).count(),
        steps_with_set_change: steps.len() - unchanged_steps().count(),
        positive_set_work_relative: steps
            .iter()
            .zip(&tol)
            .filter(|(r, t)| r.positive_set_work > t.step)
            .map(|(r, _)| r.positive_set_work)
            .sum::<f64>()
            / e0,
        positive_set_work_steps: steps
            .iter()
            .zip(&tol)
            .filter(|(r, t)| r.positive_set_work > t.step)
            .count(),
        energy_rise_ratio: energy_rise_ratio(first, steps),
        final_energy_ratio: steps.last().map_or(first.energy, |r| r.energy) / e0,
    }
}

/// max_n (E_n − E_0 − Σ_{j≤n} (W_ext + W_T)_j) / (C ε (s_0 + Σ_{j≤n} (s_j + |W_ext| + |W_T| +
/// |E_j|)) + Σ_{j≤n} (ν_j + the holding constraints' gap work)): the energy's rise over the
/// work supplied, in its tolerances (0 when it never rose).
fn energy_rise_ratio(first: &MultibodyRecord, steps: &[MultibodyRecord]) -> f64 {
    let supplied = running(steps, |r| r.external_work + r.friction_work);
    let scale = running(steps, |r| {
        r.identity_scale + r.external_work.abs() + r.friction_work.abs() + r.energy.abs()
    });
    let newton = running(steps, |r| r.newton_bound + r.holding_gap_work);
    let ratios = steps.iter().enumerate().map(|(i, r)| {
        let rise = r.energy - first.energy - supplied[i];
        let tol = C * f64::EPSILON * (first.identity_scale + scale[i]) + newton[i];
        rise / tol.max(tiny())
    });
    ratios.fold(0.0, f64::max)
}

/// Every field of a summary, named.
fn fields(s: &MultibodySummary) -> [(&'static str, f64); 22] {
    [
        ("steps", s.steps as f64),
        ("energy_drift", s.energy_drift),
        ("identity_ratio", s.identity_ratio),
        ("unchanged_ratio", s.unchanged_ratio),
        ("unchanged_relative", s.unchanged_relative),
        ("activation_work", s.activation_work),
        ("activation_relative", s.activation_relative),
        ("friction_work", s.friction_work),
        ("friction_ratio", s.friction_ratio),
        ("momentum_ratio", s.momentum_ratio),
        ("momentum_ratio_x", s.momentum_ratio_x),
        ("momentum_ratio_y", s.momentum_ratio_y),
        ("angular_ratio", s.angular_ratio),
        ("momentum_relative", s.momentum_relative),
        ("angular_relative", s.angular_relative),
        ("max_newton_iterations", s.max_newton_iterations as f64),
        ("steps_with_contact", s.steps_with_contact as f64),
        ("steps_with_set_change", s.steps_with_set_change as f64),
        ("positive_set_work_relative", s.positive_set_work_relative),
        ("positive_set_work_steps", s.positive_set_work_steps as f64),
        ("energy_rise_ratio", s.energy_rise_ratio),
        ("final_energy_ratio", s.final_energy_ratio),
    ]
}

/// The largest relative difference between two summaries over their fields, with its field.
pub fn disagreement(a: &MultibodySummary, b: &MultibodySummary) -> (f64, &'static str) {
    fields(a)
        .iter()
        .zip(fields(b).iter())
        .map(|(&(name, x), &(_, y))| {
            let d = (x - y).abs() / x.abs().max(y.abs()).max(tiny());
            (if d.is_nan() { f64::INFINITY } else { d }, name)
        })
        .fold((0.0, "—"), |m, v| if v.0 > m.0 { v } else { m })
}

/// An audited quantity that a control perturbs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Defect {
    Identity,
    Unchanged,
    MomentumX,
    MomentumY,
    Angular,
    Friction,
}

impl Defect {
    const ALL: [Defect; 6] = [
        Defect::Identity,
        Defect::Unchanged,
        Defect::MomentumX,
        Defect::MomentumY,
        Defect::Angular,
        Defect::Friction,
    ];

    fn name(self) -> &'static str {
        match self {
            Defect::Identity => "energy identity residual",
            Defect::Unchanged => "energy of a step without a set change",
            Defect::MomentumX => "P_x",
            Defect::MomentumY => "P_y",
            Defect::Angular => "J",
            Defect::Friction => "friction work of a step",
        }
    }

    fn ratio(self, s: &MultibodySummary) -> f64 {
        match self {
            Defect::Identity => s.identity_ratio,
            Defect::Unchanged => s.unchanged_ratio,
            Defect::MomentumX => s.momentum_ratio_x,
            Defect::MomentumY => s.momentum_ratio_y,
            Defect::Angular => s.angular_ratio,
            Defect::Friction => s.friction_ratio,
        }
    }

    /// The audited field of the last record and its tolerance.
    fn field<'a>(self, last: &'a mut MultibodyRecord, t: &StepTolerances) -> (&'a mut f64, f64) {
        match self {
            Defect::Identity => (&mut last.identity_residual, t.identity),
            Defect::Unchanged => (&mut last.energy, t.unchanged),
            Defect::MomentumX => (&mut last.momentum[0], t.momentum),
            Defect::MomentumY => (&mut last.momentum[1], t.momentum),
            Defect::Angular => (&mut last.angular_momentum, t.angular),
            Defect::Friction => (&mut last.friction_work, t.step),
        }
    }

    /// Adds `f` tolerances of this quantity to the last record. Returns the defect as stored, in
    /// tolerances (the sum x + δ is rounded to x's precision: ε|x|/2 can be a fraction of the
    /// tolerance; the stored δ = (x + δ) − x is exact, Sterbenz), and the clean value's own ratio
    /// at that step, |x|/tol (the part of the flagged ratio that is not the defect).
    fn inject(self, records: &mut [MultibodyRecord], f: f64) -> (f64, f64) {
        let tol = tolerances(records);
        let (Some(t), Some(first)) = (tol.last().copied(), records.first().copied()) else {
            return (0.0, 0.0);
        };
        let n = records.len() - 1;
        let drift: f64 = records[1..].iter().map(|r| r.identity_residual).sum();
        let previous = records[n - 1];
        let last = &mut records[n];
        let own = match self {
            Defect::Identity => drift.abs(),
            Defect::Unchanged => {
                (last.energy - previous.energy - last.external_work - last.friction_work).abs()
            }
            Defect::MomentumX => (last.momentum[0] - first.momentum[0]).abs(),
            Defect::MomentumY => (last.momentum[1] - first.momentum[1]).abs(),
            Defect::Angular => (last.angular_momentum - first.angular_momentum).abs(),
            Defect::Friction => last.friction_work.abs(),
        };
        let (x, tolerance) = self.field(last, &t);
        let before = *x;
        *x += f * tolerance;
        ((*x - before) / tolerance, own / tolerance)
    }
}

/// The controls on a run's records (at least two records; its last step without a change of the
/// active set): the summary against the reference, clean and with each defect of `f` tolerances,
/// and each defect flagged (ratio > 1) with its ratio f ± ρ (ρ the clean step's own ratio; at most
/// the clean run's ratio where that is larger). Returns the checks and the table of the defects (None when the records do not allow them).
pub fn audit_controls(
    label: &str,
    records: &[MultibodyRecord],
    summarize: impl Fn(&[MultibodyRecord]) -> MultibodySummary,
    f: f64,
) -> (Vec<Check>, Option<Table>) {
    let mut checks = Vec::new();
    let mut rows = Vec::new();
    let n = records.len();
    let last_unchanged = records
        .last()
        .is_some_and(|r| r.activated + r.released + r.switches == 0);
    checks.push(Check::holds(
        &format!("{label}: ≥ 1 step, the last without a change of the active set"),
        n >= 2 && last_unchanged,
        "holds",
    ));
    if n < 2 || !last_unchanged {
        return (checks, None);
    }
    let clean = summarize(records);
    let (d, field) = disagreement(&clean, &reference_summary(records));
    checks.push(Check::at_most(
        &format!(
            "{label}: the summary against the definition, largest relative difference ({field})"
        ),
        d,
        AGREEMENT,
    ));
    for defect in Defect::ALL {
        let mut defective = records.to_vec();
        let (stored, own) = defect.inject(&mut defective, f);
        let s = summarize(&defective);
        let (d, field) = disagreement(&s, &reference_summary(&defective));
        checks.push(Check::at_most(
            &format!(
                "{label}, {f} tolerances added to the last step's {}: the summary against the definition ({field})",
                defect.name()
            ),
            d,
            AGREEMENT,
        ));
        let observed = defect.ratio(&s);
        let clean_ratio = defect.ratio(&clean);
        // the defective step's ratio is δ ± own; the other steps keep their clean ratios
        let (low, high) = (stored - own, (stored + own).max(clean_ratio));
        let slack = AGREEMENT * high;
        checks.push(Check {
            name: format!(
                "{label}: a defect of {stored:.4} tolerances (stored) in the {} is flagged (ratio in [δ − ρ, δ + ρ], ρ the clean step's own ratio {own:.3e})",
                defect.name()
            ),
            observed,
            limit: format!("in [{}, {}]", low - slack, high + slack),
            passed: observed >= low - slack && observed <= high + slack && observed > 1.0,
        });
        rows.push(vec![
            defect.name().to_string(),
            format!("{clean_ratio:.3e}"),
            format!("{own:.3e}"),
            format!("{stored:.6}"),
            format!("{observed:.6}"),
            format!("{d:.1e}"),
        ]);
    }
    let table = Table {
        title: format!(
            "The audit's injected-defect controls on {label}: each quantity's last step given a defect of {f} tolerances"
        ),
        header: [
            "quantity",
            "clean run's ratio",
            "last step's own ratio ρ",
            "defect stored δ (tolerances)",
            "ratio with the defect",
            "summary vs definition (rel.)",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    };
    (checks, Some(table))
}

#[cfg(test)]
mod tests {
    use super::*;
    use contactlab::model::multibody::audit::summarize;

    fn record(step: usize) -> MultibodyRecord {
        let t = step as f64;
        MultibodyRecord {
            step,
            time: t,
            energy: 1.0 + 1e-17 * t,
            momentum: [0.5 + 1e-18 * t, -0.25],
            angular_momentum: 2.0 - 1e-18 * t,
            identity_residual: 1e-18 * (-1.0f64).powi(step as i32),
            identity_scale: 3.0,
            newton_bound: 1e-17,
            momentum_scale: 1.5,
            angular_scale: 4.0,
            momentum_round_off: 0.1,
            angular_round_off: 0.2,
            momentum_bound: 1e-18,
            angular_bound: 2e-18,
            friction_work: if (2..=3).contains(&step) { -1e-6 } else { 0.0 },
            activation_work: if step == 2 { -1e-3 } else { 0.0 },
            activated: usize::from(step == 2),
            released: usize::from(step == 4),
            active: usize::from((2..=3).contains(&step)),
            newton_iterations: step % 3,
            ..Default::default()
        }
    }

    #[test]
    fn reference_summary_equals_the_library_summary_on_synthetic_records() {
        let records: Vec<_> = (0..6).map(record).collect();
        let (d, field) = disagreement(&summarize(&records), &reference_summary(&records));
        assert!(d <= AGREEMENT, "{field}: {d}");
    }

    #[test]
    fn every_injected_defect_is_flagged_at_its_size() {
        let records: Vec<_> = (0..6).map(record).collect();
        let (checks, table) = audit_controls("synthetic", &records, summarize, 4.0);
        assert_eq!(table.map(|t| t.rows.len()), Some(6));
        for c in &checks {
            assert!(c.passed, "{}: {} {}", c.name, c.observed, c.limit);
        }
    }

    #[test]
    fn a_summary_with_a_loosened_tolerance_fails_the_controls() {
        let records: Vec<_> = (0..6).map(record).collect();
        let loose = |r: &[MultibodyRecord]| {
            let mut s = summarize(r);
            s.momentum_ratio_y /= 10.0;
            s
        };
        let (checks, _) = audit_controls("synthetic", &records, loose, 4.0);
        assert!(checks.iter().any(|c| !c.passed));
    }
}
