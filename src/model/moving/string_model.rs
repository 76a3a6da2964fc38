//! The axially moving string with an oscillator in the bushing, discretized by a Ritz basis
//! (Hetzler 2009, §4.2.1–4.2.2): the matrices of (84)–(86), (90)–(91), (102)–(103), (107)–(108).
//!
//! Coordinates: the string's q (N of them), then the oscillator's u; the penalty formulation
//! adds the massless bushing coordinate y_c. Ideal contact (y_c = w(ā)):
//!
//! ```text
//!   M = diag(⟨Φᵀ,Φ⟩, m̄),  D = diag(⟨Φᵀ,Φ⟩, 0),  G = [ 2⟨Φᵀ,Φ'⟩  0 ; 0  0 ],
//!   K = [ ⟨Φ'ᵀ,Φ'⟩ + v̄²⟨Φᵀ,Φ''⟩ + c̄ Φ(ā)ᵀΦ(ā)   −c̄ Φ(ā)ᵀ ; −c̄ Φ(ā)   c̄ ]          (85)
//! ```
//!
//! plus −p R with p = μ h̄ c̄ for the thick string (`friction.rs`). The penalty bushing
//! ((90), (107)) has M = diag(⟨Φᵀ,Φ⟩, m̄, 0): a DAE. By default it is condensed exactly and
//! without cancellation: the massless bushing's equation k̄_p (y_c − w(ā)) = c̄ (u − y_c) makes the
//! spring and the contact layer two springs in series, c_eff = c̄ k̄_p / (c̄ + k̄_p), and the
//! friction force (μ k̄_p h̄/2)(w(ā) − y_c) = (μ h̄/2) c_eff (w(ā) − u). The condensed penalty model
//! is therefore the ideal model with c̄ → c_eff and p → μ h̄ c_eff (nominal p = μ h̄ k̄_p). The
//! generic Schur complement ([`PenaltyCondensation::Schur`]) and the uncondensed DAE
//! ([`MovingStringModel::system_with_bushing`], solved by QZ) are available for comparison.

use faer::Mat;

use crate::error::InputError;
use crate::model::moving::basis::{RitzBasis, SineBasis, StringOperators};
use crate::model::moving::finite_element_basis::{ElementKind, FiniteElementBasis};
use crate::model::moving::friction::add_friction;
use crate::model::moving::string_data::{ContactModel, MovingStringData, OscillatorData};
use crate::model::moving::system::MovingSystem;

/// The Ritz discretization of the string.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case", tag = "basis")]
pub enum StringDiscretization {
    /// Φ_k = √2 sin(kπξ), k = 1..modes.
    Sine { modes: usize },
    /// Finite elements on `elements` equal elements.
    FiniteElements { kind: ElementKind, elements: usize },
}

impl StringDiscretization {
    /// The basis.
    pub fn basis(&self) -> Result<Box<dyn RitzBasis>, InputError> {
        Ok(match *self {
            StringDiscretization::Sine { modes } => Box::new(SineBasis::new(modes)?),
            StringDiscretization::FiniteElements { kind, elements } => {
                Box::new(FiniteElementBasis::uniform(kind, elements)?)
            }
        })
    }
}

/// How the massless penalty bushing is eliminated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PenaltyCondensation {
    /// Springs in series, c_eff = c̄ / (1 + c̄/k̄_p): exact and free of cancellation for any k̄_p.
    #[default]
    SeriesSprings,
    /// The generic Schur complement of the assembled stiffness (loses ~log10(k̄_p/c̄) digits).
    Schur,
}

/// Options of the string model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MovingStringParams {
    pub condensation: PenaltyCondensation,
}

/// The discretized moving string: the basis and its operators, computed once; systems for any
/// data are assembled from them.
pub struct MovingStringModel {
    discretization: StringDiscretization,
    basis: Box<dyn RitzBasis>,
    operators: StringOperators,
    params: MovingStringParams,
}

impl std::fmt::Debug for MovingStringModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MovingStringModel")
            .field("discretization", &self.discretization)
            .field("params", &self.params)
            .finish()
    }
}

impl MovingStringModel {
    /// Builds the basis and its operators.
    pub fn new(
        discretization: StringDiscretization,
        params: MovingStringParams,
    ) -> Result<Self, InputError> {
        let basis = discretization.basis()?;
        let operators = basis.operators();
        Ok(Self {
            discretization,
            basis,
            operators,
            params,
        })
    }

    /// The discretization.
    pub fn discretization(&self) -> StringDiscretization {
        self.discretization
    }

    /// The basis.
    pub fn basis(&self) -> &dyn RitzBasis {
        self.basis.as_ref()
    }

    /// The Gram matrices of the basis.
    pub fn operators(&self) -> &StringOperators {
        &self.operators
    }

    /// N, the number of string coordinates.
    pub fn string_dimension(&self) -> usize {
        self.basis.len()
    }

    /// The coordinates of the (condensed) system for `data`: q1..qN and u.
    pub fn coordinates(&self, data: &MovingStringData) -> Vec<String> {
        let mut c: Vec<String> = (1..=self.string_dimension())
            .map(|k| format!("q{k}"))
            .collect();
        if data.oscillator.is_some() {
            c.push("u".into());
        }
        c
    }

    /// The system for `data`; penalty contact is condensed (see the module docs).
    pub fn system(&self, data: &MovingStringData) -> Result<MovingSystem, InputError> {
        let mut s = MovingSystem::zeros(self.coordinates(data));
        self.assemble_into(data, &mut s)?;
        Ok(s)
    }

    /// Assembles the (condensed) system for `data` into `out`, whose dimension must match
    /// [`MovingStringModel::coordinates`].
    pub fn assemble_into(
        &self,
        data: &MovingStringData,
        out: &mut MovingSystem,
    ) -> Result<(), InputError> {
        data.validate()?;
        let n = self.string_dimension();
        let dim = n + usize::from(data.oscillator.is_some());
        if out.dimension() != dim {
            return Err(InputError::new(
                "system.dimension",
                out.dimension(),
                format!("{dim} coordinates"),
            ));
        }
        if let Some(o) = &data.oscillator {
            if let (ContactModel::Penalty { .. }, PenaltyCondensation::Schur) =
                (o.contact, self.params.condensation)
            {
                let full = self.system_with_bushing(data)?;
                *out = full.condense_massless(n + 1)?;
                return Ok(());
            }
        }
        self.assemble_string_into(data.speed, data.damping, out);
        if let Some(o) = &data.oscillator {
            let (c, mu_h) = match o.contact {
                ContactModel::Ideal => (o.stiffness, o.friction),
                ContactModel::Penalty { stiffness } => {
                    (o.stiffness / (1.0 + o.stiffness / stiffness), o.friction)
                }
            };
            let (phi, dphi) = self.contact_values(o);
            out.mass[(n, n)] = o.mass;
            add_spring_between(c, &phi, n, &mut out.stiffness);
            add_friction(
                mu_h * c,
                &phi,
                &dphi,
                n,
                &mut out.stiffness,
                &mut out.circulatory,
            );
        }
        Ok(())
    }

    /// The uncondensed penalty system (q, u, y_c) of (90) and (107): M is singular (the bushing
    /// is massless). Solve it with `solve_generalized_quadratic_eigen`, or condense it.
    pub fn system_with_bushing(&self, data: &MovingStringData) -> Result<MovingSystem, InputError> {
        data.validate()?;
        let o = data.oscillator.ok_or_else(|| {
            InputError::new(
                "oscillator",
                "(missing)",
                "an oscillator with penalty contact",
            )
        })?;
        let ContactModel::Penalty { stiffness: kp } = o.contact else {
            return Err(InputError::new(
                "oscillator.contact",
                "ideal",
                "penalty contact for the bushing coordinate y_c",
            ));
        };
        let n = self.string_dimension();
        let mut coords = self.coordinates(data);
        coords.push("y_c".into());
        let mut s = MovingSystem::zeros(coords);
        self.assemble_string_into(data.speed, data.damping, &mut s);
        let (phi, dphi) = self.contact_values(&o);
        s.mass[(n, n)] = o.mass;
        let (u, y) = (n, n + 1);
        // spring c̄ (u − y_c)²/2 and contact k̄_p (y_c − w(ā))²/2.
        let k = &mut s.stiffness;
        k[(u, u)] += o.stiffness;
        k[(u, y)] -= o.stiffness;
        k[(y, u)] -= o.stiffness;
        k[(y, y)] += o.stiffness;
        add_spring_between(kp, &phi, y, k);
        add_friction(
            o.friction * kp,
            &phi,
            &dphi,
            y,
            &mut s.stiffness,
            &mut s.circulatory,
        );
        Ok(s)
    }

    /// How the total stiffness depends on the friction along `parameter` (μh̄ or p): with
    /// r = [Φ'(ā); 0] and s = [Φ(ā); −1] on (q, u),
    ///
    ///   K_total(t) = K_total(0) + t · coefficient · r sᵀ,   coefficient = −κ/2,
    ///
    /// where κ = d p_eff/dt: c_eff for t = μh̄, c_eff/k for t = p (k = c̄ or k̄_p; c_eff = c̄ for
    /// ideal contact, c̄/(1 + c̄/k̄_p) for the condensed penalty bushing) — the friction matrix is
    /// rank one (`friction.rs`). `None` for other parameters, without oscillator, or for the Schur
    /// condensation (whose friction entries are not assembled in this form).
    pub fn friction_rank_one(
        &self,
        data: &MovingStringData,
        parameter: crate::model::moving::string_data::StringParameter,
    ) -> Option<(Vec<f64>, Vec<f64>, f64)> {
        use crate::model::moving::string_data::StringParameter;
        let o = data.oscillator.as_ref()?;
        let c_eff = match o.contact {
            ContactModel::Ideal => o.stiffness,
            ContactModel::Penalty { stiffness } => match self.params.condensation {
                PenaltyCondensation::SeriesSprings => o.stiffness / (1.0 + o.stiffness / stiffness),
                PenaltyCondensation::Schur => return None,
            },
        };
        let kappa = match parameter {
            StringParameter::Friction => c_eff,
            StringParameter::ControlParameter => c_eff / o.contact_stiffness(),
            _ => return None,
        };
        let (phi, dphi) = self.contact_values(o);
        let mut r = dphi;
        r.push(0.0);
        let mut s = phi;
        s.push(-1.0);
        Some((r, s, -0.5 * kappa))
    }

    /// What the bushing reads of the string: Φ(ā), Φ'(ā) for point contact; the patch means
    /// Φ̄ and mean slopes (Φ(ā + ε/2) − Φ(ā − ε/2))/ε for a patch of width ε > 0.
    pub fn contact_values(&self, o: &OscillatorData) -> (Vec<f64>, Vec<f64>) {
        if o.patch_width > 0.0 {
            let n = self.string_dimension();
            let (mut v, mut s) = (vec![0.0; n], vec![0.0; n]);
            let half = 0.5 * o.patch_width;
            self.basis
                .patch_means_into(o.position - half, o.position + half, &mut v, &mut s);
            (v, s)
        } else {
            self.point_values(o.position)
        }
    }

    /// Φ(ā), Φ'(ā).
    pub fn point_values(&self, xi: f64) -> (Vec<f64>, Vec<f64>) {
        let n = self.string_dimension();
        let (mut v, mut s) = (vec![0.0; n], vec![0.0; n]);
        self.basis.point_values_into(xi, &mut v, &mut s);
        (v, s)
    }

    /// The string block: M, ᾱ D = ᾱ M, v̄ G = 2 v̄ ⟨Φᵀ,Φ'⟩, K = ⟨Φ'ᵀ,Φ'⟩ + v̄² ⟨Φᵀ,Φ''⟩; every
    /// other entry of `out` is zeroed.
    fn assemble_string_into(&self, speed: f64, damping: f64, out: &mut MovingSystem) {
        let n = self.string_dimension();
        let dim = out.dimension();
        let ops = &self.operators;
        let v2 = speed * speed;
        for j in 0..dim {
            for i in 0..dim {
                let inside = i < n && j < n;
                let (m, t, s, c) = if inside {
                    (
                        ops.mass[(i, j)],
                        ops.transport[(i, j)],
                        ops.stiffness[(i, j)],
                        ops.curvature[(i, j)],
                    )
                } else {
                    (0.0, 0.0, 0.0, 0.0)
                };
                out.mass[(i, j)] = m;
                out.damping[(i, j)] = damping * m;
                out.gyroscopic[(i, j)] = 2.0 * speed * t;
                out.stiffness[(i, j)] = s + v2 * c;
                out.circulatory[(i, j)] = 0.0;
            }
        }
    }
}

/// Adds c (s − Φ(ā) q)²/2: c ΦᵀΦ on the string block, −c Φ coupling to `s`, c on (s, s).
fn add_spring_between(c: f64, phi: &[f64], s: usize, k: &mut Mat<f64>) {
    let n = phi.len();
    for i in 0..n {
        for j in 0..n {
            k[(i, j)] += c * (phi[i] * phi[j]);
        }
        k[(i, s)] -= c * phi[i];
        k[(s, i)] -= c * phi[i];
    }
    k[(s, s)] += c;
}

#[cfg(test)]
mod tests {
    //! Setting: the string with and without oscillator, sine basis. Goal: the structure of (85),
    //! the skew gyroscopic matrix, the series-spring condensation of the penalty bushing equal to
    //! the generic Schur complement, and the typed errors.
    use super::*;

    fn data(contact: ContactModel, friction: f64) -> MovingStringData {
        MovingStringData {
            speed: 0.4,
            damping: 0.02,
            oscillator: Some(crate::model::moving::string_data::OscillatorData {
                stiffness: 3.0,
                mass: 0.7,
                position: 0.31,
                contact,
                friction,
                patch_width: 0.0,
            }),
        }
    }

    fn model(c: PenaltyCondensation) -> MovingStringModel {
        MovingStringModel::new(
            StringDiscretization::Sine { modes: 6 },
            MovingStringParams { condensation: c },
        )
        .unwrap()
    }

    #[test]
    fn oscillator_matrices_have_the_structure_of_85() {
        let m = model(PenaltyCondensation::SeriesSprings);
        let s = m.system(&data(ContactModel::Ideal, 0.0)).unwrap();
        let n = 6;
        assert_eq!(s.dimension(), 7);
        assert_eq!(s.mass[(n, n)], 0.7);
        assert_eq!(s.damping[(n, n)], 0.0);
        assert_eq!(s.stiffness[(n, n)], 3.0);
        let (phi, _) = m.point_values(0.31);
        for i in 0..n {
            assert!((s.stiffness[(i, n)] + 3.0 * phi[i]).abs() < 1e-15);
            for j in 0..n {
                assert_eq!(s.gyroscopic[(i, j)], -s.gyroscopic[(j, i)]);
                assert_eq!(s.stiffness[(i, j)], s.stiffness[(j, i)]);
            }
        }
        assert!(s.circulatory.as_ref().norm_max() == 0.0);
    }

    #[test]
    fn series_spring_condensation_equals_the_schur_complement() {
        for friction in [0.0, 0.3] {
            let d = data(ContactModel::Penalty { stiffness: 40.0 }, friction);
            let a = model(PenaltyCondensation::SeriesSprings)
                .system(&d)
                .unwrap();
            let b = model(PenaltyCondensation::Schur).system(&d).unwrap();
            let (ka, kb) = (a.stiffness_matrix(), b.stiffness_matrix());
            let diff = (&ka - &kb).norm_max();
            assert!(diff < 1e-12 * ka.norm_max(), "{diff}");
        }
    }

    #[test]
    fn friction_is_rank_one_along_the_control_parameter() {
        use crate::model::moving::string_data::StringParameter;
        let m = model(PenaltyCondensation::SeriesSprings);
        for contact in [
            ContactModel::Ideal,
            ContactModel::Penalty { stiffness: 7.0 },
        ] {
            for param in [StringParameter::Friction, StringParameter::ControlParameter] {
                let mut d0 = data(contact, 0.0);
                param.set(&mut d0, 0.0).unwrap();
                let mut d1 = d0;
                param.set(&mut d1, 0.8).unwrap();
                let (r, sv, coef) = m.friction_rank_one(&d0, param).unwrap();
                let (k0, k1) = (
                    m.system(&d0).unwrap().stiffness_matrix(),
                    m.system(&d1).unwrap().stiffness_matrix(),
                );
                for i in 0..7 {
                    for j in 0..7 {
                        let pred = k0[(i, j)] + 0.8 * coef * r[i] * sv[j];
                        assert!(
                            (pred - k1[(i, j)]).abs() < 1e-12 * k1.norm_max(),
                            "{contact:?} {param:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn bushing_requires_penalty_contact() {
        let m = model(PenaltyCondensation::SeriesSprings);
        let e = m
            .system_with_bushing(&data(ContactModel::Ideal, 0.0))
            .unwrap_err();
        assert_eq!(e.field, "oscillator.contact");
        let e = m
            .system(&data(ContactModel::Penalty { stiffness: 0.0 }, 0.0))
            .unwrap_err();
        assert_eq!(e.field, "oscillator.penalty_stiffness");
    }
}
