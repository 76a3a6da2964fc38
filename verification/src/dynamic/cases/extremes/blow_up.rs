//! `[[blow_up]]` of `dynamic_extremes`: the midpoint rule against Gonzalez's scheme on a
//! hyperelastic body with a large step. The midpoint rule evaluates F_int at u_{n−1/2}, whose
//! work over the step is not 𝒲(u_n) − 𝒲(u_{n−1}) for a nonlinear law, so (1.48) fails and the
//! energy can grow without bound (BDS §1.6; EM paper §4); Gonzalez's discrete gradient (BDS
//! (1.41)–(1.43)) makes Π^algo : (∇u_n − ∇u_{n−1}) = W̃(C_n) − W̃(C_{n−1}) exact, so the energy
//! is conserved to round-off without contact and the identities (1.48)/(1.49)/HLT 3.7 hold with
//! an energy-consistent contact force. The unstable scheme must show the blow-up (a least
//! relative energy error) as a solution or a typed error; the stable one must complete with the
//! balance drift at round-off.

use crate::core::context::RunContext;
use crate::core::gate::Check;
use crate::core::report::case_report::{CaseReport, Table};
use crate::dynamic::study::{plot_audits, AuditRun};

use super::common::{at_least, header, push_run_gate, run_one, set1, slug};
use super::BlowUpSpec;

pub(super) fn run_blow_up(
    index: usize,
    spec: &BlowUpSpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let study = format!("blow-up: {}", spec.name);
    let mut runs = Vec::new();
    for scheme in [spec.unstable, spec.stable] {
        runs.push(run_one(
            scheme.name(),
            &spec.scene,
            &set1("time.scheme", scheme.name()),
            &mut |_| {},
        )?);
    }
    let mut rows = Vec::new();
    for (i, run) in runs.iter().enumerate() {
        let drift = run.max_relative_drift();
        let (its, max_it) = run.newton();
        let mut checks = Vec::new();
        let expect;
        if i == 0 {
            expect = format!(
                "energy error ≥ {:.1e} (a solution or a typed error)",
                spec.min_energy_error
            );
            checks.push(at_least(
                &format!(
                    "{}: largest relative energy error max_n |drift_n| / (E + Φ)_0",
                    run.label
                ),
                drift,
                spec.min_energy_error,
            ));
        } else {
            expect = "a solution conserving energy to round-off".into();
            checks.push(Check::holds(
                &format!("{}: the run completes", run.label),
                run.completed(),
                "a solution",
            ));
            checks.extend(run.audit_checks());
            checks.push(Check::at_most(
                &format!(
                    "{}: largest relative balance drift over the run (limit C ε √N S / E_ref)",
                    run.label
                ),
                drift,
                run.summary_value(|s| s.tolerance()),
            ));
        }
        push_run_gate(report, &study, run, checks, &expect, &spec.note);
        let recs = run.records();
        let e0 = recs.first().map_or(f64::NAN, |r| r.energy() + r.penalty);
        let emax = recs
            .iter()
            .map(|r| r.energy() + r.penalty)
            .fold(f64::NEG_INFINITY, f64::max);
        rows.push(vec![
            run.label.clone(),
            run.outcome(),
            format!("{}", recs.len().saturating_sub(1)),
            format!("{:.3e}", run.k()),
            format!(
                "{:.2}",
                run.k() * run.scene.problem.body.wave_speed() / run.scene.problem.body.h_min()
            ),
            format!("{e0:.6e}"),
            format!("{:.6e}", emax),
            format!("{drift:.3e}"),
            format!("{:.2e}", run.summary_value(|s| s.max_drift_1_48)),
            format!("{its} / {max_it}"),
            format!("{}", run.backtracks()),
        ]);
    }
    report.tables.push(Table {
        title: format!("{study} ({})", runs[0].scene.problem.body.describe()),
        header: header(&[
            "scheme",
            "outcome",
            "steps done",
            "k",
            "k c / h_min",
            "(E + Φ)_0",
            "max (E + Φ)_n",
            "max |drift| / E_0",
            "max |R(1.48)| / E_ref",
            "Newton its (total / max)",
            "backtracks",
        ]),
        rows,
    });
    let audits: Vec<AuditRun<'_>> = runs
        .iter()
        .filter_map(|r| {
            r.run.as_ref().ok().map(|rec| AuditRun {
                label: r.label.clone(),
                audit: &rec.audit,
            })
        })
        .collect();
    plot_audits(
        ctx,
        report,
        &format!("blow_up_{index}_{}", slug(&spec.name)),
        &spec.name,
        &audits,
        None,
    )
}
