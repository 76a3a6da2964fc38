//! `moving_oscillator`: the moving string with the oscillator in the bushing (ideal contact, thin
//! string: friction does no work, Hetzler 2009 §4.2.1, (83)–(86)) against the roots of its exact
//! characteristic equation (`exact.rs`).
//!
//! - Convergence of the lowest coupled frequencies in N (sine) and h (P1, Hermite). The
//!   eigenfunctions have a kink at ā (the spring's point force): sine coefficients decay like
//!   k⁻², the best energy-norm error is O(N^{-1/2}) and the eigenvalue error O(N⁻¹); P1 with ā on
//!   a node represents the kink and keeps O(h²); C¹ Hermite cubics cannot bend at a point and drop
//!   to the kink's rate.
//! - Nodal modes: with ā = 1/2 the even string modes do not move the bushing, so
//!   λ = i nπ(1 − v̄²) (n even) stay exact eigenvalues for any oscillator.
//! - The Campbell diagram over v̄ with tracked branches (veering between the string modes and the
//!   oscillator) against the exact roots followed by continuation in v̄.

use std::path::Path;

use nalgebra::Complex;
use serde::{Deserialize, Serialize};

use contactlab::model::moving::c64;
use contactlab::model::moving::finite_element_basis::ElementKind;
use contactlab::model::moving::string_data::{ContactModel, MovingStringData};
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};

use crate::core::context::RunContext;
use crate::core::format::CaseError;
use crate::core::format::{invalid, positive};
use crate::core::gate::RateGate;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::exact::moving_string::{string_eigenvalue, OscillatorCharacteristic};
use crate::moving::bounds::{ceiling_factor, predicted_error};
use crate::moving::convergence::{rate_gates, Convergence, Level};
use crate::moving::errors::frequencies;
use crate::moving::plots::{loci_figures, upper_branches};
use crate::moving::study::{speed_axis, speed_sweep, string_eigenvalues, Bushing, SeriesSelect};
use crate::plot::Series;

/// The case format of `moving_oscillator`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OscillatorCase {
    pub oscillator: Oscillator,
    pub convergence: Convergence,
    #[serde(default)]
    pub gate: Vec<RateGate<SeriesSelect>>,
    pub nodal: Nodal,
    pub campbell: Campbell,
}

/// `[oscillator]`: c̄, m̄, ā (ideal contact, no friction, no damping).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Oscillator {
    pub stiffness: f64,
    pub mass: f64,
    pub position: f64,
}

/// `[nodal]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Nodal {
    pub speed: f64,
    /// The even string modes checked.
    pub modes: Vec<usize>,
    /// P1 elements of the discrete eigenvalues reported next to the roots.
    pub elements: usize,
    /// |root of F − i nπ(1 − v̄²)| ≤ this × ε |λ|: the secant stops at a step ≤ 4ε|λ|, so the
    /// root is exact to a few ulps.
    pub round_off: f64,
}

/// `[campbell]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Campbell {
    pub elements: usize,
    pub from: f64,
    pub to: f64,
    pub points: usize,
    pub branches: usize,
    /// The error model's coarse level: the same sweep with this many P1 elements (ā a node).
    pub coarse_elements: usize,
    /// The largest error at `elements` at most this (≤ 3) times the prediction
    /// E(coarse) · (coarse/elements)² of P1's rate 2.
    pub ceiling_factor: f64,
}

impl OscillatorCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        positive(p, "oscillator.stiffness", self.oscillator.stiffness)?;
        positive(p, "oscillator.mass", self.oscillator.mass)?;
        if !(self.oscillator.position > 0.0 && self.oscillator.position < 1.0) {
            return Err(invalid(
                p,
                "oscillator.position",
                self.oscillator.position,
                "in (0, 1)",
            ));
        }
        self.convergence.check(p)?;
        for (i, g) in self.gate.iter().enumerate() {
            g.criteria.check(p, &format!("gate[{i}]"))?;
        }
        positive(p, "nodal.round_off", self.nodal.round_off)?;
        ceiling_factor(p, "campbell.ceiling_factor", self.campbell.ceiling_factor)?;
        for (field, m) in [
            ("campbell.elements", self.campbell.elements),
            ("campbell.coarse_elements", self.campbell.coarse_elements),
        ] {
            let x = self.oscillator.position * m as f64;
            if m < 2 || (x - x.round()).abs() > 1e-9 {
                return Err(invalid(
                    p,
                    field,
                    m,
                    "≥ 2 elements with ā a node (ā·M an integer)",
                ));
            }
        }
        if self.campbell.coarse_elements >= self.campbell.elements {
            return Err(invalid(
                p,
                "campbell.coarse_elements",
                self.campbell.coarse_elements,
                "fewer than campbell.elements",
            ));
        }
        if self.campbell.points < 3 {
            return Err(invalid(p, "campbell.points", self.campbell.points, ">= 3"));
        }
        Ok(())
    }
}

impl Oscillator {
    /// The string at speed v̄ = `speed` (undamped) with this oscillator at ā = `position` in
    /// ideal contact, without friction.
    fn data(&self, speed: f64, position: f64) -> MovingStringData {
        let bushing = Bushing {
            stiffness: self.stiffness,
            mass: self.mass,
            position,
        };
        bushing.data(speed, 0.0, ContactModel::Ideal, 0.0)
    }

    /// The exact characteristic equation of the undamped string at speed v̄ = `speed` with this
    /// oscillator at ā = `position`.
    fn characteristic(&self, speed: f64, position: f64) -> OscillatorCharacteristic {
        OscillatorCharacteristic {
            speed,
            damping: 0.0,
            stiffness: self.stiffness,
            mass: self.mass,
            position,
        }
    }
}

/// Runs the case.
pub fn run(case: &OscillatorCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let o = &case.oscillator;
    let c = &case.convergence;
    let fine = |m: usize| StringDiscretization::FiniteElements {
        kind: ElementKind::P1,
        elements: m,
    };
    let mut exact_roots = Vec::new();
    let mut levels = Vec::new();
    for &v in &c.speeds {
        let d = o.data(v, o.position);
        let ch = o.characteristic(v, o.position);
        // Exact roots from the finest P1 approximation (ā on a node).
        let guess = frequencies(&string_eigenvalues(
            fine(c.p1_elements[c.p1_elements.len() - 1]),
            &d,
        )?);
        let mut exact = Vec::new();
        for &g in guess.iter().take(c.modes_checked) {
            let r = ch.refine(Complex::new(0.0, g))?;
            exact.push(r.im);
            if r.re.abs() > 1e-10 * r.norm() {
                return Err(format!("exact root {r} is not on the imaginary axis"));
            }
        }
        for w in exact.windows(2) {
            if (w[1] - w[0]).abs() < 1e-8 * w[1] {
                return Err(format!("two guesses converged to the same root {}", w[0]));
            }
        }
        levels.extend(c.levels(v, &d, &exact, false)?);
        exact_roots.push((v, exact));
    }
    rate_gates(&case.gate, &levels, "coupled frequency error", report)?;

    // Nodal modes at ā = 1/2.
    let n = &case.nodal;
    let dn = o.data(n.speed, 0.5);
    let chn = o.characteristic(n.speed, 0.5);
    let fnodal = frequencies(&string_eigenvalues(fine(n.elements), &dn)?);
    let mut checks = Vec::new();
    let mut nodal_rows = Vec::new();
    for &m in &n.modes {
        let exact = string_eigenvalue(m, n.speed);
        let root = chn.refine(Complex::new(0.0, exact * (1.0 + 1e-4)))?;
        let nearest = fnodal
            .iter()
            .copied()
            .min_by(|a, b| (a - exact).abs().total_cmp(&(b - exact).abs()))
            .unwrap_or(f64::NAN);
        let root_err = (root - Complex::new(0.0, exact)).norm() / (exact * f64::EPSILON);
        checks.push(Check::at_most(
            &format!("mode {m}: root of F near i·{exact:.6} vs i nπ(1 − v̄²), in units of ε |λ|"),
            root_err,
            n.round_off,
        ));
        nodal_rows.push((m, exact, root.im, nearest));
    }
    report.gates.push(GateVerdict::from_checks(
        format!(
            "ā = 1/2, v̄ = {}: even string modes are exact eigenvalues for any oscillator",
            n.speed
        ),
        "exact",
        checks,
        "W_n = e^{inπv̄ξ} sin(nπξ) vanishes at ξ = 1/2 for even n: the bushing does not move",
    ));

    // Campbell diagram with tracked branches against the exact roots continued in v̄, with the
    // ceiling of P1's error model E ∝ h² from the same sweep on the coarse mesh.
    let cb = &case.campbell;
    let axis = speed_axis(cb.from, cb.to, cb.points)?;
    let (sweep, chosen, exact_branches, worst) =
        campbell_errors(o, cb.elements, &axis, cb.branches)?;
    let (_, _, _, coarse) = campbell_errors(o, cb.coarse_elements, &axis, cb.branches)?;
    let predicted = predicted_error(coarse, cb.coarse_elements as f64, cb.elements as f64, 2.0);
    // The smallest relative gap between neighbouring exact branches: a swapped branch would be
    // off by at least this much.
    let mut min_gap = f64::INFINITY;
    for i in 0..axis.values.len() {
        let mut col: Vec<f64> = exact_branches.iter().map(|b| b[i]).collect();
        col.sort_by(f64::total_cmp);
        for w in col.windows(2) {
            min_gap = min_gap.min((w[1] - w[0]) / w[1]);
        }
    }
    report.gates.push(GateVerdict::from_checks(
        "tracked branches through veering match the exact roots".into(),
        "exact",
        vec![
            Check::at_most(
                &format!(
                    "first {} branches (P1, {} elements), v̄ ∈ [{}, {}]: max |λ − λ_exact| / |λ_exact| vs {} × the prediction {predicted:.3e} of E ∝ h² from {} elements ({coarse:.3e})",
                    cb.branches, cb.elements, cb.from, cb.to, cb.ceiling_factor, cb.coarse_elements
                ),
                worst,
                cb.ceiling_factor * predicted,
            ),
            Check::at_most(
                &format!("the same, relative to the smallest gap between exact branches ({min_gap:.3e})"),
                worst / min_gap,
                0.5,
            ),
        ],
        "the exact roots are continued in v̄ independently of the tracker; a swapped branch would be off by at least the gap between branches (hence at most half of it)",
    ));
    let exact_series: Vec<Series> = exact_branches
        .iter()
        .enumerate()
        .map(|(k, pts)| {
            Series::markers(
                if k == 0 { "exact roots" } else { "" },
                axis.values
                    .iter()
                    .zip(pts)
                    .step_by(4)
                    .map(|(&v, &w)| (v, w))
                    .collect::<Vec<_>>(),
            )
            .color(6)
        })
        .collect();
    let (_, im_fig) = loci_figures(
        "string with oscillator",
        "v̄",
        &sweep.branches,
        &chosen,
        &exact_series,
    );
    let omega0 = (o.stiffness / o.mass).sqrt();
    let im_fig = im_fig.series(
        Series::line(
            "oscillator sqrt(c̄/m̄)",
            vec![(cb.from, omega0), (cb.to, omega0)],
        )
        .color(7)
        .dashed(),
    );
    let conv = c.figures(&levels, "coupled frequencies", [1.0, 2.0, 1.0]);
    ctx.plot(report, "campbell", &im_fig)?;
    ctx.panels(
        report,
        "convergence",
        "String with oscillator: the kink at ā limits the sine basis and Hermite cubics to rate 1; P1 with ā on a node keeps rate 2",
        &conv,
        3,
    )?;
    #[derive(Serialize)]
    struct Data<'a> {
        exact_roots: &'a [(f64, Vec<f64>)],
        levels: &'a [Level],
        nodal: &'a [(usize, f64, f64, f64)],
        campbell_max_error: f64,
        campbell_min_gap: f64,
    }
    ctx.write_data(
        report,
        &Data {
            exact_roots: &exact_roots,
            levels: &levels,
            nodal: &nodal_rows,
            campbell_max_error: worst,
            campbell_min_gap: min_gap,
        },
    )
}

/// The Campbell sweep of P1 with `elements` elements over `axis`: the sweep, its lowest
/// `branches` tracked branches, the exact roots continued in v̄ on their own (secant from the
/// linear extrapolation of the previous two roots, independently of the discrete tracking), and
/// the largest relative distance of the tracked branches from them.
#[allow(clippy::type_complexity)]
fn campbell_errors(
    o: &Oscillator,
    elements: usize,
    axis: &contactlab::model::moving::stability_map::GridAxis,
    branches: usize,
) -> Result<
    (
        contactlab::model::moving::sweep::Sweep,
        Vec<usize>,
        Vec<Vec<f64>>,
        f64,
    ),
    String,
> {
    let disc = StringDiscretization::FiniteElements {
        kind: ElementKind::P1,
        elements,
    };
    let model = MovingStringModel::new(disc, Default::default()).map_err(|e| e.to_string())?;
    let from = axis.values[0];
    let sweep = speed_sweep(&model, &o.data(from, o.position), axis)?;
    let chosen = upper_branches(&sweep.branches, branches);
    let mut exact_branches: Vec<Vec<f64>> = Vec::new();
    let mut worst: f64 = 0.0;
    for &b in &chosen {
        let mut roots: Vec<Complex<f64>> = Vec::new();
        for (i, &v) in axis.values.iter().enumerate() {
            let ch = o.characteristic(v, o.position);
            let guess = match roots.len() {
                0 => Complex::new(0.0, sweep.branches.branches[b][0].im),
                1 => roots[0],
                k => roots[k - 1] * 2.0 - roots[k - 2],
            };
            let root = ch.refine(guess)?;
            let x: c64 = sweep.branches.branches[b][i];
            worst = worst.max(((x.im - root.im).abs() + x.re.abs()) / root.norm());
            roots.push(root);
        }
        exact_branches.push(roots.iter().map(|r| r.im).collect());
    }
    Ok((sweep, chosen, exact_branches, worst))
}
