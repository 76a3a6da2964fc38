//! `moving_symmetry`: the transport operators P_T (gyroscopic when R_P = 0) and Q_T (symmetric
//! when R_Q = 0) for the boundary conditions of Figs 10–12 (Hetzler 2009, §3.3.1, (58)–(64)).
//!
//! For each family the program computes P_ij = ⟨Φ_i, v̄Φ_j'⟩ and Q_ij = ⟨Φ_i, v̄²Φ_j''⟩ by
//! quadrature without integrating by parts; the boundary terms R_P and R_Q are formed here, from
//! the end values and slopes of each family written out in closed form ([`ends`]) — not from the
//! program's shape functions or its boundary-term code. Then (both directions are gates):
//! - the integration-by-parts identities P + Pᵀ = R_P and Q − Qᵀ = R_Q hold to round-off: the
//!   quadrature (16 panels × 12 Gauss points, m = 192 terms per entry, exact to degree 23 per
//!   panel; the sines turn by at most 1.6 rad per panel) leaves only the summation's round-off,
//!   at most m ε relative (`round_off` = C in C m ε),
//! - the program's table of which families are gyroscopic / have a symmetric transport
//!   stiffness agrees with whether the independent R_P, R_Q vanish,
//! - G = 2P is skew to round-off exactly for the families whose R_P vanishes (Fig. 10) and
//!   measurably not otherwise (Figs 11, 12b),
//! - K_T = Q is symmetric to round-off exactly for the families whose R_Q vanishes (Fig. 12 and
//!   periodic ends) and measurably not otherwise (rigid coupling, Fig. 11).
//!
//! The assembled string models (sine, P1, Hermite; fixed guides) have M, D, K symmetric and G
//! skew to round-off.

use std::path::Path;

use serde::{Deserialize, Serialize};

use contactlab::model::moving::finite_element_basis::ElementKind;
use contactlab::model::moving::properties::{
    skew_defect, symmetry_defect, transport_operators, TransportBoundary,
};
use contactlab::model::moving::string_data::{ContactModel, MovingStringData, OscillatorData};
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};

use crate::core::context::RunContext;
use crate::core::format::positive;
use crate::core::format::CaseError;
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::plot::{Figure, Series};

/// The case format of `moving_symmetry`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SymmetryCase {
    pub symmetry: Symmetry,
}

/// `[symmetry]`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Symmetry {
    pub functions: usize,
    pub speed: f64,
    /// C of the round-off bound C m ε of the identities and of a defect predicted zero (m the
    /// number of terms summed per entry: 192 quadrature nodes for P and Q, 8 for an entry of the
    /// assembled element matrices, 1 for the closed-form sine operators).
    pub round_off: f64,
    /// A defect predicted non-zero is at least this (a separation from round-off, ≥ 10¹¹ m ε).
    pub measurable: f64,
    /// Sizes of the assembled string models checked (sine modes; elements of P1 and Hermite).
    pub model_size: usize,
}

impl SymmetryCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        let s = &self.symmetry;
        positive(p, "symmetry.speed", s.speed)?;
        positive(p, "symmetry.round_off", s.round_off)?;
        positive(p, "symmetry.measurable", s.measurable)?;
        if !(2..=12).contains(&s.functions) {
            return Err(crate::core::format::invalid(
                p,
                "symmetry.functions",
                s.functions,
                "2 to 12",
            ));
        }
        Ok(())
    }
}

#[derive(Debug, Clone, Serialize)]
struct FamilyResult {
    family: TransportBoundary,
    figure: &'static str,
    gyroscopic_predicted: bool,
    symmetric_predicted: bool,
    skew_defect_g: f64,
    symmetry_defect_kt: f64,
    identity_rp: f64,
    identity_rq: f64,
}

/// ‖A − B‖_F.
fn diff_norm(
    a: &contactlab::model::moving::Mat<f64>,
    b: &contactlab::model::moving::Mat<f64>,
) -> f64 {
    let n = a.nrows();
    let mut d = 0.0;
    for i in 0..n {
        for j in 0..n {
            d += (a[(i, j)] - b[(i, j)]).powi(2);
        }
    }
    d.sqrt()
}

/// Runs the case.
pub fn run(case: &SymmetryCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let s = &case.symmetry;
    let mut results = Vec::new();
    let quad_terms = 192.0;
    let bound = s.round_off * quad_terms * f64::EPSILON;
    for family in TransportBoundary::ALL {
        let t = transport_operators(family, s.functions, s.speed).map_err(|e| e.to_string())?;
        let n = s.functions;
        let (r_p, r_q) = boundary_terms(family, n, s.speed);
        let sum_p =
            contactlab::model::moving::Mat::<f64>::from_fn(n, n, |i, j| t.p[(i, j)] + t.p[(j, i)]);
        let diff_q =
            contactlab::model::moving::Mat::<f64>::from_fn(n, n, |i, j| t.q[(i, j)] - t.q[(j, i)]);
        let scale_p = t.p.norm_l2();
        let scale_q = t.q.norm_l2();
        let identity_rp = diff_norm(&sum_p, &r_p) / scale_p;
        let identity_rq = diff_norm(&diff_q, &r_q) / scale_q;
        let rp_zero = r_p.norm_max() == 0.0;
        let rq_zero = r_q.norm_max() == 0.0;
        let r = FamilyResult {
            family,
            figure: family.figure(),
            gyroscopic_predicted: rp_zero,
            symmetric_predicted: rq_zero,
            skew_defect_g: skew_defect(t.p.as_ref()),
            symmetry_defect_kt: symmetry_defect(t.q.as_ref()),
            identity_rp,
            identity_rq,
        };
        let g_check = if r.gyroscopic_predicted {
            Check::at_most(
                "G = 2P skew: ‖G + Gᵀ‖/‖G‖ (R_P = 0 predicted)",
                r.skew_defect_g,
                bound,
            )
        } else {
            Check::holds(
                &format!(
                    "G not skew: ‖G + Gᵀ‖/‖G‖ = {:.3e} ≥ {:.0e} (R_P ≠ 0 predicted)",
                    r.skew_defect_g, s.measurable
                ),
                r.skew_defect_g >= s.measurable,
                "measurably not skew",
            )
        };
        let k_check = if r.symmetric_predicted {
            Check::at_most(
                "K_T = Q symmetric: ‖Q − Qᵀ‖/‖Q‖ (R_Q = 0 predicted)",
                r.symmetry_defect_kt,
                bound,
            )
        } else {
            Check::holds(
                &format!(
                    "K_T not symmetric: ‖Q − Qᵀ‖/‖Q‖ = {:.3e} ≥ {:.0e} (R_Q ≠ 0 predicted)",
                    r.symmetry_defect_kt, s.measurable
                ),
                r.symmetry_defect_kt >= s.measurable,
                "measurably not symmetric",
            )
        };
        report.gates.push(GateVerdict::from_checks(
            format!("{family:?} ({})", r.figure),
            "symmetry",
            vec![
                Check::at_most(
                    "‖P + Pᵀ − R_P‖/‖P‖ (58)–(60), R_P from the closed-form end values",
                    identity_rp,
                    bound,
                ),
                Check::at_most(
                    "‖Q − Qᵀ − R_Q‖/‖Q‖ (61)–(63), R_Q from the closed-form end values",
                    identity_rq,
                    bound,
                ),
                Check::holds(
                    &format!(
                        "the program's table (gyroscopic {}, symmetric K_T {}) vs the independent R_P = 0: {rp_zero}, R_Q = 0: {rq_zero}",
                        family.gyroscopic_predicted(),
                        family.symmetric_transport_stiffness_predicted()
                    ),
                    family.gyroscopic_predicted() == rp_zero
                        && family.symmetric_transport_stiffness_predicted() == rq_zero,
                    "the same",
                ),
                g_check,
                k_check,
            ],
            "the boundary terms decide: R_P = v̄[VW]₀¹, R_Q = v̄²[VW' − V'W]₀¹",
        ));
        results.push(r);
    }
    // The assembled models (fixed guides, with an oscillator).
    let mut model_rows = Vec::new();
    let data = MovingStringData {
        speed: s.speed,
        damping: 0.1,
        oscillator: Some(OscillatorData {
            stiffness: 3.0,
            mass: 0.5,
            position: 0.37,
            contact: ContactModel::Ideal,
            friction: 0.0,
            patch_width: 0.0,
        }),
    };
    let mut checks = Vec::new();
    for disc in [
        StringDiscretization::Sine {
            modes: s.model_size,
        },
        StringDiscretization::FiniteElements {
            kind: ElementKind::P1,
            elements: s.model_size,
        },
        StringDiscretization::FiniteElements {
            kind: ElementKind::Hermite,
            elements: s.model_size,
        },
    ] {
        let m = MovingStringModel::new(disc, Default::default()).map_err(|e| e.to_string())?;
        let sys = m.system(&data).map_err(|e| e.to_string())?;
        let label = m.basis().label();
        let worst_sym = [&sys.mass, &sys.damping, &sys.stiffness]
            .iter()
            .map(|a| symmetry_defect(a.as_ref()))
            .fold(0.0, f64::max);
        let g = skew_defect(sys.gyroscopic.as_ref());
        // terms summed per entry: 1 (closed-form sine operators; the oscillator adds one product)
        // or 2 elements × 4 Gauss points
        let terms = match disc {
            StringDiscretization::Sine { .. } => 2.0,
            StringDiscretization::FiniteElements { .. } => 8.0,
        };
        let model_bound = s.round_off * terms * f64::EPSILON;
        checks.push(Check::at_most(
            &format!("{label}: M, D, K symmetric (bound C·{terms}·ε)"),
            worst_sym,
            model_bound,
        ));
        checks.push(Check::at_most(
            &format!("{label}: G skew (bound C·{terms}·ε)"),
            g,
            model_bound,
        ));
        model_rows.push((label, worst_sym, g));
    }
    report.gates.push(GateVerdict::from_checks(
        "assembled string models (fixed guides): M, D, K symmetric, G skew".into(),
        "symmetry",
        checks,
        "fixed guides: R_P = R_Q = 0",
    ));
    // Plot: the defects per family.
    let floor = 1e-17;
    let mut fg = Figure::new(format!("‖G + Gᵀ‖/‖G‖, v̄ = {} (0 drawn at 1e-17)", s.speed))
        .x_label("family")
        .y_label("skew-symmetry defect of G")
        .semilog_y()
        .horizontal_line(bound, "round-off gate")
        .horizontal_line(s.measurable, "measurable gate");
    let mut fk = Figure::new(format!(
        "‖K_T − K_Tᵀ‖/‖K_T‖, v̄ = {} (0 drawn at 1e-17)",
        s.speed
    ))
    .x_label("family")
    .y_label("symmetry defect of K_T")
    .semilog_y()
    .horizontal_line(s.round_off, "round-off gate")
    .horizontal_line(s.measurable, "measurable gate");
    for (k, r) in results.iter().enumerate() {
        let name = format!("{}: {:?} ({})", k + 1, r.family, r.figure);
        fg = fg.series(
            Series::markers(
                name.clone(),
                vec![((k + 1) as f64, r.skew_defect_g.max(floor))],
            )
            .color(k),
        );
        fk = fk.series(
            Series::markers(
                name,
                vec![((k + 1) as f64, r.symmetry_defect_kt.max(floor))],
            )
            .color(k),
        );
    }
    ctx.panels(
        report,
        "defects",
        "Figs 10–12: G is skew exactly when R_P vanishes, K_T symmetric exactly when R_Q vanishes",
        &[
            fg.x_range(0.5, 6.5).y_range(1e-17, 1e12),
            fk.x_range(0.5, 6.5).y_range(1e-17, 1e12),
        ],
        2,
    )?;
    #[derive(Serialize)]
    struct Data<'a> {
        families: &'a [FamilyResult],
        models: &'a [(String, f64, f64)],
    }
    ctx.write_data(
        report,
        &Data {
            families: &results,
            models: &model_rows,
        },
    )
}

/// The end values and slopes of member `k` (0-based) of a boundary family, written out:
/// ([V(0), V'(0)], [V(1), V'(1)]). The families (Figs 10–12): fixed guides √2 sin((k+1)πξ);
/// rigidly coupled 1, sin(kπξ); periodic 1, cos(2πmξ), sin(2πmξ) (m = ⌈k/2⌉, cosine for odd k);
/// zero slope cos(kπξ); one end free ξ^{k+1}; both ends free ξ^k.
pub fn ends(family: TransportBoundary, k: usize) -> ([f64; 2], [f64; 2]) {
    let pi = std::f64::consts::PI;
    let sign = |m: usize| if m % 2 == 0 { 1.0 } else { -1.0 };
    match family {
        TransportBoundary::FixedGuides => {
            let w = std::f64::consts::SQRT_2 * (k + 1) as f64 * pi;
            ([0.0, w], [0.0, w * sign(k + 1)])
        }
        TransportBoundary::RigidlyCoupled => {
            if k == 0 {
                ([1.0, 0.0], [1.0, 0.0])
            } else {
                let w = k as f64 * pi;
                ([0.0, w], [0.0, w * sign(k)])
            }
        }
        TransportBoundary::Periodic => {
            if k == 0 || k % 2 == 1 {
                ([1.0, 0.0], [1.0, 0.0])
            } else {
                let w = 2.0 * pi * k.div_ceil(2) as f64;
                ([0.0, w], [0.0, w])
            }
        }
        TransportBoundary::ZeroSlope => ([1.0, 0.0], [sign(k), 0.0]),
        TransportBoundary::OneEndFree => {
            ([0.0, if k == 0 { 1.0 } else { 0.0 }], [1.0, (k + 1) as f64])
        }
        TransportBoundary::BothEndsFree => (
            [
                if k == 0 { 1.0 } else { 0.0 },
                if k == 1 { 1.0 } else { 0.0 },
            ],
            [1.0, k as f64],
        ),
    }
}

/// R_P(Φ_i, Φ_j) = v̄[Φ_iΦ_j]₀¹ and R_Q(Φ_i, Φ_j) = v̄²[Φ_iΦ_j' − Φ_i'Φ_j]₀¹ (58)–(64) from [`ends`].
fn boundary_terms(
    family: TransportBoundary,
    n: usize,
    speed: f64,
) -> (
    contactlab::model::moving::Mat<f64>,
    contactlab::model::moving::Mat<f64>,
) {
    let e: Vec<([f64; 2], [f64; 2])> = (0..n).map(|k| ends(family, k)).collect();
    let r_p = contactlab::model::moving::Mat::<f64>::from_fn(n, n, |i, j| {
        speed * (e[i].1[0] * e[j].1[0] - e[i].0[0] * e[j].0[0])
    });
    let wr = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let r_q = contactlab::model::moving::Mat::<f64>::from_fn(n, n, |i, j| {
        speed * speed * (wr(e[i].1, e[j].1) - wr(e[i].0, e[j].0))
    });
    (r_p, r_q)
}
