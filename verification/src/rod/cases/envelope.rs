//! Kind `rod_envelope`: the rod T1D at the edges of its range (docs/quasistatic.md, "The range of
//! the quasistatic family"): meshes from 10 to 10⁵ elements, uniform and graded to the edge of the
//! grading range, steps from 10 to 10⁵, a soft and a stiff foundation, every scheme. Reference: for
//! constant data the P1 Galerkin solution is exact at the nodes in space (the operator has constant
//! coefficients and the load is integrated exactly), so the end displacement U_n = u_n(L) of every
//! mesh follows the scalar recurrence of the time scheme alone,
//!
//!   a w_n + b (U_{n−1} + θ k w_n) = f0 L²/2 − L p_ν(w_n),   U_n = U_{n−1} + k w_n,
//!
//! (the integral of a ε_t + b ε = σ over (0, L), docs/quasistatic.md, Test T1D), solved here in
//! closed form per step for the lubricated law p_ν(r) = β r_+ + p0 — no mesh, no solver of the
//! program. The gate is the round-off of the two computations.

use contactlab::scene::{Scene, Solution};
use serde::Deserialize;

use crate::core::case::Case;
use crate::core::context::RunContext;
use crate::core::format::{at_least, positive, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};

/// The case body of `rod_envelope`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeCase {
    pub rod_envelope: EnvelopeSpec,
}

/// `[rod_envelope]`: the points swept.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeSpec {
    /// The (M elements, N steps) pairs swept.
    pub points: Vec<[usize; 2]>,
    /// Mesh gradings towards the contact end (1 = uniform).
    pub gradings: Vec<f64>,
    /// Foundation dampers β.
    pub betas: Vec<f64>,
    /// Schemes.
    pub schemes: Vec<String>,
    /// |U_N − U_N^ref| / |U_N^ref| at most this multiple of ε (κ(K) + N)(1 + Lβ/a) (see
    /// [`round_off_bound`]).
    pub round_off_factor: f64,
}

impl EnvelopeCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: Self = case.body()?;
        let p = &c.rod_envelope;
        at_least(case.path(), "rod_envelope.points", &p.points, 1)?;
        at_least(case.path(), "rod_envelope.betas", &p.betas, 1)?;
        at_least(case.path(), "rod_envelope.schemes", &p.schemes, 1)?;
        at_least(case.path(), "rod_envelope.gradings", &p.gradings, 1)?;
        positive(
            case.path(),
            "rod_envelope.round_off_factor",
            p.round_off_factor,
        )?;
        Ok(c)
    }
}

/// The data: L = a = b = 1, f0 = 10, p0 = 2 (the paper's receding-then-pressing threshold is
/// p0 = f0 L / 2 = 5: with p0 = 2 the end presses and the damper acts), T = 1, u0 = 0.
const F0: f64 = 10.0;
const P0: f64 = 2.0;

fn scene_text(m: usize, grading: f64, n: usize, beta: f64, scheme: &str) -> String {
    let grading = if grading > 1.0 {
        format!("grading = {grading}\ngraded_towards = \"end\"\n")
    } else {
        String::new()
    };
    format!(
        "model = \"rod\"\n[rod]\nlength = 1.0\nfinal_time = 1.0\nviscosity = 1.0\nelasticity = 1.0\n\
         load = {F0}\n[foundation]\nlaw = \"lubricated\"\nbeta = {beta:e}\np0 = {P0}\n[mesh]\n\
         elements = {m}\n{grading}[time]\nsteps = {n}\nscheme = \"{scheme}\"\n"
    )
}

/// θ of a scheme name (explicit 0, midpoint 1/2, implicit 1).
fn theta(scheme: &str) -> f64 {
    match scheme {
        "explicit" => 0.0,
        "midpoint" => 0.5,
        _ => 1.0,
    }
}

/// U_N by the scalar recurrence: with c = f0 L²/2 − L p0 and w_n > 0 (the end presses),
/// w_n = (c − b U_{n−1}) / (a + θ b k + L β); if that is ≤ 0 the damper is off:
/// w_n = (c − b U_{n−1}) / (a + θ b k).
fn reference_end_displacement(n: usize, beta: f64, theta: f64) -> f64 {
    let (a, b, l) = (1.0, 1.0, 1.0);
    let c = F0 * l * l / 2.0 - l * P0;
    let mut u = 0.0;
    for i in 1..=n {
        let k = (i as f64) / (n as f64) - ((i - 1) as f64) / (n as f64);
        let rhs = c - b * u;
        let w_on = rhs / (a + theta * b * k + l * beta);
        let w = if w_on > 0.0 {
            w_on
        } else {
            rhs / (a + theta * b * k)
        };
        u += k * w;
    }
    u
}

/// The round-off model of U_N: the solve with the P1 stiffness K (backward stable) errs by
/// ε κ(K) relatively, κ(K) ≤ 4 (L/h_min)² / π² (λ_max ≤ 4a/h_min, λ_min ≥ π² a h_min / L²; the
/// uniform mesh attains it), each of the N steps adds ε, and the contact equation
/// r + c p_ν(r) = w* cancels terms of size (1 + Lβ/a) |r| (a stiff damper leaves a small velocity
/// out of large terms). `nodes` are the mesh nodes of the run (recomputed here, not the solver's
/// statistics).
fn round_off_bound(nodes: &[f64], n: usize, beta: f64) -> f64 {
    let l = nodes.last().copied().unwrap_or(1.0) - nodes.first().copied().unwrap_or(0.0);
    let h_min = nodes
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    let kappa = 4.0 * (l / h_min).powi(2) / std::f64::consts::PI.powi(2);
    f64::EPSILON * (kappa + n as f64) * (1.0 + l * beta)
}

/// Runs the case.
pub fn run(case: &Case, _ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let c = EnvelopeCase::parse(case).map_err(|e| e.to_string())?;
    let spec = &c.rod_envelope;
    let mut checks = Vec::new();
    let mut rows = Vec::new();
    for &[m, n] in &spec.points {
        for &q in &spec.gradings {
            {
                for &beta in &spec.betas {
                    for scheme in &spec.schemes {
                        let what = format!("M = {m}, grading {q}, N = {n}, β = {beta:e}, {scheme}");
                        let reference = reference_end_displacement(n, beta, theta(scheme));
                        let run = Scene::from_toml_str(
                            &scene_text(m, q, n, beta, scheme),
                            "rod_envelope.toml",
                        )
                        .and_then(|s| s.run());
                        let (u, bound) = match run {
                            Ok(Solution::Rod(r)) => (
                                r.end_displacement.last().copied().unwrap_or(f64::NAN),
                                round_off_bound(&r.nodes, n, beta),
                            ),
                            Ok(_) => (f64::NAN, f64::NAN),
                            Err(e) => {
                                checks.push(Check::holds(&what, false, &e.to_string()));
                                continue;
                            }
                        };
                        let rel = (u - reference).abs() / reference.abs();
                        checks.push(Check::at_most(
                            &format!(
                                "{what}: |U_N − U_N^ref|/|U_N^ref| over ε (κ(K) + N)(1 + Lβ/a) = {bound:.1e}"
                            ),
                            rel / bound,
                            spec.round_off_factor,
                        ));
                        rows.push(vec![
                            m.to_string(),
                            q.to_string(),
                            n.to_string(),
                            format!("{beta:e}"),
                            scheme.clone(),
                            format!("{u:.15e}"),
                            format!("{rel:.2e}"),
                            format!("{:.2}", rel / bound),
                        ]);
                    }
                }
            }
        }
    }
    report.gates.push(GateVerdict::from_checks(
        "the end displacement is the time scheme's scalar recurrence on every mesh, to round-off"
            .into(),
        "rod_envelope",
        checks,
        "P1 in 1D with constant coefficients and a constant load is exact at the nodes, so every \
         mesh (uniform or graded, up to 10⁵ elements) and every step count gives the end \
         displacement of the scalar recurrence written in this file; the two computations differ \
         by round-off: the stiffness solve's ε κ(K), κ(K) ≤ 4 (L/h_min)²/π² from the run's nodes, \
         ε per step, amplified by the contact equation's cancellation 1 + Lβ/a",
    ));
    report.tables.push(Table {
        title: "the sweep: the program's U_N against the scalar recurrence".into(),
        header: [
            "M",
            "grading",
            "N",
            "β",
            "scheme",
            "U_N",
            "relative difference",
            "of the bound",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
    report.gates.push(past_range_gate());
    Ok(())
}

/// Past the range: typed errors naming the key as written.
fn past_range_gate() -> GateVerdict {
    let base = scene_text(10, 1.0, 10, 1.0, "midpoint");
    let cases = [
        (
            "mesh.grading = 11 (range [1, 10])",
            base.replace("elements = 10\n", "elements = 10\ngrading = 11.0\n"),
            "mesh.grading",
        ),
        (
            "mesh.grading = 10 with 100 elements (ε M^q = 2e4 ≥ 1)",
            base.replace("elements = 10\n", "elements = 100\ngrading = 10.0\n"),
            "mesh.grading",
        ),
        (
            "mesh.elements = 0",
            base.replace("elements = 10\n", "elements = 0\n"),
            "mesh.elements",
        ),
        (
            "time.steps = 0",
            base.replace("steps = 10\n", "steps = 0\n"),
            "time.steps",
        ),
        (
            "mesh.elements = 10¹² (beyond memory)",
            base.replace("elements = 10\n", "elements = 1000000000000\n"),
            "mesh.elements",
        ),
        (
            "foundation.beta = −1",
            base.replace("beta = 1e0", "beta = -1.0"),
            "foundation.beta",
        ),
    ];
    let checks = cases
        .iter()
        .map(|(what, text, key)| {
            let message =
                match Scene::from_toml_str(text, "rod_envelope.toml").and_then(|s| s.run()) {
                    Ok(_) => "accepted".to_string(),
                    Err(e) => e.to_string(),
                };
            Check::holds(
                &format!("{what}: a typed error naming `{key}`"),
                message.contains(key),
                &message,
            )
        })
        .collect();
    GateVerdict::from_checks(
        "inputs past the range are typed errors naming the key".into(),
        "rod_envelope",
        checks,
        "past the range the family answers with an error that names what the user wrote, never a \
         quiet answer",
    )
}
