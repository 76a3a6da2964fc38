//! The program's thick string against the independent sine-Galerkin model
//! (`exact::thick_string_galerkin`) at equal N: the same discrete model, so the matrices, the
//! eigenvalues and the flutter onsets must agree to round-off.
//!
//! Round-off bounds (the gates):
//! - matrices: every entry is a sum of at most four rounded products, and the two codes evaluate
//!   the sines at arguments rounded differently (jπā against (j·π)·ā): |Δ| ≤ C ε max|entry| with a
//!   small C (`matrix_round_off`);
//! - eigenvalues: both eigensolvers are backward stable, so to first order
//!   |Δλ| ≤ κ(λ) (‖δA_ref‖ + ‖δA_prog‖ + ‖A_ref − A_prog‖) with backward errors of order n ε ‖A‖;
//!   κ(λ) = ‖x‖‖y‖/|yᴴx| is the eigenvalue's condition number (right and left eigenvectors of the
//!   reference's first-order matrix A, by one step of inverse iteration). The gate is
//!   |Δλ| ≤ C n ε ‖A‖_F κ(λ) (`eigen_round_off` = C), so a near-defective eigenvalue (large κ)
//!   is held to what round-off permits and a well-conditioned one to a few ulps of ‖A‖;
//! - onsets: two bisections of growth rates that agree to δ (measured: max |Δ max Re λ|) locate
//!   their zeros within the bracket width plus δ/|d max Re λ/dp|; with the second term far below
//!   the bracket (reported), the onsets agree within two bracket widths.

use nalgebra::{Complex, DMatrix};

use crate::moving::bounds::agreement;
use serde::Serialize;

use contactlab::model::moving::string_data::{ContactModel, MovingStringData};
use contactlab::model::moving::string_model::{MovingStringModel, StringDiscretization};
use contactlab::model::moving::system::MovingSystem;

use super::format::{Discrete, ParameterSet};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::CaseReport;
use crate::exact::thick_string_galerkin::{GalerkinMatrices, ThickString};
use crate::moving::study::{eigenvalues, flutter_onset, Bushing};

type C64 = Complex<f64>;

/// The program's data for the thick string `d` (ideal contact, μh̄ = p/c̄).
pub(super) fn program_data(d: &ThickString) -> MovingStringData {
    let bushing = Bushing {
        stiffness: d.stiffness,
        mass: d.mass,
        position: d.position,
    };
    let mut data = bushing.data(
        d.speed,
        d.damping,
        ContactModel::Ideal,
        d.control / d.stiffness,
    );
    if let Some(o) = data.oscillator.as_mut() {
        o.patch_width = d.patch;
    }
    data
}

/// The program's eigenvalues of `model` for `d`.
pub(super) fn program_eigenvalues(
    model: &MovingStringModel,
    d: &ThickString,
) -> Result<Vec<C64>, String> {
    let s = model.system(&program_data(d)).map_err(|e| e.to_string())?;
    Ok(eigenvalues(&s)?
        .iter()
        .map(|z| C64::new(z.re, z.im))
        .collect())
}

/// One comparison at (set, N, p).
#[derive(Debug, Clone, Serialize)]
pub(super) struct DiscreteRow {
    pub set: String,
    pub modes: usize,
    pub control: f64,
    /// max |Δ entry| / (ε max |entry|) of M, C, K.
    pub matrix_defects: [f64; 3],
    /// max over λ of |Δλ| / (n ε ‖A‖_F κ(λ)).
    pub eigen_ratio: f64,
    /// max |Δλ| / max |λ|.
    pub eigen_relative: f64,
    /// The largest κ(λ).
    pub max_condition: f64,
    pub max_re_program: f64,
    pub max_re_reference: f64,
}

/// The flutter onsets of both models at one (set, N).
#[derive(Debug, Clone, Serialize)]
pub(super) struct OnsetRow {
    pub set: String,
    pub modes: usize,
    pub program: f64,
    pub reference: f64,
}

/// max |a − b| / (ε max |b|) over the entries of the program's `a` and the reference's `b`.
fn defect(a: impl Fn(usize, usize) -> f64, b: &DMatrix<f64>) -> f64 {
    let n = b.nrows();
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut worst: f64 = 0.0;
    for i in 0..n {
        for j in 0..n {
            worst = worst.max((a(i, j) - b[(i, j)]).abs());
        }
    }
    if scale == 0.0 {
        worst
    } else {
        worst / (f64::EPSILON * scale)
    }
}

/// Compares the program with the reference at one (set, N, p).
fn compare(
    model: &MovingStringModel,
    d: &ThickString,
    modes: usize,
    set: &str,
) -> Result<DiscreteRow, String> {
    let reference = d.galerkin(modes);
    let sys: MovingSystem = model.system(&program_data(d)).map_err(|e| e.to_string())?;
    let c = sys.velocity_matrix();
    let k = sys.stiffness_matrix();
    let matrix_defects = [
        defect(|i, j| sys.mass[(i, j)], &reference.mass),
        defect(|i, j| c[(i, j)], &reference.velocity),
        defect(|i, j| k[(i, j)], &reference.stiffness),
    ];
    let a = reference.first_order()?;
    let ref_ev = GalerkinMatrices::eigenvalues(&reference)?;
    let prog_ev: Vec<C64> = eigenvalues(&sys)?
        .iter()
        .map(|z| C64::new(z.re, z.im))
        .collect();
    let agreed =
        agreement(&a, &ref_ev, &prog_ev, 0.0).map_err(|e| format!("{set}, N = {modes}: {e}"))?;
    let max_re = |v: &[C64]| v.iter().map(|l| l.re).fold(f64::NEG_INFINITY, f64::max);
    Ok(DiscreteRow {
        set: set.to_string(),
        modes,
        control: d.control,
        matrix_defects,
        eigen_ratio: agreed.ratio,
        eigen_relative: agreed.relative,
        max_condition: agreed.max_condition,
        max_re_program: max_re(&prog_ev),
        max_re_reference: max_re(&ref_ev),
    })
}

/// What the equal-discretization study measured.
pub(super) struct DiscreteData {
    pub rows: Vec<DiscreteRow>,
    pub onsets: Vec<OnsetRow>,
}

/// Runs the comparisons and pushes the three gates (matrices, eigenvalues, onsets).
pub(super) fn study(
    sets: &[ParameterSet],
    c: &Discrete,
    report: &mut CaseReport,
) -> Result<DiscreteData, String> {
    let mut rows = Vec::new();
    for &modes in &c.modes {
        let model =
            MovingStringModel::new(StringDiscretization::Sine { modes }, Default::default())
                .map_err(|e| e.to_string())?;
        for s in sets {
            for &p in &c.controls {
                rows.push(compare(&model, &s.at(p), modes, &s.name)?);
            }
        }
    }
    let worst_m = rows.iter().map(|r| r.matrix_defects[0]).fold(0.0, f64::max);
    let worst_c = rows.iter().map(|r| r.matrix_defects[1]).fold(0.0, f64::max);
    let worst_k = rows.iter().map(|r| r.matrix_defects[2]).fold(0.0, f64::max);
    let what = format!(
        "{} sets × N ∈ {:?} × p ∈ {:?}",
        sets.len(),
        c.modes,
        c.controls
    );
    report.gates.push(GateVerdict::from_checks(
        "equal discretization: the program's matrices are the closed-form sine-Galerkin ones".into(),
        "exact",
        vec![
            Check::at_most(&format!("M: max |Δ| / (ε max|M|), {what}"), worst_m, c.matrix_round_off),
            Check::at_most("C = ᾱD + 2v̄⟨Φ,Φ'⟩: max |Δ| / (ε max|C|)", worst_c, c.matrix_round_off),
            Check::at_most(
                "K = ⟨Φ',Φ'⟩ + v̄²⟨Φ,Φ''⟩ + c̄φφᵀ − (p/2)φ'φᵀ (with the u column): max |Δ| / (ε max|K|)",
                worst_k,
                c.matrix_round_off,
            ),
        ],
        "the reference writes the integrals of (100) out from sin/cos products; a wrong factor or sign of any term (the gyroscopic 2v̄, the friction p/2) differs by O(1) of the matrix scale",
    ));
    let worst_ratio = rows.iter().map(|r| r.eigen_ratio).fold(0.0, f64::max);
    let worst_rel = rows.iter().map(|r| r.eigen_relative).fold(0.0, f64::max);
    let worst_kappa = rows.iter().map(|r| r.max_condition).fold(0.0, f64::max);
    let worst_re = rows
        .iter()
        .map(|r| (r.max_re_program - r.max_re_reference).abs())
        .fold(0.0, f64::max);
    report.gates.push(GateVerdict::from_checks(
        "equal discretization: the program's eigenvalues are the reference's (nalgebra's Schur form of its own first-order matrix)".into(),
        "exact",
        vec![
            Check::at_most(
                &format!(
                    "max |Δλ| / (n ε ‖A‖_F κ(λ)) over every eigenvalue ({what}; largest κ {worst_kappa:.2e}, max |Δλ|/max|λ| = {worst_rel:.2e}, max |Δ max Re λ| = {worst_re:.2e})"
                ),
                worst_ratio,
                c.eigen_round_off,
            ),
        ],
        "first-order perturbation: |Δλ| ≤ κ(λ) × the backward errors of two backward-stable eigensolvers (order n ε ‖A‖ each)",
    ));
    // Flutter onsets of the discrete models.
    let mut onsets = Vec::new();
    let mut checks = Vec::new();
    for &modes in &c.onset_modes {
        let model =
            MovingStringModel::new(StringDiscretization::Sine { modes }, Default::default())
                .map_err(|e| e.to_string())?;
        for s in sets {
            let grow_prog = |p: f64| -> Result<f64, String> {
                let ev = program_eigenvalues(&model, &s.at(p))?;
                Ok(ev.iter().map(|l| l.re).fold(f64::NEG_INFINITY, f64::max))
            };
            let grow_ref = |p: f64| -> Result<f64, String> {
                let ev = s.at(p).galerkin_eigenvalues(modes)?;
                Ok(ev.iter().map(|l| l.re).fold(f64::NEG_INFINITY, f64::max))
            };
            let a = flutter_onset(grow_prog, "p", 0.01, c.bisection_tolerance, 1e3)?;
            let b = flutter_onset(grow_ref, "p", 0.01, c.bisection_tolerance, 1e3)?;
            checks.push(Check::at_most(
                &format!(
                    "{}, N = {modes}: |p*_program − p*_reference| / p*_reference (p* = {a:.10}, {b:.10}) vs 2 bracket widths",
                    s.name
                ),
                (a - b).abs() / b,
                2.0 * c.bisection_tolerance,
            ));
            onsets.push(OnsetRow {
                set: s.name.clone(),
                modes,
                program: a,
                reference: b,
            });
        }
    }
    report.gates.push(GateVerdict::from_checks(
        "equal discretization: the flutter onsets of the discrete model are the reference's".into(),
        "exact",
        checks,
        "bisection of max Re λ in p for both models; the onsets are those of the N-mode model (issue 16: at large N the discrete onset is a property of the basis, not of the string — see the continuum gates)",
    ));
    Ok(DiscreteData { rows, onsets })
}
