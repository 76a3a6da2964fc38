//! The plate's transport operators in `moving_plate` (Hetzler 2009, (74) and §3.3.1): for the
//! periodic disc G = −Gᵀ and K_T = K_Tᵀ to round-off (full and modal bases); for an annular
//! sector 0 ≤ φ ≤ Θ through whose radial edges the material is transported, with the angular
//! functions of each family of Figs 10–12 in φ/Θ, the integration-by-parts identities
//!
//! ```text
//!   G + Gᵀ = 2ρh R_P ⊗ m,  R_P[l,k] = [χ_l ψ_k]₀^Θ;   K_T − K_Tᵀ = ρh R_Q ⊗ m,  R_Q = [χ_l ψ_k' − χ_l' ψ_k]₀^Θ
//! ```
//!
//! hold to round-off with R_P, R_Q from the closed-form end values of the families
//! (`symmetry::ends`, not the program's shapes), and G is skew (K_T symmetric) exactly for the
//! families whose R_P (R_Q) vanishes — measurably not otherwise.

use serde::{Deserialize, Serialize};

use contactlab::model::moving::plate::angular::AngularBasis;
use contactlab::model::moving::plate::radial::RadialBasis;
use contactlab::model::moving::plate::{PlateDiscretization, PlateProperties, RotatingPlateModel};
use contactlab::model::moving::properties::{skew_defect, symmetry_defect, TransportBoundary};
use contactlab::model::moving::Mat;

use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::moving::cases::plate::common::plate_model;
use crate::moving::cases::symmetry::ends;

/// `[symmetry]`.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SymmetrySection {
    pub harmonics: usize,
    pub radial_modes: usize,
    pub sector_angle: f64,
    pub functions: usize,
    pub elements: usize,
    /// C of the round-off bound C m ε (m: the terms summed per entry).
    pub round_off: f64,
    /// A defect predicted non-zero is at least this.
    pub measurable: f64,
}

/// One family's measured defects.
#[derive(Debug, Clone, Serialize)]
pub struct FamilyRow {
    pub family: TransportBoundary,
    pub identity_p: f64,
    pub identity_q: f64,
    pub skew_defect_g: f64,
    pub symmetry_defect_kt: f64,
}

fn kron(a: &Mat<f64>, r: &Mat<f64>) -> Mat<f64> {
    let (na, nr) = (a.nrows(), r.nrows());
    Mat::from_fn(na * nr, na * nr, |i, j| {
        a[(i / nr, j / nr)] * r[(i % nr, j % nr)]
    })
}

/// A defect predicted zero is at round-off, one predicted non-zero is measurable.
fn decided(predicted_zero: bool, defect: f64, round_off: f64, measurable: f64) -> bool {
    if predicted_zero {
        defect <= round_off
    } else {
        defect >= measurable
    }
}

/// Runs the checks.
pub fn run(
    plate: PlateProperties,
    s: &SymmetrySection,
    report: &mut CaseReport,
) -> Result<Vec<FamilyRow>, String> {
    let eps = f64::EPSILON;
    // periodic: the closed forms; terms per entry of the modal blocks: 2 × radial functions
    let mut checks = Vec::new();
    for modes in [None, Some(s.radial_modes)] {
        let m = plate_model(plate, s.harmonics, s.elements, modes)?;
        let terms = 4.0 * s.elements as f64;
        checks.push(Check::at_most(
            &format!(
                "{}: ‖G + Gᵀ‖/‖G‖ in units of m ε (m = {terms})",
                if modes.is_some() { "modal" } else { "full" }
            ),
            skew_defect(m.gyroscopic_unit().as_ref()) / (terms * eps),
            s.round_off,
        ));
        checks.push(Check::at_most(
            &format!(
                "{}: ‖K_T − K_Tᵀ‖/‖K_T‖ in units of m ε",
                if modes.is_some() { "modal" } else { "full" }
            ),
            symmetry_defect(m.transport_unit().as_ref()) / (terms * eps),
            s.round_off,
        ));
    }
    report.gates.push(GateVerdict::from_checks(
        format!(
            "periodic disc, N = {}: G skew and K_T symmetric (74)",
            s.harmonics
        ),
        "exact",
        checks,
        "R_P = R_Q = 0 for periodic functions in φ",
    ));
    // sectors
    let radial = RadialBasis::uniform(
        plate.inner_radius,
        plate.outer_radius,
        s.elements,
        plate.outer_edge,
    )
    .map_err(|e| e.to_string())?;
    let mass = radial
        .matrices(plate.poisson)
        .map_err(|e| e.to_string())?
        .mass;
    let theta = s.sector_angle;
    let rho_h = plate.mass_per_area;
    let terms = 192.0 * 4.0;
    let mut rows = Vec::new();
    let mut checks = Vec::new();
    for family in TransportBoundary::ALL {
        let model = RotatingPlateModel::new(
            plate,
            PlateDiscretization {
                angular: AngularBasis::Sector {
                    angle: theta,
                    edges: family,
                    functions: s.functions,
                },
                elements: s.elements,
                radial_modes: None,
            },
        )
        .map_err(|e| e.to_string())?;
        let e: Vec<([f64; 2], [f64; 2])> = (0..s.functions).map(|k| ends(family, k)).collect();
        let nf = s.functions;
        let rp = Mat::from_fn(nf, nf, |l, k| e[l].1[0] * e[k].1[0] - e[l].0[0] * e[k].0[0]);
        let rq = Mat::from_fn(nf, nf, |l, k| {
            let at = |x: &[f64; 2], y: &[f64; 2]| x[0] * y[1] / theta - x[1] / theta * y[0];
            at(&e[l].1, &e[k].1) - at(&e[l].0, &e[k].0)
        });
        let g = model.gyroscopic_unit();
        let kt = model.transport_unit();
        let g_sym = Mat::from_fn(g.nrows(), g.ncols(), |i, j| g[(i, j)] + g[(j, i)]);
        let kt_skew = Mat::from_fn(kt.nrows(), kt.ncols(), |i, j| kt[(i, j)] - kt[(j, i)]);
        let expect_p = kron(&rp, &mass);
        let expect_p = Mat::from_fn(expect_p.nrows(), expect_p.ncols(), |i, j| {
            2.0 * rho_h * expect_p[(i, j)]
        });
        let expect_q = kron(&rq, &mass);
        let expect_q = Mat::from_fn(expect_q.nrows(), expect_q.ncols(), |i, j| {
            rho_h * expect_q[(i, j)]
        });
        let gn = g.norm_l2();
        let ktn = kt.norm_l2();
        let identity_p = (&g_sym - &expect_p).norm_l2() / gn;
        let identity_q = (&kt_skew - &expect_q).norm_l2() / ktn;
        let row = FamilyRow {
            family,
            identity_p,
            identity_q,
            skew_defect_g: skew_defect(g.as_ref()),
            symmetry_defect_kt: symmetry_defect(kt.as_ref()),
        };
        let rp_zero = rp.norm_l2() == 0.0;
        let rq_zero = rq.norm_l2() < 1e-14 * (nf as f64);
        checks.push(Check::at_most(
            &format!("{family:?}: ‖G + Gᵀ − 2ρh R_P⊗m‖/‖G‖ and ‖K_T − K_Tᵀ − ρh R_Q⊗m‖/‖K_T‖ in units of m ε"),
            identity_p.max(identity_q) / (terms * eps),
            s.round_off,
        ));
        checks.push(Check::holds(
            &format!(
                "{family:?} ({}): G skew = {} (defect {:.2e}), K_T symmetric = {} (defect {:.2e})",
                family.figure(),
                rp_zero,
                row.skew_defect_g,
                rq_zero,
                row.symmetry_defect_kt
            ),
            decided(rp_zero, row.skew_defect_g, s.round_off * terms * eps, s.measurable)
                && decided(rq_zero, row.symmetry_defect_kt, s.round_off * terms * eps, s.measurable)
                && rp_zero == family.gyroscopic_predicted()
                && rq_zero == family.symmetric_transport_stiffness_predicted(),
            "skew / symmetric to round-off exactly where the closed-form R_P / R_Q vanish, measurably not elsewhere",
        ));
        rows.push(row);
    }
    report.gates.push(GateVerdict::from_checks(
        format!(
            "annular sector Θ = {theta}, {} angular functions per family of Figs 10–12: the transport identities and where they make G skew and K_T symmetric",
            s.functions
        ),
        "exact",
        checks,
        "R_P, R_Q formed from the families' closed-form end values (the string's symmetry case)",
    ));
    Ok(rows)
}
