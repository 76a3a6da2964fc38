//! `[[speed]]` of `dynamic_extremes`: impact speeds over decades. Every run must complete with
//! the identities (1.48)/(1.49) at round-off (BDS); over the speeds, the trends of penetration
//! and contact time: exact homogeneity (a linear body with zero initial gap: u scales with v),
//! wave theory for a bar (contact time 2L/c, rebound at v, mean contact force ρ c A v),
//! Hertz-like stiffening for a curved body (sublinear penetration, non-increasing contact time).

use contactlab::scene::dynamic::{DynamicScene, SceneBody};

use crate::core::context::RunContext;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use crate::plot::{Figure, Series};

use super::common::{header, push_run_gate, run_one, set1, slope_line, slug};
use super::SpeedSpec;

fn velocity_value(direction: &[f64], v: f64) -> toml::Value {
    if direction.len() == 1 {
        toml::Value::Float(v * direction[0])
    } else {
        toml::Value::Array(
            direction
                .iter()
                .map(|d| toml::Value::Float(v * d))
                .collect(),
        )
    }
}

/// The rigid translation along `direction` as a free-dof vector.
fn translation(scene: &DynamicScene, direction: &[f64]) -> Vec<f64> {
    match &scene.body {
        SceneBody::Bar(b) => b.from_nodal(&vec![direction[0]; b.data().mesh.nodes().len()]),
        SceneBody::Plane(p) => {
            let nodes = p.data().mesh.nodes().len();
            let d = [direction[0], *direction.get(1).unwrap_or(&0.0)];
            p.from_nodal(&(0..2 * nodes).map(|i| d[i % 2]).collect::<Vec<_>>())
        }
    }
}

/// The rigid-body velocity of `v` along the translation `e`: eᵀ M v / eᵀ M e.
fn rigid_velocity(scene: &DynamicScene, e: &[f64], v: &[f64]) -> f64 {
    let body = &scene.problem.body;
    let mut me = vec![0.0; e.len()];
    body.pattern().symmetric_mul(body.mass(), e, &mut me);
    let num: f64 = me.iter().zip(v).map(|(a, b)| a * b).sum();
    let den: f64 = me.iter().zip(e).map(|(a, b)| a * b).sum();
    num / den
}

pub(super) fn run_speed(
    index: usize,
    spec: &SpeedSpec,
    ctx: &RunContext,
    report: &mut CaseReport,
) -> Result<(), String> {
    let study = format!("speed: {}", spec.name);
    let mut runs = Vec::new();
    for &v in &spec.speeds {
        runs.push(run_one(
            &format!("v = {v} m/s"),
            &spec.scene,
            &set1("initial.velocity", velocity_value(&spec.direction, v)),
            &mut |_| {},
        )?);
    }
    struct Measured {
        v: f64,
        pen: f64,
        force: f64,
        contact: f64,
        rebound: f64,
        mean_force: f64,
    }
    let mut measured = Vec::new();
    let mut rows = Vec::new();
    for (run, &v) in runs.iter().zip(&spec.speeds) {
        let mut checks = vec![Check::holds(
            &format!("{}: the run completes", run.label),
            run.completed(),
            "a solution",
        )];
        checks.extend(run.audit_checks());
        push_run_gate(
            report,
            &study,
            run,
            checks,
            "a solution with the identities at round-off",
            &spec.note,
        );
        let e = translation(&run.scene, &spec.direction);
        let rebound = match &run.run {
            Ok(r) => -rigid_velocity(&run.scene, &e, &r.velocity) / v,
            Err(_) => f64::NAN,
        };
        let contact = run.contact_interval().map_or(f64::NAN, |c| c.2);
        let m = Measured {
            v,
            pen: run.max_penetration(),
            force: run.max_contact_force(),
            contact,
            rebound,
            mean_force: run.impulse() / contact,
        };
        let (its, max_it) = run.newton();
        rows.push(vec![
            format!("{v}"),
            run.outcome(),
            format!("{:.6e}", m.pen),
            format!("{:.6e}", m.pen / v),
            format!("{:.6e}", m.force / v),
            format!("{:.6e}", m.mean_force / v),
            format!("{:.6e}", m.contact),
            format!("{:.6}", m.rebound),
            format!("{:.2e}", run.summary_value(|s| s.max_drift_1_48)),
            format!("{:.2e}", run.summary_value(|s| s.max_drift_1_49)),
            format!("{its} / {max_it}"),
        ]);
        measured.push(m);
    }
    let k = runs[0].k();
    let mut checks = Vec::new();
    if let Some(tol) = spec.homogeneity_tolerance {
        let base = &measured[0];
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs().max(f64::MIN_POSITIVE);
        let worst = |f: &dyn Fn(&Measured) -> f64| {
            measured
                .iter()
                .map(|m| rel(f(m), f(base)))
                .fold(0.0, f64::max)
        };
        checks.push(Check::at_most(
            "homogeneity: p_max / v across speeds (relative spread)",
            worst(&|m| m.pen / m.v),
            tol,
        ));
        checks.push(Check::at_most(
            "homogeneity: F_max / v across speeds",
            worst(&|m| m.force / m.v),
            tol,
        ));
        checks.push(Check::at_most(
            "homogeneity: contact time across speeds",
            worst(&|m| m.contact),
            tol,
        ));
        checks.push(Check::at_most(
            "homogeneity: rebound coefficient across speeds",
            worst(&|m| m.rebound),
            tol,
        ));
    }
    if let Some(tol) = spec.wave_theory_tolerance {
        match &runs[0].scene.body {
            SceneBody::Bar(b) => {
                let d = b.data();
                let c = runs[0].scene.problem.body.wave_speed();
                let t_exact = 2.0 * d.mesh.length() / c;
                for m in &measured {
                    checks.push(Check::within(
                        &format!("v = {}: contact time / (2L/c)", m.v),
                        m.contact / t_exact,
                        1.0,
                        tol,
                    ));
                    checks.push(Check::within(
                        &format!("v = {}: rebound velocity / v", m.v),
                        m.rebound,
                        1.0,
                        tol,
                    ));
                    checks.push(Check::within(
                        &format!("v = {}: mean contact force / (ρ c A v)", m.v),
                        m.mean_force / (d.density * c * d.area * m.v),
                        1.0,
                        tol,
                    ));
                }
            }
            SceneBody::Plane(_) => {
                return Err(format!("{study}: wave_theory_tolerance is for bars"));
            }
        }
    }
    if let Some([lo, hi]) = spec.penetration_exponent {
        for w in measured.windows(2) {
            let e = (w[1].pen / w[0].pen).ln() / (w[1].v / w[0].v).ln();
            checks.push(Check {
                name: format!(
                    "exponent d ln p_max / d ln v between v = {} and {}",
                    w[0].v, w[1].v
                ),
                observed: e,
                limit: format!("in [{lo}, {hi}]"),
                passed: (lo..=hi).contains(&e),
            });
        }
    }
    if spec.contact_time_nonincreasing {
        for w in measured.windows(2) {
            checks.push(Check::at_most(
                &format!(
                    "contact time at v = {} minus at v = {} (≤ one step)",
                    w[1].v, w[0].v
                ),
                w[1].contact - w[0].contact,
                k * (1.0 + 1e-9),
            ));
        }
    }
    if !checks.is_empty() {
        report.gates.push(GateVerdict::from_checks(
            format!("{study}: trends in the speed"),
            "extreme",
            checks,
            &spec.note,
        ));
    }
    report.tables.push(Table {
        title: format!("{study} ({})", runs[0].scene.problem.body.describe()),
        header: header(&[
            "v",
            "outcome",
            "max penetration",
            "p_max / v",
            "F_max / v",
            "mean force / v",
            "contact time",
            "rebound v_N / v",
            "max |R(1.48)|/E_ref",
            "max |R(1.49)|/E_ref",
            "Newton its (total / max)",
        ]),
        rows,
    });
    let pen = Figure::new(format!("{}: largest penetration", spec.name))
        .x_label("impact speed v")
        .y_label("max penetration")
        .log_log()
        .series(Series::line_markers(
            "p_max",
            measured.iter().map(|m| (m.v, m.pen)),
        ));
    let pen = match (measured.first(), measured.last()) {
        (Some(a), Some(b)) => pen
            .series(slope_line("slope 1", (a.v, 0.5 * a.pen), b.v, 1.0))
            .series(slope_line("slope 1/2", (a.v, 0.5 * a.pen), b.v, 0.5).color(6)),
        _ => pen,
    };
    let tc = Figure::new("contact time")
        .x_label("impact speed v")
        .y_label("t_last − t_first + k")
        .semilog_x()
        .series(Series::line_markers(
            "contact time",
            measured.iter().map(|m| (m.v, m.contact)),
        ));
    let mut hist = Figure::new("normal contact force / v against t")
        .x_label("t")
        .y_label("Σ w_i N_i / v");
    for (i, (run, &v)) in runs.iter().zip(&spec.speeds).enumerate() {
        hist = hist.series(
            Series::line(
                format!("v = {v}"),
                run.records().iter().map(|r| (r.time, r.contact_force / v)),
            )
            .color(i),
        );
    }
    ctx.panels(
        report,
        &format!("speed_{index}_{}", slug(&spec.name)),
        &format!(
            "{}: penetration, contact time and contact force against the speed",
            spec.name
        ),
        &[pen, tc, hist],
        3,
    )
}
